//! Smoothing groups as crease boundaries: vertex normals only average faces
//! of the same group, faces in no group are faceted, and groups combine with
//! the crease angle. Checked on meshes whose normals are worked out by hand,
//! and against the same mesh cut apart along the groups' boundaries.

use glam::Vec3;
use shadelab_core::{
    builtin_model, face_normals, vertex_normals, Mesh, MeshError, NormalWeighting,
};

const WEIGHTINGS: [NormalWeighting; 3] = [
    NormalWeighting::Uniform,
    NormalWeighting::Area,
    NormalWeighting::Angle,
];

/// Each corner's normal, in corner order.
fn per_corner(mesh: &Mesh, weighting: NormalWeighting, crease: Option<f32>) -> Vec<Vec3> {
    let n = vertex_normals(mesh, weighting, crease);
    n.corner().iter().map(|&i| n.normals[i as usize]).collect()
}

#[track_caller]
fn assert_normals(actual: &[Vec3], expected: &[Vec3], what: &str) {
    assert_eq!(actual.len(), expected.len(), "{what}");
    for (k, (a, e)) in actual.iter().zip(expected).enumerate() {
        assert!(
            (*a - *e).length() < 1e-6,
            "{what}: corner {k} has {a}, expected {e}"
        );
    }
}

/// A tent: two rectangles meeting at a ridge along x at y = 1, each sloping
/// down at 45°; the ridge's dihedral angle is 90°.
fn tent(groups: Option<[u32; 2]>) -> Mesh {
    let positions = vec![
        Vec3::new(0.0, 1.0, 0.0), // 0: ridge
        Vec3::new(1.0, 1.0, 0.0), // 1: ridge
        Vec3::new(0.0, 0.0, 1.0),
        Vec3::new(1.0, 0.0, 1.0),
        Vec3::new(0.0, 0.0, -1.0),
        Vec3::new(1.0, 0.0, -1.0),
    ];
    let mesh = Mesh::from_polygons(positions, [[2u32, 3, 1, 0], [5, 4, 0, 1]]).unwrap();
    match groups {
        Some(g) => mesh.with_smoothing_groups(g.to_vec()).unwrap(),
        None => mesh,
    }
}

/// Groups, crease angle, expected corner normals, description.
type Case<'a> = (Option<[u32; 2]>, Option<f32>, &'a [Vec3; 8], &'a str);

#[test]
fn tent_normals_by_hand() {
    let s = std::f32::consts::FRAC_1_SQRT_2;
    let front = Vec3::new(0.0, s, s);
    let back = Vec3::new(0.0, s, -s);
    let up = Vec3::Y;
    // Corner order: front [2, 3, 1, 0], back [5, 4, 0, 1].
    let smooth = [front, front, up, up, back, back, up, up];
    let faceted = [front, front, front, front, back, back, back, back];
    let back_alone = [front, front, front, front, back, back, back, back];
    for weighting in WEIGHTINGS {
        let cases: [Case; 9] = [
            (None, None, &smooth, "no groups"),
            (Some([1, 1]), None, &smooth, "one group"),
            (Some([7, 7]), None, &smooth, "one group, any number"),
            (Some([1, 2]), None, &faceted, "two groups"),
            (Some([0, 1]), None, &back_alone, "front not smoothed"),
            (Some([0, 0]), None, &faceted, "none smoothed"),
            (Some([1, 1]), Some(60.0), &faceted, "one group, crease 60°"),
            (Some([1, 1]), Some(100.0), &smooth, "one group, crease 100°"),
            (
                Some([1, 2]),
                Some(100.0),
                &faceted,
                "two groups, crease 100°",
            ),
        ];
        for (groups, crease, expected, what) in cases {
            let mesh = tent(groups);
            assert_normals(
                &per_corner(&mesh, weighting, crease),
                expected,
                &format!("{what}, {weighting:?}"),
            );
        }
    }
    // Corners that share a vertex and a group share one normal index.
    let n = vertex_normals(&tent(Some([1, 1])), NormalWeighting::Uniform, None);
    assert_eq!(n.corner()[2], n.corner()[7], "vertex 1 in both faces");
    assert_eq!(n.corner()[3], n.corner()[6], "vertex 0 in both faces");
    let n = vertex_normals(&tent(Some([1, 2])), NormalWeighting::Uniform, None);
    assert_ne!(n.corner()[2], n.corner()[7]);
    assert_eq!(
        n.normals.len(),
        8,
        "every corner has its own (vertex, normal)"
    );
}

