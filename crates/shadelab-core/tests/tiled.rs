//! The tiled rasterizer against the scanline reference: identical coverage,
//! colours within 1/255, on every built-in model and on random triangles
//! (slivers, huge, sub-pixel, vertices on pixel centres and edges), in all
//! three shading methods and both interpolation modes; and its portable
//! SIMD fallback against its AVX2 path.
//!
//! The scanline rasterizer draws polygons as the same triangle fans here
//! (`Polygons::Fans`), the tiled one's only mode. A failure prints the first
//! differing pixel and writes a diff image (red: differs) to the test
//! output directory.

mod common;

use common::*;
use glam::{DVec3, Vec3};
use proptest::prelude::*;
use shadelab_core::{
    builtin_model, vertex_normals, CornerNormals, Image, Interpolation, Mesh, NormalWeighting,
    Polygons, Rasterizer, RenderOptions, Renderer, Rgb8, Scene, Shading, SimdLevel, Specular,
    BUILTIN_MODELS,
};

/// Renders with both rasterizers (and the tiled one with both SIMD levels)
/// and compares coverage, pixels and counts.
fn check_equivalent(name: &str, scene: &Scene, options: &RenderOptions) -> Result<(), String> {
    let scanline = RenderOptions {
        rasterizer: Rasterizer::Scanline,
        polygons: Polygons::Fans,
        ..*options
    };
    let tiled = RenderOptions {
        rasterizer: Rasterizer::Tiled,
        ..scanline
    };
    let mut reference = Renderer::new();
    let mut best = Renderer::new();
    let mut portable = Renderer::with_simd(SimdLevel::Portable);

    let want = reference
        .coverage(scene, &scanline)
        .map_err(|e| e.to_string())?;
    let got = best.coverage(scene, &tiled).map_err(|e| e.to_string())?;
    if let Some(i) = (0..want.len()).find(|&i| want[i] != got[i]) {
        let (w, h) = (options.width, options.height);
        let path = write_ppm(&format!("{name}-coverage-diff"), w, h, |x, y| {
            let k = (y * w + x) as usize;
            match (want[k], got[k]) {
                (a, b) if a != b => [255, 0, 0],
                (0, _) => [0, 0, 0],
                _ => [128, 128, 128],
            }
        });
        return Err(format!(
            "{name}: coverage differs first at ({}, {}): scanline {}, tiled {}; diff: {}",
            i as u32 % w,
            i as u32 / w,
            want[i],
            got[i],
            path.display()
        ));
    }

    let mut expected = Image::filled(1, 1, options.background);
    let mut actual = expected.clone();
    let mut fallback = expected.clone();
    let s1 = reference
        .render_into(scene, &scanline, &mut expected)
        .map_err(|e| e.to_string())?;
    let s2 = best
        .render_into(scene, &tiled, &mut actual)
        .map_err(|e| e.to_string())?;
    portable
        .render_into(scene, &tiled, &mut fallback)
        .map_err(|e| e.to_string())?;
    within_one(&format!("{name}-tiled"), &expected, &actual)?;
    within_one(&format!("{name}-portable"), &actual, &fallback)?;
    // The other x86 levels compile the same intrinsics: the same bytes.
    for level in SimdLevel::supported().filter(|&l| l != SimdLevel::Portable) {
        let mut other = expected.clone();
        Renderer::with_simd(level)
            .render_into(scene, &tiled, &mut other)
            .map_err(|e| e.to_string())?;
        if other != actual {
            return Err(format!(
                "{name}: {} and {} differ",
                level.name(),
                best.simd().name()
            ));
        }
    }
    let counts = |s: shadelab_core::RenderStats| {
        (
            s.polygons,
            s.degenerate,
            s.invisible,
            s.culled,
            s.rasterized,
            s.covered_pixels,
        )
    };
    if counts(s1) != counts(s2) {
        return Err(format!(
            "{name}: stats differ: scanline {s1:?}, tiled {s2:?}"
        ));
    }
    Ok(())
}

