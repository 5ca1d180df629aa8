//! STL and PLY loading, and `load_mesh`'s dispatch and limits for every
//! format, on files written here (glTF alone: `gltf.rs`).

mod common;

use common::*;
use glam::Vec3;
use shadelab_core::Mesh;
use shadelab_io::{load_gltf, load_mesh, load_ply, load_stl, LoadError, MAX_MESH_BYTES};

// ---------------------------------------------------------------- STL

#[test]
fn stl_ascii_tetrahedron_is_welded_and_has_no_normals() {
    let dir = tempfile::tempdir().unwrap();
    // A bare `solid` first line, and -0 for one corner that elsewhere is 0.
    let text = ascii_stl("solid", &tetra_triangles()).replacen("vertex 0 0 0", "vertex -0 0 -0", 1);
    let path = write(dir.path(), "tetra.stl", text);
    let mesh = load_stl(&path).unwrap();
    assert_eq!(mesh.positions().len(), 4, "equal positions are welded");
    assert_eq!(mesh.polygon_count(), 4);
    assert!(mesh.file_normals().is_none());
    assert_eq!(triangle_set(&mesh), {
        let (p, f) = (TETRA.map(Vec3::from_array).to_vec(), TETRA_FACES);
        triangle_set(&Mesh::from_polygons(p, f).unwrap())
    });
}

#[test]
fn stl_binary_tetrahedron() {
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "tetra.stl", binary_stl(b"", &tetra_triangles()));
    let mesh = load_stl(&path).unwrap();
    assert_eq!(mesh.positions().len(), 4);
    assert_eq!(mesh.polygon_count(), 4);
    assert!(mesh.file_normals().is_none());
    assert_eq!(sorted_positions(&mesh), {
        let mut v: Vec<_> = TETRA.iter().map(|p| p.map(f32::to_bits)).collect();
        v.sort_unstable();
        v
    });
}

#[test]
fn stl_binary_whose_header_begins_with_solid() {
    let dir = tempfile::tempdir().unwrap();
    let bytes = binary_stl(
        b"solid tetra exported by a tool that should know better\n",
        &tetra_triangles(),
    );
    // Upper case extension, through the dispatcher.
    let path = write(dir.path(), "tetra.STL", bytes);
    let mesh = load_mesh(&path).unwrap();
    assert_eq!(mesh.positions().len(), 4);
    assert_eq!(mesh.polygon_count(), 4);
}

#[test]
fn stl_errors() {
    let dir = tempfile::tempdir().unwrap();
    let tris = tetra_triangles();

    // Truncated binary: the count says 4, the data holds 3.5 triangles.
    let mut bytes = binary_stl(b"", &tris);
    bytes.truncate(bytes.len() - 25);
    let path = write(dir.path(), "truncated.stl", &bytes);
    assert_invalid(load_stl(&path), &path, "claims 4 triangles");

    // A count that lies by a lot: must fail at once, allocating nothing.
    let mut bytes = binary_stl(b"", &tris);
    bytes[80..84].copy_from_slice(&(1u32 << 31).to_le_bytes());
    let path = write(dir.path(), "huge.stl", &bytes);
    let start = std::time::Instant::now();
    assert_invalid(load_stl(&path), &path, "claims 2147483648 triangles");
    assert!(start.elapsed().as_secs() < 2);

    // The same lie behind a `solid` header: tried as ASCII, which fails too.
    let mut bytes = binary_stl(b"solid x", &tris);
    bytes[80..84].copy_from_slice(&(1u32 << 31).to_le_bytes());
    let path = write(dir.path(), "huge_solid.stl", &bytes);
    assert_invalid(load_stl(&path), &path, "not binary");

    // Too short for anything, wrong magic.
    let path = write(dir.path(), "short.stl", b"hello");
    assert_invalid(load_stl(&path), &path, "too short");
    let path = write(dir.path(), "empty.stl", b"");
    assert_invalid(load_stl(&path), &path, "too short");

    // Zero triangles, binary and ASCII.
    let path = write(dir.path(), "zero.stl", binary_stl(b"", &[]));
    assert_invalid(load_stl(&path), &path, "no faces");
    let path = write(dir.path(), "zero_ascii.stl", "solid x\nendsolid x\n");
    assert_invalid(load_stl(&path), &path, "no faces");

    // Truncated ASCII (no endloop / endsolid).
    let text = ascii_stl("solid t", &tris);
    let path = write(dir.path(), "cut.stl", &text[..text.len() / 2]);
    assert_invalid(load_stl(&path), &path, "ASCII STL");

    // Non-finite coordinates: binary (with the byte offset) and ASCII.
    let mut bad = tris.clone();
    bad[1][2].y = f32::NAN;
    let path = write(dir.path(), "nan.stl", binary_stl(b"", &bad));
    // Triangle 1, corner 2, y: 84 + 50 + 12 + 2·12 + 4.
    assert_invalid(load_stl(&path), &path, "byte 174: triangle 1, corner 2");
    let text = ascii_stl("solid t", &tris).replacen("vertex 1 0 0", "vertex 1 inf 0", 1);
    let path = write(dir.path(), "inf.stl", text);
    assert_invalid(load_stl(&path), &path, "finite");
}

