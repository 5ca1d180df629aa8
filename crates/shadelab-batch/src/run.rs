//! A batch run: every mesh of a manifest's share, every view and mode, into PNGs.
//!
//! **Throughput.** `jobs` workers (two per core by default) each take the
//! next manifest entry, load the mesh, draw its frames and encode its PNGs;
//! a worker draws its frames in its own pool of `frame_threads` threads (one
//! by default). Parallel across meshes, a worker's loading, drawing and
//! encoding overlap with the others', which keeps every core busy on the
//! many small frames of a batch; drawing one frame on all cores leaves them
//! waiting on each other's loading and encoding. Two workers per core rather
//! than one because each PNG is synced to disk before it is renamed into
//! place: while one worker waits on the disk, the other draws (measured in
//! BENCHMARKS.md: 2 jobs 60, 3 jobs 83, 4 jobs 94 images/s on 2 cores).
//!
//! **Memory** is bounded by the meshes in flight, at most `jobs` of them:
//! workers pull entries from the manifest as they become free, the manifest
//! is read one line at a time, and each worker keeps one image buffer. A
//! mesh file above `max_mesh_bytes` is refused before it is read.
//!
//! **Resuming.** Every PNG is written through `shadelab-io`'s writer, which
//! renames a complete temporary file into place, so an output that exists
//! is complete; a run skips those (checking that the file is a regular file
//! that ends with PNG's `IEND` chunk) unless `force` is set, and loads a mesh
//! only when one of its outputs is missing.
//!
//! **Failures** of one mesh (a broken or oversized file, a path outside the
//! root, a duplicate id, an unwritable output) become `error` rows in the
//! index and never stop the run; only what makes the whole run meaningless
//! (an unreadable manifest, bad shared settings, an output folder that
//! cannot be made) is a [`BatchError`].

use std::collections::HashMap;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;
use std::time::Instant;

use shadelab_core::limits::MAX_MEMORY_BYTES;
use shadelab_core::{Image, Renderer, Rgb8, Shading};
use shadelab_io::write_png_with;

use crate::config::{BatchConfig, Summary};
use crate::index::{IndexWriter, Row, Status};
use crate::manifest::{Entry, LineError, Manifest};
use crate::plan::{check_id, default_id, output_name, Shard, View};
use crate::prepared::PreparedMesh;
use crate::progress::Reporter;
use crate::{escape, BatchError};

/// Shared state of a run's workers.
struct Run<'a> {
    config: &'a BatchConfig,
    modes: Vec<Shading>,
    dir: PathBuf,
    root: PathBuf,
    index: IndexWriter,
    reporter: Reporter,
    seen: Mutex<HashMap<String, u64>>,
    meshes: AtomicU64,
    meshes_failed: AtomicU64,
    written: AtomicU64,
    skipped: AtomicU64,
    failed: AtomicU64,
    bad_lines: AtomicU64,
    /// How many workers draw at once (each may hold a mesh and a frame).
    jobs: usize,
}

/// Renders the manifest's share as `config` says.
///
/// # Errors
/// [`BatchError`] when the run cannot start (manifest, settings, output
/// folder, index); failures of single meshes are rows of the index.
pub fn run(config: &BatchConfig) -> Result<Summary, BatchError> {
    let start = Instant::now();
    config
        .settings
        .render_options()
        .map_err(BatchError::Settings)?;
    let modes = match &config.modes {
        Some(m) if !m.is_empty() => m.clone(),
        _ => vec![config.settings.render.shading.unwrap_or_default()],
    };
    let manifest = Manifest::open(&config.manifest)?;
    let dir = manifest.dir().to_path_buf();
    let root_given = config.root.clone().unwrap_or_else(|| dir.clone());
    let root = root_given.canonicalize().map_err(|e| BatchError::Output {
        path: root_given.display().to_string(),
        source: e,
    })?;
    std::fs::create_dir_all(&config.output).map_err(|e| BatchError::Output {
        path: config.output.display().to_string(),
        source: e,
    })?;
    let index_path = config.output.join(config.shard.index_name());
    let index = IndexWriter::create(&index_path).map_err(|e| BatchError::Output {
        path: index_path.display().to_string(),
        source: e,
    })?;
    let total = count_share(&config.manifest, config.shard)?;
    let jobs = match config.jobs {
        0 => 2 * std::thread::available_parallelism().map_or(1, |n| n.get()),
        n => n,
    };
    let run = Run {
        config,
        modes,
        dir,
        root,
        index,
        reporter: Reporter::new(config.progress, total),
        seen: Mutex::new(HashMap::new()),
        meshes: AtomicU64::new(0),
        meshes_failed: AtomicU64::new(0),
        written: AtomicU64::new(0),
        skipped: AtomicU64::new(0),
        failed: AtomicU64::new(0),
        bad_lines: AtomicU64::new(0),
        jobs,
    };
    let manifest = Mutex::new(manifest);
    let index_error = Mutex::new(None);
    std::thread::scope(|scope| {
        for _ in 0..jobs {
            scope.spawn(|| {
                if let Err(e) = run.worker(&manifest) {
                    *index_error.lock().unwrap_or_else(|e| e.into_inner()) = Some(e);
                }
            });
        }
    });
    run.reporter.finish();
    if let Some(e) = index_error.into_inner().unwrap_or_else(|e| e.into_inner()) {
        return Err(BatchError::Output {
            path: index_path.display().to_string(),
            source: e,
        });
    }
    Ok(Summary {
        meshes: run.meshes.into_inner(),
        meshes_failed: run.meshes_failed.into_inner(),
        written: run.written.into_inner(),
        skipped: run.skipped.into_inner(),
        failed: run.failed.into_inner(),
        bad_lines: run.bad_lines.into_inner(),
        seconds: start.elapsed().as_secs_f64(),
        index: index_path,
    })
}