/// Every channel of every pixel within 1/255.
fn within_one(name: &str, expected: &Image, actual: &Image) -> Result<(), String> {
    let (w, h) = (expected.width(), expected.height());
    let far = |x: u32, y: u32| {
        let (a, b) = (expected.pixel(x, y).0, actual.pixel(x, y).0);
        (0..3).any(|c| a[c].abs_diff(b[c]) > 1)
    };
    let Some((x, y)) = (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .find(|&(x, y)| far(x, y))
    else {
        return Ok(());
    };
    let bad = (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .filter(|&(x, y)| far(x, y))
        .count();
    let path = write_ppm(&format!("{name}-diff"), w, h, |x, y| {
        if far(x, y) {
            [255, 0, 0]
        } else {
            actual.pixel(x, y).0.map(|c| c / 3)
        }
    });
    Err(format!(
        "{name}: {bad} pixels differ by more than 1/255; first at ({x}, {y}): expected {:?}, got {:?}; diff: {}",
        expected.pixel(x, y).0,
        actual.pixel(x, y).0,
        path.display()
    ))
}

fn all_modes() -> impl Iterator<Item = (Shading, Interpolation)> {
    Shading::ALL.into_iter().flat_map(|s| {
        [Interpolation::Perspective, Interpolation::Screen]
            .into_iter()
            .map(move |i| (s, i))
    })
}

#[test]
fn every_builtin_model_matches_the_scanline_rasterizer() {
    for info in BUILTIN_MODELS {
        let mesh = builtin_model(info.name, Some(info.default_detail))
            .unwrap()
            .normalized();
        let crease = info.default_crease_degrees;
        let normals = vertex_normals(&mesh, NormalWeighting::Angle, crease);
        let base = scene(
            mesh,
            normals,
            camera(DVec3::new(0.4, 0.6, 3.2), DVec3::ZERO, 40.0, 0.5, 20.0),
        );
        for (view, (yaw, pitch)) in [(0.0, 0.0), (37.0, 21.0), (-120.0, -48.0)]
            .into_iter()
            .enumerate()
        {
            let scene = Scene {
                camera: base.camera.orbit(yaw, pitch),
                ..base.clone()
            };
            for (shading, interpolation) in all_modes() {
                for cull in [true, false] {
                    let options = RenderOptions {
                        shading,
                        interpolation,
                        cull_backfaces: cull,
                        gouraud_specular: true,
                        ..options(173, 131, shading)
                    };
                    let name = format!(
                        "{}-view{view}-{}-{interpolation:?}-cull{cull}",
                        info.name,
                        shading.name()
                    );
                    check_equivalent(&name, &scene, &options).unwrap();
                }
            }
        }
    }
}

#[test]
fn camera_inside_a_mesh_and_clipped_floors_match() {
    // Clipping against the near plane and the guard band happens on both sides.
    for (name, scene) in &clipped_scenes() {
        for (shading, interpolation) in all_modes() {
            let options = RenderOptions {
                interpolation,
                cull_backfaces: false,
                ..options(160, 120, shading)
            };
            check_equivalent(
                &format!("{name}-{}-{interpolation:?}", shading.name()),
                scene,
                &options,
            )
            .unwrap();
        }
    }
}

#[test]
fn image_sizes_that_are_not_multiples_of_the_block() {
    let mesh = builtin_model("torus", None).unwrap().normalized();
    let normals = vertex_normals(&mesh, NormalWeighting::Uniform, None);
    let s = scene(
        mesh,
        normals,
        camera(DVec3::new(0.0, 1.5, 2.5), DVec3::ZERO, 50.0, 0.5, 20.0),
    );
    for (w, h) in [(1, 1), (7, 3), (9, 17), (33, 65), (100, 1)] {
        check_equivalent(
            &format!("torus-{w}x{h}"),
            &s,
            &options(w, h, Shading::Phong),
        )
        .unwrap();
    }
}

/// Triangles parallel to the image, seen straight on in perspective, so
/// that their corners' w are equal. Large ones (spans, pairs of blocks) and
/// small ones (blocks of 8), nearer ones over farther ones, every method,
/// both interpolation modes: the scanline rasterizer's pixels within 1/255.
/// And the tiled rasterizer draws such triangles in screen mode whatever
/// the frame's (`Triangle::interpolated`): perspective mode's image is
/// screen mode's, byte for byte.
#[test]
fn triangles_of_constant_w_match_the_scanline_rasterizer() {
    let cam = camera(DVec3::new(0.0, 0.0, 4.0), DVec3::ZERO, 50.0, 0.5, 20.0);
    let mut points = Vec::new();
    let mut normals = Vec::new();
    // (corners x, y; depth z): a quad wider than the view at z = 0 (w = 4),
    // a smaller one in front at z = 1 (w = 3), and small triangles at
    // z = 2 (w = 2), a few pixels across.
    let quad = |half: f32, z: f32| {
        let c = [(-half, -half), (half, -half), (half, half), (-half, half)];
        [c[0], c[1], c[2], c[0], c[2], c[3]].map(|(x, y)| Vec3::new(x, y, z))
    };
    points.extend(quad(3.0, 0.0));
    points.extend(quad(0.9, 1.0));
    for k in 0..12 {
        let (x, y) = (-0.9 + 0.15 * k as f32, 0.5 - 0.08 * k as f32);
        let size = 0.01 + 0.006 * k as f32;
        points.extend([
            Vec3::new(x, y, 2.0),
            Vec3::new(x + size, y, 2.0),
            Vec3::new(x, y + size, 2.0),
        ]);
    }
    for k in 0..points.len() {
        let t = k as f32 * 0.7;
        normals.push(Vec3::new(0.6 * t.sin(), 0.5 * (1.3 * t).cos(), 1.0).normalize());
    }
    let (mesh, normals) = triangle_mesh(&points, &normals);
    let scene = scene(mesh, normals, cam);
    for (shading, interpolation) in all_modes() {
        for (w, h) in [(197, 151), (512, 512)] {
            let options = RenderOptions {
                interpolation,
                gouraud_specular: true,
                ..options(w, h, shading)
            };
            check_equivalent(&format!("constant-w-{w}x{h}"), &scene, &options)
                .unwrap_or_else(|e| panic!("{shading:?}, {interpolation:?}: {e}"));
        }
    }
    for shading in [Shading::Gouraud, Shading::Phong] {
        let [perspective, screen] = [Interpolation::Perspective, Interpolation::Screen].map(|i| {
            let options = RenderOptions {
                interpolation: i,
                rasterizer: Rasterizer::Tiled,
                gouraud_specular: true,
                ..options(512, 512, shading)
            };
            let mut image = Image::filled(1, 1, options.background);
            Renderer::new()
                .render_into(&scene, &options, &mut image)
                .unwrap();
            image
        });
        assert!(
            perspective == screen,
            "{shading:?}: the modes' images differ"
        );
        // Not a blank or flat image: the colours vary over the quads.
        let colours: std::collections::HashSet<_> = perspective.pixels().iter().collect();
        assert!(
            colours.len() > 1000,
            "{shading:?}: {} colours",
            colours.len()
        );
    }
}

const W: u32 = 61;
const H: u32 = 47;

/// A point of the camera's view at window position (`x`, `y`) (pixels) and
/// view depth `depth`.
fn unproject(view: &View, x: f64, y: f64, depth: f64) -> Vec3 {
    f(view.eye + view.ray(x, y) * depth)
}

/// Window coordinates that favour pixel centres (k + ½) and pixel edges (k).
fn window_coordinate(limit: f64) -> impl Strategy<Value = f64> {
    prop_oneof![
        (-2i32..70).prop_map(|k| f64::from(k) + 0.5),
        (-2i32..70).prop_map(f64::from),
        -limit..limit,
        (-3.0f64..3.0).prop_map(|t| t * 1e5),
    ]
}

fn triangle_mesh(points: &[Vec3], normals: &[Vec3]) -> (Mesh, CornerNormals) {
    let polygons: Vec<[u32; 3]> = (0..points.len() as u32 / 3)
        .map(|t| [3 * t, 3 * t + 1, 3 * t + 2])
        .collect();
    let mesh = Mesh::from_polygons(points.to_vec(), &polygons).unwrap();
    let corners = CornerNormals::new(normals.to_vec(), (0..points.len() as u32).collect());
    (mesh, corners)
}

fn random_normal() -> impl Strategy<Value = Vec3> {
    (-1.0f32..1.0, -1.0f32..1.0, 0.2f32..1.0).prop_map(|(x, y, z)| Vec3::new(x, y, z).normalize())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    /// One triangle anywhere (on and off screen, huge, sliver, sub-pixel,
    /// crossing the near plane): same pixels, same colours within 1/255.
    #[test]
    fn one_triangle(
        corners in prop::collection::vec((window_coordinate(80.0), window_coordinate(60.0), -0.5f64..20.0), 3),
        normals in prop::collection::vec(random_normal(), 3),
        shading in prop::sample::select(Shading::ALL.to_vec()),
        screen in any::<bool>(),
        cull in any::<bool>(),
        blinn in any::<bool>(),
    ) {
        let cam = camera(DVec3::new(0.0, 0.0, 5.0), DVec3::ZERO, 50.0, 0.25, 30.0);
        let view = View::new(&cam, W, H);
        let points: Vec<Vec3> = corners.iter().map(|&(x, y, d)| unproject(&view, x, y, d)).collect();
        let (mesh, normals) = triangle_mesh(&points, &normals);
        let scene = scene(mesh, normals, cam);
        let options = RenderOptions {
            interpolation: if screen { Interpolation::Screen } else { Interpolation::Perspective },
            cull_backfaces: cull,
            gouraud_specular: true,
            specular: if blinn { Specular::BlinnPhong } else { Specular::Phong },
            ..options(W, H, shading)
        };
        if let Err(e) = check_equivalent("one-triangle", &scene, &options) {
            return Err(TestCaseError::fail(format!("{e}\n  triangle {corners:?}")));
        }
    }

    /// Many overlapping triangles: identical coverage counts (depth ties at
    /// intersections may resolve differently in f32 and f64, so colours are
    /// compared on single triangles above and on closed meshes).
    #[test]
    fn many_triangles_cover_the_same_pixels(
        corners in prop::collection::vec((window_coordinate(70.0), window_coordinate(50.0), 0.5f64..20.0), 3..60),
    ) {
        let cam = camera(DVec3::new(0.0, 0.0, 5.0), DVec3::ZERO, 50.0, 0.25, 30.0);
        let view = View::new(&cam, W, H);
        let n = corners.len() / 3 * 3;
        let points: Vec<Vec3> = corners[..n].iter().map(|&(x, y, d)| unproject(&view, x, y, d)).collect();
        let normals = vec![Vec3::Z; n];
        let (mesh, normals) = triangle_mesh(&points, &normals);
        let scene = scene(mesh, normals, cam);
        for cull in [true, false] {
            let scanline = RenderOptions {
                rasterizer: Rasterizer::Scanline,
                cull_backfaces: cull,
                ..options(W, H, Shading::Flat)
            };
            let tiled = RenderOptions { rasterizer: Rasterizer::Tiled, ..scanline };
            let want = shadelab_core::coverage(&scene, &scanline).unwrap();
            let got = shadelab_core::coverage(&scene, &tiled).unwrap();
            prop_assert_eq!(want, got);
        }
    }
}

/// Window coordinates for triangles of a few to a few hundred pixels on a
/// 257×193 image: large enough that rows are walked as spans, not blocks.
fn large_coordinate(limit: f64) -> impl Strategy<Value = f64> {
    prop_oneof![
        (-20i32..300).prop_map(|k| f64::from(k) + 0.5),
        (-20i32..300).prop_map(f64::from),
        -40.0..limit,
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 120, ..ProptestConfig::default() })]

    /// Triangles of up to a few hundred pixels, in all methods and both
    /// interpolations: the exact span walk covers what the scanline covers.
    #[test]
    fn large_triangles(
        corners in prop::collection::vec((large_coordinate(300.0), large_coordinate(230.0), 0.5f64..20.0), 3),
        normals in prop::collection::vec(random_normal(), 3),
        shading in prop::sample::select(Shading::ALL.to_vec()),
        screen in any::<bool>(),
    ) {
        let (w, h) = (257, 193);
        let cam = camera(DVec3::new(0.0, 0.0, 5.0), DVec3::ZERO, 50.0, 0.25, 30.0);
        let view = View::new(&cam, w, h);
        let points: Vec<Vec3> = corners.iter().map(|&(x, y, d)| unproject(&view, x, y, d)).collect();
        let (mesh, normals) = triangle_mesh(&points, &normals);
        let scene = scene(mesh, normals, cam);
        let options = RenderOptions {
            interpolation: if screen { Interpolation::Screen } else { Interpolation::Perspective },
            cull_backfaces: false,
            ..options(w, h, shading)
        };
        if let Err(e) = check_equivalent("large-triangle", &scene, &options) {
            return Err(TestCaseError::fail(format!("{e}\n  triangle {corners:?}")));
        }
    }

    /// Stacks of triangles at distinct depths (no two intersect), drawn in
    /// any order with culling on or off: Phong's queued fragments, later
    /// overwritten by nearer ones, leave the same colours as the scanline.
    #[test]
    fn overlapping_layers(
        layers in prop::collection::vec(
            (prop::collection::vec((window_coordinate(70.0), window_coordinate(50.0)), 3), random_normal()),
            2..24,
        ),
        cull in any::<bool>(),
    ) {
        check_layers(W, H, &layers, cull, Shading::Phong)?;
    }

    /// The same with layers of up to a few hundred pixels, whose rows are
    /// walked as spans: for Phong, whole blocks and packed ones queued over
    /// pixels that earlier layers left queued; for flat and Gouraud, blocks
    /// two at a time, whole or partly hidden.
    #[test]
    fn overlapping_large_layers(
        layers in prop::collection::vec(
            (prop::collection::vec((large_coordinate(300.0), large_coordinate(230.0)), 3), random_normal()),
            2..12,
        ),
        cull in any::<bool>(),
        shading in prop::sample::select(Shading::ALL.to_vec()),
    ) {
        check_layers(257, 193, &layers, cull, shading)?;
    }
}

