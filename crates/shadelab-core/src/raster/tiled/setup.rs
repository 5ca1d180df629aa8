//! Triangle setup: edge functions in fixed point and attribute planes.
//!
//! What must hold:
//!
//! * **Coverage equals the scanline rasterizer's, bit for bit.** The vertices
//!   are the same snapped window coordinates (1/256 pixel). A pixel is
//!   covered when its centre `s` has `E(s) ≥ 0` for all three edges, where
//!   `E(s) = a·s.x + b·s.y + c` is exact in `i64` (coordinates stay within
//!   ±2^29 snapped units, so products stay below 2^61). Centres exactly on an
//!   edge belong to the triangle only for left edges (going down the screen)
//!   and top edges (horizontal, going left): the top-left rule, folded into
//!   `c` as a bias of −1 for the other edges. This is the scanline's rule
//!   "rows in [top, bottom), spans in [left, right)" restated per edge.
//! * **Attributes are planes.** Over a triangle, depth, 1/w and attribute/w
//!   (or the attribute itself, in screen-space mode) are affine in window
//!   coordinates. Their gradients are solved once, in f64, and stored as f32
//!   relative to the triangle's first pixel, so per-pixel offsets stay small
//!   and f32 keeps its precision whatever the triangle's position.

use crate::raster::{Interpolation, ScreenVertex, SUBPIXEL_BITS, SUBPIXEL_HALF, SUBPIXEL_ONE};
use crate::simd::{PlaneSolve, Simd, SOLVE_LANES};

/// The attributes of a triangle set up for the three methods at once
/// (`TiledRasterizer::render_methods`): Phong's six (normal, position),
/// then Gouraud's three colours.
pub(crate) const ALL_ATTRS: usize = 9;

/// The most planes a triangle has: depth, 1/w and the attributes of the
/// three methods at once.
pub(crate) const PLANES: usize = 2 + ALL_ATTRS;

/// Where Gouraud's planes (depth, 1/w, three colours) are among those of a
/// triangle set up for the three methods at once.
pub(crate) const GOURAUD_OF_ALL: [usize; 5] = [0, 1, 8, 9, 10];

/// Image rows per band: the unit of binning and of parallel work.
pub(crate) const BAND_ROWS: u32 = 16;

/// An affine function of the pixel position: `at_origin + dx·(x − x0) + dy·(y − y0)`
/// for pixel (x, y) and the triangle's first pixel (x0, y0).
///
/// Laid out as the [`crate::simd::SolvedPlane`] that setup's arithmetic
/// writes (`Simd::solve_planes`).
#[derive(Debug, Clone, Copy, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
#[repr(C)]
pub(crate) struct Plane {
    pub at_origin: f32,
    pub dx: f32,
    pub dy: f32,
}

/// How a triangle's rows are walked (see `band/mod.rs`, `band/walk.rs`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Walk {
    /// Every edge function stays within ±2^31 over the triangle's block-aligned
    /// bounding box: blocks of 8 lanes of `i32`, one add per block and edge.
    Blocks,
    /// Larger triangles: each row's covered span is found exactly per edge
    /// (an `f64` quotient corrected by exact integer tests), then filled.
    Spans,
}

/// A triangle ready to rasterize. Its planes live in a separate array:
/// depth, then (Gouraud and Phong) 1/w and the shading method's attributes.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Triangle {
    /// Edge functions `a·x + b·y + c` over snapped pixel centres, inside ≥ 0.
    /// `a` and `b` are differences of snapped coordinates (within ±2^30).
    pub a: [i32; 3],
    pub b: [i32; 3],
    pub c: [i64; 3],
    /// Covered pixels lie in columns `x0..x1` and rows `y0..y1` (clipped to the image).
    pub x0: i32,
    pub y0: i32,
    pub x1: i32,
    pub y1: i32,
    pub walk: Walk,
    /// Flat shading (and the three methods at once): the index of its
    /// polygon's colour in its chunk's `flat_colors`, packed as
    /// `r | g << 8 | b << 16` (see `chunk.rs`).
    pub color: u32,
    /// −1 for a back face drawn with culling off (Phong turns its normals), else 1.
    pub flip: f32,
    /// For the triangles of a self-crossing polygon: the polygon's number + 1,
    /// so each pixel is drawn once per polygon; 0 otherwise.
    pub once: u32,
    /// How its attributes are interpolated, set by setup
    /// ([`Triangle::interpolated`]): the frame's mode, but screen mode for
    /// a triangle whose corners have the same w.
    pub interpolation: Interpolation,
}

