//! STL meshes, ASCII and binary, read with `stl_io`.
//!
//! The encoding is told by content, never by extension: a file is binary when
//! it is at least 84 bytes long and `84 + 50 · count` equals its length, where
//! `count` is the little-endian `u32` at byte 80; otherwise it must be ASCII
//! STL (beginning with `solid`). So a binary file whose 80-byte header starts
//! with `solid`, as many exporters write, still loads. `stl_io`'s own probe
//! would take such a file for ASCII, so a binary file is handed to it with its
//! header blanked (the header carries no geometry). A binary file whose count
//! does not match its length is rejected before `stl_io` sees it, so a header
//! that claims 2^31 triangles fails at once and allocates nothing; so does a
//! true count beyond [`Mesh::MAX_TRIANGLES`].
//!
//! STL stores every triangle with its own three corners. `stl_io`'s
//! `IndexedMesh` welds corners whose coordinates have the same bits; this
//! module then also welds `-0.0` with `0.0`, so that exactly equal positions
//! share one vertex and vertex normals can be averaged across triangles.
//!
//! The facet normals in the file are ignored: exporters often write zeros or
//! stale values, and the winding of the corners (counter-clockwise seen from
//! outside) already gives each face its orientation. A loaded STL mesh
//! therefore has no file normals. The 2-byte attribute of binary facets and
//! the header text are ignored too. `stl_io` was not seen to panic on
//! malformed input, so it is called directly.

use std::collections::HashMap;
use std::io::{Read, Seek, SeekFrom};
use std::path::Path;

use glam::Vec3;
use shadelab_core::{escape_message, Mesh};

use crate::input::{lone_cr_to_lf, read_capped};
use crate::mesh_file::{invalid, mesh_error, MAX_MESH_BYTES};
use crate::LoadError;

/// Bytes before the first triangle of a binary STL: header and count.
const BINARY_HEADER: usize = 84;
/// Bytes of one binary STL triangle: normal, three corners, attribute.
const BINARY_TRIANGLE: usize = 50;

/// Reads an STL file, ASCII or binary.
///
/// # Errors
/// [`LoadError`] naming the file: unreadable, too large, a binary triangle
/// count that does not match the length, malformed ASCII, non-finite
/// coordinates, no triangles.
pub fn load_stl(path: &Path) -> Result<Mesh, LoadError> {
    let bytes = read_capped(path, MAX_MESH_BYTES)?;
    parse_stl(&bytes, &path.display().to_string())
}

/// Parses an STL file's bytes; `name` is used in error messages.
///
/// # Errors
/// As [`load_stl`].
pub fn parse_stl(bytes: &[u8], name: &str) -> Result<Mesh, LoadError> {
    let ascii = starts_with_solid(bytes);
    if bytes.len() < BINARY_HEADER {
        if ascii {
            return parse_ascii(bytes, name, None);
        }
        return Err(invalid(
            name,
            format!(
                "{} bytes: too short for binary STL (an 84-byte header comes first) \
                 and not ASCII STL (it does not begin with `solid`)",
                bytes.len()
            ),
        ));
    }
    let count = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]);
    let needed = BINARY_HEADER as u64 + BINARY_TRIANGLE as u64 * u64::from(count);
    if needed == bytes.len() as u64 {
        if count as usize > Mesh::MAX_TRIANGLES {
            return Err(invalid(
                name,
                format!(
                    "byte 80: the binary STL header declares {count} triangles; at most {} are supported",
                    Mesh::MAX_TRIANGLES
                ),
            ));
        }
        return parse_binary(bytes, name, count as usize);
    }
    let mismatch = format!(
        "byte 80: a binary STL header there claims {count} triangles, which take {needed} bytes, \
         but the file has {} bytes",
        bytes.len()
    );
    if ascii {
        parse_ascii(bytes, name, Some(&mismatch))
    } else {
        Err(invalid(
            name,
            format!("{mismatch} (and it is not ASCII STL: it does not begin with `solid`)"),
        ))
    }
}

/// Whether the text begins, after white space, with the word `solid`.
fn starts_with_solid(bytes: &[u8]) -> bool {
    let start = bytes
        .iter()
        .position(|b| !b.is_ascii_whitespace())
        .unwrap_or(bytes.len());
    let rest = &bytes[start..];
    rest.starts_with(b"solid") && rest.get(5).is_none_or(|b| b.is_ascii_whitespace())
}

