//! An RGB image in memory, row 0 at the top.

use crate::color::Rgb8;

/// An 8-bit RGB image, rows top to bottom, pixels left to right.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Image {
    width: u32,
    height: u32,
    pixels: Vec<Rgb8>,
}

impl Image {
    /// An image filled with one colour.
    ///
    /// # Panics
    /// If `width · height` does not fit in memory addressing (`usize`).
    pub fn filled(width: u32, height: u32, color: Rgb8) -> Image {
        let count = (width as usize)
            .checked_mul(height as usize)
            .expect("image size overflows usize");
        Image {
            width,
            height,
            pixels: vec![color; count],
        }
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The pixel at column `x`, row `y`.
    ///
    /// # Panics
    /// If (`x`, `y`) is outside the image.
    pub fn pixel(&self, x: u32, y: u32) -> Rgb8 {
        assert!(
            x < self.width && y < self.height,
            "pixel ({x}, {y}) outside the image"
        );
        self.pixels[(y * self.width + x) as usize]
    }

    /// Sets the pixel at column `x`, row `y`; outside the image does nothing.
    pub fn set_pixel(&mut self, x: u32, y: u32, color: Rgb8) {
        if x < self.width && y < self.height {
            self.pixels[(y as usize) * self.width as usize + x as usize] = color;
        }
    }

    /// All pixels, row by row.
    pub fn pixels(&self) -> &[Rgb8] {
        &self.pixels
    }

    /// All pixels, row by row, for writing.
    pub(crate) fn pixels_mut(&mut self) -> &mut [Rgb8] {
        &mut self.pixels
    }

    /// The pixels as packed RGB bytes, as PNG encoders take them.
    pub fn to_rgb_bytes(&self) -> Vec<u8> {
        self.pixels.iter().flat_map(|p| p.0).collect()
    }

    /// Copies `src` into this image with its top-left corner at (`x`, `y`),
    /// dropping what falls outside.
    pub fn blit(&mut self, src: &Image, x: u32, y: u32) {
        for sy in 0..src.height {
            for sx in 0..src.width {
                self.set_pixel(x + sx, y + sy, src.pixel(sx, sy));
            }
        }
    }
}
