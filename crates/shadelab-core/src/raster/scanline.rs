//! The reference rasterizer: the textbook scanline algorithm over convex polygons.
//!
//! For every pixel row the polygon's left and right edges are crossed at the
//! row's centre line, giving the span's end points P and Q; the pixels whose
//! centres lie in [P, Q) are filled, left to right. What must hold:
//!
//! * **Exact coverage.** Vertices are snapped to 1/256 pixel; each edge's
//!   first covered pixel per row is `ceil(x_cross − ½)`, stepped from row to
//!   row by an integer DDA (quotient and remainder) with no rounding at all.
//!   Rows take an edge's centre lines in `[y_top, y_bottom)`, a span takes
//!   centres in `[x_left, x_right)`: that is the top-left fill rule, so
//!   polygons sharing an edge never leave a gap nor overlap.
//! * **Incremental interpolation.** Depth, 1/w and the attributes are stepped
//!   along each edge by a constant per row, then along each span by a constant
//!   per pixel, `I_O = (1 − u)·I_P + u·I_Q` with `u = |PO| / |PQ|`. In
//!   perspective mode the stepped quantities are attribute/w and 1/w, divided
//!   per pixel; in screen mode the attributes themselves. The stepping runs in
//!   f64 so drift stays far below 1/255 on any image size.
//! * **Polygons, not just triangles.** A convex polygon is walked as a whole,
//!   as the textbook does (Gouraud over a quad is not Gouraud over its two
//!   triangles). A polygon that snapping made non-convex is drawn as a fan.
//!
//! The caller passes polygons wound counter-clockwise as the viewer sees them
//! (see [`super::signed_area_ccw`]); others draw nothing. With that winding,
//! edges going down the screen bound spans on the left and edges going up
//! bound them on the right.

use super::{
    signed_area_ccw, FragmentSink, Interpolation, ScreenVertex, SUBPIXEL_HALF, SUBPIXEL_ONE,
};

/// Depth, 1/w and attributes, the quantities stepped across a polygon.
#[derive(Clone, Copy)]
struct Varyings<const N: usize> {
    depth: f64,
    inv_w: f64,
    attrs: [f64; N],
}

impl<const N: usize> Varyings<N> {
    fn at_vertex(v: &ScreenVertex<N>, interpolation: Interpolation) -> Self {
        let scale = match interpolation {
            Interpolation::Perspective => v.inv_w as f64,
            Interpolation::Screen => 1.0,
        };
        Varyings {
            depth: v.depth as f64,
            inv_w: v.inv_w as f64,
            attrs: v.attrs.map(|a| a as f64 * scale),
        }
    }

    /// `self + (other − self)·t`, and its derivative scaled by `rate`.
    fn lerp_and_rate(&self, other: &Self, t: f64, rate: f64) -> (Self, Self) {
        let mut value = *self;
        let mut step = *self;
        value.depth += (other.depth - self.depth) * t;
        step.depth = (other.depth - self.depth) * rate;
        value.inv_w += (other.inv_w - self.inv_w) * t;
        step.inv_w = (other.inv_w - self.inv_w) * rate;
        for k in 0..N {
            let d = other.attrs[k] - self.attrs[k];
            value.attrs[k] += d * t;
            step.attrs[k] = d * rate;
        }
        (value, step)
    }

    fn add(&mut self, step: &Self) {
        self.depth += step.depth;
        self.inv_w += step.inv_w;
        for k in 0..N {
            self.attrs[k] += step.attrs[k];
        }
    }
}

/// The first pixel whose centre is at or right of an edge's crossing with the
/// current row, kept exactly as `q + r/d` (pixels, minus the half-pixel offset)
/// and stepped by a constant per row.
#[derive(Clone, Copy)]
struct EdgeBound {
    q: i64,
    r: i64,
    d: i64,
    step_q: i64,
    step_r: i64,
}

