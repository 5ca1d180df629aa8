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
mod model;
mod scalar;

pub(crate) use self::blocks::{
    byte_units, FlatShader, GouraudShader, PhongShader, Shader, MAX_ATTRS,
};
pub use self::model::{
    Light, LightKind, LightTerm, Lighting, LightingTerms, Material, Specular, Terms,
};
pub(crate) use self::scalar::{
    with_method, Indexed, Method, MethodVisitor, Output, SceneRefs, TrueColor,
};

/// The three classic shading methods: the one definition every layer uses
/// (names and help declared below, see [`crate::choice`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Shading {
    /// One lighting evaluation per polygon.
    Flat,
    /// Lighting per vertex, colours interpolated.
    Gouraud,
    /// Normals interpolated and lit per pixel.
    #[default]
    Phong,
}

choices!(Shading, "shading method", {
    Flat => "flat": "one lighting evaluation per polygon",
    Gouraud => "gouraud": "lighting per vertex, colours interpolated",
    Phong => "phong": "normals interpolated, lighting per pixel",
});

impl Shading {
    /// The display name ("Flat", "Gouraud", "Phong").
    pub fn title(self) -> &'static str {
        match self {
            Shading::Flat => "Flat",
            Shading::Gouraud => "Gouraud",
            Shading::Phong => "Phong",
        }
    }
}
