//! The teaching subcommands end to end: the real binary in a temporary
//! directory, its text and its pictures read back.

mod support;

use support::*;

use std::collections::BTreeSet;
use std::path::Path;

/// (width, height, RGB bytes) of a PNG.
fn png(path: &Path) -> (u32, u32, Vec<u8>) {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    buf.truncate(info.buffer_size());
    (info.width, info.height, buf)
}

fn colours(rgb: &[u8]) -> BTreeSet<[u8; 3]> {
    rgb.chunks(3).map(|p| [p[0], p[1], p[2]]).collect()
}

#[test]
fn explain_prints_the_formulas_with_the_numbers() {
    let dir = tempfile::tempdir().unwrap();
    let args = [
        "explain",
        "--model",
        "sphere",
        "--detail",
        "8",
        "--size",
        "120x100",
        "--pixel",
        "60,40",
        "--interpolation",
        "screen",
        "--polygons",
        "whole",
    ];
    let out = run(dir.path(), &args);
    assert_ok(&out);
    let text = stdout(&out);
    for needle in [
        "Pixel (60, 40)",
        "== Flat shading",
        "== Gouraud shading",
        "== Phong shading",
        "I_O = (1 − u)·I_P + u·I_Q",
        "N_O = (1 − u)·N_P + u·N_Q",
        "u = |PO| / |PQ|",
        "Final colour",
    ] {
        assert!(text.contains(needle), "{needle:?} missing:\n{text}");
    }
    // The colour it reports is the pixel `render` draws.
    let out = run(
        dir.path(),
        &[
            "render",
            "--model",
            "sphere",
            "--detail",
            "8",
            "--size",
            "120x100",
            "--interpolation",
            "screen",
            "--polygons",
            "whole",
            "--shading",
            "gouraud",
            "-o",
            "g.png",
        ],
    );
    assert_ok(&out);
    let (w, _, rgb) = png(&dir.path().join("g.png"));
    let at = ((40 * w + 60) * 3) as usize;
    let colour = format!("gives ({}, {}, {})", rgb[at], rgb[at + 1], rgb[at + 2]);
    let gouraud = text
        .split("== Gouraud")
        .nth(1)
        .unwrap()
        .split("==")
        .next()
        .unwrap();
    assert!(gouraud.contains(&colour), "{colour} not in:\n{gouraud}");

    let out = run(
        dir.path(),
        &[
            "explain",
            "--model",
            "sphere",
            "--pixel",
            "200,200",
            "--lang",
            "ru",
            "--shading",
            "gouraud",
        ],
    );
    assert_ok(&out);
    let text = stdout(&out);
    assert!(
        text.contains("Закраска по Гуро") && !text.contains("Фонгу"),
        "{text}"
    );
    for lang in ["sk", "cs"] {
        let out = run(
            dir.path(),
            &[
                "explain", "--model", "torus", "--pixel", "240,240", "--lang", lang,
            ],
        );
        assert_ok(&out);
        assert!(stdout(&out).contains("Gouraudovo"), "{lang}");
    }
    assert_fails(
        &run(dir.path(), &["explain", "--pixel", "480,3"]),
        2,
        &["outside the 480x480 image"],
    );
    assert_fails(
        &run(dir.path(), &["explain", "--pixel", "3"]),
        2,
        &["pixel"],
    );
}

#[test]
fn profile_writes_a_plot_and_reports_the_edges() {
    let dir = tempfile::tempdir().unwrap();
    let out = run(
        dir.path(),
        &[
            "profile", "--model", "sphere", "--detail", "10", "--size", "200x160", "--row", "70",
            "-o", "p.png", "--table",
        ],
    );
    assert_ok(&out);
    let text = stdout(&out);
    assert!(
        text.contains("Exact surface") && text.contains("polygon edges crossed"),
        "{text}"
    );
    // One line per pixel of the row in the table.
    assert!(
        text.lines()
            .filter(|l| l.split('\t').nth(1) == Some("70"))
            .count()
            == 200,
        "{text}"
    );
    let (w, h, rgb) = png(&dir.path().join("p.png"));
    assert_eq!((w, h), (1300, 720));
    let c = colours(&rgb);
    // White paper, black text, and the four curves' colours.
    for curve in [[230, 120, 20], [40, 110, 220], [30, 160, 60]] {
        assert!(c.contains(&curve), "curve colour {curve:?} missing");
    }
    // A line across the image, and a model without an exact surface.
    assert_ok(&run(
        dir.path(),
        &[
            "profile",
            "--model",
            "teapot",
            "--size",
            "160x120",
            "--line",
            "0,0,159,119",
            "-o",
            "l.png",
        ],
    ));
    assert_fails(
        &run(
            dir.path(),
            &[
                "profile", "--size", "100x100", "--row", "100", "-o", "x.png",
            ],
        ),
        2,
        &["outside"],
    );
}

#[test]
fn errors_writes_heat_maps_and_ranks_the_methods() {
    let dir = tempfile::tempdir().unwrap();
    let out = run(
        dir.path(),
        &[
            "errors", "--model", "sphere", "--detail", "12", "--size", "160x160", "-o", "e.png",
        ],
    );
    assert_ok(&out);
    let text = stdout(&out);
    let mean = |method: &str| -> f64 {
        let line = text.lines().find(|l| l.starts_with(method)).unwrap();
        line.split_whitespace().nth(1).unwrap().parse().unwrap()
    };
    assert!(
        mean("Phong") < mean("Gouraud") && mean("Gouraud") < mean("Flat"),
        "{text}"
    );
    let (w, h, _) = png(&dir.path().join("e.png"));
    assert_eq!((w, h), (4 * 160 + 3 * 6 + 90, 34 + 160 + 30));
    assert_fails(
        &run(dir.path(), &["errors", "--model", "teapot", "-o", "t.png"]),
        2,
        &["no exact surface"],
    );
    assert_fails(
        &run(dir.path(), &["errors", "--scale", "-1", "-o", "t.png"]),
        2,
        &["--scale must be a positive number"],
    );
    assert!(!dir.path().join("t.png").exists());
}

