//! Text labels drawn into images with an 8×8 bitmap font (ASCII only).

use font8x8::legacy::BASIC_LEGACY;
use shadelab_core::{Image, Rgb8};

/// Width in pixels of `text` drawn at `scale`.
pub fn text_width(text: &str, scale: u32) -> u32 {
    text.chars().count() as u32 * 8 * scale
}

/// Draws `text` with its top-left corner at (`x`, `y`), each font pixel a
/// `scale` × `scale` square; characters outside ASCII are drawn as `?`.
pub fn draw_text(image: &mut Image, text: &str, x: u32, y: u32, scale: u32, color: Rgb8) {
    for (k, ch) in text.chars().enumerate() {
        let code = if ch.is_ascii() {
            ch as usize
        } else {
            '?' as usize
        };
        let glyph = BASIC_LEGACY[code];
        let left = x + k as u32 * 8 * scale;
        for (row, bits) in glyph.iter().enumerate() {
            for col in 0..8 {
                if bits & (1 << col) != 0 {
                    for dy in 0..scale {
                        for dx in 0..scale {
                            image.set_pixel(
                                left + col * scale + dx,
                                y + row as u32 * scale + dy,
                                color,
                            );
                        }
                    }
                }
            }
        }
    }
}
