//! Reading input files that may come from anyone.
//!
//! Every file shadelab reads (scene, model, material library, glTF buffer)
//! goes through [`read_capped`]: it opens the file without blocking
//! (`O_NONBLOCK`, so a FIFO with no writer cannot stall the open), asks the
//! open file what it is and refuses anything but a regular file (a FIFO, a
//! device such as `/dev/zero` or `/dev/stdin`, a directory, a socket), and
//! reads at most the limit given, so a file that grows while it is read is
//! refused too. A symbolic link to a regular file is followed.
//!
//! A file named by another file (an OBJ file's `mtllib`, a glTF file's
//! buffer URIs) is resolved by [`resolve_inside`]: it must be a relative
//! path that, with every symbolic link resolved, stays inside the folder of
//! the file that names it (with its links resolved too). So a model cannot
//! read `/etc/passwd`, `../../secret` or a link pointing out of its folder,
//! nor show their bytes in an error.

use std::io::Read;
use std::path::{Path, PathBuf};

use shadelab_core::escape_token;

use crate::output::kind_of;
use crate::LoadError;

/// Reads the whole of the regular file at `path`, at most `limit` bytes.
///
/// # Errors
/// [`LoadError::Io`] when it cannot be opened or read;
/// [`LoadError::Invalid`] when it is not a regular file;
/// [`LoadError::TooLarge`] when it holds more than `limit` bytes.
pub(crate) fn read_capped(path: &Path, limit: u64) -> Result<Vec<u8>, LoadError> {
    let name = path.display().to_string();
    let io = |source| LoadError::Io {
        path: name.clone(),
        source,
    };
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        options.custom_flags(libc::O_NONBLOCK);
    }
    let file = options.open(path).map_err(io)?;
    let meta = file.metadata().map_err(io)?;
    if !meta.is_file() {
        return Err(LoadError::Invalid {
            path: name.clone(),
            message: format!(
                "{}, not a regular file: only regular files are read",
                kind_of(&meta)
            ),
        });
    }
    let too_large = |bytes| LoadError::TooLarge {
        path: name.clone(),
        bytes,
        limit,
    };
    let size = meta.len();
    if size > limit {
        return Err(too_large(size));
    }
    // The file may grow between the size check and the read: read one byte
    // more than the limit at most, to notice.
    let mut bytes = Vec::with_capacity(size as usize);
    file.take(limit + 1).read_to_end(&mut bytes).map_err(io)?;
    if bytes.len() as u64 > limit {
        return Err(too_large(bytes.len() as u64));
    }
    Ok(bytes)
}

/// Why a file named by another file is not read.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) enum Refusal {
    /// It does not exist (or a folder on its way does not).
    Missing,
    /// It is absolute, names a drive or a URI scheme, or resolves (through
    /// `..` or a symbolic link) outside the folder.
    Outside,
    /// It could not be looked up.
    Unreadable(String),
}

impl Refusal {
    /// The reason, as a message ends.
    pub(crate) fn describe(&self, reference: &str) -> String {
        let shown = escape_token(reference);
        match self {
            Refusal::Missing => format!("`{shown}` does not exist"),
            Refusal::Outside => format!(
                "`{shown}` is outside the folder that holds the file naming it: only files in \
                 that folder (and its subfolders) are read"
            ),
            Refusal::Unreadable(why) => format!("`{shown}`: {why}"),
        }
    }
}

/// The file `reference` names, relative to `base` (the folder of the file
/// that names it): refused when absolute or when it resolves, with every
/// symbolic link followed, outside `base` (itself resolved).
pub(crate) fn resolve_inside(base: &Path, reference: &str) -> Result<PathBuf, Refusal> {
    let relative = Path::new(reference);
    if reference.is_empty()
        || relative.is_absolute()
        || reference.starts_with(['/', '\\'])
        || relative.has_root()
    {
        return Err(Refusal::Outside);
    }
    let base = if base.as_os_str().is_empty() {
        Path::new(".")
    } else {
        base
    };
    let base = base
        .canonicalize()
        .map_err(|e| Refusal::Unreadable(format!("its folder cannot be resolved: {e}")))?;
    let resolved = match base.join(relative).canonicalize() {
        Ok(p) => p,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            // Say "outside" rather than "missing" for a path that would
            // leave the folder anyway.
            return Err(if escapes_lexically(relative) {
                Refusal::Outside
            } else {
                Refusal::Missing
            });
        }
        Err(e) => return Err(Refusal::Unreadable(e.to_string())),
    };
    if resolved.starts_with(&base) && resolved != base {
        Ok(resolved)
    } else {
        Err(Refusal::Outside)
    }
}

