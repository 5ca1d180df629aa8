//! Output files, written whole or not at all: the one way every command
//! writes a file.
//!
//! [`write_atomic`] never writes into the path it is given. It creates an
//! unpredictable temporary file exclusively (`O_EXCL`, a random name,
//! `tempfile`) in the target's folder, writes and syncs it, and renames it
//! over the target. So:
//!
//! - an interrupted or failed write (a full disk, an encoding error) leaves
//!   the old file as it was and no temporary file behind;
//! - a symbolic link planted under a temporary name cannot redirect the
//!   write, because the name is random and created exclusively;
//! - the target is replaced only when it is a regular file, a symbolic link
//!   or nothing. A link is replaced by the new file (the file it pointed to
//!   is left as it was: nothing is ever written through a link). A
//!   directory, device, FIFO or socket is refused, so `-o /dev/null` run as
//!   root cannot turn the device into a regular file;
//! - the temporary name is short (`.shadelab` and six random characters and
//!   `.tmp`), so any file name the file system allows (255 bytes) can be
//!   written.
//!
//! The path `-` means standard output, written straight through.
//!
//! A check-then-rename cannot be atomic against someone who can write to the
//! target's folder at the same moment; such a person could replace the file
//! anyway. What the check protects is the user's own mistake and a file
//! planted in advance.

use std::io::{BufWriter, Write};
use std::path::Path;

/// The path that means standard output.
pub const STDOUT_PATH: &str = "-";

/// Writes a file through `write`, atomically: a temporary file in the same
/// folder is renamed over `path` only once `write` succeeded and the data
/// reached the disk. `-` writes to standard output instead (flushed at the
/// end); see the [module documentation](self) for what is refused and why.
///
/// `write` gets a buffered writer; it need not buffer or flush itself.
///
/// # Errors
/// - [`std::io::ErrorKind::InvalidInput`] when `path` names no file (empty,
///   `..`, a root);
/// - [`std::io::ErrorKind::AlreadyExists`] when `path` exists and is a
///   directory, device, FIFO or socket;
/// - any error from `write` or from creating, writing, syncing or renaming
///   the temporary file (a full disk is `StorageFull`, standard output
///   closed by its reader `BrokenPipe`). Nothing is left behind.
pub fn write_atomic(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> std::io::Result<()> {
    if path.as_os_str() == STDOUT_PATH {
        let mut out = BufWriter::new(std::io::stdout().lock());
        write(&mut out)?;
        return out.flush();
    }
    if path.file_name().is_none() {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            "the output path names no file",
        ));
    }
    check_replaceable(path)?;
    let dir = path
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let mut builder = tempfile::Builder::new();
    builder.prefix(".shadelab").suffix(".tmp").rand_bytes(6);
    #[cfg(unix)]
    {
        // As `File::create` would make it (the umask applies), not the
        // owner-only mode of a temporary file.
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    let mut temp = builder.tempfile_in(dir)?;
    {
        let mut out = BufWriter::new(temp.as_file_mut());
        write(&mut out)?;
        out.flush()?;
    }
    temp.as_file().sync_all()?;
    // The target may have changed since the check: look once more, as
    // close to the rename as can be.
    check_replaceable(path)?;
    temp.persist(path).map_err(|e| e.error)?;
    Ok(())
}

/// Fails unless `path` is absent, a regular file or a symbolic link (which
/// is itself replaced, never followed).
fn check_replaceable(path: &Path) -> std::io::Result<()> {
    match std::fs::symlink_metadata(path) {
        Ok(meta) if meta.is_file() || meta.file_type().is_symlink() => Ok(()),
        Ok(meta) => Err(std::io::Error::new(
            std::io::ErrorKind::AlreadyExists,
            format!(
                "it exists and is {}, not a regular file: refusing to replace it",
                kind_of(&meta)
            ),
        )),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(()),
        Err(e) => Err(e),
    }
}

/// What kind of file `meta` describes, with its article.
pub(crate) fn kind_of(meta: &std::fs::Metadata) -> &'static str {
    let t = meta.file_type();
    if t.is_dir() {
        return "a directory";
    }
    if t.is_symlink() {
        return "a symbolic link";
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return "a FIFO";
        }
        if t.is_socket() {
            return "a socket";
        }
        if t.is_block_device() || t.is_char_device() {
            return "a device";
        }
    }
    if t.is_file() {
        return "a regular file";
    }
    "a special file"
}
