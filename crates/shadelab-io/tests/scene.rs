//! Scene files: the full format, defaults, unknown keys, wrong types, and
//! out-of-range values reported under the right key.

mod common;

use std::path::Path;

use common::*;
use glam::Vec3;
use shadelab_core::{
    Interpolation, LightKind, Polygons, Rasterizer, RenderOptions, Rgb, Rgb8, Shading, Specular,
    BUILTIN_MODELS,
};
use shadelab_io::{LightKindName, NormalsChoice, SceneError, SceneFile};

const FULL: &str = r#"
[model]
source = "teapot"
normals = "auto"
[camera]
eye = [0.0, 0.5, 3.0]
target = [0.0, 0.0, 0.0]
up = [0.0, 1.0, 0.0]
fov_y = 45.0
near = 0.1
far = 100.0
[ambient]
color = [255, 255, 255]
intensity = 0.2
[[lights]]
kind = "point"
position = [2.0, 2.0, 3.0]
color = [255, 255, 255]
intensity = 1.0
[[lights]]
kind = "directional"
direction = [0.0, -1.0, 0.0]
[material]
ka = [255, 60, 60]
kd = [255, 60, 60]
ks = [255, 255, 255]
shininess = 32.0
[render]
width = 800
height = 600
shading = "phong"
background = [0, 0, 0]
cull_backfaces = true
gouraud_specular = false
interpolation = "perspective"
"#;

/// Asserts that `text` parses but fails to resolve with a value error on exactly `key`.
fn assert_value_error(text: &str, key: &str) {
    match resolve(text) {
        Err(SceneError::Value { key: k, message }) => {
            assert_eq!(k, key, "wrong key (message: {message})");
            assert!(!message.is_empty());
            let shown = SceneError::Value {
                key: k.clone(),
                message: message.clone(),
            }
            .to_string();
            assert!(shown.starts_with(&format!("{key}: ")), "{shown}");
        }
        Err(other) => panic!("expected a value error on {key}, got {other:?}"),
        Ok(_) => panic!("expected a value error on {key}, but the scene resolved"),
    }
}

/// Asserts that parsing fails and the message contains every needle.
fn assert_parse_error(text: &str, needles: &[&str]) {
    match SceneFile::parse(text, "bad.toml") {
        Err(e @ SceneError::Parse { .. }) => {
            let shown = e.to_string();
            assert!(shown.starts_with("bad.toml: "), "{shown}");
            for needle in needles {
                assert!(
                    shown.contains(needle),
                    "{shown:?} should mention {needle:?}"
                );
            }
        }
        Err(other) => panic!("expected a parse error, got {other:?}"),
        Ok(file) => panic!("expected a parse error, got {file:?}"),
    }
}

fn close(a: Rgb, b: Rgb) -> bool {
    (a.r - b.r).abs() < 1e-6 && (a.g - b.g).abs() < 1e-6 && (a.b - b.b).abs() < 1e-6
}

// ---- the full example and the defaults ----

#[test]
fn full_example_parses_as_written() {
    let file = parse(FULL);
    assert_eq!(file.model.source.as_deref(), Some("teapot"));
    assert_eq!(file.model.normals, Some(NormalsChoice::Auto));
    let camera = file.camera.as_ref().expect("camera");
    assert_eq!(camera.eye, [0.0, 0.5, 3.0]);
    assert_eq!(camera.target, Some([0.0, 0.0, 0.0]));
    assert_eq!(camera.up, Some([0.0, 1.0, 0.0]));
    assert_eq!(
        (camera.fov_y, camera.near, camera.far),
        (Some(45.0), Some(0.1), Some(100.0))
    );
    assert_eq!(file.ambient.color, Some([255, 255, 255]));
    assert_eq!(file.ambient.intensity, Some(0.2));
    let lights = file.lights.as_ref().expect("lights");
    assert_eq!(lights.len(), 2);
    assert_eq!(lights[0].kind, LightKindName::Point);
    assert_eq!(lights[0].position, Some([2.0, 2.0, 3.0]));
    assert_eq!(lights[1].kind, LightKindName::Directional);
    assert_eq!(lights[1].direction, Some([0.0, -1.0, 0.0]));
    assert_eq!(lights[1].intensity, None);
    assert_eq!(file.material.ks, Some([255, 255, 255]));
    assert_eq!(file.material.shininess, Some(32.0));
    assert_eq!(file.render.width, Some(800));
    assert_eq!(file.render.shading, Some(Shading::Phong));
    assert_eq!(file.render.interpolation, Some(Interpolation::Perspective));
    assert_eq!(file.render.cull_backfaces, Some(true));
    assert_eq!(file.render.gouraud_specular, Some(false));
}

