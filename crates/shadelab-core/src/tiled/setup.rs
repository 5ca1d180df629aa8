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

use crate::raster::{Interpolation, ScreenVertex, SUBPIXEL_HALF, SUBPIXEL_ONE};

/// Image rows per band: the unit of binning and of parallel work.
pub(crate) const BAND_ROWS: u32 = 16;

/// An affine function of the pixel position: `at_origin + dx·(x − x0) + dy·(y − y0)`
/// for pixel (x, y) and the triangle's first pixel (x0, y0).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct Plane {
    pub at_origin: f32,
    pub dx: f32,
    pub dy: f32,
}

/// A triangle ready to rasterize. Its planes live in a separate array:
/// depth, 1/w, then the shading method's attributes.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Triangle {
    /// Edge functions `a·x + b·y + c` over snapped pixel centres, inside ≥ 0.
    pub a: [i64; 3],
    pub b: [i64; 3],
    pub c: [i64; 3],
    /// Covered pixels lie in columns `x0..x1` and rows `y0..y1` (clipped to the image).
    pub x0: i32,
    pub y0: i32,
    pub x1: i32,
    pub y1: i32,
    /// Flat shading's colour, packed as `r | g << 8 | b << 16`.
    pub color: u32,
    /// −1 for a back face drawn with culling off (Phong turns its normals), else 1.
    pub flip: f32,
    /// For the triangles of a self-crossing polygon: the polygon's number + 1,
    /// so each pixel is drawn once per polygon; 0 otherwise.
    pub once: u32,
}

impl Triangle {
    /// Sets up a counter-clockwise triangle of positive area, or `None`
    /// when no pixel centre of the image can be inside it. Its depth, 1/w
    /// and attribute planes are appended to `planes`.
    pub fn new<const N: usize>(
        v: &[ScreenVertex<N>; 3],
        attrs: usize,
        width: u32,
        height: u32,
        interpolation: Interpolation,
        planes: &mut Vec<Plane>,
    ) -> Option<Triangle> {
        let min_x = v[0].x.min(v[1].x).min(v[2].x);
        let max_x = v[0].x.max(v[1].x).max(v[2].x);
        let min_y = v[0].y.min(v[1].y).min(v[2].y);
        let max_y = v[0].y.max(v[1].y).max(v[2].y);
        // Pixels whose centres lie within the bounding box.
        let first = |min: i64| (min - SUBPIXEL_HALF + SUBPIXEL_ONE - 1).div_euclid(SUBPIXEL_ONE);
        let last = |max: i64| (max - SUBPIXEL_HALF).div_euclid(SUBPIXEL_ONE);
        let x0 = first(min_x).max(0);
        let y0 = first(min_y).max(0);
        let x1 = (last(max_x) + 1).min(i64::from(width));
        let y1 = (last(max_y) + 1).min(i64::from(height));
        if x0 >= x1 || y0 >= y1 {
            return None;
        }

        let (mut a, mut b, mut c) = ([0i64; 3], [0i64; 3], [0i64; 3]);
        for i in 0..3 {
            let (p, q) = (&v[i], &v[(i + 1) % 3]);
            a[i] = q.y - p.y;
            b[i] = p.x - q.x;
            c[i] = -(a[i] * p.x + b[i] * p.y);
            let top_left = a[i] > 0 || (a[i] == 0 && b[i] > 0);
            if !top_left {
                c[i] -= 1;
            }
        }

        let pixel = |u: i64| u as f64 / SUBPIXEL_ONE as f64;
        let (px, py) = (v.map(|v| pixel(v.x)), v.map(|v| pixel(v.y)));
        let (e1x, e1y) = (px[1] - px[0], py[1] - py[0]);
        let (e2x, e2y) = (px[2] - px[0], py[2] - py[0]);
        let inv_det = 1.0 / (e1x * e2y - e2x * e1y);
        // Pixel centre of the first pixel, relative to vertex 0.
        let (ox, oy) = (x0 as f64 + 0.5 - px[0], y0 as f64 + 0.5 - py[0]);
        let mut plane = |q: [f64; 3]| {
            let (d1, d2) = (q[1] - q[0], q[2] - q[0]);
            let dx = (d1 * e2y - d2 * e1y) * inv_det;
            let dy = (d2 * e1x - d1 * e2x) * inv_det;
            planes.push(Plane {
                at_origin: (q[0] + dx * ox + dy * oy) as f32,
                dx: dx as f32,
                dy: dy as f32,
            });
        };
        plane(v.map(|v| f64::from(v.depth)));
        plane(v.map(|v| f64::from(v.inv_w)));
        for k in 0..attrs.min(N) {
            plane(v.map(|v| {
                let scale = match interpolation {
                    Interpolation::Perspective => f64::from(v.inv_w),
                    Interpolation::Screen => 1.0,
                };
                f64::from(v.attrs[k]) * scale
            }));
        }
        Some(Triangle {
            a,
            b,
            c,
            x0: x0 as i32,
            y0: y0 as i32,
            x1: x1 as i32,
            y1: y1 as i32,
            color: 0,
            flip: 1.0,
            once: 0,
        })
    }

    /// The bands this triangle's rows fall in.
    pub fn bands(&self) -> std::ops::Range<usize> {
        self.y0 as usize / BAND_ROWS as usize..(self.y1 as usize - 1) / BAND_ROWS as usize + 1
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
        let mut planes = Vec::new();
        let t = Triangle::new(&tri, 1, 64, 64, Interpolation::Screen, &mut planes).unwrap();
        assert_eq!(planes.len(), 3);
        // attr = x + 2y in snapped units = 256·(X + 2Y) in pixels.
        let p = planes[2];
        assert!((p.dx - 256.0).abs() < 1e-3 && (p.dy - 512.0).abs() < 1e-3);
        let centre = |x: i32, y: i32| (x as f32 + 0.5) * 256.0 + 2.0 * (y as f32 + 0.5) * 256.0;
        assert!((p.at_origin - centre(t.x0, t.y0)).abs() < 1e-2);
    }

    #[test]
    fn bounding_box_takes_pixel_centres() {
        let tri = [v(128, 128), v(128, 1152), v(1152, 128)];
        let t = Triangle::new(&tri, 1, 64, 64, Interpolation::Screen, &mut Vec::new()).unwrap();
        assert_eq!((t.x0, t.y0, t.x1, t.y1), (0, 0, 5, 5));
        let off = [v(-900, 10), v(-900, 900), v(-200, 10)];
        assert!(Triangle::new(&off, 1, 64, 64, Interpolation::Screen, &mut Vec::new()).is_none());
    }
}
