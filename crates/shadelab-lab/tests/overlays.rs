//! Overlays land on the pixels the projection predicts, and hidden ones do not.

mod common;

use common::*;
use glam::Vec3;
use shadelab_core::{
    render, vertex_normals, Light, LightKind, Mesh, NormalWeighting, Rgb, Scene, Shading,
};
use shadelab_lab::{draw_overlays, Overlays, FACE_NORMAL, LIGHT, VERTEX_NORMAL, WIREFRAME};

const W: u32 = 201;
const H: u32 = 161;

/// The window position of a world point, derived from the camera's
/// parameters alone: eye on +z looking at the origin, fov 40°.
fn project(p: Vec3, eye_z: f32) -> (f32, f32) {
    let t = (20f32).to_radians().tan();
    let depth = eye_z - p.z;
    let aspect = W as f32 / H as f32;
    let ndc = (p.x / (depth * t * aspect), p.y / (depth * t));
    (
        (ndc.0 + 1.0) * 0.5 * W as f32,
        (1.0 - ndc.1) * 0.5 * H as f32,
    )
}

fn squares_scene(second: bool) -> Scene {
    // A front square, and (optionally) a bigger one behind it, wholly hidden in the middle.
    let mut positions = square_mesh().positions().to_vec();
    let mut polygons = vec![vec![0u32, 1, 2, 3]];
    if second {
        positions.extend([
            Vec3::new(-0.5, -0.5, -1.0),
            Vec3::new(0.5, -0.5, -1.0),
            Vec3::new(0.5, 0.5, -1.0),
            Vec3::new(-0.5, 0.5, -1.0),
        ]);
        polygons.push(vec![4, 5, 6, 7]);
    }
    let mesh = Mesh::from_polygons(positions, polygons).unwrap();
    let normals = vertex_normals(&mesh, NormalWeighting::Uniform, None);
    let mut s = scene("cube", 1, Vec3::new(0.0, 0.0, 5.0));
    s.mesh = mesh;
    s.normals = normals;
    s.lights = vec![Light {
        kind: LightKind::Point {
            position: Vec3::new(0.4, 0.3, 2.0),
        },
        color: Rgb::WHITE,
        intensity: 1.0,
        attenuation: shadelab_core::NO_ATTENUATION,
    }];
    s
}

fn is(image: &shadelab_core::Image, p: (f32, f32), c: shadelab_core::Rgb8) -> bool {
    // The stroke may fall on either pixel a half-pixel boundary touches.
    let (x, y) = (p.0.floor() as i64, p.1.floor() as i64);
    (-1..=1).any(|dy| {
        (-1..=1).any(|dx| {
            let (px, py) = (x + dx, y + dy);
            px >= 0
                && py >= 0
                && px < W as i64
                && py < H as i64
                && image.pixel(px as u32, py as u32) == c
        })
    })
}

#[test]
fn wireframe_runs_along_the_projected_edges_and_hides_behind_the_model() {
    let scene = squares_scene(true);
    let options = options(W, H, Shading::Gouraud);
    let (mut image, _) = render(&scene, &options).unwrap();
    let plain = image.clone();
    draw_overlays(
        &mut image,
        &scene,
        &options,
        Overlays::parse("wireframe").unwrap(),
    )
    .unwrap();
    for (a, b) in [
        ((-1.0, -1.0), (1.0, -1.0)),
        ((1.0, -1.0), (1.0, 1.0)),
        ((1.0, 1.0), (-1.0, 1.0)),
        ((-1.0, 1.0), (-1.0, -1.0)),
    ] {
        for f in [0.1f32, 0.37, 0.5, 0.81] {
            let p = Vec3::new(a.0 + (b.0 - a.0) * f, a.1 + (b.1 - a.1) * f, 0.0);
            assert!(is(&image, project(p, 5.0), WIREFRAME), "edge point {p}");
        }
    }
    // The hidden square's edges: inside the front square's image, untouched.
    for p in [Vec3::new(0.0, 0.5, -1.0), Vec3::new(0.5, 0.0, -1.0)] {
        let (x, y) = project(p, 5.0);
        for dy in -1..=1 {
            for dx in -1..=1 {
                let (px, py) = (
                    (x.floor() as i64 + dx) as u32,
                    (y.floor() as i64 + dy) as u32,
                );
                assert_eq!(
                    image.pixel(px, py),
                    plain.pixel(px, py),
                    "hidden edge drawn at ({px}, {py})"
                );
            }
        }
    }
    // The middle of the square is not touched.
    let (cx, cy) = project(Vec3::ZERO, 5.0);
    assert_eq!(
        image.pixel(cx as u32, cy as u32),
        plain.pixel(cx as u32, cy as u32)
    );
    // Only near the edges did anything change.
    let changed = image
        .pixels()
        .iter()
        .zip(plain.pixels())
        .filter(|(a, b)| a != b)
        .count();
    assert!(changed > 200 && changed < 1200, "{changed} pixels changed");
}

#[test]
fn normals_and_the_light_land_where_projected() {
    let mut scene = squares_scene(false);
    // Turn the square 40° about y so its normal shows as a segment.
    let turn = glam::Quat::from_rotation_y(40f32.to_radians());
    let positions: Vec<Vec3> = scene.mesh.positions().iter().map(|&p| turn * p).collect();
    scene.mesh = Mesh::from_polygons(positions, [[0u32, 1, 2, 3]]).unwrap();
    scene.normals = vertex_normals(&scene.mesh, NormalWeighting::Uniform, None);
    let options = options(W, H, Shading::Phong);
    let (mut image, _) = render(&scene, &options).unwrap();
    draw_overlays(
        &mut image,
        &scene,
        &options,
        Overlays::parse("face-normals,vertex-normals,light").unwrap(),
    )
    .unwrap();
    let n = turn * Vec3::Z;
    let (lo, hi) = scene.mesh.bounds();
    let length = (hi - lo).length() * shadelab_lab::NORMAL_LENGTH;
    // Face normal: from the centroid (the origin) along n.
    for f in [0.3f32, 0.6, 0.9] {
        assert!(
            is(&image, project(n * length * f, 5.0), FACE_NORMAL),
            "face normal at {f}"
        );
    }
    // Vertex normals: from each corner along n.
    for &corner in scene.mesh.positions() {
        assert!(
            is(
                &image,
                project(corner + n * length * 0.7, 5.0),
                VERTEX_NORMAL
            ),
            "vertex normal at {corner}"
        );
    }
    // The light, a filled sun at its projection.
    let (lx, ly) = project(Vec3::new(0.4, 0.3, 2.0), 5.0);
    assert_eq!(image.pixel(lx as u32, ly as u32), LIGHT);
}
