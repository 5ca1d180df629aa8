//! shadelab's file formats: OBJ, STL, PLY and glTF meshes in, TOML scenes, PNG images out,
//! and the one way every command writes a file ([`write_atomic`]).
#![warn(missing_docs)]

mod gltf;
mod input;
mod mesh_file;
mod mtl;
mod obj;
mod output;
mod ply;
mod png;
mod scene;
mod stl;

pub use gltf::{load_gltf, parse_gltf};
pub use mesh_file::{
    companion_files, load_mesh, load_mesh_file, parse_mesh, FileMaterial, MeshFile, MAX_MESH_BYTES,
    MESH_EXTENSIONS,
};
pub use obj::{load_obj, load_obj_file, parse_obj, parse_obj_file};
pub use output::{write_atomic, STDOUT_PATH};
pub use ply::{load_ply, parse_ply};
pub use png::{encode_png, encode_png_with, read_png, write_png, write_png_with, PngCompression};
pub use scene::{
    model_path, AmbientSection, CameraSection, LightKindName, LightSection, MaterialSection,
    ModelSection, NormalsChoice, RenderSection, SceneError, SceneFile, MAX_ZOOM, MIN_ZOOM,
};
pub use stl::{load_stl, parse_stl};

/// Why a mesh file could not be loaded.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum LoadError {
    /// The file could not be read.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// What went wrong.
        source: std::io::Error,
    },
    /// A line is malformed or refers to something that does not exist.
    #[error("{path}:{line}: {message}")]
    Syntax {
        /// The file.
        path: String,
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// The file as a whole is not a usable mesh.
    #[error("{path}: {message}")]
    Invalid {
        /// The file.
        path: String,
        /// What is wrong.
        message: String,
    },
    /// The file is larger than the documented limit.
    #[error("{path}: {bytes} bytes is more than the limit of {limit} bytes")]
    TooLarge {
        /// The file.
        path: String,
        /// Its size.
        bytes: u64,
        /// The limit.
        limit: u64,
    },
}
