//! Face and vertex normals on meshes whose answers are known: a cube's
//! corners and edges, vertices shared by faces of different sizes and
//! angles, crease angles that split a cube's corners, and extreme scales.

mod common;

use std::f64::consts::{FRAC_PI_2, FRAC_PI_3};

use common::*;
use glam::{DVec3, Vec3};
use shadelab_core::{
    builtin_model, face_normal, vertex_normals, CornerNormals, Mesh, NormalWeighting,
};

const ALL: [NormalWeighting; 3] = [
    NormalWeighting::Uniform,
    NormalWeighting::Area,
    NormalWeighting::Angle,
];

fn corner_normal(normals: &CornerNormals, corner: usize) -> DVec3 {
    d(normals.normals[normals.corner()[corner] as usize])
}

/// Every corner of `vertex` has the normal `expected` (normalised here).
fn assert_vertex_normal(
    mesh: &Mesh,
    normals: &CornerNormals,
    vertex: u32,
    expected: DVec3,
    what: &str,
) {
    let expected = expected.normalize();
    let mut found = 0;
    for (c, &v) in mesh.corners().iter().enumerate() {
        if v == vertex {
            found += 1;
            let n = corner_normal(normals, c);
            assert!(
                (n - expected).length() < 1e-6,
                "{what}: vertex {vertex} at {:?}, corner {c}: {n:?}, expected {expected:?}",
                mesh.positions()[vertex as usize]
            );
        }
    }
    assert!(found > 0, "{what}: vertex {vertex} is not used");
}

fn index_of(mesh: &Mesh, p: Vec3) -> u32 {
    mesh.positions()
        .iter()
        .position(|&q| (q - p).length() < 1e-5)
        .unwrap_or_else(|| panic!("no vertex at {p:?}")) as u32
}

/// On a cube every vertex's faces are squares meeting at right angles, with
/// as many quads on each face around it: corners get (±1, ±1, ±1)/√3, edge
/// vertices (±1, ±1, 0)/√2, face vertices the face's axis, whatever the weighting.
#[test]
fn cube_vertices_in_every_weighting() {
    for detail in [1, 2, 3, 8] {
        let mesh = builtin_model("cube", Some(detail)).unwrap();
        for weighting in ALL {
            let normals = vertex_normals(&mesh, weighting, None);
            assert_eq!(normals.corner().len(), mesh.corners().len());
            for (v, &p) in mesh.positions().iter().enumerate() {
                let p = d(p);
                let on_face = |x: f64| {
                    if (x.abs() - 1.0).abs() < 1e-6 {
                        x.signum()
                    } else {
                        0.0
                    }
                };
                let expected = DVec3::new(on_face(p.x), on_face(p.y), on_face(p.z));
                assert_vertex_normal(
                    &mesh,
                    &normals,
                    v as u32,
                    expected,
                    &format!("cube{detail} {weighting:?}"),
                );
            }
        }
    }
    // The corner (1, 1, 1) spelled out.
    let mesh = builtin_model("cube", Some(1)).unwrap();
    let normals = vertex_normals(&mesh, NormalWeighting::Uniform, None);
    let v = index_of(&mesh, Vec3::ONE);
    let s = 1.0 / 3f64.sqrt();
    assert_vertex_normal(&mesh, &normals, v, DVec3::new(s, s, s), "cube corner");
}

