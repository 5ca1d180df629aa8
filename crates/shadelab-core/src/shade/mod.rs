//! The shading stage: the three classic methods and the reflection model
//! they all evaluate.
//!
//! | method  | lighting evaluated          | interpolated            |
//! |---------|-----------------------------|-------------------------|
//! | flat    | once per polygon (centroid) | nothing but depth       |
//! | Gouraud | once per distinct vertex    | the vertex colours      |
//! | Phong   | once per pixel              | normal, world position  |
//!
//! The reflection model is written twice, once per arithmetic: `model.rs`
//! in scalars (the specification, and what the scanline rasterizer and the
//! probe use) and `lanes.rs` in SIMD lanes (what the tiled rasterizer uses,
//! tested against the scalar one). `scalar.rs` and `blocks.rs` are the three
//! methods on top of each: per fragment, and per block of 8 fragments.
//!
//! This layer knows nothing of rasterizers or frames: it sees points,
//! normals, attributes and colours (see `docs/architecture.md`).

mod blocks;
mod lanes;
mod model;
mod scalar;

pub(crate) use self::blocks::{
    known, AllMethods, FlatShader, GouraudShader, PhongShader, Shader, MAX_ATTRS,
};
pub(crate) use self::lanes::byte_units;
pub use self::model::{LightTerm, Lighting, LightingTerms, Terms};
pub(crate) use self::scalar::{
    with_method, Indexed, Method, MethodVisitor, Output, SceneRefs, TrueColor,
};
