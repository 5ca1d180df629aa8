//! Whole meshes through the renderer's geometry stage ([`coverage`]): shared
//! edges and vertices never leave holes nor cover a pixel twice.
//!
//! The expected silhouettes are computed independently: the convex hull of
//! the projected vertices for convex polyhedra, the analytic disc for the
//! sphere, and ray marching of the analytic torus.

mod common;

use common::*;
use glam::{DVec2, DVec3, Vec3};
use shadelab_core::{
    builtin_model, coverage, render, vertex_normals, Mesh, NormalWeighting, RenderOptions, Scene,
    Shading,
};

fn smooth_scene(mesh: Mesh, eye: DVec3) -> Scene {
    let normals = vertex_normals(&mesh, NormalWeighting::Uniform, None);
    scene(mesh, normals, camera(eye, DVec3::ZERO, 40.0, 0.5, 20.0))
}

/// The window outline of a convex polyhedron: the hull of its projected vertices.
fn hull_outline(view: &View, mesh: &Mesh) -> Vec<(i64, i64)> {
    let points: Vec<(i64, i64)> = mesh
        .positions()
        .iter()
        .map(|&p| view.snapped(d(p)))
        .collect();
    convex_hull(&points)
}

/// For a closed convex mesh seen from outside, with culling on, every pixel
/// centre inside the outline is covered once and every one outside never;
/// with culling off, inside twice (front and back).
fn check_convex(name: &str, mesh: Mesh, eye: DVec3, width: u32, height: u32) -> usize {
    let scene = smooth_scene(mesh, eye);
    let view = View::new(&scene.camera, width, height);
    let outline = hull_outline(&view, &scene.mesh);
    let mut checked = 0;
    for cull in [true, false] {
        let per_face = if cull { 1 } else { 2 };
        let options = RenderOptions {
            cull_backfaces: cull,
            ..options(width, height, Shading::Flat)
        };
        let counts = coverage(&scene, &options).unwrap();
        checked += ok(compare_counts(
            &format!("{name}-cull-{cull}"),
            &counts,
            width,
            height,
            |i, j| {
                let inside = inside_distance(&outline, f64::from(i) + 0.5, f64::from(j) + 0.5);
                Some(if inside > 0.05 {
                    per_face..=per_face
                } else if inside < -0.05 {
                    0..=0
                } else {
                    0..=per_face
                })
            },
        ));
    }
    checked
}

fn eyes() -> [DVec3; 4] {
    [
        DVec3::new(0.7, 1.3, 3.5),
        DVec3::new(-3.2, -0.8, 1.5),
        DVec3::new(2.5, -2.5, 1.0),
        DVec3::new(0.2, 0.3, -4.0),
    ]
}

#[test]
fn convex_builtin_meshes_cover_their_outline_once() {
    let models = [
        ("sphere", 3),
        ("sphere", 12),
        ("sphere", 48),
        ("sphere", 160),
        ("icosphere", 0),
        ("icosphere", 2),
        ("icosphere", 4),
        ("cube", 1),
        ("cube", 8),
        ("cylinder", 5),
        ("cylinder", 40),
        ("cone", 7),
        ("cone", 64),
    ];
    for (model, detail) in models {
        for (k, eye) in eyes().into_iter().enumerate() {
            let mesh = builtin_model(model, Some(detail)).unwrap();
            check_convex(&format!("{model}{detail}-view{k}"), mesh, eye, 96, 80);
        }
    }
}

/// The sphere against its analytic disc: the mesh is inscribed, so nothing
/// outside the true disc is covered, and everything inside it, away from a
/// one-pixel rim (wider than the gap between mesh and sphere), is covered once.
#[test]
fn sphere_covers_the_analytic_disc() {
    let (w, h) = (160u32, 120u32);
    for detail in [24, 64, 256] {
        for (k, eye) in eyes().into_iter().enumerate() {
            let mesh = builtin_model("sphere", Some(detail)).unwrap();
            let scene = smooth_scene(mesh, eye);
            let view = View::new(&scene.camera, w, h);
            let counts = coverage(&scene, &options(w, h, Shading::Flat)).unwrap();
            let radius = (1.0 / eye.length()).asin();
            // The mesh's largest gap to the sphere: the middle of a face, at
            // most 1 − cos(π / stacks) in from the surface, seen as an angle.
            let stacks = f64::from(detail / 2);
            let gap = (1.0 - (std::f64::consts::PI / stacks).cos()) / eye.length();
            let rim = view.pixel_angle() + gap;
            let n = ok(compare_counts(
                &format!("sphere{detail}-disc-view{k}"),
                &counts,
                w,
                h,
                |i, j| {
                    let angle = view.angle_to(f64::from(i) + 0.5, f64::from(j) + 0.5, DVec3::ZERO);
                    if angle < radius - rim {
                        Some(1..=1)
                    } else if angle > radius + 0.05 * view.pixel_angle() {
                        Some(0..=0)
                    } else {
                        Some(0..=1)
                    }
                },
            ));
            assert_eq!(n, (w * h) as usize);
            let covered = counts.iter().filter(|&&c| c == 1).count();
            assert!(
                covered > 3000,
                "sphere{detail}-view{k}: only {covered} pixels"
            );
        }
    }
}

