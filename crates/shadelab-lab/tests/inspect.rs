//! The pixel inspector explains what was drawn: its colour is the rendered
//! pixel's, its interpolated values are the renderer's own, and the
//! textbook formulas it fills in agree with the values the walk stepped.

use glam::Vec3;
use shadelab_core::{
    builtin_model, render, vertex_normals, Camera, Interpolation, Light, LightKind, Material,
    NormalWeighting, Polygons, Rasterizer, RenderOptions, Rgb, Rgb8, Scene, Shading, Specular,
    Terms,
};
use shadelab_lab::{inspect, inspection_text, lighting_of, Lang, Texts};

fn scene(model: &str, detail: u32, eye: Vec3) -> Scene {
    let mesh = builtin_model(model, Some(detail)).unwrap();
    let normals = vertex_normals(&mesh, NormalWeighting::Uniform, None);
    Scene {
        mesh,
        normals,
        camera: Camera {
            eye,
            target: Vec3::ZERO,
            up: Vec3::Y,
            fov_y_degrees: 40.0,
            near: 0.5,
            far: 20.0,
        },
        ambient: Rgb::new(0.15, 0.12, 0.1),
        lights: vec![
            Light {
                kind: LightKind::Point {
                    position: Vec3::new(2.0, 3.0, 4.0),
                },
                color: Rgb::new(1.0, 0.95, 0.9),
                intensity: 0.9,
                attenuation: shadelab_core::NO_ATTENUATION,
            },
            Light {
                kind: LightKind::Directional {
                    direction: Vec3::new(-0.3, -0.2, -1.0),
                },
                color: Rgb::new(0.4, 0.5, 1.0),
                intensity: 0.5,
                attenuation: shadelab_core::NO_ATTENUATION,
            },
        ],
        material: Material {
            ka: Rgb::new(0.9, 0.4, 0.3),
            kd: Rgb::new(0.8, 0.45, 0.3),
            ks: Rgb::new(0.6, 0.6, 0.6),
            shininess: 12.0,
        },
    }
}

fn options(interpolation: Interpolation, polygons: Polygons) -> RenderOptions {
    RenderOptions {
        width: 72,
        height: 60,
        shading: Shading::Phong,
        background: Rgb8::new(0, 255, 0),
        cull_backfaces: true,
        gouraud_specular: false,
        interpolation,
        rasterizer: Rasterizer::Scanline,
        polygons,
        specular: Specular::Phong,
        fixed_point_bits: None,
        palette: None,
    }
}

fn close(a: f64, b: f64, tolerance: f64) -> bool {
    (a - b).abs() <= tolerance * (1.0 + a.abs().max(b.abs()))
}

/// Checks every claim of the inspection of pixel (x, y) against the render.
fn check_pixel(
    scene: &Scene,
    options: &RenderOptions,
    images: &[shadelab_core::Image],
    x: u32,
    y: u32,
) -> bool {
    let insp = inspect(scene, options, x, y, &Shading::ALL).unwrap();
    let lighting = lighting_of(scene, options);
    let mut drawn = false;
    for (m, image) in insp.methods.iter().zip(images) {
        let what = format!(
            "{:?} {:?} {:?} pixel ({x}, {y})",
            m.shading, options.interpolation, options.polygons
        );
        assert_eq!(m.color, image.pixel(x, y), "{what}: colour");
        let Some(f) = &m.fragment else {
            assert_eq!(image.pixel(x, y), options.background, "{what}");
            continue;
        };
        drawn = true;
        assert_eq!(Rgb8::from_rgb(f.lit), f.color, "{what}: lit → colour");
        let span = m.span.as_ref().expect("traced");
        assert_eq!(span.row, y);
        assert!(
            span.pixels.contains(&x),
            "{what}: the span covers the pixel"
        );
        assert!((0.0..1.0).contains(&span.u), "{what}: u = {}", span.u);
        assert!(
            span.p.x <= f64::from(x) + 0.5 && f64::from(x) + 0.5 <= span.q.x,
            "{what}: P ≤ O ≤ Q"
        );
        for e in [&span.p, &span.q] {
            assert!((0.0..=1.0).contains(&e.s), "{what}: s = {}", e.s);
            for (a, b) in e.formula.iter().zip(&e.stepped) {
                assert!(
                    close(*a, *b, 1e-9),
                    "{what}: edge formula {a} vs stepped {b}"
                );
            }
        }
        for (k, (a, b)) in span.formula.iter().zip(&f.attrs).enumerate() {
            assert!(
                close(*a, f64::from(*b), 2e-6),
                "{what}: attribute {k} formula {a} vs rendered {b}"
            );
        }
        // The polygon's walked vertices are the mesh corners, unclipped here.
        assert!(!m.clipped, "{what}");
        for v in &m.walked {
            let c = v.corner.as_ref().expect("every vertex is a corner");
            assert!(m.polygon.contains(&c.vertex));
        }
        match m.shading {
            Shading::Flat => {
                let terms = m.lighting.as_ref().unwrap();
                assert_eq!(terms.total, f.lit, "{what}: flat light at the centroid");
                assert_eq!(
                    terms.total,
                    lighting.eval(m.point.unwrap(), m.normal.unwrap(), Terms::Full)
                );
            }
            Shading::Gouraud => {
                assert_eq!(
                    Rgb::from_array([f.attrs[0], f.attrs[1], f.attrs[2]]),
                    f.lit,
                    "{what}"
                );
                for v in &m.walked {
                    let terms = v.corner.as_ref().unwrap().lighting.as_ref().unwrap();
                    assert_eq!(
                        terms.total.clamped().to_array().to_vec(),
                        v.attrs,
                        "{what}: vertex intensity"
                    );
                }
            }
            Shading::Phong => {
                let terms = m.lighting.as_ref().unwrap();
                assert_eq!(terms.total, f.lit, "{what}: Phong light at O");
                let raw = m.raw_normal.unwrap();
                assert_eq!(raw.to_array().to_vec(), f.attrs[..3].to_vec());
                assert_eq!(m.normal.unwrap(), raw.normalize());
            }
        }
    }
    drawn
}

