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
//!   triangles). A polygon that snapping made non-convex is drawn as a fan
//!   from a vertex that sees all the others.
//!
//! * **Fixed point on request.** With [`ScanlineOptions::fraction_bits`] the
//!   attributes (attribute/w in perspective mode) are held as multiples of
//!   2^−F: every start value and every step is rounded down to that grid (an
//!   arithmetic shift, as integer hardware does), and the sums stay on it
//!   exactly, so the error of a span grows with its length as it did on
//!   old machines. Depth, 1/w and coverage stay exact.
//! * **A trace for whoever asks.** A sink whose
//!   [`FragmentSink::wants_trace`] says yes for a row is told the walk's state
//!   there ([`SpanTrace`]: the edges crossed, P and Q, the values stepped
//!   along the edges and the span) before the row's fragments. The default
//!   answer is a constant `false`, so an ordinary render pays nothing.
//!
//! The caller passes polygons wound counter-clockwise as the viewer sees them
//! (see [`super::signed_area_ccw`]); others draw nothing. With that winding,
//! edges going down the screen bound spans on the left and edges going up
//! bound them on the right.

mod draw;

pub(crate) use self::draw::{draw, ScanlineRasterizer, Target};
pub use crate::scene::{MAX_FRACTION_BITS, MIN_FRACTION_BITS};

use super::{
    fan, is_convex, signed_area_ccw, FragmentSink, Interpolation, ScreenVertex, SUBPIXEL_HALF,
    SUBPIXEL_ONE,
};

/// How the scanline rasterizer steps its quantities.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ScanlineOptions {
    /// Perspective-correct or screen-linear attributes.
    pub interpolation: Interpolation,
    /// Hold the stepped attributes in fixed point with this many fraction
    /// bits ([`MIN_FRACTION_BITS`]`..=`[`MAX_FRACTION_BITS`]); `None`: in `f64`.
    pub fraction_bits: Option<u32>,
}

impl ScanlineOptions {
    /// Floating-point stepping with `interpolation`.
    pub fn new(interpolation: Interpolation) -> ScanlineOptions {
        ScanlineOptions {
            interpolation,
            fraction_bits: None,
        }
    }
}

/// Rounds attributes down to multiples of 1/`scale` (depth and 1/w
/// untouched) when `FIXED`; compiled away otherwise.
#[inline(always)]
fn snap<const N: usize, const FIXED: bool>(scale: f64, v: &mut Varyings<N>) {
    if FIXED {
        for a in &mut v.attrs {
            *a = (*a * scale).floor() / scale;
        }
    }
}

/// Depth, 1/w and attributes: the quantities stepped across a polygon. In
/// perspective mode `attrs` holds attribute/w; in screen mode the attributes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Varyings<const N: usize> {
    /// Window depth.
    pub depth: f64,
    /// 1/w.
    pub inv_w: f64,
    /// The attributes as stepped (attribute/w in perspective mode).
    pub attrs: [f64; N],
}

