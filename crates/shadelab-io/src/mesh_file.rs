//! Mesh files of any supported format, chosen by extension.
//!
//! [`load_mesh`] dispatches on the file's extension (case-insensitive):
//! `.obj` ([`crate::load_obj`]), `.stl` ([`crate::load_stl`]), `.ply`
//! ([`crate::load_ply`]), `.gltf` and `.glb` ([`crate::load_gltf`]). Every
//! loader reads at most [`MAX_MESH_BYTES`] and reports errors as
//! [`LoadError`]s naming the file.

use std::io::Read;
use std::path::Path;

use shadelab_core::{Mesh, MeshError};

use crate::LoadError;

/// Largest mesh file read, in bytes, whatever its format (the same 1 GiB as
/// [`crate::MAX_OBJ_BYTES`]). For glTF it bounds the `.gltf` file and every
/// external buffer together.
pub const MAX_MESH_BYTES: u64 = crate::MAX_OBJ_BYTES;

/// The extensions [`load_mesh`] knows, lower case, without the dot.
pub const MESH_EXTENSIONS: &[&str] = &["obj", "stl", "ply", "gltf", "glb"];

/// Reads a mesh file, choosing the format by the extension (case-insensitive).
///
/// # Errors
/// [`LoadError::Invalid`] naming the file and the supported extensions when
/// the extension is none of [`MESH_EXTENSIONS`]; otherwise the format
/// loader's errors.
pub fn load_mesh(path: &Path) -> Result<Mesh, LoadError> {
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match extension.as_deref() {
        Some("obj") => crate::load_obj(path),
        Some("stl") => crate::load_stl(path),
        Some("ply") => crate::load_ply(path),
        Some("gltf" | "glb") => crate::load_gltf(path),
        _ => Err(unknown_format(&path.display().to_string())),
    }
}

/// Parses a mesh file's bytes, choosing the format by the extension of
/// `name` (case-insensitive), as [`load_mesh`] does: for a file that did not
/// come from disk (the viewer's uploads). A glTF file must be self-contained
/// (a `.glb`, or buffers embedded as data URIs).
///
/// # Errors
/// As [`load_mesh`]; an OBJ file that is not UTF-8 text is
/// [`LoadError::Invalid`].
pub fn parse_mesh(bytes: &[u8], name: &str) -> Result<Mesh, LoadError> {
    let extension = Path::new(name)
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match extension.as_deref() {
        Some("obj") => {
            let text = std::str::from_utf8(bytes).map_err(|e| {
                invalid(
                    name,
                    format!(
                        "not UTF-8 text (invalid byte at offset {})",
                        e.valid_up_to()
                    ),
                )
            })?;
            crate::parse_obj(text, name)
        }
        Some("stl") => crate::parse_stl(bytes, name),
        Some("ply") => crate::parse_ply(bytes, name),
        Some("gltf" | "glb") => crate::parse_gltf(bytes, name, None),
        _ => Err(unknown_format(name)),
    }
}

fn unknown_format(name: &str) -> LoadError {
    invalid(
        name,
        format!(
            "unknown mesh format: the extension must be one of {}",
            MESH_EXTENSIONS
                .iter()
                .map(|e| format!(".{e}"))
                .collect::<Vec<_>>()
                .join(", ")
        ),
    )
}

/// Reads a whole file of at most `limit` bytes.
pub(crate) fn read_capped(path: &Path, limit: u64) -> Result<Vec<u8>, LoadError> {
    let name = path.display().to_string();
    let io = |source| LoadError::Io {
        path: name.clone(),
        source,
    };
    let file = std::fs::File::open(path).map_err(io)?;
    let size = file.metadata().map_err(io)?.len();
    let too_large = |bytes| LoadError::TooLarge {
        path: name.clone(),
        bytes,
        limit,
    };
    if size > limit {
        return Err(too_large(size));
    }
    // The file may grow between the size check and the read: read one byte
    // more than the limit at most, to notice.
    let mut bytes = Vec::with_capacity(size as usize);
    file.take(limit + 1)
        .read_to_end(&mut bytes)
        .map_err(|source| LoadError::Io {
            path: name.clone(),
            source,
        })?;
    if bytes.len() as u64 > limit {
        return Err(too_large(bytes.len() as u64));
    }
    Ok(bytes)
}

/// A [`LoadError::Invalid`] for `name`.
pub(crate) fn invalid(name: &str, message: impl Into<String>) -> LoadError {
    LoadError::Invalid {
        path: name.to_owned(),
        message: message.into(),
    }
}

/// A [`MeshError`] as a [`LoadError::Invalid`] for `name`.
pub(crate) fn mesh_error(name: &str) -> impl Fn(MeshError) -> LoadError + '_ {
    move |e| invalid(name, e.to_string())
}
