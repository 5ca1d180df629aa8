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

/// Whether a finite clip-space point is inside the view volume and guard
/// band: a polygon of such points leaves [`clip_polygon`] unchanged.
pub(crate) fn is_inside(p: Vec4, guard: f32) -> bool {
    (0..PLANES).all(|plane| plane_distance(plane, guard, p) >= 0.0)
}

/// Moves an intersection exactly onto its plane. When both ends of an edge
/// are far from the plane (coordinates near 1e30), the interpolated
/// coordinate can miss the plane by far more than the whole guard band.
fn put_on_plane(plane: usize, guard: f32, p: &mut Vec4) {
    match plane {
        0 => p.z = -p.w,
        1 => p.z = p.w,
        2 => p.x = guard * p.w,
        3 => p.x = -(guard * p.w),
        4 => p.y = guard * p.w,
        _ => p.y = -(guard * p.w),
    }
}

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
    out.extend_from_slice(polygon);
    if polygon.iter().all(|v| is_inside(v.clip, guard)) {
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
                let mut v = inside.lerp(outside, t);
                put_on_plane(plane, guard, &mut v.clip);
                out.push(v);
            }
        }
    }
    if out.len() < 3 {
        out.clear();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cv(x: f32, y: f32, z: f32, w: f32) -> ClipVertex<0> {
        ClipVertex {
            clip: Vec4::new(x, y, z, w),
            attrs: [],
        }
    }

    fn clip(polygon: &[ClipVertex<0>], guard: f32) -> Vec<ClipVertex<0>> {
        let (mut out, mut scratch) = (Vec::new(), Vec::new());
        clip_polygon(polygon, guard, &mut out, &mut scratch);
        out
    }

    #[test]
    fn inside_polygons_pass_unchanged() {
        let tri = [
            cv(-0.5, -0.5, 0.0, 1.0),
            cv(0.5, -0.5, 0.5, 2.0),
            cv(0.0, 0.5, 0.9, 1.0),
        ];
        assert_eq!(clip(&tri, 2.0), tri);
    }

    #[test]
    fn outside_or_broken_polygons_vanish() {
        // Behind the eye: z < −w everywhere.
        assert!(clip(
            &[
                cv(0.0, 0.0, -2.0, -1.0),
                cv(1.0, 0.0, -2.0, -1.0),
                cv(0.0, 1.0, -2.0, -1.0)
            ],
            2.0
        )
        .is_empty());
        // Beyond the guard band.
        assert!(clip(
            &[
                cv(5.0, 0.0, 0.0, 1.0),
                cv(6.0, 0.0, 0.0, 1.0),
                cv(5.0, 1.0, 0.0, 1.0)
            ],
            2.0
        )
        .is_empty());
        // Not finite.
        assert!(clip(
            &[
                cv(f32::NAN, 0.0, 0.0, 1.0),
                cv(1.0, 0.0, 0.0, 1.0),
                cv(0.0, 1.0, 0.0, 1.0)
            ],
            2.0
        )
        .is_empty());
        assert!(clip(
            &[
                cv(f32::INFINITY, 0.0, 0.0, 1.0),
                cv(1.0, 0.0, 0.0, 1.0),
                cv(0.0, 1.0, 0.0, 1.0)
            ],
            2.0
        )
        .is_empty());
    }

    /// Output vertices are inside every plane (to rounding), and the cut
    /// vertices lie exactly on their plane.
    #[test]
    fn output_lies_inside_the_volume() {
        let guard = 3.0;
        let tri = [
            cv(-10.0, -1.0, -5.0, 2.0),
            cv(10.0, 0.5, 3.0, 2.5),
            cv(0.5, 7.0, 0.5, 1.0),
        ];
        let out = clip(&tri, guard);
        assert!(out.len() >= 3);
        for v in &out {
            for plane in 0..PLANES {
                let d = plane_distance(plane, guard, v.clip);
                assert!(d >= -1e-5 * v.clip.w.abs(), "{v:?}: plane {plane} at {d}");
            }
            assert!(v.clip.w > 0.0);
        }
        // The near cut of the first vertex (z = −w exactly).
        assert!(out.iter().any(|v| v.clip.z == -v.clip.w));
    }

    /// Two triangles sharing an edge compute the same cut on it, bit for bit,
    /// whichever way round they walk it.
    #[test]
    fn shared_edge_cut_is_bit_identical() {
        let a = cv(0.3, -0.2, -3.0, 1.0); // behind the near plane
        let b = cv(-0.4, 0.6, 0.2, 1.7);
        let c = cv(0.8, 0.9, 0.5, 2.1);
        let d = cv(-0.9, -0.7, 0.1, 1.2);
        let one = clip(&[a, b, c], 2.0);
        let two = clip(&[b, a, d], 2.0);
        let shared: Vec<_> = one
            .iter()
            .filter(|v| {
                v.clip != b.clip
                    && two.iter().any(|u| {
                        u.clip.to_array().map(f32::to_bits) == v.clip.to_array().map(f32::to_bits)
                    })
            })
            .collect();
        assert_eq!(shared.len(), 1, "{one:?}\n{two:?}");
        assert_eq!(shared[0].clip.z, -shared[0].clip.w);
    }

    /// A triangle of coordinates near 1e30 around the view: both ends of its
    /// edges are far from every guard plane, and the interpolated cuts used to
    /// miss their plane by up to 1e23. The result is the guard square, exactly.
    #[test]
    fn huge_triangle_becomes_the_guard_square() {
        let guard = 16383.0f32;
        let tri = [
            cv(-1.299_038e30, -1.732_050_7e30, 4.8, 5.0),
            cv(1.299_038e30, -1.732_050_7e30, 4.8, 5.0),
            cv(0.0, 1.732_050_7e30, 4.8, 5.0),
        ];
        let out = clip(&tri, guard);
        assert_eq!(out.len(), 4, "{out:?}");
        let g = guard * 5.0;
        for v in &out {
            assert_eq!(v.clip.x.abs(), g, "{out:?}");
            assert_eq!(v.clip.y.abs(), g, "{out:?}");
        }
    }
}
