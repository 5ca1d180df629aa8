//! `Renderer::render_methods` (the three methods over one geometry pass)
//! against three frames of `Renderer::render_into`: the same bytes and the
//! same statistics, on every built-in model, from several views, with every
//! option that changes what setup computes (interpolation, culling,
//! Gouraud's specular term, Blinn, attenuation, one point light or several),
//! at every SIMD level, on clipped scenes, odd sizes and both thread counts;
//! and the modes only the scanline rasterizer draws fall back to three frames.

mod common;

use common::*;
use glam::{DVec3, Vec3};
use shadelab_core::{
    builtin_model, draws_in_parts, part_rows, vertex_normals, Image, Interpolation, Light,
    LightKind, NormalWeighting, Palette, Polygons, Rasterizer, RenderOptions, RenderStats,
    Renderer, Scene, Shading, SimdLevel, Specular, BUILTIN_MODELS, ROW_ALIGN,
};

/// The three methods' images and statistics, one frame each.
fn one_by_one(
    renderer: &mut Renderer,
    scene: &Scene,
    options: &RenderOptions,
) -> ([Image; 3], [RenderStats; 3]) {
    let mut stats = [RenderStats::default(); 3];
    let images = std::array::from_fn(|k| {
        let o = RenderOptions {
            shading: Shading::ALL[k],
            ..*options
        };
        let mut image = Image::filled(1, 1, o.background);
        stats[k] = renderer.render_into(scene, &o, &mut image).unwrap();
        image
    });
    (images, stats)
}

/// Checks `render_methods` against [`one_by_one`] at every SIMD level, with
/// a renderer kept from the checks before (`kept`) and fresh ones, twice
/// each (images of a wrong size first, to be replaced; then the same ones).
fn check(name: &str, kept: &mut Renderer, scene: &Scene, options: &RenderOptions) {
    let mut fresh: Vec<Renderer> = SimdLevel::supported().map(Renderer::with_simd).collect();
    for renderer in std::iter::once(kept).chain(fresh.iter_mut()) {
        let level = renderer.simd();
        let (want, want_stats) = one_by_one(&mut Renderer::with_simd(level), scene, options);
        let mut got: [Image; 3] = std::array::from_fn(|_| Image::filled(3, 2, options.background));
        for round in 0..2 {
            let [a, b, c] = &mut got;
            let stats = renderer.render_methods(scene, options, [a, b, c]).unwrap();
            for k in 0..3 {
                let method = Shading::ALL[k].name();
                let level = level.name();
                assert!(
                    got[k] == want[k],
                    "{name}: {method} ({level}, round {round}) differs from its own frame"
                );
                assert_eq!(
                    stats[k], want_stats[k],
                    "{name}: {method} ({level}) statistics"
                );
            }
        }
        check_parts(name, renderer, scene, options, &want, &want_stats);
    }
}

