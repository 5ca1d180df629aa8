//! Light attenuation, `Id = Is = colour · intensity / (k0 + k1·d + k2·d²)`
//! for a point light at distance `d`: the scalar model against the formula,
//! and both rasterizers (each through its own writing of the model) drawing
//! the same attenuated image.

mod common;

use common::*;
use glam::{DVec3, Vec3};
use shadelab_core::{
    builtin_model, render, vertex_normals, Light, LightKind, Lighting, Material, NormalWeighting,
    Rasterizer, RenderOptions, Rgb, Scene, Shading, Specular, Terms, NO_ATTENUATION,
};

fn point_light(position: Vec3, attenuation: [f32; 3]) -> Light {
    Light {
        kind: LightKind::Point { position },
        color: Rgb::new(1.0, 0.8, 0.6),
        intensity: 2.0,
        attenuation,
    }
}

#[test]
fn the_model_divides_a_point_light_by_its_attenuation() {
    // A light 4 units above a point facing it: n·l = 1, d = 4.
    let k = [0.5, 0.25, 0.125];
    let lighting = |attenuation| Lighting {
        ambient: Rgb::BLACK,
        lights: vec![point_light(Vec3::new(0.0, 4.0, 0.0), attenuation)],
        material: Material::default(),
        eye: Vec3::new(0.0, 10.0, 0.0),
        specular: Specular::Phong,
    };
    let point = Vec3::ZERO;
    let up = Vec3::Y;
    let plain = lighting(NO_ATTENUATION).eval(point, up, Terms::AmbientDiffuse);
    let faded = lighting(k).eval(point, up, Terms::AmbientDiffuse);
    let divisor = 0.5 + 0.25 * 4.0 + 0.125 * 16.0;
    for (p, f) in plain.to_array().into_iter().zip(faded.to_array()) {
        assert!((f - p / divisor).abs() < 1e-6, "{f} vs {p} / {divisor}");
    }
    // Directional lights have no position, so no attenuation.
    let mut directional = lighting(k);
    directional.lights[0].kind = LightKind::Directional { direction: -up };
    let mut reference = lighting(NO_ATTENUATION);
    reference.lights[0].kind = LightKind::Directional { direction: -up };
    assert_eq!(
        directional.eval(point, up, Terms::Full),
        reference.eval(point, up, Terms::Full)
    );
}

#[test]
fn both_rasterizers_draw_the_same_attenuated_image_and_it_is_darker() {
    let mesh = builtin_model("torus", Some(24)).unwrap().normalized();
    let normals = vertex_normals(&mesh, NormalWeighting::Angle, None);
    let base = scene(
        mesh,
        normals,
        camera(DVec3::new(0.4, 1.6, 2.8), DVec3::ZERO, 40.0, 0.5, 20.0),
    );
    let with = |attenuation| Scene {
        lights: vec![
            point_light(Vec3::new(1.5, 1.5, 2.0), attenuation),
            point_light(Vec3::new(-2.0, 0.5, 1.0), attenuation),
        ],
        ..base.clone()
    };
    for shading in Shading::ALL {
        let draw = |scene: &Scene, rasterizer| {
            let options = RenderOptions {
                rasterizer,
                gouraud_specular: true,
                ..options(160, 120, shading)
            };
            render(scene, &options).unwrap().0
        };
        let faded = with([1.0, 0.2, 0.3]);
        let scanline = draw(&faded, Rasterizer::Scanline);
        let tiled = draw(&faded, Rasterizer::Tiled);
        for (y, (a, b)) in (scanline.pixels().iter())
            .zip(tiled.pixels())
            .enumerate()
            .map(|(i, p)| (i / 160, p))
        {
            for c in 0..3 {
                let (a, b) = (a.0[c], b.0[c]);
                assert!(
                    a.abs_diff(b) <= 1,
                    "{shading:?} row {y}: scanline {a} vs tiled {b}"
                );
            }
        }
        let sum = |image: &shadelab_core::Image| -> u64 {
            (image.pixels().iter())
                .map(|p| p.0.iter().map(|&c| u64::from(c)).sum::<u64>())
                .sum()
        };
        let plain = draw(&with(NO_ATTENUATION), Rasterizer::Scanline);
        assert!(
            sum(&scanline) < sum(&plain) * 9 / 10,
            "{shading:?}: attenuated {} vs plain {}",
            sum(&scanline),
            sum(&plain)
        );
    }
}
