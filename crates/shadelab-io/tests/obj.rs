//! OBJ loading: polygons kept as written, index forms, file normals, merged
//! objects, and errors that name the file and the line.

use std::path::{Path, PathBuf};

use glam::Vec3;
use shadelab_core::Mesh;
use shadelab_io::{load_obj, parse_obj, LoadError};

/// Writes `text` to `name` in `dir` and returns the path.
fn write(dir: &Path, name: &str, text: impl AsRef<[u8]>) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).expect("write test file");
    path
}

/// Loads `text` from a real file, so errors carry the real path.
fn load(text: &str) -> (tempfile::TempDir, PathBuf, Result<Mesh, LoadError>) {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = write(dir.path(), "model.obj", text);
    let result = load_obj(&path);
    (dir, path, result)
}

fn loaded(text: &str) -> Mesh {
    let (_dir, path, result) = load(text);
    result.unwrap_or_else(|e| panic!("{} should load: {e}", path.display()))
}

fn arities(mesh: &Mesh) -> Vec<usize> {
    (0..mesh.polygon_count())
        .map(|f| mesh.polygon(f).len())
        .collect()
}

/// The positions of polygon `face`'s corners.
fn face_points(mesh: &Mesh, face: usize) -> Vec<Vec3> {
    mesh.polygon(face)
        .iter()
        .map(|&i| mesh.positions()[i as usize])
        .collect()
}

/// Asserts a syntax error at `line` whose message contains `needle`, and
/// that its Display is "path:line: ...".
fn assert_syntax(text: &str, line: usize, needle: &str) {
    let (_dir, path, result) = load(text);
    let err = result.expect_err("should fail");
    let shown = err.to_string();
    match &err {
        LoadError::Syntax {
            path: p,
            line: l,
            message,
        } => {
            assert_eq!(p, &path.display().to_string(), "{shown}");
            assert_eq!(*l, line, "wrong line in {shown}");
            assert!(
                message.contains(needle),
                "message {message:?} should contain {needle:?}"
            );
        }
        other => panic!("expected a syntax error at line {line}, got {other:?}"),
    }
    let prefix = format!("{}:{line}: ", path.display());
    assert!(
        shown.starts_with(&prefix),
        "{shown:?} should start with {prefix:?}"
    );
}

const SQUARE_VERTS: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";

#[test]
fn triangles_quads_and_ngons_are_kept_as_polygons() {
    let text = "\
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 2 0 0
v 3 0 0
v 3.5 1 0
v 3 2 0
v 2 2 0
v 1.5 1 0
f 1 2 3
f 1 2 3 4
f 5 6 7 8 9
f 5 6 7 8 9 10
";
    let mesh = loaded(text);
    assert_eq!(mesh.polygon_count(), 4);
    assert_eq!(arities(&mesh), vec![3, 4, 5, 6]);
    assert_eq!(mesh.corners().len(), 18);
    assert_eq!(mesh.triangle_count(), 1 + 2 + 3 + 4);
    // The hexagon's corners are the file's vertices, in the file's order.
    assert_eq!(
        face_points(&mesh, 3),
        vec![
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(3.0, 0.0, 0.0),
            Vec3::new(3.5, 1.0, 0.0),
            Vec3::new(3.0, 2.0, 0.0),
            Vec3::new(2.0, 2.0, 0.0),
            Vec3::new(1.5, 1.0, 0.0),
        ]
    );
    assert!(mesh.file_normals().is_none());
}

#[test]
fn negative_indices_are_relative_to_the_vertices_so_far() {
    let text = "\
v 0 0 0
v 1 0 0
v 1 1 0
f -3 -2 -1
v 5 5 5
v 6 5 5
v 6 6 5
v 5 6 5
f -4 -3 -2 -1
f 1 -4 -1
";
    let mesh = loaded(text);
    assert_eq!(arities(&mesh), vec![3, 4, 3]);
    assert_eq!(
        face_points(&mesh, 0),
        vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
        ]
    );
    assert_eq!(
        face_points(&mesh, 1),
        vec![
            Vec3::new(5.0, 5.0, 5.0),
            Vec3::new(6.0, 5.0, 5.0),
            Vec3::new(6.0, 6.0, 5.0),
            Vec3::new(5.0, 6.0, 5.0),
        ]
    );
    assert_eq!(
        face_points(&mesh, 2),
        vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(5.0, 5.0, 5.0),
            Vec3::new(5.0, 6.0, 5.0),
        ]
    );
}