/// How many entries (and unreadable lines) of the manifest fall in `shard`:
/// a first pass that reads lines and ids only, for the progress display.
fn count_share(path: &Path, shard: Shard) -> Result<u64, BatchError> {
    let mut n = 0;
    for item in Manifest::open(path)? {
        let mine = match &item {
            Ok(entry) => shard.has_id(&entry_id(entry)),
            Err(e) => shard.has_line(e.line),
        };
        n += u64::from(mine);
    }
    Ok(n)
}

/// The entry's id: as given, or made from its path.
fn entry_id(entry: &Entry) -> String {
    entry.id.clone().unwrap_or_else(|| default_id(&entry.path))
}

impl Run<'_> {
    /// One worker: takes entries until the manifest ends. Only a failure to
    /// write the index stops it.
    fn worker(&self, manifest: &Mutex<Manifest>) -> std::io::Result<()> {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(self.config.frame_threads.max(1))
            .build()
            .map_err(std::io::Error::other)?;
        pool.install(|| {
            let mut image = Image::filled(1, 1, Rgb8::default());
            loop {
                // Ids are claimed in manifest order, under the manifest's lock,
                // so the first line with an id always wins it.
                let (item, duplicate_of) = {
                    let mut manifest = manifest.lock().unwrap_or_else(|e| e.into_inner());
                    let item = manifest.next();
                    let duplicate_of = match &item {
                        Some(Ok(entry)) => self.claim(entry),
                        _ => None,
                    };
                    (item, duplicate_of)
                };
                match item {
                    None => return Ok(()),
                    Some(Err(e)) => self.bad_line(&e)?,
                    Some(Ok(entry)) => self.mesh(&entry, duplicate_of, &mut image)?,
                }
            }
        })
    }

    /// Records the entry's id (when in this share); the line that used it
    /// first, when it is a repeat.
    fn claim(&self, entry: &Entry) -> Option<u64> {
        use std::collections::hash_map::Entry as Slot;
        let id = entry_id(entry);
        if !self.config.shard.has_id(&id) {
            return None;
        }
        match self
            .seen
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .entry(id)
        {
            Slot::Occupied(first) => Some(*first.get()),
            Slot::Vacant(slot) => {
                slot.insert(entry.line);
                None
            }
        }
    }

    fn bad_line(&self, e: &LineError) -> std::io::Result<()> {
        if !self.config.shard.has_line(e.line) {
            return Ok(());
        }
        self.bad_lines.fetch_add(1, Ordering::Relaxed);
        let message = escape(&e.to_string());
        self.reporter.line_failed(&message);
        self.index.write(&Row {
            line: e.line,
            id: None,
            view: None,
            mode: None,
            file: None,
            ms: None,
            triangles: None,
            status: Status::Error,
            error: Some(message),
        })
    }

    /// Every output of one entry.
    fn mesh(
        &self,
        entry: &Entry,
        duplicate_of: Option<u64>,
        image: &mut Image,
    ) -> std::io::Result<()> {
        let id = entry_id(entry);
        if !self.config.shard.has_id(&id) {
            return Ok(());
        }
        self.meshes.fetch_add(1, Ordering::Relaxed);
        let views = entry.views.unwrap_or(self.config.views).list();
        let modes = entry.modes.as_deref().unwrap_or(&self.modes);
        let id_ref = id.as_str();
        let outputs: Vec<(&View, Shading, String)> = views
            .iter()
            .flat_map(|v| {
                modes
                    .iter()
                    .map(move |&m| (v, m, output_name(id_ref, v, m)))
            })
            .collect();
        let mut tally = Tally::default();
        let result = self.draw_all(entry, &id, duplicate_of, &outputs, image, &mut tally);
        let failure = match result {
            Ok(()) => tally.first_error.take(),
            Err(Failed::Io(e)) => return Err(e),
            Err(Failed::Mesh(message)) => {
                // Every output not already complete fails with the mesh.
                let message = escape(&format!(
                    "{}:{}: {message}",
                    self.manifest_name(),
                    entry.line
                ));
                for (view, mode, name) in &outputs {
                    if tally.done.contains(name) {
                        continue;
                    }
                    self.row(
                        entry,
                        &id,
                        view,
                        *mode,
                        name,
                        None,
                        None,
                        Status::Error,
                        Some(&message),
                    )?;
                    tally.failed += 1;
                }
                Some(message)
            }
        };
        self.written.fetch_add(tally.written, Ordering::Relaxed);
        self.skipped.fetch_add(tally.skipped, Ordering::Relaxed);
        self.failed.fetch_add(tally.failed, Ordering::Relaxed);
        if tally.failed > 0 {
            self.meshes_failed.fetch_add(1, Ordering::Relaxed);
        }
        let total = self.written.load(Ordering::Relaxed);
        self.reporter
            .mesh_done(tally.written, total, failure.as_deref());
        Ok(())
    }

    fn manifest_name(&self) -> String {
        self.config.manifest.display().to_string()
    }

    fn draw_all(
        &self,
        entry: &Entry,
        id: &str,
        duplicate_of: Option<u64>,
        outputs: &[(&View, Shading, String)],
        image: &mut Image,
        tally: &mut Tally,
    ) -> Result<(), Failed> {
        check_id(id).map_err(Failed::Mesh)?;
        if let Some(first) = duplicate_of {
            return Err(Failed::Mesh(format!(
                "id \"{id}\" was already used on line {first}"
            )));
        }
        let mut missing = Vec::new();
        for (view, mode, name) in outputs {
            let path = self.config.output.join(name);
            if !self.config.force && is_complete_png(&path) {
                self.row(
                    entry,
                    id,
                    view,
                    *mode,
                    name,
                    None,
                    None,
                    Status::Skipped,
                    None,
                )?;
                tally.skipped += 1;
                tally.done.push(name.clone());
            } else {
                missing.push((*view, *mode, name, path));
            }
        }
        if missing.is_empty() {
            return Ok(());
        }
        let path = self.mesh_path(&entry.path).map_err(Failed::Mesh)?;
        let mut mesh = PreparedMesh::load(&self.config.settings, &path, entry.size)
            .map_err(|e| Failed::Mesh(e.to_string()))?;
        let triangles = mesh.triangles() as u64;
        // Every worker may hold a mesh this large at once: each gets its share.
        let share = MAX_MEMORY_BYTES / self.jobs.max(1) as u64;
        if mesh.memory_estimate() > share {
            return Err(Failed::Mesh(format!(
                "drawing it would need about {} MiB of memory, more than a worker's share ({} MiB, the limit of {} MiB over {} workers)",
                mesh.memory_estimate() >> 20,
                share >> 20,
                MAX_MEMORY_BYTES >> 20,
                self.jobs.max(1)
            )));
        }
        std::fs::create_dir_all(self.config.output.join(id))
            .map_err(|e| Failed::Mesh(format!("cannot make the output folder: {e}")))?;
        let mut renderer = Renderer::new();
        for (view, mode, name, out) in missing {
            let start = Instant::now();
            let result = mesh.render(&mut renderer, view, mode, image).and_then(|_| {
                write_png_with(&out, image, self.config.compression)
                    .map_err(|e| format!("cannot write {}: {e}", out.display()))
            });
            let ms = start.elapsed().as_secs_f64() * 1e3;
            let (ms, status, message) = match result {
                Ok(()) => (Some(ms), Status::Ok, None),
                Err(e) => {
                    let message = escape(&format!("{}:{}: {e}", self.manifest_name(), entry.line));
                    (None, Status::Error, Some(message))
                }
            };
            let tri = Some(triangles);
            self.row(
                entry,
                id,
                view,
                mode,
                name,
                ms,
                tri,
                status,
                message.as_deref(),
            )?;
            match message {
                None => tally.written += 1,
                Some(message) => {
                    tally.failed += 1;
                    tally.first_error.get_or_insert(message);
                }
            }
            tally.done.push(name.clone());
        }
        Ok(())
    }

    /// The mesh file an entry names: relative to the manifest's folder, and
    /// inside the root once links are followed; a regular file within the size limit.
    fn mesh_path(&self, given: &str) -> Result<PathBuf, String> {
        let path = self.dir.join(given);
        let real = path
            .canonicalize()
            .map_err(|e| format!("{}: {e}", path.display()))?;
        if !real.starts_with(&self.root) {
            return Err(format!(
                "{}: outside {} (mesh paths must stay inside the manifest's folder, or the --root given)",
                path.display(),
                self.root.display()
            ));
        }
        let meta = std::fs::metadata(&real).map_err(|e| format!("{}: {e}", path.display()))?;
        if !meta.is_file() {
            return Err(format!("{}: not a regular file", path.display()));
        }
        if meta.len() > self.config.max_mesh_bytes {
            return Err(format!(
                "{}: {} bytes is more than the limit of {} bytes",
                path.display(),
                meta.len(),
                self.config.max_mesh_bytes
            ));
        }
        Ok(path)
    }

    #[allow(clippy::too_many_arguments)]
    fn row(
        &self,
        entry: &Entry,
        id: &str,
        view: &View,
        mode: Shading,
        file: &str,
        ms: Option<f64>,
        triangles: Option<u64>,
        status: Status,
        error: Option<&str>,
    ) -> std::io::Result<()> {
        self.index.write(&Row {
            line: entry.line,
            id: Some(id.to_owned()),
            view: Some(view.name.clone()),
            mode: Some(mode.name()),
            file: Some(file.to_owned()),
            ms: ms.map(|ms| (ms * 1000.0).round() / 1000.0),
            triangles,
            status,
            error: error.map(str::to_owned),
        })
    }
}