// ---------------------------------------------------------------- PLY

#[test]
fn ply_ascii_cube_keeps_quads_and_normals() {
    let dir = tempfile::tempdir().unwrap();
    let (p, faces) = cube();
    let mut text = format!(
        "ply\nformat ascii 1.0\nelement vertex {}\nproperty double x\nproperty double y\n\
         property double z\nproperty float nx\nproperty float ny\nproperty float nz\n\
         property uchar red\nelement face {}\nproperty list uchar uint vertex_indices\n\
         element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n",
        p.len(),
        faces.len()
    );
    for v in &p {
        let n = *v - Vec3::splat(0.5);
        text += &format!("{} {} {} {} {} {} 200\n", v.x, v.y, v.z, n.x, n.y, n.z);
    }
    for f in &faces {
        text += &format!("4 {} {} {} {}\n", f[0], f[1], f[2], f[3]);
    }
    text += "0 1\n";
    let path = write(dir.path(), "cube.ply", text);
    let mesh = load_ply(&path).unwrap();
    assert_eq!(mesh.positions(), &p[..]);
    assert_eq!(mesh.polygon_count(), 6);
    assert_eq!(mesh.polygon(1), &faces[1]);
    let normals = mesh.file_normals().expect("normals");
    assert_eq!(normals.corner(), mesh.corners());
    assert!((normals.normals[7] - Vec3::splat(0.5).normalize()).length() < 1e-6);
}

#[test]
fn ply_binary_both_endians_and_vertex_index() {
    let dir = tempfile::tempdir().unwrap();
    let (p, faces) = cube();
    let polys: Vec<Vec<u32>> = faces.iter().map(|f| f.to_vec()).collect();
    for big in [false, true] {
        let path = write(dir.path(), "cube.ply", binary_ply(&p, &polys, None, big));
        let mesh = load_ply(&path).unwrap();
        assert_eq!(mesh.positions(), &p[..], "big endian: {big}");
        assert_eq!(mesh.corners(), polys.concat());
        assert!(mesh.file_normals().is_none());
    }
    let normals: Vec<Vec3> = p.iter().map(|v| *v - Vec3::splat(0.5)).collect();
    let path = write(
        dir.path(),
        "n.ply",
        binary_ply(&p, &polys, Some(&normals), true),
    );
    assert!(load_ply(&path).unwrap().file_normals().is_some());

    // `vertex_index` with a short/ushort list, and ASCII ints as coordinates are fine too.
    let mut text = String::from(
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n\
         property float z\nelement face 4\nproperty list short ushort vertex_index\nend_header\n",
    );
    for v in TETRA {
        text += &format!("{} {} {}\n", v[0], v[1], v[2]);
    }
    for f in TETRA_FACES {
        text += &format!("3 {} {} {}\n", f[0], f[1], f[2]);
    }
    let path = write(dir.path(), "tetra.Ply", text);
    let mesh = load_mesh(&path).unwrap();
    assert_eq!(mesh.polygon_count(), 4);
    assert_eq!(mesh.corners(), TETRA_FACES.concat());
}

