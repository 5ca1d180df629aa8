//! Face normals and vertex normals.
//!
//! A face normal is the cross product of two edges for a triangle and Newell's
//! method for a polygon of more than three vertices (robust for slightly
//! non-planar quads). A vertex normal is the normalised, weighted sum of the
//! unit normals of the faces around the vertex; with a crease angle, a face
//! only takes part in a corner's normal when it bends from that corner's face
//! by no more than the angle, which splits vertices along sharp edges.
//!
//! Smoothing groups (an OBJ file's `s` statements, kept by the mesh) split
//! vertices too: a face only takes part in a corner's normal when it is in
//! the same group as the corner's face, and a face in no group
//! ([`Mesh::NOT_SMOOTHED`]) is smoothed with no other, so its corners take
//! its face normal. The normals are exactly those of the mesh cut apart along
//! the groups' boundaries (the same faces summed in the same order). A crease
//! angle and smoothing groups apply together: a face must pass both.

use std::collections::HashMap;

use glam::{DVec3, Vec3};
use rayon::prelude::*;

use crate::mesh::{CornerNormals, Mesh};

/// How the faces around a vertex are weighted in its normal.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum NormalWeighting {
    /// Every adjacent face counts the same: the textbook rule.
    Uniform,
    /// Faces weighted by their area.
    Area,
    /// Faces weighted by the angle of their corner at the vertex.
    Angle,
}

/// Where a scene's vertex normals come from (`model.normals`): the file's,
/// or made from the faces with one of the [`NormalWeighting`]s.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash)]
pub enum NormalsChoice {
    /// The file's normals when it has them, else uniform.
    #[default]
    Auto,
    /// The file's normals (an error when it has none).
    File,
    /// Unweighted average of adjacent face normals.
    Uniform,
    /// Area-weighted average.
    Area,
    /// Angle-weighted average.
    Angle,
}

choices!(NormalsChoice, "vertex normals", {
    Auto => "auto": "the file's normals when it has them, else uniform",
    File => "file": "the file's normals (an error when it has none)",
    Uniform => "uniform": "unweighted average of the adjacent face normals",
    Area => "area": "face normals weighted by the faces' areas",
    Angle => "angle": "face normals weighted by the angles of their corners at the vertex",
});

/// The face normal of a polygon, not normalised: twice the polygon's area in
/// length for a planar polygon, zero for a degenerate one.
pub fn face_normal_unnormalized(points: &[Vec3]) -> Vec3 {
    match points {
        [a, b, c] => (*b - *a).cross(*c - *a),
        _ => {
            // Newell's method.
            let mut n = Vec3::ZERO;
            for (i, &p) in points.iter().enumerate() {
                let q = points[(i + 1) % points.len()];
                n += Vec3::new(
                    (p.y - q.y) * (p.z + q.z),
                    (p.z - q.z) * (p.x + q.x),
                    (p.x - q.x) * (p.y + q.y),
                );
            }
            n
        }
    }
}

/// The unit face normal of a polygon, or `None` for a degenerate one.
pub fn face_normal(points: &[Vec3]) -> Option<Vec3> {
    face_normal_unnormalized(points)
        .try_normalize()
        .or_else(|| {
            // The f32 products overflow for coordinates beyond about 1e19 (and
            // underflow below about 1e-19); Newell's method in f64 has room for
            // any f32 polygon.
            let mut n = DVec3::ZERO;
            for (i, p) in points.iter().enumerate() {
                let (p, q) = (p.as_dvec3(), points[(i + 1) % points.len()].as_dvec3());
                n += DVec3::new(
                    (p.y - q.y) * (p.z + q.z),
                    (p.z - q.z) * (p.x + q.x),
                    (p.x - q.x) * (p.y + q.y),
                );
            }
            n.try_normalize().map(|n| n.as_vec3())
        })
}

/// The unit face normal of each polygon of `mesh`, `None` where degenerate.
pub fn face_normals(mesh: &Mesh) -> Vec<Option<Vec3>> {
    let (mut normals, mut centroids) = (Vec::new(), Vec::new());
    face_geometry(mesh, &mut normals, &mut centroids);
    normals
}

/// The centroid of a polygon: the mean of its corners' positions, the
/// point flat shading lights.
pub(crate) fn centroid(points: &[Vec3]) -> Vec3 {
    points.iter().sum::<Vec3>() / points.len() as f32
}

/// Each polygon's unit face normal ([`face_normal`]) and [`centroid`], into
/// `normals` and `centroids` (reusing their storage), in parallel: the frame
/// keeps them until the mesh's geometry changes.
pub(crate) fn face_geometry(
    mesh: &Mesh,
    normals: &mut Vec<Option<Vec3>>,
    centroids: &mut Vec<Vec3>,
) {
    const CHUNK: usize = 1024;
    let count = mesh.polygon_count();
    normals.resize(count, None);
    centroids.resize(count, Vec3::ZERO);
    normals
        .par_chunks_mut(CHUNK)
        .zip(centroids.par_chunks_mut(CHUNK))
        .enumerate()
        .for_each(|(k, (normals, centroids))| {
            let mut points = Vec::new();
            for (i, (normal, c)) in normals.iter_mut().zip(centroids).enumerate() {
                points.clear();
                let polygon = mesh.polygon(k * CHUNK + i);
                points.extend(polygon.iter().map(|&v| mesh.positions()[v as usize]));
                *normal = face_normal(&points);
                *c = if points.is_empty() {
                    Vec3::ZERO
                } else {
                    centroid(&points)
                };
            }
        });
}

