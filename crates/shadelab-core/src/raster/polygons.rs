//! What a rasterizer receives from the frame: the frame's polygons,
//! assembled (faced, culled, clipped, in window space) by the frame's
//! polygon assembly (`frame/assemble.rs`) and handed to the rasterizer's
//! [`PolygonSink`], any run of consecutive polygons at a time
//! ([`PolygonSource::walk`]), so that a rasterizer may walk them in parallel
//! chunks.
//!
//! The rasterizers name only these types: the window transform, clipping
//! and facing are the frame's, and the raster layer never sees how.

use std::ops::Range;

use glam::Vec3;

use super::ScreenVertex;
use crate::clip::ClipVertex;
use crate::scene::RenderStats;

/// The frame's polygons before its vertex stage. The rasterizer runs the
/// stage once per frame, when it suits it (the tiled one beside its own
/// per-vertex work, which does not depend on it), and walks the polygons
/// it returns. Implemented by the frame (`frame/assemble.rs`).
pub(crate) trait VertexStage: Send {
    /// The polygons, once every vertex is in window space.
    type Polygons<'a>: PolygonSource + Send
    where
        Self: 'a;

    /// The vertex stage: every position transformed and snapped.
    fn project(&mut self) -> Self::Polygons<'_>;
}

/// The frame's polygons, as a rasterizer walks them. Implemented by the
/// frame's polygon assembly (`frame/assemble.rs`).
pub(crate) trait PolygonSource: Sync {
    /// How many polygons the mesh has.
    fn count(&self) -> usize;

    /// One unit normal per polygon, `None` where its area is zero (flat
    /// shading's normal).
    fn faces(&self) -> &[Option<Vec3>];

    /// Each polygon's centroid, the mean of its corners' positions (the
    /// point flat shading lights).
    fn centroids(&self) -> &[Vec3];

    /// Each mesh position's window position (the vertex stage's output).
    fn projected(&self) -> &[Projected];

    /// Hands the visible ones of polygons `faces`, in order, to `sink`,
    /// counting in `stats` the degenerate, invisible, culled and rasterized
    /// ones. Inlined into the rasterizer's loop (implementations are
    /// `#[inline(always)]`).
    fn walk<const N: usize, S: PolygonSink<N>>(
        &self,
        faces: Range<usize>,
        scratch: &mut Scratch<N>,
        sink: &mut S,
        stats: &mut RenderStats,
    );
}

/// A vertex's window position, when it is inside the view volume and guard
/// band (`x == OUTSIDE` otherwise). Snapped coordinates stay within ±2^29,
/// so they fit in `i32`; 16 bytes, so that the walk's random accesses stay
/// in cache.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Projected {
    pub(crate) x: i32,
    pub(crate) y: i32,
    pub(crate) depth: f32,
    pub(crate) inv_w: f32,
}

impl Projected {
    pub(crate) const OUTSIDE: i32 = i32::MIN;

    pub(crate) fn inside(&self) -> bool {
        self.x != Projected::OUTSIDE
    }

    /// The window vertex, with attributes `attrs`.
    #[inline(always)]
    pub(crate) fn vertex<const N: usize>(&self, attrs: [f32; N]) -> ScreenVertex<N> {
        ScreenVertex {
            x: i64::from(self.x),
            y: i64::from(self.y),
            depth: self.depth,
            inv_w: self.inv_w,
            attrs,
        }
    }
}

/// What receives the assembled polygons: a rasterizer's setup (tiled) or
/// its fill (scanline). `N` attributes per corner.
pub(crate) trait PolygonSink<const N: usize> {
    /// The attributes at corner `corner` (of vertex `vertex`), of the
    /// polygon's front side or, with `back`, its back (normals reversed).
    fn corner(&mut self, corner: usize, vertex: u32, back: bool) -> [f32; N];

    /// A visible polygon `face` (unit normal `normal`): clipped, in window
    /// space, counter-clockwise, with its attributes, `back` when it is
    /// seen from behind (its attributes are then the back's).
    fn polygon(&mut self, face: usize, normal: Vec3, back: bool, window: &[ScreenVertex<N>]);

    /// A front-facing triangle needing no clipping: polygon `face`, its
    /// corners `first_corner..first_corner + 3` (of vertices `vertices`) at
    /// the snapped positions `p`. The default reads the attributes and
    /// hands it to [`PolygonSink::polygon`]; a sink may first decide
    /// whether it draws anything at all.
    #[inline(always)]
    fn triangle(
        &mut self,
        face: usize,
        normal: Vec3,
        first_corner: usize,
        vertices: [u32; 3],
        p: &[Projected; 3],
    ) {
        let window: [ScreenVertex<N>; 3] =
            std::array::from_fn(|k| p[k].vertex(self.corner(first_corner + k, vertices[k], false)));
        self.polygon(face, normal, false, &window);
    }

    /// Starts loading what [`PolygonSink::corner`] reads of corner
    /// `corner` (of vertex `vertex`), a few polygons ahead.
    #[inline(always)]
    fn prefetch_corner(&self, corner: usize, vertex: u32) {
        let _ = (corner, vertex);
    }
}

/// Working storage of [`PolygonSource::walk`] (clipping's polygons), kept by
/// the rasterizer for each of its walks and reused from polygon to
/// polygon and frame to frame.
#[derive(Debug)]
pub(crate) struct Scratch<const N: usize> {
    pub(crate) input: Vec<ClipVertex<N>>,
    pub(crate) clipped: Vec<ClipVertex<N>>,
    pub(crate) spare: Vec<ClipVertex<N>>,
    pub(crate) window: Vec<ScreenVertex<N>>,
}

impl<const N: usize> Default for Scratch<N> {
    fn default() -> Self {
        Scratch {
            input: Vec::new(),
            clipped: Vec::new(),
            spare: Vec::new(),
            window: Vec::new(),
        }
    }
}
