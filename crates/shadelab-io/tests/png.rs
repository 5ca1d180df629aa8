//! PNG output: exact round trips and atomic writes.

use std::path::Path;

use shadelab_core::{Image, Rgb8};
use shadelab_io::{encode_png, read_png, write_png};

/// An image where every pixel differs from its neighbours.
fn pattern(width: u32, height: u32) -> Image {
    let mut image = Image::filled(width, height, Rgb8::default());
    for y in 0..height {
        for x in 0..width {
            image.set_pixel(
                x,
                y,
                Rgb8::new(
                    (x * 37 + y * 11) as u8,
                    (x * 5 + y * 97 + 3) as u8,
                    (x ^ y).wrapping_mul(29) as u8,
                ),
            );
        }
    }
    image
}

/// Names of the entries in `dir`.
fn entries(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[test]
fn write_then_read_is_identical() {
    let dir = tempfile::tempdir().unwrap();
    for (w, h) in [(1, 1), (7, 3), (64, 48), (3, 200)] {
        let image = pattern(w, h);
        let path = dir.path().join(format!("p{w}x{h}.png"));
        write_png(&path, &image).unwrap();
        let back = read_png(&path).unwrap();
        assert_eq!((back.width(), back.height()), (w, h));
        assert_eq!(back, image, "{w}x{h}");
    }
}

#[test]
fn written_file_is_an_8_bit_rgb_png() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("out.png");
    let image = pattern(5, 4);
    write_png(&path, &image).unwrap();
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(&path).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!(info.color_type, png::ColorType::Rgb);
    assert_eq!(info.bit_depth, png::BitDepth::Eight);
    assert_eq!((info.width, info.height), (5, 4));
    assert_eq!(&buf[..info.buffer_size()], &image.to_rgb_bytes()[..]);
}

#[test]
fn encode_png_matches_the_written_file() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("out.png");
    let image = pattern(9, 6);
    write_png(&path, &image).unwrap();
    let mut bytes = Vec::new();
    encode_png(&mut bytes, &image).unwrap();
    assert_eq!(std::fs::read(&path).unwrap(), bytes);
    assert!(bytes.starts_with(b"\x89PNG\r\n\x1a\n"));
}

#[test]
fn writing_into_a_missing_directory_fails_and_leaves_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("no").join("such");
    let path = missing.join("out.png");
    let err = write_png(&path, &pattern(4, 4)).expect_err("missing directory");
    assert_eq!(err.kind(), std::io::ErrorKind::NotFound, "{err}");
    assert!(!path.exists());
    assert!(!missing.exists());
    assert!(entries(dir.path()).is_empty(), "{:?}", entries(dir.path()));
}

#[test]
fn failed_write_leaves_no_temporary_file() {
    // The target is an existing directory: the temporary file is written,
    // the rename fails, and the temporary file must be removed.
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("taken.png");
    std::fs::create_dir(&target).unwrap();
    std::fs::write(target.join("keep"), b"x").unwrap();
    write_png(&target, &pattern(4, 4)).expect_err("cannot replace a directory");
    assert_eq!(entries(dir.path()), vec!["taken.png".to_owned()]);
    assert!(target.is_dir());
}

#[test]
fn no_temporary_file_is_left_after_success() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("out.png");
    write_png(&path, &pattern(8, 8)).unwrap();
    assert_eq!(entries(dir.path()), vec!["out.png".to_owned()]);
}

#[test]
fn an_existing_file_is_replaced() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("out.png");
    std::fs::write(&path, b"not a png at all, and longer than nothing").unwrap();
    let image = pattern(6, 2);
    write_png(&path, &image).unwrap();
    assert_eq!(read_png(&path).unwrap(), image);
    // And again, with a different image of a different size.
    let second = Image::filled(3, 3, Rgb8::new(1, 2, 3));
    write_png(&path, &second).unwrap();
    assert_eq!(read_png(&path).unwrap(), second);
    assert_eq!(entries(dir.path()), vec!["out.png".to_owned()]);
}

#[test]
fn a_path_naming_no_file_is_rejected() {
    let dir = tempfile::tempdir().unwrap();
    let err = write_png(&dir.path().join(".."), &pattern(2, 2)).expect_err("no file name");
    assert_eq!(err.kind(), std::io::ErrorKind::InvalidInput);
}

#[test]
fn read_png_accepts_rgba_and_drops_alpha() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("rgba.png");
    {
        let file = std::io::BufWriter::new(std::fs::File::create(&path).unwrap());
        let mut encoder = png::Encoder::new(file, 2, 1);
        encoder.set_color(png::ColorType::Rgba);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder.write_header().unwrap();
        writer
            .write_image_data(&[10, 20, 30, 0, 40, 50, 60, 255])
            .unwrap();
    }
    let image = read_png(&path).unwrap();
    assert_eq!(image.pixel(0, 0), Rgb8::new(10, 20, 30));
    assert_eq!(image.pixel(1, 0), Rgb8::new(40, 50, 60));
}

#[test]
fn read_png_rejects_other_formats_and_garbage() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("gray.png");
    {
        let file = std::io::BufWriter::new(std::fs::File::create(&path).unwrap());
        let mut encoder = png::Encoder::new(file, 2, 2);
        encoder.set_color(png::ColorType::Grayscale);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder.write_header().unwrap();
        writer.write_image_data(&[0, 1, 2, 3]).unwrap();
    }
    let err = read_png(&path).expect_err("grayscale");
    assert!(err.to_string().contains("unsupported"), "{err}");

    let garbage = dir.path().join("garbage.png");
    std::fs::write(&garbage, b"hello").unwrap();
    read_png(&garbage).expect_err("not a PNG");
    read_png(&dir.path().join("absent.png")).expect_err("missing");
}
