//! Plots and captions drawn with `plotters` into RGB buffers, labelled with
//! the embedded DejaVu Sans, so they look the same on any machine, with no
//! system fonts, and write Cyrillic as well as Latin.

use plotters::prelude::*;
use plotters::style::{register_font, FontStyle};
use shadelab_core::{Image, Rgb8};

/// The family name the embedded font is registered under.
pub const FONT: &str = "sans-serif";

static FONT_BYTES: &[u8] = include_bytes!("../assets/fonts/DejaVuSans.ttf");

/// Registers the embedded font (once).
pub fn init_font() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        if register_font(FONT, FontStyle::Normal, FONT_BYTES).is_err() {
            unreachable!("the embedded DejaVu Sans is a valid font");
        }
    });
}

/// The colour of each curve: flat, Gouraud, Phong, exact.
pub const CURVE_COLORS: [RGBColor; 4] = [
    RGBColor(230, 120, 20),
    RGBColor(40, 110, 220),
    RGBColor(30, 160, 60),
    RGBColor(20, 20, 20),
];

/// Packed RGB bytes of an image, as plotters' bitmap backend takes them.
pub fn to_buffer(image: &Image) -> Vec<u8> {
    image.to_rgb_bytes()
}

/// An image from packed RGB bytes.
pub fn from_buffer(bytes: &[u8], width: u32, height: u32) -> Image {
    let mut image = Image::filled(width, height, Rgb8::default());
    for (k, px) in bytes.chunks_exact(3).enumerate() {
        let k = k as u32;
        image.set_pixel(k % width, k / width, Rgb8::new(px[0], px[1], px[2]));
    }
    image
}

/// Runs `draw` on a drawing area over `image` and returns the result.
///
/// # Errors
/// What `draw` or the backend reports.
pub fn draw_on(
    image: &Image,
    draw: impl FnOnce(&DrawingArea<BitMapBackend<'_>, plotters::coord::Shift>) -> anyhow::Result<()>,
) -> anyhow::Result<Image> {
    init_font();
    let (w, h) = (image.width(), image.height());
    let mut bytes = to_buffer(image);
    {
        let root = BitMapBackend::with_buffer(&mut bytes, (w, h)).into_drawing_area();
        draw(&root)?;
        root.present()
            .map_err(|e| anyhow::anyhow!("drawing: {e}"))?;
    }
    Ok(from_buffer(&bytes, w, h))
}

/// Converts a plotters error into ours.
pub fn err<E: std::fmt::Display>(e: E) -> anyhow::Error {
    anyhow::anyhow!("drawing: {e}")
}

/// A text style of the embedded font.
pub fn font(size: f64, color: RGBColor) -> TextStyle<'static> {
    (FONT, size).into_font().color(&color)
}
