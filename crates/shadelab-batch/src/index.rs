//! `index.jsonl`: one JSON object per output, written as outputs finish.
//!
//! Each run rewrites its index from the start, so after any run that ends
//! the index lists every output of its share exactly once: `ok` (drawn now,
//! with its time and triangles), `skipped` (already there from an earlier
//! run), or `error` (with the message). A manifest line that could not be
//! read has one `error` row with its line and no id. Rows are written whole,
//! one `write` each, as they finish, so a run that is killed leaves the rows
//! of what it completed.

use std::fs::File;
use std::io::Write;
use std::path::Path;
use std::sync::Mutex;

use serde::Serialize;

/// What became of one output.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Status {
    /// Drawn and written by this run.
    Ok,
    /// Already complete from an earlier run; left alone.
    Skipped,
    /// Not drawn: see `error`.
    Error,
}

/// One row of the index.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Row {
    /// The manifest line the mesh came from.
    pub line: u64,
    /// The mesh's id (none when its line could not be read).
    pub id: Option<String>,
    /// The view's name.
    pub view: Option<String>,
    /// The shading method.
    pub mode: Option<&'static str>,
    /// The PNG, relative to the output folder.
    pub file: Option<String>,
    /// Milliseconds to draw, encode and write it.
    pub ms: Option<f64>,
    /// The mesh's triangles.
    pub triangles: Option<u64>,
    /// What became of it.
    pub status: Status,
    /// Why it failed.
    pub error: Option<String>,
}

/// The index file being written, shared by the threads of a run.
#[derive(Debug)]
pub struct IndexWriter {
    file: Mutex<File>,
}

impl IndexWriter {
    /// Creates (or empties) the index at `path`, refusing to follow a
    /// symbolic link or to open anything that is not a regular file.
    ///
    /// # Errors
    /// The I/O error.
    pub fn create(path: &Path) -> std::io::Result<IndexWriter> {
        use std::os::unix::fs::OpenOptionsExt;
        if let Ok(meta) = std::fs::symlink_metadata(path) {
            if !meta.is_file() {
                return Err(std::io::Error::other(
                    "exists and is not a regular file; refusing to replace it",
                ));
            }
        }
        let file = std::fs::OpenOptions::new()
            .write(true)
            .create(true)
            .truncate(true)
            .custom_flags(libc::O_NOFOLLOW | libc::O_NONBLOCK)
            .open(path)?;
        if !file.metadata()?.is_file() {
            return Err(std::io::Error::other("is not a regular file"));
        }
        Ok(IndexWriter {
            file: Mutex::new(file),
        })
    }

    /// Appends one row.
    ///
    /// # Errors
    /// The I/O error.
    pub fn write(&self, row: &Row) -> std::io::Result<()> {
        let mut line = serde_json::to_string(row).map_err(std::io::Error::other)?;
        line.push('\n');
        let mut file = self.file.lock().unwrap_or_else(|e| e.into_inner());
        file.write_all(line.as_bytes())
    }
}
