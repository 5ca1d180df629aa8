//! What a batch run is asked ([`BatchConfig`]) and what it answers
//! ([`Summary`]); the run itself is in `run.rs`.

use std::path::PathBuf;

use shadelab_core::Shading;
use shadelab_io::{PngCompression, SceneFile, MAX_MESH_BYTES};

use crate::escape;
use crate::plan::{Shard, Views};
use crate::progress::Progress;

/// Everything a run needs to know.
#[derive(Debug, Clone)]
pub struct BatchConfig {
    /// The manifest (JSON Lines, or CSV by its `.csv` extension).
    pub manifest: PathBuf,
    /// The folder the PNGs and the index go to (made if missing).
    pub output: PathBuf,
    /// Shared settings: a scene file with the flags applied, as `render` builds it.
    pub settings: SceneFile,
    /// Cameras per mesh.
    pub views: Views,
    /// Shading methods per view; `None`: the settings' one (Phong by default).
    pub modes: Option<Vec<Shading>>,
    /// This run's share of the manifest.
    pub shard: Shard,
    /// Draw outputs again even when they exist.
    pub force: bool,
    /// The folder mesh paths must stay inside; `None`: the manifest's folder.
    pub root: Option<PathBuf>,
    /// Meshes in flight at once; 0: two per core.
    pub jobs: usize,
    /// Threads drawing each worker's frames; 0 is taken as 1.
    pub frame_threads: usize,
    /// Largest mesh file read, in bytes.
    pub max_mesh_bytes: u64,
    /// PNG compression.
    pub compression: PngCompression,
    /// Progress on standard error.
    pub progress: Progress,
}

impl BatchConfig {
    /// A run of `manifest` into `output` with the defaults: one view, the
    /// settings' method, the whole manifest, resuming, two workers per core.
    pub fn new(manifest: impl Into<PathBuf>, output: impl Into<PathBuf>) -> BatchConfig {
        BatchConfig {
            manifest: manifest.into(),
            output: output.into(),
            settings: SceneFile::default(),
            views: Views::Ring(1),
            modes: None,
            shard: Shard::default(),
            force: false,
            root: None,
            jobs: 0,
            frame_threads: 1,
            max_mesh_bytes: MAX_MESH_BYTES,
            compression: PngCompression::Fast,
            progress: Progress::Auto,
        }
    }
}

/// What a run did.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Summary {
    /// Manifest entries in this share.
    pub meshes: u64,
    /// Of those, meshes with at least one failed output.
    pub meshes_failed: u64,
    /// Images drawn and written.
    pub written: u64,
    /// Images already complete, left alone.
    pub skipped: u64,
    /// Images that failed.
    pub failed: u64,
    /// Manifest lines of this share that could not be read.
    pub bad_lines: u64,
    /// Wall-clock seconds.
    pub seconds: f64,
    /// The index file written.
    pub index: PathBuf,
}

impl Summary {
    /// Whether anything failed.
    pub fn has_errors(&self) -> bool {
        self.failed > 0 || self.bad_lines > 0
    }
}

impl std::fmt::Display for Summary {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} meshes: {} images written, {} already there, {} failed ({} meshes), {} bad manifest lines; {:.1} s, {:.1} images/s; index {}",
            self.meshes,
            self.written,
            self.skipped,
            self.failed,
            self.meshes_failed,
            self.bad_lines,
            self.seconds,
            self.written as f64 / self.seconds.max(1e-9),
            self.output_index()
        )
    }
}

impl Summary {
    fn output_index(&self) -> String {
        escape(&self.index.display().to_string())
    }
}
