//! Bad input and unsafe output, end to end: exit codes, messages, and
//! nothing the user had lost or half-written.

mod support;

use support::*;

// ---- errors ----

#[test]
fn missing_scene_file() {
    let dir = tempfile::tempdir().unwrap();
    assert_render_fails(dir.path(), &["absent.toml"], &["absent.toml"]);
}

#[test]
fn missing_files_are_reported_once() {
    // The OS error appears once, not once per level of the error chain.
    let dir = tempfile::tempdir().unwrap();
    for args in [
        &["render", "absent.toml", "-o", "out.png"][..],
        &["render", "--model", "absent.obj", "-o", "out.png"][..],
        &["compare", "--model", "absent.obj", "-o", "out.png"][..],
        &["render", "--model", "cube", "-o", "no/dir/out.png"][..],
    ] {
        let err = stderr(&run(dir.path(), args));
        assert_eq!(err.matches("os error").count(), 1, "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
    }
}

#[test]
fn malformed_scene_file() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "bad.toml", "[render\nwidth = 10\n");
    assert_render_fails(dir.path(), &["bad.toml"], &["bad.toml", "line 1"]);
}

#[test]
fn unknown_key_in_the_scene() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "bad.toml", "[render]\nwidht = 10\n");
    assert_render_fails(dir.path(), &["bad.toml"], &["bad.toml", "widht"]);
}

#[test]
fn out_of_range_value_in_the_scene() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "bad.toml", "[material]\nshininess = -3\n");
    assert_render_fails(dir.path(), &["bad.toml"], &["material.shininess"]);
    write(dir.path(), "bad2.toml", "[[lights]]\nkind = \"point\"\n");
    assert_render_fails(dir.path(), &["bad2.toml"], &["lights[0].position"]);
}

#[test]
fn out_of_range_override() {
    let dir = tempfile::tempdir().unwrap();
    assert_render_fails(
        dir.path(),
        &["--model", "sphere", "--shininess", "-1"],
        &["material.shininess"],
    );
    assert_render_fails(
        dir.path(),
        &["--model", "sphere", "--detail", "1"],
        &["model.detail"],
    );
    assert_render_fails(
        dir.path(),
        &["--model", "cube", "--crease-angle", "200"],
        &["model.crease_angle"],
    );
    assert_render_fails(
        dir.path(),
        &["--model", "cube", "--normals", "file"],
        &["model.normals"],
    );
}

#[test]
fn missing_obj() {
    let dir = tempfile::tempdir().unwrap();
    assert_render_fails(dir.path(), &["--model", "absent.obj"], &["absent.obj"]);
    write(dir.path(), "s.toml", "[model]\nsource = \"gone.obj\"\n");
    assert_render_fails(dir.path(), &["s.toml"], &["gone.obj"]);
}

#[test]
fn obj_with_a_syntax_error() {
    let dir = tempfile::tempdir().unwrap();
    write(
        dir.path(),
        "bad.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 oops\nf 1 2 3\n",
    );
    assert_render_fails(dir.path(), &["--model", "bad.obj"], &["bad.obj:3:", "oops"]);
}

#[test]
fn obj_with_an_index_out_of_range() {
    let dir = tempfile::tempdir().unwrap();
    write(
        dir.path(),
        "bad.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 4\n",
    );
    assert_render_fails(
        dir.path(),
        &["--model", "bad.obj"],
        &["bad.obj:5:", "out of range"],
    );
    write(
        dir.path(),
        "neg.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n",
    );
    assert_render_fails(
        dir.path(),
        &["--model", "neg.obj"],
        &["neg.obj:4:", "out of range"],
    );
}

#[test]
fn obj_with_nan() {
    let dir = tempfile::tempdir().unwrap();
    write(
        dir.path(),
        "bad.obj",
        "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n",
    );
    assert_render_fails(
        dir.path(),
        &["--model", "bad.obj"],
        &["bad.obj:2:", "finite"],
    );
}

#[test]
fn obj_without_faces() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    assert_render_fails(
        dir.path(),
        &["--model", "bad.obj"],
        &["bad.obj", "no faces"],
    );
}

#[test]
fn unknown_model_name() {
    let dir = tempfile::tempdir().unwrap();
    assert_render_fails(
        dir.path(),
        &["--model", "dodecahedron"],
        &[
            "dodecahedron",
            "cube",
            "sphere",
            "icosphere",
            "torus",
            "cylinder",
            "cone",
            "teapot",
        ],
    );
}