impl EdgeBound {
    fn new(numerator: i64, denominator: i64, step: i64) -> EdgeBound {
        EdgeBound {
            q: numerator.div_euclid(denominator),
            r: numerator.rem_euclid(denominator),
            d: denominator,
            step_q: step.div_euclid(denominator),
            step_r: step.rem_euclid(denominator),
        }
    }

    /// `ceil(x_cross − ½)`: the first pixel whose centre is not left of the crossing.
    fn first_pixel(&self) -> i64 {
        self.q + i64::from(self.r > 0)
    }

    /// The crossing's x in pixels.
    fn crossing(&self) -> f64 {
        self.q as f64 + self.r as f64 / self.d as f64 + 0.5
    }

    fn step(&mut self) {
        self.q += self.step_q;
        self.r += self.step_r;
        if self.r >= self.d {
            self.r -= self.d;
            self.q += 1;
        }
    }
}

/// An edge running down the screen from `top` to `bottom` (`top.y < bottom.y`).
struct Edge<'a, const N: usize> {
    top: &'a ScreenVertex<N>,
    bottom: &'a ScreenVertex<N>,
    /// Rows whose centre line the edge crosses, clipped to the image.
    rows: std::ops::Range<i64>,
}

/// An edge being walked, row by row.
struct EdgeWalk<const N: usize> {
    end_row: i64,
    bound: EdgeBound,
    varyings: Varyings<N>,
    step: Varyings<N>,
}

impl<const N: usize> EdgeWalk<N> {
    fn start(edge: &Edge<'_, N>, row: i64, interpolation: Interpolation) -> EdgeWalk<N> {
        let (a, b) = (edge.top, edge.bottom);
        let dy = b.y - a.y;
        let dx = b.x - a.x;
        let centre_y = row * SUBPIXEL_ONE + SUBPIXEL_HALF;
        let bound = EdgeBound::new(
            (a.x - SUBPIXEL_HALF) * dy + (centre_y - a.y) * dx,
            SUBPIXEL_ONE * dy,
            SUBPIXEL_ONE * dx,
        );
        let t = (centre_y - a.y) as f64 / dy as f64;
        let rate = SUBPIXEL_ONE as f64 / dy as f64;
        let (varyings, step) = Varyings::at_vertex(a, interpolation).lerp_and_rate(
            &Varyings::at_vertex(b, interpolation),
            t,
            rate,
        );
        EdgeWalk {
            end_row: edge.rows.end,
            bound,
            varyings,
            step,
        }
    }

    fn step(&mut self) {
        self.bound.step();
        self.varyings.add(&self.step);
    }
}

/// The rows whose pixel centres lie in `[top, bottom)` (snapped units).
fn rows_between(top: i64, bottom: i64) -> std::ops::Range<i64> {
    let first = |y: i64| (y - SUBPIXEL_HALF + SUBPIXEL_ONE - 1).div_euclid(SUBPIXEL_ONE);
    first(top)..first(bottom)
}

/// Whether a counter-clockwise polygon is convex and winds once.
fn is_convex<const N: usize>(polygon: &[ScreenVertex<N>]) -> bool {
    let n = polygon.len();
    if n == 3 {
        return true;
    }
    let mut direction_changes = 0;
    let mut last_dy = 0i64;
    for i in 0..n {
        let a = &polygon[i];
        let b = &polygon[(i + 1) % n];
        let c = &polygon[(i + 2) % n];
        let turn =
            (b.x - a.x) as i128 * (c.y - b.y) as i128 - (b.y - a.y) as i128 * (c.x - b.x) as i128;
        // Window y points down, so a counter-clockwise turn is negative here.
        if turn > 0 {
            return false;
        }
        let dy = (b.y - a.y).signum();
        if dy != 0 {
            if last_dy != 0 && dy != last_dy {
                direction_changes += 1;
            }
            last_dy = dy;
        }
    }
    // Close the cycle: compare the last non-zero direction with the first.
    if let Some(first) = (0..n)
        .map(|i| (polygon[(i + 1) % n].y - polygon[i].y).signum())
        .find(|&d| d != 0)
    {
        if first != last_dy {
            direction_changes += 1;
        }
    }
    direction_changes <= 2
}

