//! Writers for every mesh format, shared by the I/O tests: each test writes
//! the files it reads. Independent of the loaders: plain byte layouts from
//! the formats' specifications.
#![allow(dead_code)]

mod fixtures;
mod scenes;

// Each test binary uses some of these.
#[allow(unused_imports)]
pub use fixtures::*;
#[allow(unused_imports)]
pub use scenes::*;

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use glam::Vec3;
use shadelab_core::Mesh;

/// Writes `bytes` as `name` (which may name a subdirectory) in `dir`.
pub fn write(dir: &Path, name: &str, bytes: impl AsRef<[u8]>) -> PathBuf {
    let path = dir.join(name);
    if let Some(parent) = path.parent() {
        std::fs::create_dir_all(parent).unwrap();
    }
    std::fs::write(&path, bytes).unwrap();
    path
}

pub fn binary_stl(header: &[u8], triangles: &[[Vec3; 3]]) -> Vec<u8> {
    let mut out = vec![0u8; 80];
    out[..header.len()].copy_from_slice(header);
    out.extend_from_slice(&(triangles.len() as u32).to_le_bytes());
    for t in triangles {
        // A deliberately wrong facet normal: the loader ignores it.
        for v in [Vec3::new(9.0, 9.0, 9.0), t[0], t[1], t[2]] {
            for c in v.to_array() {
                out.extend_from_slice(&c.to_le_bytes());
            }
        }
        out.extend_from_slice(&[0, 0]);
    }
    out
}

pub fn ascii_stl(first_line: &str, triangles: &[[Vec3; 3]]) -> String {
    let mut s = format!("{first_line}\n");
    for t in triangles {
        s += "  facet normal 0 0 0\n    outer loop\n";
        for v in t {
            s += &format!("      vertex {} {} {}\n", v.x, v.y, v.z);
        }
        s += "    endloop\n  endfacet\n";
    }
    s + "endsolid t\n"
}

/// A binary PLY: float positions, optional float normals, uchar/int face lists.
pub fn binary_ply(
    positions: &[Vec3],
    polygons: &[Vec<u32>],
    normals: Option<&[Vec3]>,
    big_endian: bool,
) -> Vec<u8> {
    let mut header = format!(
        "ply\nformat binary_{}_endian 1.0\ncomment written by a test\nelement vertex {}\n\
         property float x\nproperty float y\nproperty float z\n",
        if big_endian { "big" } else { "little" },
        positions.len()
    );
    if normals.is_some() {
        header += "property float nx\nproperty float ny\nproperty float nz\n";
    }
    header += &format!(
        "element face {}\nproperty list uchar int vertex_indices\nend_header\n",
        polygons.len()
    );
    let mut out = header.into_bytes();
    let f32b = |v: f32| {
        if big_endian {
            v.to_be_bytes()
        } else {
            v.to_le_bytes()
        }
    };
    for (k, p) in positions.iter().enumerate() {
        for c in p.to_array() {
            out.extend_from_slice(&f32b(c));
        }
        if let Some(n) = normals {
            for c in n[k].to_array() {
                out.extend_from_slice(&f32b(c));
            }
        }
    }
    for poly in polygons {
        out.push(poly.len() as u8);
        for &i in poly {
            let i = i as i32;
            out.extend_from_slice(&if big_endian {
                i.to_be_bytes()
            } else {
                i.to_le_bytes()
            });
        }
    }
    out
}

/// A GLB container around `json` and `bin`.
pub fn glb(json: &str, bin: &[u8]) -> Vec<u8> {
    let mut json = json.as_bytes().to_vec();
    while !json.len().is_multiple_of(4) {
        json.push(b' ');
    }
    let mut bin = bin.to_vec();
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = Vec::new();
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(json.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&json);
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&bin);
    out
}

pub fn f32_bytes(values: impl IntoIterator<Item = f32>) -> Vec<u8> {
    values.into_iter().flat_map(f32::to_le_bytes).collect()
}

pub fn data_uri(bytes: &[u8]) -> String {
    use base64::Engine;
    format!(
        "data:application/octet-stream;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(bytes)
    )
}