/// A square pyramid with its apex at (0, 0, 1): four side faces of equal
/// area and equal apex angle, groups [1, 1, 2, 2].
#[test]
fn pyramid_split_into_two_groups() {
    let positions = vec![
        Vec3::new(-1.0, -1.0, 0.0),
        Vec3::new(1.0, -1.0, 0.0),
        Vec3::new(1.0, 1.0, 0.0),
        Vec3::new(-1.0, 1.0, 0.0),
        Vec3::new(0.0, 0.0, 1.0),
    ];
    let faces = [[0u32, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]];
    let mesh = Mesh::from_polygons(positions, faces)
        .unwrap()
        .with_smoothing_groups(vec![1, 1, 2, 2])
        .unwrap();
    let s2 = 2f32.sqrt();
    let s6 = 6f32.sqrt();
    let south = Vec3::new(0.0, -1.0, 1.0) / s2;
    let east = Vec3::new(1.0, 0.0, 1.0) / s2;
    let west = Vec3::new(-1.0, 0.0, 1.0) / s2;
    let north = Vec3::new(0.0, 1.0, 1.0) / s2;
    let se = Vec3::new(1.0, -1.0, 2.0) / s6;
    let nw = Vec3::new(-1.0, 1.0, 2.0) / s6;
    // Vertex 0 is in faces 0 (group 1) and 3 (group 2): split. Vertex 1 is in
    // faces 0 and 1, both group 1. Vertex 2: faces 1 (1) and 2 (2), split.
    // Vertex 3: faces 2 and 3, both group 2. The apex: two normals.
    let expected = [
        south, se, se, // face 0: 0, 1, apex
        se, east, se, // face 1: 1, 2, apex
        north, nw, nw, // face 2: 2, 3, apex
        nw, west, nw, // face 3: 3, 0, apex
    ];
    // The side faces have equal areas and equal apex angles, so all three
    // weightings agree at the apex; at the base corners the two faces of a
    // group have equal angles and areas too.
    for weighting in WEIGHTINGS {
        assert_normals(
            &per_corner(&mesh, weighting, None),
            &expected,
            &format!("{weighting:?}"),
        );
    }
    let n = vertex_normals(&mesh, NormalWeighting::Uniform, None);
    let apex: Vec<u32> = [2, 5, 8, 11].map(|c| n.corner()[c]).to_vec();
    assert_eq!(apex[0], apex[1]);
    assert_eq!(apex[2], apex[3]);
    assert_ne!(apex[0], apex[2]);
}

/// Every face in the same group: the normals of a mesh without groups, bit
/// for bit; every face in no group: its face normal at every corner.
#[test]
fn one_group_changes_nothing_and_no_group_is_faceted() {
    for (model, detail) in [("sphere", 12), ("teapot", 4), ("cone", 16), ("torus", 12)] {
        let mesh = builtin_model(model, Some(detail)).unwrap();
        let faces = mesh.polygon_count();
        let one = mesh.clone().with_smoothing_groups(vec![3; faces]).unwrap();
        let none = mesh
            .clone()
            .with_smoothing_groups(vec![Mesh::NOT_SMOOTHED; faces])
            .unwrap();
        let face = face_normals(&mesh);
        let flat: Vec<Vec3> = (0..faces)
            .flat_map(|f| mesh.corner_range(f).map(move |_| f))
            .map(|f| face[f].unwrap_or(Vec3::Z))
            .collect();
        for weighting in WEIGHTINGS {
            for crease in [None, Some(30.0)] {
                assert_eq!(
                    per_corner(&one, weighting, crease),
                    per_corner(&mesh, weighting, crease),
                    "{model}, {weighting:?}, {crease:?}"
                );
                assert_normals(
                    &per_corner(&none, weighting, crease),
                    &flat,
                    &format!("{model} not smoothed, {weighting:?}, {crease:?}"),
                );
            }
        }
    }
}

