//! The window transform, the frame's vertex stage: the camera's
//! view-projection, the perspective divide and viewport, snapping to the
//! rasterizers' fixed-point grid ([`crate::raster::snap`]), and the guard
//! band that keeps snapped coordinates small enough for exact integer
//! edge arithmetic.
//!
//! Each position is transformed and snapped once per frame
//! ([`project_vertices`], eight at a time in `f64` lanes:
//! [`project_vertices_lanes`]); the few polygons that need clipping compute
//! their corners' clip-space positions again, with the same expression
//! ([`View::clip`]), and place the clipped vertices with [`to_window`].

use glam::{Mat4, Vec3, Vec4};

use crate::clip::{is_inside, ClipVertex};
use crate::raster::{snap, Projected, ScreenVertex};
use crate::simd::{Kernel, Simd};

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

/// Vertices per block of [`project_vertices_lanes`].
const LANES: usize = 8;

/// [`project_vertices`] with the same operations in the same order (so the
/// same bits), eight vertices at a time in a form the compiler puts in
/// vector lanes: each vertex's clip-space position as before, then the
/// inside test, the divide, the viewport and the snapping for all eight,
/// with selects instead of branches. Run inside [`crate::simd::dispatch`]
/// ([`ProjectKernel`], as the vertex stage in `assemble.rs` runs it), it
/// compiles to AVX2 `f64` lanes (the AVX-512 build measured the same); one
/// vertex at a time, it was a tenth of the bunny's 512×512 Gouraud frame
/// (BENCHMARKS.md, "The vertex stage in lanes").
///
/// The snapped coordinates are computed in `i32`, not `i64` as [`snap`]
/// does: [`to_window`] clamps the window coordinate to ±2^21 pixels, so
/// the snapped value lies within ±2^29 and both give the same number
/// (checked by `lanes_project_as_one_at_a_time`).
#[inline(always)]
pub(crate) fn project_vertices_lanes(view: &View, points: &[Vec3], out: &mut [Projected]) {
    let (width, height) = (f64::from(view.width), f64::from(view.height));
    let limit = f64::from(1u32 << 21);
    let guard = view.guard;
    let mut outs = out.chunks_exact_mut(LANES);
    let mut ins = points.chunks_exact(LANES);
    for (o, p) in (&mut outs).zip(&mut ins) {
        let mut c = [[0f32; LANES]; 4];
        for i in 0..LANES {
            let v = view.clip(p[i]);
            for k in 0..4 {
                c[k][i] = v[k];
            }
        }
        let [cx, cy, cz, cw] = c;
        for i in 0..LANES {
            let (x, y, z, w) = (cx[i], cy[i], cz[i], cw[i]);
            // `is_finite` and `is_inside` of the vertex, without branches.
            let finite = x.is_finite() & y.is_finite() & z.is_finite() & w.is_finite();
            let g = guard * w;
            let inside = (z + w >= 0.0)
                & (w - z >= 0.0)
                & (g - x >= 0.0)
                & (g + x >= 0.0)
                & (g - y >= 0.0)
                & (g + y >= 0.0);
            // `to_window`'s arithmetic.
            let inv_w = 1.0 / f64::from(w);
            let wx = (f64::from(x) * inv_w + 1.0) * 0.5 * width;
            let wy = (1.0 - f64::from(y) * inv_w) * 0.5 * height;
            let depth = (f64::from(z) * inv_w + 1.0) * 0.5;
            let sx = snap_i32(wx.clamp(-limit, limit));
            let sy = snap_i32(wy.clamp(-limit, limit));
            let keep = finite & inside;
            o[i] = Projected {
                x: if keep { sx } else { Projected::OUTSIDE },
                y: if keep { sy } else { 0 },
                depth: if keep { depth as f32 } else { 0.0 },
                inv_w: if keep { inv_w as f32 } else { 0.0 },
            };
        }
    }
    project_vertices(view, ins.remainder(), outs.into_remainder());
}