/// Each triangle (after fan triangulation) as its corners' position bits,
/// rotated to start at the smallest corner (keeping the winding), sorted.
pub fn triangle_set(mesh: &Mesh) -> Vec<[[u32; 3]; 3]> {
    let p = mesh.positions();
    let mut out = Vec::new();
    for f in 0..mesh.polygon_count() {
        let poly = mesh.polygon(f);
        for k in 1..poly.len() - 1 {
            let t = [poly[0], poly[k], poly[k + 1]]
                .map(|i| p[i as usize].to_array().map(|c| (c + 0.0).to_bits()));
            let m = (0..3).min_by_key(|&r| t[r]).unwrap();
            out.push([t[m], t[(m + 1) % 3], t[(m + 2) % 3]]);
        }
    }
    out.sort_unstable();
    out
}

pub fn fan(mesh: &Mesh) -> Vec<[Vec3; 3]> {
    let p = mesh.positions();
    let mut out = Vec::new();
    for f in 0..mesh.polygon_count() {
        let poly = mesh.polygon(f);
        for k in 1..poly.len() - 1 {
            out.push([poly[0], poly[k], poly[k + 1]].map(|i| p[i as usize]));
        }
    }
    out
}

/// PLY text (`format ascii 1.0`): float positions, optional float normals,
/// uchar/int face lists. Numbers are written with Rust's shortest exact form.
pub fn ascii_ply(positions: &[Vec3], polygons: &[Vec<u32>], normals: Option<&[Vec3]>) -> String {
    let mut out = format!(
        "ply\nformat ascii 1.0\nelement vertex {}\nproperty float x\nproperty float y\n\
         property float z\n",
        positions.len()
    );
    if normals.is_some() {
        out += "property float nx\nproperty float ny\nproperty float nz\n";
    }
    out += &format!(
        "element face {}\nproperty list uchar int vertex_indices\nend_header\n",
        polygons.len()
    );
    for (k, p) in positions.iter().enumerate() {
        out += &format!("{} {} {}", p.x, p.y, p.z);
        if let Some(n) = normals {
            out += &format!(" {} {} {}", n[k].x, n[k].y, n[k].z);
        }
        out.push('\n');
    }
    for poly in polygons {
        out += &poly.len().to_string();
        for i in poly {
            out += &format!(" {i}");
        }
        out.push('\n');
    }
    out
}

/// Where a glTF file's one buffer lives.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GltfBuffer {
    /// A base64 data URI inside the `.gltf` JSON.
    Embedded,
    /// A `.bin` file beside the `.gltf` (the name is given).
    External(&'static str),
    /// The binary chunk of a `.glb`.
    Glb,
}

