//! PLY meshes (ASCII, binary little-endian and binary big-endian), read with
//! `ply-rs-bw`.
//!
//! The original `ply-rs` (0.1.3, its latest release) depends on
//! `linked-hash-map`, affected by CVE-2020-25573, and no release of it fixes
//! that; `ply-rs-bw` is the fork made to fix it, with the same API and
//! regular releases since (it also caps the preallocation for element and
//! list counts read from a file, and rejects negative list lengths). 3.0.3
//! is used because 4.x requires Rust 1.87 and this workspace supports 1.85.
//! Its ASCII grammar takes plain decimal numbers only (`1`, `-0.5`, `2e-3`;
//! not `.5`, `nan` or `inf`).
//!
//! What is read: the `vertex` element's `x`, `y`, `z` (any scalar type, float
//! or double in practice) and, when all three are present, `nx`, `ny`, `nz`,
//! which become the mesh's file normals (one per vertex, so each corner uses
//! its vertex's normal; a file where one of them is zero is treated as one
//! without normals, as for OBJ); the `face` element's `vertex_indices` (or
//! `vertex_index`) list of any integer type. Faces stay polygons. Every other
//! element and property (colours, texture coordinates, edges, materials) is
//! read past and ignored. Elements are parsed into small structs, not
//! `ply-rs-bw`'s string-keyed default element, to keep memory per vertex low.
//!
//! Before any element is read, the header's counts are checked against the
//! bytes after `end_header` (for binary files, the smallest size each element
//! can take; for ASCII, one line per element), so a header promising more
//! elements than the file holds fails at once, and so do counts beyond
//! [`Mesh::MAX_VERTICES`] vertices or [`Mesh::MAX_TRIANGLES`] faces. Memory
//! then stays within a small multiple of the file's size. `ply-rs-bw` was
//! not seen to panic on malformed input, so it is called directly.

use std::io::Cursor;
use std::path::Path;

use glam::Vec3;
use ply_rs_bw::parser::Parser;
use ply_rs_bw::ply::{
    ElementDef, Encoding, Header, Property, PropertyAccess, PropertyType, ScalarType,
};
use shadelab_core::{escape_message, escape_token, CornerNormals, Mesh};

use crate::input::{lone_cr_to_lf, read_capped};
use crate::mesh_file::{invalid, mesh_error, MAX_MESH_BYTES};
use crate::LoadError;

/// Reads a PLY file.
///
/// # Errors
/// [`LoadError`] naming the file: unreadable, too large, not PLY, a malformed
/// header, counts the data cannot hold, truncated or malformed data, missing
/// coordinates or faces, indices out of range, non-finite coordinates.
pub fn load_ply(path: &Path) -> Result<Mesh, LoadError> {
    let bytes = read_capped(path, MAX_MESH_BYTES)?;
    parse_ply(&bytes, &path.display().to_string())
}

