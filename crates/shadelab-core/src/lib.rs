//! shadelab's renderer: meshes, vertex normals, the camera, the Phong
//! reflection model, clipping, and the scanline rasterizer that draws flat,
//! Gouraud and Phong shading. No I/O: formats live in `shadelab-io`.
//!
//! Conventions (the project's `docs/conventions.md` is the full table): world
//! right-handed with +y up; OpenGL projection with NDC z in [-1, 1] and depth
//! test "less"; window row 0 at the top; pixel centres at half-integers; top-left
//! fill rule; front faces counter-clockwise as the viewer sees them.
#![warn(missing_docs)]

#[macro_use]
pub mod choice;
mod camera;
mod clip;
mod color;
pub mod cores;
mod frame;
mod image;
mod light;
pub mod limits;
mod mesh;
mod models;
mod normals;
mod palette;
pub mod params;
mod probe;
pub mod raster;
mod scene;
mod shade;
mod simd;
mod text;

pub use camera::{Camera, CameraError};
pub use choice::{Choice, UnknownChoice};
pub use clip::{clip_polygon, ClipVertex};
pub use color::{Rgb, Rgb8};
pub use frame::to_window;
pub use frame::{coverage, draws_in_parts, part_rows, render, Renderer, ROW_ALIGN};
pub use image::Image;
pub use light::{Light, LightKind, LightKindName, Material, Specular, NO_ATTENUATION};
pub use limits::{MAX_IMAGE_PIXELS, MAX_IMAGE_SIDE};
pub use mesh::{CornerNormals, Mesh, MeshError};
pub use models::{builtin_model, builtin_model_info, ModelError, ModelInfo, BUILTIN_MODELS};
pub use normals::{
    face_normal, face_normal_unnormalized, face_normals, vertex_normals, NormalWeighting,
    NormalsChoice,
};
pub use palette::{Palette, PaletteShade};
pub use probe::{
    depth_buffer, probe, EdgeRecord, FragmentRecord, ProbeRequest, SpanRecord, SteppedRecord,
    VertexRecord,
};
pub use raster::Interpolation;
pub use scene::{Polygons, Rasterizer, RenderError, RenderOptions, RenderStats, Scene, Shading};
pub use shade::{LightTerm, Lighting, LightingTerms, Terms};
pub use simd::SimdLevel;
pub use text::{escape_message, escape_token, format_number, is_unsafe_char};