/// An indexed triangle list as glTF: `(json, bin)`; for [`GltfBuffer::Glb`]
/// the JSON goes into [`glb`] with `bin`, for `External` `bin` is the file's
/// content, for `Embedded` the JSON holds it already.
pub fn mesh_gltf(
    positions: &[Vec3],
    triangles: &[[u32; 3]],
    normals: Option<&[Vec3]>,
    buffer: GltfBuffer,
) -> (String, Vec<u8>) {
    let mut bin = f32_bytes(positions.iter().flat_map(|v| v.to_array()));
    let positions_len = bin.len();
    let mut views = vec![format!(r#"{{"buffer":0,"byteLength":{positions_len}}}"#)];
    let (lo, hi) = positions.iter().fold(
        (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
        |(lo, hi), &v| (lo.min(v), hi.max(v)),
    );
    let mut accessors = vec![format!(
        r#"{{"bufferView":0,"componentType":5126,"count":{},"type":"VEC3","min":{:?},"max":{:?}}}"#,
        positions.len(),
        lo.to_array(),
        hi.to_array()
    )];
    let mut attributes = r#""POSITION":0"#.to_string();
    if let Some(n) = normals {
        let at = bin.len();
        bin.extend(f32_bytes(n.iter().flat_map(|v| v.to_array())));
        views.push(format!(
            r#"{{"buffer":0,"byteOffset":{at},"byteLength":{}}}"#,
            bin.len() - at
        ));
        accessors.push(format!(
            r#"{{"bufferView":1,"componentType":5126,"count":{},"type":"VEC3"}}"#,
            n.len()
        ));
        attributes += r#","NORMAL":1"#;
    }
    let at = bin.len();
    bin.extend(triangles.iter().flatten().flat_map(|i| i.to_le_bytes()));
    views.push(format!(
        r#"{{"buffer":0,"byteOffset":{at},"byteLength":{}}}"#,
        bin.len() - at
    ));
    accessors.push(format!(
        r#"{{"bufferView":{},"componentType":5125,"count":{},"type":"SCALAR"}}"#,
        views.len() - 1,
        triangles.len() * 3
    ));
    let uri = match buffer {
        GltfBuffer::Embedded => format!(r#","uri":"{}""#, data_uri(&bin)),
        GltfBuffer::External(file) => format!(r#","uri":"{file}""#),
        GltfBuffer::Glb => String::new(),
    };
    let json = format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],
        "meshes":[{{"primitives":[{{"attributes":{{{attributes}}},"indices":{}}}]}}],
        "buffers":[{{"byteLength":{}{uri}}}],"bufferViews":[{}],"accessors":[{}]}}"#,
        accessors.len() - 1,
        bin.len(),
        views.join(","),
        accessors.join(",")
    );
    (json, bin)
}

/// OBJ text: `v` lines, `vn` lines and faces (`f v//vn` when normals are
/// given as a table and one index per corner).
pub fn obj_text(
    positions: &[Vec3],
    polygons: &[Vec<u32>],
    normals: Option<(&[Vec3], &[u32])>,
) -> String {
    let mut out = String::new();
    for p in positions {
        out += &format!("v {} {} {}\n", p.x, p.y, p.z);
    }
    if let Some((table, _)) = normals {
        for n in table {
            out += &format!("vn {} {} {}\n", n.x, n.y, n.z);
        }
    }
    let mut corner = 0;
    for poly in polygons {
        out.push('f');
        for &i in poly {
            match normals {
                Some((_, per_corner)) => out += &format!(" {}//{}", i + 1, per_corner[corner] + 1),
                None => out += &format!(" {}", i + 1),
            }
            corner += 1;
        }
        out.push('\n');
    }
    out
}

/// A mesh's polygons as vectors of vertex indices.
pub fn polygons(mesh: &Mesh) -> Vec<Vec<u32>> {
    (0..mesh.polygon_count())
        .map(|f| mesh.polygon(f).to_vec())
        .collect()
}

/// Fan triangulation, `[v0, vk, vk+1]`, as the renderer's fans draw it.
pub fn fan_indices(polygons: &[Vec<u32>]) -> Vec<[u32; 3]> {
    polygons
        .iter()
        .flat_map(|p| (1..p.len() - 1).map(move |k| [p[0], p[k], p[k + 1]]))
        .collect()
}

/// One vertex per distinct (position, normal) pair, as formats with one
/// normal per vertex need: `(positions, normals, polygons)`.
pub fn split_by_normal(
    positions: &[Vec3],
    polygons: &[Vec<u32>],
    normals: &[Vec3],
    corner_normal: &[u32],
) -> (Vec<Vec3>, Vec<Vec3>, Vec<Vec<u32>>) {
    let mut index: HashMap<(u32, u32), u32> = HashMap::new();
    let (mut p, mut n) = (Vec::new(), Vec::new());
    let mut corner = 0;
    let out = polygons
        .iter()
        .map(|poly| {
            poly.iter()
                .map(|&v| {
                    let key = (v, corner_normal[corner]);
                    corner += 1;
                    *index.entry(key).or_insert_with(|| {
                        p.push(positions[key.0 as usize]);
                        n.push(normals[key.1 as usize]);
                        p.len() as u32 - 1
                    })
                })
                .collect()
        })
        .collect();
    (p, n, out)
}

/// Positions with equal coordinates (`-0.0` equal to `0.0`) merged into one
/// vertex, as an STL file (which keeps no vertex identity) can only give.
pub fn weld(positions: &[Vec3], polygons: &[Vec<u32>]) -> (Vec<Vec3>, Vec<Vec<u32>>) {
    let mut index: HashMap<[u32; 3], u32> = HashMap::new();
    let mut out = Vec::new();
    let remap: Vec<u32> = positions
        .iter()
        .map(|p| {
            let key = p.to_array().map(|c| (c + 0.0).to_bits());
            *index.entry(key).or_insert_with(|| {
                out.push(*p);
                out.len() as u32 - 1
            })
        })
        .collect();
    let polys = polygons
        .iter()
        .map(|poly| poly.iter().map(|&v| remap[v as usize]).collect())
        .collect();
    (out, polys)
}

/// `../shared/models/` beside the project, or `None` with a printed note.
pub fn shared_models() -> Option<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/models");
    if dir.is_dir() {
        Some(dir)
    } else {
        eprintln!(
            "note: {} is absent; skipping the real-model checks",
            dir.display()
        );
        None
    }
}
