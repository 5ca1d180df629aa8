//! Wavefront OBJ meshes, read with `tobj`.
//!
//! `tobj` does the loading; a line-by-line check runs first so that a bad
//! file is reported with its line number (which `tobj` does not give) and so
//! that faces with and without `vn` are told apart: file normals are kept
//! only when every face corner has one. Faces keep their polygons (no
//! triangulation); objects and groups are merged into one mesh; materials,
//! texture coordinates, points and lines are ignored.

use std::path::Path;

use glam::Vec3;
use shadelab_core::{CornerNormals, Mesh};

use crate::LoadError;

/// Largest OBJ file read, in bytes (1 GiB).
pub const MAX_OBJ_BYTES: u64 = 1 << 30;

/// Reads an OBJ file.
///
/// # Errors
/// [`LoadError`] naming the file, and the line for syntax errors, bad
/// indices and non-finite coordinates.
pub fn load_obj(path: &Path) -> Result<Mesh, LoadError> {
    let name = path.display().to_string();
    let size = std::fs::metadata(path)
        .map_err(|source| LoadError::Io {
            path: name.clone(),
            source,
        })?
        .len();
    if size > MAX_OBJ_BYTES {
        return Err(LoadError::TooLarge {
            path: name,
            bytes: size,
            limit: MAX_OBJ_BYTES,
        });
    }
    let bytes = std::fs::read(path).map_err(|source| LoadError::Io {
        path: name.clone(),
        source,
    })?;
    let text = String::from_utf8(bytes).map_err(|e| LoadError::Invalid {
        path: name.clone(),
        message: format!(
            "not UTF-8 text (invalid byte at offset {})",
            e.utf8_error().valid_up_to()
        ),
    })?;
    parse_obj(&text, &name)
}

/// Parses OBJ text; `name` is used in error messages.
///
/// # Errors
/// As [`load_obj`].
pub fn parse_obj(text: &str, name: &str) -> Result<Mesh, LoadError> {
    let summary = check(text, name)?;
    let options = tobj::LoadOptions {
        single_index: false,
        triangulate: false,
        ignore_points: true,
        ignore_lines: true,
    };
    // `tobj` reads only the checked statements: it knows neither comments
    // after a statement nor continued lines, and what shadelab ignores
    // (materials, lines, colours) cannot make it fail.
    let (models, _materials) =
        tobj::load_obj_buf(&mut summary.statements.as_bytes(), &options, |_| {
            Err(tobj::LoadError::MaterialParseError)
        })
        .map_err(|e| LoadError::Invalid {
            path: name.to_owned(),
            message: e.to_string(),
        })?;

    let mut positions = Vec::new();
    let mut polygons: Vec<Vec<u32>> = Vec::new();
    let mut normals = Vec::new();
    let mut corner_normals = Vec::new();
    for model in &models {
        let m = &model.mesh;
        let base = positions.len() as u32;
        let normal_base = normals.len() as u32;
        positions.extend(
            m.positions
                .chunks_exact(3)
                .map(|p| Vec3::new(p[0], p[1], p[2])),
        );
        normals.extend(
            m.normals
                .chunks_exact(3)
                .map(|n| Vec3::new(n[0], n[1], n[2])),
        );
        let arities: Vec<usize> = if m.face_arities.is_empty() {
            vec![3; m.indices.len() / 3]
        } else {
            m.face_arities.iter().map(|&a| a as usize).collect()
        };
        let mut start = 0;
        for arity in arities {
            polygons.push(
                m.indices[start..start + arity]
                    .iter()
                    .map(|&i| base + i)
                    .collect(),
            );
            if m.normal_indices.len() == m.indices.len() {
                corner_normals.extend(
                    m.normal_indices[start..start + arity]
                        .iter()
                        .map(|&i| normal_base + i),
                );
            }
            start += arity;
        }
    }
    let invalid = |e: shadelab_core::MeshError| LoadError::Invalid {
        path: name.to_owned(),
        message: e.to_string(),
    };
    let mesh = Mesh::from_polygons(positions, polygons).map_err(invalid)?;
    if summary.every_corner_has_normal && corner_normals.len() == mesh.corners().len() {
        // A file whose normals include a zero vector has no usable normals:
        // it is treated like a file without them, and normals are computed.
        let with_normals = mesh.clone().with_file_normals(CornerNormals {
            normals,
            corner: corner_normals,
        });
        Ok(with_normals.unwrap_or(mesh))
    } else {
        Ok(mesh)
    }
}

