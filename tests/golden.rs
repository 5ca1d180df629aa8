//! Golden images: a few scenes rendered and compared byte for byte with PNGs
//! under `tests/golden/`. They guard against unintended change; correctness
//! itself is proven against independent computations in the core's tests.
//!
//! After a deliberate change, regenerate them with
//! `BLESS=1 cargo test --release --test golden` and look at every new image.

use std::path::{Path, PathBuf};

use shadelab_core::{render, Image, Rasterizer, Rgb8};
use shadelab_io::{read_png, write_png, SceneFile};

/// (name, scene) pairs; every scene is small so the set stays quick.
const CASES: &[(&str, &str)] = &[
    ("sphere-flat", "[model]\nsource = \"sphere\"\n[render]\nwidth = 96\nheight = 96\nshading = \"flat\"\n"),
    ("sphere-gouraud", "[model]\nsource = \"sphere\"\n[render]\nwidth = 96\nheight = 96\nshading = \"gouraud\"\n"),
    ("sphere-phong", "[model]\nsource = \"sphere\"\n[render]\nwidth = 96\nheight = 96\nshading = \"phong\"\n"),
    (
        "teapot-phong",
        "[model]\nsource = \"teapot\"\n[render]\nwidth = 160\nheight = 120\nyaw = 30\npitch = 20\n",
    ),
    (
        "torus-gouraud-screen",
        "[model]\nsource = \"torus\"\n[render]\nwidth = 128\nheight = 96\nshading = \"gouraud\"\ninterpolation = \"screen\"\npitch = 35\n",
    ),
    (
        "cube-inside-no-cull",
        "[model]\nsource = \"cube\"\n[camera]\neye = [0.2, 0.1, 0.3]\ntarget = [1.0, 0.4, -1.0]\nfov_y = 90\nnear = 0.05\nfar = 10\n[[lights]]\nkind = \"point\"\nposition = [0.0, 0.5, 0.0]\n[render]\nwidth = 96\nheight = 96\ncull_backfaces = false\nshading = \"phong\"\n",
    ),
    (
        "cylinder-two-lights",
        "[model]\nsource = \"cylinder\"\n[[lights]]\nkind = \"point\"\nposition = [2.0, 2.0, 3.0]\ncolor = [255, 200, 150]\n[[lights]]\nkind = \"directional\"\ndirection = [1.0, 0.0, -0.5]\ncolor = [80, 120, 255]\nintensity = 0.8\n[material]\nks = [200, 200, 200]\nshininess = 12\n[render]\nwidth = 96\nheight = 96\npitch = 25\n",
    ),
];

fn golden_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden")
}

/// Renders a golden scene with `rasterizer`.
fn render_case(scene: &str, rasterizer: Rasterizer) -> Image {
    let file = SceneFile::parse(scene, "golden scene").expect("golden scene parses");
    let (scene, mut options) = file.resolve(Path::new(".")).expect("golden scene resolves");
    options.rasterizer = rasterizer;
    render(&scene, &options).expect("golden scene renders").0
}

/// Where `actual` and `expected` first differ, or `None`.
fn first_difference(actual: &Image, expected: &Image) -> Option<(u32, u32, Rgb8, Rgb8)> {
    (0..actual.height())
        .flat_map(|y| (0..actual.width()).map(move |x| (x, y)))
        .map(|(x, y)| (x, y, actual.pixel(x, y), expected.pixel(x, y)))
        .find(|(_, _, a, e)| a != e)
}

/// An image that is black where the two agree and shows the difference, amplified, elsewhere.
fn diff_image(actual: &Image, expected: &Image) -> Image {
    let mut diff = Image::filled(actual.width(), actual.height(), Rgb8::default());
    for y in 0..actual.height() {
        for x in 0..actual.width() {
            let (a, e) = (actual.pixel(x, y).0, expected.pixel(x, y).0);
            let d = |k: usize| (a[k].abs_diff(e[k]) as u32 * 16).min(255) as u8;
            diff.set_pixel(x, y, Rgb8::new(d(0), d(1), d(2)));
        }
    }
    diff
}

#[test]
fn golden_images_match() {
    let bless = std::env::var_os("BLESS").is_some();
    let mut failures = Vec::new();
    for (name, scene) in CASES {
        let actual = render_case(scene, Rasterizer::Scanline);
        let path = golden_dir().join(format!("{name}.png"));
        if bless {
            write_png(&path, &actual).expect("write golden image");
            continue;
        }
        let expected = read_png(&path)
            .unwrap_or_else(|e| panic!("{}: {e} (run with BLESS=1 to create it)", path.display()));
        let same_size = (actual.width(), actual.height()) == (expected.width(), expected.height());
        let difference = if same_size {
            first_difference(&actual, &expected)
        } else {
            None
        };
        if !same_size || difference.is_some() {
            let out = std::env::temp_dir().join(format!("shadelab-golden-{name}"));
            std::fs::create_dir_all(&out).unwrap();
            write_png(&out.join("actual.png"), &actual).unwrap();
            if same_size {
                write_png(&out.join("diff.png"), &diff_image(&actual, &expected)).unwrap();
            }
            failures.push(format!(
                "{name}: {} (actual and diff written to {})",
                match difference {
                    Some((x, y, a, e)) => format!("first difference at ({x}, {y}): {a:?} != {e:?}"),
                    None => format!(
                        "size {}x{} != {}x{}",
                        actual.width(),
                        actual.height(),
                        expected.width(),
                        expected.height()
                    ),
                },
                out.display()
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "golden images differ:\n{}",
        failures.join("\n")
    );
}

/// The default (tiled) rasterizer stays within 1/255 of the scanline goldens,
/// with identical coverage of the background.
#[test]
fn tiled_rasterizer_matches_the_golden_images_within_one_level() {
    if std::env::var_os("BLESS").is_some() {
        return; // the goldens are being rewritten by the other test
    }
    for (name, scene) in CASES {
        let expected = read_png(&golden_dir().join(format!("{name}.png"))).expect("golden image");
        let actual = render_case(scene, Rasterizer::Tiled);
        for y in 0..expected.height() {
            for x in 0..expected.width() {
                let (a, e) = (actual.pixel(x, y).0, expected.pixel(x, y).0);
                let worst = (0..3).map(|k| a[k].abs_diff(e[k])).max().unwrap();
                assert!(
                    worst <= 1,
                    "{name}: tiled pixel ({x}, {y}) is {a:?}, golden {e:?}"
                );
            }
        }
    }
}