/// Parses a PLY file's bytes; `name` is used in error messages.
///
/// # Errors
/// As [`load_ply`].
pub fn parse_ply(bytes: &[u8], name: &str) -> Result<Mesh, LoadError> {
    if !(bytes.starts_with(b"ply\n") || bytes.starts_with(b"ply\r")) {
        return Err(invalid(
            name,
            "byte 0: not a PLY file (it does not begin with the line `ply`)",
        ));
    }
    let bytes = &*unify_header_line_ends(bytes);
    let mut cursor = Cursor::new(bytes);
    let header = Parser::<Ignored>::new()
        .read_header(&mut cursor)
        .map_err(|e| {
            invalid(
                name,
                format!("PLY header: {}", escape_message(&e.to_string())),
            )
        })?;
    let data_start = cursor.position();
    // An element with nothing in it takes no bytes: its count would be
    // read past for ever.
    if let Some(empty) = header
        .elements
        .values()
        .find(|e| e.count > 0 && e.properties.is_empty())
    {
        return Err(invalid(
            name,
            format!(
                "PLY element `{}` declares {} elements but no properties: there is nothing to \
                 read (an element needs at least one property)",
                escape_token(&empty.name),
                empty.count
            ),
        ));
    }

    let vertex_def = header
        .elements
        .get("vertex")
        .ok_or_else(|| invalid(name, "PLY header declares no `vertex` element"))?;
    for axis in ["x", "y", "z"] {
        if !is_scalar(vertex_def, axis) {
            return Err(invalid(
                name,
                format!("PLY element `vertex` has no scalar property `{axis}`"),
            ));
        }
    }
    let with_normals = ["nx", "ny", "nz"].iter().all(|n| is_scalar(vertex_def, n));
    let face_def = header
        .elements
        .get("face")
        .filter(|f| f.count > 0)
        .ok_or_else(|| {
            invalid(
                name,
                "PLY file has no faces (no `face` element, or 0 faces)",
            )
        })?;
    let index_list = ["vertex_indices", "vertex_index"]
        .into_iter()
        .find(|p| face_def.properties.contains_key(*p))
        .ok_or_else(|| {
            invalid(
                name,
                "PLY element `face` has no `vertex_indices` (or `vertex_index`) property",
            )
        })?;
    match face_def.properties[index_list].data_type {
        PropertyType::List(_, ScalarType::Float | ScalarType::Double) | PropertyType::Scalar(_) => {
            return Err(invalid(
                name,
                format!("PLY property `face.{index_list}` must be a list of integers"),
            ));
        }
        PropertyType::List(..) => {}
    }
    let vertex_count = vertex_def.count;
    if vertex_count > Mesh::MAX_VERTICES {
        return Err(invalid(
            name,
            format!(
                "the PLY header declares {vertex_count} vertices; at most {} are supported",
                Mesh::MAX_VERTICES
            ),
        ));
    }
    if face_def.count > Mesh::MAX_TRIANGLES {
        return Err(invalid(
            name,
            format!(
                "the PLY header declares {} faces; at most {} triangles are supported",
                face_def.count,
                Mesh::MAX_TRIANGLES
            ),
        ));
    }
    check_counts(&header, &bytes[data_start as usize..], data_start, name)?;

    let mut positions = Vec::new();
    let mut normals = Vec::new();
    let mut polygons = Vec::new();
    for (element, def) in &header.elements {
        let start = cursor.position();
        let context = |e: std::io::Error| {
            invalid(
                name,
                format!(
                    "PLY element `{element}` ({} declared, data from byte {start}): {e}",
                    def.count
                ),
            )
        };
        match element.as_str() {
            "vertex" => {
                let vertices = Parser::<PlyVertex>::new()
                    .read_payload_for_element(&mut cursor, def, &header)
                    .map_err(context)?;
                positions = vertices.iter().map(|v| v.position.as_vec3()).collect();
                if with_normals {
                    normals = vertices.iter().map(|v| v.normal.as_vec3()).collect();
                }
            }
            "face" => {
                let faces = Parser::<PlyFace>::new()
                    .read_payload_for_element(&mut cursor, def, &header)
                    .map_err(context)?;
                polygons = Vec::with_capacity(faces.len());
                for (k, face) in faces.into_iter().enumerate() {
                    let bad = face.out_of_range.or_else(|| {
                        face.indices
                            .iter()
                            .find(|&&i| i as usize >= vertex_count)
                            .map(|&i| i64::from(i))
                    });
                    if let Some(i) = bad {
                        return Err(invalid(
                            name,
                            format!(
                                "PLY face {k} refers to vertex {i}, but there are {} vertices",
                                vertex_def.count
                            ),
                        ));
                    }
                    polygons.push(face.indices);
                }
            }
            _ => {
                Parser::<Ignored>::new()
                    .read_payload_for_element(&mut cursor, def, &header)
                    .map_err(context)?;
            }
        }
    }

    let mesh = Mesh::from_polygons(positions, polygons).map_err(mesh_error(name))?;
    // A non-finite normal is an error (from `with_file_normals`); a zero one
    // means the file's normals are not usable.
    if with_normals
        && normals
            .iter()
            .all(|n| !n.is_finite() || n.try_normalize().is_some())
    {
        let corner = mesh.corners().to_vec();
        mesh.with_file_normals(CornerNormals::new(normals, corner))
            .map_err(mesh_error(name))
    } else {
        Ok(mesh)
    }
}

/// The file with CR-only line ends made LF, where that is text: in the
/// header when its first line ends with a lone CR (up to `end_header` and
/// its CR, so binary data after it is left alone; one byte for one byte, so
/// offsets stay), and in the whole file when the header says `format ascii`.
fn unify_header_line_ends(bytes: &[u8]) -> std::borrow::Cow<'_, [u8]> {
    let cr_only = bytes.get(3) == Some(&b'\r') && bytes.get(4) != Some(&b'\n');
    let ascii = |header: &[u8]| {
        header.split(|&b| b == b'\n' || b == b'\r').any(|line| {
            line.split(|b| b.is_ascii_whitespace())
                .filter(|w| !w.is_empty())
                .take(2)
                .eq([&b"format"[..], b"ascii"])
        })
    };
    let end = |bytes: &[u8], terminator: &[u8]| {
        bytes
            .windows(terminator.len())
            .position(|w| w == terminator)
            .map(|k| k + terminator.len())
    };
    if cr_only {
        let Some(header_end) = end(bytes, b"\rend_header\r") else {
            return lone_cr_to_lf(bytes);
        };
        if ascii(&bytes[..header_end]) {
            return lone_cr_to_lf(bytes);
        }
        let mut out = bytes.to_vec();
        for b in &mut out[..header_end] {
            if *b == b'\r' {
                *b = b'\n';
            }
        }
        return std::borrow::Cow::Owned(out);
    }
    match end(bytes, b"end_header") {
        Some(header_end) if ascii(&bytes[..header_end]) => lone_cr_to_lf(bytes),
        _ => std::borrow::Cow::Borrowed(bytes),
    }
}

fn is_scalar(def: &ElementDef, property: &str) -> bool {
    matches!(
        def.properties.get(property).map(|p| &p.data_type),
        Some(PropertyType::Scalar(_))
    )
}

