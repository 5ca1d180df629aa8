//! Every mesh format, materials and impossible cameras, end to end.

mod support;

use std::path::Path;

use support::*;

// ---- mesh formats, materials and the robustness list, end to end ----

/// The tetrahedron as ASCII STL, ASCII PLY and glTF with an embedded buffer.
fn tetra_formats(dir: &Path) {
    let p = [[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]];
    let faces = [[0usize, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
    let mut stl = String::from("solid tetra\n");
    for f in faces {
        stl += "facet normal 0 0 0\nouter loop\n";
        for i in f {
            stl += &format!("vertex {} {} {}\n", p[i][0], p[i][1], p[i][2]);
        }
        stl += "endloop\nendfacet\n";
    }
    write(dir, "tetra.stl", &(stl + "endsolid tetra\n"));
    let mut ply = String::from(
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n\
         property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n",
    );
    for v in p {
        ply += &format!("{} {} {}\n", v[0], v[1], v[2]);
    }
    for f in faces {
        ply += &format!("3 {} {} {}\n", f[0], f[1], f[2]);
    }
    write(dir, "tetra.ply", &ply);
    // Positions then u16 indices, base64: written out by hand.
    let mut bin: Vec<u8> = p
        .iter()
        .flatten()
        .flat_map(|c: &f32| c.to_le_bytes())
        .collect();
    bin.extend(
        faces
            .iter()
            .flatten()
            .flat_map(|&i| (i as u16).to_le_bytes()),
    );
    let uri = data_uri(&bin);
    let gltf = format!(
        r#"{{"asset":{{"version":"2.0"}},"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],
        "meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}},"indices":1}}]}}],
        "buffers":[{{"byteLength":{},"uri":"{uri}"}}],
        "bufferViews":[{{"buffer":0,"byteLength":48}},{{"buffer":0,"byteOffset":48,"byteLength":24}}],
        "accessors":[{{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[0,0,0],"max":[1,1,1]}},
        {{"bufferView":1,"componentType":5123,"count":12,"type":"SCALAR"}}]}}"#,
        bin.len()
    );
    write(dir, "tetra.gltf", &gltf);
}

#[test]
fn every_format_renders_like_its_obj_twin() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "tetra.obj", TETRA);
    tetra_formats(dir.path());
    let render = |model: &str, out: &str| {
        assert_ok(&run(
            dir.path(),
            &[
                "render", "--model", model, "--size", "48x40", "--yaw", "30", "-o", out,
            ],
        ));
        Png::read(&dir.path().join(out))
    };
    let obj = render("tetra.obj", "obj.png");
    assert!(obj.drawn(BLACK) > 100, "{obj:?}");
    for model in ["tetra.stl", "tetra.ply", "tetra.gltf"] {
        assert_eq!(render(model, "other.png"), obj, "{model}");
    }
}