#[test]
fn v_vt_vn_form_attaches_file_normals() {
    let text = format!(
        "{SQUARE_VERTS}vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\nvn 0 0 2\n\
         f 1/1/1 2/2/1 3/3/2 4/4/2\n"
    );
    let mesh = loaded(&text);
    assert_eq!(arities(&mesh), vec![4]);
    let normals = mesh.file_normals().expect("every corner has a normal");
    assert_eq!(normals.corner().len(), 4);
    let per_corner: Vec<Vec3> = normals
        .corner()
        .iter()
        .map(|&i| normals.normals[i as usize])
        .collect();
    // Normals are unit length (the second one is written as (0, 0, 2)).
    assert_eq!(per_corner, vec![Vec3::Z; 4]);
    assert_eq!(
        face_points(&mesh, 0),
        vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
        ]
    );
}

#[test]
fn v_slash_slash_vn_form_attaches_file_normals_per_corner() {
    let text =
        format!("{SQUARE_VERTS}vn 1 0 0\nvn 0 1 0\nvn 0 0 1\nf 1//1 2//2 3//3\nf 1//3 3//2 4//1\n");
    let mesh = loaded(&text);
    assert_eq!(arities(&mesh), vec![3, 3]);
    let normals = mesh.file_normals().expect("complete normals");
    let per_corner: Vec<Vec3> = normals
        .corner()
        .iter()
        .map(|&i| normals.normals[i as usize])
        .collect();
    assert_eq!(
        per_corner,
        vec![Vec3::X, Vec3::Y, Vec3::Z, Vec3::Z, Vec3::Y, Vec3::X]
    );
}

#[test]
fn negative_normal_indices_are_relative() {
    let text = format!("{SQUARE_VERTS}vn 1 0 0\nvn 0 1 0\nf -4//-1 -3//-2 -2//-1\n");
    let mesh = loaded(&text);
    let normals = mesh.file_normals().expect("complete normals");
    let per_corner: Vec<Vec3> = normals
        .corner()
        .iter()
        .map(|&i| normals.normals[i as usize])
        .collect();
    assert_eq!(per_corner, vec![Vec3::Y, Vec3::X, Vec3::Y]);
}

#[test]
fn v_slash_vt_form_has_no_file_normals() {
    let text = format!("{SQUARE_VERTS}vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n");
    let mesh = loaded(&text);
    assert_eq!(arities(&mesh), vec![4]);
    assert!(mesh.file_normals().is_none());
}

#[test]
fn zero_normals_are_not_attached() {
    // A zero `vn` gives no direction: the file's normals are not used.
    let text = format!("{SQUARE_VERTS}vn 0 0 0\nvn 0 0 1\nf 1//1 2//2 3//2\nf 1//2 3//2 4//2\n");
    let mesh = loaded(&text);
    assert_eq!(mesh.polygon_count(), 2);
    assert!(mesh.file_normals().is_none());
}

#[test]
fn partial_normals_are_not_attached() {
    // The second face has no `vn`: normals are all or nothing.
    let text = format!("{SQUARE_VERTS}vn 0 0 1\nf 1//1 2//1 3//1\nf 1 3 4\n");
    let mesh = loaded(&text);
    assert_eq!(mesh.polygon_count(), 2);
    assert!(mesh.file_normals().is_none());

    // One corner without a normal in an otherwise complete face.
    let text = format!("{SQUARE_VERTS}vn 0 0 1\nf 1//1 2//1 3//1\nf 1//1 3 4//1\n");
    assert!(loaded(&text).file_normals().is_none());

    // The first face without, the second with.
    let text = format!("{SQUARE_VERTS}vn 0 0 1\nf 1 2 3\nf 1//1 3//1 4//1\n");
    assert!(loaded(&text).file_normals().is_none());
}

#[test]
fn objects_and_groups_are_merged_into_one_mesh() {
    let text = "\
o first
v 0 0 0
v 1 0 0
v 1 1 0
f 1 2 3
g second
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
f 4 5 6 7
o third
g inner
f 1 2 3 4 5
";
    let mesh = loaded(text);
    assert_eq!(mesh.polygon_count(), 3);
    assert_eq!(arities(&mesh), vec![3, 4, 5]);
    assert_eq!(
        face_points(&mesh, 1),
        vec![
            Vec3::new(0.0, 0.0, 1.0),
            Vec3::new(1.0, 0.0, 1.0),
            Vec3::new(1.0, 1.0, 1.0),
            Vec3::new(0.0, 1.0, 1.0),
        ]
    );
    assert_eq!(
        face_points(&mesh, 2),
        vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(0.0, 0.0, 1.0),
            Vec3::new(1.0, 0.0, 1.0),
        ]
    );
}