/// A finely tessellated plane seen head-on: the +z face of a cube of 32 × 32
/// quads covers its square exactly once.
#[test]
fn fine_cube_face_head_on() {
    let (w, h) = (128u32, 128u32);
    let mesh = builtin_model("cube", Some(32)).unwrap();
    let scene = smooth_scene(mesh, DVec3::new(0.0, 0.0, 6.0));
    let view = View::new(&scene.camera, w, h);
    let square: Vec<(i64, i64)> = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .iter()
        .map(|&(x, y)| view.snapped(DVec3::new(x, y, 1.0)))
        .collect();
    let counts = coverage(&scene, &options(w, h, Shading::Flat)).unwrap();
    ok(compare_counts("cube32-head-on", &counts, w, h, |i, j| {
        let inside = inside_distance(&square, f64::from(i) + 0.5, f64::from(j) + 0.5);
        Some(if inside > 0.01 {
            1..=1
        } else if inside < -0.01 {
            0..=0
        } else {
            0..=1
        })
    }));
    let covered = counts.iter().filter(|&&c| c == 1).count();
    assert!(covered > 60 * 60, "{covered}");
}

/// A small deterministic generator (64-bit LCG), for reproducible jitter.
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A plane of jittered triangles and quads, built by hand, seen obliquely:
/// inside its (convex) outline every pixel is covered exactly once.
#[test]
fn jittered_grid_is_watertight() {
    let n = 40usize;
    let mut rng = Lcg(0x5eed);
    let mut positions = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let mut p = DVec2::new(i as f64, j as f64);
            if i > 0 && i < n && j > 0 && j < n {
                p += DVec2::new(rng.next() - 0.5, rng.next() - 0.5) * 0.4;
            }
            let p = p / n as f64 * 3.0 - 1.5;
            // A tilted plane through the origin.
            positions.push(Vec3::new(p.x as f32, (0.3 * p.x) as f32, -p.y as f32));
        }
    }
    let at = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    let mut polygons: Vec<Vec<u32>> = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, dd) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            match (i + 2 * j) % 3 {
                0 => polygons.push(vec![a, b, c, dd]),
                1 => {
                    polygons.push(vec![a, b, c]);
                    polygons.push(vec![a, c, dd]);
                }
                _ => {
                    polygons.push(vec![a, b, dd]);
                    polygons.push(vec![b, c, dd]);
                }
            }
        }
    }
    let mesh = Mesh::from_polygons(positions, polygons).unwrap();
    let corners = [at(0, 0), at(n, 0), at(n, n), at(0, n)].map(|v| d(mesh.positions()[v as usize]));
    let (w, h) = (160u32, 120u32);
    for (k, eye) in [
        DVec3::new(0.8, 3.0, 2.5),
        DVec3::new(-2.0, 1.5, 3.0),
        DVec3::new(0.1, 4.0, 0.4),
    ]
    .into_iter()
    .enumerate()
    {
        let scene = smooth_scene(mesh.clone(), eye);
        let view = View::new(&scene.camera, w, h);
        let outline = ccw_outline(corners.iter().map(|&p| view.snapped(p)).collect());
        let counts = coverage(&scene, &options(w, h, Shading::Flat)).unwrap();
        ok(compare_counts(
            &format!("grid-view{k}"),
            &counts,
            w,
            h,
            |i, j| {
                let inside = inside_distance(&outline, f64::from(i) + 0.5, f64::from(j) + 0.5);
                Some(if inside > 0.05 {
                    1..=1
                } else if inside < -0.05 {
                    0..=0
                } else {
                    0..=1
                })
            },
        ));
        // And the image has no background pixel inside.
        let (image, _) = render(&scene, &options(w, h, Shading::Phong)).unwrap();
        let mut expected = Expected::new(w, h);
        for j in 0..h {
            for i in 0..w {
                if inside_distance(&outline, f64::from(i) + 0.5, f64::from(j) + 0.5) < -0.05 {
                    expected.set_rgb8(i, j, BACKGROUND);
                }
            }
        }
        ok(compare_images(
            &format!("grid-view{k}"),
            &image,
            &expected,
            0.0,
        ));
        let drawn = image.pixels().iter().filter(|&&p| p != BACKGROUND).count();
        let covered = counts.iter().filter(|&&c| c > 0).count();
        assert_eq!(
            drawn, covered,
            "grid-view{k}: every covered pixel is shaded"
        );
    }
}