impl<const N: usize> Varyings<N> {
    /// The values at a vertex, as the walk starts from them.
    pub fn at_vertex(v: &ScreenVertex<N>, interpolation: Interpolation) -> Self {
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

    /// The attributes themselves: divided by 1/w in perspective mode.
    pub fn attributes(&self, interpolation: Interpolation) -> [f64; N] {
        match interpolation {
            Interpolation::Perspective => self.attrs.map(|a| a / self.inv_w),
            Interpolation::Screen => self.attrs,
        }
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
    /// Indices of `top` and `bottom` in the polygon.
    ends: (usize, usize),
    /// Rows whose centre line the edge crosses, clipped to the image.
    rows: std::ops::Range<i64>,
}

/// An edge being walked, row by row.
struct EdgeWalk<const N: usize> {
    end_row: i64,
    ends: (usize, usize),
    /// The edge's ends in snapped window y, for the trace's edge parameter.
    y_range: (i64, i64),
    bound: EdgeBound,
    varyings: Varyings<N>,
    step: Varyings<N>,
}

impl<const N: usize> EdgeWalk<N> {
    fn start<const FIXED: bool>(
        edge: &Edge<'_, N>,
        row: i64,
        interpolation: Interpolation,
        scale: f64,
    ) -> EdgeWalk<N> {
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
        let (mut varyings, mut step) = Varyings::at_vertex(a, interpolation).lerp_and_rate(
            &Varyings::at_vertex(b, interpolation),
            t,
            rate,
        );
        snap::<N, FIXED>(scale, &mut varyings);
        snap::<N, FIXED>(scale, &mut step);
        EdgeWalk {
            end_row: edge.rows.end,
            ends: edge.ends,
            y_range: (a.y, b.y),
            bound,
            varyings,
            step,
        }
    }

    fn step(&mut self) {
        self.bound.step();
        self.varyings.add(&self.step);
    }

    fn trace(&self, row: i64) -> EdgeTrace<N> {
        let centre_y = row * SUBPIXEL_ONE + SUBPIXEL_HALF;
        let (top, bottom) = self.y_range;
        EdgeTrace {
            top: self.ends.0,
            bottom: self.ends.1,
            x: self.bound.crossing(),
            t: (centre_y - top) as f64 / (bottom - top) as f64,
            value: self.varyings,
        }
    }
}

/// Where a scanline crosses one edge of the polygon, as the walk found it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EdgeTrace<const N: usize> {
    /// Index in [`SpanTrace::polygon`] of the edge's upper end.
    pub top: usize,
    /// Index of its lower end.
    pub bottom: usize,
    /// The crossing's x in pixels (P on a left edge, Q on a right one).
    pub x: f64,
    /// The edge parameter there: 0 at `top`, 1 at `bottom`, linear in y.
    pub t: f64,
    /// The values stepped down the edge to this row.
    pub value: Varyings<N>,
}

/// The scanline walk's state for one span, handed to sinks that ask
/// ([`FragmentSink::wants_trace`]) before the span's fragments.
#[derive(Debug, Clone)]
pub struct SpanTrace<'a, const N: usize> {
    /// The convex polygon walked: the whole polygon, or a triangle of its fan.
    pub polygon: &'a [ScreenVertex<N>],
    /// The row; its centre line is at y = row + ½.
    pub row: u32,
    /// The left edge crossed, at P.
    pub left: EdgeTrace<N>,
    /// The right edge crossed, at Q.
    pub right: EdgeTrace<N>,
    /// First pixel filled, and one past the last.
    pub pixels: std::ops::Range<u32>,
    /// The values at the first pixel's centre.
    pub start: Varyings<N>,
    /// Their step from one pixel to the next.
    pub step: Varyings<N>,
    /// How the values were stepped.
    pub options: ScanlineOptions,
}

/// The rows whose pixel centres lie in `[top, bottom)` (snapped units).
fn rows_between(top: i64, bottom: i64) -> std::ops::Range<i64> {
    let first = |y: i64| (y - SUBPIXEL_HALF + SUBPIXEL_ONE - 1).div_euclid(SUBPIXEL_ONE);
    first(top)..first(bottom)
}

/// Passes on the first fragment of each pixel and drops the rest.
struct OncePerPixel<'a, S> {
    drawn: Vec<u64>,
    width: u32,
    sink: &'a mut S,
}

impl<const N: usize, S: FragmentSink<N>> FragmentSink<N> for OncePerPixel<'_, S> {
    fn fragment(&mut self, x: u32, y: u32, depth: f32, attrs: &[f32; N]) {
        let bit = y as usize * self.width as usize + x as usize;
        let (word, mask) = (bit / 64, 1u64 << (bit % 64));
        if self.drawn[word] & mask == 0 {
            self.drawn[word] |= mask;
            self.sink.fragment(x, y, depth, attrs);
        }
    }

    fn wants_trace(&self, y: u32) -> bool {
        self.sink.wants_trace(y)
    }

    fn trace(&mut self, span: &SpanTrace<'_, N>) {
        self.sink.trace(span);
    }
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
    let options = ScanlineOptions::new(interpolation);
    rasterize_polygon_with(polygon, width, height, &options, sink);
}

/// [`rasterize_polygon`] with every stepping option.
pub fn rasterize_polygon_with<const N: usize>(
    polygon: &[ScreenVertex<N>],
    width: u32,
    height: u32,
    options: &ScanlineOptions,
    sink: &mut impl FragmentSink<N>,
) {
    if polygon.len() < 3 || signed_area_ccw(polygon) <= 0 {
        return;
    }
    if !is_convex(polygon) {
        rasterize_fan_with(polygon, width, height, options, sink);
        return;
    }
    rasterize_convex(polygon, width, height, options, sink);
}

/// Rasterizes a polygon as the triangles of its [`fan`], the way the tiled
/// rasterizer draws every polygon: per-triangle (planar) interpolation.
pub fn rasterize_fan<const N: usize>(
    polygon: &[ScreenVertex<N>],
    width: u32,
    height: u32,
    interpolation: Interpolation,
    sink: &mut impl FragmentSink<N>,
) {
    let options = ScanlineOptions::new(interpolation);
    rasterize_fan_with(polygon, width, height, &options, sink);
}