/// Fills a convex polygon, wound counter-clockwise as the viewer sees it,
/// into a `width` × `height` image, sending each covered pixel to `sink`.
///
/// Polygons with clockwise or zero area draw nothing.
pub fn rasterize_polygon<const N: usize>(
    polygon: &[ScreenVertex<N>],
    width: u32,
    height: u32,
    interpolation: Interpolation,
    sink: &mut impl FragmentSink<N>,
) {
    if polygon.len() < 3 || signed_area_ccw(polygon) <= 0 {
        return;
    }
    if !is_convex(polygon) {
        for k in 1..polygon.len() - 1 {
            let triangle = [polygon[0], polygon[k], polygon[k + 1]];
            rasterize_polygon(&triangle, width, height, interpolation, sink);
        }
        return;
    }

    let image_rows = 0..i64::from(height);
    let clip_rows =
        |r: std::ops::Range<i64>| r.start.max(image_rows.start)..r.end.min(image_rows.end);
    let n = polygon.len();
    let mut left: Vec<Edge<'_, N>> = Vec::with_capacity(n);
    let mut right: Vec<Edge<'_, N>> = Vec::with_capacity(n);
    for i in 0..n {
        let a = &polygon[i];
        let b = &polygon[(i + 1) % n];
        let (edge_list, top, bottom) = match a.y.cmp(&b.y) {
            std::cmp::Ordering::Less => (&mut left, a, b),
            std::cmp::Ordering::Greater => (&mut right, b, a),
            std::cmp::Ordering::Equal => continue,
        };
        let rows = clip_rows(rows_between(top.y, bottom.y));
        if !rows.is_empty() {
            edge_list.push(Edge { top, bottom, rows });
        }
    }
    left.sort_by_key(|e| e.rows.start);
    right.sort_by_key(|e| e.rows.start);
    let (Some(first), Some(last)) = (left.first(), left.last()) else {
        return;
    };
    let rows = first.rows.start..last.rows.end;

    let mut next_left = left.iter();
    let mut next_right = right.iter();
    let mut left_walk: Option<EdgeWalk<N>> = None;
    let mut right_walk: Option<EdgeWalk<N>> = None;
    let advance = |walk: &mut Option<EdgeWalk<N>>,
                   edges: &mut std::slice::Iter<'_, Edge<'_, N>>,
                   row: i64| {
        if walk.as_ref().is_none_or(|w| row >= w.end_row) {
            *walk = edges
                .by_ref()
                .find(|e| e.rows.end > row)
                .filter(|e| e.rows.start <= row)
                .map(|e| EdgeWalk::start(e, row, interpolation));
        }
    };
    let mut attrs = [0f32; N];
    for row in rows {
        advance(&mut left_walk, &mut next_left, row);
        advance(&mut right_walk, &mut next_right, row);
        let (Some(l), Some(r)) = (left_walk.as_mut(), right_walk.as_mut()) else {
            // Only a polygon that is not convex could get here; it has no more spans.
            return;
        };
        let first = l.bound.first_pixel().max(0);
        let end = r.bound.first_pixel().min(i64::from(width));
        if first < end {
            let (p, q) = (l.bound.crossing(), r.bound.crossing());
            let (mut v, step) = l.varyings.lerp_and_rate(
                &r.varyings,
                (first as f64 + 0.5 - p) / (q - p),
                1.0 / (q - p),
            );
            for x in first..end {
                for k in 0..N {
                    attrs[k] = match interpolation {
                        Interpolation::Perspective => (v.attrs[k] / v.inv_w) as f32,
                        Interpolation::Screen => v.attrs[k] as f32,
                    };
                }
                sink.fragment(x as u32, row as u32, v.depth as f32, &attrs);
                v.add(&step);
            }
        }
        l.step();
        r.step();
    }
}
