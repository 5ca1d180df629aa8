//! Clipping in the renderer: the camera inside a closed mesh, polygons that
//! cross the near and far planes, clipped polygons that cross themselves or
//! wind twice. (Coordinates far beyond the screen, NaN: `extremes.rs`.)

mod common;

use common::*;
use glam::{DVec3, Vec3};
use shadelab_core::{
    builtin_model, coverage, render, Camera, Interpolation, Mesh, Rasterizer, RenderOptions,
    Shading,
};

/// Inside a closed convex mesh with culling off, every ray leaves through
/// exactly one (back) face: every pixel is covered exactly once and every
/// pixel is shaded, in all three methods. With culling on nothing is drawn.
#[test]
fn camera_inside_cube() {
    let (w, h) = (80u32, 60u32);
    let views = [
        (DVec3::new(0.0, 0.0, 0.0), DVec3::new(0.0, 0.0, -1.0), 90.0),
        (DVec3::new(0.2, 0.1, 0.3), DVec3::new(1.0, 0.5, -0.3), 100.0),
        (
            DVec3::new(-0.6, 0.5, 0.55),
            DVec3::new(1.0, -1.0, -1.0),
            120.0,
        ),
        (
            DVec3::new(0.45, -0.4, -0.5),
            DVec3::new(-1.0, -1.0, 1.0),
            60.0,
        ),
    ];
    for detail in [1, 4] {
        for (k, &(eye, target, fov)) in views.iter().enumerate() {
            let mesh = builtin_model("cube", Some(detail)).unwrap();
            let scene = smooth(mesh, camera(eye, target, fov, 0.01, 100.0));
            let name = format!("inside-cube{detail}-view{k}");
            let off = RenderOptions {
                cull_backfaces: false,
                ..options(w, h, Shading::Flat)
            };
            let counts = coverage(&scene, &off).unwrap();
            ok(compare_counts(&name, &counts, w, h, |_, _| Some(1..=1)));
            for shading in Shading::ALL {
                for interpolation in [Interpolation::Perspective, Interpolation::Screen] {
                    let options = RenderOptions {
                        shading,
                        interpolation,
                        ..off
                    };
                    let (image, stats) = render(&scene, &options).unwrap();
                    let background = image.pixels().iter().filter(|&&p| p == BACKGROUND).count();
                    assert_eq!(
                        background, 0,
                        "{name} {shading:?} {interpolation:?}: background pixels"
                    );
                    assert_eq!(
                        stats.fragments_shaded,
                        u64::from(w * h),
                        "{name}: one fragment per pixel"
                    );
                }
            }
            let culled = coverage(&scene, &options(w, h, Shading::Flat)).unwrap();
            assert!(
                culled.iter().all(|&c| c == 0),
                "{name}: inside faces are back faces"
            );
        }
    }
}

/// A floor crossing the near plane (and, far away, the far plane) covers
/// exactly the pixels whose rays meet it between the two.
#[test]
fn floor_crossing_the_near_plane() {
    let (w, h) = (120u32, 90u32);
    // (near, far, camera target): the cut by the near plane is visible on
    // screen when near is large; the far plane cuts the floor when far is small.
    let setups = [
        (0.1, 1000.0, DVec3::new(0.0, 0.0, -1.0), 200.0, 50.0),
        (3.0, 1000.0, DVec3::new(0.0, 0.0, -1.0), 200.0, 50.0),
        (2.0, 20.0, DVec3::new(0.0, 0.0, -1.0), 200.0, 50.0),
        (1.5, 40.0, DVec3::new(0.4, -0.5, -1.0), 30.0, 50.0),
        (0.05, 100.0, DVec3::new(-0.3, -0.9, -0.2), 8.0, 6.0),
    ];
    for (k, &(near, far, target, half_width, depth)) in setups.iter().enumerate() {
        let cam = camera(DVec3::ZERO, target, 60.0, near as f32, far as f32);
        let view = View::new(&cam, w, h);
        for (m, mesh) in floor(half_width as f32, depth as f32)
            .into_iter()
            .enumerate()
        {
            let scene = smooth(mesh, cam);
            let name = format!("floor-setup{k}-mesh{m}");
            let counts = coverage(&scene, &options(w, h, Shading::Flat)).unwrap();
            let n = ok(compare_counts(
                &name,
                &counts,
                w,
                h,
                polygon_expectation(&view, floor_corners(half_width, depth), 0.05),
            ));
            assert!(
                n > (w * h) as usize * 9 / 10,
                "{name}: only {n} pixels checked"
            );
            let covered = counts.iter().filter(|&&c| c > 0).count();
            assert!(covered > 100, "{name}: only {covered} pixels covered");
            for shading in Shading::ALL {
                let (image, stats) = render(&scene, &options(w, h, shading)).unwrap();
                let drawn = image.pixels().iter().filter(|&&p| p != BACKGROUND).count();
                assert_eq!(drawn, covered, "{name} {shading:?}");
                assert_eq!(
                    stats.fragments_shaded as usize, covered,
                    "{name} {shading:?}"
                );
            }
        }
    }
}

