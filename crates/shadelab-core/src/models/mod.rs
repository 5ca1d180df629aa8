//! Built-in models: procedural solids and the Utah teapot.
//!
//! Every model is wound counter-clockwise seen from outside, and every solid
//! is closed (each edge shared by exactly two polygons); the teapot keeps the
//! openings of Newell's original patches. The `detail` of a model is its
//! tessellation level; the defaults are low so the three methods differ visibly.

mod primitives;
mod teapot;

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
    BUILTIN_MODELS
        .iter()
        .map(|m| m.name)
        .collect::<Vec<_>>()
        .join(", ")
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
    let info = builtin_model_info(name).ok_or_else(|| ModelError::Unknown {
        name: name.to_owned(),
    })?;
    let detail = detail.unwrap_or(info.default_detail);
    let (min, max) = info.detail_range;
    if !(min..=max).contains(&detail) {
        return Err(ModelError::Detail {
            name: info.name,
            detail,
            min,
            max,
        });
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

#[cfg(test)]
mod tests {
    use std::collections::HashMap;

    use super::*;
    use crate::normals::face_normal_unnormalized;

    /// Directed edges and how often each appears.
    fn directed_edges(mesh: &Mesh) -> HashMap<(u32, u32), u32> {
        let mut edges = HashMap::new();
        for f in 0..mesh.polygon_count() {
            let p = mesh.polygon(f);
            for k in 0..p.len() {
                *edges.entry((p[k], p[(k + 1) % p.len()])).or_insert(0) += 1;
            }
        }
        edges
    }

    /// Signed volume enclosed by the mesh (positive when wound outward).
    fn signed_volume(mesh: &Mesh) -> f32 {
        let pos = mesh.positions();
        (0..mesh.polygon_count())
            .map(|f| {
                let p = mesh.polygon(f);
                (1..p.len() - 1)
                    .map(|k| {
                        let (a, b, c) = (
                            pos[p[0] as usize],
                            pos[p[k] as usize],
                            pos[p[k + 1] as usize],
                        );
                        a.dot(b.cross(c)) / 6.0
                    })
                    .sum::<f32>()
            })
            .sum()
    }

    #[test]
    fn solids_are_closed_and_consistently_wound() {
        for info in BUILTIN_MODELS.iter().filter(|m| m.name != "teapot") {
            for detail in [
                info.detail_range.0,
                info.default_detail,
                info.default_detail * 2,
            ]
            .into_iter()
            .filter(|d| *d <= info.detail_range.1)
            {
                let mesh = builtin_model(info.name, Some(detail)).unwrap();
                let edges = directed_edges(&mesh);
                for (&(a, b), &count) in &edges {
                    assert_eq!(
                        count, 1,
                        "{} {detail}: edge {a}->{b} used {count} times",
                        info.name
                    );
                    assert_eq!(
                        edges.get(&(b, a)),
                        Some(&1),
                        "{} {detail}: edge {a}->{b} has no opposite: not closed or not consistently wound",
                        info.name
                    );
                }
                assert!(
                    signed_volume(&mesh) > 0.0,
                    "{} {detail} is wound inward",
                    info.name
                );
            }
        }
    }

    #[test]
    fn solid_volumes_approach_the_analytic_ones() {
        use std::f32::consts::PI;
        let cases = [
            ("cube", 1, 8.0, 1e-5),
            ("sphere", 256, 4.0 / 3.0 * PI, 2e-3),
            ("icosphere", 5, 4.0 / 3.0 * PI, 2e-3),
            ("torus", 256, 2.0 * PI * PI * 1.0 * 0.4 * 0.4, 2e-3),
            ("cylinder", 512, PI * 2.0, 1e-3),
            ("cone", 512, PI * 2.0 / 3.0, 1e-3),
        ];
        for (name, detail, exact, tolerance) in cases {
            let v = signed_volume(&builtin_model(name, Some(detail)).unwrap());
            assert!(
                ((v - exact) / exact).abs() < tolerance,
                "{name}: volume {v}, exact {exact}"
            );
        }
    }

    #[test]
    fn every_polygon_is_planar_and_non_degenerate() {
        for info in BUILTIN_MODELS.iter().filter(|m| m.name != "teapot") {
            let mesh = builtin_model(info.name, None).unwrap();
            for f in 0..mesh.polygon_count() {
                let pts: Vec<_> = mesh
                    .polygon(f)
                    .iter()
                    .map(|&i| mesh.positions()[i as usize])
                    .collect();
                let n = face_normal_unnormalized(&pts);
                assert!(n.length() > 1e-6, "{} face {f} is degenerate", info.name);
                let n = n.normalize();
                for p in &pts {
                    assert!(
                        (n.dot(*p - pts[0])).abs() < 1e-5,
                        "{} face {f} is not planar",
                        info.name
                    );
                }
            }
        }
    }

    #[test]
    fn sphere_counts_follow_the_detail() {
        let mesh = builtin_model("sphere", Some(12)).unwrap();
        // 12 slices, 6 stacks: two poles and 5 rings of 12.
        assert_eq!(mesh.positions().len(), 2 + 5 * 12);
        assert_eq!(mesh.polygon_count(), 12 * 6);
        let triangles = (0..mesh.polygon_count())
            .filter(|&f| mesh.polygon(f).len() == 3)
            .count();
        assert_eq!(triangles, 24);
        let ico = builtin_model("icosphere", Some(2)).unwrap();
        assert_eq!(ico.polygon_count(), 20 * 16);
        assert_eq!(ico.positions().len(), 162);
    }

    #[test]
    fn bad_names_and_details_are_errors() {
        assert!(matches!(
            builtin_model("dodecahedron", None),
            Err(ModelError::Unknown { .. })
        ));
        let e = builtin_model("sphere", Some(2)).unwrap_err();
        assert!(e.to_string().contains("3..=512"), "{e}");
        assert!(builtin_model("icosphere", Some(8)).is_err());
    }
}
