//! Polygon meshes: positions and convex polygons that index them.
//!
//! A mesh keeps polygons as they came (triangles, quads, n-gons) because the
//! scanline rasterizer interpolates over a polygon directly, as the textbook
//! does; triangulating would change what Gouraud shading shows on a quad.
//!
//! Besides geometry a mesh may carry what its file said about shading: normals
//! per corner ([`Mesh::file_normals`]) and smoothing groups per face
//! ([`Mesh::smoothing_groups`]), which [`crate::vertex_normals`] honours.
//!
//! Size is bounded so that memory stays predictable whatever a file claims:
//! at most [`Mesh::MAX_TRIANGLES`] triangles (counting a polygon of `n`
//! corners as `n − 2`), [`Mesh::MAX_CORNERS`] corners and
//! [`Mesh::MAX_VERTICES`] vertices. Loaders check these limits against a
//! file's header or running counts before they allocate.

use std::sync::atomic::{AtomicU64, Ordering};

use glam::Vec3;

/// Why a mesh could not be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum MeshError {
    /// The mesh has no polygon at all.
    #[error("the mesh has no faces")]
    NoFaces,
    /// A polygon has fewer than three corners.
    #[error("face {face} has {corners} corners; a face needs at least 3")]
    TooFewCorners {
        /// Index of the face.
        face: usize,
        /// How many corners it has.
        corners: usize,
    },
    /// A polygon refers to a vertex that does not exist.
    #[error("face {face} refers to vertex {index}, but the mesh has {count} vertices")]
    IndexOutOfRange {
        /// Index of the face.
        face: usize,
        /// The offending vertex index.
        index: u32,
        /// How many vertices there are.
        count: usize,
    },
    /// A coordinate is NaN or infinite.
    #[error("vertex {vertex} has a coordinate that is not a finite number: {position}")]
    NonFinite {
        /// Index of the vertex.
        vertex: usize,
        /// The position as read.
        position: Vec3,
    },
    /// Per-corner normals do not match the polygons.
    #[error("normals: {0}")]
    Normals(String),
    /// The mesh exceeds [`Mesh::MAX_CORNERS`].
    #[error("the mesh has {0} face corners; at most {max} are supported", max = Mesh::MAX_CORNERS)]
    TooLarge(usize),
    /// The mesh exceeds [`Mesh::MAX_TRIANGLES`].
    #[error("the mesh has at least {0} triangles; at most {max} are supported", max = Mesh::MAX_TRIANGLES)]
    TooManyTriangles(usize),
    /// The mesh exceeds [`Mesh::MAX_VERTICES`].
    #[error("the mesh has {0} vertices; at most {max} are supported", max = Mesh::MAX_VERTICES)]
    TooManyVertices(usize),
    /// Smoothing groups do not match the polygons.
    #[error("{groups} smoothing groups for {faces} faces")]
    SmoothingGroups {
        /// Groups given.
        groups: usize,
        /// Faces in the mesh.
        faces: usize,
    },
}

/// One normal per polygon corner, by index into a table of unit normals.
///
/// Corners that share a normal share its index, so a renderer can light each
/// distinct (position, normal) pair once. The indices are fixed once made
/// (read them with [`CornerNormals::corner`]): a renderer keys what it
/// derives from them by an id, as it keys what it derives from a mesh's
/// geometry, instead of comparing them every frame. The normals themselves
/// may change freely.
#[derive(Debug, Clone)]
pub struct CornerNormals {
    /// Distinct unit normals.
    pub normals: Vec<Vec3>,
    /// For each corner of each polygon, in [`Mesh::corners`] order, an index into `normals`.
    corner: Vec<u32>,
    /// The largest index in `corner` (0 when there is none), found once so
    /// that a renderer checks the indices against `normals` every frame
    /// without reading them all.
    largest: u32,
    /// Names `corner` (see [`CornerNormals::indices_id`]).
    indices_id: u64,
}

/// Two sets of corner normals are equal when their contents are, whatever
/// their ids.
impl PartialEq for CornerNormals {
    fn eq(&self, other: &CornerNormals) -> bool {
        self.normals == other.normals && self.corner == other.corner
    }
}

impl Default for CornerNormals {
    fn default() -> CornerNormals {
        CornerNormals::new(Vec::new(), Vec::new())
    }
}

impl CornerNormals {
    /// Normals `normals` and, per corner of each polygon in [`Mesh::corners`]
    /// order, an index into them (checked where they meet a mesh:
    /// [`Mesh::with_file_normals`], or the renderer for a scene's normals).
    pub fn new(normals: Vec<Vec3>, corner: Vec<u32>) -> CornerNormals {
        CornerNormals {
            normals,
            largest: corner.iter().copied().max().unwrap_or(0),
            corner,
            indices_id: fresh_geometry_id(),
        }
    }

