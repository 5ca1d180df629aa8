//! Rendered images against images computed independently in the test: one
//! triangle in every shading method and both interpolation modes, the flat
//! shading of a cube face worked out by hand, and the depth test.

mod common;

use common::*;
use glam::{DVec3, Vec3};
use shadelab_core::{
    builtin_model, coverage, render, vertex_normals, Camera, Interpolation, Light, LightKind,
    Material, Mesh, NormalWeighting, RenderOptions, Rgb, Rgb8, Shading, Specular,
};

/// One triangle to draw, with its vertex normals, seen by a camera.
struct TriangleCase {
    name: &'static str,
    camera: Camera,
    width: u32,
    height: u32,
    /// Counter-clockwise as the camera sees it.
    vertices: [DVec3; 3],
    normals: [DVec3; 3],
    /// Whether the triangle crosses the near plane (then only perspective
    /// interpolation has a simple exact answer).
    crosses_near: bool,
}

fn tilted_normals(vertices: &[DVec3; 3], tilts: [DVec3; 3]) -> [DVec3; 3] {
    let face = (vertices[1] - vertices[0])
        .cross(vertices[2] - vertices[0])
        .normalize();
    tilts.map(|t| (face + t).normalize())
}

fn cases() -> Vec<TriangleCase> {
    let tilts = [
        DVec3::new(-0.55, -0.35, 0.1),
        DVec3::new(0.6, -0.2, 0.0),
        DVec3::new(-0.1, 0.7, 0.2),
    ];
    let inside = [
        DVec3::new(-2.0, -1.5, -0.8),
        DVec3::new(2.1, -1.1, 1.0),
        DVec3::new(-0.3, 1.7, -1.2),
    ];
    let large = [
        DVec3::new(-4.5, -3.2, -2.0),
        DVec3::new(3.8, -2.6, 1.6),
        DVec3::new(-0.8, 3.9, -1.4),
    ];
    // Crosses the near plane: the third vertex is behind the eye.
    let crossing = [
        DVec3::new(-2.5, -1.2, -5.0),
        DVec3::new(0.2, -0.4, 1.5),
        DVec3::new(2.8, -0.9, -4.0),
    ];
    vec![
        TriangleCase {
            name: "inside",
            camera: camera(DVec3::new(0.4, 0.6, 5.0), DVec3::ZERO, 45.0, 0.5, 20.0),
            width: 120,
            height: 90,
            vertices: inside,
            normals: tilted_normals(&inside, tilts),
            crosses_near: false,
        },
        TriangleCase {
            name: "beyond-borders",
            camera: camera(
                DVec3::new(-0.3, 0.4, 5.0),
                DVec3::new(0.1, 0.0, 0.0),
                50.0,
                0.5,
                20.0,
            ),
            width: 96,
            height: 112,
            vertices: large,
            normals: tilted_normals(&large, tilts),
            crosses_near: false,
        },
        TriangleCase {
            name: "crossing-near",
            camera: camera(
                DVec3::new(0.0, 0.5, 0.0),
                DVec3::new(0.0, -0.2, -5.0),
                60.0,
                1.0,
                30.0,
            ),
            width: 110,
            height: 80,
            vertices: crossing,
            normals: tilted_normals(&crossing, tilts),
            crosses_near: true,
        },
    ]
}

/// The triangle clipped to the near plane in world space (Sutherland–Hodgman
/// on view depth), so its window outline can be computed.
fn clip_near(view: &View, poly: &[DVec3]) -> Vec<DVec3> {
    let mut out = Vec::new();
    for i in 0..poly.len() {
        let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
        let (da, db) = (view.depth(a) - view.near, view.depth(b) - view.near);
        if da >= 0.0 {
            out.push(a);
        }
        if (da >= 0.0) != (db >= 0.0) {
            out.push(a + (b - a) * (da / (da - db)));
        }
    }
    out
}

/// Barycentric coordinates of `p` in the triangle `v`, measured along `normal`.
fn barycentric_3d(v: &[DVec3; 3], p: DVec3) -> [f64; 3] {
    let n = (v[1] - v[0]).cross(v[2] - v[0]);
    let total = n.dot(n);
    let la = (v[1] - p).cross(v[2] - p).dot(n) / total;
    let lb = (v[2] - p).cross(v[0] - p).dot(n) / total;
    [la, lb, 1.0 - la - lb]
}

/// Barycentric coordinates of a window point in a window triangle (pixels).
fn barycentric_2d(v: &[(f64, f64); 3], p: (f64, f64)) -> [f64; 3] {
    let cross = |a: (f64, f64), b: (f64, f64), c: (f64, f64)| {
        (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0)
    };
    let total = cross(v[0], v[1], v[2]);
    let la = cross(p, v[1], v[2]) / total;
    let lb = cross(v[0], p, v[2]) / total;
    [la, lb, 1.0 - la - lb]
}

