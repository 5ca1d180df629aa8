//! Wavefront OBJ meshes, read with `tobj`.
//!
//! `tobj` does the loading; a line-by-line check runs first so that a bad
//! file is reported with its line number (which `tobj` does not give) and so
//! that faces with and without `vn` are told apart: file normals are kept
//! only when every face corner has one. Faces keep their polygons (no
//! triangulation); objects and groups are merged into one mesh; texture
//! coordinates, points and lines are ignored (`tobj` is not even given the
//! `vt` statements, whose indices the check has already verified).
//!
//! The check also reads what `tobj` does not keep or cannot be trusted with:
//!
//! - smoothing groups: `s N` puts the faces that follow in group `N`, and
//!   `s off` or `s 0` in none (faceted). They become the mesh's smoothing
//!   groups, which [`shadelab_core::vertex_normals`] honours. A file with no
//!   `s` statement has none, and every face may be smoothed with its
//!   neighbours; in a file that has some, faces before the first `s` are in
//!   none, as the format's default says. A group that is neither a number
//!   nor `off` is a syntax error.
//! - materials: `mtllib` names libraries beside the file, `usemtl` picks a
//!   material for the faces that follow. [`load_obj_file`] gives the colours
//!   of the material used by the most faces (the first used among equals),
//!   read from the first library that defines it (`crate::mtl`). Materials
//!   never make loading fail: a missing library, an unknown name or a
//!   malformed statement mean no material, and the scene's colours apply.

use std::collections::HashMap;
use std::path::Path;

use glam::Vec3;
use shadelab_core::{escape_token, CornerNormals, Mesh};

use crate::input::{lines_any, read_capped, resolve_inside, Refusal};
use crate::mesh_file::{invalid, mesh_error, FileMaterial, MeshFile, MAX_MESH_BYTES};
use crate::mtl::{parse_mtl, split_keyword};
use crate::LoadError;

/// Reads an OBJ file's geometry (its materials are not read; see
/// [`load_obj_file`]).
///
/// # Errors
/// [`LoadError`] naming the file, and the line for syntax errors, bad
/// indices, non-finite coordinates and meshes beyond the limits of [`Mesh`].
pub fn load_obj(path: &Path) -> Result<Mesh, LoadError> {
    let text = read_text(path)?;
    parse_obj(&text, &path.display().to_string())
}

/// Reads an OBJ file and the colours of its main material from the
/// libraries its `mtllib` statements name, in the file's folder.
///
/// A library is read only when it is a regular file inside the model's
/// folder (every symbolic link resolved); one that is missing, outside,
/// not a regular file, too large or unreadable is passed over with a
/// message in [`MeshFile::warnings`], and the mesh loads all the same.
///
/// # Errors
/// As [`load_obj`]; the material libraries never cause an error.
pub fn load_obj_file(path: &Path) -> Result<MeshFile, LoadError> {
    let text = read_text(path)?;
    let base = path.parent().unwrap_or(Path::new("."));
    let mut warnings = Vec::new();
    let mut file = parse_obj_file(&text, &path.display().to_string(), &mut |library| {
        match read_library(base, library) {
            Ok(text) => Some(text),
            Err(why) => {
                // A name with blanks is tried whole first, then word by
                // word: only the words' absence is worth a message.
                let whole_of_several = library.split_whitespace().nth(1).is_some();
                if !(whole_of_several && why == Refusal::Missing) {
                    warnings.push(format!(
                        "{}: material library {}; its colours are not used",
                        path.display(),
                        why.describe(library)
                    ));
                }
                None
            }
        }
    })?;
    file.warnings = warnings;
    Ok(file)
}

/// A material library's text, read only from inside `base`.
fn read_library(base: &Path, library: &str) -> Result<String, Refusal> {
    let path = resolve_inside(base, library)?;
    let bytes = read_capped(&path, MAX_MESH_BYTES).map_err(|e| {
        Refusal::Unreadable(match e {
            LoadError::Invalid { message, .. } => message,
            LoadError::Io { source, .. } => source.to_string(),
            other => other.to_string(),
        })
    })?;
    Ok(String::from_utf8_lossy(&bytes).into_owned())
}