    /// For each corner of each polygon, in [`Mesh::corners`] order, an index
    /// into [`CornerNormals::normals`].
    pub fn corner(&self) -> &[u32] {
        &self.corner
    }

    /// The largest index in [`CornerNormals::corner`] (0 when there are no
    /// corners).
    pub(crate) fn largest_index(&self) -> u32 {
        self.largest
    }

    /// The normals and the corners' indices, given back.
    pub fn into_parts(self) -> (Vec<Vec3>, Vec<u32>) {
        (self.normals, self.corner)
    }

    /// A number that names the corner indices: two values with the same id
    /// have the same indices (a clone keeps its original's id; every new
    /// value gets a number none had before), so the vertex table built from
    /// them is checked by comparing two numbers, not two arrays of a few MB.
    pub(crate) fn indices_id(&self) -> u64 {
        self.indices_id
    }
}

/// A polygon mesh: vertex positions and convex polygons wound counter-clockwise
/// as seen from outside.
#[derive(Debug, Clone)]
pub struct Mesh {
    positions: Vec<Vec3>,
    corners: Vec<u32>,
    offsets: Vec<u32>,
    file_normals: Option<CornerNormals>,
    smoothing_groups: Option<Vec<u32>>,
    /// Names this geometry (see [`Mesh::geometry_id`]).
    geometry_id: u64,
}

/// Two meshes are equal when their contents are, whatever their geometry ids.
impl PartialEq for Mesh {
    fn eq(&self, other: &Mesh) -> bool {
        self.positions == other.positions
            && self.corners == other.corners
            && self.offsets == other.offsets
            && self.file_normals == other.file_normals
            && self.smoothing_groups == other.smoothing_groups
    }
}

/// A number no mesh or set of corner normals built so far has had.
fn fresh_geometry_id() -> u64 {
    static NEXT: AtomicU64 = AtomicU64::new(1);
    NEXT.fetch_add(1, Ordering::Relaxed)
}

impl Mesh {
    /// The largest number of polygon corners a mesh may have (2^28), so that
    /// every index fits comfortably in `u32` ([`crate::limits::MAX_CORNERS`]).
    pub const MAX_CORNERS: usize = crate::limits::MAX_CORNERS;

    /// The largest number of triangles a mesh may have, a polygon of `n`
    /// corners counting as `n − 2`: 2^24, 16,777,216. Loading and rendering
    /// take about 200 bytes per triangle, so a mesh at the ceiling needs a
    /// few GiB; the largest common scanned meshes (a few million triangles)
    /// are well inside it ([`crate::limits::MAX_TRIANGLES`]).
    pub const MAX_TRIANGLES: usize = crate::limits::MAX_TRIANGLES;

    /// The largest number of vertices a mesh may have: three per triangle of
    /// [`Mesh::MAX_TRIANGLES`], enough for a triangle soup
    /// ([`crate::limits::MAX_VERTICES`]).
    pub const MAX_VERTICES: usize = crate::limits::MAX_VERTICES;

    /// The smoothing group that smooths nothing: a face in it is faceted.
    pub const NOT_SMOOTHED: u32 = 0;

    /// Builds a mesh from positions and polygons given as lists of vertex indices.
    ///
    /// # Errors
    /// [`MeshError`] when there is no polygon, a polygon has fewer than three
    /// corners, an index is out of range, a position is not finite, or the
    /// mesh is beyond [`Mesh::MAX_VERTICES`], [`Mesh::MAX_CORNERS`] or
    /// [`Mesh::MAX_TRIANGLES`].
    pub fn from_polygons<P: AsRef<[u32]>>(
        positions: Vec<Vec3>,
        polygons: impl IntoIterator<Item = P>,
    ) -> Result<Mesh, MeshError> {
        if positions.len() > Self::MAX_VERTICES {
            return Err(MeshError::TooManyVertices(positions.len()));
        }
        let mut corners = Vec::new();
        let mut offsets = vec![0u32];
        let mut triangles = 0usize;
        for polygon in polygons {
            let polygon = polygon.as_ref();
            if corners.len() + polygon.len() > Self::MAX_CORNERS {
                return Err(MeshError::TooLarge(corners.len() + polygon.len()));
            }
            triangles += polygon.len().saturating_sub(2);
            if triangles > Self::MAX_TRIANGLES {
                return Err(MeshError::TooManyTriangles(triangles));
            }
            corners.extend_from_slice(polygon);
            offsets.push(corners.len() as u32);
        }
        Mesh::from_parts(positions, corners, offsets)
    }

