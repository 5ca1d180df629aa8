//! What every rasterizer shares: window-space vertices in fixed point,
//! what it receives from the frame (`polygons.rs`: the frame's polygons,
//! clipped and in window space, handed to its `PolygonSink`), the
//! fragment output interface, fans and the interpolation modes.
//!
//! Window coordinates are snapped to 1/256 pixel ([`SUBPIXEL_BITS`] = 8) once,
//! by [`snap`]; coverage is then decided in exact integer arithmetic, so two
//! rasterizers fed the same vertices agree on every pixel.

mod polygons;
pub mod scanline;
pub(crate) mod tiled;

pub(crate) use self::polygons::{PolygonSink, PolygonSource, Projected, Scratch, VertexStage};
pub use crate::scene::Interpolation;

use crate::image::Image;
use crate::scene::{RenderOptions, RenderStats, Scene};
use crate::shade::Lighting;

/// What the frame asks of a rasterizer, given a checked scene, the frame's
/// lighting and its polygons: both rasterizers implement it, and the frame
/// (`frame/mod.rs`) knows no more of them.
///
/// The frame's polygons (`frame/assemble.rs`: the window transform,
/// facing, culling, clipping) come in as a [`VertexStage`]: each rasterizer
/// runs it, then walks the [`PolygonSource`] it returns into its own
/// [`PolygonSink`], receiving the
/// visible ones, clipped, in window space, with their attributes. The
/// tiled rasterizer walks one chunk of polygons per sink, in parallel (its
/// setup and binning); the scanline rasterizer all of them into one sink
/// (its fill).
pub(crate) trait Rasterize {
    /// Draws `scene`'s polygons, `frame`, into `image` (already of the
    /// options' size).
    fn render<V: VertexStage>(
        &mut self,
        frame: &mut V,
        scene: &Scene,
        options: &RenderOptions,
        lighting: &Lighting,
        image: &mut Image,
    ) -> RenderStats;
    /// How many polygons cover each pixel, row by row, with no depth test
    /// (`options.shading` is flat: no colour is needed).
    fn coverage<V: VertexStage>(
        &mut self,
        frame: &mut V,
        scene: &Scene,
        options: &RenderOptions,
        lighting: &Lighting,
    ) -> Vec<u32>;
}

/// Bits of sub-pixel precision in snapped window coordinates.
pub const SUBPIXEL_BITS: u32 = 8;
/// One pixel in snapped units.
pub const SUBPIXEL_ONE: i64 = 1 << SUBPIXEL_BITS;
/// Half a pixel in snapped units: the offset of a pixel's centre.
pub const SUBPIXEL_HALF: i64 = SUBPIXEL_ONE / 2;

/// Snaps a window coordinate (in pixels) to the fixed-point grid.
pub fn snap(pixels: f64) -> i64 {
    // `f64::round` (half away from zero) without a libm call: truncate, then
    // step away from zero when the remainder is at least one half. Exact for
    // |x| < 2^52; beyond i64 the casts saturate, as `round() as i64` does.
    let x = pixels * SUBPIXEL_ONE as f64;
    let t = x as i64;
    // Without branches: the remainder's sign is a coin toss from vertex to
    // vertex, and mispredicted branches here cost more than the arithmetic.
    let rest = x - t as f64;
    t.saturating_add(i64::from(rest >= 0.5))
        .saturating_sub(i64::from(rest <= -0.5))
}

#[cfg(test)]
mod tests {
    #[test]
    fn snap_rounds_half_away_from_zero() {
        for x in [
            0.0,
            0.5,
            -0.5,
            1.5,
            -1.5,
            2.49999,
            -2.50001,
            1e9 + 0.5,
            -7.25,
            1e30,
            -1e30,
        ] {
            for scale in [1.0, 1.0 / 256.0] {
                let pixels = x * scale;
                assert_eq!(
                    super::snap(pixels),
                    (pixels * 256.0).round() as i64,
                    "{pixels}"
                );
            }
        }
        assert_eq!(super::snap(f64::NAN), 0);
    }
}

/// A polygon vertex in window space, ready to rasterize.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScreenVertex<const N: usize> {
    /// x in 1/256 pixel, 0 at the left edge of the image.
    pub x: i64,
    /// y in 1/256 pixel, 0 at the top edge of the image.
    pub y: i64,
    /// Window depth in [0, 1] (OpenGL's default depth range).
    pub depth: f32,
    /// 1 / w of the clip-space position.
    pub inv_w: f32,
    /// Attributes to interpolate.
    pub attrs: [f32; N],
}

/// Receives the fragments a rasterizer produces (tiny-skia's `Blitter`).
pub trait FragmentSink<const N: usize> {
    /// Pixel (`x`, `y`) is covered, at window depth `depth`, with the
    /// interpolated attributes `attrs`.
    fn fragment(&mut self, x: u32, y: u32, depth: f32, attrs: &[f32; N]);

    /// Whether the scanline rasterizer should describe its spans on row `y`
    /// ([`FragmentSink::trace`]). The default, a constant `false`, lets the
    /// compiler drop the tracing from ordinary renders.
    #[inline(always)]
    fn wants_trace(&self, _y: u32) -> bool {
        false
    }