struct Summary {
    every_corner_has_normal: bool,
    /// The `v`, `vn`, `vt` and `f` statements, one a line, without comments.
    statements: String,
}

/// Checks every line `tobj` will read, so errors can name the line.
fn check(text: &str, name: &str) -> Result<Summary, LoadError> {
    let mut vertices = 0i64;
    let mut normals = 0i64;
    let mut texcoords = 0i64;
    let mut faces = 0usize;
    let mut corners = 0usize;
    let mut every_corner_has_normal = true;
    let mut logical = String::new();
    let mut first_line = 0;
    let mut statements = String::new();
    for (k, raw) in text.lines().enumerate() {
        // A trailing backslash continues a statement on the next line.
        if logical.is_empty() {
            first_line = k + 1;
        }
        if let Some(head) = raw.strip_suffix('\\') {
            logical.push_str(head);
            logical.push(' ');
            continue;
        }
        logical.push_str(raw);
        let line = std::mem::take(&mut logical);
        let error = |message: String| LoadError::Syntax {
            path: name.to_owned(),
            line: first_line,
            message,
        };
        let statement = line.split('#').next().unwrap_or("");
        let mut words = statement.split_whitespace();
        let Some(keyword) = words.next() else {
            continue;
        };
        let args: Vec<&str> = words.collect();
        match keyword {
            "v" | "vn" => {
                if args.len() < 3 {
                    return Err(error(format!(
                        "`{keyword}` needs 3 coordinates, found {}",
                        args.len()
                    )));
                }
                // A vertex may have a fourth coordinate w (positions are divided
                // by it); colours after x y z are ignored.
                let used = if keyword == "v" && args.len() == 4 {
                    4
                } else {
                    3
                };
                for (axis, a) in args[..used].iter().enumerate() {
                    let value: f32 = a
                        .parse()
                        .map_err(|_| error(format!("`{a}` is not a number")))?;
                    if !value.is_finite() {
                        return Err(error(format!("coordinate `{a}` is not a finite number")));
                    }
                    if axis == 3 && value == 0.0 {
                        return Err(error("the w coordinate must not be 0".into()));
                    }
                }
                statements.push_str(keyword);
                for a in &args[..used] {
                    statements.push(' ');
                    statements.push_str(a);
                }
                statements.push('\n');
                if keyword == "v" {
                    vertices += 1;
                } else {
                    normals += 1;
                }
            }
            "vt" => {
                // Texture coordinates are ignored; only their count matters.
                statements.push_str("vt 0 0\n");
                texcoords += 1;
            }
            "f" => {
                if args.len() < 3 {
                    return Err(error(format!(
                        "a face needs at least 3 vertices, found {}",
                        args.len()
                    )));
                }
                faces += 1;
                corners += args.len();
                if corners > Mesh::MAX_CORNERS {
                    return Err(error(format!(
                        "more than {} face corners",
                        Mesh::MAX_CORNERS
                    )));
                }
                for corner in &args {
                    let mut parts = corner.split('/');
                    let mut index = |what: &str,
                                     count: i64,
                                     required: bool|
                     -> Result<bool, LoadError> {
                        match parts.next() {
                            Some(s) if !s.is_empty() => {
                                let i: i64 = s.parse().map_err(|_| {
                                    error(format!("`{corner}`: `{s}` is not an index"))
                                })?;
                                let resolved = if i < 0 { count + i } else { i - 1 };
                                if i == 0 || resolved < 0 || resolved >= count {
                                    return Err(error(format!(
                                        "`{corner}`: {what} index {i} is out of range ({count} {what}s defined so far)"
                                    )));
                                }
                                Ok(true)
                            }
                            _ if required => {
                                Err(error(format!("`{corner}`: missing vertex index")))
                            }
                            _ => Ok(false),
                        }
                    };
                    index("vertex", vertices, true)?;
                    index("texture coordinate", texcoords, false)?;
                    let has_normal = index("normal", normals, false)?;
                    every_corner_has_normal &= has_normal;
                    if parts.next().is_some() {
                        return Err(error(format!("`{corner}`: too many `/`-separated indices")));
                    }
                }
                statements.push_str("f ");
                statements.push_str(&args.join(" "));
                statements.push('\n');
            }
            _ => {}
        }
    }
    if faces == 0 {
        return Err(LoadError::Invalid {
            path: name.to_owned(),
            message: "no faces (a mesh needs at least one `f` line)".into(),
        });
    }
    Ok(Summary {
        every_corner_has_normal,
        statements,
    })
}