#[test]
fn accuracy_prints_a_table_and_plots_it() {
    let dir = tempfile::tempdir().unwrap();
    let out = run(
        dir.path(),
        &[
            "accuracy",
            "--model",
            "torus",
            "--details",
            "8,16,32",
            "--size",
            "120x120",
            "-o",
            "a.png",
        ],
    );
    assert_ok(&out);
    let text = stdout(&out);
    let rows: Vec<&str> = text
        .lines()
        .filter(|l| l.trim_start().starts_with(char::is_numeric))
        .collect();
    assert_eq!(rows.len(), 3, "{text}");
    let (w, h, _) = png(&dir.path().join("a.png"));
    assert_eq!((w, h), (820, 560));
    assert_fails(
        &run(dir.path(), &["accuracy", "--model", "cube"]),
        2,
        &["no exact surface"],
    );
}

#[test]
fn quad_and_cost() {
    let dir = tempfile::tempdir().unwrap();
    let out = run(
        dir.path(),
        &["quad", "-o", "q.png", "--angles", "0,45", "--size", "61"],
    );
    assert_ok(&out);
    let text = stdout(&out);
    assert!(text.contains("0.2500") && text.contains("0.5000"), "{text}");
    assert!(dir.path().join("q.png").exists());
    let out = run(
        dir.path(),
        &[
            "cost", "--model", "teapot", "--size", "160x120", "--runs", "2",
        ],
    );
    assert_ok(&out);
    let text = stdout(&out);
    for m in ["Flat", "Gouraud", "Phong", "per vertex"] {
        assert!(text.contains(m), "{text}");
    }
}

#[test]
fn overlays_draw_on_render_and_compare() {
    let dir = tempfile::tempdir().unwrap();
    let base = [
        "--model", "cube", "--size", "120x120", "--yaw", "30", "--pitch", "20",
    ];
    let plain: Vec<&str> = ["render", "-o", "plain.png"]
        .iter()
        .chain(&base)
        .copied()
        .collect();
    assert_ok(&run(dir.path(), &plain));
    let wire: Vec<&str> = ["render", "-o", "wire.png", "--overlay", "wireframe,light"]
        .iter()
        .chain(&base)
        .copied()
        .collect();
    assert_ok(&run(dir.path(), &wire));
    let (_, _, a) = png(&dir.path().join("plain.png"));
    let (_, _, b) = png(&dir.path().join("wire.png"));
    let wire_pixels = b.chunks(3).filter(|p| *p == [255, 230, 90]).count();
    assert!(wire_pixels > 150, "{wire_pixels} wireframe pixels");
    assert!(!colours(&a).contains(&[255, 230, 90]));
    let cmp: Vec<&str> = ["compare", "-o", "c.png", "--overlay", "all"]
        .iter()
        .chain(&base)
        .copied()
        .collect();
    assert_ok(&run(dir.path(), &cmp));
    assert_fails(
        &run(dir.path(), &["render", "-o", "x.png", "--overlay", "grid"]),
        2,
        &["unknown overlay"],
    );
}

#[test]
fn palette_and_fixed_point_flags_and_scene_keys() {
    let dir = tempfile::tempdir().unwrap();
    let out = run(
        dir.path(),
        &[
            "render",
            "--model",
            "sphere",
            "--size",
            "100x100",
            "--shading",
            "gouraud",
            "--palette",
            "6",
            "--palette-offset",
            "10",
            "--ambient-intensity",
            "0",
            "-o",
            "p.png",
        ],
    );
    assert_ok(&out);
    let (_, _, rgb) = png(&dir.path().join("p.png"));
    let mut c = colours(&rgb);
    c.remove(&[0, 0, 0]);
    // Six shades of the default material colour; the darkest is black, like the background.
    assert_eq!(c.len(), 5, "{c:?}");
    assert_fails(
        &run(
            dir.path(),
            &[
                "render",
                "--palette",
                "6",
                "--rasterizer",
                "tiled",
                "-o",
                "x.png",
            ],
        ),
        2,
        &["render.palette_shades"],
    );
    assert_fails(
        &run(
            dir.path(),
            &["render", "--fixed-point", "40", "-o", "x.png"],
        ),
        2,
        &["--fixed-point <BITS>': render.fixed_point_bits: must be 1..=30 bits, got 40"],
    );
    assert_fails(
        &run(
            dir.path(),
            &[
                "render",
                "--palette",
                "200",
                "--palette-offset",
                "100",
                "-o",
                "x.png",
            ],
        ),
        2,
        &["palette"],
    );
    std::fs::write(
        dir.path().join("s.toml"),
        "[model]\nsource = \"sphere\"\n[render]\nwidth = 80\nheight = 80\nfixed_point_bits = 3\nshading = \"gouraud\"\n",
    )
    .unwrap();
    assert_ok(&run(dir.path(), &["render", "s.toml", "-o", "f.png"]));
    assert_ok(&run(
        dir.path(),
        &["render", "s.toml", "--fixed-point", "24", "-o", "g.png"],
    ));
    let (_, _, f) = png(&dir.path().join("f.png"));
    let (_, _, g) = png(&dir.path().join("g.png"));
    let worst = f.iter().zip(&g).map(|(a, b)| a.abs_diff(*b)).max().unwrap();
    assert!(worst >= 8, "3 fraction bits should show: {worst}");
}