fn ccw_outline(mut poly: Vec<(i64, i64)>) -> Vec<(i64, i64)> {
    if area2_ccw(&poly) < 0 {
        poly.reverse();
    }
    poly
}

/// The torus, not convex: a pixel whose ray passes through the solid torus
/// (by ray marching its distance function, the tube shrunk by more than the
/// mesh's gap to it) is covered once or twice, one whose ray misses the tube
/// grown by that much is not covered. No ray enters a torus more than twice.
#[test]
fn torus_has_no_holes() {
    let (w, h) = (128u32, 96u32);
    let detail = 48u32;
    let (ring, tube) = (1.0f64, 0.4f64);
    let sides = f64::from(detail / 2);
    // The mesh lies within this distance of the analytic torus.
    let gap = (ring + tube) * (1.0 - (std::f64::consts::PI / f64::from(detail)).cos())
        + tube * (1.0 - (std::f64::consts::PI / sides).cos())
        + 1e-4;
    for (k, eye) in [
        DVec3::new(0.3, 2.2, 3.0),
        DVec3::new(3.5, 0.4, 0.5),
        DVec3::new(-0.5, 3.5, 0.8),
    ]
    .into_iter()
    .enumerate()
    {
        let mesh = builtin_model("torus", Some(detail)).unwrap();
        let scene = smooth_scene(mesh, eye);
        let view = View::new(&scene.camera, w, h);
        let counts = coverage(&scene, &options(w, h, Shading::Flat)).unwrap();
        let hits = |x: f64, y: f64, tube: f64| {
            let dir = view.ray(x, y).normalize();
            let sdf =
                |p: DVec3| DVec2::new(DVec2::new(p.x, p.z).length() - ring, p.y).length() - tube;
            let mut t = 0.0;
            for _ in 0..2000 {
                let dist = sdf(view.eye + dir * t);
                if dist < 1e-7 {
                    return true;
                }
                t += dist;
                if t > 20.0 {
                    break;
                }
            }
            false
        };
        let n = ok(compare_counts(
            &format!("torus-view{k}"),
            &counts,
            w,
            h,
            |i, j| {
                let (x, y) = (f64::from(i) + 0.5, f64::from(j) + 0.5);
                Some(if hits(x, y, tube - gap) {
                    1..=2
                } else if !hits(x, y, tube + gap) {
                    0..=0
                } else {
                    0..=2
                })
            },
        ));
        assert_eq!(n, (w * h) as usize);
    }
}

/// Every ray enters a closed surface as often as it leaves it, so with the
/// mesh wholly inside the view volume each pixel is covered by as many
/// back faces as front faces: coverage with culling off is exactly twice
/// coverage with culling on, convex or not (torus included), grazing views
/// included.
///
/// (Known exception, not covered here: at very fine tessellation a quad seen
/// almost edge-on on the silhouette can snap into a self-intersecting bow-tie,
/// which the rasterizer fans without regard to its winding; about one pixel
/// in 2400 grazing views of 200-slice spheres and cylinders.)
#[test]
fn closed_meshes_cover_as_often_front_as_back() {
    let (w, h) = (128u32, 96u32);
    for (model, detail) in [
        ("sphere", 16),
        ("sphere", 64),
        ("icosphere", 3),
        ("cube", 5),
        ("cylinder", 16),
        ("cylinder", 64),
        ("cone", 16),
        ("cone", 64),
        ("torus", 16),
        ("torus", 64),
    ] {
        let mesh = builtin_model(model, Some(detail)).unwrap().normalized();
        let normals = vertex_normals(&mesh, NormalWeighting::Uniform, None);
        for k in 0..24 {
            // Around the model, some views grazing its caps (y ≈ 1).
            let a = f64::from(k) * 0.731;
            let lift = 1.0 + 1e-4 * f64::from(k % 7) * if k % 2 == 0 { 1.0 } else { -1.0 };
            let eye =
                DVec3::new(3.5 * a.cos(), lift, 3.5 * a.sin()) * (1.0 + f64::from(k % 5) * 0.3);
            let scene = scene(
                mesh.clone(),
                normals.clone(),
                camera(eye, DVec3::ZERO, 40.0, 0.1, 50.0),
            );
            let on = coverage(&scene, &options(w, h, Shading::Flat)).unwrap();
            let off = coverage(
                &scene,
                &RenderOptions {
                    cull_backfaces: false,
                    ..options(w, h, Shading::Flat)
                },
            )
            .unwrap();
            ok(compare_counts(
                &format!("front-back-{model}{detail}-view{k}"),
                &off,
                w,
                h,
                |i, j| {
                    let n = 2 * on[(j * w + i) as usize];
                    Some(n..=n)
                },
            ));
            assert!(on.iter().any(|&c| c > 0));
        }
    }
}
