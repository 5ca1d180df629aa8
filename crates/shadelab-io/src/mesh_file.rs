//! Mesh files of any supported format, chosen by extension.
//!
//! [`load_mesh`] dispatches on the file's extension (case-insensitive):
//! `.obj` ([`crate::load_obj`]), `.stl` ([`crate::load_stl`]), `.ply`
//! ([`crate::load_ply`]), `.gltf` and `.glb` ([`crate::load_gltf`]);
//! [`load_mesh_file`] also gives the surface colours the file names (an OBJ
//! file's material). Every loader reads at most [`MAX_MESH_BYTES`], builds
//! meshes within the limits of [`Mesh`] (checked against a file's counts
//! before allocating), and reports errors as [`LoadError`]s naming the file.

use std::path::{Path, PathBuf};

use shadelab_core::{Mesh, MeshError, Rgb};

use crate::LoadError;

pub use shadelab_core::limits::MAX_MESH_BYTES;

/// A mesh file's contents: the mesh, and the colours its material gives.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshFile {
    /// The geometry, with the file's normals and smoothing groups if any.
    pub mesh: Mesh,
    /// The material the file gives the mesh, if it gives one with a colour.
    pub material: Option<FileMaterial>,
    /// What was passed over while reading it (a material library that is
    /// missing, outside the model's folder or not a regular file), one
    /// message each, for the user to see.
    pub warnings: Vec<String>,
}

/// Surface colours a mesh file gives: the `Ka` and `Kd` of the material an
/// OBJ file uses (the one on the most faces), from its `.mtl` library.
#[derive(Debug, Clone, PartialEq)]
pub struct FileMaterial {
    /// The material's name.
    pub name: String,
    /// The library that defines it, as the model file names it.
    pub library: String,
    /// Ambient reflectance, 0–1 per channel, if given.
    pub ka: Option<Rgb>,
    /// Diffuse reflectance, 0–1 per channel, if given.
    pub kd: Option<Rgb>,
}

/// The extensions [`load_mesh`] knows, lower case, without the dot.
pub const MESH_EXTENSIONS: &[&str] = &["obj", "stl", "ply", "gltf", "glb"];

/// Reads a mesh file, choosing the format by the extension (case-insensitive).
///
/// # Errors
/// [`LoadError::Invalid`] naming the file and the supported extensions when
/// the extension is none of [`MESH_EXTENSIONS`]; otherwise the format
/// loader's errors.
pub fn load_mesh(path: &Path) -> Result<Mesh, LoadError> {
    match extension(path).as_deref() {
        Some("obj") => crate::load_obj(path),
        _ => load_mesh_file(path).map(|file| file.mesh),
    }
}

/// Reads a mesh file as [`load_mesh`] does, with the colours of its
/// material: for OBJ, those of the material on the most faces, read from
/// the `.mtl` libraries beside it (see [`crate::load_obj_file`]); the other
/// formats give none.
///
/// # Errors
/// As [`load_mesh`]; a material library never causes an error.
pub fn load_mesh_file(path: &Path) -> Result<MeshFile, LoadError> {
    let mesh = match extension(path).as_deref() {
        Some("obj") => return crate::load_obj_file(path),
        Some("stl") => crate::load_stl(path),
        Some("ply") => crate::load_ply(path),
        Some("gltf" | "glb") => crate::load_gltf(path),
        _ => Err(unknown_format(&path.display().to_string())),
    }?;
    Ok(MeshFile {
        mesh,
        material: None,
        warnings: Vec::new(),
    })
}

/// The files besides `path` that loading it reads: an OBJ file's material
/// libraries (each `mtllib` name, whole and split at blanks, beside the
/// file) and a glTF file's external buffers; none for the other formats.
/// For callers that must not write over anything a model came from, so it
/// lists names whether or not they exist, and nothing for a file it cannot
/// read or parse.
pub fn companion_files(path: &Path) -> Vec<PathBuf> {
    let base = path.parent().unwrap_or(Path::new("."));
    match extension(path).as_deref() {
        Some("obj") => crate::obj::library_names(path)
            .into_iter()
            .map(|name| base.join(name))
            .collect(),
        Some("gltf" | "glb") => crate::gltf::external_buffers(path, base),
        _ => Vec::new(),
    }
}

fn extension(path: &Path) -> Option<String> {
    path.extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
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