#[test]
fn full_example_resolves() {
    let (scene, options) = resolved(FULL);
    assert_eq!(
        options,
        RenderOptions {
            width: 800,
            height: 600,
            shading: Shading::Phong,
            background: Rgb8::new(0, 0, 0),
            cull_backfaces: true,
            gouraud_specular: false,
            interpolation: Interpolation::Perspective,
            rasterizer: Rasterizer::Tiled,
            polygons: Polygons::Fans,
            specular: Specular::Phong,
            fixed_point_bits: None,
            palette: None,
        }
    );
    assert_eq!(scene.camera.eye, Vec3::new(0.0, 0.5, 3.0));
    assert_eq!(scene.camera.target, Vec3::ZERO);
    assert_eq!(scene.camera.fov_y_degrees, 45.0);
    assert_eq!((scene.camera.near, scene.camera.far), (0.1, 100.0));
    assert_eq!(scene.lights.len(), 2);
    assert_eq!(
        scene.lights[0].kind,
        LightKind::Point {
            position: Vec3::new(2.0, 2.0, 3.0)
        }
    );
    assert_eq!(
        scene.lights[1].kind,
        LightKind::Directional {
            direction: Vec3::new(0.0, -1.0, 0.0)
        }
    );
    assert_eq!(scene.lights[1].color, Rgb::WHITE);
    assert_eq!(scene.lights[1].intensity, 1.0);
    assert!(close(scene.ambient, Rgb::splat(0.2)));
    assert_eq!(scene.material.ka, Rgb8::new(255, 60, 60).to_rgb());
    assert_eq!(scene.material.shininess, 32.0);
    // One normal per corner of the teapot.
    assert_eq!(scene.normals.corner().len(), scene.mesh.corners().len());
    assert!(scene.mesh.polygon_count() > 100);
}

#[test]
fn other_enum_values_resolve() {
    let (scene, options) = resolved(
        r#"
[model]
source = "cylinder"
normals = "angle"
crease_angle = 30
detail = 12
[render]
shading = "gouraud"
interpolation = "screen"
cull_backfaces = false
gouraud_specular = true
background = [10, 20, 30]
width = 64
height = 32
"#,
    );
    assert_eq!(options.shading, Shading::Gouraud);
    assert_eq!(options.interpolation, Interpolation::Screen);
    assert!(!options.cull_backfaces);
    assert!(options.gouraud_specular);
    assert_eq!(options.background, Rgb8::new(10, 20, 30));
    assert_eq!((options.width, options.height), (64, 32));
    assert_eq!(scene.normals.corner().len(), scene.mesh.corners().len());
    for shading in ["flat", "phong"] {
        let (_, options) = resolved(&format!("[render]\nshading = \"{shading}\"\n"));
        assert_eq!(options.shading.name(), shading);
    }
    for normals in ["uniform", "area", "angle", "auto"] {
        let (scene, _) = resolved(&format!(
            "[model]\nsource = \"cube\"\nnormals = \"{normals}\"\n"
        ));
        assert_eq!(scene.normals.corner().len(), scene.mesh.corners().len());
    }
}