/// Checks `render_methods_rows` of the frame in 2 and 3 parts (`part_rows`)
/// against the whole frame's `want`: each part holds the bytes of its rows,
/// counts the frame's polygons and Gouraud's evaluations, and the parts'
/// pixel counts and flat's and Phong's evaluations add up.
fn check_parts(
    name: &str,
    renderer: &mut Renderer,
    scene: &Scene,
    options: &RenderOptions,
    want: &[Image; 3],
    want_stats: &[RenderStats; 3],
) {
    let width = options.width as usize;
    for parts in [2, 3] {
        let mut sums = [(0, 0, 0); 3];
        let mut covered = 0..0;
        for part in 0..parts {
            let rows = part_rows(options.height, part, parts);
            if rows.is_empty() {
                continue;
            }
            assert_eq!(rows.start, covered.end, "{name}: parts follow each other");
            covered.end = rows.end;
            let mut got: [Image; 3] =
                std::array::from_fn(|_| Image::filled(1, 1, options.background));
            let [a, b, c] = &mut got;
            let (stats, drawn) = renderer
                .render_methods_rows(scene, options, rows.clone(), [a, b, c])
                .unwrap();
            // What is drawn whole, `draws_in_parts` tells beforehand.
            let whole = 0..options.height;
            let told = if draws_in_parts(options) {
                &rows
            } else {
                &whole
            };
            assert_eq!(&drawn, told, "{name}: the rows drawn");
            if drawn != rows {
                // A mode only the scanline rasterizer draws: whole frames.
                assert_eq!(drawn, 0..options.height, "{name}: drawn whole");
                for k in 0..3 {
                    assert!(got[k] == want[k], "{name}: a whole frame");
                    assert_eq!(stats[k], want_stats[k], "{name}: a whole frame's counts");
                }
                return;
            }
            for k in 0..3 {
                let method = Shading::ALL[k].name();
                let expected =
                    &want[k].pixels()[rows.start as usize * width..rows.end as usize * width];
                assert_eq!(got[k].height(), rows.end - rows.start);
                assert!(
                    got[k].pixels() == expected,
                    "{name}: {method}, rows {rows:?} of {parts} parts differ from the frame's"
                );
                let per_polygon = |s: &RenderStats| {
                    (
                        s.polygons,
                        s.degenerate,
                        s.invisible,
                        s.culled,
                        s.rasterized,
                    )
                };
                assert_eq!(
                    per_polygon(&stats[k]),
                    per_polygon(&want_stats[k]),
                    "{name}: {method} polygons"
                );
                if k == 1 {
                    assert_eq!(
                        stats[k].lighting_evaluations, want_stats[k].lighting_evaluations,
                        "{name}: {method}"
                    );
                }
                sums[k].0 += stats[k].fragments_shaded;
                sums[k].1 += stats[k].covered_pixels;
                sums[k].2 += stats[k].lighting_evaluations;
            }
        }
        assert_eq!(
            covered,
            0..options.height,
            "{name}: the parts cover the image"
        );
        for k in 0..3 {
            let w = &want_stats[k];
            assert_eq!(
                sums[k].0, w.fragments_shaded,
                "{name}: fragments of {parts} parts"
            );
            assert_eq!(
                sums[k].1, w.covered_pixels,
                "{name}: pixels of {parts} parts"
            );
            if k != 1 {
                assert_eq!(
                    sums[k].2, w.lighting_evaluations,
                    "{name}: evaluations of {parts} parts"
                );
            }
        }
    }
}

#[test]
fn parts_are_runs_of_whole_bands_and_others_are_refused() {
    for height in [1, 15, 16, 17, 100, 480, 1080, 4096] {
        for parts in 1..6 {
            let rows: Vec<_> = (0..parts).map(|k| part_rows(height, k, parts)).collect();
            assert_eq!(rows[0].start, 0);
            assert_eq!(rows[parts as usize - 1].end, height);
            for pair in rows.windows(2) {
                assert_eq!(pair[0].end, pair[1].start);
            }
            for r in &rows {
                assert!(
                    r.start % ROW_ALIGN == 0 || r.is_empty(),
                    "{height} {parts} {r:?}"
                );
                let len = r.end - r.start;
                assert!(
                    len <= height.div_ceil(ROW_ALIGN).div_ceil(parts) * ROW_ALIGN,
                    "{height} {parts} {r:?}"
                );
            }
        }
        assert!(part_rows(height, 2, 2).is_empty());
    }
    let mesh = builtin_model("teapot", None).unwrap().normalized();
    let normals = vertex_normals(&mesh, NormalWeighting::Uniform, None);
    let camera = camera(DVec3::new(0.4, 0.6, 3.2), DVec3::ZERO, 40.0, 0.5, 20.0);
    let (scene, options) = (
        scene(mesh, normals, camera),
        options(64, 40, Shading::Phong),
    );
    let mut renderer = Renderer::new();
    let backwards = std::ops::Range { start: 32, end: 16 };
    for rows in [0..0, 8..40, 0..20, 16..41, backwards] {
        let mut images: [Image; 3] =
            std::array::from_fn(|_| Image::filled(2, 2, options.background));
        let before = images.clone();
        let [a, b, c] = &mut images;
        let error = renderer
            .render_methods_rows(&scene, &options, rows.clone(), [a, b, c])
            .unwrap_err();
        assert!(
            matches!(error, shadelab_core::RenderError::Rows { .. }),
            "{rows:?}: {error}"
        );
        assert!(error.to_string().contains("multiple of 16 rows"), "{error}");
        assert!(
            images == before,
            "{rows:?}: a refused part leaves the images alone"
        );
    }
    // Modes only the scanline rasterizer draws: the whole frame, said so.
    let scanline = RenderOptions {
        rasterizer: Rasterizer::Scanline,
        ..options
    };
    let mut images: [Image; 3] = std::array::from_fn(|_| Image::filled(2, 2, options.background));
    let [a, b, c] = &mut images;
    let (_, drawn) = renderer
        .render_methods_rows(&scene, &scanline, 16..40, [a, b, c])
        .unwrap();
    assert_eq!(drawn, 0..40);
    assert_eq!(images[2].height(), 40);
}