#[test]
fn bad_size() {
    let dir = tempfile::tempdir().unwrap();
    assert_render_fails(
        dir.path(),
        &["--model", "cube", "--size", "0x10"],
        &["1..=16384", "\"0x10\""],
    );
    assert_render_fails(
        dir.path(),
        &["--model", "cube", "--size", "10x0"],
        &["1..=16384", "\"10x0\""],
    );
    assert_render_fails(dir.path(), &["--model", "cube", "--size", "abc"], &["abc"]);
    assert_render_fails(
        dir.path(),
        &["--model", "cube", "--size", "10x"],
        &["--size"],
    );
    assert_render_fails(
        dir.path(),
        &["--model", "cube", "--size", "20000x10"],
        &["1..=16384", "\"20000x10\""],
    );
}

#[test]
fn bad_colour_and_vector_flags() {
    let dir = tempfile::tempdir().unwrap();
    assert_render_fails(
        dir.path(),
        &["--model", "cube", "--ka", "300,0,0"],
        &["--ka"],
    );
    assert_render_fails(dir.path(), &["--model", "cube", "--kd", "1,2"], &["--kd"]);
    assert_render_fails(
        dir.path(),
        &["--model", "cube", "--background=-1,0,0"],
        &["--background"],
    );
    // Without `=`, a leading minus reads as a flag; still a clean usage error.
    assert_render_fails(
        dir.path(),
        &["--model", "cube", "--background", "-1,0,0"],
        &["-1"],
    );
    assert_render_fails(
        dir.path(),
        &["--model", "cube", "--light-pos", "nan,0,0"],
        &["--light-pos"],
    );
    assert_render_fails(
        dir.path(),
        &["--model", "cube", "--shading", "glossy"],
        &["glossy"],
    );
}

#[test]
fn compare_errors_exit_2_without_output() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "bad.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\n");
    let out = run(
        dir.path(),
        &["compare", "--model", "bad.obj", "-o", "three.png"],
    );
    assert_input_error(&out, &["bad.obj:3:"]);
    assert!(!dir.path().join("three.png").exists());
    let out = run(dir.path(), &["compare", "--size", "0x5", "-o", "three.png"]);
    assert_input_error(&out, &["--size", "1..=16384", "\"0x5\""]);
    assert!(!dir.path().join("three.png").exists());
}

#[test]
fn missing_output_flag_and_unknown_subcommand() {
    let dir = tempfile::tempdir().unwrap();
    assert_input_error(
        &run(dir.path(), &["render", "--model", "cube"]),
        &["--output"],
    );
    assert_input_error(&run(dir.path(), &["paint"]), &["paint"]);
    assert_input_error(&run(dir.path(), &[]), &["Usage"]);
}

#[test]
fn unwritable_output_exits_1() {
    let dir = tempfile::tempdir().unwrap();
    let out = run(
        dir.path(),
        &[
            "render",
            "--model",
            "cube",
            "--size",
            "8x8",
            "-o",
            "no/such/dir/out.png",
        ],
    );
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("cannot write"), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(entries(dir.path()).is_empty(), "{:?}", entries(dir.path()));
}

// ---- inputs and outputs ----

#[test]
fn render_refuses_to_overwrite_the_scene_file() {
    let dir = tempfile::tempdir().unwrap();
    let text = "[model]\nsource = \"cube\"\n[render]\nwidth = 8\nheight = 8\n";
    let scene = write(dir.path(), "scene.toml", text);
    for output in ["scene.toml", "./scene.toml"] {
        let out = run(dir.path(), &["render", "scene.toml", "-o", output]);
        assert_input_error(&out, &["scene.toml"]);
        assert_eq!(std::fs::read_to_string(&scene).unwrap(), text);
        let out = run(dir.path(), &["compare", "scene.toml", "-o", output]);
        assert_input_error(&out, &["scene.toml"]);
        assert_eq!(std::fs::read_to_string(&scene).unwrap(), text);
    }
    assert_eq!(entries(dir.path()), vec!["scene.toml".to_owned()]);
}