#[test]
fn ply_errors() {
    let dir = tempfile::tempdir().unwrap();
    let (p, faces) = cube();
    let polys: Vec<Vec<u32>> = faces.iter().map(|f| f.to_vec()).collect();
    let good = binary_ply(&p, &polys, None, false);
    let ascii = |vertices: usize, faces: usize, body: &str| {
        format!(
            "ply\nformat ascii 1.0\nelement vertex {vertices}\nproperty float x\n\
             property float y\nproperty float z\nelement face {faces}\n\
             property list uchar int vertex_indices\nend_header\n{body}"
        )
    };
    let tri = "0 0 0\n1 0 0\n0 1 0\n";

    let path = write(
        dir.path(),
        "magic.ply",
        b"PLY\nformat ascii 1.0\nend_header\n",
    );
    assert_invalid(load_ply(&path), &path, "byte 0: not a PLY file");

    let header_end = good.windows(11).position(|w| w == b"end_header\n").unwrap();
    let path = write(dir.path(), "header.ply", &good[..header_end]);
    assert_invalid(load_ply(&path), &path, "header");

    // Counts that lie: binary, by a lot (no allocation for them) and by a
    // little; counts beyond the mesh ceilings fail before the size check.
    let with_header = |from: &str, to: &str| {
        let text = String::from_utf8_lossy(&good[..header_end + 11]).replace(from, to);
        let mut bytes = text.into_bytes();
        bytes.extend_from_slice(&good[header_end + 11..]);
        bytes
    };
    let path = write(
        dir.path(),
        "lie.ply",
        with_header("vertex 8", "vertex 40000000"),
    );
    assert_invalid(load_ply(&path), &path, "promises");
    let path = write(
        dir.path(),
        "absurd.ply",
        with_header("vertex 8", "vertex 4000000000"),
    );
    assert_invalid(
        load_ply(&path),
        &path,
        &format!(
            "declares 4000000000 vertices; at most {} are supported",
            Mesh::MAX_VERTICES
        ),
    );
    let path = write(
        dir.path(),
        "absurd_faces.ply",
        with_header("face 6", "face 16777217"),
    );
    assert_invalid(
        load_ply(&path),
        &path,
        "declares 16777217 faces; at most 16777216 triangles",
    );
    let path = write(dir.path(), "truncated.ply", &good[..good.len() - 100]);
    assert_invalid(load_ply(&path), &path, "promises");
    // Truncated inside the last face list (the minimum size still fits).
    let path = write(dir.path(), "cut_list.ply", &good[..good.len() - 2]);
    assert_invalid(load_ply(&path), &path, "element `face`");
    // ASCII: more lines promised than present.
    let path = write(
        dir.path(),
        "lie_ascii.ply",
        ascii(3, 5, &format!("{tri}3 0 1 2\n")),
    );
    assert_invalid(load_ply(&path), &path, "promises");

    let path = write(
        dir.path(),
        "range.ply",
        ascii(3, 1, &format!("{tri}3 0 1 3\n")),
    );
    assert_invalid(load_ply(&path), &path, "refers to vertex 3");
    let path = write(
        dir.path(),
        "negative.ply",
        ascii(3, 1, &format!("{tri}3 0 -1 2\n")),
    );
    assert_invalid(load_ply(&path), &path, "refers to vertex -1");
    // ASCII PLY numbers are plain decimals (ply-rs-bw's grammar has no `nan`):
    // NaN in binary, infinity as a float that overflows in ASCII.
    let mut nan = p.clone();
    nan[5].z = f32::NAN;
    let path = write(dir.path(), "nan.ply", binary_ply(&nan, &polys, None, true));
    assert_invalid(
        load_ply(&path),
        &path,
        "vertex 5 has a coordinate that is not a finite",
    );
    let path = write(
        dir.path(),
        "inf.ply",
        ascii(3, 1, "0 0 0\n1 1e39 0\n0 1 0\n3 0 1 2\n"),
    );
    assert_invalid(load_ply(&path), &path, "not a finite number");
    let path = write(dir.path(), "zero.ply", ascii(3, 0, tri));
    assert_invalid(load_ply(&path), &path, "no faces");
    let path = write(
        dir.path(),
        "cloud.ply",
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n\
         property float z\nend_header\n0 0 0\n",
    );
    assert_invalid(load_ply(&path), &path, "no faces");
    let path = write(
        dir.path(),
        "garbage.ply",
        ascii(3, 1, &format!("{tri}3 0 x 2\n")),
    );
    assert_invalid(load_ply(&path), &path, "element `face`");
    let path = write(
        dir.path(),
        "float_list.ply",
        ascii(3, 1, tri).replace("uchar int", "uchar float") + "3 0 1 2\n",
    );
    assert_invalid(load_ply(&path), &path, "list of integers");
    let path = write(dir.path(), "two.ply", ascii(3, 1, &format!("{tri}2 0 1\n")));
    assert_invalid(load_ply(&path), &path, "at least 3");
}

// ---------------------------------------------------------------- dispatch, limits