/// Found by `extremes::never_panics` (`extremes.rs`): vertices near 1e31
/// snap so far from their true place that the clipped triangle crosses
/// itself; it must still cover no pixel twice.
#[test]
fn self_crossing_clipped_triangle_covers_each_pixel_once() {
    let corners = vec![
        Vec3::new(-2.91511e18, 1.0, 1.0),
        Vec3::new(1.0, 4.6490695e27, 1.0),
        Vec3::new(1.0, -4.190012e31, 1.0),
    ];
    let near = 1.0f32;
    let cam = Camera {
        eye: Vec3::new(2.667776, -1.6294, 4.0965047),
        target: Vec3::new(2.4332476, 1.6754103, 4.7603703),
        up: Vec3::Y,
        fov_y_degrees: 70.0,
        near,
        far: near * 18.061548 * 10.0,
    };
    let scene = smooth(Mesh::from_polygons(corners, [[0u32, 1, 2]]).unwrap(), cam);
    for shading in Shading::ALL {
        render(
            &scene,
            &RenderOptions {
                cull_backfaces: false,
                ..options(40, 30, shading)
            },
        )
        .unwrap();
    }
    let counts = coverage(
        &scene,
        &RenderOptions {
            cull_backfaces: false,
            ..options(40, 30, Shading::Flat)
        },
    )
    .unwrap();
    assert!(counts.iter().all(|&c| c <= 1), "a pixel covered twice");
}

/// Clipping keeps exactly the part of a polygon in front of the near plane.
///
/// Each corner of a random clip-space triangle carries its barycentric
/// coordinates as attributes, so every vertex `clip_polygon` makes says where
/// on the triangle it lies. The kept region, measured in barycentric space,
/// must equal the triangle cut by the near plane `z + w ≥ 0`, whose area
/// fraction has a closed form in the plane distances at the corners.
mod near_plane {
    use glam::Vec4;
    use proptest::prelude::*;
    use shadelab_core::{clip_polygon, ClipVertex};

    /// Twice the signed area of a polygon in the (b1, b2) barycentric plane.
    fn barycentric_area(polygon: &[ClipVertex<3>]) -> f64 {
        let n = polygon.len();
        (0..n)
            .map(|i| {
                let (a, b) = (&polygon[i].attrs, &polygon[(i + 1) % n].attrs);
                f64::from(a[1]) * f64::from(b[2]) - f64::from(b[1]) * f64::from(a[2])
            })
            .sum()
    }

    /// The fraction of a triangle where a linear function with corner values
    /// `d` is ≥ 0.
    fn kept_fraction(d: [f64; 3]) -> f64 {
        let inside: Vec<usize> = (0..3).filter(|&k| d[k] >= 0.0).collect();
        match inside.len() {
            3 => 1.0,
            0 => 0.0,
            1 => {
                let i = inside[0];
                let (j, k) = ((i + 1) % 3, (i + 2) % 3);
                d[i] * d[i] / ((d[i] - d[j]) * (d[i] - d[k]))
            }
            _ => {
                let o = (0..3).find(|&k| d[k] < 0.0).unwrap();
                let (j, k) = ((o + 1) % 3, (o + 2) % 3);
                1.0 - d[o] * d[o] / ((d[o] - d[j]) * (d[o] - d[k]))
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 3000, failure_persistence: None, ..ProptestConfig::default() })]

