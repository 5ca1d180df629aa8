//! `shadelab compare --orbit N`: one full orbit of the camera as an animated
//! PNG, and `--lang` on the commands that print prose. Each test runs the
//! real binary in a fresh temporary directory.

mod support;

use support::*;

use std::path::Path;
use std::process::{Command, Output};

/// An animated PNG's frames, decoded: (width, height, frames as RGB, delay of each in ms).
struct Apng {
    width: u32,
    height: u32,
    plays: u32,
    frames: Vec<Vec<u8>>,
    delays: Vec<f64>,
}

fn read_apng(path: &Path) -> Apng {
    let file = std::fs::File::open(path).expect("the file was written");
    let mut reader = png::Decoder::new(std::io::BufReader::new(file))
        .read_info()
        .expect("a PNG header");
    let info = reader.info();
    let (width, height) = (info.width, info.height);
    let control = info
        .animation_control
        .expect("an acTL chunk: the PNG is animated");
    let mut frames = Vec::new();
    let mut delays = Vec::new();
    for _ in 0..control.num_frames {
        let mut buf = vec![0; reader.output_buffer_size()];
        let out = reader.next_frame(&mut buf).expect("every frame decodes");
        assert_eq!(out.color_type, png::ColorType::Rgb);
        let fc = reader.info().frame_control.expect("an fcTL per frame");
        assert_eq!(
            (fc.width, fc.height, fc.x_offset, fc.y_offset),
            (width, height, 0, 0),
            "every frame is whole"
        );
        delays.push(1000.0 * f64::from(fc.delay_num) / f64::from(fc.delay_den));
        buf.truncate(out.buffer_size());
        frames.push(buf);
    }
    Apng {
        width,
        height,
        plays: control.num_plays,
        frames,
        delays,
    }
}

fn read_png(path: &Path) -> (u32, u32, Vec<u8>) {
    let file = std::fs::File::open(path).expect("the file was written");
    let mut reader = png::Decoder::new(std::io::BufReader::new(file))
        .read_info()
        .expect("a PNG header");
    let mut buf = vec![0; reader.output_buffer_size()];
    let out = reader.next_frame(&mut buf).expect("a frame");
    buf.truncate(out.buffer_size());
    (out.width, out.height, buf)
}

#[test]
fn an_orbit_is_an_animated_png_of_the_compare_sheets_at_each_turn() {
    let dir = tempfile::tempdir().unwrap();
    let out = run(
        dir.path(),
        &[
            "compare",
            "--model",
            "cube",
            "--size",
            "64x48",
            "--pitch",
            "20",
            "--orbit",
            "8",
            "--delay",
            "50",
            "-o",
            "orbit.apng",
        ],
    );
    assert_ok(&out);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("wrote 8 frames of 200x76 pixels, 50 ms each"),
        "{stderr}"
    );
    let apng = read_apng(&dir.path().join("orbit.apng"));
    // Three 64-pixel panels, two 4-pixel gaps; a 28-pixel label band over 48 rows.
    assert_eq!((apng.width, apng.height), (3 * 64 + 2 * 4, 28 + 48));
    assert_eq!(apng.frames.len(), 8);
    assert_eq!(apng.plays, 0, "it loops");
    assert!(
        apng.delays.iter().all(|&d| (d - 50.0).abs() < 1e-9),
        "{:?}",
        apng.delays
    );
    // Frame k is `compare` at yaw 360·k/8: the same sheet, pixel for pixel.
    for (k, yaw) in [(0, "0"), (1, "45"), (3, "135"), (7, "315")] {
        let png = format!("still-{k}.png");
        assert_ok(&run(
            dir.path(),
            &[
                "compare", "--model", "cube", "--size", "64x48", "--pitch", "20", "--yaw", yaw,
                "-o", &png,
            ],
        ));
        let (w, h, rgb) = read_png(&dir.path().join(&png));
        assert_eq!((w, h), (apng.width, apng.height));
        assert!(rgb == apng.frames[k], "frame {k} is the sheet at yaw {yaw}");
    }
    // The camera turns: each frame is another picture.
    for k in 1..8 {
        assert_ne!(apng.frames[0], apng.frames[k], "frame {k}");
    }
}