fn blend<T: std::ops::Mul<f64, Output = T> + std::ops::Add<Output = T> + Copy>(
    w: [f64; 3],
    v: [T; 3],
) -> T {
    v[0] * w[0] + v[1] * w[1] + v[2] * w[2]
}

/// The expected colour (unclamped, 0–1) of a pixel whose interpolation
/// weights for the triangle's vertices are `w`.
fn shade(
    model: &PhongModel,
    case: &TriangleCase,
    shading: Shading,
    gouraud_specular: bool,
    w: [f64; 3],
) -> DVec3 {
    let v = &case.vertices;
    match shading {
        Shading::Flat => {
            let centroid = (v[0] + v[1] + v[2]) / 3.0;
            let normal = (v[1] - v[0]).cross(v[2] - v[0]).normalize();
            model.eval(centroid, normal, true)
        }
        Shading::Gouraud => {
            let colors =
                [0, 1, 2].map(|k| clamp01(model.eval(v[k], case.normals[k], gouraud_specular)));
            blend(w, colors)
        }
        Shading::Phong => {
            let n = blend(w, case.normals).normalize();
            model.eval(blend(w, *v), n, true)
        }
    }
}

#[test]
fn single_triangle_every_method_and_interpolation() {
    let methods = [
        (Shading::Flat, false, Specular::Phong),
        (Shading::Gouraud, false, Specular::Phong),
        (Shading::Gouraud, true, Specular::Phong),
        (Shading::Phong, false, Specular::Phong),
        (Shading::Flat, false, Specular::BlinnPhong),
        (Shading::Gouraud, true, Specular::BlinnPhong),
        (Shading::Phong, false, Specular::BlinnPhong),
    ];
    let mut report = Vec::new();
    for case in cases() {
        let view = View::new(&case.camera, case.width, case.height);
        let v = case.vertices;
        // The window outline of what is drawn, snapped like the renderer snaps.
        let outline: Vec<(i64, i64)> = clip_near(&view, &v)
            .iter()
            .map(|&p| view.snapped(p))
            .collect();
        assert!(
            area2_ccw(&outline) > 0,
            "{}: the test triangle must face the camera",
            case.name
        );
        let window: [(f64, f64); 3] = v.map(|p| {
            let (x, y) = view.snapped(p);
            (x as f64 / SUB as f64, y as f64 / SUB as f64)
        });
        let face = (v[1] - v[0]).cross(v[2] - v[0]).normalize();

        for back in [false, true] {
            // The back-facing variant: reversed winding, reversed normals.
            // Drawn with culling off it must look exactly like the front face.
            let (order, sign) = if back {
                ([0usize, 2, 1], -1.0)
            } else {
                ([0, 1, 2], 1.0)
            };
            let mesh =
                Mesh::from_polygons(order.map(|k| f(v[k])).to_vec(), [[0u32, 1, 2]]).unwrap();
            let normals = explicit_normals(&order.map(|k| f(case.normals[k] * sign)));
            let scene = scene(mesh, normals, case.camera);
            for interpolation in [Interpolation::Perspective, Interpolation::Screen] {
                if case.crosses_near && interpolation == Interpolation::Screen {
                    continue;
                }
                for (shading, gouraud_specular, specular) in methods {
                    let model = PhongModel {
                        blinn: specular == Specular::BlinnPhong,
                        ..PhongModel::of_scene(&scene)
                    };
                    let options = RenderOptions {
                        gouraud_specular,
                        specular,
                        interpolation,
                        cull_backfaces: !back,
                        ..options(case.width, case.height, shading)
                    };
                    let (image, _) = render(&scene, &options).unwrap();
                    let counts = coverage(&scene, &options).unwrap();
                    let mut expected = Expected::new(case.width, case.height);
                    let mut must_cover = vec![None; (case.width * case.height) as usize];
                    let mut shaded = 0usize;
                    for j in 0..case.height {
                        for i in 0..case.width {
                            let (x, y) = (f64::from(i) + 0.5, f64::from(j) + 0.5);
                            let inside = inside_distance(&outline, x, y);
                            let at = (j * case.width + i) as usize;
                            // Coverage, away from ties the snapping of an
                            // f32 pipeline might tip either way.
                            if inside > 2.0 / SUB as f64 {
                                must_cover[at] = Some(1..=1);
                            } else if inside < -2.0 / SUB as f64 {
                                must_cover[at] = Some(0..=0);
                                expected.set_rgb8(i, j, BACKGROUND);
                            }
                            if inside <= 1.0 {
                                continue;
                            }
                            shaded += 1;
                            let weights = match interpolation {
                                Interpolation::Perspective => {
                                    let (_, p) = view.hit_plane(x, y, v[0], face).unwrap();
                                    barycentric_3d(&v, p)
                                }
                                Interpolation::Screen => barycentric_2d(&window, (x, y)),
                            };
                            expected.set(
                                i,
                                j,
                                to_255(shade(&model, &case, shading, gouraud_specular, weights)),
                            );
                        }
                    }
                    let name = format!(
                        "triangle-{}-{}-{}{}-{}-{:?}",
                        case.name,
                        if back { "back" } else { "front" },
                        shading.name(),
                        if gouraud_specular { "-spec" } else { "" },
                        specular.name(),
                        interpolation
                    );
                    let checked = ok(compare_images(&name, &image, &expected, 1.0));
                    ok(compare_counts(
                        &name,
                        &counts,
                        case.width,
                        case.height,
                        |x, y| must_cover[(y * case.width + x) as usize].clone(),
                    ));
                    assert!(shaded > 1000, "{name}: only {shaded} shaded pixels checked");
                    report.push(format!(
                        "{name}: {shaded} shaded pixels, {} in all",
                        checked
                    ));
                }
            }

            if back {
                // With culling on, the back-facing triangle draws nothing.
                let (image, stats) =
                    render(&scene, &options(case.width, case.height, Shading::Phong)).unwrap();
                assert!(
                    image.pixels().iter().all(|&p| p == BACKGROUND),
                    "{}: culled face drawn",
                    case.name
                );
                assert_eq!(stats.culled, 1);
            }
        }
    }
    println!("{}", report.join("\n"));
}

