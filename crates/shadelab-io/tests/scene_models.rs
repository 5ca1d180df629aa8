//! Scene files whose model is a file: paths taken from the scene's folder,
//! unknown names, the file's errors passed through with their line, file
//! normals, and a mesh drawn as written (with a camera) or normalised.

mod common;

use std::path::Path;

use common::*;
use glam::Vec3;
use shadelab_core::{Specular, BUILTIN_MODELS};
use shadelab_io::{load_obj, SceneError, SceneFile};

// ---- models from files ----

#[test]
fn relative_obj_path_is_resolved_against_the_scene_directory() {
    let dir = tempfile::tempdir().unwrap();
    let obj = write(dir.path(), "scenes/meshes/tetra.obj", TETRA_OBJ);
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
    write(dir.path(), "tetra.obj", TETRA_OBJ);
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
    write(dir.path(), "plain.obj", TETRA_OBJ);
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
            .corner()
            .iter()
            .map(|&i| scene.normals.normals[i as usize])
            .collect();
        assert_eq!(per_corner, vec![Vec3::Z; 3], "normals = {choice}");
    }
}

#[test]
fn with_a_camera_the_mesh_is_used_as_written() {
    let dir = tempfile::tempdir().unwrap();
    let obj = write(dir.path(), "tetra.obj", TETRA_OBJ);
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
    let obj = write(dir.path(), "tetra.obj", TETRA_OBJ);
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