/// Each layer, a triangle with window corners `(x, y)` and one normal,
/// parallel to the image at a depth of its own (near and far layers
/// alternating), drawn with `shading` by both rasterizers.
fn check_layers(
    w: u32,
    h: u32,
    layers: &[(Vec<(f64, f64)>, Vec3)],
    cull: bool,
    shading: Shading,
) -> Result<(), TestCaseError> {
    let cam = camera(DVec3::new(0.0, 0.0, 5.0), DVec3::ZERO, 50.0, 0.25, 30.0);
    let view = View::new(&cam, w, h);
    let mut points = Vec::new();
    let mut normals = Vec::new();
    for (k, (corners, normal)) in layers.iter().enumerate() {
        let depth = 2.0 + 0.37 * k as f64 + if k % 2 == 0 { 0.0 } else { 5.0 };
        for &(x, y) in corners {
            points.push(unproject(&view, x, y, depth));
            normals.push(*normal);
        }
    }
    let (mesh, normals) = triangle_mesh(&points, &normals);
    let scene = scene(mesh, normals, cam);
    let options = RenderOptions {
        cull_backfaces: cull,
        ..options(w, h, shading)
    };
    check_equivalent("layers", &scene, &options)
        .map_err(|e| TestCaseError::fail(format!("{e}\n  layers {layers:?}")))
}