#[test]
fn merged_objects_keep_complete_normals() {
    let text = "\
o a
v 0 0 0
v 1 0 0
v 1 1 0
vn 0 0 1
f 1//1 2//1 3//1
o b
v 0 0 1
v 1 0 1
v 1 1 1
vn 1 0 0
f 4//2 5//2 6//2
";
    let mesh = loaded(text);
    let normals = mesh
        .file_normals()
        .expect("complete normals across objects");
    let per_corner: Vec<Vec3> = normals
        .corner()
        .iter()
        .map(|&i| normals.normals[i as usize])
        .collect();
    assert_eq!(
        per_corner,
        vec![Vec3::Z, Vec3::Z, Vec3::Z, Vec3::X, Vec3::X, Vec3::X]
    );
}

#[test]
fn comments_blank_lines_and_materials_are_accepted() {
    let text = "\
# a comment
mtllib materials.mtl

   # an indented comment
#no space after the hash
o thing
usemtl red
v 0 0 0
v 1 0 0   # trailing comment on a vertex
v 1 1 0
v 0 1 0

s off
usemtl blue
f 1 2 3 4 # trailing comment on a face
";
    let mesh = loaded(text);
    assert_eq!(arities(&mesh), vec![4]);
    assert_eq!(
        face_points(&mesh, 0),
        vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
        ]
    );
}

#[test]
fn continued_lines_are_joined() {
    // A trailing backslash continues a statement; errors name its first line.
    let mesh = loaded("v 0 0 0\nv 1 \\\n  0 0\nv 0 1 0\nf 1 2 \\\n 3\n");
    assert_eq!(arities(&mesh), vec![3]);
    assert_eq!(face_points(&mesh, 0)[1], Vec3::new(1.0, 0.0, 0.0));
    assert_syntax(
        "v 0 0 0\nv 1 \\\n  x 0\nv 0 1 0\nf 1 2 3\n",
        2,
        "not a number",
    );
}

#[test]
fn what_is_ignored_cannot_fail() {
    // Lines (`l`), smoothing groups, an empty `usemtl`, a one-value `vt`, and
    // vertex colours on only some vertices are all ignored.
    let text = "\
v 0 0 0 1 0 0
v 1 0 0
v 0 1 0
vt 0.5
l 1 2
l 1 x
s 1
usemtl
f 1/1 2/1 3/1
";
    let mesh = loaded(text);
    assert_eq!(arities(&mesh), vec![3]);
    assert_eq!(
        face_points(&mesh, 0),
        vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
        ]
    );
}

#[test]
fn homogeneous_w_divides_the_position() {
    let mesh = loaded("v 2 4 6 2\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    assert_eq!(face_points(&mesh, 0)[0], Vec3::new(1.0, 2.0, 3.0));
    assert_syntax("v 0 0 0\nv 1 0 0 0\nv 0 1 0\nf 1 2 3\n", 2, "w coordinate");
    assert_syntax(
        "v 0 0 0\nv 1 0 0\nv 0 1 0 nan\nf 1 2 3\n",
        3,
        "not a finite number",
    );
}

#[test]
fn crlf_line_endings_are_accepted() {
    let mesh = loaded("v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 3\r\n");
    assert_eq!(arities(&mesh), vec![3]);
}

#[test]
fn degenerate_faces_load() {
    // A repeated vertex and three collinear vertices.
    let text = "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 1 4\nf 1 2 3\nf 1 2 2 4\n";
    let mesh = loaded(text);
    assert_eq!(arities(&mesh), vec![3, 3, 4]);
}

#[test]
fn parse_obj_uses_the_given_name() {
    let err = parse_obj("v 0 0 0\nv 1 0\n", "memory.obj").expect_err("bad vertex");
    assert!(err.to_string().starts_with("memory.obj:2: "), "{err}");
    let mesh = parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "memory.obj").expect("loads");
    assert_eq!(mesh.polygon_count(), 1);
}

// ---- errors ----

#[test]
fn missing_file_is_an_io_error_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("absent.obj");
    let err = load_obj(&path).expect_err("missing file");
    assert!(matches!(err, LoadError::Io { .. }), "{err:?}");
    if let LoadError::Io { source, .. } = &err {
        assert_eq!(source.kind(), std::io::ErrorKind::NotFound);
    }
    assert!(
        err.to_string().contains(&path.display().to_string()),
        "{err}"
    );
}