fn lights_variants() -> Vec<(&'static str, Vec<Light>)> {
    let (_, standard, _) = standard_lighting();
    let mut attenuated = standard.clone();
    attenuated[0].attenuation = [1.0, 0.2, 0.05];
    let one_point = vec![standard[0]];
    let directional = vec![standard[1]];
    vec![
        ("two-lights", standard),
        ("attenuated", attenuated),
        ("one-point", one_point),
        ("directional", directional),
        ("dark", Vec::new()),
    ]
}

#[test]
fn the_three_methods_at_once_equal_three_frames_on_every_builtin_model() {
    let mut kept = Renderer::new();
    for info in BUILTIN_MODELS {
        let mesh = builtin_model(info.name, Some(info.default_detail))
            .unwrap()
            .normalized();
        let normals = vertex_normals(&mesh, NormalWeighting::Angle, info.default_crease_degrees);
        let base = scene(
            mesh,
            normals,
            camera(DVec3::new(0.4, 0.6, 3.2), DVec3::ZERO, 40.0, 0.5, 20.0),
        );
        for (view, (yaw, pitch)) in [(0.0, 0.0), (-120.0, -48.0)].into_iter().enumerate() {
            let scene = Scene {
                camera: base.camera.orbit(yaw, pitch),
                ..base.clone()
            };
            for interpolation in [Interpolation::Perspective, Interpolation::Screen] {
                for cull in [true, false] {
                    let options = RenderOptions {
                        interpolation,
                        cull_backfaces: cull,
                        gouraud_specular: view == 1,
                        specular: if cull {
                            Specular::Phong
                        } else {
                            Specular::BlinnPhong
                        },
                        ..options(97, 83, Shading::Phong)
                    };
                    let name = format!("{}-view{view}-{interpolation:?}-cull{cull}", info.name);
                    check(&name, &mut kept, &scene, &options);
                }
            }
        }
    }
}

/// Close up, where triangles are large: their spans' blocks are drawn two
/// at a time in the frames of flat and Gouraud (16 lanes, a pair that is
/// partly hidden or partly outside block by block), one at a time in the
/// three-methods frame; the bytes must not tell. Head on, the cube's front
/// face has the same w at every corner, so that the frames of Gouraud take
/// w once per row (`band/pairs.rs`), and the three-methods frame per pixel.
#[test]
fn the_three_methods_at_once_equal_three_frames_close_up() {
    let mut kept = Renderer::new();
    let eyes = [
        ("torus", DVec3::new(0.3, 0.5, 1.7)),
        ("cube", DVec3::new(0.3, 0.5, 1.7)),
        ("cube", DVec3::new(0.0, 0.0, 1.2)),
        ("teapot", DVec3::new(0.3, 0.5, 1.7)),
    ];
    for (name, eye) in eyes {
        let mesh = builtin_model(name, None).unwrap().normalized();
        let normals = vertex_normals(&mesh, NormalWeighting::Angle, Some(40.0));
        let base = scene(mesh, normals, camera(eye, DVec3::ZERO, 50.0, 0.2, 20.0));
        for (yaw, pitch) in [(0.0, 0.0), (35.0, -30.0)] {
            let scene = Scene {
                camera: base.camera.orbit(yaw, pitch),
                ..base.clone()
            };
            for interpolation in [Interpolation::Perspective, Interpolation::Screen] {
                let options = RenderOptions {
                    interpolation,
                    cull_backfaces: false,
                    ..options(331, 217, Shading::Phong)
                };
                let name = format!("{name}-close-{eye}-{yaw}-{interpolation:?}");
                check(&name, &mut kept, &scene, &options);
            }
        }
    }
}