    /// The scanline walk's state for a span about to be filled, on a row
    /// for which [`FragmentSink::wants_trace`] said yes.
    #[inline(always)]
    fn trace(&mut self, _span: &scanline::SpanTrace<'_, N>) {}
}

/// Twice the signed area of a snapped polygon in window units, positive when
/// the viewer sees it counter-clockwise (window y points down).
pub fn signed_area_ccw<const N: usize>(polygon: &[ScreenVertex<N>]) -> i128 {
    let n = polygon.len();
    let mut sum: i128 = 0;
    for i in 0..n {
        let a = &polygon[i];
        let b = &polygon[(i + 1) % n];
        sum += a.x as i128 * b.y as i128 - b.x as i128 * a.y as i128;
    }
    -sum
}

/// Whether a counter-clockwise polygon is convex and winds once.
pub(crate) fn is_convex<const N: usize>(polygon: &[ScreenVertex<N>]) -> bool {
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

/// How a polygon is split into triangles: a fan from one of its vertices.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Fan {
    /// The vertex all triangles share.
    pub apex: usize,
    /// No vertex sees all others (a polygon crossing itself, which only
    /// clipping of absurd coordinates produces): the fan's triangles overlap,
    /// and each pixel must be drawn once only.
    pub once_per_pixel: bool,
}

/// The fan both rasterizers use for a counter-clockwise polygon: from the
/// first vertex whose fan has no clockwise triangle and goes round it at
/// most once, which is vertex 0 for every convex polygon. Where there is
/// none, the first counter-clockwise fan that goes round more than once,
/// else the fan from vertex 0, drawn once per pixel.
///
/// Triangles that all turn counter-clockwise about the apex still overlap
/// when their angles there add up to a full turn or more: a polygon that
/// clipping of absurd coordinates made wind twice round the apex (found by
/// `tests/extremes.rs`, `extremes::never_panics`: five pixels drawn twice).
/// With four vertices that cannot happen (two angles of at most half a
/// turn each, the second one's triangle empty if both are half a turn), so
/// only polygons of five or more vertices, which only clipping makes in a
/// mesh of triangles and quads, pay for the angles.
pub fn fan<const N: usize>(polygon: &[ScreenVertex<N>]) -> Fan {
    let n = polygon.len();
    let fan = |apex: usize| Fan {
        apex,
        once_per_pixel: false,
    };
    if n <= 3 {
        return fan(0);
    }
    let counter_clockwise = |f: &Fan| f.triangles(polygon).all(|t| signed_area_ccw(&t) >= 0);
    if n > 4 {
        return fan_of_many(polygon, counter_clockwise);
    }
    (0..n).map(fan).find(counter_clockwise).unwrap_or(Fan {
        apex: 0,
        once_per_pixel: true,
    })
}

/// [`fan`] of a polygon of five or more vertices, whose fan's angles must
/// be added up: kept out of line, off the path of every quad.
#[inline(never)]
fn fan_of_many<const N: usize>(
    polygon: &[ScreenVertex<N>],
    counter_clockwise: impl Fn(&Fan) -> bool,
) -> Fan {
    // The first apex whose fan turns counter-clockwise but round it more
    // than once: drawn once per pixel, if no apex is better.
    let mut wrapping = None;
    for apex in 0..polygon.len() {
        let f = Fan {
            apex,
            once_per_pixel: false,
        };
        if !counter_clockwise(&f) {
            continue;
        }
        if f.turn(polygon) < std::f64::consts::TAU * (1.0 - 1e-9) {
            return f;
        }
        wrapping.get_or_insert(apex);
    }
    Fan {
        apex: wrapping.unwrap_or(0),
        once_per_pixel: true,
    }
}

impl Fan {
    /// The angles of the fan's triangles at the apex added up, in radians,
    /// each in `[0, π]` for a counter-clockwise triangle: below a full turn
    /// (with a margin for rounding), the triangles do not overlap.
    fn turn<const N: usize>(self, polygon: &[ScreenVertex<N>]) -> f64 {
        self.triangles(polygon)
            .map(|[a, b, c]| {
                let (ux, uy) = ((b.x - a.x) as f64, (b.y - a.y) as f64);
                let (vx, vy) = ((c.x - a.x) as f64, (c.y - a.y) as f64);
                // Window y points down: counter-clockwise is a negative cross product.
                (uy * vx - ux * vy).atan2(ux * vx + uy * vy)
            })
            .sum()
    }

    /// The fan's triangles, in order, counter-clockwise like the polygon.
    pub fn triangles<'a, const N: usize>(
        self,
        polygon: &'a [ScreenVertex<N>],
    ) -> impl Iterator<Item = [ScreenVertex<N>; 3]> + 'a {
        let n = polygon.len();
        (1..n.saturating_sub(1)).map(move |k| {
            [
                polygon[self.apex],
                polygon[(self.apex + k) % n],
                polygon[(self.apex + k + 1) % n],
            ]
        })
    }
}