/// Every library name the file's `mtllib` statements give, whole and split
/// at blanks (as [`load_obj_file`] tries them); none when it cannot be read.
pub(crate) fn library_names(path: &Path) -> Vec<String> {
    let Ok(text) = read_text(path) else {
        return Vec::new();
    };
    let mut names = Vec::new();
    for (_, statement) in statements_of(&text) {
        if let Some(("mtllib", rest)) = split_keyword(&statement) {
            names.extend(library_files(rest).map(str::to_owned));
        }
    }
    names.sort();
    names.dedup();
    names
}

/// Parses OBJ text; `name` is used in error messages. Materials are ignored.
///
/// # Errors
/// As [`load_obj`].
pub fn parse_obj(text: &str, name: &str) -> Result<Mesh, LoadError> {
    Ok(parse(text, name)?.0)
}

/// Parses OBJ text and finds its main material: `read_library` is given each
/// library a `mtllib` statement names and returns its text, or `None` when
/// there is no such library.
///
/// # Errors
/// As [`load_obj`]; the material libraries never cause an error.
pub fn parse_obj_file(
    text: &str,
    name: &str,
    read_library: &mut dyn FnMut(&str) -> Option<String>,
) -> Result<MeshFile, LoadError> {
    let (mesh, summary) = parse(text, name)?;
    let material = summary
        .material
        .and_then(|wanted| find_material(&wanted, &summary.libraries, read_library));
    Ok(MeshFile {
        mesh,
        material,
        warnings: Vec::new(),
    })
}

/// The file's text, at most [`MAX_MESH_BYTES`] of UTF-8.
fn read_text(path: &Path) -> Result<String, LoadError> {
    let bytes = read_capped(path, MAX_MESH_BYTES)?;
    String::from_utf8(bytes).map_err(|e| {
        invalid(
            &path.display().to_string(),
            format!(
                "not UTF-8 text (invalid byte at offset {})",
                e.utf8_error().valid_up_to()
            ),
        )
    })
}

/// The files an `mtllib` statement may name: the whole of it first (one
/// name containing blanks), then each blank-separated name.
fn library_files(statement: &str) -> impl Iterator<Item = &str> {
    std::iter::once(statement).chain(
        statement
            .split_whitespace()
            .filter(move |&file| file != statement),
    )
}

/// An OBJ text's statements, each with the number of its first line: a
/// trailing backslash joins a line to the next, and `#` starts a comment.
fn statements_of(text: &str) -> impl Iterator<Item = (usize, String)> + '_ {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut logical = String::new();
    let mut first_line = 0;
    lines_any(text).enumerate().filter_map(move |(k, raw)| {
        if logical.is_empty() {
            first_line = k + 1;
        }
        if let Some(head) = raw.strip_suffix('\\') {
            logical.push_str(head);
            logical.push(' ');
            return None;
        }
        logical.push_str(raw);
        let mut statement = std::mem::take(&mut logical);
        statement.truncate(statement.find('#').unwrap_or(statement.len()));
        Some((first_line, statement))
    })
}

/// The material `wanted` from the first library that defines it with a colour.
fn find_material(
    wanted: &str,
    libraries: &[String],
    read_library: &mut dyn FnMut(&str) -> Option<String>,
) -> Option<FileMaterial> {
    // Each library is read once, however often it is named.
    let mut tried = std::collections::HashSet::new();
    let mut read_once = |file: &str| {
        if tried.insert(file.to_owned()) {
            read_library(file)
        } else {
            None
        }
    };
    for statement in libraries {
        // `mtllib` takes several names separated by blanks, but exporters
        // also write one name containing blanks: try the whole first.
        let mut files = library_files(statement);
        let whole = files
            .next()
            .and_then(|file| read_once(file).map(|text| (file, text)));
        let texts: Vec<(&str, String)> = match whole {
            Some(found) => vec![found],
            None => files
                .filter_map(|file| read_once(file).map(|text| (file, text)))
                .collect(),
        };
        for (library, text) in texts {
            if let Some(m) = parse_mtl(&text).into_iter().find(|m| m.name == wanted) {
                if m.ka.is_none() && m.kd.is_none() {
                    return None;
                }
                return Some(FileMaterial {
                    name: m.name,
                    library: library.to_owned(),
                    ka: m.ka,
                    kd: m.kd,
                });
            }
        }
    }
    None
}

