//! PNG images: 8-bit RGB out, and back in for tests and comparisons.

use std::io::Write;
use std::path::Path;

use shadelab_core::{Image, Rgb8};

/// Writes `image` as an 8-bit RGB PNG file through [`crate::write_atomic`]:
/// whole or not at all, never through a link or over anything but a regular
/// file; `-` is standard output.
///
/// # Errors
/// As [`crate::write_atomic`], and the encoding error.
pub fn write_png(path: &Path, image: &Image) -> std::io::Result<()> {
    write_png_with(path, image, PngCompression::Default)
}

/// How hard the PNG encoder compresses: a trade of file size for time.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum PngCompression {
    /// zlib's default level: the smallest files, for single images.
    #[default]
    Default,
    /// A fast deflate (`fdeflate`) with the Up filter: several times quicker
    /// to encode and larger, for rendering many images.
    Fast,
}

/// [`write_png`] with a chosen compression.
///
/// # Errors
/// As [`write_png`].
pub fn write_png_with(
    path: &Path,
    image: &Image,
    compression: PngCompression,
) -> std::io::Result<()> {
    crate::write_atomic(path, |mut out| {
        encode_png_with(&mut out, image, compression)
    })
}

/// Encodes `image` as PNG into `out`.
///
/// # Errors
/// The I/O error as it came (a full disk stays `StorageFull`, a closed pipe
/// `BrokenPipe`), or the encoding error.
pub fn encode_png(out: &mut impl Write, image: &Image) -> std::io::Result<()> {
    encode_png_with(out, image, PngCompression::Default)
}

/// [`encode_png`] with a chosen compression.
///
/// # Errors
/// The I/O or encoding error.
pub fn encode_png_with(
    out: &mut impl Write,
    image: &Image,
    compression: PngCompression,
) -> std::io::Result<()> {
    let mut encoder = png::Encoder::new(out, image.width(), image.height());
    if compression == PngCompression::Fast {
        encoder.set_compression(png::Compression::Fast);
        encoder.set_filter(png::FilterType::Up);
    }
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header().map_err(io_error)?;
    writer
        .write_image_data(&image.to_rgb_bytes())
        .map_err(io_error)?;
    writer.finish().map_err(io_error)
}

/// The I/O error inside an encoding error, or the encoding error as one.
fn io_error(e: png::EncodingError) -> std::io::Error {
    match e {
        png::EncodingError::IoError(e) => e,
        other => std::io::Error::other(other),
    }
}

/// Reads an 8-bit RGB or RGBA PNG (alpha is dropped).
///
/// # Errors
/// The I/O or decoding error, or an unsupported pixel format.
pub fn read_png(path: &Path) -> std::io::Result<Image> {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path)?));
    let mut reader = decoder.read_info().map_err(std::io::Error::other)?;
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).map_err(std::io::Error::other)?;
    let channels = match (info.color_type, info.bit_depth) {
        (png::ColorType::Rgb, png::BitDepth::Eight) => 3,
        (png::ColorType::Rgba, png::BitDepth::Eight) => 4,
        other => {
            return Err(std::io::Error::other(format!(
                "unsupported PNG pixel format {other:?}"
            )));
        }
    };
    let mut image = Image::filled(info.width, info.height, Rgb8::default());
    for y in 0..info.height {
        for x in 0..info.width {
            let at = y as usize * info.line_size + x as usize * channels;
            image.set_pixel(x, y, Rgb8::new(buf[at], buf[at + 1], buf[at + 2]));
        }
    }
    Ok(image)
}