/// [`project_vertices_lanes`] compiled for a SIMD level (through
/// [`crate::simd::dispatch`]).
pub(crate) struct ProjectKernel<'a> {
    pub(crate) view: &'a View,
    pub(crate) points: &'a [Vec3],
    pub(crate) out: &'a mut [Projected],
}

impl Kernel for ProjectKernel<'_> {
    type Output = ();
    #[inline(always)]
    fn run<S: Simd>(self, _: S) {
        project_vertices_lanes(self.view, self.points, self.out);
    }
}

/// [`snap`] for a coordinate within ±2^21 pixels, in `i32`.
#[inline(always)]
fn snap_i32(pixels: f64) -> i32 {
    let x = pixels * crate::raster::SUBPIXEL_ONE as f64;
    let t = x as i32;
    let rest = x - f64::from(t);
    // Wrapping: lanes outside the view volume (whose values are dropped)
    // may hold saturated ones.
    t.wrapping_add(i32::from(rest >= 0.5))
        .wrapping_sub(i32::from(rest <= -0.5))
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

#[cfg(test)]
mod tests {
    use glam::{Mat4, Vec3};

    use super::*;
    use crate::simd::{dispatch, SimdLevel};

    /// Points of every kind: near and far, behind the eye, on and past the
    /// guard band, huge, infinite and NaN, and in counts that leave each
    /// remainder of a block of eight.
    fn points() -> Vec<Vec3> {
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 40) as f32 / (1u64 << 24) as f32
        };
        let mut out = Vec::new();
        for scale in [0.01, 1.0, 3.0, 50.0, 1e4, 1e20, 1e38] {
            for _ in 0..600 {
                out.push(Vec3::new(next() - 0.5, next() - 0.5, next() - 0.5) * 2.0 * scale);
            }
        }
        for special in [
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
            0.0,
            -0.0,
            f32::MAX,
        ] {
            out.push(Vec3::new(special, 0.1, 0.2));
            out.push(Vec3::new(0.3, special, -0.1));
            out.push(Vec3::new(-0.2, 0.4, special));
        }
        out
    }

    /// The lanes give the bits of the vertex-by-vertex stage, on every SIMD
    /// level, for several cameras and window sizes.
    #[test]
    fn lanes_project_as_one_at_a_time() {
        let points = points();
        let eye = Vec3::new(0.3, 0.4, 3.0);
        let cameras = [
            Mat4::perspective_rh_gl(1.0, 1.3, 0.1, 100.0)
                * Mat4::look_at_rh(eye, Vec3::ZERO, Vec3::Y),
            Mat4::perspective_rh_gl(0.3, 1.0, 0.5, 10.0)
                * Mat4::look_at_rh(Vec3::new(0.0, 0.0, 0.6), Vec3::ZERO, Vec3::Y),
            Mat4::orthographic_rh_gl(-2.0, 2.0, -1.5, 1.5, -5.0, 5.0),
        ];
        for (width, height) in [(512, 512), (1921, 1080), (3, 7), (16384, 16384)] {
            for view_projection in cameras {
                let view = View {
                    view_projection,
                    width,
                    height,
                    guard: guard_band(width, height),
                };
                for len in [points.len(), points.len() - 3, 5, 0] {
                    let points = &points[..len];
                    let mut want = vec![Projected::default(); len];
                    project_vertices(&view, points, &mut want);
                    let kept = want.iter().filter(|p| p.inside()).count();
                    assert!(
                        len < 100 || (kept > len / 10 && kept < len),
                        "{kept} of {len}"
                    );
                    for level in SimdLevel::supported() {
                        let mut got = vec![Projected::default(); len];
                        dispatch(
                            level,
                            ProjectKernel {
                                view: &view,
                                points,
                                out: &mut got,
                            },
                        );
                        for (i, (g, w)) in got.iter().zip(&want).enumerate() {
                            let bits =
                                |p: &Projected| (p.x, p.y, p.depth.to_bits(), p.inv_w.to_bits());
                            assert_eq!(
                                bits(g),
                                bits(w),
                                "{level:?}, {width}×{height}, point {i}: {:?}",
                                points[i]
                            );
                        }
                    }
                }
            }
        }
    }
}