/// Snapped extents (in x and in y) below this many units, 64 pixels, keep
/// every edge function within `i32` over the walked box, with no need to
/// check (`Triangle::fits_i32`): with `W`, `H` the extents, `|a| ≤ H` and
/// `|b| ≤ W`, and the walk's sample points lie within `W + 23` pixels in x
/// (the box rounded out to blocks, one block stepped past it) and `H + 2`
/// rows in y of every vertex, so `|E| ≤ 2·H·W + 256·(23·H + 2·W) + 1`,
/// below 2^30 for `W, H < 2^14`.
const SMALL_EXTENT: i64 = 1 << 14;

/// The pixel range `first..last + 1` whose centres lie within `min..=max`
/// (snapped units), clipped to `0..size`.
#[inline(always)]
fn centres(min: i64, max: i64, size: u32) -> (i64, i64) {
    // Floor divisions by a power of two: arithmetic shifts.
    let first = (min - SUBPIXEL_HALF + SUBPIXEL_ONE - 1) >> SUBPIXEL_BITS;
    let last = (max - SUBPIXEL_HALF) >> SUBPIXEL_BITS;
    (first.max(0), (last + 1).min(i64::from(size)))
}

impl Triangle {
    /// The edges and pixel bounds of a counter-clockwise triangle of
    /// positive area with snapped vertices `x`, `y`, or `None` when no pixel
    /// centre of the image lies within its bounding box.
    #[inline(always)]
    pub fn edges(x: [i64; 3], y: [i64; 3], width: u32, height: u32) -> Option<Triangle> {
        Triangle::edges_in_rows(x, y, width, height, 0..height as i32)
    }

    /// [`Triangle::edges`], or `None` as soon as the box is found to have
    /// no row among `rows` (a part of the image drawn by a thread of its
    /// own): the edges of a triangle outside a part are not needed.
    #[inline(always)]
    pub fn edges_in_rows(
        x: [i64; 3],
        y: [i64; 3],
        width: u32,
        height: u32,
        rows: std::ops::Range<i32>,
    ) -> Option<Triangle> {
        let (y_min, y_max) = (y[0].min(y[1]).min(y[2]), y[0].max(y[1]).max(y[2]));
        let (y0, y1) = centres(y_min, y_max, height);
        if y0 >= y1 || y1 <= i64::from(rows.start) || y0 >= i64::from(rows.end) {
            return None;
        }
        let (x_min, x_max) = (x[0].min(x[1]).min(x[2]), x[0].max(x[1]).max(x[2]));
        let (x0, x1) = centres(x_min, x_max, width);
        if x0 >= x1 {
            return None;
        }
        let (mut a, mut b, mut c) = ([0i32; 3], [0i32; 3], [0i64; 3]);
        for i in 0..3 {
            let j = (i + 1) % 3;
            let (ai, bi) = (y[j] - y[i], x[i] - x[j]);
            // Without branches: an edge's direction is a coin toss.
            let top_left = (ai > 0) | ((ai == 0) & (bi > 0));
            c[i] = -(ai * x[i] + bi * y[i]) - i64::from(!top_left);
            a[i] = ai as i32;
            b[i] = bi as i32;
        }
        let small = x_max - x_min < SMALL_EXTENT && y_max - y_min < SMALL_EXTENT;
        let fits = small || Triangle::fits_i32(&a, &b, &c, (x0, y0, x1, y1));
        Some(Triangle {
            a,
            b,
            c,
            x0: x0 as i32,
            y0: y0 as i32,
            x1: x1 as i32,
            y1: y1 as i32,
            walk: if fits { Walk::Blocks } else { Walk::Spans },
            color: 0,
            flip: 1.0,
            once: 0,
            interpolation: Interpolation::Perspective,
        })
    }