#[test]
fn empty_file_gets_the_defaults() {
    let file = parse("");
    assert_eq!(file, SceneFile::default());
    let (scene, options) = file.resolve(Path::new(".")).expect("defaults resolve");
    assert_eq!((options.width, options.height), (800, 600));
    assert_eq!(options.shading, Shading::Phong);
    assert_eq!(options.background, Rgb8::new(0, 0, 0));
    assert!(options.cull_backfaces);
    assert!(!options.gouraud_specular);
    assert_eq!(options.interpolation, Interpolation::Perspective);
    assert_eq!(options, RenderOptions::default());

    assert_eq!(scene.lights.len(), 1);
    let light = scene.lights[0];
    assert_eq!(
        light.kind,
        LightKind::Point {
            position: Vec3::new(2.0, 2.0, 3.0)
        }
    );
    assert_eq!(light.color, Rgb::WHITE);
    assert_eq!(light.intensity, 1.0);

    // Ambient: white at 0.2.
    assert!(close(scene.ambient, Rgb::splat(0.2)), "{:?}", scene.ambient);

    let red = Rgb::new(200.0 / 255.0, 60.0 / 255.0, 60.0 / 255.0);
    assert!(close(scene.material.ka, red), "{:?}", scene.material.ka);
    assert!(close(scene.material.kd, red), "{:?}", scene.material.kd);
    assert_eq!(scene.material.ks, Rgb::WHITE);
    assert_eq!(scene.material.shininess, 32.0);

    // The default model is the teapot, normalised and framed.
    let teapot = shadelab_core::builtin_model("teapot", None).unwrap();
    assert_eq!(scene.mesh.polygon_count(), teapot.polygon_count());
    let (centre, radius) = centre_and_radius(&scene.mesh);
    assert!(centre.length() < 1e-4, "{centre}");
    assert!((radius - 1.0).abs() < 1e-4, "{radius}");
    assert_eq!(scene.camera.target, Vec3::ZERO);
    scene
        .camera
        .validate()
        .expect("the framing camera is valid");
}

#[test]
fn sections_with_only_some_keys_keep_the_other_defaults() {
    let (scene, options) = resolved(
        "[render]\nwidth = 100\n[material]\nshininess = 5\n[ambient]\nintensity = 0.5\n[camera]\neye = [0, 0, 5]\n",
    );
    assert_eq!((options.width, options.height), (100, 600));
    assert_eq!(scene.material.shininess, 5.0);
    assert_eq!(scene.material.ks, Rgb::WHITE);
    assert!(close(scene.ambient, Rgb::splat(0.5)));
    assert_eq!(scene.camera.target, Vec3::ZERO);
    assert_eq!(scene.camera.up, Vec3::Y);
    assert_eq!(scene.camera.fov_y_degrees, 45.0);
    assert_eq!((scene.camera.near, scene.camera.far), (0.1, 100.0));
}

#[test]
fn light_defaults_and_empty_light_list() {
    let (scene, _) = resolved("[[lights]]\nkind = \"directional\"\ndirection = [0, 0, -2]\n");
    assert_eq!(scene.lights.len(), 1);
    assert_eq!(scene.lights[0].color, Rgb::WHITE);
    assert_eq!(scene.lights[0].intensity, 1.0);
    let (scene, _) = resolved("lights = []\n");
    assert!(scene.lights.is_empty());
    let (scene, _) = resolved(
        "[[lights]]\nkind = \"point\"\nposition = [1, 2, 3]\ncolor = [255, 0, 0]\nintensity = 0.5\n",
    );
    assert_eq!(scene.lights[0].color, Rgb::new(1.0, 0.0, 0.0));
    assert_eq!(scene.lights[0].intensity, 0.5);
}

// ---- unknown keys and wrong types ----

#[test]
fn unknown_keys_are_errors_naming_the_key() {
    assert_parse_error("colour_space = \"srgb\"\n", &["colour_space"]);
    assert_parse_error("[model]\nsourse = \"teapot\"\n", &["sourse"]);
    assert_parse_error("[camera]\neye = [0, 0, 3]\nfocus = 2.0\n", &["focus"]);
    assert_parse_error("[ambient]\ncolour = [1, 2, 3]\n", &["colour"]);
    assert_parse_error(
        "[[lights]]\nkind = \"point\"\nposition = [1, 1, 1]\nradius = 2\n",
        &["radius"],
    );
    assert_parse_error("[material]\nspecular = [1, 2, 3]\n", &["specular"]);
    assert_parse_error("[render]\nantialias = true\n", &["antialias"]);
    assert_parse_error("[lighting]\nintensity = 1\n", &["lighting"]);
}