/// Whether `relative`'s `..` components climb above its start.
fn escapes_lexically(relative: &Path) -> bool {
    let mut depth = 0i64;
    for component in relative.components() {
        match component {
            std::path::Component::ParentDir => depth -= 1,
            std::path::Component::Normal(_) => depth += 1,
            std::path::Component::CurDir => {}
            _ => return true,
        }
        if depth < 0 {
            return true;
        }
    }
    false
}

/// `bytes` with every carriage return that does not start a CR LF pair
/// made a line feed, so that text with CR, LF or CR LF line ends (old Mac
/// files, Unix, Windows) reads alike. One byte for one byte: offsets stay.
pub(crate) fn lone_cr_to_lf(bytes: &[u8]) -> std::borrow::Cow<'_, [u8]> {
    let lone = |k: usize| bytes[k] == b'\r' && bytes.get(k + 1) != Some(&b'\n');
    if !(0..bytes.len()).any(lone) {
        return std::borrow::Cow::Borrowed(bytes);
    }
    let mut out = bytes.to_vec();
    for (k, b) in out.iter_mut().enumerate() {
        if lone(k) {
            *b = b'\n';
        }
    }
    std::borrow::Cow::Owned(out)
}

/// [`lone_cr_to_lf`] for text.
pub(crate) fn unify_line_ends(text: &str) -> std::borrow::Cow<'_, str> {
    match lone_cr_to_lf(text.as_bytes()) {
        std::borrow::Cow::Borrowed(_) => std::borrow::Cow::Borrowed(text),
        // Only ASCII bytes were swapped for ASCII bytes.
        std::borrow::Cow::Owned(bytes) => std::borrow::Cow::Owned(
            String::from_utf8(bytes)
                .unwrap_or_else(|e| String::from_utf8_lossy(e.as_bytes()).into_owned()),
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_ends_are_unified() {
        assert_eq!(unify_line_ends("a\rb\r\nc\n\r"), "a\nb\r\nc\n\n");
        assert!(matches!(
            unify_line_ends("a\r\nb\n"),
            std::borrow::Cow::Borrowed(_)
        ));
    }

    #[test]
    fn references_stay_inside_their_folder() {
        let dir = tempfile::tempdir().unwrap();
        let base = dir.path().join("model");
        std::fs::create_dir_all(base.join("sub")).unwrap();
        std::fs::write(base.join("sub/b.bin"), b"x").unwrap();
        std::fs::write(dir.path().join("secret"), b"x").unwrap();
        std::os::unix::fs::symlink(dir.path().join("secret"), base.join("link")).unwrap();
        assert!(resolve_inside(&base, "sub/b.bin").is_ok());
        assert!(resolve_inside(&base, "sub/../sub/b.bin").is_ok());
        for outside in [
            "../secret",
            "link",
            "/etc/passwd",
            "",
            ".",
            "sub/../../secret",
            "../nowhere",
        ] {
            assert_eq!(
                resolve_inside(&base, outside),
                Err(Refusal::Outside),
                "{outside:?}"
            );
        }
        assert_eq!(resolve_inside(&base, "missing.bin"), Err(Refusal::Missing));
    }
}

/// The lines of `text`, each ended by LF, CR LF or a lone CR (not
/// included), as [`str::lines`] gives them for LF and CR LF.
pub(crate) fn lines_any(text: &str) -> impl Iterator<Item = &str> {
    let mut rest = Some(text);
    std::iter::from_fn(move || {
        let current = rest?;
        if current.is_empty() {
            rest = None;
            return None;
        }
        match current.find(['\n', '\r']) {
            Some(end) => {
                let bytes = current.as_bytes();
                let next = if bytes[end] == b'\r' && bytes.get(end + 1) == Some(&b'\n') {
                    end + 2
                } else {
                    end + 1
                };
                rest = Some(&current[next..]);
                Some(&current[..end])
            }
            None => {
                rest = None;
                Some(current)
            }
        }
    })
}

#[cfg(test)]
mod line_tests {
    use super::lines_any;

    #[test]
    fn every_line_end_ends_a_line() {
        let lines: Vec<&str> = lines_any("a\rb\r\nc\n\nd").collect();
        assert_eq!(lines, ["a", "b", "c", "", "d"]);
        assert_eq!(lines_any("x\n").collect::<Vec<_>>(), ["x"]);
        assert_eq!(lines_any("").count(), 0);
        assert_eq!(
            lines_any("one\ntwo\r\n").collect::<Vec<_>>(),
            "one\ntwo\r\n".lines().collect::<Vec<_>>()
        );
    }
}