    /// This triangle, to be interpolated in the frame's mode
    /// `interpolation`, its corners' 1/w being `inv_w`.
    ///
    /// A triangle whose three corners have the same 1/w is drawn in screen
    /// mode whatever the frame's: attribute/w linear, times w, is the
    /// attribute linear, exactly in real arithmetic, and its planes are the
    /// attributes' own. Each pixel then takes its colours (or normal and
    /// position) from their planes alone, without w and its rounding: a
    /// Gouraud pair of the full-screen quad does without its three
    /// multiplies by w (docs/conventions.md, "The shading methods";
    /// BENCHMARKS.md, "Triangles of equal w drawn in screen mode").
    #[inline(always)]
    pub fn interpolated(self, interpolation: Interpolation, inv_w: [f32; 3]) -> Triangle {
        let same_w = inv_w[0] == inv_w[1] && inv_w[1] == inv_w[2];
        let interpolation = if same_w {
            Interpolation::Screen
        } else {
            interpolation
        };
        Triangle {
            interpolation,
            ..self
        }
    }

    /// Whether the edge functions `a·x + b·y + c` stay within `i32` over
    /// the pixel box `(x0, y0, x1, y1)` rounded out to whole blocks, one
    /// more block and one more row included (the walk steps that far).
    fn fits_i32(
        a: &[i32; 3],
        b: &[i32; 3],
        c: &[i64; 3],
        (x0, y0, x1, y1): (i64, i64, i64, i64),
    ) -> bool {
        // The edge functions' extremes over the block-aligned box are at its corners.
        let bx0 = (x0 & !7) * SUBPIXEL_ONE + SUBPIXEL_HALF;
        let bx1 = (((x1 + 7) & !7) - 1) * SUBPIXEL_ONE + SUBPIXEL_HALF;
        let (by0, by1) = (
            y0 * SUBPIXEL_ONE + SUBPIXEL_HALF,
            (y1 - 1) * SUBPIXEL_ONE + SUBPIXEL_HALF,
        );
        (0..3).all(|i| {
            let (a, b) = (i64::from(a[i]), i64::from(b[i]));
            let e = a * bx0 + b * by0 + c[i];
            // One more block and one more row are stepped past the box.
            let reach = a.abs() * (bx1 - bx0 + 16 * SUBPIXEL_ONE)
                + b.abs() * (by1 - by0 + 2 * SUBPIXEL_ONE);
            e.abs() + reach < i64::from(i32::MAX)
        })
    }

    /// Whether a triangle whose bounding box holds at most four pixel
    /// centres covers none of them (tested exactly, as the walk would);
    /// `false` for larger boxes. Many triangles of a dense mesh seen small
    /// cover no centre: this spares them planes, binning and walking.
    #[inline(always)]
    pub fn covers_no_centre(&self) -> bool {
        let (w, h) = (self.x1 - self.x0, self.y1 - self.y0);
        if w > 2 || h > 2 {
            return false;
        }
        // The (up to) four centres tested at once, without branches: which
        // of them is covered is a coin toss from one triangle to the next.
        let xs = i64::from(self.x0) * SUBPIXEL_ONE + SUBPIXEL_HALF;
        let ys = i64::from(self.y0) * SUBPIXEL_ONE + SUBPIXEL_HALF;
        let mut inside = [true; 4];
        for i in 0..3 {
            let (a, b) = (i64::from(self.a[i]), i64::from(self.b[i]));
            let e = a * xs + b * ys + self.c[i];
            let (right, down) = (a * SUBPIXEL_ONE, b * SUBPIXEL_ONE);
            inside[0] &= e >= 0;
            inside[1] &= e + right >= 0;
            inside[2] &= e + down >= 0;
            inside[3] &= e + right + down >= 0;
        }
        let (wide, tall) = (w == 2, h == 2);
        !(inside[0] | (inside[1] & wide) | (inside[2] & tall) | (inside[3] & wide & tall))
    }