#[test]
fn wrong_types_are_errors() {
    assert_parse_error("[render]\nwidth = \"800\"\n", &["width"]);
    assert_parse_error("[render]\nwidth = 800.5\n", &["width"]);
    assert_parse_error("[render]\nwidth = -5\n", &["width"]);
    assert_parse_error("[render]\ncull_backfaces = 1\n", &["cull_backfaces"]);
    assert_parse_error("[render]\nshading = \"glossy\"\n", &["glossy"]);
    assert_parse_error("[render]\ninterpolation = \"linear\"\n", &["linear"]);
    assert_parse_error("[material]\nka = [255, 60]\n", &["ka"]);
    assert_parse_error("[material]\nka = \"red\"\n", &["ka"]);
    assert_parse_error("[material]\nshininess = \"high\"\n", &["shininess"]);
    assert_parse_error("[ambient]\nintensity = [0.2]\n", &["intensity"]);
    assert_parse_error("[[lights]]\nkind = \"spot\"\n", &["spot"]);
    assert_parse_error("[[lights]]\nposition = [1, 2, 3]\n", &["kind"]);
    assert_parse_error("[model]\nnormals = \"smooth\"\n", &["smooth"]);
    assert_parse_error("[model]\nsource = 3\n", &["source"]);
    assert_parse_error("[camera]\neye = [0, 0]\n", &["eye"]);
    assert_parse_error("[camera]\ntarget = [0, 0, 0]\n", &["eye"]);
    assert_parse_error("model = \"teapot\"\n", &["model"]);
}

#[test]
fn malformed_toml_is_a_parse_error_with_a_line() {
    assert_parse_error("[render\nwidth = 10\n", &["line 1"]);
    assert_parse_error("[render]\nwidth = 10\nheight = \n", &["line 3"]);
}

#[test]
fn load_reports_a_missing_file() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("absent.toml");
    let err = SceneFile::load(&path).expect_err("missing");
    assert!(matches!(err, SceneError::Io { .. }), "{err:?}");
    assert!(
        err.to_string().contains(&path.display().to_string()),
        "{err}"
    );

    let path = write(dir.path(), "bad.toml", "[render]\nwidth = \"wide\"\n");
    let err = SceneFile::load(&path).expect_err("bad type");
    assert!(matches!(err, SceneError::Parse { .. }), "{err:?}");
    assert!(
        err.to_string().starts_with(&path.display().to_string()),
        "{err}"
    );
}

// ---- values out of range ----

#[test]
fn colour_channels_out_of_range() {
    assert_value_error("[material]\nka = [256, 0, 0]\n", "material.ka");
    assert_value_error("[material]\nka = [0, -1, 0]\n", "material.ka");
    assert_value_error("[material]\nkd = [0, 0, 300]\n", "material.kd");
    assert_value_error("[material]\nks = [-5, 0, 0]\n", "material.ks");
    assert_value_error("[ambient]\ncolor = [0, 0, 256]\n", "ambient.color");
    assert_value_error("[render]\nbackground = [0, 1000, 0]\n", "render.background");
    assert_value_error(
        "[[lights]]\nkind = \"point\"\nposition = [1, 1, 1]\ncolor = [0, 0, -1]\n",
        "lights[0].color",
    );
    // The edges of the range are fine.
    resolved("[material]\nka = [0, 255, 0]\n[render]\nwidth = 8\nheight = 8\n");
}

#[test]
fn negative_intensities_and_shininess() {
    assert_value_error("[ambient]\nintensity = -0.1\n", "ambient.intensity");
    assert_value_error("[ambient]\nintensity = nan\n", "ambient.intensity");
    assert_value_error("[material]\nshininess = -1.0\n", "material.shininess");
    assert_value_error("[material]\nshininess = inf\n", "material.shininess");
    assert_value_error("[material]\nshininess = 20000\n", "material.shininess");
    assert_value_error(
        "[[lights]]\nkind = \"point\"\nposition = [1, 1, 1]\nintensity = -2\n",
        "lights[0].intensity",
    );
    // Zero is allowed.
    let (scene, _) = resolved(
        "[ambient]\nintensity = 0\n[material]\nshininess = 0\n[render]\nwidth = 8\nheight = 8\n",
    );
    assert_eq!(scene.ambient, Rgb::BLACK);
    assert_eq!(scene.material.shininess, 0.0);
}

