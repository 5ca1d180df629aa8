//! The vertex stage (step 1 of `mod.rs`): the mesh's distinct (position,
//! normal) pairs and face normals, kept from frame to frame, and Gouraud's
//! per-vertex lighting, 8 vertices at a time.

use std::collections::HashMap;

use glam::Vec3;
use rayon::prelude::*;

use crate::mesh::CornerNormals;
use crate::scene::{RenderOptions, Scene};
use crate::shade::{byte_units, PhongShader, Terms, MAX_ATTRS};
use crate::simd::{dispatch, Kernel, Lanes, Simd, SimdLevel, Vf};

/// Distinct (position, normal) pairs of a mesh, rebuilt only when the
/// mesh's geometry or its corner normal indices change: both are named by
/// ids ([`crate::mesh::Mesh::geometry_id`],
/// [`crate::mesh::CornerNormals::indices_id`]), so a frame checks the table
/// by comparing three numbers instead of reading the indices (two arrays of
/// 1.2 MB on the dragon, every frame and in each of the viewer's workers).
#[derive(Debug, Default)]
pub(super) struct VertexTable {
    /// What it was built for: the geometry, the corner normal indices and
    /// how many normals they index (0: none).
    key: (u64, u64, usize),
    /// Per corner, its vertex.
    corner_vertex: Vec<u32>,
    /// Whether each corner's vertex is its normal index (no normal is
    /// shared by two positions): `corner_vertex` then equals the corner
    /// normal indices it was built from.
    identity: bool,
    /// Per vertex, its position and normal index (`u32::MAX` when unused).
    pub(super) position: Vec<u32>,
    pub(super) normal: Vec<u32>,
    pub(super) used: u64,
}

impl VertexTable {
    pub(super) fn update(&mut self, mesh: &crate::mesh::Mesh, normals: &CornerNormals) {
        let key = (
            mesh.geometry_id(),
            normals.indices_id(),
            normals.normals.len(),
        );
        if self.key == key {
            return;
        }
        self.key = key;
        let corner_normals = normals.corner();
        let normal_count = normals.normals.len();
        let corners = mesh.corners();
        // A vertex per normal index, owned by the first position using it;
        // a normal shared by several positions gets extra vertices.
        self.position.clear();
        self.position.resize(normal_count, u32::MAX);
        self.normal.clear();
        self.normal.extend(0..normal_count as u32);
        self.corner_vertex.clear();
        let mut extra: HashMap<(u32, u32), u32> = HashMap::new();
        for (&p, &n) in corners.iter().zip(corner_normals) {
            let owner = &mut self.position[n as usize];
            let id = if *owner == u32::MAX || *owner == p {
                *owner = p;
                n
            } else {
                *extra.entry((p, n)).or_insert_with(|| {
                    self.normal.push(n);
                    (self.normal.len() - 1) as u32
                })
            };
            self.corner_vertex.push(id);
        }
        self.position.resize(self.normal.len(), u32::MAX);
        for (&(p, _), &id) in &extra {
            self.position[id as usize] = p;
        }
        self.used = self.position.iter().filter(|&&p| p != u32::MAX).count() as u64;
        self.identity = extra.is_empty();
    }

    /// Per corner, its vertex, for the corner normal indices the table was
    /// last built for (`corner_normals`, unless it is not in use). Where
    /// each corner's vertex is its normal index (nearly every mesh), that
    /// is `corner_normals` itself: setup, which reads a corner's normal
    /// index for Phong, then reads the same memory for Gouraud's colour
    /// instead of a second array as large (1.2 MB on the dragon, read per
    /// frame of the three methods at once).
    pub(super) fn corner_vertex<'a>(&'a self, corner_normals: &'a [u32]) -> &'a [u32] {
        if self.identity {
            corner_normals
        } else {
            &self.corner_vertex
        }
    }
}

/// Gouraud's vertex colours, 8 vertices per SIMD evaluation, clamped to
/// [0, 1] as `Lighting::eval(..).clamped()`.
pub(super) struct VertexKernel<'a> {
    pub(super) first: usize,
    pub(super) colors: &'a mut [[f32; 3]],
    pub(super) table: &'a VertexTable,
    pub(super) positions: &'a [Vec3],
    pub(super) normals: &'a [Vec3],
    pub(super) sign: f32,
    pub(super) shader: &'a PhongShader,
    pub(super) specular: bool,
}

impl Kernel for VertexKernel<'_> {
    type Output = ();

    #[inline(always)]
    fn run<S: Simd>(self, s: S) {
        let t = self.table;
        for (j, colors) in self.colors.chunks_mut(8).enumerate() {
            let base = self.first + 8 * j;
            let mut lanes = [[0f32; 8]; 6];
            for (i, v) in (base..base + colors.len()).enumerate() {
                let p = t.position[v];
                if p == u32::MAX {
                    continue;
                }
                let n = self.normals[t.normal[v] as usize] * self.sign;
                let q = self.positions[p as usize];
                for (k, value) in [n.x, n.y, n.z, q.x, q.y, q.z].into_iter().enumerate() {
                    lanes[k][i] = value;
                }
            }
            let attrs: [Vf<S>; MAX_ATTRS] = std::array::from_fn(|k| Vf::load(s, &lanes[k]));
            let rgb = self.shader.radiance(&attrs, self.specular);
            let mut out = [[0f32; 8]; 3];
            for k in 0..3 {
                let c = rgb[k].max(Vf::splat(s, 0.0)).min(Vf::splat(s, 1.0));
                byte_units(c).store(&mut out[k]);
            }
            for (i, color) in colors.iter_mut().enumerate() {
                *color = [out[0][i], out[1][i], out[2][i]];
            }
        }
    }
}

