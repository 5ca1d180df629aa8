//! Procedural solids, closed and wound counter-clockwise seen from outside.

use std::collections::HashMap;
use std::f32::consts::{PI, TAU};

use glam::Vec3;

use crate::mesh::Mesh;
use crate::normals::face_normal_unnormalized;

/// Accumulates welded vertices and polygons, orienting each polygon so its
/// normal points away from a given inside point.
#[derive(Default)]
struct Builder {
    positions: Vec<Vec3>,
    polygons: Vec<Vec<u32>>,
    welded: HashMap<[i64; 3], u32>,
}

impl Builder {
    /// The index of a vertex at `p`, shared with any earlier vertex there.
    fn vertex(&mut self, p: Vec3) -> u32 {
        let key = (p * 1e5).round().as_i64vec3().to_array();
        let positions = &mut self.positions;
        *self.welded.entry(key).or_insert_with(|| {
            positions.push(p);
            (positions.len() - 1) as u32
        })
    }

    /// Adds a polygon, dropping repeated corners, wound outward from `inside`.
    fn polygon(&mut self, points: &[Vec3], inside: Vec3) {
        let mut indices: Vec<u32> = points.iter().map(|&p| self.vertex(p)).collect();
        indices.dedup();
        while indices.len() > 1 && indices.first() == indices.last() {
            indices.pop();
        }
        if indices.len() < 3 {
            return;
        }
        let corners: Vec<Vec3> = indices
            .iter()
            .map(|&i| self.positions[i as usize])
            .collect();
        let centroid = corners.iter().sum::<Vec3>() / corners.len() as f32;
        if face_normal_unnormalized(&corners).dot(centroid - inside) < 0.0 {
            indices.reverse();
        }
        self.polygons.push(indices);
    }

    fn build(self) -> Mesh {
        Mesh::from_polygons(self.positions, self.polygons).expect("procedural meshes are valid")
    }
}

/// A cube of side 2 centred on the origin, each face split into `n` × `n` quads.
pub fn cube(n: u32) -> Mesh {
    let mut b = Builder::default();
    let step = 2.0 / n as f32;
    for axis in 0..3 {
        for sign in [-1.0f32, 1.0] {
            let normal = Vec3::AXES[axis] * sign;
            let u = Vec3::AXES[(axis + 1) % 3];
            let v = Vec3::AXES[(axis + 2) % 3];
            for i in 0..n {
                for j in 0..n {
                    let at = |a: u32, c: u32| {
                        normal + u * (-1.0 + a as f32 * step) + v * (-1.0 + c as f32 * step)
                    };
                    b.polygon(
                        &[at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)],
                        Vec3::ZERO,
                    );
                }
            }
        }
    }
    b.build()
}

/// A UV sphere of radius 1: `slices` around the y axis, `slices / 2` stacks.
pub fn uv_sphere(slices: u32) -> Mesh {
    let stacks = (slices / 2).max(2);
    let mut b = Builder::default();
    let at = |i: u32, j: u32| {
        let theta = PI * i as f32 / stacks as f32;
        let phi = TAU * (j % slices) as f32 / slices as f32;
        if i == 0 {
            Vec3::Y
        } else if i == stacks {
            -Vec3::Y
        } else {
            Vec3::new(
                theta.sin() * phi.cos(),
                theta.cos(),
                -theta.sin() * phi.sin(),
            )
        }
    };
    for i in 0..stacks {
        for j in 0..slices {
            b.polygon(
                &[at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)],
                Vec3::ZERO,
            );
        }
    }
    b.build()
}

/// An icosahedron subdivided `levels` times, on the unit sphere.
pub fn icosphere(levels: u32) -> Mesh {
    let t = (1.0 + 5f32.sqrt()) / 2.0;
    let mut corners: Vec<Vec3> = [
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ]
    .iter()
    .map(|&p| Vec3::from_array(p).normalize())
    .collect();
    let mut triangles: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..levels {
        let mut midpoints: HashMap<(u32, u32), u32> = HashMap::new();
        let mut midpoint = |a: u32, b: u32, corners: &mut Vec<Vec3>| {
            *midpoints.entry((a.min(b), a.max(b))).or_insert_with(|| {
                corners.push(((corners[a as usize] + corners[b as usize]) * 0.5).normalize());
                (corners.len() - 1) as u32
            })
        };
        triangles = triangles
            .iter()
            .flat_map(|&[a, b, c]| {
                let ab = midpoint(a, b, &mut corners);
                let bc = midpoint(b, c, &mut corners);
                let ca = midpoint(c, a, &mut corners);
                [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]
            })
            .collect();
    }
    let mut b = Builder::default();
    for [i, j, k] in triangles {
        b.polygon(
            &[
                corners[i as usize],
                corners[j as usize],
                corners[k as usize],
            ],
            Vec3::ZERO,
        );
    }
    b.build()
}

/// A torus around the y axis: ring radius 1, tube radius 0.4, `segments`
/// around the ring and `segments / 2` around the tube.
pub fn torus(segments: u32) -> Mesh {
    let (ring, tube) = (1.0f32, 0.4f32);
    let sides = (segments / 2).max(3);
    let mut b = Builder::default();
    let centre = |i: u32| {
        let phi = TAU * (i % segments) as f32 / segments as f32;
        Vec3::new(phi.cos(), 0.0, -phi.sin()) * ring
    };
    let at = |i: u32, j: u32| {
        let theta = TAU * (j % sides) as f32 / sides as f32;
        let c = centre(i);
        c + c.normalize() * (tube * theta.cos()) + Vec3::Y * (tube * theta.sin())
    };
    for i in 0..segments {
        let inside = (centre(i) + centre(i + 1)) * 0.5;
        for j in 0..sides {
            b.polygon(
                &[at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)],
                inside,
            );
        }
    }
    b.build()
}

fn rim(slices: u32, y: f32) -> Vec<Vec3> {
    (0..slices)
        .map(|j| {
            let phi = TAU * j as f32 / slices as f32;
            Vec3::new(phi.cos(), y, -phi.sin())
        })
        .collect()
}

/// A cylinder of radius 1 from y = −1 to y = 1: `slices` quads around, and
/// one `slices`-gon for each cap.
pub fn cylinder(slices: u32) -> Mesh {
    let (bottom, top) = (rim(slices, -1.0), rim(slices, 1.0));
    let mut b = Builder::default();
    for j in 0..slices as usize {
        let k = (j + 1) % slices as usize;
        b.polygon(&[bottom[j], bottom[k], top[k], top[j]], Vec3::ZERO);
    }
    b.polygon(&top, Vec3::ZERO);
    b.polygon(&bottom, Vec3::ZERO);
    b.build()
}

/// A cone of radius 1 with its base at y = −1 and its apex at y = 1:
/// `slices` triangles around and one `slices`-gon for the base.
pub fn cone(slices: u32) -> Mesh {
    let base = rim(slices, -1.0);
    let apex = Vec3::Y;
    let mut b = Builder::default();
    for j in 0..slices as usize {
        let k = (j + 1) % slices as usize;
        b.polygon(&[base[j], base[k], apex], Vec3::ZERO);
    }
    b.polygon(&base, Vec3::ZERO);
    b.build()
}