#[test]
fn render_refuses_to_overwrite_the_obj() {
    let dir = tempfile::tempdir().unwrap();
    let obj = write(dir.path(), "tetra.obj", TETRA);
    let out = run(
        dir.path(),
        &[
            "render",
            "--model",
            "tetra.obj",
            "--size",
            "8x8",
            "-o",
            "tetra.obj",
        ],
    );
    assert_input_error(&out, &["tetra.obj"]);
    assert_eq!(std::fs::read_to_string(&obj).unwrap(), TETRA);

    // Named by a scene file in a subdirectory, written from elsewhere.
    std::fs::create_dir(dir.path().join("sub")).unwrap();
    let nested = write(&dir.path().join("sub"), "m.obj", TETRA);
    write(
        &dir.path().join("sub"),
        "s.toml",
        "[model]\nsource = \"m.obj\"\n[render]\nwidth = 8\nheight = 8\n",
    );
    let out = run(dir.path(), &["render", "sub/s.toml", "-o", "sub/m.obj"]);
    assert_input_error(&out, &["m.obj"]);
    assert_eq!(std::fs::read_to_string(&nested).unwrap(), TETRA);
}

#[test]
fn render_refuses_to_overwrite_a_material_library_or_external_buffer() {
    let dir = tempfile::tempdir().unwrap();
    let obj_text = format!("mtllib  my lib.mtl\nusemtl red\n{TETRA}");
    write(dir.path(), "tetra.obj", &obj_text);
    let mtl_text = "newmtl red\nKd 1 0 0\n";
    for library in ["my lib.mtl", "lib.mtl"] {
        let path = write(dir.path(), library, mtl_text);
        let out = run(
            dir.path(),
            &[
                "render",
                "--model",
                "tetra.obj",
                "--size",
                "8x8",
                "-o",
                library,
            ],
        );
        assert_input_error(&out, &[library]);
        assert_eq!(std::fs::read_to_string(&path).unwrap(), mtl_text);
    }

    // A glTF file whose buffer lives in a file beside it.
    let positions: Vec<u8> = [0f32, 0., 0., 1., 0., 0., 0., 1., 0.]
        .iter()
        .flat_map(|v| v.to_le_bytes())
        .collect();
    let bin = dir.path().join("tri.bin");
    std::fs::write(&bin, &positions).unwrap();
    let gltf = r#"{"asset":{"version":"2.0"},"buffers":[{"uri":"tri.bin","byteLength":36}],
        "bufferViews":[{"buffer":0,"byteLength":36}],
        "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3",
        "min":[0,0,0],"max":[1,1,0]}],
        "meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
        "nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],"scene":0}"#;
    write(dir.path(), "tri.gltf", gltf);
    assert_ok(&run(
        dir.path(),
        &[
            "render", "--model", "tri.gltf", "--size", "8x8", "-o", "tri.png",
        ],
    ));
    let out = run(
        dir.path(),
        &[
            "render", "--model", "tri.gltf", "--size", "8x8", "-o", "tri.bin",
        ],
    );
    assert_input_error(&out, &["tri.bin"]);
    assert_eq!(std::fs::read(&bin).unwrap(), positions);
}

#[test]
fn existing_output_is_replaced_atomically() {
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "out.png", "an old file that is not a PNG");
    assert_ok(&run(
        dir.path(),
        &[
            "render", "--model", "cube", "--size", "20x10", "-o", "out.png",
        ],
    ));
    let image = Png::read(&path);
    assert_eq!((image.width, image.height), (20, 10));
    assert_eq!(entries(dir.path()), vec!["out.png".to_owned()]);

    assert_ok(&run(
        dir.path(),
        &[
            "compare", "--model", "cube", "--size", "20x10", "-o", "out.png",
        ],
    ));
    let sheet = Png::read(&path);
    assert_eq!((sheet.width, sheet.height), (68, 38));
    assert_eq!(entries(dir.path()), vec!["out.png".to_owned()]);
}

#[test]
fn failed_render_keeps_an_existing_output() {
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "out.png", "previous contents");
    let out = run(
        dir.path(),
        &["render", "--model", "nosuchmodel", "-o", "out.png"],
    );
    assert_input_error(&out, &["nosuchmodel"]);
    assert_eq!(std::fs::read_to_string(&path).unwrap(), "previous contents");
    assert_eq!(entries(dir.path()), vec!["out.png".to_owned()]);
}