        #[test]
        fn keeps_exactly_the_part_in_front(
            corners in prop::array::uniform3((-1.0f32..1.0, -1.0f32..1.0, -3.0f32..1.0, 0.2f32..3.0)),
        ) {
            // x, y within the guard band and z ≤ w: only the near plane cuts.
            let polygon: Vec<ClipVertex<3>> = corners
                .iter()
                .enumerate()
                .map(|(k, &(x, y, z, w))| {
                    let mut attrs = [0.0; 3];
                    attrs[k] = 1.0;
                    ClipVertex { clip: Vec4::new(x * w, y * w, z * w, w), attrs }
                })
                .collect();
            let d = polygon.iter().map(|v| f64::from(v.clip.z + v.clip.w)).collect::<Vec<_>>();
            let d = [d[0], d[1], d[2]];
            // Skip near-degenerate cases where rounding decides the answer.
            prop_assume!(d.iter().all(|v| v.abs() > 1e-3));
            let (mut out, mut scratch) = (Vec::new(), Vec::new());
            clip_polygon(&polygon, 1000.0, &mut out, &mut scratch);

            for v in &out {
                // Every vertex in front of (or on) the near plane…
                prop_assert!(v.clip.z + v.clip.w >= -1e-5 * v.clip.w.abs().max(1.0), "{v:?} behind the near plane");
                // …and on the original triangle.
                let sum: f32 = v.attrs.iter().sum();
                prop_assert!((sum - 1.0).abs() < 1e-5 && v.attrs.iter().all(|&b| b >= -1e-5), "{v:?} off the triangle");
            }
            let whole = barycentric_area(&polygon);
            let kept = if out.is_empty() { 0.0 } else { barycentric_area(&out) / whole };
            let expected = kept_fraction(d);
            prop_assert!((kept - expected).abs() < 1e-4, "kept {kept}, expected {expected}, distances {d:?}");
        }
    }
}

/// A triangle with coordinates up to 5e33 that clipping turns into a
/// polygon winding twice round the apex the fan would have started from
/// (found by `extremes::never_panics`, `extremes.rs`): each pixel is drawn
/// at most once, by both rasterizers, and both cover the same 82 pixels.
#[test]
fn a_polygon_clipping_makes_wind_twice_is_drawn_once_per_pixel() {
    let corners = vec![
        Vec3::new(-2.949_222_2e21, 1.0, 7.678_203_7e27),
        Vec3::new(1.0, 1.0, -5.381_456e33),
        Vec3::new(1.0, 1.0, 2.685_232e30),
    ];
    let cam = Camera {
        eye: Vec3::new(-2.849_584, -0.984_042_3, -3.133_278_1),
        target: Vec3::new(2.553_940_3, 2.973_986, 4.374_611),
        up: Vec3::Y,
        fov_y_degrees: 70.0,
        near: 1.0,
        far: 259.497_4,
    };
    let mesh = Mesh::from_polygons(corners, [[0u32, 1, 2]]).unwrap();
    let scene = smooth(mesh, cam);
    let mut covered = Vec::new();
    for rasterizer in [Rasterizer::Scanline, Rasterizer::Tiled] {
        let options = RenderOptions {
            cull_backfaces: false,
            rasterizer,
            ..options(40, 30, Shading::Flat)
        };
        let counts = coverage(&scene, &options).unwrap();
        assert!(counts.iter().all(|&c| c <= 1), "{rasterizer:?}");
        covered.push(counts);
    }
    assert_eq!(covered[0], covered[1]);
    assert_eq!(covered[0].iter().filter(|&&c| c == 1).count(), 82);
}
