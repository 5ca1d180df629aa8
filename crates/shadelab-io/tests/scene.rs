//! Scene files: the full format, defaults, unknown keys, wrong types, and
//! out-of-range values reported under the right key.

use std::path::{Path, PathBuf};

use glam::Vec3;
use shadelab_core::{
    Interpolation, LightKind, Mesh, Polygons, Rasterizer, RenderOptions, Rgb, Rgb8, Scene, Shading,
    Specular, BUILTIN_MODELS,
};
use shadelab_io::{load_obj, LightKindName, NormalsChoice, SceneError, SceneFile};

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

/// A small tetrahedron away from the origin, with no normals.
const TETRA: &str = "\
v 10 0 0
v 12 0 0
v 10 2 0
v 10 0 2
f 1 3 2
f 1 2 4
f 1 4 3
f 2 3 4
";

fn parse(text: &str) -> SceneFile {
    SceneFile::parse(text, "test.toml").unwrap_or_else(|e| panic!("should parse: {e}"))
}

fn resolve(text: &str) -> Result<(Scene, RenderOptions), SceneError> {
    parse(text).resolve(Path::new("."))
}

fn resolved(text: &str) -> (Scene, RenderOptions) {
    resolve(text).unwrap_or_else(|e| panic!("should resolve: {e}"))
}

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

/// Centre of the bounding box and the distance of the farthest vertex from it.
fn centre_and_radius(mesh: &Mesh) -> (Vec3, f32) {
    let (lo, hi) = mesh.bounds();
    let centre = (lo + hi) * 0.5;
    let radius = mesh
        .corners()
        .iter()
        .map(|&i| (mesh.positions()[i as usize] - centre).length())
        .fold(0.0f32, f32::max);
    (centre, radius)
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    if let Some(parent) = path.parent() {
        std::fs::create_dir_all(parent).unwrap();
    }
    std::fs::write(&path, text).unwrap();
    path
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
    assert_eq!(scene.normals.corner.len(), scene.mesh.corners().len());
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
    assert_eq!(scene.normals.corner.len(), scene.mesh.corners().len());
    for shading in ["flat", "phong"] {
        let (_, options) = resolved(&format!("[render]\nshading = \"{shading}\"\n"));
        assert_eq!(options.shading.name(), shading);
    }
    for normals in ["uniform", "area", "angle", "auto"] {
        let (scene, _) = resolved(&format!(
            "[model]\nsource = \"cube\"\nnormals = \"{normals}\"\n"
        ));
        assert_eq!(scene.normals.corner.len(), scene.mesh.corners().len());
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

// ---- models from files ----

#[test]
fn relative_obj_path_is_resolved_against_the_scene_directory() {
    let dir = tempfile::tempdir().unwrap();
    let obj = write(dir.path(), "scenes/meshes/tetra.obj", TETRA);
    let scene_path = write(
        dir.path(),
        "scenes/tetra.toml",
        "[model]\nsource = \"meshes/tetra.obj\"\n[render]\nwidth = 8\nheight = 8\n",
    );
    let file = SceneFile::load(&scene_path).unwrap();
    let base = scene_path.parent().unwrap();
    let (scene, _) = file
        .resolve(base)
        .expect("resolved from the scene's directory");
    let expected = load_obj(&obj).unwrap();
    assert_eq!(scene.mesh.polygon_count(), expected.polygon_count());
    assert_eq!(scene.mesh.corners(), expected.corners());

    // From another directory the same relative path does not exist.
    let err = file.resolve(dir.path()).expect_err("wrong base directory");
    assert!(
        matches!(err, SceneError::Model(shadelab_io::LoadError::Io { .. })),
        "{err:?}"
    );
    assert!(err.to_string().contains("tetra.obj"), "{err}");

    // An absolute path ignores the base directory.
    let text = format!(
        "[model]\nsource = {:?}\n[render]\nwidth = 8\nheight = 8\n",
        obj.display().to_string()
    );
    let (scene, _) = parse(&text).resolve(Path::new("/nonexistent")).unwrap();
    assert_eq!(scene.mesh.polygon_count(), 4);
}

#[test]
fn unknown_model_name_lists_the_builtins() {
    match resolve("[model]\nsource = \"dodecahedron\"\n") {
        Err(SceneError::Value { key, message }) => {
            assert_eq!(key, "model.source");
            assert!(message.contains("dodecahedron"), "{message}");
            for info in BUILTIN_MODELS {
                assert!(message.contains(info.name), "{message} lacks {}", info.name);
            }
        }
        other => panic!("expected model.source error, got {other:?}"),
    }
}

#[test]
fn missing_obj_file_is_a_model_error() {
    let dir = tempfile::tempdir().unwrap();
    let err = parse("[model]\nsource = \"absent.obj\"\n")
        .resolve(dir.path())
        .expect_err("missing");
    assert!(matches!(err, SceneError::Model(_)), "{err:?}");
    assert!(err.to_string().contains("absent.obj"), "{err}");
}

#[test]
fn obj_errors_pass_through_with_their_line() {
    let dir = tempfile::tempdir().unwrap();
    write(
        dir.path(),
        "bad.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n",
    );
    let err = parse("[model]\nsource = \"bad.obj\"\n")
        .resolve(dir.path())
        .expect_err("bad index");
    assert!(
        matches!(
            err,
            SceneError::Model(shadelab_io::LoadError::Syntax { line: 4, .. })
        ),
        "{err:?}"
    );
    assert!(err.to_string().contains("bad.obj:4:"), "{err}");
}

#[test]
fn detail_is_rejected_for_a_file() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "tetra.obj", TETRA);
    let err = parse("[model]\nsource = \"tetra.obj\"\ndetail = 3\n")
        .resolve(dir.path())
        .expect_err("detail for a file");
    assert!(
        matches!(&err, SceneError::Value { key, .. } if key == "model.detail"),
        "{err:?}"
    );
}

