//! The vertex stage (step 1 of `mod.rs`): the mesh's distinct (position,
//! normal) pairs and face normals, kept from frame to frame, and Gouraud's
//! per-vertex lighting, 8 vertices at a time.

use std::collections::HashMap;

use glam::Vec3;
use rayon::prelude::*;

use crate::scene::{RenderOptions, Scene};
use crate::shade::{byte_units, PhongShader, Terms, MAX_ATTRS};
use crate::simd::{dispatch, Kernel, Lanes, Simd, SimdLevel, Vf};

/// Distinct (position, normal) pairs of a mesh, rebuilt only when the
/// mesh's geometry or its corner normal indices change.
#[derive(Debug, Default)]
pub(super) struct VertexTable {
    /// The geometry it was built for ([`crate::mesh::Mesh::geometry_id`], 0: none).
    pub(super) key_geometry: u64,
    pub(super) key_normals: Vec<u32>,
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
    pub(super) fn update(
        &mut self,
        mesh: &crate::mesh::Mesh,
        corner_normals: &[u32],
        normal_count: usize,
    ) {
        if self.key_geometry == mesh.geometry_id() && same(&self.key_normals, corner_normals) {
            return;
        }
        let corners = mesh.corners();
        self.key_geometry = mesh.geometry_id();
        self.key_normals.clear();
        self.key_normals.extend_from_slice(corner_normals);
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

/// `a == b`, compared in parallel: the vertex table is keyed by the scene's
/// corner normal indices (which a caller may change between frames without
/// changing the mesh), checked every frame.
///
/// Each run of 64 indices is compared by OR-ing the differences, which the
/// compiler turns into lane operations: `==` on slices is a `memcmp` call,
/// which in WebAssembly compares byte by byte (4 % of the dragon's frame of
/// the three methods at once).
pub(super) fn same(a: &[u32], b: &[u32]) -> bool {
    const CHUNK: usize = 1 << 14;
    const RUN: usize = 64;
    let same_run = |x: &[u32], y: &[u32]| x.iter().zip(y).fold(0, |d, (x, y)| d | (x ^ y)) == 0;
    a.len() == b.len()
        && a.par_chunks(CHUNK).zip(b.par_chunks(CHUNK)).all(|(x, y)| {
            x.chunks(RUN)
                .zip(y.chunks(RUN))
                .all(|(x, y)| same_run(x, y))
        })
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
    let normals = &scene.normals;
    vertices.update(&scene.mesh, &normals.corner, normals.normals.len());
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
                    normals: &normals.normals,
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

    use super::{same, VertexTable};
    use crate::mesh::Mesh;

    /// A square of two triangles: positions 0 1 2 and 0 2 3.
    fn square() -> Mesh {
        let positions = vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y];
        Mesh::from_polygons(positions, [[0, 1, 2], [0, 2, 3]]).unwrap()
    }

    #[test]
    fn corner_vertex_is_the_normal_index_unless_a_normal_is_shared() {
        let mesh = square();
        // One normal per position: each corner's vertex is its normal index.
        let per_position = [0, 1, 2, 0, 2, 3];
        let mut table = VertexTable::default();
        table.update(&mesh, &per_position, 4);
        assert!(table.identity);
        assert_eq!(table.corner_vertex, per_position);
        assert_eq!(table.corner_vertex(&per_position), per_position);
        // One normal for the whole square (flat): positions 1..3 share
        // position 0's normal, so they get vertices of their own.
        let shared = [0; 6];
        table.update(&mesh, &shared, 1);
        assert!(!table.identity);
        assert_eq!(table.corner_vertex(&shared), [0, 1, 2, 0, 2, 3]);
        assert_eq!(table.position, [0, 1, 2, 3]);
        assert_eq!(table.normal, [0, 0, 0, 0]);
    }

    #[test]
    fn same_finds_any_difference() {
        // Lengths around the runs (64) and the parallel chunks (2^14).
        for len in [
            0usize,
            1,
            63,
            64,
            65,
            1000,
            (1 << 14) - 1,
            1 << 14,
            (1 << 14) + 70,
        ] {
            let a: Vec<u32> = (0..len as u32)
                .map(|i| i.wrapping_mul(2_654_435_761))
                .collect();
            assert!(same(&a, &a.clone()), "{len}");
            for at in [0, len / 2, len.saturating_sub(1)] {
                if at < len {
                    let mut b = a.clone();
                    b[at] ^= 1 << (at % 32);
                    assert!(!same(&a, &b), "{len} {at}");
                }
            }
            let mut longer = a.clone();
            longer.push(0);
            assert!(!same(&a, &longer), "{len}");
        }
    }
}