/// Vertex O shared by a big right-angled triangle in z = 0 (normal +z, area
/// 8, angle 90°) and a small triangle in y = 0 (normal −y, area 1, angle 45°).
///   uniform: +z − y                → (0, −1, 1)/√2
///   area:    8·(+z) + 1·(−y)       → (0, −1, 8)/√65
///   angle:   (π/2)·(+z) + (π/4)·(−y) → (0, −1, 2)/√5
#[test]
fn big_and_small_triangle_at_a_known_angle() {
    let positions = vec![
        Vec3::ZERO,
        Vec3::new(4.0, 0.0, 0.0),
        Vec3::new(0.0, 4.0, 0.0),
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(1.0, 0.0, 1.0),
    ];
    let mesh = Mesh::from_polygons(positions, [[0u32, 1, 2], [0, 3, 4]]).unwrap();
    let cases = [
        (NormalWeighting::Uniform, DVec3::new(0.0, -1.0, 1.0)),
        (NormalWeighting::Area, DVec3::new(0.0, -1.0, 8.0)),
        (NormalWeighting::Angle, DVec3::new(0.0, -1.0, 2.0)),
    ];
    for (weighting, expected) in cases {
        let normals = vertex_normals(&mesh, weighting, None);
        assert_vertex_normal(&mesh, &normals, 0, expected, &format!("{weighting:?}"));
        // Vertices of one face only take that face's normal.
        for v in [1, 2] {
            assert_vertex_normal(&mesh, &normals, v, DVec3::Z, &format!("{weighting:?}"));
        }
        for v in [3, 4] {
            assert_vertex_normal(&mesh, &normals, v, -DVec3::Y, &format!("{weighting:?}"));
        }
    }
}

/// A quad (Newell's normal +z, area 4, corner 90°) and a triangle (normal
/// −y, area √3/2, corner 60°) sharing O:
///   uniform → (0, −1, 1)/√2, area → (0, −√3/2, 4), angle → (0, −π/3, π/2) ∝ (0, −2, 3).
#[test]
fn quad_and_triangle_sharing_a_vertex() {
    let s3 = 3f32.sqrt();
    let positions = vec![
        Vec3::ZERO,
        Vec3::new(0.0, -2.0, 0.0),
        Vec3::new(2.0, -2.0, 0.0),
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(1.0, 0.0, s3),
    ];
    let mesh = Mesh::from_polygons(positions, [vec![0u32, 1, 2, 3], vec![0, 4, 5]]).unwrap();
    let cases = [
        (NormalWeighting::Uniform, DVec3::new(0.0, -1.0, 1.0)),
        (
            NormalWeighting::Area,
            DVec3::new(0.0, -(3f64.sqrt()) / 2.0, 4.0),
        ),
        (
            NormalWeighting::Angle,
            DVec3::new(0.0, -FRAC_PI_3, FRAC_PI_2),
        ),
    ];
    for (weighting, expected) in cases {
        let normals = vertex_normals(&mesh, weighting, None);
        assert_vertex_normal(&mesh, &normals, 0, expected, &format!("{weighting:?}"));
    }
    let angle = vertex_normals(&mesh, NormalWeighting::Angle, None);
    assert_vertex_normal(
        &mesh,
        &angle,
        0,
        DVec3::new(0.0, -2.0, 3.0),
        "angle, integers",
    );
}

/// An irregular fan around a vertex, where uniform, area and angle weighting
/// all differ: each checked against the definition evaluated in f64.
#[test]
fn irregular_fan_against_the_definitions() {
    // The hub, and a ring of points at uneven angles, radii and heights.
    let ring: Vec<DVec3> = [
        (0.0, 1.0, 0.8),
        (50.0, 2.5, -0.6),
        (130.0, 0.6, 0.4),
        (200.0, 1.8, 1.0),
        (290.0, 1.2, -0.9),
    ]
    .iter()
    .map(|&(deg, r, z): &(f64, f64, f64)| {
        DVec3::new(r * deg.to_radians().cos(), r * deg.to_radians().sin(), z)
    })
    .collect();
    let mut positions = vec![Vec3::new(0.0, 0.0, 0.2)];
    positions.extend(ring.iter().map(|&p| f(p)));
    let n = ring.len() as u32;
    let triangles: Vec<[u32; 3]> = (0..n).map(|k| [0, 1 + k, 1 + (k + 1) % n]).collect();
    let mesh = Mesh::from_polygons(positions, &triangles).unwrap();
    let hub = d(mesh.positions()[0]);
    let mut sums = [DVec3::ZERO; 3];
    for k in 0..ring.len() {
        let (a, b) = (ring[k], ring[(k + 1) % ring.len()]);
        let cross = (a - hub).cross(b - hub);
        let unit = cross.normalize();
        let area = 0.5 * cross.length();
        let angle = (a - hub).normalize().dot((b - hub).normalize()).acos();
        sums[0] += unit;
        sums[1] += unit * area;
        sums[2] += unit * angle;
    }
    for (weighting, sum) in ALL.into_iter().zip(sums) {
        let normals = vertex_normals(&mesh, weighting, None);
        assert_vertex_normal(&mesh, &normals, 0, sum, &format!("{weighting:?}"));
    }
    // The three really differ here.
    let [u, a, g] = sums.map(DVec3::normalize);
    assert!(
        (u - a).length() > 0.02 && (u - g).length() > 0.02 && (a - g).length() > 0.02,
        "{u} {a} {g}"
    );
}