/// Groups give exactly the normals of the mesh cut apart along their
/// boundaries: each group (and each face in no group) on vertices of its own.
#[test]
fn groups_equal_the_mesh_cut_apart() {
    for (model, detail) in [
        ("sphere", 16),
        ("teapot", 6),
        ("torus", 16),
        ("icosphere", 2),
    ] {
        let mesh = builtin_model(model, Some(detail)).unwrap();
        // Groups by where the face is: three bands, the top one not smoothed.
        let groups: Vec<u32> = (0..mesh.polygon_count())
            .map(|f| {
                let centre = mesh
                    .polygon(f)
                    .iter()
                    .map(|&i| mesh.positions()[i as usize])
                    .sum::<Vec3>()
                    / mesh.polygon(f).len() as f32;
                if centre.y > 0.4 {
                    Mesh::NOT_SMOOTHED
                } else if centre.x > 0.0 {
                    1
                } else {
                    2
                }
            })
            .collect();
        // Cut apart: a vertex copy per (vertex, group), per (vertex, face) in no group.
        let mut copies = std::collections::HashMap::new();
        let mut positions = Vec::new();
        let polygons: Vec<Vec<u32>> = (0..mesh.polygon_count())
            .map(|f| {
                let key_group = if groups[f] == Mesh::NOT_SMOOTHED {
                    u64::MAX - f as u64
                } else {
                    u64::from(groups[f])
                };
                mesh.polygon(f)
                    .iter()
                    .map(|&v| {
                        *copies.entry((v, key_group)).or_insert_with(|| {
                            positions.push(mesh.positions()[v as usize]);
                            positions.len() as u32 - 1
                        })
                    })
                    .collect()
            })
            .collect();
        let cut = Mesh::from_polygons(positions, polygons).unwrap();
        let grouped = mesh.with_smoothing_groups(groups).unwrap();
        for weighting in WEIGHTINGS {
            for crease in [None, Some(45.0)] {
                assert_eq!(
                    per_corner(&grouped, weighting, crease),
                    per_corner(&cut, weighting, crease),
                    "{model}, {weighting:?}, {crease:?}"
                );
            }
        }
    }
}

#[test]
fn one_group_per_face_is_required() {
    let mesh = tent(None);
    for groups in [vec![], vec![1], vec![1, 2, 3]] {
        let n = groups.len();
        assert_eq!(
            mesh.clone().with_smoothing_groups(groups),
            Err(MeshError::SmoothingGroups {
                groups: n,
                faces: 2
            })
        );
    }
    assert_eq!(tent(None).smoothing_groups(), None);
    assert_eq!(tent(Some([4, 0])).smoothing_groups(), Some(&[4, 0][..]));
}

/// A degenerate face in a group takes no part in its neighbours' normals and
/// falls back to +z itself, as without groups.
#[test]
fn degenerate_faces_in_groups() {
    let positions = vec![
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, -1.0),
        Vec3::new(2.0, 0.0, 0.0),
    ];
    // Face 0 faces +y; face 1 is a segment.
    let mesh = Mesh::from_polygons(positions, [[0u32, 1, 2], [0, 1, 3]]).unwrap();
    let expected = [Vec3::Y, Vec3::Y, Vec3::Y, Vec3::Z, Vec3::Z, Vec3::Z];
    for groups in [vec![1, 1], vec![0, 0], vec![1, 0], vec![0, 1]] {
        let mesh = mesh.clone().with_smoothing_groups(groups.clone()).unwrap();
        for crease in [None, Some(10.0)] {
            assert_normals(
                &per_corner(&mesh, NormalWeighting::Uniform, crease),
                &expected,
                &format!("{groups:?}, {crease:?}"),
            );
        }
    }
}

#[test]
fn mesh_ceilings() {
    // One polygon of MAX_TRIANGLES + 3 corners is one triangle too many
    // (and fails before it is copied).
    let corners = Mesh::MAX_TRIANGLES + 3;
    let positions = vec![Vec3::ZERO, Vec3::X, Vec3::Y];
    let polygon: Vec<u32> = (0..corners as u32).map(|k| k % 3).collect();
    assert_eq!(
        Mesh::from_polygons(positions.clone(), [&polygon]),
        Err(MeshError::TooManyTriangles(Mesh::MAX_TRIANGLES + 1))
    );
    assert!(Mesh::from_polygons(positions, [&polygon[..corners - 1]]).is_ok());
    assert_eq!(Mesh::MAX_VERTICES, 3 * Mesh::MAX_TRIANGLES);
    const { assert!(3 * Mesh::MAX_TRIANGLES <= Mesh::MAX_CORNERS) };
}