fn parse(text: &str, name: &str) -> Result<(Mesh, Summary), LoadError> {
    let mut summary = check(text, name)?;
    let options = tobj::LoadOptions {
        single_index: false,
        triangulate: false,
        ignore_points: true,
        ignore_lines: true,
    };
    // `tobj` reads only the checked statements: it knows neither comments
    // after a statement nor continued lines, and what shadelab ignores
    // (materials, lines, colours) cannot make it fail.
    let statements = std::mem::take(&mut summary.statements);
    let (models, _materials) = tobj::load_obj_buf(&mut statements.as_bytes(), &options, |_| {
        Err(tobj::LoadError::MaterialParseError)
    })
    .map_err(|e| invalid(name, e.to_string()))?;
    drop(statements);

    let mut positions = Vec::new();
    let mut corners: Vec<u32> = Vec::new();
    let mut offsets = vec![0usize];
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
        corners.extend(m.indices.iter().map(|&i| base + i));
        let arities: Box<dyn Iterator<Item = usize>> = if m.face_arities.is_empty() {
            Box::new(std::iter::repeat_n(3, m.indices.len() / 3))
        } else {
            Box::new(m.face_arities.iter().map(|&a| a as usize))
        };
        for arity in arities {
            offsets.push(offsets[offsets.len() - 1] + arity);
        }
        if m.normal_indices.len() == m.indices.len() {
            corner_normals.extend(m.normal_indices.iter().map(|&i| normal_base + i));
        }
    }
    drop(models);
    let polygons = offsets.windows(2).map(|w| &corners[w[0]..w[1]]);
    let mut mesh = Mesh::from_polygons(positions, polygons).map_err(mesh_error(name))?;
    drop(corners);
    // A file whose normals include a zero vector has no usable normals: it is
    // treated like a file without them, and normals are computed.
    if summary.every_corner_has_normal
        && corner_normals.len() == mesh.corners().len()
        && normals.iter().all(|n| n.try_normalize().is_some())
    {
        mesh = mesh
            .with_file_normals(CornerNormals::new(normals, corner_normals))
            .map_err(mesh_error(name))?;
    }
    if let Some(groups) = summary.smoothing.take() {
        mesh = mesh
            .with_smoothing_groups(groups)
            .map_err(mesh_error(name))?;
    }
    Ok((mesh, summary))
}

struct Summary {
    every_corner_has_normal: bool,
    /// The `v`, `vn` and `f` statements, one a line, without comments and
    /// without texture coordinate indices.
    statements: String,
    /// Each face's smoothing group, when the file has an `s` statement.
    smoothing: Option<Vec<u32>>,
    /// What each `mtllib` statement names, in order.
    libraries: Vec<String>,
    /// The material used by the most faces.
    material: Option<String>,
}