    /// The planes of depth and, when `attrs > 0`, of 1/w and the first
    /// `attrs` attributes (divided by w in the triangle's perspective mode,
    /// [`Triangle::interpolation`]): the first [`plane_count`]`(attrs)`
    /// entries. The arithmetic per plane is the SIMD backend's
    /// ([`Simd::solve_planes`], the same bits on every one).
    #[inline(always)]
    pub fn planes<S: Simd, const N: usize>(
        &self,
        s: S,
        v: &[ScreenVertex<N>; 3],
        attrs: usize,
    ) -> [Plane; PLANES] {
        // The values at the three corners, one array per corner so that
        // the per-plane arithmetic is the same operations on each lane.
        let mut q = [[0f64; SOLVE_LANES]; 3];
        for i in 0..3 {
            let inv_w = f64::from(v[i].inv_w);
            let scale = match self.interpolation {
                Interpolation::Perspective => inv_w,
                Interpolation::Screen => 1.0,
            };
            q[i][0] = f64::from(v[i].depth);
            q[i][1] = inv_w;
            for k in 0..N.min(PLANES - 2) {
                q[i][2 + k] = f64::from(v[i].attrs[k]) * scale;
            }
        }
        let unit = 1.0 / SUBPIXEL_ONE as f64;
        let (px0, py0) = (v[0].x as f64 * unit, v[0].y as f64 * unit);
        let (e1x, e1y) = (
            (v[1].x - v[0].x) as f64 * unit,
            (v[1].y - v[0].y) as f64 * unit,
        );
        let (e2x, e2y) = (
            (v[2].x - v[0].x) as f64 * unit,
            (v[2].y - v[0].y) as f64 * unit,
        );
        let inv_det = 1.0 / (e1x * e2y - e2x * e1y);
        let solve = PlaneSolve {
            q,
            gx: [e2y * inv_det, -e1y * inv_det],
            gy: [-e2x * inv_det, e1x * inv_det],
            // Pixel centre of the first pixel, relative to vertex 0.
            origin: [
                f64::from(self.x0) + 0.5 - px0,
                f64::from(self.y0) + 0.5 - py0,
            ],
        };
        let mut planes = [Plane::default(); PLANES];
        let count = plane_count(attrs).min(PLANES);
        s.solve_planes(&solve, bytemuck::cast_slice_mut(&mut planes[..count]));
        planes
    }

    /// The bands this triangle's rows fall in.
    pub fn bands(&self) -> std::ops::Range<usize> {
        self.y0 as usize / BAND_ROWS as usize..(self.y1 as usize - 1) / BAND_ROWS as usize + 1
    }
}

