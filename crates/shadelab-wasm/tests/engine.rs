//! The engine behind each viewer panel, run natively: it draws what
//! `shadelab render` draws for the same scene text, keeps the model between
//! frames without changing a pixel, keeps the previous file when a new one
//! is bad, and speaks the JSON protocol of its exports.

use std::path::Path;

use shadelab_core::{render, Image, BUILTIN_MODELS};
use shadelab_io::SceneFile;
use shadelab_wasm::{abi, Engine, MAX_FILE_BYTES};

const OCTAHEDRON: &str = "v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n\
f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6\n";

/// What `shadelab render` draws for `toml` (files relative to `dir`).
fn cli_image(toml: &str, dir: &Path) -> Image {
    let file = SceneFile::parse(toml, "scene").unwrap();
    let (scene, options) = file.resolve(dir).unwrap();
    render(&scene, &options).unwrap().0
}

fn engine_image(engine: &mut Engine, toml: &str) -> Image {
    engine.render(toml).unwrap();
    let image = engine.image().unwrap().clone();
    let rgba = engine.rgba();
    assert_eq!(rgba.len(), image.pixels().len() * 4);
    for (p, q) in image.pixels().iter().zip(rgba.chunks(4)) {
        assert_eq!([p.0[0], p.0[1], p.0[2], 255], q);
    }
    image
}

fn scene(model: &str, shading: &str, extra: &str) -> String {
    format!("[model]\n{model}\n[render]\nwidth = 96\nheight = 80\nshading = \"{shading}\"\n{extra}")
}

#[test]
fn panels_draw_what_the_command_line_draws() {
    let mut engine = Engine::new();
    for model in [
        "source = \"teapot\"",
        "source = \"cylinder\"\ndetail = 7",
        "source = \"torus\"\nnormals = \"angle\"\ncrease_angle = 20",
    ] {
        for shading in ["flat", "gouraud", "phong"] {
            for extra in ["", "yaw = 33\npitch = -12\nzoom = 1.7\nspecular = \"blinn-phong\"\n", "rasterizer = \"scanline\"\npolygons = \"whole\"\ninterpolation = \"screen\"\ncull_backfaces = false\ngouraud_specular = true\n"] {
                let toml = scene(model, shading, extra);
                assert_eq!(engine_image(&mut engine, &toml), cli_image(&toml, Path::new("")), "{toml}");
            }
        }
    }
}

#[test]
fn the_kept_model_changes_no_pixel() {
    let mut engine = Engine::new();
    let frames = [
        scene("source = \"sphere\"", "phong", ""),
        scene(
            "source = \"sphere\"",
            "phong",
            "yaw = 10\n[material]\nkd = [0, 255, 0]\n",
        ),
        scene("source = \"sphere\"\nnormals = \"area\"", "gouraud", ""),
        scene("source = \"sphere\"\ndetail = 5", "gouraud", "pitch = 40\n"),
        scene("source = \"cube\"", "flat", "[ambient]\nintensity = 0.7\n"),
        scene(
            "source = \"sphere\"",
            "phong",
            "[[lights]]\nkind = \"point\"\nposition = [-3.0, 1.0, 2.0]\n",
        ),
    ];
    for toml in frames.iter().chain(frames.iter().rev()) {
        assert_eq!(
            engine_image(&mut engine, toml),
            cli_image(toml, Path::new("")),
            "{toml}"
        );
    }
    // A camera in the scene means the mesh is not normalised: a new model.
    let with_camera = format!("{}[camera]\neye = [0.0, 0.0, 4.0]\n", frames[0]);
    assert_eq!(
        engine_image(&mut engine, &with_camera),
        cli_image(&with_camera, Path::new(""))
    );
}

#[test]
fn a_loaded_file_draws_as_the_same_file_on_disk() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("octahedron.obj"), OCTAHEDRON).unwrap();
    let mut engine = Engine::new();
    let summary = engine
        .load_file("octahedron.obj", OCTAHEDRON.as_bytes())
        .unwrap();
    assert_eq!(
        (
            summary.vertices,
            summary.polygons,
            summary.triangles,
            summary.has_normals
        ),
        (6, 8, 8, false)
    );
    for shading in ["flat", "gouraud", "phong"] {
        let toml = scene("source = \"octahedron.obj\"", shading, "yaw = 20\n");
        assert_eq!(
            engine_image(&mut engine, &toml),
            cli_image(&toml, dir.path())
        );
    }
}

#[test]
fn a_bad_file_keeps_the_previous_one() {
    let mut engine = Engine::new();
    engine.load_file("good.obj", OCTAHEDRON.as_bytes()).unwrap();
    let toml = scene("source = \"good.obj\"", "phong", "");
    let good = engine_image(&mut engine, &toml);
    for (name, bytes, expected) in [
        ("bad.obj", &b"v 1 2\nf 1 2 3\n"[..], "bad.obj:1:"),
        ("empty.obj", b"# nothing\n", "empty.obj: no faces"),
        (
            "nan.obj",
            b"v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
            "nan.obj:1:",
        ),
        ("notes.txt", b"hello", "notes.txt: unknown mesh format"),
        ("x.stl", b"solid x\nfacet\n", "x.stl"),
        ("x.glb", b"glTF\x02\0\0\0", "x.glb"),
        ("teapot", OCTAHEDRON.as_bytes(), "name of a built-in model"),
    ] {
        let err = engine.load_file(name, bytes).unwrap_err().to_string();
        assert!(err.contains(expected), "{name}: {err}");
        assert_eq!(
            engine_image(&mut engine, &toml),
            good,
            "{name} changed the model"
        );
    }
    let huge = vec![b' '; MAX_FILE_BYTES + 1];
    let err = engine.load_file("huge.obj", &huge).unwrap_err().to_string();
    assert!(err.contains("limit of 128 MiB"), "{err}");
    // A file that is not loaded is named as such.
    let err = engine
        .render(&scene("source = \"other.obj\"", "phong", ""))
        .unwrap_err()
        .to_string();
    assert!(
        err.starts_with("model.source: \"other.obj\" is neither"),
        "{err}"
    );
}

