//! Built-in models: procedural solids and the Utah teapot.
//!
//! Every model is wound counter-clockwise seen from outside, and every solid
//! is closed (each edge shared by exactly two polygons); the teapot keeps the
//! openings of Newell's original patches. The `detail` of a model is its
//! tessellation level; the defaults are low so the three methods differ visibly.

mod primitives;
// TEMP until teapot.rs lands
mod teapot { pub const DEFAULT_DETAIL: u32 = 8; pub fn teapot(_: u32) -> crate::Mesh { super::primitives::cube(1) } }

use crate::mesh::Mesh;

/// What the model list says about one built-in model.
#[derive(Debug, Clone, PartialEq)]
pub struct ModelInfo {
    /// The name to ask for it by.
    pub name: &'static str,
    /// One line about it.
    pub description: &'static str,
    /// What `detail` means for it.
    pub detail_meaning: &'static str,
    /// Detail used when none is given.
    pub default_detail: u32,
    /// Smallest and largest detail accepted.
    pub detail_range: (u32, u32),
    /// Crease angle used when the scene sets none (degrees), for models
    /// with sharp edges that smoothing would smear.
    pub default_crease_degrees: Option<f32>,
}

/// The built-in models, in the order they are listed.
pub const BUILTIN_MODELS: &[ModelInfo] = &[
    ModelInfo {
        name: "cube",
        description: "cube of side 2: six quads on eight shared vertices",
        detail_meaning: "quads per edge",
        default_detail: 1,
        detail_range: (1, 64),
        default_crease_degrees: None,
    },
    ModelInfo {
        name: "sphere",
        description: "UV sphere of radius 1: quads, triangles at the poles",
        detail_meaning: "slices around the axis (stacks: half as many)",
        default_detail: 12,
        detail_range: (3, 512),
        default_crease_degrees: None,
    },
    ModelInfo {
        name: "icosphere",
        description: "subdivided icosahedron of radius 1: near-uniform triangles",
        detail_meaning: "subdivisions of the icosahedron",
        default_detail: 1,
        detail_range: (0, 7),
        default_crease_degrees: None,
    },
    ModelInfo {
        name: "torus",
        description: "torus, ring radius 1, tube radius 0.4: quads",
        detail_meaning: "segments around the ring (around the tube: half as many)",
        default_detail: 24,
        detail_range: (3, 512),
        default_crease_degrees: None,
    },
    ModelInfo {
        name: "cylinder",
        description: "cylinder of radius 1 and height 2: quad sides, polygon caps",
        detail_meaning: "slices around the axis",
        default_detail: 16,
        detail_range: (3, 1024),
        default_crease_degrees: Some(60.0),
    },
    ModelInfo {
        name: "cone",
        description: "cone of radius 1 and height 2: triangle sides, polygon base",
        detail_meaning: "slices around the axis",
        default_detail: 16,
        detail_range: (3, 1024),
        default_crease_degrees: Some(60.0),
    },
    ModelInfo {
        name: "teapot",
        description: "the Utah teapot from Newell's 32 Bézier patches",
        detail_meaning: "quads along each patch edge",
        default_detail: teapot::DEFAULT_DETAIL,
        detail_range: (1, 64),
        default_crease_degrees: None,
    },
];

/// Why a built-in model could not be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ModelError {
    /// No built-in model has that name.
    #[error("no built-in model named {name:?} (built-in models: {})", names())]
    Unknown {
        /// The name asked for.
        name: String,
    },
    /// The detail is out of the model's range.
    #[error("detail {detail} is out of range for {name}: {min}..={max}")]
    Detail {
        /// The model.
        name: &'static str,
        /// The detail asked for.
        detail: u32,
        /// Smallest accepted.
        min: u32,
        /// Largest accepted.
        max: u32,
    },
}

fn names() -> String {
    BUILTIN_MODELS.iter().map(|m| m.name).collect::<Vec<_>>().join(", ")
}

/// Information on the built-in model `name`, if there is one.
pub fn builtin_model_info(name: &str) -> Option<&'static ModelInfo> {
    BUILTIN_MODELS.iter().find(|m| m.name == name)
}

/// Makes built-in model `name` at `detail` (its default when `None`).
///
/// # Errors
/// [`ModelError`] for an unknown name or a detail out of range.
pub fn builtin_model(name: &str, detail: Option<u32>) -> Result<Mesh, ModelError> {
    let info = builtin_model_info(name).ok_or_else(|| ModelError::Unknown { name: name.to_owned() })?;
    let detail = detail.unwrap_or(info.default_detail);
    let (min, max) = info.detail_range;
    if !(min..=max).contains(&detail) {
        return Err(ModelError::Detail { name: info.name, detail, min, max });
    }
    Ok(match info.name {
        "cube" => primitives::cube(detail),
        "sphere" => primitives::uv_sphere(detail),
        "icosphere" => primitives::icosphere(detail),
        "torus" => primitives::torus(detail),
        "cylinder" => primitives::cylinder(detail),
        "cone" => primitives::cone(detail),
        "teapot" => teapot::teapot(detail),
        _ => unreachable!("every listed model is built above"),
    })
}