#[test]
fn an_orbit_starts_from_the_scene_yaw_and_keeps_its_other_settings() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("scene.toml"),
        "[model]\nsource = \"torus\"\n[render]\nwidth = 40\nheight = 40\nyaw = 30.0\nbackground = [0, 0, 90]\n",
    )
    .unwrap();
    assert_ok(&run(
        dir.path(),
        &["compare", "scene.toml", "--orbit", "4", "-o", "t.png"],
    ));
    assert_ok(&run(
        dir.path(),
        &["compare", "scene.toml", "-o", "still.png"],
    ));
    let apng = read_apng(&dir.path().join("t.png"));
    assert_eq!((apng.width, apng.height, apng.frames.len()), (128, 68, 4));
    let (_, _, still) = read_png(&dir.path().join("still.png"));
    assert!(
        apng.frames[0] == still,
        "the first frame is the scene as it is"
    );
    assert!(
        apng.frames
            .iter()
            .all(|f| f.chunks(3).any(|p| p == [0, 0, 90])),
        "the background stays"
    );
}

#[test]
fn an_orbit_refuses_other_formats_and_bad_counts_and_leaves_files_alone() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("keep.webp"), b"mine").unwrap();
    let out = run(
        dir.path(),
        &[
            "compare",
            "--size",
            "32x32",
            "--orbit",
            "4",
            "-o",
            "keep.webp",
        ],
    );
    assert_fails(&out, 2, &["animated WebP is not supported"]);
    assert_fails(&out, 2, &["keep.apng"]);
    assert_eq!(
        std::fs::read(dir.path().join("keep.webp")).unwrap(),
        b"mine"
    );
    assert_fails(
        &run(
            dir.path(),
            &["compare", "--size", "32x32", "--orbit", "4", "-o", "a.gif"],
        ),
        2,
        &["name the file .apng"],
    );
    assert_fails(
        &run(
            dir.path(),
            &["compare", "--size", "32x32", "--orbit", "0", "-o", "a.apng"],
        ),
        2,
        &["--orbit must be 1..=720"],
    );
    assert_fails(
        &run(
            dir.path(),
            &[
                "compare", "--size", "32x32", "--orbit", "2", "--delay", "0", "-o", "a.apng",
            ],
        ),
        2,
        &["--delay must be at least 1 ms"],
    );
    // `--delay` means nothing without an orbit.
    let out = run(
        dir.path(),
        &["compare", "--size", "32x32", "--delay", "40", "-o", "a.png"],
    );
    assert_eq!(out.status.code(), Some(2));
    // A directory in the way is not replaced.
    std::fs::create_dir(dir.path().join("d.apng")).unwrap();
    let out = run(
        dir.path(),
        &["compare", "--size", "32x32", "--orbit", "2", "-o", "d.apng"],
    );
    assert_fails(&out, 1, &["not a regular file"]);
    assert!(dir.path().join("d.apng").is_dir());
    // Nothing is left behind: no temporary file, no partial output.
    let left: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert!(
        left.iter().all(|n| n == "keep.webp" || n == "d.apng"),
        "{left:?}"
    );
}