/// Planes per triangle for a method interpolating `attrs` attributes.
pub(crate) const fn plane_count(attrs: usize) -> usize {
    if attrs == 0 {
        1
    } else {
        2 + attrs
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: i64, y: i64) -> ScreenVertex<1> {
        ScreenVertex {
            x,
            y,
            depth: 0.5,
            inv_w: 1.0,
            attrs: [(x + 2 * y) as f32],
        }
    }

    #[test]
    fn planes_reproduce_vertex_values() {
        let tri = [v(300, 200), v(900, 2000), v(2500, 700)];
        let t = Triangle::edges(tri.map(|v| v.x), tri.map(|v| v.y), 64, 64).unwrap();
        let t = t.interpolated(Interpolation::Screen, tri.map(|v| v.inv_w));
        let planes = t.planes(crate::simd::Portable, &tri, 1);
        assert_eq!(plane_count(1), 3);
        // attr = x + 2y in snapped units = 256·(X + 2Y) in pixels.
        let p = planes[2];
        assert!((p.dx - 256.0).abs() < 1e-3 && (p.dy - 512.0).abs() < 1e-3);
        let centre = |x: i32, y: i32| (x as f32 + 0.5) * 256.0 + 2.0 * (y as f32 + 0.5) * 256.0;
        assert!((p.at_origin - centre(t.x0, t.y0)).abs() < 1e-2);
    }

    /// A reproducible generator of numbers in `0..range` (xorshift64).
    fn xorshift(mut seed: u64) -> impl FnMut(i64) -> i64 {
        move |range| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed % range as u64) as i64
        }
    }

    #[test]
    fn covers_no_centre_agrees_with_the_edge_functions() {
        // Small random triangles near pixel centres, including vertices and
        // edges exactly on centres (multiples of 128 snapped units).
        let mut next = xorshift(0x2545_f491_4f6c_dd1d);
        let (mut empty, mut skipped) = (0, 0);
        for _ in 0..20_000 {
            let coarse = next(2) == 0;
            let mut coord = || {
                if coarse {
                    256 + 64 * next(12)
                } else {
                    256 + next(700)
                }
            };
            let (x, y) = ([coord(), coord(), coord()], [coord(), coord(), coord()]);
            if (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]) >= 0 {
                continue; // not counter-clockwise in window coordinates (y down)
            }
            let Some(t) = Triangle::edges(x, y, 16, 16) else {
                continue;
            };
            let covered = (t.y0..t.y1).any(|py| {
                (t.x0..t.x1).any(|px| {
                    let (sx, sy) = (i64::from(px) * 256 + 128, i64::from(py) * 256 + 128);
                    (0..3).all(|i| i64::from(t.a[i]) * sx + i64::from(t.b[i]) * sy + t.c[i] >= 0)
                })
            });
            if t.covers_no_centre() {
                assert!(!covered, "{x:?} {y:?}");
                skipped += 1;
            }
            empty += usize::from(!covered);
        }
        // Most empty boxes are small enough to be recognised.
        assert!(
            skipped > 0 && skipped * 10 >= empty * 7,
            "{skipped} of {empty}"
        );
    }

    #[test]
    fn small_triangles_fit_i32() {
        // Triangles just under the small extent, anywhere in a large image,
        // in every orientation: the exact check agrees with the shortcut.
        let mut next = xorshift(0x9e37_79b9_7f4a_7c15);
        for _ in 0..20_000 {
            let (ox, oy) = (next(1 << 21), next(1 << 21));
            let mut x = [0; 3].map(|_| ox + next(SMALL_EXTENT));
            let mut y = [0; 3].map(|_| oy + next(SMALL_EXTENT));
            if (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]) > 0 {
                x.swap(1, 2);
                y.swap(1, 2);
            }
            let Some(t) = Triangle::edges(x, y, 1 << 14, 1 << 14) else {
                continue;
            };
            let bounds = (t.x0.into(), t.y0.into(), t.x1.into(), t.y1.into());
            assert!(Triangle::fits_i32(&t.a, &t.b, &t.c, bounds), "{x:?} {y:?}");
        }
    }

    #[test]
    fn bounding_box_takes_pixel_centres() {
        let tri = [v(128, 128), v(128, 1152), v(1152, 128)];
        let t = Triangle::edges(tri.map(|v| v.x), tri.map(|v| v.y), 64, 64).unwrap();
        assert_eq!((t.x0, t.y0, t.x1, t.y1), (0, 0, 5, 5));
        assert_eq!(t.walk, Walk::Blocks);
        let off = [v(-900, 10), v(-900, 900), v(-200, 10)];
        assert!(Triangle::edges(off.map(|v| v.x), off.map(|v| v.y), 64, 64).is_none());
        let huge = [v(0, 0), v(0, 1 << 20), v(1 << 20, 0)];
        let t = Triangle::edges(huge.map(|v| v.x), huge.map(|v| v.y), 4096, 4096).unwrap();
        assert_eq!(t.walk, Walk::Spans);
    }
}
