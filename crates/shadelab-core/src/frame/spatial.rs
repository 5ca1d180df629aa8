//! A mesh's polygons in a spatial order, for the tiled rasterizer: the
//! Morton order of their centroids, 10 bits per axis over the centroids'
//! box, polygons of one cell in the file's order; and a copy of a scene
//! whose mesh lists its polygons in that order ([`SpatialScene`]).
//!
//! Why: the tiled rasterizer's setup walks the polygons in chunks, and a
//! mesh whose file lists its faces in no spatial order (the 100k dragon:
//! 0.43 of its faces share a vertex with one of the 8 before them, the cow
//! 0.94) sends every polygon's corner loads, facing branch and bin pushes
//! somewhere new. Walked in this order, one frame of the dragon took 0.79
//! of the file order's time in a viewer part (WebAssembly) and 0.86–0.89
//! natively (BENCHMARKS.md, "The dragon's face order").
//!
//! Why a copy: walking the file's polygons through a permutation made every
//! per-polygon stream (corners, offsets, face normals, centroids, corner
//! normals) a random one, and the dragon's frame took 2–3 times as long
//! (BENCHMARKS.md, "The dragon in a spatial order, exactly"). The copy
//! lists the same polygons, each with its corners in the same order, with
//! each corner's normal the original's, and numbers the positions and the
//! normals in the order its polygons first use them (the dragon numbers
//! them in its faces' order, which would leave near polygons reading far
//! positions). The normals' numbers matter as much as the positions':
//! Gouraud's vertex colours are stored by normal, and a thread's setup reads
//! the colours of its own polygons. In the file's numbering those were lit
//! by both threads alike, and with the two cores apart half of the colours
//! crossed between them every frame (the bunny's and the dragon's Gouraud
//! frames at 1.78× one thread's speed on two, flat's and Phong's at
//! 1.86–1.9×: BENCHMARKS.md, "Normals numbered in the copy's order").
//! The vertex normals are the ones summed in the file's order, every
//! polygon's face normal, centroid and fan are the same numbers, and so is
//! every fragment.
//!
//! What the order changes is which of two fragments at the same depth the
//! depth test keeps ("less" keeps the first drawn). The tiled rasterizer
//! watches for such ties while it draws the copy
//! (`TiledRasterizer::watch_ties`, `TiledRasterizer::met_ties`), and the
//! frame that met one is drawn again from the scene itself
//! (`frame/mod.rs`): the pixels are always the file order's. So are the
//! counts, but for the fragments that passed the depth test on their way
//! (Phong's evaluations among them), which depend on the order by nature.
//!
//! The order is built in linear time: two passes of a counting sort on 15
//! bits of the code each (stable, so the second keeps the first's order
//! within a digit).

use glam::Vec3;

use super::Geometry;
use crate::mesh::{CornerNormals, Mesh};
use crate::scene::Scene;
use crate::simd::SimdLevel;

/// Meshes of fewer polygons are walked in their file's order: their
/// corners and bins stay in a core's second-level cache whatever the
/// order (as the tiled rasterizer's streamed images, 16,384 polygons
/// at 64 bytes or more each fill 1 MB).
pub(crate) const SPATIAL_POLYGONS: usize = 16_384;

/// Meshes of more polygons are walked in their file's order: the copy
/// would take some 70 bytes a polygon more (at this limit, 140 MB).
pub(crate) const SPATIAL_MAX_POLYGONS: usize = 2_000_000;

/// A copy of the last scene drawn, its polygons in a spatial order, kept
/// from frame to frame with its own face normals and vertex stage.
///
/// Made on the second frame in a row of one mesh and normals (a mesh drawn
/// once, as in a batch, does not pay for it), and given up for that mesh
/// once a frame of it met a depth tie (a mesh drawn twice over itself
/// would otherwise draw every frame twice).
#[derive(Debug)]
pub(crate) struct SpatialScene {
    /// The last frame's mesh geometry and normal indices.
    seen: (u64, u64),
    /// What the copy is of, and whether a frame of it met a tie.
    key: (u64, u64),
    tied: bool,
    copy: Option<Scene>,
    /// The scene's normals the copy's were last taken from, and, per
    /// normal of the copy, the index of the scene's it is.
    normals_of: Vec<Vec3>,
    normal_order: Vec<u32>,
    geometry: Geometry,
}

impl SpatialScene {
    /// No copy yet; the copy's vertex stage runs at `level` (see
    /// [`Geometry::with_simd`]).
    pub(crate) fn with_simd(level: SimdLevel) -> SpatialScene {
        SpatialScene {
            seen: (0, 0),
            key: (0, 0),
            tied: false,
            copy: None,
            normals_of: Vec::new(),
            normal_order: Vec::new(),
            geometry: Geometry::with_simd(level),
        }
    }

