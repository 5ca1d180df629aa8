//! The window transform, the frame's vertex stage: the camera's
//! view-projection, the perspective divide and viewport, snapping to the
//! rasterizers' fixed-point grid ([`crate::raster::snap`]), and the guard
//! band that keeps snapped coordinates small enough for exact integer
//! edge arithmetic.
//!
//! Each position is transformed and snapped once per frame
//! ([`project_vertices`]); the few polygons that need clipping compute
//! their corners' clip-space positions again, with the same expression
//! ([`View::clip`]), and place the clipped vertices with [`to_window`].

use glam::{Mat4, Vec3, Vec4};

use crate::clip::{is_inside, ClipVertex};
use crate::raster::{snap, Projected, ScreenVertex};

/// Where a frame's positions land: the camera's transform and the window.
#[derive(Debug, Clone, Copy)]
pub(crate) struct View {
    pub(crate) view_projection: Mat4,
    pub(crate) width: u32,
    pub(crate) height: u32,
    /// The guard band, in NDC units ([`guard_band`]).
    pub(crate) guard: f32,
}

impl View {
    /// A position in clip space: one expression for the vertex stage and
    /// for the polygons that clipping recomputes, so both see the same
    /// values.
    #[inline(always)]
    pub(crate) fn clip(&self, p: Vec3) -> Vec4 {
        self.view_projection * p.extend(1.0)
    }
}

/// The vertex stage: each position transformed and snapped once, into
/// `out` (as long as `points`).
pub(crate) fn project_vertices(view: &View, points: &[Vec3], out: &mut [Projected]) {
    for (o, p) in out.iter_mut().zip(points) {
        let clip = view.clip(*p);
        *o = if clip.is_finite() && is_inside(clip, view.guard) {
            let w = to_window(&ClipVertex { clip, attrs: [] }, view.width, view.height);
            Projected {
                x: w.x as i32,
                y: w.y as i32,
                depth: w.depth,
                inv_w: w.inv_w,
            }
        } else {
            Projected {
                x: Projected::OUTSIDE,
                ..Projected::default()
            }
        };
    }
}

/// The guard band, in NDC units, that keeps window coordinates within ±2^20
/// pixels, so snapped edge arithmetic fits in `i64` with room to spare.
pub(crate) fn guard_band(width: u32, height: u32) -> f32 {
    ((1u32 << 20) as f32 / width.max(height) as f32 - 1.0).max(1.0)
}

/// The perspective divide and viewport transform, then snapping: where a
/// clip-space vertex lands in the window, as both rasterizers place it.
pub fn to_window<const N: usize>(v: &ClipVertex<N>, width: u32, height: u32) -> ScreenVertex<N> {
    let inv_w = 1.0 / f64::from(v.clip.w);
    let x = (f64::from(v.clip.x) * inv_w + 1.0) * 0.5 * f64::from(width);
    let y = (1.0 - f64::from(v.clip.y) * inv_w) * 0.5 * f64::from(height);
    let depth = (f64::from(v.clip.z) * inv_w + 1.0) * 0.5;
    // Clipping keeps vertices within the guard band (±2^19 pixels) unless an
    // edge's ends are both so far away (beyond about 1e20) that f32 cannot
    // place the cut; the clamp keeps the edge arithmetic from overflowing then.
    let limit = f64::from(1u32 << 21);
    ScreenVertex {
        x: snap(x.clamp(-limit, limit)),
        y: snap(y.clamp(-limit, limit)),
        depth: depth as f32,
        inv_w: inv_w as f32,
        attrs: v.attrs,
    }
}