    /// Builds a mesh from positions, every polygon's vertex indices one
    /// polygon after another, and where each polygon starts in them
    /// (`offsets`, one more than the polygons, from 0 to `corners.len()`),
    /// as [`Mesh::corners`] and [`Mesh::corner_range`] give them back: a
    /// mesh's own arrays reordered, with no polygon copied alone.
    ///
    /// # Errors
    /// As [`Mesh::from_polygons`].
    ///
    /// # Panics
    /// If `offsets` do not run from 0 to `corners.len()` in order: the
    /// caller's arrays are not a mesh's.
    pub(crate) fn from_parts(
        positions: Vec<Vec3>,
        corners: Vec<u32>,
        offsets: Vec<u32>,
    ) -> Result<Mesh, MeshError> {
        if positions.len() > Self::MAX_VERTICES {
            return Err(MeshError::TooManyVertices(positions.len()));
        }
        if corners.len() > Self::MAX_CORNERS {
            return Err(MeshError::TooLarge(corners.len()));
        }
        assert!(
            offsets.first() == Some(&0)
                && offsets.last().map(|&end| end as usize) == Some(corners.len())
                && offsets.windows(2).all(|w| w[0] <= w[1]),
            "offsets that do not run from 0 to the {} corners in order",
            corners.len()
        );
        let triangles: usize = offsets
            .windows(2)
            .map(|w| (w[1] - w[0]).saturating_sub(2) as usize)
            .sum();
        if triangles > Self::MAX_TRIANGLES {
            return Err(MeshError::TooManyTriangles(triangles));
        }
        let mesh = Mesh {
            positions,
            corners,
            offsets,
            file_normals: None,
            smoothing_groups: None,
            geometry_id: fresh_geometry_id(),
        };
        mesh.validate()?;
        Ok(mesh)
    }

    /// Attaches normals that came with the model (an OBJ file's `vn`).
    ///
    /// # Errors
    /// [`MeshError::Normals`] when there is not one index per corner, an index
    /// is out of range, or a normal is not finite and non-zero.
    pub fn with_file_normals(mut self, normals: CornerNormals) -> Result<Mesh, MeshError> {
        if normals.corner.len() != self.corners.len() {
            return Err(MeshError::Normals(format!(
                "{} normal indices for {} face corners",
                normals.corner.len(),
                self.corners.len()
            )));
        }
        if let Some(&i) = normals
            .corner
            .iter()
            .find(|&&i| i as usize >= normals.normals.len())
        {
            return Err(MeshError::Normals(format!(
                "normal index {i} out of range ({} normals)",
                normals.normals.len()
            )));
        }
        let mut normals = normals;
        for (k, n) in normals.normals.iter_mut().enumerate() {
            *n = n.try_normalize().ok_or_else(|| {
                MeshError::Normals(format!("normal {k} ({n}) is zero or not finite"))
            })?;
        }
        self.file_normals = Some(normals);
        Ok(self)
    }

    /// Attaches smoothing groups, one per polygon, as an OBJ file's `s`
    /// statements give them: vertex normals are only averaged between faces
    /// of the same group, and a face in [`Mesh::NOT_SMOOTHED`] is faceted
    /// (its corners take its face normal). Without smoothing groups every
    /// face may be smoothed with every other.
    ///
    /// # Errors
    /// [`MeshError::SmoothingGroups`] when there is not one group per polygon.
    pub fn with_smoothing_groups(mut self, groups: Vec<u32>) -> Result<Mesh, MeshError> {
        if groups.len() != self.polygon_count() {
            return Err(MeshError::SmoothingGroups {
                groups: groups.len(),
                faces: self.polygon_count(),
            });
        }
        self.smoothing_groups = Some(groups);
        Ok(self)
    }

    fn validate(&self) -> Result<(), MeshError> {
        if self.polygon_count() == 0 {
            return Err(MeshError::NoFaces);
        }
        if let Some((vertex, &position)) = self
            .positions
            .iter()
            .enumerate()
            .find(|(_, p)| !p.is_finite())
        {
            return Err(MeshError::NonFinite { vertex, position });
        }
        for face in 0..self.polygon_count() {
            let polygon = self.polygon(face);
            if polygon.len() < 3 {
                return Err(MeshError::TooFewCorners {
                    face,
                    corners: polygon.len(),
                });
            }
            if let Some(&index) = polygon
                .iter()
                .find(|&&i| i as usize >= self.positions.len())
            {
                return Err(MeshError::IndexOutOfRange {
                    face,
                    index,
                    count: self.positions.len(),
                });
            }
        }
        Ok(())
    }

    /// A number that names this mesh's positions and polygons: two meshes
    /// with the same id have the same ones (a clone keeps its original's id;
    /// anything that changes them gives a new one). Renderers key what they
    /// derive from the geometry, such as face normals, by it instead of
    /// comparing whole meshes every frame.
    pub(crate) fn geometry_id(&self) -> u64 {
        self.geometry_id
    }