    /// `scene` with its polygons in a spatial order, and the copy's
    /// geometry, where the tiled rasterizer should draw that: `None` for a
    /// mesh of fewer than [`SPATIAL_POLYGONS`] or more than
    /// [`SPATIAL_MAX_POLYGONS`] polygons, on the first frame of a mesh, and
    /// for a mesh a frame of which met a tie. `geometry` is the scene's own
    /// (its face normals and centroids, which the copy reorders).
    pub(crate) fn update(
        &mut self,
        scene: &Scene,
        geometry: &mut Geometry,
    ) -> Option<(&Scene, &mut Geometry)> {
        let count = scene.mesh.polygon_count();
        if !(SPATIAL_POLYGONS..=SPATIAL_MAX_POLYGONS).contains(&count) {
            return None;
        }
        let key = (scene.mesh.geometry_id(), scene.normals.indices_id());
        if key != self.key {
            let again = key == self.seen;
            self.seen = key;
            self.copy = None;
            if !again {
                return None;
            }
            self.key = key;
            self.tied = false;
            let (faces, centroids) = geometry.faces_of(&scene.mesh);
            let (copy, faces, centroids) =
                spatial_copy(scene, faces, centroids, &mut self.normal_order)?;
            self.geometry.adopt_faces(&copy.mesh, faces, centroids);
            self.normals_of.clone_from(&scene.normals.normals);
            self.copy = Some(copy);
        }
        if self.tied {
            return None;
        }
        let copy = self.copy.as_mut()?;
        copy.camera = scene.camera;
        copy.ambient = scene.ambient;
        copy.material = scene.material;
        copy.lights.clone_from(&scene.lights);
        // The same indices with other values (another weighting of the
        // faces' normals, say): taken again, in the copy's numbering.
        if self.normals_of != scene.normals.normals {
            if scene.normals.normals.len() != self.normal_order.len() {
                return None;
            }
            self.normals_of.clone_from(&scene.normals.normals);
            let normals = self
                .normal_order
                .iter()
                .map(|&n| self.normals_of[n as usize]);
            copy.normals.normals.clear();
            copy.normals.normals.extend(normals);
        }
        Some((copy, &mut self.geometry))
    }

    /// Notes that the last frame of the copy met a depth tie: the mesh is
    /// drawn from the scene itself from now on.
    pub(crate) fn met_tie(&mut self) {
        self.tied = true;
    }

    /// Whether there is a copy to draw (for tests).
    #[cfg(test)]
    pub(crate) fn has_copy(&self) -> bool {
        self.copy.is_some() && !self.tied
    }
}

/// `scene` with its mesh's polygons in [`spatial_order`], each with its
/// corners in the same order and the same normals, and the positions and
/// the normals numbered in the order those polygons first use them (so
/// that near polygons read near positions and normals; the ones no polygon
/// uses come last); with the copy's face normals and centroids, `faces`
/// and `centroids` (the mesh's) reordered. `normal_order` receives, per
/// normal of the copy, the index of the scene's it is. `None` if it cannot
/// be made (it always can of a valid scene).
///
/// Made on a frame of the viewer, which waits for it: every array is
/// allocated once at its size, and nothing is computed again that the
/// scene's own frames have (the face normals and centroids).
fn spatial_copy(
    scene: &Scene,
    faces: &[Option<Vec3>],
    centroids: &[Vec3],
    normal_order: &mut Vec<u32>,
) -> Option<(Scene, Vec<Option<Vec3>>, Vec<Vec3>)> {
    let mesh = &scene.mesh;
    let mut order = Vec::new();
    spatial_order(centroids, &mut order);
    let (old, mut position_order) = (mesh.positions(), Vec::new());
    let mut corners = Vec::with_capacity(mesh.corners().len());
    let used = order.iter().flat_map(|&f| mesh.polygon(f as usize));
    first_use(old.len(), used, &mut corners, &mut position_order)?;
    let positions = position_order.iter().map(|&v| old[v as usize]).collect();
    let mut offsets = Vec::with_capacity(order.len() + 1);
    offsets.push(0);
    offsets.extend(order.iter().scan(0, |at, &f| {
        *at += mesh.polygon(f as usize).len() as u32;
        Some(*at)
    }));
    let copy = Mesh::from_parts(positions, corners, offsets).ok()?;
    let (old, corner_normals) = (&scene.normals.normals, scene.normals.corner());
    let mut corner = Vec::with_capacity(corner_normals.len());
    let used = order
        .iter()
        .flat_map(|&f| &corner_normals[mesh.corner_range(f as usize)]);
    first_use(old.len(), used, &mut corner, normal_order)?;
    let normals = normal_order.iter().map(|&n| old[n as usize]).collect();
    let faces = order.iter().map(|&f| faces[f as usize]).collect();
    let centroids = order.iter().map(|&f| centroids[f as usize]).collect();
    let scene = Scene {
        mesh: copy,
        normals: CornerNormals::new(normals, corner),
        camera: scene.camera,
        ambient: scene.ambient,
        lights: scene.lights.clone(),
        material: scene.material,
    };
    Some((scene, faces, centroids))
}

