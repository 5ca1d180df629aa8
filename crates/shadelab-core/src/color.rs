//! Colours: [`Rgb`] in linear 0–1 floats for lighting, [`Rgb8`] for pixels.
//!
//! Colours are not gamma-corrected anywhere: the lighting model works on the
//! 0–255 values scaled to 0–1, and the result is scaled back, as the textbook does.

use std::ops::{Add, AddAssign, Mul};

/// An RGB colour or reflectance with channels in 0–1 (lighting may exceed 1).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Rgb {
    /// Red.
    pub r: f32,
    /// Green.
    pub g: f32,
    /// Blue.
    pub b: f32,
}

impl Rgb {
    /// Black.
    pub const BLACK: Rgb = Rgb::new(0.0, 0.0, 0.0);
    /// White.
    pub const WHITE: Rgb = Rgb::new(1.0, 1.0, 1.0);

    /// A colour from its three channels.
    pub const fn new(r: f32, g: f32, b: f32) -> Rgb {
        Rgb { r, g, b }
    }

    /// The same value in all three channels.
    pub const fn splat(v: f32) -> Rgb {
        Rgb::new(v, v, v)
    }

    /// Each channel clamped to 0–1.
    pub fn clamped(self) -> Rgb {
        Rgb::new(
            self.r.clamp(0.0, 1.0),
            self.g.clamp(0.0, 1.0),
            self.b.clamp(0.0, 1.0),
        )
    }

    /// The channels as an array.
    pub const fn to_array(self) -> [f32; 3] {
        [self.r, self.g, self.b]
    }

    /// A colour from an array of channels.
    pub const fn from_array(c: [f32; 3]) -> Rgb {
        Rgb::new(c[0], c[1], c[2])
    }
}

impl Add for Rgb {
    type Output = Rgb;
    fn add(self, o: Rgb) -> Rgb {
        Rgb::new(self.r + o.r, self.g + o.g, self.b + o.b)
    }
}

impl AddAssign for Rgb {
    fn add_assign(&mut self, o: Rgb) {
        *self = *self + o;
    }
}

/// Channel by channel product (light times reflectance).
impl Mul for Rgb {
    type Output = Rgb;
    fn mul(self, o: Rgb) -> Rgb {
        Rgb::new(self.r * o.r, self.g * o.g, self.b * o.b)
    }
}

impl Mul<f32> for Rgb {
    type Output = Rgb;
    fn mul(self, s: f32) -> Rgb {
        Rgb::new(self.r * s, self.g * s, self.b * s)
    }
}

/// An 8-bit RGB pixel, channels 0–255.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash, bytemuck::Pod, bytemuck::Zeroable)]
#[repr(transparent)]
pub struct Rgb8(pub [u8; 3]);

impl Rgb8 {
    /// A pixel from its three channels.
    pub const fn new(r: u8, g: u8, b: u8) -> Rgb8 {
        Rgb8([r, g, b])
    }

    /// `round(clamp(c, 0, 1) · 255)` per channel: the project's one conversion
    /// from light to pixel. NaN becomes 0.
    pub fn from_rgb(c: Rgb) -> Rgb8 {
        fn q(v: f32) -> u8 {
            // `as u8` saturates and maps NaN to 0.
            (v.clamp(0.0, 1.0) * 255.0).round() as u8
        }
        Rgb8([q(c.r), q(c.g), q(c.b)])
    }

    /// The 0–255 channels scaled to 0–1.
    pub fn to_rgb(self) -> Rgb {
        let [r, g, b] = self.0;
        Rgb::new(r as f32 / 255.0, g as f32 / 255.0, b as f32 / 255.0)
    }
}