#[test]
fn normals_file_for_an_obj() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "plain.obj", TETRA);
    write(
        dir.path(),
        "normals.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n",
    );
    let err = parse("[model]\nsource = \"plain.obj\"\nnormals = \"file\"\n")
        .resolve(dir.path())
        .expect_err("no normals in the file");
    assert!(
        matches!(&err, SceneError::Value { key, .. } if key == "model.normals"),
        "{err:?}"
    );
    for choice in ["file", "auto"] {
        let text = format!(
            "[model]\nsource = \"normals.obj\"\nnormals = \"{choice}\"\n[render]\nwidth = 8\nheight = 8\n"
        );
        let (scene, _) = parse(&text).resolve(dir.path()).expect("file normals");
        let per_corner: Vec<Vec3> = scene
            .normals
            .corner
            .iter()
            .map(|&i| scene.normals.normals[i as usize])
            .collect();
        assert_eq!(per_corner, vec![Vec3::Z; 3], "normals = {choice}");
    }
}

#[test]
fn with_a_camera_the_mesh_is_used_as_written() {
    let dir = tempfile::tempdir().unwrap();
    let obj = write(dir.path(), "tetra.obj", TETRA);
    let text = "[model]\nsource = \"tetra.obj\"\n[camera]\neye = [11, 1, 10]\ntarget = [11, 0.5, 0.5]\n[render]\nwidth = 8\nheight = 8\n";
    let (scene, _) = parse(text).resolve(dir.path()).unwrap();
    let original = load_obj(&obj).unwrap();
    assert_eq!(scene.mesh.positions(), original.positions());
    assert_eq!(scene.mesh.corners(), original.corners());
    assert_eq!(scene.camera.eye, Vec3::new(11.0, 1.0, 10.0));
}

#[test]
fn without_a_camera_the_mesh_is_normalised() {
    let dir = tempfile::tempdir().unwrap();
    let obj = write(dir.path(), "tetra.obj", TETRA);
    let text = "[model]\nsource = \"tetra.obj\"\n[render]\nwidth = 8\nheight = 8\n";
    let (scene, _) = parse(text).resolve(dir.path()).unwrap();
    let original = load_obj(&obj).unwrap();
    assert_ne!(scene.mesh.positions(), original.positions());
    assert_eq!(scene.mesh.corners(), original.corners());
    let (centre, radius) = centre_and_radius(&scene.mesh);
    assert!(centre.length() < 1e-5, "bbox centre {centre}");
    assert!((radius - 1.0).abs() < 1e-5, "radius {radius}");
    // Normalising is a translation and a uniform scale: shapes are kept.
    let (lo, hi) = original.bounds();
    let (c0, r0) = ((lo + hi) * 0.5, centre_and_radius(&original).1);
    for (p, q) in scene.mesh.positions().iter().zip(original.positions()) {
        assert!((*p - (*q - c0) / r0).length() < 1e-5);
    }
    // The framing camera looks at the origin from +z.
    assert_eq!(scene.camera.target, Vec3::ZERO);
    assert!(scene.camera.eye.z > 1.0);
}

#[test]
fn specular_term_by_name() {
    for (text, want) in [
        ("phong", Specular::Phong),
        ("blinn-phong", Specular::BlinnPhong),
    ] {
        let (_, options) = resolved(&format!("[render]\nspecular = \"{text}\"\n"));
        assert_eq!(options.specular, want);
    }
    let err = SceneFile::parse("[render]\nspecular = \"blinn\"\n", "s.toml").unwrap_err();
    assert!(err.to_string().contains("specular"), "{err}");
}

/// The default material does not clip outside the specular highlight: with
/// every built-in model, under the default camera and lights, by every
/// method, no channel reaches 255 once the specular term is off, and the
/// highlight alone reaches it when it is on (issue: a red that clipped over a
/// large area hid the methods' differences).
#[test]
fn the_default_material_clips_only_in_the_highlight() {
    for model in shadelab_core::BUILTIN_MODELS {
        for shading in ["flat", "gouraud", "phong"] {
            let base = format!(
                "[model]\nsource = \"{}\"\n[render]\nwidth = 96\nheight = 96\nshading = \"{shading}\"\n",
                model.name
            );
            let (scene, options) = resolved(&format!("{base}[material]\nks = [0, 0, 0]\n"));
            let image = shadelab_core::render(&scene, &options).unwrap().0;
            let brightest = image
                .pixels()
                .iter()
                .map(|p| p.0.into_iter().max().unwrap())
                .max()
                .unwrap();
            assert!(
                brightest < 255,
                "{} {shading}: a channel clips without the specular term",
                model.name
            );
            assert!(
                brightest > 100,
                "{} {shading}: the lit side is drawn ({brightest})",
                model.name
            );
        }
    }
    // With the default specular term, Phong's highlight does reach white on the sphere.
    let (scene, options) = resolved(
        "[model]\nsource = \"sphere\"\n[render]\nwidth = 96\nheight = 96\nshading = \"phong\"\n",
    );
    let image = shadelab_core::render(&scene, &options).unwrap().0;
    assert!(image.pixels().iter().any(|p| p.0[1] >= 250));
}