#[test]
fn the_image_does_not_depend_on_the_thread_count() {
    let mesh = builtin_model("teapot", None).unwrap().normalized();
    let normals = vertex_normals(&mesh, NormalWeighting::Uniform, None);
    let s = scene(
        mesh,
        normals,
        camera(DVec3::new(0.5, 1.0, 3.0), DVec3::ZERO, 40.0, 0.5, 20.0),
    );
    for shading in Shading::ALL {
        let options = options(320, 240, shading);
        let render_with = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| shadelab_core::render(&s, &options).unwrap().0)
        };
        let one = render_with(1);
        for threads in [2, 3, 8] {
            assert!(
                one == render_with(threads),
                "{} with {threads} threads",
                shading.name()
            );
        }
    }
}

/// A renderer keeps its band buffers from frame to frame, clears only the
/// columns each frame's triangles can reach, and leaves the depths of a
/// band it wrote out cleared for the next: frames drawn one after another
/// by one renderer (the model moving across the image, seen from close up
/// in large triangles, the image changing size, a coverage pass or the
/// three methods at once in between) must equal the same frames drawn by
/// fresh renderers.
#[test]
fn frames_in_sequence_match_fresh_renders() {
    let mesh = builtin_model("teapot", None).unwrap().normalized();
    let normals = vertex_normals(&mesh, NormalWeighting::Uniform, None);
    let mut kept = Renderer::new();
    // Kept between frames of one size too: every pixel must be written.
    let mut again = Image::filled(1, 1, Rgb8([255, 0, 255]));
    let frames = [
        (0.0, 3.0, 320, 240),
        (1.2, 3.0, 320, 240),
        (-1.5, 3.0, 320, 240),
        (0.3, 0.9, 320, 240),
        (3.0, 3.0, 320, 240),
        (0.4, 3.0, 203, 157),
        (0.0, 0.8, 203, 157),
        (-0.9, 3.0, 400, 120),
    ];
    for shading in Shading::ALL {
        for (k, &(offset, distance, w, h)) in frames.iter().enumerate() {
            let eye = DVec3::new(offset, 0.8 * distance / 3.0, distance);
            let target = DVec3::new(offset, 0.0, 0.0);
            let s = scene(
                mesh.clone(),
                normals.clone(),
                camera(eye, target, 30.0, 0.1, 20.0),
            );
            let o = RenderOptions {
                rasterizer: Rasterizer::Tiled,
                ..options(w, h, shading)
            };
            if (again.width(), again.height()) != (w, h) {
                again = Image::filled(w, h, Rgb8([255, 0, 255]));
            }
            let case = format!(
                "{} offset {offset} distance {distance} {w}x{h}",
                shading.name()
            );
            kept.render_into(&s, &o, &mut again).unwrap();
            let mut fresh = Image::filled(w, h, Rgb8([0, 255, 0]));
            Renderer::new().render_into(&s, &o, &mut fresh).unwrap();
            assert!(
                again == fresh,
                "{case}: a reused renderer drew a different image"
            );
            // Other passes between frames, on the same band buffers.
            match k % 3 {
                0 => assert_eq!(
                    kept.coverage(&s, &o).unwrap(),
                    Renderer::new().coverage(&s, &o).unwrap(),
                    "{case}: coverage"
                ),
                1 => {
                    let mut got: [Image; 3] =
                        std::array::from_fn(|_| Image::filled(1, 1, o.background));
                    let mut want = got.clone();
                    let [a, b, c] = &mut got;
                    kept.render_methods(&s, &o, [a, b, c]).unwrap();
                    let [a, b, c] = &mut want;
                    Renderer::new().render_methods(&s, &o, [a, b, c]).unwrap();
                    assert!(got == want, "{case}: the three methods at once");
                }
                _ => {}
            }
        }
    }
}