#[test]
fn bad_mesh_files_of_every_format() {
    let dir = tempfile::tempdir().unwrap();
    tetra_formats(dir.path());
    // Binary STL whose header claims 2^31 triangles: refused at byte 80.
    let mut stl = vec![0u8; 84 + 50];
    stl[80..84].copy_from_slice(&(1u32 << 31).to_le_bytes());
    std::fs::write(dir.path().join("lie.stl"), &stl).unwrap();
    assert_render_fails(
        dir.path(),
        &["--model", "lie.stl"],
        &["lie.stl", "byte 80", "2147483648 triangles"],
    );
    // A PLY header promising more faces than follow.
    let ply = std::fs::read_to_string(dir.path().join("tetra.ply"))
        .unwrap()
        .replace("element face 4", "element face 40");
    write(dir.path(), "short.ply", &ply);
    assert_render_fails(
        dir.path(),
        &["--model", "short.ply"],
        &["short.ply", "promises"],
    );
    // A glTF index beyond its vertices.
    let gltf = std::fs::read_to_string(dir.path().join("tetra.gltf"))
        .unwrap()
        .replace(r#""count":4,"type":"VEC3""#, r#""count":3,"type":"VEC3""#);
    write(dir.path(), "range.gltf", &gltf);
    assert_render_fails(
        dir.path(),
        &["--model", "range.gltf"],
        &["range.gltf", "index", "3 vertices"],
    );
    // Truncated and empty files, wrong magic.
    std::fs::write(dir.path().join("empty.glb"), b"").unwrap();
    assert_render_fails(dir.path(), &["--model", "empty.glb"], &["empty.glb"]);
    std::fs::write(dir.path().join("magic.ply"), b"PLY\nformat ascii 1.0\n").unwrap();
    assert_render_fails(
        dir.path(),
        &["--model", "magic.ply"],
        &["magic.ply", "byte 0"],
    );
    // A bad smoothing group names its line.
    write(
        dir.path(),
        "s.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\ns smooth\nf 1 2 3\n",
    );
    assert_render_fails(
        dir.path(),
        &["--model", "s.obj"],
        &["s.obj:4:", "`s` takes"],
    );
}

/// The material an OBJ file uses colours the render where no flag or scene
/// key sets the colours; a missing library is no error.
#[test]
fn obj_materials_colour_the_render() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write(d, "blue.mtl", "newmtl blue\nKa 0.2 0.2 0.6\nKd 0.2 0.6 1\n");
    write(d, "tetra.obj", TETRA);
    write(
        d,
        "blue.obj",
        format!("mtllib blue.mtl\nusemtl blue\n{TETRA}"),
    );
    write(
        d,
        "lost.obj",
        format!("mtllib lost.mtl\nusemtl blue\n{TETRA}"),
    );
    let render = |args: &[&str]| {
        let mut all = vec!["render", "--size", "40x40", "--yaw", "30", "-o", "out.png"];
        all.extend_from_slice(args);
        let out = run(d, &all);
        assert_ok(&out);
        // The report line, and for a lost library one warning that names it.
        let lines = stderr(&out).lines().count();
        assert!(
            lines <= 1 || (lines == 2 && stderr(&out).contains("lost.mtl")),
            "{}",
            stderr(&out)
        );
        Png::read(&d.join("out.png"))
    };
    let from_file = render(&["--model", "blue.obj"]);
    let by_flags = render(&[
        "--model",
        "tetra.obj",
        "--ka",
        "51,51,153",
        "--kd",
        "51,153,255",
    ]);
    assert_eq!(from_file, by_flags);
    assert_ne!(from_file, render(&["--model", "tetra.obj"]));
    // A flag wins over the file, key by key.
    let kd_flag = render(&["--model", "blue.obj", "--kd", "255,0,0"]);
    let kd_flag_plain = render(&[
        "--model",
        "tetra.obj",
        "--ka",
        "51,51,153",
        "--kd",
        "255,0,0",
    ]);
    assert_eq!(kd_flag, kd_flag_plain);
    // No library: the default colours, and no warning.
    assert_eq!(
        render(&["--model", "lost.obj"]),
        render(&["--model", "tetra.obj"])
    );
}

/// The camera cases of the robustness list, from a scene file: errors that
/// name the camera key, no output, no temporary file.
#[test]
fn impossible_cameras_in_the_scene() {
    let dir = tempfile::tempdir().unwrap();
    for (k, (camera, needles)) in [
        (
            "eye = [1, 2, 3]\ntarget = [1, 2, 3]",
            &["camera", "eye equals camera.target"][..],
        ),
        ("eye = [0, 0, 3]\nfov_y = 0", &["camera", "fov_y", "0"]),
        ("eye = [0, 0, 3]\nfov_y = 180", &["camera", "fov_y", "180"]),
        (
            "eye = [0, 0, 3]\nnear = 5.0\nfar = 5.0",
            &["camera", "near", "far"],
        ),
        (
            "eye = [0, 0, 3]\nnear = 6.0\nfar = 5.0",
            &["camera", "near", "far"],
        ),
        ("eye = [0, 0, 3]\nup = [0, 0, 1]", &["camera", "up"]),
    ]
    .into_iter()
    .enumerate()
    {
        let name = format!("camera{k}.toml");
        write(
            dir.path(),
            &name,
            format!("[camera]\n{camera}\n[render]\nwidth = 16\nheight = 16\n"),
        );
        assert_render_fails(dir.path(), &[&name], needles);
    }
}

/// Extreme but valid cameras and an eye inside the model render images of
/// the requested size.
#[test]
fn extreme_cameras_render_the_requested_size() {
    let dir = tempfile::tempdir().unwrap();
    for (k, camera) in [
        "eye = [0, 0, 3]\nfov_y = 0.001",
        "eye = [0, 0, 3]\nfov_y = 179.999",
        "eye = [0, 0, 0]\ntarget = [0, 0, -1]\nnear = 0.001",
        "eye = [0, 0, 3]\nnear = 1e-30\nfar = 1e30",
        "eye = [0, 0, 3]\nnear = 2.9\nfar = 2.9000003",
    ]
    .into_iter()
    .enumerate()
    {
        let name = format!("camera{k}.toml");
        write(
            dir.path(),
            &name,
            format!("[model]\nsource = \"sphere\"\n[camera]\n{camera}\n[render]\nwidth = 23\nheight = 17\ncull_backfaces = false\n"),
        );
        let out = run(dir.path(), &["render", &name, "-o", "out.png"]);
        assert_ok(&out);
        let png = Png::read(&dir.path().join("out.png"));
        assert_eq!((png.width, png.height), (23, 17), "{camera}");
    }
}