fn check_scene(scene: &Scene, step: u32) {
    for interpolation in [Interpolation::Perspective, Interpolation::Screen] {
        for polygons in [Polygons::Whole, Polygons::Fans] {
            let options = options(interpolation, polygons);
            let images: Vec<_> = Shading::ALL
                .iter()
                .map(|&shading| {
                    render(scene, &RenderOptions { shading, ..options })
                        .unwrap()
                        .0
                })
                .collect();
            let mut drawn = 0;
            for y in (1..options.height).step_by(step as usize) {
                for x in (2..options.width).step_by(step as usize) {
                    drawn += usize::from(check_pixel(scene, &options, &images, x, y));
                }
            }
            assert!(
                drawn > 20,
                "{interpolation:?} {polygons:?}: only {drawn} pixels drawn"
            );
        }
    }
}

#[test]
fn inspector_matches_the_render_on_a_sphere_of_quads() {
    check_scene(&scene("sphere", 8, Vec3::new(0.8, 1.1, 3.6)), 5);
}

#[test]
fn inspector_matches_the_render_on_a_torus_seen_steeply() {
    check_scene(&scene("torus", 10, Vec3::new(0.5, 3.5, 3.0)), 6);
}

#[test]
fn fan_triangles_are_named_and_whole_quads_are_walked_whole() {
    let scene = scene("cube", 1, Vec3::new(1.5, 1.2, 3.8));
    let whole = inspect(
        &scene,
        &options(Interpolation::Screen, Polygons::Whole),
        36,
        30,
        &[Shading::Gouraud],
    )
    .unwrap();
    let m = &whole.methods[0];
    assert_eq!(m.walked.len(), 4, "a cube face is walked as a quad");
    assert_eq!(m.fan_triangle, None);
    let fans = inspect(
        &scene,
        &options(Interpolation::Screen, Polygons::Fans),
        36,
        30,
        &[Shading::Gouraud],
    )
    .unwrap();
    let m = &fans.methods[0];
    assert_eq!(m.walked.len(), 3);
    assert!(
        matches!(m.fan_triangle, Some(1 | 2)),
        "{:?}",
        m.fan_triangle
    );
}

#[test]
fn fixed_point_stepping_is_reported_and_still_what_was_drawn() {
    let scene = scene("sphere", 8, Vec3::new(0.8, 1.1, 3.6));
    let options = RenderOptions {
        fixed_point_bits: Some(3),
        ..options(Interpolation::Screen, Polygons::Whole)
    };
    let images: Vec<_> = Shading::ALL
        .iter()
        .map(|&shading| {
            render(&scene, &RenderOptions { shading, ..options })
                .unwrap()
                .0
        })
        .collect();
    let insp = inspect(&scene, &options, 40, 28, &Shading::ALL).unwrap();
    let g = &insp.methods[1];
    assert_eq!(g.color, images[1].pixel(40, 28));
    let span = g.span.as_ref().unwrap();
    assert_eq!(span.fraction_bits, Some(3));
    // Stepped values sit on the 1/8 grid at P and Q.
    for v in span.p.stepped.iter().chain(&span.q.stepped) {
        assert_eq!((v * 8.0).fract(), 0.0, "{v}");
    }
    let text = inspection_text(&insp, &Texts::new(Lang::En));
    assert!(text.contains("3 fraction bits"), "{text}");
}