/// A crease angle below 90° splits every cube corner into its three face
/// normals; at 90° and above the faces all take part (the bend is inclusive).
#[test]
fn crease_angle_splits_cube_corners() {
    let mesh = builtin_model("cube", Some(1)).unwrap();
    let faces = shadelab_core::face_normals(&mesh);
    for weighting in ALL {
        for crease in [1.0, 30.0, 89.0] {
            let normals = vertex_normals(&mesh, weighting, Some(crease));
            for (f, face) in faces.iter().enumerate() {
                let face = face.unwrap();
                // The face normals of a cube are the axes.
                assert_eq!(face.abs().max_element(), 1.0);
                for c in mesh.corner_range(f) {
                    let n = corner_normal(&normals, c);
                    assert!(
                        (n - d(face)).length() < 1e-6,
                        "crease {crease}: corner {c}: {n} vs face {face}"
                    );
                }
            }
            // 8 corners × 3 faces, shared by the corners that agree.
            assert_eq!(normals.normals.len(), 24, "crease {crease}");
        }
        for crease in [90.0, 100.0, 179.0] {
            let normals = vertex_normals(&mesh, weighting, Some(crease));
            for (v, &p) in mesh.positions().iter().enumerate() {
                assert_vertex_normal(&mesh, &normals, v as u32, d(p), &format!("crease {crease}"));
            }
        }
    }
    // A finer cube: vertices inside a face are not split, edges split in two.
    let mesh = builtin_model("cube", Some(2)).unwrap();
    let normals = vertex_normals(&mesh, NormalWeighting::Uniform, Some(45.0));
    let faces = shadelab_core::face_normals(&mesh);
    for (f, face) in faces.iter().enumerate() {
        for c in mesh.corner_range(f) {
            assert!((corner_normal(&normals, c) - d(face.unwrap())).length() < 1e-6);
        }
    }
    let centre = index_of(&mesh, Vec3::Z);
    assert_vertex_normal(&mesh, &normals, centre, DVec3::Z, "face centre");
}

/// The cylinder with a 60° crease: side corners get the radial direction
/// (two side quads bending 360°/n apart), cap corners the caps' axis.
#[test]
fn crease_angle_on_a_cylinder() {
    let slices = 16;
    let mesh = builtin_model("cylinder", Some(slices)).unwrap();
    let faces = shadelab_core::face_normals(&mesh);
    for weighting in ALL {
        let normals = vertex_normals(&mesh, weighting, Some(60.0));
        for (f, face) in faces.iter().enumerate() {
            let is_cap = mesh.polygon(f).len() == slices as usize;
            for c in mesh.corner_range(f) {
                let p = d(mesh.positions()[mesh.corners()[c] as usize]);
                let expected = if is_cap {
                    d(face.unwrap())
                } else {
                    DVec3::new(p.x, 0.0, p.z).normalize()
                };
                if is_cap {
                    assert_eq!(expected.abs().y, 1.0);
                }
                let n = corner_normal(&normals, c);
                assert!(
                    (n - expected).length() < 1e-5,
                    "{weighting:?}: corner {c} at {p}: {n} vs {expected}"
                );
            }
        }
    }
}

