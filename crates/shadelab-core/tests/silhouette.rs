//! Property: a closed convex mesh seen from outside covers every pixel of its
//! silhouette exactly once and nothing else, through both rasterizers — on
//! random convex polyhedra (the hull of random points on a sphere) and on
//! the closed convex built-in models at random detail, from random views.
//!
//! The silhouette is computed independently of the renderer: the convex hull
//! of the vertices projected (in f64, from the camera's parameters) and
//! snapped to 1/256 pixel. Pixel centres within 0.05 pixel of its outline
//! may go either way (faces seen edge-on there may snap to either side);
//! every other pixel must be covered exactly once inside, never outside.

mod common;

use common::*;
use glam::{DVec3, Vec3};
use proptest::prelude::*;
use shadelab_core::{
    builtin_model, coverage, vertex_normals, Mesh, NormalWeighting, Rasterizer, RenderOptions,
    Shading,
};

/// The triangles of the convex hull of `points` (all on its surface),
/// wound counter-clockwise seen from outside, by brute force over triples;
/// `None` when four points are too close to coplanar for the faces to be
/// decided safely.
fn hull_triangles(points: &[DVec3]) -> Option<Vec<[u32; 3]>> {
    let n = points.len();
    let mut faces = Vec::new();
    for i in 0..n {
        for j in i + 1..n {
            for k in j + 1..n {
                let (a, b, c) = (points[i], points[j], points[k]);
                let normal = (b - a).cross(c - a);
                let scale = normal.length();
                let (mut above, mut below) = (0, 0);
                for (m, &p) in points.iter().enumerate() {
                    if m == i || m == j || m == k {
                        continue;
                    }
                    let side = normal.dot(p - a) / scale;
                    if side.abs() < 1e-6 {
                        return None;
                    }
                    if side > 0.0 {
                        above += 1;
                    } else {
                        below += 1;
                    }
                }
                let (i, j, k) = (i as u32, j as u32, k as u32);
                if above == 0 {
                    faces.push([i, j, k]);
                } else if below == 0 {
                    faces.push([i, k, j]);
                }
            }
        }
    }
    Some(faces)
}

/// Checks the property for `mesh` (inside the unit sphere) seen from `eye`,
/// with both rasterizers; returns the number of pixels checked.
fn check(
    mesh: &Mesh,
    eye: DVec3,
    target: DVec3,
    fov: f32,
    w: u32,
    h: u32,
) -> Result<usize, String> {
    let normals = vertex_normals(mesh, NormalWeighting::Uniform, None);
    let cam = camera(eye, target, fov, 0.1, 50.0);
    if cam.validate().is_err() {
        return Ok(0);
    }
    let scene = scene(mesh.clone(), normals, cam);
    let view = View::new(&scene.camera, w, h);
    let points: Vec<(i64, i64)> = mesh
        .positions()
        .iter()
        .map(|&p| view.snapped(d(p)))
        .collect();
    let outline = convex_hull(&points);
    let mut checked = 0;
    for rasterizer in Rasterizer::ALL {
        let options = RenderOptions {
            rasterizer,
            ..options(w, h, Shading::Flat)
        };
        let counts = coverage(&scene, &options).map_err(|e| e.to_string())?;
        checked += compare_counts(
            &format!("silhouette-{rasterizer:?}"),
            &counts,
            w,
            h,
            |i, j| {
                if outline.len() < 3 {
                    return Some(0..=1);
                }
                let inside = inside_distance(&outline, f64::from(i) + 0.5, f64::from(j) + 0.5);
                Some(if inside > 0.05 {
                    1..=1
                } else if inside < -0.05 {
                    0..=0
                } else {
                    0..=1
                })
            },
        )?;
    }
    Ok(checked)
}

fn direction() -> impl Strategy<Value = DVec3> {
    (-1.0f64..1.0, 0.0f64..std::f64::consts::TAU).prop_map(|(z, a)| {
        let r = (1.0 - z * z).sqrt();
        DVec3::new(r * a.cos(), r * a.sin(), z)
    })
}

/// A view from outside the unit sphere, looking near its centre.
fn view() -> impl Strategy<Value = (DVec3, DVec3, f32, u32, u32)> {
    (
        direction(),
        1.6f64..8.0,
        prop::array::uniform3(-0.3f64..0.3),
        15.0f32..100.0,
        8u32..72,
        8u32..72,
    )
        .prop_map(|(dir, distance, t, fov, w, h)| (dir * distance, DVec3::from_array(t), fov, w, h))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn random_convex_polyhedra(
        dirs in prop::collection::vec(direction(), 4..16),
        radius in 0.3f64..1.0,
        (eye, target, fov, w, h) in view(),
    ) {
        let points: Vec<DVec3> = dirs.iter().map(|&d| d * radius).collect();
        let faces = hull_triangles(&points);
        prop_assume!(faces.is_some());
        let faces = faces.unwrap();
        // Euler: a closed triangulated sphere with V vertices has 2V − 4 faces.
        prop_assume!(faces.len() == 2 * points.len() - 4);
        let positions: Vec<Vec3> = points.iter().map(|&p| f(p)).collect();
        let mesh = Mesh::from_polygons(positions, faces).unwrap();
        let checked = check(&mesh, eye, target, fov, w, h).map_err(TestCaseError::fail)?;
        prop_assume!(checked > 0, "the camera's up was along its view");
    }

    #[test]
    fn closed_convex_builtin_models(
        which in 0usize..5,
        detail in 0u32..40,
        (eye, target, fov, w, h) in view(),
    ) {
        let (model, detail) = match which {
            0 => ("sphere", 3 + detail),
            1 => ("icosphere", detail % 4),
            2 => ("cube", 1 + detail % 6),
            3 => ("cylinder", 3 + detail),
            _ => ("cone", 3 + detail),
        };
        let mesh = builtin_model(model, Some(detail)).unwrap().normalized();
        let checked = check(&mesh, eye, target, fov, w, h)
            .map_err(|e| TestCaseError::fail(format!("{model} {detail}: {e}")))?;
        prop_assume!(checked > 0, "the camera's up was along its view");
    }
}

#[test]
fn the_hull_of_a_tetrahedron_and_an_octahedron() {
    let tetra = [
        DVec3::new(1.0, 1.0, 1.0),
        DVec3::new(1.0, -1.0, -1.0),
        DVec3::new(-1.0, 1.0, -1.0),
        DVec3::new(-1.0, -1.0, 1.0),
    ];
    let faces = hull_triangles(&tetra).unwrap();
    assert_eq!(faces.len(), 4);
    for face in &faces {
        let [a, b, c] = face.map(|i| tetra[i as usize]);
        // Counter-clockwise from outside: the normal points away from the centre.
        assert!((b - a).cross(c - a).dot(a) > 0.0, "{face:?}");
    }
    // Four coplanar points (an octahedron's equator) are refused.
    let octa = [
        DVec3::X,
        DVec3::NEG_X,
        DVec3::Y,
        DVec3::NEG_Y,
        DVec3::Z,
        DVec3::NEG_Z,
    ];
    assert!(hull_triangles(&octa).is_none());
    let mesh = Mesh::from_polygons(tetra.iter().map(|&p| f(p * 0.5)).collect(), faces).unwrap();
    let checked = check(&mesh, DVec3::new(0.3, 0.4, 3.0), DVec3::ZERO, 45.0, 40, 30).unwrap();
    assert!(checked > 0);
}
