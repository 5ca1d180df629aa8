//! Triangle setup's plane arithmetic in `f64`, the one part of setup that
//! is the same operations for every plane: [`PlaneSolve`], solved by
//! [`super::Simd::solve_planes`], four planes per vector where the backend
//! has vectors of `f64` (AVX2), else by [`solve_planes`].
//!
//! Every backend performs, per plane, the same `f64` operations in the
//! same order (no fused multiply-add), and rounds to `f32` the same way:
//! the planes are bit for bit those of [`solve_planes`]. Written as one
//! scalar loop building each plane, the compiler left most of it scalar,
//! between shuffles and spills: about a tenth of the bunny's Phong frame.

/// The most planes one solve holds: a triangle's (`raster/tiled/setup.rs`,
/// at most 11), rounded up to whole vectors of four.
pub(crate) const SOLVE_LANES: usize = 12;

/// The inputs of a triangle's planes: each plane's values at the three
/// corners, the gradients of the corners' weights and the first pixel's
/// offset from corner 0.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PlaneSolve {
    /// `q[i][k]`: plane `k`'s value at corner `i` (0 past the planes used).
    pub q: [[f64; SOLVE_LANES]; 3],
    /// The x gradients of corners 1 and 2's weights.
    pub gx: [f64; 2],
    /// Their y gradients.
    pub gy: [f64; 2],
    /// The first pixel's centre relative to corner 0.
    pub origin: [f64; 2],
}

/// A plane's value at the first pixel and its steps in x and y, as `f32`
/// (the layout of the rasterizer's `Plane`).
pub(crate) type SolvedPlane = [f32; 3];

/// The first `out.len()` planes of `p`, one at a time, into `out`: the
/// specification every backend's [`super::Simd::solve_planes`] matches bit
/// for bit. For each plane, with `d1 = q1 − q0` and `d2 = q2 − q0`:
/// `dx = d1·gx1 + d2·gx2`, `dy = d1·gy1 + d2·gy2` and
/// `at = (q0 + dx·ox) + dy·oy`, each rounded to `f32` at the end.
#[inline(always)]
pub(crate) fn solve_planes(p: &PlaneSolve, out: &mut [SolvedPlane]) {
    let ([gx1, gx2], [gy1, gy2], [ox, oy]) = (p.gx, p.gy, p.origin);
    for (k, out) in out.iter_mut().enumerate().take(SOLVE_LANES) {
        let (d1, d2) = (p.q[1][k] - p.q[0][k], p.q[2][k] - p.q[0][k]);
        let dx = d1 * gx1 + d2 * gx2;
        let dy = d1 * gy1 + d2 * gy2;
        *out = [(p.q[0][k] + dx * ox + dy * oy) as f32, dx as f32, dy as f32];
    }
}