/// Vertex normals of `mesh` with the given weighting, one per corner.
///
/// With `crease_degrees`, a corner's normal only sums the faces around its
/// vertex whose normal is within that angle of its own face's normal; when
/// the mesh has smoothing groups, only the faces of its own face's group
/// (and none for a face in [`Mesh::NOT_SMOOTHED`], whose corners take its
/// face normal). A corner whose sum vanishes (or whose face is degenerate)
/// falls back to its face normal, or +z for a degenerate face.
pub fn vertex_normals(
    mesh: &Mesh,
    weighting: NormalWeighting,
    crease_degrees: Option<f32>,
) -> CornerNormals {
    let positions = mesh.positions();
    let faces = face_normals(mesh);
    let mut points = Vec::new();
    // Weighted contribution of each corner's face to its vertex.
    let mut contribution = vec![Vec3::ZERO; mesh.corners().len()];
    for (f, normal) in faces.iter().enumerate() {
        let Some(normal) = *normal else { continue };
        let range = mesh.corner_range(f);
        points.clear();
        points.extend(
            mesh.corners()[range.clone()]
                .iter()
                .map(|&i| positions[i as usize]),
        );
        let n = points.len();
        for (k, c) in range.enumerate() {
            let weight = match weighting {
                NormalWeighting::Uniform => 1.0,
                NormalWeighting::Area => 0.5 * face_normal_unnormalized(&points).length(),
                NormalWeighting::Angle => {
                    let p = points[k];
                    let prev = (points[(k + n - 1) % n] - p).normalize_or_zero();
                    let next = (points[(k + 1) % n] - p).normalize_or_zero();
                    prev.dot(next).clamp(-1.0, 1.0).acos()
                }
            };
            contribution[c] = normal * weight;
        }
    }

    let fallback = |f: usize| faces[f].unwrap_or(Vec3::Z);
    let corner_face: Vec<usize> = (0..mesh.polygon_count())
        .flat_map(|f| mesh.corner_range(f).map(move |_| f))
        .collect();

    let groups = mesh.smoothing_groups();
    if crease_degrees.is_none() && groups.is_none() {
        let mut sum = vec![Vec3::ZERO; positions.len()];
        for (c, &v) in mesh.corners().iter().enumerate() {
            sum[v as usize] += contribution[c];
        }
        let mut normals: Vec<Vec3> = sum.iter().map(|s| s.normalize_or_zero()).collect();
        let corner = mesh
            .corners()
            .iter()
            .enumerate()
            .map(|(c, &v)| {
                if normals[v as usize] == Vec3::ZERO {
                    normals.push(fallback(corner_face[c]));
                    (normals.len() - 1) as u32
                } else {
                    v
                }
            })
            .collect();
        return CornerNormals::new(normals, corner);
    }

    // Whether face `other` takes part in the normals of face `own`'s corners.
    let cos_limit = crease_degrees.map(|d| d.to_radians().cos());
    let joins = |own: usize, own_normal: Vec3, other: usize| {
        let same_group = groups
            .is_none_or(|g| g[other] == g[own] && (g[own] != Mesh::NOT_SMOOTHED || other == own));
        let within_crease = cos_limit
            .is_none_or(|limit| faces[other].is_some_and(|n| n.dot(own_normal) >= limit - 1e-6));
        same_group && within_crease
    };
    let mut corners_of_vertex = vec![Vec::new(); positions.len()];
    for (c, &v) in mesh.corners().iter().enumerate() {
        corners_of_vertex[v as usize].push(c as u32);
    }
    let mut normals = Vec::new();
    let mut seen: HashMap<(u32, [u32; 3]), u32> = HashMap::new();
    let corner = mesh
        .corners()
        .iter()
        .enumerate()
        .map(|(c, &v)| {
            let face = corner_face[c];
            let n = faces[face]
                .and_then(|own| {
                    corners_of_vertex[v as usize]
                        .iter()
                        .filter(|&&o| joins(face, own, corner_face[o as usize]))
                        .map(|&o| contribution[o as usize])
                        .sum::<Vec3>()
                        .try_normalize()
                })
                .unwrap_or_else(|| fallback(face));
            let key = (v, n.to_array().map(f32::to_bits));
            *seen.entry(key).or_insert_with(|| {
                normals.push(n);
                (normals.len() - 1) as u32
            })
        })
        .collect();
    CornerNormals::new(normals, corner)
}