#[test]
fn every_command_that_prints_prose_takes_lang() {
    let dir = tempfile::tempdir().unwrap();
    let stdout = |out: &Output| String::from_utf8_lossy(&out.stdout).into_owned();
    let stderr = |out: &Output| String::from_utf8_lossy(&out.stderr).into_owned();

    let out = run(
        dir.path(),
        &[
            "quad", "--lang", "ru", "--angles", "0,45", "--size", "31", "-o", "q.png",
        ],
    );
    assert_ok(&out);
    assert!(stdout(&out).contains("центр, целиком"), "{}", stdout(&out));

    let out = run(
        dir.path(),
        &[
            "compare", "--lang", "ru", "--model", "cube", "--size", "48x48", "-o", "c.png",
        ],
    );
    assert_ok(&out);
    assert!(
        stderr(&out).contains("растеризовано многоугольников"),
        "{}",
        stderr(&out)
    );
    assert!(stderr(&out).starts_with("Плоская"), "{}", stderr(&out));
    // The labels are drawn in the language: not the English sheet.
    assert_ok(&run(
        dir.path(),
        &[
            "compare", "--model", "cube", "--size", "48x48", "-o", "e.png",
        ],
    ));
    let (_, _, ru) = read_png(&dir.path().join("c.png"));
    let (_, _, en) = read_png(&dir.path().join("e.png"));
    let band = 3 * 48 + 2 * 4;
    assert_ne!(
        ru[..28 * band * 3],
        en[..28 * band * 3],
        "the label band differs"
    );
    assert_eq!(
        ru[28 * band * 3..],
        en[28 * band * 3..],
        "the panels are the same"
    );

    let out = run(
        dir.path(),
        &[
            "render", "--lang", "cs", "--model", "cube", "--size", "32x32", "-o", "r.png",
        ],
    );
    assert_ok(&out);
    assert!(
        stderr(&out).contains("vystínované pixely"),
        "{}",
        stderr(&out)
    );

    let out = run(
        dir.path(),
        &[
            "cost", "--lang", "sk", "--model", "cube", "--size", "32x32", "--runs", "1",
        ],
    );
    assert_ok(&out);
    assert!(
        stdout(&out).contains("rasterizátor: dlaždicový"),
        "{}",
        stdout(&out)
    );
    assert!(stdout(&out).contains("Konštantné"), "{}", stdout(&out));

    let out = run(dir.path(), &["models", "--lang", "cs"]);
    assert_ok(&out);
    assert!(
        stdout(&out).contains("konvička z Utahu"),
        "{}",
        stdout(&out)
    );

    // English stays as it was, a polygon count never reads "1 polygons".
    let out = run(dir.path(), &["models"]);
    assert_ok(&out);
    assert!(stdout(&out).contains("the Utah teapot from Newell's 32 Bézier patches"));
    let out = run(
        dir.path(),
        &["cost", "--model", "cube", "--size", "32x32", "--runs", "3"],
    );
    assert!(
        stdout(&out).starts_with("32x32, tiled rasterizer, median of 3 runs"),
        "{}",
        stdout(&out)
    );
    std::fs::write(
        dir.path().join("one.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    )
    .unwrap();
    let out = run(
        dir.path(),
        &[
            "render", "--model", "one.obj", "--size", "16x16", "-o", "one.png",
        ],
    );
    assert_ok(&out);
    assert!(
        stderr(&out).contains("polygons rasterized: 1 "),
        "{}",
        stderr(&out)
    );
}

#[test]
fn view_takes_lang_for_its_messages_and_the_page() {
    use std::io::{BufRead, BufReader};
    let mut child = Command::new(env!("CARGO_BIN_EXE_shadelab"))
        .args(["view", "--port", "0", "--no-open", "--lang", "sk"])
        .stdout(std::process::Stdio::piped())
        .spawn()
        .expect("the server starts");
    let mut lines = BufReader::new(child.stdout.take().unwrap()).lines();
    let first = lines.next().unwrap().unwrap();
    let second = lines.next().unwrap().unwrap();
    child.kill().unwrap();
    child.wait().unwrap();
    // The address line keeps its form; the page opens in Slovak.
    assert!(
        first.starts_with("shadelab viewer: http://127.0.0.1:"),
        "{first}"
    );
    assert!(first.ends_with("/#lang=sk"), "{first}");
    assert_eq!(second, "Zastavíte ho klávesmi Ctrl+C.");
}
