//! The probe reports what the scanline rasterizer drew: at every pixel the
//! recorded colour is the rendered one, the trace describes the span that
//! drew it, and the spelled-out lighting sums to exactly what the model
//! returns.

mod common;

use common::*;
use glam::{DVec3, Vec3};
use shadelab_core::{
    builtin_model, depth_buffer, probe, render, vertex_normals, Interpolation, Lighting,
    NormalWeighting, Polygons, ProbeRequest, Rasterizer, RenderOptions, Shading, Specular, Terms,
};

fn all_pixels(w: u32, h: u32) -> Vec<(u32, u32)> {
    (0..h).flat_map(|y| (0..w).map(move |x| (x, y))).collect()
}

#[test]
fn probed_colours_are_the_rendered_pixels_everywhere() {
    // The teapot has openings: with culling off, back faces show through.
    let mesh = builtin_model("teapot", Some(4)).unwrap().normalized();
    let normals = vertex_normals(&mesh, NormalWeighting::Uniform, None);
    let scene = scene(
        mesh,
        normals,
        camera(DVec3::new(0.6, 1.6, 2.4), DVec3::ZERO, 45.0, 0.3, 10.0),
    );
    let (w, h) = (90, 70);
    let pixels = all_pixels(w, h);
    for shading in Shading::ALL {
        for interpolation in [Interpolation::Perspective, Interpolation::Screen] {
            for polygons in [Polygons::Fans, Polygons::Whole] {
                for cull_backfaces in [true, false] {
                    let options = RenderOptions {
                        interpolation,
                        polygons,
                        cull_backfaces,
                        rasterizer: Rasterizer::Scanline,
                        ..options(w, h, shading)
                    };
                    let what =
                        format!("{shading:?} {interpolation:?} {polygons:?} cull {cull_backfaces}");
                    let (image, _) = render(&scene, &options).unwrap();
                    let records = probe(
                        &scene,
                        &options,
                        ProbeRequest {
                            pixels: &pixels,
                            trace: true,
                        },
                    )
                    .unwrap();
                    let mut back = 0;
                    for (&(x, y), r) in pixels.iter().zip(&records) {
                        match r {
                            None => assert_eq!(image.pixel(x, y), BACKGROUND, "{what} ({x}, {y})"),
                            Some(r) => {
                                assert_eq!((r.x, r.y), (x, y));
                                assert_eq!(r.color, image.pixel(x, y), "{what} ({x}, {y})");
                                back += usize::from(r.back);
                                let span = r.span.as_ref().expect("traced");
                                assert_eq!(span.row, y);
                                assert!(span.pixels.contains(&x));
                                let u = span.u(x);
                                assert!((0.0..1.0).contains(&u), "{what}: u = {u}");
                                // The recorded attributes are the span's start plus whole steps.
                                let k = f64::from(x - span.pixels.start);
                                let start = span.start.attributes(interpolation);
                                for (i, a) in r.attrs.iter().enumerate() {
                                    let stepped = span.start.stepped[i] + k * span.step.stepped[i];
                                    let inv_w = span.start.inv_w + k * span.step.inv_w;
                                    let expect = match interpolation {
                                        Interpolation::Perspective => stepped / inv_w,
                                        Interpolation::Screen => stepped,
                                    };
                                    assert!(
                                        (f64::from(*a) - expect).abs()
                                            <= 1e-5 * (1.0 + expect.abs()),
                                        "{what} ({x}, {y}) attr {i}: {a} vs {expect} (start {:?})",
                                        start
                                    );
                                }
                            }
                        }
                    }
                    if !cull_backfaces {
                        assert!(back > 0, "{what}: the inside of the pot shows");
                    }
                }
            }
        }
    }
}

#[test]
fn probe_outside_the_image_and_repeated_pixels() {
    let mesh = builtin_model("sphere", Some(8)).unwrap();
    let normals = vertex_normals(&mesh, NormalWeighting::Uniform, None);
    let scene = scene(
        mesh,
        normals,
        camera(DVec3::new(0.0, 0.0, 4.0), DVec3::ZERO, 40.0, 0.5, 10.0),
    );
    let options = options(40, 30, Shading::Phong);
    let r = probe(
        &scene,
        &options,
        ProbeRequest {
            pixels: &[(20, 15), (99, 1), (20, 15), (0, 0)],
            trace: false,
        },
    )
    .unwrap();
    assert!(r[0].is_some() && r[0] == r[2]);
    assert!(r[1].is_none() && r[3].is_none());
    assert!(r[0].as_ref().unwrap().span.is_none());
}

#[test]
fn depth_buffer_marks_exactly_the_drawn_pixels() {
    let mesh = builtin_model("torus", Some(16)).unwrap();
    let normals = vertex_normals(&mesh, NormalWeighting::Uniform, None);
    let scene = scene(
        mesh,
        normals,
        camera(DVec3::new(0.0, 2.5, 3.0), DVec3::ZERO, 45.0, 0.5, 10.0),
    );
    let options = options(80, 60, Shading::Gouraud);
    let (image, _) = render(&scene, &options).unwrap();
    let depth = depth_buffer(&scene, &options).unwrap();
    let records = probe(
        &scene,
        &options,
        ProbeRequest {
            pixels: &all_pixels(80, 60),
            trace: false,
        },
    )
    .unwrap();
    for (k, d) in depth.iter().enumerate() {
        let drawn = image.pixels()[k] != BACKGROUND;
        assert_eq!(*d < 1.0, drawn, "pixel {k}");
        if let Some(r) = &records[k] {
            assert_eq!(r.depth, *d, "pixel {k}: the winner is the nearest");
        }
    }
}

#[test]
fn spelled_out_lighting_sums_to_the_model_bit_for_bit() {
    let (ambient, lights, material) = standard_lighting();
    let mut seed = 99u64;
    let mut next = || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((seed >> 40) as f32 / (1u64 << 24) as f32) * 2.0 - 1.0
    };
    for specular in [Specular::Phong, Specular::BlinnPhong] {
        let lighting = Lighting {
            ambient,
            lights: lights.clone(),
            material,
            eye: Vec3::new(0.5, 1.0, 4.0),
            specular,
        };
        for _ in 0..5000 {
            let p = Vec3::new(next(), next(), next());
            let n = Vec3::new(next(), next(), next()).normalize_or_zero();
            for terms in [Terms::Full, Terms::AmbientDiffuse] {
                let explained = lighting.explain(p, n, terms);
                assert_eq!(
                    explained.total,
                    lighting.eval(p, n, terms),
                    "{specular:?} {terms:?} at {p}, n = {n}"
                );
                let lit = explained.lights.iter().filter(|l| l.n_dot_l > 0.0).count();
                let with_specular = explained
                    .lights
                    .iter()
                    .filter(|l| l.cosine.is_some())
                    .count();
                assert_eq!(with_specular, if terms == Terms::Full { lit } else { 0 });
            }
        }
    }
}