fn scalar_size(t: &ScalarType) -> u128 {
    match t {
        ScalarType::Char | ScalarType::UChar => 1,
        ScalarType::Short | ScalarType::UShort => 2,
        ScalarType::Int | ScalarType::UInt | ScalarType::Float => 4,
        ScalarType::Double => 8,
    }
}

/// Fails when the header's counts cannot fit in the data after it.
fn check_counts(
    header: &Header,
    data: &[u8],
    data_start: u64,
    name: &str,
) -> Result<(), LoadError> {
    let summary = || {
        header
            .elements
            .values()
            .map(|e| format!("{} `{}`", e.count, e.name))
            .collect::<Vec<_>>()
            .join(", ")
    };
    match header.encoding {
        Encoding::Ascii => {
            // One line per element.
            let lines = data.iter().filter(|&&b| b == b'\n').count() as u128
                + u128::from(data.last().is_some_and(|&b| b != b'\n'));
            let promised: u128 = header.elements.values().map(|e| e.count as u128).sum();
            if promised > lines {
                return Err(invalid(
                    name,
                    format!(
                        "the PLY header promises {} ({promised} lines of data), but only {lines} \
                         lines follow `end_header` (byte {data_start}): the file is truncated \
                         or the counts are wrong",
                        summary()
                    ),
                ));
            }
        }
        Encoding::BinaryLittleEndian | Encoding::BinaryBigEndian => {
            // A list takes at least its length field.
            let least: u128 = header
                .elements
                .values()
                .map(|e| {
                    let each: u128 = e
                        .properties
                        .values()
                        .map(|p| match &p.data_type {
                            PropertyType::Scalar(t) | PropertyType::List(t, _) => scalar_size(t),
                        })
                        .sum();
                    each * e.count as u128
                })
                .sum();
            if least > data.len() as u128 {
                return Err(invalid(
                    name,
                    format!(
                        "the PLY header promises {}, which take at least {least} bytes, but only \
                         {} bytes follow `end_header` (byte {data_start}): the file is \
                         truncated or the counts are wrong",
                        summary(),
                        data.len()
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// Three optional coordinates, as read (a `double` rounded to `f32`, the
/// precision of a [`Mesh`]).
#[derive(Default)]
struct Xyz([f32; 3]);

impl Xyz {
    fn as_vec3(&self) -> Vec3 {
        Vec3::from_array(self.0)
    }
}

/// A scalar property as `f64` (lists give `None`).
fn scalar(property: &Property) -> Option<f64> {
    Some(match *property {
        Property::Char(v) => v.into(),
        Property::UChar(v) => v.into(),
        Property::Short(v) => v.into(),
        Property::UShort(v) => v.into(),
        Property::Int(v) => v.into(),
        Property::UInt(v) => v.into(),
        Property::Float(v) => v.into(),
        Property::Double(v) => v,
        _ => return None,
    })
}

/// An integer list property as `i64`s (floats and scalars give `None`).
fn integers(property: Property) -> Option<Vec<i64>> {
    fn all<T: Into<i64>>(v: Vec<T>) -> Vec<i64> {
        v.into_iter().map(Into::into).collect()
    }
    Some(match property {
        Property::ListChar(v) => all(v),
        Property::ListUChar(v) => all(v),
        Property::ListShort(v) => all(v),
        Property::ListUShort(v) => all(v),
        Property::ListInt(v) => all(v),
        Property::ListUInt(v) => all(v),
        _ => return None,
    })
}

/// A `vertex` element: position and normal (zero when absent).
#[derive(Default)]
struct PlyVertex {
    position: Xyz,
    normal: Xyz,
}

impl PropertyAccess for PlyVertex {
    fn new() -> Self {
        Self::default()
    }

    fn set_property(&mut self, name: &str, property: Property) {
        let slot = match name {
            "x" => &mut self.position.0[0],
            "y" => &mut self.position.0[1],
            "z" => &mut self.position.0[2],
            "nx" => &mut self.normal.0[0],
            "ny" => &mut self.normal.0[1],
            "nz" => &mut self.normal.0[2],
            _ => return,
        };
        // The header check made these scalars.
        if let Some(v) = scalar(&property) {
            *slot = v as f32;
        }
    }
}

/// A `face` element: its vertex indices.
#[derive(Default)]
struct PlyFace {
    indices: Vec<u32>,
    /// An index that is negative or beyond `u32`, if any.
    out_of_range: Option<i64>,
    /// Whether `indices` came from `vertex_indices`, which wins over `vertex_index`.
    from_indices: bool,
}

impl PropertyAccess for PlyFace {
    fn new() -> Self {
        Self::default()
    }

    fn set_property(&mut self, name: &str, property: Property) {
        let preferred = name == "vertex_indices";
        if preferred || (name == "vertex_index" && !self.from_indices) {
            if let Some(indices) = integers(property) {
                self.out_of_range = indices.iter().copied().find(|&i| u32::try_from(i).is_err());
                self.indices = indices.iter().map(|&i| i as u32).collect();
                self.from_indices = preferred;
            }
        }
    }
}

/// Any other element: read past, nothing kept.
struct Ignored;

impl PropertyAccess for Ignored {
    fn new() -> Self {
        Ignored
    }
}
