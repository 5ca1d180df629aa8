//! The shapes the format tests write (a tetrahedron, a cube), a glTF
//! document builder, and the assertions they share.

#![allow(dead_code)]

use std::path::Path;

use glam::Vec3;
use shadelab_core::Mesh;
use shadelab_io::LoadError;

use super::*;

/// A tetrahedron wound counter-clockwise seen from outside.
pub const TETRA: [[f32; 3]; 4] = [[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]];
pub const TETRA_FACES: [[u32; 3]; 4] = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];

pub fn tetra_triangles() -> Vec<[Vec3; 3]> {
    TETRA_FACES
        .iter()
        .map(|f| f.map(|i| Vec3::from_array(TETRA[i as usize])))
        .collect()
}

/// A unit cube: 8 corners, 6 quads wound counter-clockwise from outside.
pub fn cube() -> (Vec<Vec3>, Vec<[u32; 4]>) {
    let p = (0..8)
        .map(|i| Vec3::new((i & 1) as f32, ((i >> 1) & 1) as f32, ((i >> 2) & 1) as f32))
        .collect();
    let faces = vec![
        [0, 2, 3, 1], // z = 0
        [4, 5, 7, 6], // z = 1
        [0, 1, 5, 4], // y = 0
        [2, 6, 7, 3], // y = 1
        [0, 4, 6, 2], // x = 0
        [1, 3, 7, 5], // x = 1
    ];
    (p, faces)
}

/// glTF JSON for one buffer of `buffer_len` bytes at `uri` (None: the GLB
/// chunk) holding positions (`count` VEC3 floats, then optionally as many
/// normals) and optionally u16 indices after them; `extra` adds to the root.
pub struct GltfDoc<'a> {
    pub uri: Option<&'a str>,
    pub buffer_len: usize,
    pub count: usize,
    pub normals: bool,
    pub indices: Option<usize>,
    pub nodes: &'a str,
    pub scene_nodes: &'a str,
    pub mode: u32,
}

impl GltfDoc<'_> {
    pub fn json(&self) -> String {
        let positions_len = self.count * 12;
        let mut views = vec![format!(
            r#"{{"buffer":0,"byteOffset":0,"byteLength":{positions_len}}}"#
        )];
        let mut accessors = vec![format!(
            r#"{{"bufferView":0,"componentType":5126,"count":{},"type":"VEC3","min":[0,0,0],"max":[1,1,1]}}"#,
            self.count
        )];
        let mut attributes = r#""POSITION":0"#.to_string();
        let mut offset = positions_len;
        if self.normals {
            views.push(format!(
                r#"{{"buffer":0,"byteOffset":{offset},"byteLength":{positions_len}}}"#
            ));
            accessors.push(format!(
                r#"{{"bufferView":1,"componentType":5126,"count":{},"type":"VEC3"}}"#,
                self.count
            ));
            attributes += r#","NORMAL":1"#;
            offset += positions_len;
        }
        let mut indices = String::new();
        if let Some(n) = self.indices {
            views.push(format!(
                r#"{{"buffer":0,"byteOffset":{offset},"byteLength":{}}}"#,
                n * 2
            ));
            accessors.push(format!(
                r#"{{"bufferView":{},"componentType":5123,"count":{n},"type":"SCALAR"}}"#,
                views.len() - 1
            ));
            indices = format!(r#","indices":{}"#, accessors.len() - 1);
        }
        let uri = self
            .uri
            .map(|u| format!(r#","uri":"{u}""#))
            .unwrap_or_default();
        format!(
            r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":{}}}],"nodes":{},
            "meshes":[{{"primitives":[{{"attributes":{{{attributes}}}{indices},"mode":{}}}]}}],
            "buffers":[{{"byteLength":{}{uri}}}],"bufferViews":[{}],"accessors":[{}]}}"#,
            self.scene_nodes,
            self.nodes,
            self.mode,
            self.buffer_len,
            views.join(","),
            accessors.join(",")
        )
    }
}

/// The tetrahedron as a glTF buffer: positions, normals (corner directions), u16 indices.
pub fn tetra_buffer() -> Vec<u8> {
    let mut b = f32_bytes(TETRA.iter().flatten().copied());
    let normals = [[-1., -1., -1.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]];
    b.extend(f32_bytes(normals.iter().flatten().copied()));
    for i in TETRA_FACES.iter().flatten() {
        b.extend_from_slice(&(*i as u16).to_le_bytes());
    }
    b
}

pub fn tetra_doc<'a>(uri: Option<&'a str>, nodes: &'a str, scene_nodes: &'a str) -> GltfDoc<'a> {
    GltfDoc {
        uri,
        buffer_len: 4 * 12 * 2 + 12 * 2,
        count: 4,
        normals: true,
        indices: Some(12),
        nodes,
        scene_nodes,
        mode: 4,
    }
}

/// Asserts an `Invalid` error whose message names `path` and contains `needle`.
#[track_caller]
pub fn assert_invalid(result: Result<Mesh, LoadError>, path: &Path, needle: &str) {
    let e = result.expect_err("the load should fail");
    let text = e.to_string();
    assert!(
        matches!(e, LoadError::Invalid { .. }),
        "expected Invalid, got {e:?}"
    );
    assert!(
        text.contains(&path.display().to_string()),
        "message does not name the file: {text}"
    );
    assert!(
        text.to_lowercase().contains(&needle.to_lowercase()),
        "message lacks {needle:?}: {text}"
    );
}

pub fn sorted_positions(mesh: &Mesh) -> Vec<[u32; 3]> {
    let mut v: Vec<_> = mesh
        .positions()
        .iter()
        .map(|p| p.to_array().map(|c| (c + 0.0).to_bits()))
        .collect();
    v.sort_unstable();
    v
}

/// Root node 0 (translated, with child 1 scaled by 2 holding the mesh) and
/// root node 2 holding the mesh untransformed.
pub const TWO_NODES: &str =
    r#"[{"children":[1],"translation":[10,0,0]},{"mesh":0,"scale":[2,2,2]},{"mesh":0}]"#;