/// Flat shading of the cube's +z face seen head-on, computed by hand.
///
/// Ambient Ia = 0.2 (grey), one white point light of intensity 1 at (2, 3, 5),
/// the eye at (0, 0, 5). The face's normal is n = (0, 0, 1) and its centroid
/// (the average of (±1, ±1, 1)) is c = (0, 0, 1), so
///   l = (2, 3, 4)/√29, n·l = 4/√29 = 0.742781,
///   v = (0, 0, 1),
///   r = 2(n·l)n − l = (−2, −3, 4)/√29, r·v = 4/√29, (r·v)^4 = 256/841 = 0.304400.
/// With Ka = (1, 0.2, 0.4), Kd = (0.6, 0.3, 0.1), Ks = (0.25, 0.25, 0.25):
///   R = 0.2·1.0 + 0.6·0.742781 + 0.25·0.304400 = 0.721769 → 184.05 → 184
///   G = 0.2·0.2 + 0.3·0.742781 + 0.25·0.304400 = 0.338934 →  86.43 →  86
///   B = 0.2·0.4 + 0.1·0.742781 + 0.25·0.304400 = 0.230378 →  58.75 →  59
#[test]
fn flat_cube_face_matches_hand_computation() {
    let mesh = builtin_model("cube", Some(1)).unwrap();
    let normals = vertex_normals(&mesh, NormalWeighting::Uniform, None);
    let camera = Camera {
        eye: Vec3::new(0.0, 0.0, 5.0),
        target: Vec3::ZERO,
        up: Vec3::Y,
        fov_y_degrees: 30.0,
        near: 1.0,
        far: 10.0,
    };
    let scene = shadelab_core::Scene {
        mesh,
        normals,
        camera,
        ambient: Rgb::splat(0.2),
        lights: vec![Light {
            kind: LightKind::Point {
                position: Vec3::new(2.0, 3.0, 5.0),
            },
            color: Rgb::WHITE,
            intensity: 1.0,
            attenuation: shadelab_core::NO_ATTENUATION,
        }],
        material: Material {
            ka: Rgb::new(1.0, 0.2, 0.4),
            kd: Rgb::new(0.6, 0.3, 0.1),
            ks: Rgb::splat(0.25),
            shininess: 4.0,
        },
    };
    // The numbers above, evaluated.
    let nl = 4.0 / 29f64.sqrt();
    let spec = 256.0 / 841.0;
    let by_formula = [
        0.2 * 1.0 + 0.6 * nl + 0.25 * spec,
        0.2 * 0.2 + 0.3 * nl + 0.25 * spec,
        0.2 * 0.4 + 0.1 * nl + 0.25 * spec,
    ]
    .map(|v| (v * 255.0_f64).round() as u8);
    assert_eq!(by_formula, [184, 86, 59]);
    let face_color = Rgb8::new(184, 86, 59);

    let (w, h) = (64u32, 64u32);
    let (image, stats) = render(&scene, &options(w, h, Shading::Flat)).unwrap();
    // The face spans ndc ±1/(4·tan 15°) = ±0.933013, window 2.1436..61.8564.
    let half = 1.0 / (4.0 * 15f64.to_radians().tan());
    let (lo, hi) = ((1.0 - half) * 32.0, (1.0 + half) * 32.0);
    let mut expected = Expected::new(w, h);
    for j in 0..h {
        for i in 0..w {
            let (x, y) = (f64::from(i) + 0.5, f64::from(j) + 0.5);
            let inside = x > lo && x < hi && y > lo && y < hi;
            expected.set_rgb8(i, j, if inside { face_color } else { BACKGROUND });
        }
    }
    let checked = ok(compare_images("cube-face-flat", &image, &expected, 0.0));
    assert_eq!(checked, (w * h) as usize);
    assert_eq!(
        image.pixels().iter().filter(|&&p| p == face_color).count(),
        60 * 60,
        "pixels 2..=61 in both directions"
    );
    // Only the +z face faces the camera; the other five are culled.
    assert_eq!((stats.rasterized, stats.culled), (1, 5));
    assert_eq!(stats.lighting_evaluations, 1);
}