#[test]
fn the_text_fills_in_the_formulas_in_every_language() {
    let scene = scene("sphere", 8, Vec3::new(0.8, 1.1, 3.6));
    let options = options(Interpolation::Screen, Polygons::Whole);
    let insp = inspect(&scene, &options, 36, 30, &Shading::ALL).unwrap();
    let g = &insp.methods[1];
    let u = format!("{:.4}", g.span.as_ref().unwrap().u);
    for lang in Lang::ALL {
        let texts = Texts::new(lang);
        let text = inspection_text(&insp, &texts);
        assert!(
            text.contains("I_O = (1 − u)·I_P + u·I_Q"),
            "{lang:?}:\n{text}"
        );
        assert!(text.contains(&u), "{lang:?}: u = {u}\n{text}");
        assert!(text.contains(texts.get("method.gouraud")), "{lang:?}");
        let colour = g.color.0;
        assert!(
            text.contains(&format!("({}, {}, {})", colour[0], colour[1], colour[2])),
            "{lang:?}"
        );
        // No id was left unfilled.
        assert!(!text.contains("inspect."), "{lang:?}:\n{text}");
        assert!(!text.contains('{'), "{lang:?}:\n{text}");
    }
    let background = inspect(&scene, &options, 0, 0, &[Shading::Phong]).unwrap();
    assert!(background.methods[0].fragment.is_none());
    let text = inspection_text(&background, &Texts::new(Lang::En));
    assert!(text.contains("background colour (0, 255, 0)"), "{text}");
}

#[test]
fn blinn_phong_is_explained_with_the_halfway_vector() {
    let scene = scene("sphere", 10, Vec3::new(0.8, 1.1, 3.6));
    let options = RenderOptions {
        specular: Specular::BlinnPhong,
        gouraud_specular: true,
        ..options(Interpolation::Perspective, Polygons::Fans)
    };
    let images: Vec<_> = Shading::ALL
        .iter()
        .map(|&shading| {
            render(&scene, &RenderOptions { shading, ..options })
                .unwrap()
                .0
        })
        .collect();
    let mut drawn = 0;
    for (x, y) in [(30, 20), (36, 30), (44, 26), (40, 40), (28, 34)] {
        drawn += usize::from(check_pixel(&scene, &options, &images, x, y));
    }
    assert!(drawn >= 4);
    let text = inspection_text(
        &inspect(&scene, &options, 36, 30, &Shading::ALL).unwrap(),
        &Texts::new(Lang::En),
    );
    assert!(
        text.contains("h = normalize(l + v)") && !text.contains("r·v = "),
        "{text}"
    );
}

/// A floor running under the camera is clipped by the near plane: the
/// vertices clipping made are marked, and the colour is still the pixel's.
#[test]
fn clipped_polygons_are_explained_too() {
    let mesh = shadelab_core::Mesh::from_polygons(
        vec![
            Vec3::new(-10.0, -1.0, 10.0),
            Vec3::new(10.0, -1.0, 10.0),
            Vec3::new(10.0, -1.0, -10.0),
            Vec3::new(-10.0, -1.0, -10.0),
        ],
        [[0u32, 1, 2, 3]],
    )
    .unwrap();
    let normals = vertex_normals(&mesh, NormalWeighting::Uniform, None);
    let mut floor = scene("sphere", 8, Vec3::new(0.0, 0.0, 0.0));
    floor.mesh = mesh;
    floor.normals = normals;
    floor.camera.eye = Vec3::new(0.0, 0.0, 2.0);
    floor.camera.target = Vec3::new(0.0, -0.5, -3.0);
    for polygons in [Polygons::Whole, Polygons::Fans] {
        let options = options(Interpolation::Perspective, polygons);
        let images: Vec<_> = Shading::ALL
            .iter()
            .map(|&shading| {
                render(&floor, &RenderOptions { shading, ..options })
                    .unwrap()
                    .0
            })
            .collect();
        let insp = inspect(&floor, &options, 36, 55, &Shading::ALL).unwrap();
        for (m, image) in insp.methods.iter().zip(&images) {
            assert_eq!(m.color, image.pixel(36, 55), "{polygons:?} {:?}", m.shading);
            assert!(m.fragment.is_some());
            assert!(
                m.clipped,
                "{polygons:?} {:?}: the floor is clipped",
                m.shading
            );
            assert!(m.walked.iter().any(|v| v.corner.is_none()));
        }
        let text = inspection_text(&insp, &Texts::new(Lang::En));
        assert!(text.contains("made by clipping"), "{text}");
    }
}

#[test]
fn palette_mode_explains_the_entry() {
    let scene = scene("sphere", 8, Vec3::new(0.8, 1.1, 3.6));
    let options = RenderOptions {
        palette: Some(shadelab_core::Palette {
            shades: 6,
            offset: 40,
        }),
        ..options(Interpolation::Screen, Polygons::Whole)
    };
    let images: Vec<_> = Shading::ALL
        .iter()
        .map(|&shading| {
            render(&scene, &RenderOptions { shading, ..options })
                .unwrap()
                .0
        })
        .collect();
    let insp = inspect(&scene, &options, 36, 30, &Shading::ALL).unwrap();
    for (m, image) in insp.methods.iter().zip(&images) {
        let p = m.palette.expect("a palette shade");
        assert_eq!(m.color, image.pixel(36, 30));
        assert_eq!(p.color, m.color);
        assert_eq!(p.index, 40 + p.shade);
        assert!(p.shade < 6);
    }
    let text = inspection_text(&insp, &Texts::new(Lang::En));
    assert!(text.contains("palette entry 4"), "{text}");
}