/// Gouraud's per-vertex lighting into `lit` (and `lit_back` for back faces
/// drawn), with the frame's lighting already in `shader`; returns the
/// number of evaluations.
pub(super) fn light_vertices(
    vertices: &mut VertexTable,
    lit: &mut Vec<[f32; 3]>,
    lit_back: &mut Vec<[f32; 3]>,
    shader: &PhongShader,
    simd: SimdLevel,
    scene: &Scene,
    options: &RenderOptions,
) -> u64 {
    vertices.update(&scene.mesh, &scene.normals);
    let terms = if options.gouraud_specular {
        Terms::Full
    } else {
        Terms::AmbientDiffuse
    };
    let table = &*vertices;
    let positions = scene.mesh.positions();
    let light = |out: &mut Vec<[f32; 3]>, sign: f32| {
        out.resize(table.position.len(), [0.0; 3]);
        out.par_chunks_mut(1024)
            .enumerate()
            .for_each(|(k, colors)| {
                let kernel = VertexKernel {
                    first: k * 1024,
                    colors,
                    table,
                    positions,
                    normals: &scene.normals.normals,
                    sign,
                    shader,
                    specular: terms == Terms::Full,
                };
                dispatch(simd, kernel);
            });
    };
    light(lit, 1.0);
    if options.cull_backfaces {
        table.used
    } else {
        light(lit_back, -1.0);
        2 * table.used
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::VertexTable;
    use crate::mesh::{CornerNormals, Mesh};

    /// A square of two triangles: positions 0 1 2 and 0 2 3.
    fn square() -> Mesh {
        let positions = vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y];
        Mesh::from_polygons(positions, [[0, 1, 2], [0, 2, 3]]).unwrap()
    }

    fn normals(count: usize, corner: &[u32]) -> CornerNormals {
        CornerNormals::new(vec![Vec3::Z; count], corner.to_vec())
    }

    #[test]
    fn corner_vertex_is_the_normal_index_unless_a_normal_is_shared() {
        let mesh = square();
        // One normal per position: each corner's vertex is its normal index.
        let per_position = normals(4, &[0, 1, 2, 0, 2, 3]);
        let mut table = VertexTable::default();
        table.update(&mesh, &per_position);
        assert!(table.identity);
        assert_eq!(table.corner_vertex, per_position.corner());
        assert_eq!(
            table.corner_vertex(per_position.corner()),
            per_position.corner()
        );
        // One normal for the whole square (flat): positions 1..3 share
        // position 0's normal, so they get vertices of their own.
        let shared = normals(1, &[0; 6]);
        table.update(&mesh, &shared);
        assert!(!table.identity);
        assert_eq!(table.corner_vertex(shared.corner()), [0, 1, 2, 0, 2, 3]);
        assert_eq!(table.position, [0, 1, 2, 3]);
        assert_eq!(table.normal, [0, 0, 0, 0]);
    }

    /// The table is rebuilt exactly when the geometry, the corner indices
    /// or the number of normals is another one: a clone of either keeps it.
    #[test]
    fn rebuilt_when_the_geometry_or_the_indices_change() {
        let mesh = square();
        let per_position = normals(4, &[0, 1, 2, 0, 2, 3]);
        let mut table = VertexTable::default();
        // Built for the first time (a default table is built for nothing).
        table.update(&mesh, &per_position);
        assert_eq!(table.used, 4);
        // A marker that only a rebuild overwrites.
        let kept = |table: &mut VertexTable, mesh: &Mesh, normals: &CornerNormals| {
            table.used = 99;
            table.update(mesh, normals);
            table.used == 99
        };
        assert!(kept(&mut table, &mesh, &per_position));
        assert!(kept(&mut table, &mesh.clone(), &per_position.clone()));
        // New indices, even equal ones, are new: rebuilt.
        let same_again = normals(4, per_position.corner());
        assert!(!kept(&mut table, &mesh, &same_again));
        assert_eq!(table.used, 4);
        let shared = normals(1, &[0; 6]);
        assert!(!kept(&mut table, &mesh, &shared));
        assert_eq!(table.used, 4);
        // The same indices into more normals: rebuilt, the extra unused.
        let mut more = shared.clone();
        more.normals.push(Vec3::X);
        assert!(!kept(&mut table, &mesh, &more));
        assert_eq!(table.position, [0, u32::MAX, 1, 2, 3]);
        // Another mesh of the same shape: rebuilt.
        assert!(!kept(&mut table, &square(), &more));
    }
}