#[test]
fn a_bad_scene_is_an_error_naming_the_key_and_the_last_frame_stays() {
    let mut engine = Engine::new();
    let good = engine_image(&mut engine, &scene("source = \"cube\"", "phong", ""));
    for (toml, key) in [
        (
            scene(
                "source = \"cube\"",
                "phong",
                "[material]\nshininess = -2.0\n",
            ),
            "material.shininess",
        ),
        (
            scene("source = \"cube\"", "phong", "zoom = 0.0\n"),
            "render.zoom",
        ),
        (
            scene("source = \"cube\"\ndetail = 0", "phong", ""),
            "model.detail",
        ),
        (
            scene(
                "source = \"cube\"",
                "phong",
                "polygons = \"whole\"\nrasterizer = \"tiled\"\n",
            ),
            "render.polygons",
        ),
        ("[render]\nwidth = 0\n".to_string(), "render.width"),
        ("[render\n".to_string(), "TOML parse error"),
    ] {
        let err = engine.render(&toml).unwrap_err().to_string();
        assert!(err.contains(key), "{toml}: {err}");
        assert_eq!(engine.image().unwrap(), &good);
    }
}

#[test]
fn exports_speak_json() {
    let parse = |s: String| -> serde_json::Value { serde_json::from_str(&s).unwrap() };
    assert_eq!(abi::shadelab_models(), abi::OK);
    let models = parse(abi::result_text());
    assert_eq!(models.as_array().unwrap().len(), BUILTIN_MODELS.len());
    assert_eq!(models[0]["name"], BUILTIN_MODELS[0].name);
    assert!(models
        .as_array()
        .unwrap()
        .iter()
        .any(|m| m["default_crease"] == 60.0));

    abi::set_input(b"[render]\nwidth = 20\nheight = 10\nshading = \"flat\"\n");
    assert_eq!(abi::shadelab_render(), abi::OK);
    let frame = parse(abi::result_text());
    assert_eq!(
        (frame["width"].as_u64(), frame["height"].as_u64()),
        (Some(20), Some(10))
    );
    assert!(frame["stats"]["lighting_evaluations"].as_u64().unwrap() > 0);
    assert_eq!(abi::shadelab_pixels_len(), 20 * 10 * 4);

    abi::set_input(b"[render]\nwidth = -1\n");
    assert_eq!(abi::shadelab_render(), abi::FAILED);
    assert!(parse(abi::result_text())["error"]
        .as_str()
        .unwrap()
        .contains("width"));

    let mut input = b"tri.obj".to_vec();
    input.extend_from_slice(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    abi::set_input(&input);
    assert_eq!(abi::shadelab_load_file(7), abi::OK);
    assert_eq!(parse(abi::result_text())["polygons"], 1);
    abi::set_input(b"x.obj");
    assert_eq!(abi::shadelab_load_file(99), abi::FAILED);
    assert!(parse(abi::result_text())["error"]
        .as_str()
        .unwrap()
        .contains("longer than the input"));
    abi::set_input(b"\xff\xfe");
    assert_eq!(abi::shadelab_render(), abi::FAILED);

    // The input buffer is the size asked for.
    let address = abi::shadelab_input(1000);
    assert!(!address.is_null());
}

#[test]
fn a_frame_reports_the_camera_that_drew_it_and_its_lights() {
    let mut engine = Engine::new();
    let toml = scene(
        "source = \"cube\"",
        "gouraud",
        "yaw = 40\npitch = 25\nzoom = 1.5\n",
    );
    let info = engine.render(&toml).unwrap();
    let file = SceneFile::parse(&toml, "scene").unwrap();
    let (resolved, _) = file.resolve(Path::new("")).unwrap();
    assert_eq!(info.view, resolved.camera.view().to_cols_array());
    // The view's rotation is orthonormal: the page turns light directions with it.
    let m = info.view;
    for (i, j) in [(0, 0), (0, 1), (1, 1), (1, 2), (2, 2), (0, 2)] {
        let dot: f32 = (0..3).map(|k| m[4 * k + i] * m[4 * k + j]).sum();
        assert!(
            (dot - f32::from(u8::from(i == j))).abs() < 1e-5,
            "{i} {j}: {dot}"
        );
    }
    // Several lights of both kinds, and none: each is the command line's picture.
    let lights = "[[lights]]\nkind = \"point\"\nposition = [2.0, 2.0, 3.0]\n\
        [[lights]]\nkind = \"directional\"\ndirection = [1.0, 0.0, -0.2]\ncolor = [255, 0, 0]\n\
        [[lights]]\nkind = \"point\"\nposition = [0.0, 3.0, 1.0]\ncolor = [0, 255, 0]\nintensity = 0.5\n\
        [[lights]]\nkind = \"directional\"\ndirection = [0.0, 1.0, -0.3]\ncolor = [0, 0, 255]\n";
    for prefix in [String::new(), "lights = []\n".to_owned()] {
        let toml = format!(
            "{prefix}{}{}",
            scene("source = \"sphere\"\ndetail = 16", "phong", ""),
            if prefix.is_empty() { lights } else { "" }
        );
        assert_eq!(
            engine_image(&mut engine, &toml),
            cli_image(&toml, Path::new("")),
            "{toml}"
        );
    }
}
