//! What every rasterizer shares: window-space vertices in fixed point, the
//! fragment output interface and the interpolation modes.
//!
//! Window coordinates are snapped to 1/256 pixel ([`SUBPIXEL_BITS`] = 8) once,
//! by [`snap`]; coverage is then decided in exact integer arithmetic, so two
//! rasterizers fed the same vertices agree on every pixel.

pub mod scanline;

/// Bits of sub-pixel precision in snapped window coordinates.
pub const SUBPIXEL_BITS: u32 = 8;
/// One pixel in snapped units.
pub const SUBPIXEL_ONE: i64 = 1 << SUBPIXEL_BITS;
/// Half a pixel in snapped units: the offset of a pixel's centre.
pub const SUBPIXEL_HALF: i64 = SUBPIXEL_ONE / 2;

/// Snaps a window coordinate (in pixels) to the fixed-point grid.
pub fn snap(pixels: f64) -> i64 {
    (pixels * SUBPIXEL_ONE as f64).round() as i64
}

/// How attributes are interpolated across a polygon.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Interpolation {
    /// Perspective-correct: attributes divided by w are linear in window space.
    #[default]
    Perspective,
    /// The textbook's screen-space linear interpolation along edges and spans.
    Screen,
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