/// A renderer kept between frames caches what it derives from the geometry
/// (face normals and centroids, the tiled rasterizer's distinct vertices);
/// each frame after a change of mesh, of positions only, or of corner
/// normals only must still equal a fresh renderer's, with either rasterizer.
#[test]
fn a_kept_renderer_sees_every_change_of_geometry() {
    let teapot = builtin_model("teapot", None).unwrap().normalized();
    // Same polygons, positions moved: only the positions tell them apart.
    let moved = Mesh::from_polygons(
        teapot
            .positions()
            .iter()
            .map(|p| Vec3::new(p.x * 0.7, p.y + 0.1 * p.x, p.z * 1.2))
            .collect(),
        (0..teapot.polygon_count()).map(|f| teapot.polygon(f)),
    )
    .unwrap();
    let sphere = builtin_model("sphere", None).unwrap().normalized();
    let smooth = |m: &Mesh| vertex_normals(m, NormalWeighting::Uniform, None);
    let creased = |m: &Mesh| vertex_normals(m, NormalWeighting::Angle, Some(20.0));
    let sequence = [
        (teapot.clone(), smooth(&teapot)),
        (moved.clone(), smooth(&moved)),
        (teapot.clone(), creased(&teapot)),
        (teapot.clone(), smooth(&teapot)),
        (sphere.clone(), smooth(&sphere)),
        (teapot.clone().normalized(), smooth(&teapot)),
        (teapot.clone(), smooth(&teapot)),
    ];
    for (shading, rasterizer) in Shading::ALL
        .into_iter()
        .flat_map(|s| [(s, Rasterizer::Tiled), (s, Rasterizer::Scanline)])
    {
        let mut kept = Renderer::new();
        for (k, (mesh, normals)) in sequence.iter().enumerate() {
            let s = scene(
                mesh.clone(),
                normals.clone(),
                camera(DVec3::new(0.3, 0.8, 3.0), DVec3::ZERO, 30.0, 0.5, 20.0),
            );
            let o = RenderOptions {
                rasterizer,
                ..options(240, 180, shading)
            };
            let mut again = Image::filled(1, 1, Rgb8::default());
            kept.render_into(&s, &o, &mut again).unwrap();
            let mut fresh = Image::filled(1, 1, Rgb8::default());
            Renderer::new().render_into(&s, &o, &mut fresh).unwrap();
            assert!(
                again == fresh,
                "{} {rasterizer:?} frame {k}: a kept renderer drew a different image",
                shading.name()
            );
        }
    }
}