/// Checks every line `tobj` will read, so errors can name the line.
fn check(text: &str, name: &str) -> Result<Summary, LoadError> {
    let mut vertices = 0i64;
    let mut normals = 0i64;
    let mut texcoords = 0i64;
    let mut faces = 0usize;
    let mut corners = 0usize;
    let mut triangles = 0usize;
    let mut every_corner_has_normal = true;
    let mut statements = String::new();
    let mut group = Mesh::NOT_SMOOTHED;
    let mut groups: Vec<u32> = Vec::new();
    let mut any_group = false;
    let mut libraries = Vec::new();
    let mut material: Option<usize> = None;
    // Materials by first use: name and faces using it.
    let mut usage: Vec<(String, usize)> = Vec::new();
    let mut usage_index: HashMap<String, usize> = HashMap::new();
    for (first_line, statement) in statements_of(text) {
        let error = |message: String| LoadError::Syntax {
            path: name.to_owned(),
            line: first_line,
            message,
        };
        let Some((keyword, rest)) = split_keyword(&statement) else {
            continue;
        };
        // A face's corners are counted against the limits before they are
        // gathered, so an absurdly long line allocates nothing.
        if keyword == "f" {
            let count = rest.split_whitespace().count();
            if corners + count > Mesh::MAX_CORNERS {
                return Err(error(format!(
                    "more than {} face corners",
                    Mesh::MAX_CORNERS
                )));
            }
            if triangles + count.saturating_sub(2) > Mesh::MAX_TRIANGLES {
                return Err(error(format!(
                    "more than {} triangles: that is the most supported",
                    Mesh::MAX_TRIANGLES
                )));
            }
        }
        let args: Vec<&str> = rest.split_whitespace().collect();
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
                        .map_err(|_| error(format!("`{}` is not a number", escape_token(a))))?;
                    if !value.is_finite() {
                        return Err(error(format!(
                            "coordinate `{}` is not a finite number",
                            escape_token(a)
                        )));
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
                let count = if keyword == "v" {
                    &mut vertices
                } else {
                    &mut normals
                };
                *count += 1;
                if *count as usize > Mesh::MAX_VERTICES {
                    return Err(error(format!(
                        "more than {} `{keyword}` statements: at most {} vertices are supported",
                        Mesh::MAX_VERTICES,
                        Mesh::MAX_VERTICES
                    )));
                }
            }
            "vt" => {
                // Texture coordinates are ignored; only their count matters.
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
                triangles += args.len() - 2;
                statements.push('f');
                for corner in &args {
                    let mut parts = corner.split('/');
                    let mut index = |what: &str,
                                     count: i64,
                                     required: bool|
                     -> Result<Option<&str>, LoadError> {
                        match parts.next() {
                            Some(s) if !s.is_empty() => {
                                let i: i64 = s.parse().map_err(|_| {
                                    error(format!(
                                        "`{}`: `{}` is not an index",
                                        escape_token(corner),
                                        escape_token(s)
                                    ))
                                })?;
                                let resolved = if i < 0 { count + i } else { i - 1 };
                                if i == 0 || resolved < 0 || resolved >= count {
                                    return Err(error(format!(
                                        "`{}`: {what} index {i} is out of range ({count} {what}s defined so far)",
                                        escape_token(corner)
                                    )));
                                }
                                Ok(Some(s))
                            }
                            _ if required => Err(error(format!(
                                "`{}`: missing vertex index",
                                escape_token(corner)
                            ))),
                            _ => Ok(None),
                        }
                    };
                    let vertex = index("vertex", vertices, true)?;
                    index("texture coordinate", texcoords, false)?;
                    let normal = index("normal", normals, false)?;
                    every_corner_has_normal &= normal.is_some();
                    if parts.next().is_some() {
                        return Err(error(format!(
                            "`{}`: too many `/`-separated indices",
                            escape_token(corner)
                        )));
                    }
                    statements.push(' ');
                    statements.push_str(vertex.unwrap_or_default());
                    if let Some(n) = normal {
                        statements.push_str("//");
                        statements.push_str(n);
                    }
                }
                statements.push('\n');
                groups.push(group);
                if let Some(m) = material {
                    usage[m].1 += 1;
                }
            }
            "s" => {
                group = if rest.eq_ignore_ascii_case("off") {
                    Mesh::NOT_SMOOTHED
                } else {
                    rest.parse().map_err(|_| {
                        error(format!(
                            "`s` takes a smoothing group number (0 to {}) or `off`, found `{}`",
                            u32::MAX,
                            escape_token(rest)
                        ))
                    })?
                };
                any_group = true;
            }
            "mtllib" if !rest.is_empty() => libraries.push(rest.to_owned()),
            "usemtl" => {
                material = (!rest.is_empty()).then(|| {
                    *usage_index.entry(rest.to_owned()).or_insert_with(|| {
                        usage.push((rest.to_owned(), 0));
                        usage.len() - 1
                    })
                });
            }
            _ => {}
        }
    }
    if faces == 0 {
        return Err(invalid(
            name,
            "no faces (a mesh needs at least one `f` line)",
        ));
    }
    let mut most_used: Option<&(String, usize)> = None;
    for entry in &usage {
        if entry.1 > 0 && most_used.is_none_or(|best| entry.1 > best.1) {
            most_used = Some(entry);
        }
    }
    Ok(Summary {
        every_corner_has_normal,
        statements,
        smoothing: any_group.then_some(groups),
        libraries,
        material: most_used.map(|(name, _)| name.clone()),
    })
}