fn parse_binary(bytes: &[u8], name: &str, count: usize) -> Result<Mesh, LoadError> {
    if count == 0 {
        return Err(invalid(name, "binary STL with 0 triangles: no faces"));
    }
    // Check the corners here, where the byte offset is known.
    for t in 0..count {
        let start = BINARY_HEADER + t * BINARY_TRIANGLE + 12;
        for k in 0..9 {
            let at = start + 4 * k;
            let v = f32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]]);
            if !v.is_finite() {
                return Err(invalid(
                    name,
                    format!(
                        "byte {at}: triangle {t}, corner {}: coordinate {v} is not a finite number",
                        k / 3
                    ),
                ));
            }
        }
    }
    let mut reader = BlankHeader { bytes, position: 0 };
    let indexed =
        stl_io::read_stl(&mut reader).map_err(|e| invalid(name, format!("binary STL: {e}")))?;
    build(indexed, name)
}

fn parse_ascii(bytes: &[u8], name: &str, not_binary: Option<&str>) -> Result<Mesh, LoadError> {
    let explain = |message: String| match not_binary {
        Some(why) => format!("{message} (read as ASCII STL because it is not binary: {why})"),
        None => message,
    };
    // Old Mac files end their lines with a lone CR; `stl_io` splits at LF.
    let bytes = &*lone_cr_to_lf(bytes);
    // `stl_io` wants the first line to start with exactly "solid " (a name
    // after it); "solid" alone, or leading blanks, are also found in the wild.
    let start = bytes
        .iter()
        .position(|b| !b.is_ascii_whitespace())
        .unwrap_or(bytes.len());
    let first_line_end = bytes[start..]
        .iter()
        .position(|&b| b == b'\n')
        .map_or(bytes.len(), |p| start + p + 1);
    let mut text = b"solid shadelab\n".to_vec();
    text.extend_from_slice(&bytes[first_line_end..]);
    let indexed = stl_io::read_stl(&mut std::io::Cursor::new(text)).map_err(|e| {
        invalid(
            name,
            explain(format!("ASCII STL: {}", escape_message(&e.to_string()))),
        )
    })?;
    if indexed.faces.is_empty() {
        return Err(invalid(
            name,
            explain("ASCII STL with no facets: no faces".into()),
        ));
    }
    build(indexed, name)
}

/// Welds `-0.0` with `0.0` on top of `stl_io`'s bitwise welding, and builds the mesh.
fn build(indexed: stl_io::IndexedMesh, name: &str) -> Result<Mesh, LoadError> {
    let mut positions: Vec<Vec3> = Vec::with_capacity(indexed.vertices.len());
    let mut seen: HashMap<[u32; 3], u32> = HashMap::with_capacity(indexed.vertices.len());
    let remap: Vec<u32> = indexed
        .vertices
        .iter()
        .map(|v| {
            // Adding +0.0 turns -0.0 into +0.0 and leaves every other value alone.
            let p = Vec3::new(v[0] + 0.0, v[1] + 0.0, v[2] + 0.0);
            *seen
                .entry([p.x.to_bits(), p.y.to_bits(), p.z.to_bits()])
                .or_insert_with(|| {
                    positions.push(p);
                    positions.len() as u32 - 1
                })
        })
        .collect();
    let polygons = indexed
        .faces
        .iter()
        .map(|f| f.vertices.map(|i| remap[i]))
        .collect::<Vec<_>>();
    Mesh::from_polygons(positions, polygons).map_err(mesh_error(name))
}

/// The file's bytes with the 80-byte header read as zeros, so that `stl_io`'s
/// ASCII probe (which looks for `solid `) cannot mistake a binary file.
struct BlankHeader<'a> {
    bytes: &'a [u8],
    position: usize,
}

impl Read for BlankHeader<'_> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let rest = self.bytes.get(self.position..).unwrap_or(&[]);
        let n = rest.len().min(buf.len());
        buf[..n].copy_from_slice(&rest[..n]);
        for (k, b) in buf[..n].iter_mut().enumerate() {
            match self.position + k {
                // A line break first: the probe reads one empty line.
                0 => *b = b'\n',
                1..80 => *b = 0,
                _ => {}
            }
        }
        self.position += n;
        Ok(n)
    }
}

impl Seek for BlankHeader<'_> {
    fn seek(&mut self, to: SeekFrom) -> std::io::Result<u64> {
        let target = match to {
            SeekFrom::Start(p) => Some(p),
            SeekFrom::Current(d) => (self.position as u64).checked_add_signed(d),
            SeekFrom::End(d) => (self.bytes.len() as u64).checked_add_signed(d),
        };
        let target = target.ok_or_else(|| {
            std::io::Error::new(std::io::ErrorKind::InvalidInput, "seek before the start")
        })?;
        self.position = usize::try_from(target).unwrap_or(usize::MAX);
        Ok(target)
    }
}
