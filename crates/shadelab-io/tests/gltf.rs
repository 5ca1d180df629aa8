//! glTF 2.0 loading (`.gltf` and `.glb`) on files written here: node
//! transforms and instancing, external buffers, mirroring, and every
//! malformed document refused with an error naming what is wrong.

mod common;

use common::*;
use glam::Vec3;
use shadelab_io::{load_gltf, load_mesh};

#[test]
fn gltf_embedded_with_node_transforms() {
    let dir = tempfile::tempdir().unwrap();
    let uri = data_uri(&tetra_buffer());
    let path = write(
        dir.path(),
        "tetra.gltf",
        tetra_doc(Some(&uri), TWO_NODES, "[0,2]").json(),
    );
    let mesh = load_mesh(&path).unwrap();
    assert_eq!(mesh.positions().len(), 8);
    assert_eq!(mesh.polygon_count(), 8);
    for (k, v) in TETRA.iter().enumerate() {
        let v = Vec3::from_array(*v);
        assert_eq!(mesh.positions()[k], v * 2.0 + Vec3::X * 10.0);
        assert_eq!(mesh.positions()[4 + k], v);
    }
    assert_eq!(mesh.polygon(4), &[4, 6, 5]);
    let normals = mesh.file_normals().expect("every primitive has NORMAL");
    assert_eq!(normals.corner(), mesh.corners());
    assert!((normals.normals[0] - Vec3::splat(-1.0).normalize()).length() < 1e-6);
}

#[test]
fn gltf_external_buffer_and_mirroring() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "tetra data.bin", tetra_buffer());
    // A non-uniform scale and a mirror: normals by the inverse transpose, winding reversed.
    let nodes = r#"[{"mesh":0,"scale":[-1,2,1]}]"#;
    let path = write(
        dir.path(),
        "tetra.gltf",
        tetra_doc(Some("tetra%20data.bin"), nodes, "[0]").json(),
    );
    let mesh = load_gltf(&path).unwrap();
    assert_eq!(mesh.positions()[1], Vec3::new(-1.0, 0.0, 0.0));
    assert_eq!(mesh.positions()[2], Vec3::new(0.0, 2.0, 0.0));
    assert_eq!(mesh.polygon(0), &[0, 1, 2], "file order 0 2 1, reversed");
    let n = &mesh.file_normals().unwrap().normals;
    assert!((n[0] - Vec3::new(1.0, -0.5, -1.0).normalize()).length() < 1e-6);
}

#[test]
fn glb_without_normals_or_indices() {
    let dir = tempfile::tempdir().unwrap();
    let triangles = tetra_triangles();
    let bin = f32_bytes(triangles.iter().flatten().flat_map(|v| v.to_array()));
    let doc = GltfDoc {
        uri: None,
        buffer_len: bin.len(),
        count: 12,
        normals: false,
        indices: None,
        nodes: r#"[{"mesh":0}]"#,
        scene_nodes: "[0]",
        mode: 4,
    };
    let path = write(dir.path(), "tetra.GLB", glb(&doc.json(), &bin));
    let mesh = load_mesh(&path).unwrap();
    assert_eq!(mesh.positions().len(), 12, "glTF vertices are not welded");
    assert_eq!(mesh.polygon_count(), 4);
    assert!(mesh.file_normals().is_none());
    assert_eq!(fan(&mesh), triangles);
}

#[test]
fn gltf_errors() {
    let dir = tempfile::tempdir().unwrap();
    let buffer = tetra_buffer();
    let uri = data_uri(&buffer);
    let one = r#"[{"mesh":0}]"#;

    let path = write(dir.path(), "garbage.gltf", "{ not json");
    assert_invalid(load_gltf(&path), &path, "not a valid glTF");
    let path = write(dir.path(), "magic.glb", b"glTX\x02\0\0\0\x0c\0\0\0");
    assert_invalid(load_gltf(&path), &path, "not a valid glTF");
    let good_glb = glb(&tetra_doc(None, one, "[0]").json(), &buffer);
    let path = write(dir.path(), "cut.glb", &good_glb[..good_glb.len() - 40]);
    assert_invalid(load_gltf(&path), &path, "not a valid glTF");
    let path = write(dir.path(), "ok.glb", &good_glb);
    assert_eq!(load_gltf(&path).unwrap().polygon_count(), 4);

    // A POSITION naming a missing accessor (gltf-json's validation panics on it).
    let json = tetra_doc(Some(&uri), one, "[0]")
        .json()
        .replace(r#""POSITION":0"#, r#""POSITION":9"#);
    let path = write(dir.path(), "no_accessor.gltf", json);
    assert_invalid(load_gltf(&path), &path, "names accessor 9");

    // byteLength larger than the data.
    let mut doc = tetra_doc(Some(&uri), one, "[0]");
    doc.buffer_len += 100;
    let path = write(dir.path(), "short_buffer.gltf", doc.json());
    assert_invalid(load_gltf(&path), &path, "byteLength");

    // An accessor count that lies.
    let json = tetra_doc(Some(&uri), one, "[0]").json().replace(
        r#""count":4,"type":"VEC3","min""#,
        r#""count":400000000,"type":"VEC3","min""#,
    );
    let path = write(dir.path(), "count.gltf", json);
    assert_invalid(load_gltf(&path), &path, "past the end of buffer view");

    // An index out of range.
    let mut bad = buffer.clone();
    let at = bad.len() - 2;
    bad[at..].copy_from_slice(&7u16.to_le_bytes());
    let bad_uri = data_uri(&bad);
    let path = write(
        dir.path(),
        "index.gltf",
        tetra_doc(Some(&bad_uri), one, "[0]").json(),
    );
    assert_invalid(
        load_gltf(&path),
        &path,
        "is 7, but the primitive has 4 vertices",
    );

    // A NaN position.
    let mut bad = buffer.clone();
    bad[4..8].copy_from_slice(&f32::NAN.to_le_bytes());
    let bad_uri = data_uri(&bad);
    let path = write(
        dir.path(),
        "nan.gltf",
        tetra_doc(Some(&bad_uri), one, "[0]").json(),
    );
    assert_invalid(load_gltf(&path), &path, "not a finite number");

    // No triangles: points only, or no node with a mesh.
    let mut doc = tetra_doc(Some(&uri), one, "[0]");
    doc.mode = 0;
    let path = write(dir.path(), "points.gltf", doc.json());
    assert_invalid(load_gltf(&path), &path, "no triangles");
    let path = write(
        dir.path(),
        "empty.gltf",
        tetra_doc(Some(&uri), "[{}]", "[0]").json(),
    );
    assert_invalid(load_gltf(&path), &path, "no triangles");

    // Missing external buffer; other URI schemes.
    let path = write(
        dir.path(),
        "missing.gltf",
        tetra_doc(Some("nope.bin"), one, "[0]").json(),
    );
    assert_invalid(load_gltf(&path), &path, "nope.bin");
    let path = write(
        dir.path(),
        "http.gltf",
        tetra_doc(Some("http://example.invalid/a.bin"), one, "[0]").json(),
    );
    assert_invalid(load_gltf(&path), &path, "only relative file URIs");
    let path = write(
        dir.path(),
        "bad64.gltf",
        tetra_doc(Some("data:application/octet-stream;base64,@@@"), one, "[0]").json(),
    );
    assert_invalid(load_gltf(&path), &path, "base64");
}
