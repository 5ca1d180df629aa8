//! Polygon clipping in homogeneous clip space (Sutherland–Hodgman).
//!
//! Polygons are clipped against the near and far planes (`-w ≤ z ≤ w`), so
//! every vertex that reaches the perspective divide has `w ≥ near > 0`, and
//! against a guard band `|x|, |y| ≤ g·w` far outside the viewport, so window
//! coordinates stay small enough for exact fixed-point edge arithmetic.
//! Only triangles larger than the guard band are cut at x and y; the cut runs
//! outside the viewport, so no pixel changes.
//!
//! A new vertex is always interpolated from the inside end of an edge towards
//! the outside end, so the two polygons sharing an edge compute bit-identical
//! intersection points and stay watertight after clipping.

use glam::Vec4;

/// A polygon vertex before the perspective divide, with `N` attributes that
/// vary linearly across the polygon in world space.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClipVertex<const N: usize> {
    /// Homogeneous clip-space position.
    pub clip: Vec4,
    /// Attributes (normal, world position, colour… depending on the shading).
    pub attrs: [f32; N],
}

impl<const N: usize> ClipVertex<N> {
    fn lerp(&self, other: &ClipVertex<N>, t: f32) -> ClipVertex<N> {
        let mut attrs = self.attrs;
        for (a, b) in attrs.iter_mut().zip(other.attrs) {
            *a += (b - *a) * t;
        }
        ClipVertex {
            clip: self.clip + (other.clip - self.clip) * t,
            attrs,
        }
    }
}

/// The clip planes, as the signed distance of a clip-space point (inside ≥ 0).
fn plane_distance(plane: usize, guard: f32, p: Vec4) -> f32 {
    match plane {
        0 => p.z + p.w,
        1 => p.w - p.z,
        2 => guard * p.w - p.x,
        3 => guard * p.w + p.x,
        4 => guard * p.w - p.y,
        _ => guard * p.w + p.y,
    }
}

const PLANES: usize = 6;

/// Clips a convex polygon to the view volume (with the guard band `guard`,
/// in NDC units, at x and y) and writes the result to `out`, which is empty
/// when nothing is left. `scratch` is working storage, reused between calls.
///
/// Vertices with a non-finite coordinate make the whole polygon vanish.
pub fn clip_polygon<const N: usize>(
    polygon: &[ClipVertex<N>],
    guard: f32,
    out: &mut Vec<ClipVertex<N>>,
    scratch: &mut Vec<ClipVertex<N>>,
) {
    out.clear();
    if polygon.iter().any(|v| !v.clip.is_finite()) {
        return;
    }
    let mut outside_any = false;
    for v in polygon {
        for plane in 0..PLANES {
            let d = plane_distance(plane, guard, v.clip);
            if d < 0.0 {
                outside_any = true;
            }
        }
    }
    out.extend_from_slice(polygon);
    if !outside_any {
        return;
    }
    for plane in 0..PLANES {
        if out.is_empty() {
            return;
        }
        std::mem::swap(out, scratch);
        out.clear();
        let n = scratch.len();
        for i in 0..n {
            let a = &scratch[i];
            let b = &scratch[(i + 1) % n];
            let da = plane_distance(plane, guard, a.clip);
            let db = plane_distance(plane, guard, b.clip);
            if da >= 0.0 {
                out.push(*a);
            }
            if (da >= 0.0) != (db >= 0.0) {
                let (inside, outside, d_in, d_out) = if da >= 0.0 {
                    (a, b, da, db)
                } else {
                    (b, a, db, da)
                };
                let t = d_in / (d_in - d_out);
                out.push(inside.lerp(outside, t));
            }
        }
    }
    if out.len() < 3 {
        out.clear();
    }
}