/// Numbers `count` items in the order that `used`, the copy's corners,
/// first use them: pushes each corner's new number onto `corners`, and
/// fills `order` with the old index of each new number (the items no
/// corner uses last, in their order). `None` if a corner names an item
/// past `count`.
fn first_use<'a>(
    count: usize,
    used: impl Iterator<Item = &'a u32>,
    corners: &mut Vec<u32>,
    order: &mut Vec<u32>,
) -> Option<()> {
    let mut renumbered = vec![u32::MAX; count];
    order.clear();
    for &old in used {
        let new = renumbered.get_mut(old as usize)?;
        if *new == u32::MAX {
            *new = order.len() as u32;
            order.push(old);
        }
        corners.push(*new);
    }
    let unused = (0..count as u32).filter(|&old| renumbered[old as usize] == u32::MAX);
    order.extend(unused);
    Some(())
}

/// Bits of the Morton code per axis.
const BITS: u32 = 10;

/// Bits of the code sorted per pass.
const DIGIT: u32 = 15;

/// Fills `order` with the polygons of `centroids` in Morton order of their
/// centroids (ties in index order), or empties it for a mesh of fewer than
/// [`SPATIAL_POLYGONS`] polygons. A centroid that is not finite counts as
/// the box's corner.
pub(crate) fn spatial_order(centroids: &[Vec3], order: &mut Vec<u32>) {
    order.clear();
    let n = centroids.len();
    if n < SPATIAL_POLYGONS || u32::try_from(n).is_err() {
        return;
    }
    let finite = || centroids.iter().filter(|c| c.is_finite());
    let low = finite().fold(Vec3::splat(f32::MAX), |a, &c| a.min(c));
    let high = finite().fold(Vec3::splat(f32::MIN), |a, &c| a.max(c));
    let top = ((1 << BITS) - 1) as f32;
    let scale = (high - low).max(Vec3::splat(f32::MIN_POSITIVE));
    let codes: Vec<u32> = centroids
        .iter()
        .map(|&c| {
            if !c.is_finite() {
                return 0;
            }
            let q = ((c - low) / scale * top).clamp(Vec3::ZERO, Vec3::splat(top));
            spread(q.x as u32) | spread(q.y as u32) << 1 | spread(q.z as u32) << 2
        })
        .collect();
    order.extend(0..n as u32);
    let mut spare = vec![0u32; n];
    let mut counts = vec![0u32; 1 << DIGIT];
    for pass in 0..(3 * BITS).div_ceil(DIGIT) {
        let digit = |i: u32| ((codes[i as usize] >> (pass * DIGIT)) & ((1 << DIGIT) - 1)) as usize;
        counts.fill(0);
        for &i in order.iter() {
            counts[digit(i)] += 1;
        }
        let mut at = 0;
        for count in &mut counts {
            (*count, at) = (at, at + *count);
        }
        for &i in order.iter() {
            let d = digit(i);
            spare[counts[d] as usize] = i;
            counts[d] += 1;
        }
        std::mem::swap(order, &mut spare);
    }
}

