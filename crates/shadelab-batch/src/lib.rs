//! Rendering many meshes: `shadelab batch` and the Python package's `batch`.
//!
//! A manifest (JSON Lines or CSV, [`Manifest`]) lists mesh files; each is
//! drawn from several [`Views`] in one or more shading methods, under shared
//! settings (a [`shadelab_io::SceneFile`] with the command's flags applied,
//! built exactly as `shadelab render` builds it), into
//! `DIR/<id>/<view>_<mode>.png`, with one row per output in an index
//! ([`Row`]). A run ([`run()`]) is resumable (complete outputs are skipped),
//! shardable ([`Shard`]: a stable share by id, no coordinator), and
//! survives bad meshes (error rows). [`PreparedMesh`] is the one place a
//! mesh becomes frames, shared with the Python package's `render`.
#![warn(missing_docs)]

mod config;
mod index;
mod manifest;
mod plan;
mod prepared;
mod progress;
mod run;

pub use config::{BatchConfig, Summary};
pub use index::{IndexWriter, Row, Status};
pub use manifest::{Entry, LineError, Manifest, ManifestFormat, MAX_LINE_BYTES};
pub use plan::{
    check_id, default_id, output_name, parse_modes, parse_size, Shard, View, Views, MAX_ID_BYTES,
    MAX_RING_VIEWS,
};
pub use prepared::PreparedMesh;
pub use progress::Progress;
pub use run::{is_complete_png, run};

/// Why a run could not start or had to stop.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum BatchError {
    /// The manifest cannot be read, or its CSV header is unusable.
    #[error("{path}: {message}")]
    Manifest {
        /// The manifest (with the line, for a header error).
        path: String,
        /// What is wrong.
        message: String,
    },
    /// The shared settings (scene file and flags) are invalid.
    #[error(transparent)]
    Settings(shadelab_io::SceneError),
    /// The output folder or the index cannot be written.
    #[error("{path}: {source}")]
    Output {
        /// The folder or file.
        path: String,
        /// What went wrong.
        source: std::io::Error,
    },
}

impl BatchError {
    /// Whether the user's input is at fault (exit code 2), rather than the
    /// output (exit code 1).
    pub fn is_input_error(&self) -> bool {
        !matches!(self, BatchError::Output { .. })
    }
}

/// `text` with control characters escaped (`\n`, `\u{1b}`, …), for messages
/// that quote file names and manifest text.
pub fn escape(text: &str) -> String {
    if !text.chars().any(char::is_control) {
        return text.to_owned();
    }
    text.chars()
        .flat_map(|c| {
            let escaped: Vec<char> = if c.is_control() {
                c.escape_default().collect()
            } else {
                vec![c]
            };
            escaped
        })
        .collect()
}
