//! The modes of old hardware: fixed-point stepping and the indexed palette,
//! drawn by the scanline rasterizer only; the quad study; the cost counts.

mod common;

use std::collections::BTreeSet;

use common::*;
use glam::Vec3;
use shadelab_core::{
    render, Interpolation, Palette, Polygons, Rasterizer, RenderError, RenderOptions, Rgb, Rgb8,
    Shading,
};
use shadelab_lab::{image_diff, measure_cost, quad_study};

fn lit_sphere() -> shadelab_core::Scene {
    let mut s = scene("sphere", 24, Vec3::new(0.0, 0.0, 3.6));
    // No ambient light, a light from the side: intensities from 0 to past 1.
    s.ambient = Rgb::BLACK;
    s.lights[0].kind = shadelab_core::LightKind::Point {
        position: Vec3::new(4.0, 1.0, 1.5),
    };
    s.lights[0].intensity = 1.6;
    s.material.kd = Rgb::new(1.0, 0.5, 0.25);
    s
}

#[test]
fn the_palette_draws_exactly_n_shades_of_the_material_colour() {
    let scene = lit_sphere();
    for shading in [Shading::Gouraud, Shading::Phong] {
        for shades in [4u32, 8, 16] {
            let palette = Palette { shades, offset: 32 };
            let options = RenderOptions {
                palette: Some(palette),
                ..options(160, 160, shading)
            };
            let (image, _) = render(&scene, &options).unwrap();
            let colours: BTreeSet<[u8; 3]> = image
                .pixels()
                .iter()
                .filter(|&&p| p != BACKGROUND)
                .map(|p| p.0)
                .collect();
            let entries: BTreeSet<[u8; 3]> = (0..shades)
                .map(|k| palette.entry_color(k, scene.material.kd).0)
                .collect();
            assert_eq!(entries.len(), shades as usize);
            assert_eq!(colours, entries, "{shading:?}, {shades} shades");
        }
    }
}

#[test]
fn fixed_point_with_many_bits_is_float_and_with_few_bits_is_visibly_off() {
    let scene = scene("sphere", 12, Vec3::new(0.3, 0.5, 3.6));
    for interpolation in [Interpolation::Screen, Interpolation::Perspective] {
        for shading in [Shading::Gouraud, Shading::Phong] {
            let float = RenderOptions {
                interpolation,
                polygons: Polygons::Whole,
                ..options(240, 200, shading)
            };
            let (reference, _) = render(&scene, &float).unwrap();
            let with = |bits| {
                render(
                    &scene,
                    &RenderOptions {
                        fixed_point_bits: Some(bits),
                        ..float
                    },
                )
                .unwrap()
                .0
            };
            let fine = image_diff(&reference, &with(20));
            assert!(
                fine.max <= 1,
                "{interpolation:?} {shading:?}: 20 bits differ by {}",
                fine.max
            );
            let coarse = image_diff(&reference, &with(3));
            assert!(
                coarse.max >= 8 && coarse.mean > 0.5,
                "{interpolation:?} {shading:?}: 3 bits {coarse:?}"
            );
            // Error shrinks as bits are added.
            let mid = image_diff(&reference, &with(8));
            assert!(mid.mean < coarse.mean, "{interpolation:?} {shading:?}");
        }
    }
}