/// Depth test "less": the nearer of two overlapping quads wins whatever the
/// drawing order, and a later polygon at exactly the same depth loses.
#[test]
fn nearer_polygon_wins_in_any_order() {
    let (w, h) = (48u32, 40u32);
    let cam = camera(DVec3::new(0.0, 0.0, 4.0), DVec3::ZERO, 40.0, 0.5, 10.0);
    let view = View::new(&cam, w, h);
    // A small quad in front (z = 0.5) and a larger tilted quad behind.
    let near_quad = [
        DVec3::new(-0.5, -0.5, 0.5),
        DVec3::new(0.5, -0.5, 0.5),
        DVec3::new(0.5, 0.5, 0.5),
        DVec3::new(-0.5, 0.5, 0.5),
    ];
    let far_quad = [
        DVec3::new(-1.2, -1.0, -0.4),
        DVec3::new(1.2, -1.0, 0.2),
        DVec3::new(1.2, 1.0, 0.2),
        DVec3::new(-1.2, 1.0, -0.4),
    ];
    for near_first in [true, false] {
        let quads = if near_first {
            [near_quad, far_quad]
        } else {
            [far_quad, near_quad]
        };
        let positions: Vec<Vec3> = quads.iter().flatten().map(|&p| f(p)).collect();
        let mesh = Mesh::from_polygons(positions, [[0u32, 1, 2, 3], [4, 5, 6, 7]]).unwrap();
        let normals = face_corner_normals(&mesh);
        let scene = scene(mesh, normals, cam);
        let model = PhongModel::of_scene(&scene);
        let flat = |q: &[DVec3; 4]| {
            let n = (q[1] - q[0]).cross(q[2] - q[0]).normalize();
            to_255(model.eval((q[0] + q[1] + q[2] + q[3]) / 4.0, n, true))
        };
        let (image, _) = render(&scene, &options(w, h, Shading::Flat)).unwrap();
        let outline = |q: &[DVec3; 4]| q.map(|p| view.snapped(p)).to_vec();
        let (near_outline, far_outline) = (outline(&near_quad), outline(&far_quad));
        let mut expected = Expected::new(w, h);
        for j in 0..h {
            for i in 0..w {
                let (x, y) = (f64::from(i) + 0.5, f64::from(j) + 0.5);
                let (dn, df) = (
                    inside_distance(&near_outline, x, y),
                    inside_distance(&far_outline, x, y),
                );
                if dn > 0.01 {
                    expected.set(i, j, flat(&near_quad));
                } else if dn < -0.01 && df > 0.01 {
                    expected.set(i, j, flat(&far_quad));
                } else if dn < -0.01 && df < -0.01 {
                    expected.set_rgb8(i, j, BACKGROUND);
                }
            }
        }
        ok(compare_images(
            &format!("depth-near-first-{near_first}"),
            &image,
            &expected,
            0.6,
        ));
    }

    // The same quad twice with different normals: at equal depth the first drawn stays.
    let q: Vec<Vec3> = near_quad
        .iter()
        .chain(near_quad.iter())
        .map(|&p| f(p))
        .collect();
    let mesh = Mesh::from_polygons(q, [[0u32, 1, 2, 3], [4, 5, 6, 7]]).unwrap();
    let tilted = Vec3::new(0.6, 0.0, 0.8);
    let normals = explicit_normals(&[[Vec3::Z; 4], [tilted; 4]].concat());
    let scene = scene(mesh, normals, cam);
    let model = PhongModel::of_scene(&scene);
    let (image, _) = render(&scene, &options(w, h, Shading::Phong)).unwrap();
    let centre = image.pixel(w / 2, h / 2);
    let p = view
        .hit_plane(
            f64::from(w / 2) + 0.5,
            f64::from(h / 2) + 0.5,
            near_quad[0],
            DVec3::Z,
        )
        .unwrap()
        .1;
    let first = to_255(model.eval(p, DVec3::Z, true));
    for k in 0..3 {
        assert!(
            (f64::from(centre.0[k]) - first[k]).abs() <= 1.0,
            "{centre:?} vs {first:?}"
        );
    }
}
