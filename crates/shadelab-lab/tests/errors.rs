//! Error maps on cases with known answers.

mod common;

use common::*;
use glam::Vec3;
use shadelab_core::{
    vertex_normals, Light, LightKind, NormalWeighting, Polygons, RenderOptions, Rgb, Scene, Shading,
};
use shadelab_lab::{accuracy, error_maps, ExactImage, Shape, Surface};

/// A square facing the camera, lit head-on by a directional light, no
/// highlight: the light is the same everywhere, so every method is exact.
#[test]
fn a_plane_lit_head_on_has_no_error_in_any_method() {
    let mesh = square_mesh();
    let normals = vertex_normals(&mesh, NormalWeighting::Uniform, None);
    let mut scene = Scene {
        mesh,
        normals,
        ..scene("cube", 1, Vec3::new(0.3, -0.2, 4.0))
    };
    scene.lights = vec![Light {
        kind: LightKind::Directional {
            direction: -Vec3::Z,
        },
        color: Rgb::WHITE,
        intensity: 0.8,
        attenuation: shadelab_core::NO_ATTENUATION,
    }];
    scene.material.ks = Rgb::BLACK;
    for polygons in [Polygons::Whole, Polygons::Fans] {
        let options = RenderOptions {
            polygons,
            ..options(96, 80, Shading::Flat)
        };
        let (_, maps) = error_maps(&scene, &options, &Surface::new(Shape::Square)).unwrap();
        for m in &maps {
            assert!(m.map.compared > 1500, "{:?}", m.shading);
            // Only the rounding to 8 bits remains.
            assert!(
                m.map.max <= 0.5 + 1e-3,
                "{:?}: max {}",
                m.shading,
                m.map.max
            );
            assert!(m.map.mean <= 0.5, "{:?}", m.shading);
            // The square's outline is a polygon: the silhouettes agree but for pixels on the edge.
            assert!(m.map.mesh_only + m.map.surface_only <= 4, "{:?}", m.shading);
        }
    }
}

/// Gouraud shading without the specular term misses the highlight: its
/// largest error is where the exact surface is brightest.
#[test]
fn gouraud_error_peaks_at_the_analytic_highlight() {
    let scene = scene("sphere", 16, Vec3::new(0.0, 0.4, 3.8));
    let options = options(160, 160, Shading::Gouraud);
    let surface = Surface::new(Shape::Sphere);
    let (exact, maps) = error_maps(&scene, &options, &surface).unwrap();
    // The highlight: the brightest exact pixel.
    let (mut best, mut at) = (0.0f32, (0, 0));
    for y in 0..exact.height {
        for x in 0..exact.width {
            if let Some(lit) = exact.lit(x, y) {
                let v = lit.r + lit.g + lit.b;
                if v > best {
                    best = v;
                    at = (x, y);
                }
            }
        }
    }
    let g = &maps[1];
    let (gx, gy) = g.map.max_at.unwrap();
    let distance =
        f64::from((gx as i32 - at.0 as i32).pow(2) + (gy as i32 - at.1 as i32).pow(2)).sqrt();
    assert!(
        distance < 8.0,
        "Gouraud's worst pixel ({gx}, {gy}) is {distance:.1} px from the highlight {at:?}"
    );
    // And the error there is about the highlight's height.
    assert!(g.map.max > 60.0, "{}", g.map.max);
    // Phong < Gouraud < flat on average.
    let mean = |k: usize| maps[k].map.mean;
    assert!(
        mean(2) < mean(1) && mean(1) < mean(0),
        "{} {} {}",
        mean(0),
        mean(1),
        mean(2)
    );
}

#[test]
fn every_method_converges_on_the_exact_torus_and_phong_leads() {
    let rows = accuracy(
        &[8, 16, 32, 64],
        |detail| -> Result<_, shadelab_core::RenderError> {
            let scene = scene("torus", detail, Vec3::new(0.0, 2.2, 3.2));
            let options = RenderOptions {
                gouraud_specular: true,
                ..options(140, 110, Shading::Phong)
            };
            let surface = Surface::new(Shape::Torus {
                ring: 1.0,
                tube: 0.4,
            });
            Ok((scene, options, surface))
        },
    )
    .unwrap();
    for w in rows.windows(2) {
        for m in 0..3 {
            assert!(w[1].errors[m].0 < w[0].errors[m].0, "method {m}: {rows:?}");
        }
    }
    for r in &rows {
        assert!(
            r.errors[2].0 < r.errors[1].0 && r.errors[2].0 < r.errors[0].0,
            "{r:?}"
        );
    }
    assert!(rows[3].errors[2].0 < 1.0, "{rows:?}");
}

/// On fine meshes with creased normals (as the scene gives them) the exact
/// cylinder and cone agree with Phong shading, caps and sides alike; with
/// the caps smoothed into the sides the error map shows the mistake.
#[test]
fn exact_cylinder_and_cone_cover_their_meshes() {
    for (model, shape) in [("cylinder", Shape::Cylinder), ("cone", Shape::Cone)] {
        let mut scene = scene(model, 256, Vec3::new(1.0, 1.6, 4.0));
        let smoothed = error_maps(
            &scene,
            &options(100, 100, Shading::Phong),
            &Surface::new(shape),
        )
        .unwrap()
        .1[2]
            .map
            .mean;
        scene.normals = vertex_normals(&scene.mesh, NormalWeighting::Uniform, Some(60.0));
        let options = options(100, 100, Shading::Phong);
        let exact = ExactImage::render(&Surface::new(shape), &scene, &options);
        let (_, maps) = error_maps(&scene, &options, &Surface::new(shape)).unwrap();
        let m = &maps[2].map;
        assert!(m.compared > 2000, "{model}");
        assert!(
            m.mesh_only + m.surface_only < m.compared / 50,
            "{model}: {} {}",
            m.mesh_only,
            m.surface_only
        );
        // Phong on a fine mesh is within a few levels, caps and sides alike;
        // the cone's apex has one vertex normal (straight up) for all its
        // side triangles, and interpolating from it bends every side normal
        // a little: the error map shows the apex's fault as a glow.
        let limit = if model == "cone" { 4.0 } else { 1.5 };
        assert!(m.mean < limit, "{model}: mean {}", m.mean);
        assert_eq!(
            exact.pixels.iter().filter(|p| p.is_some()).count(),
            m.compared + m.surface_only
        );
        assert!(
            smoothed > 5.0 * m.mean,
            "{model}: smoothed caps {smoothed}, creased {}",
            m.mean
        );
    }
}