#[test]
fn scanline_only_modes_are_typed_errors_for_the_tiled_rasterizer() {
    let scene = scene("sphere", 8, Vec3::new(0.0, 0.0, 3.6));
    let tiled = RenderOptions {
        rasterizer: Rasterizer::Tiled,
        ..options(32, 32, Shading::Gouraud)
    };
    let palette = Some(Palette {
        shades: 8,
        offset: 0,
    });
    assert_eq!(
        render(&scene, &RenderOptions { palette, ..tiled }).unwrap_err(),
        RenderError::ScanlineOnly("render.palette_shades")
    );
    assert_eq!(
        render(
            &scene,
            &RenderOptions {
                fixed_point_bits: Some(8),
                ..tiled
            }
        )
        .unwrap_err(),
        RenderError::ScanlineOnly("render.fixed_point_bits")
    );
    let scanline = options(32, 32, Shading::Gouraud);
    assert_eq!(
        render(
            &scene,
            &RenderOptions {
                fixed_point_bits: Some(0),
                ..scanline
            }
        )
        .unwrap_err(),
        RenderError::FractionBits(0)
    );
    assert!(matches!(
        render(
            &scene,
            &RenderOptions {
                palette: Some(Palette {
                    shades: 1,
                    offset: 0
                }),
                ..scanline
            }
        ),
        Err(RenderError::Palette {
            shades: 1,
            offset: 0
        })
    ));
    assert!(matches!(
        render(
            &scene,
            &RenderOptions {
                palette: Some(Palette {
                    shades: 100,
                    offset: 200
                }),
                ..scanline
            }
        ),
        Err(RenderError::Palette { .. })
    ));
    assert!(RenderOptions { palette, ..tiled }.needs_scanline());
}

#[test]
fn a_quad_interpolated_whole_changes_as_it_turns_and_as_triangles_it_does_not() {
    let study = quad_study(&[0.0, 45.0, 90.0, 135.0, 180.0, 225.0, 30.0], 101).unwrap();
    let centre = |a: f32| study.iter().find(|q| q.angle_degrees == a).unwrap();
    // Upright: the scanline walk is bilinear, the centre is the mean of the four.
    assert!((centre(0.0).whole_centre - 0.25).abs() < 1e-3);
    assert!((centre(90.0).whole_centre - 0.25).abs() < 1e-3);
    // On a corner: the centre's scanline joins the two side vertices, both
    // dark, or the bright one and a dark one.
    let diamond: Vec<f32> = [45.0, 135.0, 225.0]
        .iter()
        .map(|&a| centre(a).whole_centre)
        .collect();
    assert!(diamond.iter().any(|v| v.abs() < 1e-3), "{diamond:?}");
    assert!(
        diamond.iter().any(|v| (v - 0.5).abs() < 1e-3),
        "{diamond:?}"
    );
    // As triangles split through the bright vertex, the centre is 1/2 at every turn.
    for q in &study {
        assert!(
            (q.fans_centre - 0.5).abs() < 1e-3,
            "{}°: {}",
            q.angle_degrees,
            q.fans_centre
        );
    }
    // And the whole quad's picture does change with the turn.
    assert!(centre(30.0).whole_centre < 0.2);
    assert_ne!(study[0].whole, study[0].fans);
    assert_eq!(study[0].whole.pixel(0, 0), Rgb8::new(30, 30, 40));
}

#[test]
fn cost_counts_evaluations_at_each_methods_granularity() {
    let scene = scene("torus", 16, Vec3::new(0.0, 2.0, 3.0));
    let options = options(120, 100, Shading::Phong);
    let mut ticks = 0.0;
    let costs = measure_cost(&scene, &options, &Shading::ALL, 3, || {
        ticks += 1.0;
        ticks
    })
    .unwrap();
    assert_eq!(costs.len(), 3);
    let (flat, gouraud, phong) = (&costs[0], &costs[1], &costs[2]);
    assert_eq!(flat.per_polygon, flat.stats.rasterized);
    assert_eq!((flat.per_vertex, flat.per_pixel), (0, 0));
    // Gouraud lights each visible vertex once: fewer than the polygons' corners.
    assert!(gouraud.per_vertex > 0 && gouraud.per_vertex < 4 * gouraud.stats.rasterized);
    assert_eq!((gouraud.per_polygon, gouraud.per_pixel), (0, 0));
    assert_eq!(phong.per_pixel, phong.stats.fragments_shaded);
    assert!(phong.per_pixel > gouraud.per_vertex * 5);
    // Each run was timed by the clock given: one tick per run.
    for c in &costs {
        assert_eq!(c.millis, 1.0);
        assert_eq!(c.runs, 3);
    }
}