#[test]
fn image_size_out_of_range() {
    assert_value_error("[render]\nwidth = 0\n", "render.width");
    assert_value_error("[render]\nwidth = 20000\n", "render.width");
    assert_value_error("[render]\nheight = 0\n", "render.height");
    assert_value_error("[render]\nheight = 20000\n", "render.height");
    // Each side within range, but too many pixels in all.
    assert_value_error("[render]\nwidth = 16384\nheight = 16384\n", "render");
}

#[test]
fn light_position_and_direction_rules() {
    // The second light is a point light without a position.
    assert_value_error(
        "[[lights]]\nkind = \"directional\"\ndirection = [0, -1, 0]\n[[lights]]\nkind = \"point\"\n",
        "lights[1].position",
    );
    assert_value_error(
        "[[lights]]\nkind = \"point\"\nposition = [1, 1, 1]\ndirection = [0, -1, 0]\n",
        "lights[0].position",
    );
    assert_value_error(
        "[[lights]]\nkind = \"directional\"\ndirection = [0.0, 0.0, 0.0]\n",
        "lights[0].direction",
    );
    assert_value_error(
        "[[lights]]\nkind = \"directional\"\n",
        "lights[0].direction",
    );
    assert_value_error(
        "[[lights]]\nkind = \"point\"\nposition = [1, 1, 1]\n[[lights]]\nkind = \"point\"\nposition = [nan, 0, 0]\n",
        "lights[1].position",
    );
    assert_value_error(
        "[[lights]]\nkind = \"directional\"\ndirection = [0, inf, 0]\n",
        "lights[0].direction",
    );
}

#[test]
fn model_values_out_of_range() {
    assert_value_error("[model]\ncrease_angle = 200\n", "model.crease_angle");
    assert_value_error("[model]\ncrease_angle = -1\n", "model.crease_angle");
    assert_value_error("[model]\nsource = \"sphere\"\ndetail = 1\n", "model.detail");
    assert_value_error(
        "[model]\nsource = \"sphere\"\ndetail = 100000\n",
        "model.detail",
    );
    assert_value_error(
        "[model]\nsource = \"icosphere\"\ndetail = 8\n",
        "model.detail",
    );
    // Each built-in accepts its whole documented range.
    for info in BUILTIN_MODELS {
        let text = format!(
            "[model]\nsource = \"{}\"\ndetail = {}\n",
            info.name, info.detail_range.0
        );
        resolved(&text);
    }
}

#[test]
fn file_normals_requested_for_a_builtin_without_them() {
    assert_value_error(
        "[model]\nsource = \"sphere\"\nnormals = \"file\"\n",
        "model.normals",
    );
}

#[test]
fn camera_errors_are_reported_under_camera() {
    assert_value_error("[camera]\neye = [1, 2, 3]\ntarget = [1, 2, 3]\n", "camera");
    assert_value_error("[camera]\neye = [0, 0, 3]\nfov_y = 0\n", "camera.fov_y");
    assert_value_error("[camera]\neye = [0, 0, 3]\nfov_y = 180\n", "camera.fov_y");
    assert_value_error("[camera]\neye = [0, 0, 3]\nnear = 5\nfar = 5\n", "camera");
    assert_value_error("[camera]\neye = [0, 0, 3]\nnear = 10\nfar = 5\n", "camera");
    assert_value_error("[camera]\neye = [0, 0, 3]\nnear = 0\n", "camera.near");
    assert_value_error("[camera]\neye = [0, 0, 3]\nup = [0, 0, 1]\n", "camera");
    assert_value_error("[camera]\neye = [0, 0, nan]\n", "camera.eye");
}

#[test]
fn yaw_and_pitch_must_be_finite() {
    assert_value_error("[render]\nyaw = nan\n", "render.yaw");
    assert_value_error("[render]\npitch = inf\n", "render.pitch");
    let (plain, _) = resolved("[render]\nwidth = 8\nheight = 8\n");
    let (turned, _) = resolved("[render]\nwidth = 8\nheight = 8\nyaw = 90\n");
    assert_ne!(plain.camera.eye, turned.camera.eye);
    // Orbiting keeps the distance to the target.
    let d0 = (plain.camera.eye - plain.camera.target).length();
    let d1 = (turned.camera.eye - turned.camera.target).length();
    assert!((d0 - d1).abs() < 1e-4);
}