/// On the sphere models the vertex normal is close to the radius. (Area
/// weighting is worst, beside the UV sphere's poles where small triangles
/// meet larger quads: 3.7° at 24 slices, 0.94° at 96; uniform stays < 0.03°.)
#[test]
fn sphere_normals_are_nearly_radial() {
    for (model, detail, degrees) in [
        ("sphere", 24u32, 4.5f64),
        ("sphere", 96, 1.2),
        ("icosphere", 3, 1.0),
    ] {
        let mesh = builtin_model(model, Some(detail)).unwrap();
        for weighting in ALL {
            let normals = vertex_normals(&mesh, weighting, None);
            let mut worst = 0f64;
            for (c, &v) in mesh.corners().iter().enumerate() {
                let n = corner_normal(&normals, c);
                assert!((n.length() - 1.0).abs() < 1e-6);
                let radial = d(mesh.positions()[v as usize]).normalize();
                let angle = n.dot(radial).clamp(-1.0, 1.0).acos().to_degrees();
                assert!(
                    angle < degrees,
                    "{model}{detail} {weighting:?}: {angle}° off at {radial}"
                );
                worst = worst.max(angle);
            }
            println!("{model}{detail} {weighting:?}: at most {worst:.3}° from the radius");
        }
    }
}

/// A vertex only on a degenerate face falls back to +z; a degenerate face
/// does not disturb its neighbours.
#[test]
fn degenerate_faces_fall_back() {
    let positions = vec![
        Vec3::ZERO,
        Vec3::X,
        Vec3::Y,
        Vec3::new(5.0, 5.0, 5.0),
        Vec3::new(6.0, 6.0, 6.0),
    ];
    // Face 1 is a needle (collinear points) sharing vertex 0 with face 0.
    let mesh = Mesh::from_polygons(positions, [[0u32, 1, 2], [0, 3, 4]]).unwrap();
    assert_eq!(shadelab_core::face_normals(&mesh)[1], None);
    for weighting in ALL {
        for crease in [None, Some(30.0)] {
            let normals = vertex_normals(&mesh, weighting, crease);
            for v in [1, 2] {
                assert_vertex_normal(&mesh, &normals, v, DVec3::Z, "good face");
            }
            // Every corner is +z: the good face's corners and vertex 0 from
            // the good face alone, the needle's from the fallback.
            for c in 0..6 {
                assert_eq!(
                    corner_normal(&normals, c),
                    DVec3::Z,
                    "{weighting:?} {crease:?}: corner {c}"
                );
            }
        }
    }
}

/// Face normals at scales where the f32 cross product overflows or
/// underflows: still the plane's normal (a triangle with coordinates of 1e30
/// used to be dropped as degenerate).
#[test]
fn face_normal_at_extreme_scales() {
    for scale in [1e-30f32, 1e-20, 1e-3, 1.0, 1e3, 1e20, 1e30, 1e38] {
        let tri = [
            Vec3::new(-1.0, -1.0, 0.0) * scale,
            Vec3::new(1.0, -1.0, 0.0) * scale,
            Vec3::new(0.0, 1.0, 0.0) * scale,
        ];
        assert_eq!(
            face_normal(&tri),
            Some(Vec3::Z),
            "triangle at scale {scale}"
        );
        let quad = [
            Vec3::new(-1.0, 0.0, -1.0) * scale,
            Vec3::new(-1.0, 0.0, 1.0) * scale,
            Vec3::new(1.0, 0.0, 1.0) * scale,
            Vec3::new(1.0, 0.0, -1.0) * scale,
        ];
        assert_eq!(face_normal(&quad), Some(Vec3::Y), "quad at scale {scale}");
    }
    let tilted = [
        Vec3::new(-1e30, -1e30, -1e30),
        Vec3::new(1e30, -1e30, -5.0),
        Vec3::new(0.0, 1e30, -5.0),
    ];
    let expected = DVec3::new(-2.0, -1.0, 4.0).normalize();
    assert!((d(face_normal(&tilted).unwrap()) - expected).length() < 1e-6);
    // Degenerate stays degenerate.
    assert_eq!(
        face_normal(&[Vec3::ONE * 1e30, Vec3::ONE * 1e30, Vec3::ZERO]),
        None
    );
    assert_eq!(face_normal(&[Vec3::ZERO, Vec3::X, Vec3::X * 2.0]), None);
}
