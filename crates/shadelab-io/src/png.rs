//! PNG images: 8-bit RGB out, and back in for tests and comparisons.

use std::io::{BufWriter, Write};
use std::path::Path;

use shadelab_core::{Image, Rgb8};

/// Writes `image` as an 8-bit RGB PNG.
///
/// The image goes to a temporary file beside `path` that is renamed over it
/// only when complete, so a failed or interrupted write never leaves a
/// truncated image.
///
/// # Errors
/// The I/O or encoding error.
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
/// The I/O or encoding error.
pub fn write_png_with(
    path: &Path,
    image: &Image,
    compression: PngCompression,
) -> std::io::Result<()> {
    let dir = path
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let file_name = path.file_name().ok_or_else(|| {
        std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            "the output path names no file",
        )
    })?;
    let temp = dir.join(format!(
        ".{}.{}.tmp",
        file_name.to_string_lossy(),
        std::process::id()
    ));
    let result = (|| {
        let file = std::fs::File::create(&temp)?;
        let mut writer = BufWriter::new(file);
        encode_png_with(&mut writer, image, compression)?;
        let file = writer.into_inner().map_err(|e| e.into_error())?;
        file.sync_all()?;
        std::fs::rename(&temp, path)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&temp);
    }
    result
}

/// Encodes `image` as PNG into `out`.
///
/// # Errors
/// The I/O or encoding error.
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
    let mut writer = encoder.write_header().map_err(std::io::Error::other)?;
    writer
        .write_image_data(&image.to_rgb_bytes())
        .map_err(std::io::Error::other)?;
    writer.finish().map_err(std::io::Error::other)
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
