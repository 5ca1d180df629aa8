//! Scanline profiles on cases with known answers: flat shading is constant
//! on each polygon and jumps at edges; Gouraud shading (screen-linear) is
//! linear on each polygon, so its derivative is constant there and kinks at
//! edges; and every value is the renderer's own.

mod common;

use common::*;
use glam::Vec3;
use shadelab_core::{render, Interpolation, Polygons, RenderOptions, Shading};
use shadelab_lab::{intensity, profile, CurveKind, ProfileLine, Shape, Surface};

fn sphere_profile(polygons: Polygons) -> shadelab_lab::Profile {
    let scene = scene("sphere", 10, Vec3::new(0.4, 0.9, 3.6));
    let options = RenderOptions {
        interpolation: Interpolation::Screen,
        polygons,
        ..options(200, 160, Shading::Phong)
    };
    profile(
        &scene,
        &options,
        ProfileLine::Row(70),
        Some(&Surface::new(Shape::Sphere)),
    )
    .unwrap()
}

/// Runs of consecutive samples drawn from one piece.
fn runs(pieces: &[Option<u64>]) -> Vec<std::ops::Range<usize>> {
    let mut out = Vec::new();
    let mut start = 0;
    for k in 1..=pieces.len() {
        if k == pieces.len() || pieces[k] != pieces[start] {
            if pieces[start].is_some() {
                out.push(start..k);
            }
            start = k;
        }
    }
    out
}

#[test]
fn flat_is_a_staircase_with_jumps_at_edges() {
    for polygons in [Polygons::Whole, Polygons::Fans] {
        let p = sphere_profile(polygons);
        let flat = &p.curves[0];
        assert_eq!(flat.kind, CurveKind::Method(Shading::Flat));
        let faces = runs(
            &flat
                .faces
                .iter()
                .map(|f| f.map(|f| f as u64))
                .collect::<Vec<_>>(),
        );
        assert!(
            faces.len() >= 4,
            "{polygons:?}: the row crosses {} polygons",
            faces.len()
        );
        for run in &faces {
            let v = flat.values[run.start].unwrap();
            for k in run.clone() {
                assert_eq!(flat.values[k], Some(v), "{polygons:?}: sample {k}");
            }
        }
        // A jump at every polygon edge, and nowhere else.
        let edges = flat.polygon_edges();
        assert_eq!(edges.len(), faces.len() - 1);
        let jumps = flat
            .derivative
            .iter()
            .filter(|d| d.is_some_and(|d| d != 0.0))
            .count();
        assert_eq!(jumps, edges.len(), "{polygons:?}");
        for &k in &edges {
            assert!(
                flat.derivative[k].unwrap().abs() > 0.5,
                "{polygons:?}: edge at {k}"
            );
        }
    }
}

#[test]
fn gouraud_derivative_is_constant_on_each_piece_and_kinks_at_edges() {
    for polygons in [Polygons::Whole, Polygons::Fans] {
        let p = sphere_profile(polygons);
        let g = &p.curves[1];
        assert_eq!(g.kind, CurveKind::Method(Shading::Gouraud));
        let pieces = runs(&g.pieces);
        assert!(pieces.len() >= 4, "{polygons:?}");
        let mut slopes = Vec::new();
        for run in &pieces {
            if run.len() < 3 {
                continue;
            }
            let d0 = g.derivative[run.start].unwrap();
            for k in run.start..run.end - 1 {
                let d = g.derivative[k].unwrap();
                assert!(
                    (d - d0).abs() < 2e-3,
                    "{polygons:?}: slope {d} vs {d0} at {k}"
                );
            }
            slopes.push(d0);
        }
        // Neighbouring pieces have different slopes: the kinks.
        let kinks = slopes
            .windows(2)
            .filter(|w| (w[0] - w[1]).abs() > 0.01)
            .count();
        assert!(
            kinks + 1 >= slopes.len() - 1,
            "{polygons:?}: slopes {slopes:?}"
        );
        // Phong shading follows the exact surface more closely than Gouraud.
        let exact = &p.curves[3];
        let err = |c: &shadelab_lab::Curve| -> f64 {
            c.values
                .iter()
                .zip(&exact.values)
                .filter_map(|(a, b)| Some((a.as_ref()? - b.as_ref()?).abs()))
                .sum()
        };
        assert!(err(&p.curves[2]) < err(g), "{polygons:?}");
    }
}

#[test]
fn profile_values_are_the_rendered_pixels() {
    let scene = scene("torus", 12, Vec3::new(0.5, 2.5, 3.0));
    let options = options(160, 120, Shading::Phong);
    let line = ProfileLine::Segment {
        from: (10.5, 100.5),
        to: (150.5, 20.5),
    };
    let p = profile(&scene, &options, line, None).unwrap();
    assert_eq!(p.curves.len(), 3);
    for (m, shading) in Shading::ALL.into_iter().enumerate() {
        let (image, _) = render(&scene, &RenderOptions { shading, ..options }).unwrap();
        let mut drawn = 0;
        for (k, &(x, y)) in p.pixels.iter().enumerate() {
            match p.curves[m].values[k] {
                None => assert_eq!(image.pixel(x, y), BACKGROUND),
                Some(v) => {
                    drawn += 1;
                    // The pixel is the rounded light; the profile its unrounded intensity.
                    let px = intensity(image.pixel(x, y).to_rgb());
                    assert!(
                        (px - v).abs() <= 0.5 + 1e-3,
                        "{shading:?} ({x}, {y}): {px} vs {v}"
                    );
                }
            }
        }
        assert!(drawn > 40);
    }
}