#[test]
fn every_kind_of_lighting() {
    let mesh = builtin_model("torus", None).unwrap().normalized();
    let normals = vertex_normals(&mesh, NormalWeighting::Uniform, None);
    let base = scene(
        mesh,
        normals,
        camera(DVec3::new(0.0, 1.5, 2.5), DVec3::ZERO, 50.0, 0.5, 20.0),
    );
    let mut kept = Renderer::new();
    for (name, lights) in lights_variants() {
        let s = Scene {
            lights,
            ..base.clone()
        };
        for cull in [true, false] {
            let options = RenderOptions {
                cull_backfaces: cull,
                gouraud_specular: true,
                ..options(120, 90, Shading::Flat)
            };
            check(&format!("torus-{name}-cull{cull}"), &mut kept, &s, &options);
        }
    }
}

#[test]
fn clipped_scenes_odd_sizes_and_thread_counts() {
    let mut kept = Renderer::new();
    for (name, s) in &clipped_scenes() {
        for (w, h) in [(1, 1), (9, 17), (160, 120), (100, 1)] {
            let options = RenderOptions {
                cull_backfaces: false,
                ..options(w, h, Shading::Gouraud)
            };
            for threads in [1, 2] {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .unwrap();
                pool.install(|| {
                    check(
                        &format!("{name}-{w}x{h}-{threads}t"),
                        &mut kept,
                        s,
                        &options,
                    )
                });
            }
        }
    }
}

#[test]
fn modes_only_the_scanline_rasterizer_draws_render_three_frames() {
    let mesh = builtin_model("sphere", None).unwrap().normalized();
    let normals = vertex_normals(&mesh, NormalWeighting::Uniform, None);
    let s = scene(
        mesh,
        normals,
        camera(DVec3::new(0.0, 0.5, 3.0), DVec3::ZERO, 40.0, 0.5, 20.0),
    );
    let mut kept = Renderer::new();
    let base = options(64, 48, Shading::Phong);
    for (name, options) in [
        (
            "scanline",
            RenderOptions {
                rasterizer: Rasterizer::Scanline,
                ..base
            },
        ),
        (
            "whole-polygons",
            RenderOptions {
                rasterizer: Rasterizer::Scanline,
                polygons: Polygons::Whole,
                ..base
            },
        ),
        (
            "fixed-point",
            RenderOptions {
                rasterizer: Rasterizer::Scanline,
                fixed_point_bits: Some(4),
                ..base
            },
        ),
        (
            "palette",
            RenderOptions {
                rasterizer: Rasterizer::Scanline,
                palette: Some(Palette {
                    shades: 8,
                    offset: 0,
                }),
                ..base
            },
        ),
    ] {
        check(name, &mut kept, &s, &options);
    }
}

#[test]
fn a_bad_request_is_refused_for_the_three_methods() {
    let mesh = builtin_model("cube", None).unwrap();
    let normals = vertex_normals(&mesh, NormalWeighting::Uniform, None);
    let mut s = scene(
        mesh,
        normals,
        camera(DVec3::new(0.0, 0.5, 3.0), DVec3::ZERO, 40.0, 0.5, 20.0),
    );
    s.lights.push(Light {
        kind: LightKind::Point {
            position: Vec3::new(f32::NAN, 0.0, 0.0),
        },
        ..s.lights[0]
    });
    let mut images: [Image; 3] = std::array::from_fn(|_| Image::filled(2, 2, BACKGROUND));
    let before = images.clone();
    let [a, b, c] = &mut images;
    let err = Renderer::new()
        .render_methods(&s, &options(32, 32, Shading::Flat), [a, b, c])
        .unwrap_err();
    assert!(err.to_string().contains("light"), "{err}");
    assert_eq!(images, before, "a refused request leaves the images alone");
}