/// Counts of one mesh's outputs.
#[derive(Default)]
struct Tally {
    written: u64,
    skipped: u64,
    failed: u64,
    /// Outputs already given a row.
    done: Vec<String>,
    first_error: Option<String>,
}

/// Why a mesh's outputs stopped.
enum Failed {
    /// The mesh cannot be drawn at all: its remaining outputs fail with this.
    Mesh(String),
    /// The index cannot be written: the run stops.
    Io(std::io::Error),
}

impl From<std::io::Error> for Failed {
    fn from(e: std::io::Error) -> Failed {
        Failed::Io(e)
    }
}

/// PNG's last chunk: length 0, `IEND`, its CRC.
const IEND: [u8; 12] = [0, 0, 0, 0, b'I', b'E', b'N', b'D', 0xAE, 0x42, 0x60, 0x82];

/// Whether `path` is a regular file ending with PNG's `IEND` chunk: what the
/// atomic writer leaves, and what a truncated copy lacks.
pub fn is_complete_png(path: &Path) -> bool {
    use std::io::{Seek, SeekFrom};
    use std::os::unix::fs::OpenOptionsExt;
    let Ok(meta) = std::fs::symlink_metadata(path) else {
        return false;
    };
    if !meta.is_file() || meta.len() < 8 + IEND.len() as u64 {
        return false;
    }
    let tail = (|| -> std::io::Result<[u8; 12]> {
        let mut file = std::fs::OpenOptions::new()
            .read(true)
            .custom_flags(libc::O_NOFOLLOW | libc::O_NONBLOCK)
            .open(path)?;
        let mut head = [0u8; 8];
        file.read_exact(&mut head)?;
        if head != *b"\x89PNG\r\n\x1a\n" {
            return Err(std::io::Error::other("not a PNG"));
        }
        file.seek(SeekFrom::End(-(IEND.len() as i64)))?;
        let mut tail = [0u8; 12];
        file.read_exact(&mut tail)?;
        Ok(tail)
    })();
    tail.is_ok_and(|t| t == IEND)
}