    /// Vertex positions.
    pub fn positions(&self) -> &[Vec3] {
        &self.positions
    }

    /// Every polygon's vertex indices, one polygon after another.
    pub fn corners(&self) -> &[u32] {
        &self.corners
    }

    /// Number of polygons.
    pub fn polygon_count(&self) -> usize {
        self.offsets.len() - 1
    }

    /// Range of polygon `face`'s corners within [`Mesh::corners`].
    pub fn corner_range(&self, face: usize) -> std::ops::Range<usize> {
        self.offsets[face] as usize..self.offsets[face + 1] as usize
    }

    /// The vertex indices of polygon `face`.
    pub fn polygon(&self, face: usize) -> &[u32] {
        &self.corners[self.corner_range(face)]
    }

    /// Number of polygons that are triangles after fan triangulation.
    pub fn triangle_count(&self) -> usize {
        (0..self.polygon_count())
            .map(|f| self.polygon(f).len() - 2)
            .sum()
    }

    /// Normals that came with the model, if any.
    pub fn file_normals(&self) -> Option<&CornerNormals> {
        self.file_normals.as_ref()
    }

    /// Each polygon's smoothing group, if the model has them (see
    /// [`Mesh::with_smoothing_groups`]).
    pub fn smoothing_groups(&self) -> Option<&[u32]> {
        self.smoothing_groups.as_deref()
    }

    /// The axis-aligned bounding box, as (min, max).
    pub fn bounds(&self) -> (Vec3, Vec3) {
        let used = self.corners.iter().map(|&i| self.positions[i as usize]);
        used.fold(
            (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
            |(lo, hi), p| (lo.min(p), hi.max(p)),
        )
    }

    /// Moves and scales the mesh so its bounding box is centred on the origin
    /// and its farthest vertex is at distance 1 from it.
    pub fn normalized(mut self) -> Mesh {
        let (lo, hi) = self.bounds();
        let centre = (lo + hi) * 0.5;
        let radius = self
            .corners
            .iter()
            .map(|&i| (self.positions[i as usize] - centre).length())
            .fold(0.0f32, f32::max);
        let scale = if radius > 0.0 && radius.is_finite() {
            1.0 / radius
        } else {
            1.0
        };
        for p in &mut self.positions {
            *p = (*p - centre) * scale;
        }
        self.geometry_id = fresh_geometry_id();
        self
    }

    /// The power of two that brings the largest coordinate of the mesh's
    /// bounding box into [1, 2), when that coordinate is so large (over
    /// 2^24) or so small (under 2^−24) that products of coordinates (face
    /// normals, squared distances) would overflow or vanish in `f32`; `None`
    /// for any other mesh, and for one whose coordinates are all zero.
    ///
    /// Scaling by a power of two is exact, and every normal and the
    /// [`Mesh::normalized`] mesh are the same for the scaled mesh, bit for
    /// bit, as they would be without overflow: so a caller about to
    /// normalize may scale first ([`Mesh::scaled_by_power_of_two`]) and
    /// frame a model of any finite size.
    pub fn extreme_scale_exponent(&self) -> Option<i32> {
        let (lo, hi) = self.bounds();
        let extent = lo.abs().max(hi.abs()).max_element();
        if !(extent.is_finite() && extent > 0.0) {
            return None;
        }
        let limit = (1u32 << 24) as f32;
        if extent > limit || extent < 1.0 / limit {
            // extent = m · 2^e with m in [1, 2): the exponent's bits.
            let exponent = |v: f32| ((v.to_bits() >> 23) & 0xff) as i32 - 127;
            let mut scale = -exponent(extent).max(-126);
            if scale > 0 {
                // Vertices no polygon uses may be larger: keep them finite.
                let largest = self
                    .positions
                    .iter()
                    .map(|p| p.abs().max_element())
                    .fold(0.0f32, f32::max);
                scale = scale.min(100 - exponent(largest).max(-126));
            }
            Some(scale)
        } else {
            None
        }
    }

    /// The mesh with every position multiplied by 2^`exponent`, exactly
    /// (unless a coordinate leaves `f32`'s range, which
    /// [`Mesh::extreme_scale_exponent`] prevents).
    pub fn scaled_by_power_of_two(mut self, exponent: i32) -> Mesh {
        let mut left = exponent;
        while left != 0 {
            // 2^±100 at most per step: each factor is itself a normal f32.
            let step = left.clamp(-100, 100);
            let factor = f32::from_bits(((step + 127) as u32) << 23);
            for p in &mut self.positions {
                *p *= factor;
            }
            left -= step;
        }
        self.geometry_id = fresh_geometry_id();
        self
    }
}