#[test]
fn vertex_with_too_few_coordinates() {
    assert_syntax(
        "# header\nv 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n",
        3,
        "3 coordinates",
    );
}

#[test]
fn vertex_coordinate_that_is_not_a_number() {
    assert_syntax(
        "v 0 0 0\nv 1 x 0\nv 0 1 0\nf 1 2 3\n",
        2,
        "`x` is not a number",
    );
}

#[test]
fn normal_with_a_bad_coordinate() {
    assert_syntax(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 zero 1\nf 1//1 2//1 3//1\n",
        4,
        "not a number",
    );
}

#[test]
fn face_index_that_is_not_a_number() {
    assert_syntax("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 two 3\n", 4, "not an index");
}

#[test]
fn vertex_index_zero() {
    assert_syntax("v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 0 1 2\n", 5, "index 0");
}

#[test]
fn vertex_index_out_of_range_positive() {
    assert_syntax(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\n",
        5,
        "out of range",
    );
}

#[test]
fn vertex_index_refers_to_a_vertex_defined_later() {
    assert_syntax("v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\n", 3, "out of range");
}

#[test]
fn vertex_index_out_of_range_negative() {
    assert_syntax("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n", 4, "out of range");
}

#[test]
fn normal_and_texture_indices_out_of_range() {
    assert_syntax(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//2\n",
        5,
        "normal index 2",
    );
    assert_syntax(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//-2 3//1\n",
        5,
        "normal index -2",
    );
    assert_syntax(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/3\n",
        5,
        "texture coordinate index 3",
    );
}

#[test]
fn too_many_slashes_in_a_corner() {
    assert_syntax(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf 1/1/1/1 2 3\n",
        6,
        "too many",
    );
}

#[test]
fn nan_coordinate() {
    assert_syntax(
        "v 0 0 0\nv 1 0 0\nv 0 NaN 0\nf 1 2 3\n",
        3,
        "not a finite number",
    );
    assert_syntax(
        "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n",
        2,
        "not a finite number",
    );
}

#[test]
fn infinite_coordinate() {
    assert_syntax(
        "v 0 0 inf\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
        1,
        "not a finite number",
    );
    assert_syntax(
        "v 0 0 0\nv 1 0 0\nv 0 1 -inf\nf 1 2 3\n",
        3,
        "not a finite number",
    );
    // Finite in decimal but beyond f32's range.
    assert_syntax(
        "v 0 0 0\nv 1e39 0 0\nv 0 1 0\nf 1 2 3\n",
        2,
        "not a finite number",
    );
}

#[test]
fn face_with_two_vertices() {
    assert_syntax(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2\n",
        5,
        "at least 3",
    );
}

#[test]
fn line_numbers_count_comments_and_blank_lines() {
    let text = "# one\n\n# three\nv 0 0 0\n\nv 1 0 0\nv 0 1 0\n# eight\nf 1 2 9\n";
    assert_syntax(text, 9, "out of range");
}

#[test]
fn no_faces_is_invalid() {
    let (_dir, path, result) = load("# only vertices\nv 0 0 0\nv 1 0 0\nv 0 1 0\n");
    let err = result.expect_err("no faces");
    assert!(matches!(err, LoadError::Invalid { .. }), "{err:?}");
    let shown = err.to_string();
    assert!(
        shown.starts_with(&format!("{}: ", path.display())),
        "{shown}"
    );
    assert!(shown.contains("no faces"), "{shown}");

    let (_dir, _path, result) = load("");
    assert!(matches!(result, Err(LoadError::Invalid { .. })));
}

#[test]
fn non_utf8_is_invalid() {
    let dir = tempfile::tempdir().unwrap();
    let mut bytes = b"v 0 0 0\nv 1 0 0\nv 0 1 0\n# caf".to_vec();
    bytes.extend_from_slice(&[0xE9, 0xFF, b'\n']);
    bytes.extend_from_slice(b"f 1 2 3\n");
    let path = write(dir.path(), "latin1.obj", &bytes);
    let err = load_obj(&path).expect_err("not UTF-8");
    assert!(matches!(err, LoadError::Invalid { .. }), "{err:?}");
    let shown = err.to_string();
    assert!(
        shown.starts_with(&format!("{}: ", path.display())),
        "{shown}"
    );
    assert!(shown.contains("UTF-8"), "{shown}");
}
