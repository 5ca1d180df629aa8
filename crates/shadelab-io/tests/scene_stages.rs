//! Scene resolution in stages (what the viewer calls, keeping the model
//! between frames) gives what `resolve` gives; `render.zoom` narrows the
//! field of view; `parse_mesh` reads a file's bytes by its name.

use std::path::Path;

use shadelab_core::{Camera, Scene};
use shadelab_io::{parse_mesh, parse_obj, SceneError, SceneFile, MAX_ZOOM, MIN_ZOOM};

const TETRA: &str = "v 10 0 0\nv 12 0 0\nv 10 2 0\nv 10 0 2\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

fn staged(file: &SceneFile) -> Result<Scene, SceneError> {
    let options = file.render_options()?;
    let (mesh, crease) = file.model_mesh(|_| unreachable!("built-in models only"))?;
    let (mesh, normals) = file.prepare_model(mesh, crease)?;
    file.build_scene(mesh, normals, &options)
}

#[test]
fn stages_give_what_resolve_gives() {
    for text in [
        "",
        "[model]\nsource = \"cylinder\"\ndetail = 9\n[render]\nyaw = 40\npitch = -10\nwidth = 300\nheight = 200\n",
        "[model]\nsource = \"torus\"\nnormals = \"area\"\ncrease_angle = 30\n[render]\nzoom = 2.5\n",
        "[model]\nsource = \"cube\"\n[camera]\neye = [3.0, 2.0, 4.0]\n[material]\nshininess = 5.0\n",
        "[ambient]\nintensity = 0.5\n[[lights]]\nkind = \"directional\"\ndirection = [0.0, -1.0, -1.0]\n",
    ] {
        let file = SceneFile::parse(text, "scene").unwrap();
        let (resolved, options) = file.resolve(Path::new("")).unwrap();
        assert_eq!(file.render_options().unwrap(), options, "{text}");
        assert_eq!(staged(&file).unwrap(), resolved, "{text}");
    }
}

#[test]
fn update_scene_changes_only_camera_lights_and_material() {
    let first = SceneFile::parse("[model]\nsource = \"sphere\"\n", "a").unwrap();
    let mut scene = staged(&first).unwrap();
    let (mesh, normals) = (scene.mesh.clone(), scene.normals.clone());
    let second = SceneFile::parse(
        "[model]\nsource = \"sphere\"\n[render]\nyaw = 30\n[material]\nkd = [0, 0, 255]\n",
        "b",
    )
    .unwrap();
    let options = second.render_options().unwrap();
    second.update_scene(&mut scene, &options).unwrap();
    assert_eq!(scene, second.resolve(Path::new("")).unwrap().0);
    assert_eq!((scene.mesh.clone(), scene.normals.clone()), (mesh, normals));

    // A bad value leaves the scene as it was.
    let before = scene.clone();
    let bad = SceneFile::parse("[material]\nshininess = -1.0\n", "c").unwrap();
    let err = bad.update_scene(&mut scene, &options).unwrap_err();
    assert!(err.to_string().contains("material.shininess"), "{err}");
    assert_eq!(scene, before);
}

#[test]
fn model_mesh_asks_for_files_by_source() {
    let file = SceneFile::parse("[model]\nsource = \"tetra.obj\"\n", "s").unwrap();
    let (mesh, crease) = file
        .model_mesh(|source| {
            assert_eq!(source, "tetra.obj");
            Ok(parse_obj(TETRA, source).unwrap())
        })
        .unwrap();
    assert_eq!((mesh.polygon_count(), crease), (4, None));
    let with_detail = SceneFile::parse("[model]\nsource = \"a.obj\"\ndetail = 3\n", "s").unwrap();
    let err = with_detail.model_mesh(|_| unreachable!()).unwrap_err();
    assert!(err.to_string().starts_with("model.detail"), "{err}");
}

#[test]
fn zoom_narrows_the_field_of_view() {
    let fov = |text: &str| -> f32 {
        SceneFile::parse(text, "s")
            .unwrap()
            .resolve(Path::new(""))
            .unwrap()
            .0
            .camera
            .fov_y_degrees
    };
    let base = fov("");
    assert_eq!(base, 45.0);
    for zoom in [0.5f32, 2.0, 4.0] {
        let got = fov(&format!("[render]\nzoom = {zoom:?}\n"));
        let want = (2.0 * ((base.to_radians() / 2.0).tan() / zoom).atan()).to_degrees();
        assert!((got - want).abs() < 1e-4, "zoom {zoom}: {got} vs {want}");
    }
    // The eye stays where it was: zoom is the lens, not a dolly.
    let eye = |text: &str| -> Camera {
        SceneFile::parse(text, "s")
            .unwrap()
            .resolve(Path::new(""))
            .unwrap()
            .0
            .camera
    };
    assert_eq!(eye("[render]\nzoom = 3.0\n").eye, eye("").eye);
    for bad in [0.0, MIN_ZOOM / 2.0, MAX_ZOOM * 2.0] {
        let err = SceneFile::parse(&format!("[render]\nzoom = {bad:?}\n"), "s")
            .unwrap()
            .resolve(Path::new(""))
            .unwrap_err();
        assert!(err.to_string().starts_with("render.zoom"), "{err}");
    }
    let err = SceneFile::parse("[render]\nzoom = nan\n", "s")
        .unwrap()
        .resolve(Path::new(""))
        .unwrap_err();
    assert!(err.to_string().starts_with("render.zoom"), "{err}");
}

#[test]
fn parse_mesh_chooses_the_format_by_name() {
    let mesh = parse_mesh(TETRA.as_bytes(), "Tetra.OBJ").unwrap();
    assert_eq!(mesh.polygon_count(), 4);
    let ascii_stl = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n";
    assert_eq!(
        parse_mesh(ascii_stl.as_bytes(), "t.stl")
            .unwrap()
            .polygon_count(),
        1
    );
    let ply = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    assert_eq!(
        parse_mesh(ply.as_bytes(), "t.ply").unwrap().polygon_count(),
        1
    );
    let err = parse_mesh(b"\x89PNG\r\n", "photo.png")
        .unwrap_err()
        .to_string();
    assert!(err.starts_with("photo.png: unknown mesh format"), "{err}");
    let err = parse_mesh(b"v 1 2 \xff\n", "bad.obj")
        .unwrap_err()
        .to_string();
    assert!(err.contains("not UTF-8"), "{err}");
    let err = parse_mesh(b"{}", "empty.gltf").unwrap_err().to_string();
    assert!(err.starts_with("empty.gltf"), "{err}");
}