/// [`rasterize_fan`] with every stepping option.
pub fn rasterize_fan_with<const N: usize>(
    polygon: &[ScreenVertex<N>],
    width: u32,
    height: u32,
    options: &ScanlineOptions,
    sink: &mut impl FragmentSink<N>,
) {
    if polygon.len() < 3 || signed_area_ccw(polygon) <= 0 {
        return;
    }
    let fan = fan(polygon);
    if fan.once_per_pixel {
        let mut once = OncePerPixel {
            drawn: vec![0; (width as usize * height as usize).div_ceil(64)],
            width,
            sink,
        };
        for triangle in fan.triangles(polygon) {
            rasterize_triangle(&triangle, width, height, options, &mut once);
        }
    } else {
        for triangle in fan.triangles(polygon) {
            rasterize_triangle(&triangle, width, height, options, sink);
        }
    }
}

/// A fan triangle: drawn when counter-clockwise, skipped otherwise.
fn rasterize_triangle<const N: usize>(
    triangle: &[ScreenVertex<N>; 3],
    width: u32,
    height: u32,
    options: &ScanlineOptions,
    sink: &mut impl FragmentSink<N>,
) {
    if signed_area_ccw(triangle) > 0 {
        rasterize_convex(triangle, width, height, options, sink);
    }
}

/// The scanline walk for a convex counter-clockwise polygon, in floating
/// or fixed point.
fn rasterize_convex<const N: usize>(
    polygon: &[ScreenVertex<N>],
    width: u32,
    height: u32,
    options: &ScanlineOptions,
    sink: &mut impl FragmentSink<N>,
) {
    match options.fraction_bits {
        None => walk_convex::<N, false>(polygon, width, height, options, 1.0, sink),
        Some(bits) => {
            let scale = f64::from(1u32 << bits.clamp(MIN_FRACTION_BITS, MAX_FRACTION_BITS));
            walk_convex::<N, true>(polygon, width, height, options, scale, sink);
        }
    }
}

/// The scanline walk proper.
fn walk_convex<const N: usize, const FIXED: bool>(
    polygon: &[ScreenVertex<N>],
    width: u32,
    height: u32,
    options: &ScanlineOptions,
    scale: f64,
    sink: &mut impl FragmentSink<N>,
) {
    let interpolation = options.interpolation;
    let image_rows = 0..i64::from(height);
    let clip_rows =
        |r: std::ops::Range<i64>| r.start.max(image_rows.start)..r.end.min(image_rows.end);
    let n = polygon.len();
    let mut left: Vec<Edge<'_, N>> = Vec::with_capacity(n);
    let mut right: Vec<Edge<'_, N>> = Vec::with_capacity(n);
    for i in 0..n {
        let j = (i + 1) % n;
        let (a, b) = (&polygon[i], &polygon[j]);
        let (edge_list, top, bottom, ends) = match a.y.cmp(&b.y) {
            std::cmp::Ordering::Less => (&mut left, a, b, (i, j)),
            std::cmp::Ordering::Greater => (&mut right, b, a, (j, i)),
            std::cmp::Ordering::Equal => continue,
        };
        let rows = clip_rows(rows_between(top.y, bottom.y));
        if !rows.is_empty() {
            edge_list.push(Edge {
                top,
                bottom,
                ends,
                rows,
            });
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
                .map(|e| EdgeWalk::start::<FIXED>(e, row, interpolation, scale));
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
            let (mut v, mut step) = l.varyings.lerp_and_rate(
                &r.varyings,
                (first as f64 + 0.5 - p) / (q - p),
                1.0 / (q - p),
            );
            snap::<N, FIXED>(scale, &mut v);
            snap::<N, FIXED>(scale, &mut step);
            if sink.wants_trace(row as u32) {
                sink.trace(&SpanTrace {
                    polygon,
                    row: row as u32,
                    left: l.trace(row),
                    right: r.trace(row),
                    pixels: first as u32..end as u32,
                    start: v,
                    step,
                    options: *options,
                });
            }
            for x in first..end {
                for (out, value) in attrs.iter_mut().zip(v.attrs) {
                    *out = match interpolation {
                        Interpolation::Perspective => (value / v.inv_w) as f32,
                        Interpolation::Screen => value as f32,
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

#[cfg(test)]
mod tests;