/// The low [`BITS`] bits of `v` moved to every third bit (bit `b` to bit
/// `3·b`): each step moves the upper half of every group of bits up by
/// twice its width.
fn spread(v: u32) -> u32 {
    let x = v & 0x3ff;
    let x = (x | x << 16) & 0x0300_00ff;
    let x = (x | x << 8) & 0x0300_f00f;
    let x = (x | x << 4) & 0x030c_30c3;
    (x | x << 2) & 0x0924_9249
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::Camera;
    use crate::normals::{face_geometry, vertex_normals, NormalWeighting};

    #[test]
    fn small_meshes_keep_their_order() {
        let mut order = vec![7];
        spatial_order(&[Vec3::ZERO; 100], &mut order);
        assert!(order.is_empty());
    }

    #[test]
    fn the_order_is_a_permutation_sorted_by_morton_code() {
        // Points on a jittered grid, listed in a scrambled order.
        let n = SPATIAL_POLYGONS + 1000;
        let points: Vec<Vec3> = (0..n)
            .map(|i| {
                let k = (i * 7919) % n;
                Vec3::new(
                    (k % 37) as f32,
                    (k / 37 % 23) as f32,
                    (k / 851) as f32 * 0.5,
                )
            })
            .collect();
        let mut order = Vec::new();
        spatial_order(&points, &mut order);
        let mut seen = vec![false; n];
        for &i in &order {
            assert!(!std::mem::replace(&mut seen[i as usize], true));
        }
        assert!(seen.iter().all(|&s| s));
        // Neighbours in the order are near in space far more often than
        // neighbours in the list.
        let near = |a: u32, b: u32| points[a as usize].distance(points[b as usize]) < 2.5;
        let ordered = order.windows(2).filter(|w| near(w[0], w[1])).count();
        let listed = (1..n as u32).filter(|&i| near(i - 1, i)).count();
        assert!(ordered > n * 3 / 4 && listed < n / 4, "{ordered} {listed}");
    }

    #[test]
    fn equal_codes_keep_index_order_and_odd_centroids_do_not_panic() {
        let mut points = vec![Vec3::ONE; SPATIAL_POLYGONS];
        points[3] = Vec3::NAN;
        points[5] = Vec3::splat(f32::INFINITY);
        let mut order = Vec::new();
        spatial_order(&points, &mut order);
        assert_eq!(order.len(), points.len());
        // All finite centroids are one point: code 0, like the others.
        assert!(order.windows(2).all(|w| w[0] < w[1]));
    }

    #[test]
    fn spread_interleaves() {
        assert_eq!(spread(0b11), 0b1001);
        assert_eq!(spread(1023), 0o1111111111);
        // Every input, against moving one bit at a time; bits past the
        // tenth are dropped.
        for v in 0..1 << BITS {
            let slow = (0..BITS).fold(0, |m, b| m | ((v >> b) & 1) << (3 * b));
            assert_eq!(spread(v), slow, "{v}");
            assert_eq!(spread(v | 0xffff_fc00), slow, "{v}");
        }
    }

    /// The copy's mesh lists the scene's polygons in the spatial order,
    /// each with its corners' positions and normals in the same order; the
    /// face normals and centroids it takes over are bit for bit those
    /// computed from its own mesh.
    #[test]
    fn the_copy_is_the_mesh_reordered_with_its_face_numbers() {
        let mesh = crate::models::builtin_model("torus", Some(256)).unwrap();
        assert!(mesh.polygon_count() >= SPATIAL_POLYGONS);
        let normals = vertex_normals(&mesh, NormalWeighting::Uniform, None);
        let camera = Camera::framing_sphere(Vec3::ZERO, 2.0, 40.0, 1.5);
        let scene = crate::frame::tests::lit_scene(mesh, normals, camera);
        let mesh = &scene.mesh;
        let (mut faces, mut centroids) = (Vec::new(), Vec::new());
        face_geometry(mesh, &mut faces, &mut centroids);
        let mut normal_order = Vec::new();
        let (copy, copy_faces, copy_centroids) =
            spatial_copy(&scene, &faces, &centroids, &mut normal_order).unwrap();
        let mut order = Vec::new();
        spatial_order(&centroids, &mut order);
        assert_eq!(copy.mesh.polygon_count(), mesh.polygon_count());
        assert_eq!(copy.mesh.positions().len(), mesh.positions().len());
        for (new, &old) in order.iter().enumerate() {
            let at = |m: &Mesh, f: usize| -> Vec<Vec3> {
                m.polygon(f)
                    .iter()
                    .map(|&v| m.positions()[v as usize])
                    .collect()
            };
            assert_eq!(at(&copy.mesh, new), at(mesh, old as usize));
            let normals = |s: &Scene, f: usize| -> Vec<Vec3> {
                s.normals.corner()[s.mesh.corner_range(f)]
                    .iter()
                    .map(|&n| s.normals.normals[n as usize])
                    .collect()
            };
            assert_eq!(normals(&copy, new), normals(&scene, old as usize));
        }
        // The normals are numbered as the copy's polygons first use them,
        // each the scene's normal that `normal_order` names.
        assert_eq!(copy.normals.normals.len(), scene.normals.normals.len());
        let mut next = 0;
        for &n in copy.normals.corner() {
            assert!(n <= next, "normal {n} used before normal {next}");
            next = next.max(n + 1);
        }
        assert_eq!(next as usize, copy.normals.normals.len());
        for (new, &old) in normal_order.iter().enumerate() {
            assert_eq!(
                copy.normals.normals[new],
                scene.normals.normals[old as usize]
            );
        }
        let (mut own_faces, mut own_centroids) = (Vec::new(), Vec::new());
        face_geometry(&copy.mesh, &mut own_faces, &mut own_centroids);
        let bits = |v: &Vec3| v.to_array().map(f32::to_bits);
        let face_bits =
            |f: &[Option<Vec3>]| -> Vec<_> { f.iter().map(|n| n.as_ref().map(bits)).collect() };
        assert_eq!(face_bits(&copy_faces), face_bits(&own_faces));
        let centroid_bits = |c: &[Vec3]| -> Vec<_> { c.iter().map(bits).collect() };
        assert_eq!(
            centroid_bits(&copy_centroids),
            centroid_bits(&own_centroids)
        );
    }
}