#[test]
fn dispatch_and_generic_errors() {
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "model.xyz", "whatever");
    assert_invalid(load_mesh(&path), &path, ".obj, .stl, .ply, .gltf, .glb");
    let path = write(dir.path(), "noextension", "whatever");
    assert_invalid(load_mesh(&path), &path, "extension");

    let path = write(
        dir.path(),
        "tetra.Obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    );
    assert_eq!(load_mesh(&path).unwrap().polygon_count(), 1);

    let missing = dir.path().join("missing.ply");
    assert!(
        matches!(load_mesh(&missing), Err(LoadError::Io { ref path, .. }) if path.contains("missing.ply"))
    );

    // Over the size ceiling: a sparse file, refused before reading.
    for name in ["big.stl", "big.ply", "big.glb"] {
        let path = dir.path().join(name);
        let file = std::fs::File::create(&path).unwrap();
        file.set_len(MAX_MESH_BYTES + 1).unwrap();
        match load_mesh(&path) {
            Err(LoadError::TooLarge { path: p, bytes, .. }) => {
                assert!(p.contains(name));
                assert_eq!(bytes, MAX_MESH_BYTES + 1);
            }
            other => panic!("{name}: expected TooLarge, got {other:?}"),
        }
    }
}

#[test]
fn no_panic_on_mangled_files() {
    // Every prefix and a few corruptions of each format's good file: errors, never panics.
    let dir = tempfile::tempdir().unwrap();
    let (p, faces) = cube();
    let polys: Vec<Vec<u32>> = faces.iter().map(|f| f.to_vec()).collect();
    let buffer = tetra_buffer();
    let samples: Vec<(&str, Vec<u8>)> = vec![
        ("a.stl", binary_stl(b"solid x", &tetra_triangles())),
        (
            "b.stl",
            ascii_stl("solid t", &tetra_triangles()).into_bytes(),
        ),
        ("c.ply", binary_ply(&p, &polys, Some(&p), false)),
        (
            "d.glb",
            glb(&tetra_doc(None, r#"[{"mesh":0}]"#, "[0]").json(), &buffer),
        ),
        (
            "e.gltf",
            tetra_doc(Some(&data_uri(&buffer)), TWO_NODES, "[0,2]")
                .json()
                .into_bytes(),
        ),
    ];
    for (name, good) in samples {
        let path = dir.path().join(name);
        for cut in (0..good.len()).step_by(7) {
            std::fs::write(&path, &good[..cut]).unwrap();
            let _ = load_mesh(&path);
        }
        for k in (0..good.len()).step_by(11) {
            for byte in [0x00, 0xff, b'9', b'-'] {
                let mut bad = good.clone();
                bad[k] = byte;
                std::fs::write(&path, &bad).unwrap();
                let _ = load_mesh(&path);
            }
        }
    }
}

/// The failure modes every loader must meet, one by one, each a typed error
/// naming the file: empty, truncated, wrong magic, not UTF-8 where text is
/// expected, over the size ceiling.
#[test]
fn every_loader_rejects_bad_bytes_with_a_typed_error() {
    let dir = tempfile::tempdir().unwrap();
    let (p, faces) = cube();
    let polys: Vec<Vec<u32>> = faces.iter().map(|f| f.to_vec()).collect();
    let buffer = tetra_buffer();
    let gltf = tetra_doc(Some(&data_uri(&buffer)), TWO_NODES, "[0,2]").json();
    let glb_bytes = glb(&tetra_doc(None, r#"[{"mesh":0}]"#, "[0]").json(), &buffer);
    let obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    let cases: Vec<(&str, Vec<u8>, &str)> = vec![
        // Empty files.
        ("empty.obj", vec![], "no faces"),
        ("empty.stl", vec![], "too short"),
        ("empty.ply", vec![], "not a PLY file"),
        ("empty.gltf", vec![], "not a valid glTF"),
        ("empty.glb", vec![], "not a valid glTF"),
        // Truncated.
        (
            "cut.obj",
            obj.as_bytes()[..obj.len() - 3].to_vec(),
            "at least 3 vertices",
        ),
        (
            "cut.ply",
            binary_ply(&p, &polys, None, false)[..150].to_vec(),
            "PLY header",
        ),
        (
            "cut.gltf",
            gltf.as_bytes()[..gltf.len() / 2].to_vec(),
            "not a valid glTF",
        ),
        (
            "cut.glb",
            glb_bytes[..glb_bytes.len() - 8].to_vec(),
            "not a valid glTF",
        ),
        // Wrong magic.
        (
            "magic.glb",
            [b"glTX", &glb_bytes[4..]].concat(),
            "not a valid glTF",
        ),
        ("magic.stl", vec![b'x'; 200], "not ascii stl"),
        // Not UTF-8 where text is expected.
        (
            "latin1.obj",
            b"v 0 0 0\nv 1 0 0\nv 0 1 0\n# caf\xe9\nf 1 2 3\n".to_vec(),
            "not UTF-8",
        ),
        (
            "latin1.stl",
            b"solid caf\xe9\nfacet normal 0 0 0\nouter loop\nvertex \xff 0 0\n".to_vec(),
            "ascii stl",
        ),
        (
            "latin1.ply",
            b"ply\nformat ascii 1.0\ncomment \xff\xfe\nend_header\n".to_vec(),
            "ply",
        ),
        (
            "latin1.gltf",
            [b"{\"asset\":\xff".as_slice(), b"}"].concat(),
            "not a valid glTF",
        ),
    ];
    for (name, bytes, needle) in cases {
        let path = write(dir.path(), name, &bytes);
        let error = load_mesh(&path).expect_err(name);
        assert!(
            matches!(error, LoadError::Invalid { .. } | LoadError::Syntax { .. }),
            "{name}: {error:?}"
        );
        let shown = error.to_string();
        assert!(shown.starts_with(&path.display().to_string()), "{shown}");
        assert!(
            shown.to_lowercase().contains(&needle.to_lowercase()),
            "{name}: {shown:?} lacks {needle:?}"
        );
    }
    // Over the size ceiling, for the formats not checked above: sparse files,
    // refused before reading.
    for name in ["big.obj", "big.gltf"] {
        let path = dir.path().join(name);
        std::fs::File::create(&path)
            .unwrap()
            .set_len(MAX_MESH_BYTES + 1)
            .unwrap();
        assert!(
            matches!(load_mesh(&path), Err(LoadError::TooLarge { ref path, .. }) if path.contains(name)),
            "{name}"
        );
    }
}

/// An OBJ face with more corners than the triangle ceiling allows fails at
/// its line, before its corners are gathered.
#[test]
fn obj_beyond_the_triangle_ceiling() {
    let corners = Mesh::MAX_TRIANGLES + 3;
    let mut text = String::with_capacity(2 * corners + 40);
    text.push_str("v 0 0 0\nv 1 0 0\nv 0 1 0\nf");
    for _ in 0..corners {
        text.push_str(" 1");
    }
    text.push('\n');
    match shadelab_io::parse_obj(&text, "huge.obj") {
        Err(LoadError::Syntax {
            line: 4, message, ..
        }) => {
            assert!(
                message.contains("more than 16777216 triangles"),
                "{message}"
            );
        }
        other => panic!("expected a syntax error at line 4, got {other:?}"),
    }
}

/// A zero normal makes a file's normals unusable (they are computed, as for
/// OBJ); a NaN normal is an error.
#[test]
fn zero_and_nan_file_normals() {
    let dir = tempfile::tempdir().unwrap();
    let (p, faces) = cube();
    let polys: Vec<Vec<u32>> = faces.iter().map(|f| f.to_vec()).collect();
    let mut normals: Vec<Vec3> = p.iter().map(|v| *v - Vec3::splat(0.5)).collect();
    let path = write(
        dir.path(),
        "good.ply",
        binary_ply(&p, &polys, Some(&normals), false),
    );
    assert!(load_ply(&path).unwrap().file_normals().is_some());
    normals[3] = Vec3::ZERO;
    let path = write(
        dir.path(),
        "zero.ply",
        binary_ply(&p, &polys, Some(&normals), false),
    );
    let mesh = load_ply(&path).unwrap();
    assert!(mesh.file_normals().is_none());
    assert_eq!(mesh.polygon_count(), 6);
    normals[3] = Vec3::new(0.0, f32::NAN, 1.0);
    let path = write(
        dir.path(),
        "nan.ply",
        binary_ply(&p, &polys, Some(&normals), true),
    );
    assert_invalid(load_ply(&path), &path, "normal 3");

    // glTF: the tetrahedron with one normal zeroed, then NaN.
    let mut buffer = tetra_buffer();
    let normal_at = 4 * 12 + 12; // the second vertex's normal
    buffer[normal_at..normal_at + 12].copy_from_slice(&f32_bytes([0.0, 0.0, 0.0]));
    let one = r#"[{"mesh":0}]"#;
    let path = write(
        dir.path(),
        "zero.glb",
        glb(&tetra_doc(None, one, "[0]").json(), &buffer),
    );
    let mesh = load_gltf(&path).unwrap();
    assert!(mesh.file_normals().is_none());
    buffer[normal_at..normal_at + 12].copy_from_slice(&f32_bytes([0.0, f32::NAN, 0.0]));
    let path = write(
        dir.path(),
        "nan.glb",
        glb(&tetra_doc(None, one, "[0]").json(), &buffer),
    );
    assert_invalid(load_gltf(&path), &path, "normal 1");
}
