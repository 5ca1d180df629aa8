//! Golden images: a few scenes rendered and compared byte for byte with PNGs
//! under `tests/golden/`. They guard against unintended change; correctness
//! itself is proven against independent computations in the core's tests.
//!
//! Two sets: a few hand-picked scenes (`tests/golden/*.png`, drawn by the
//! scanline rasterizer, the tiled one within 1/255 of them), and the matrix
//! that locks the pixels before any refactoring (`tests/golden/matrix/`):
//! every built-in model × the three methods, and every non-default option ×
//! the three methods, each drawn by **both** rasterizers and kept apart. The
//! scanline images must stay byte-identical; the tiled ones within 1/255 per
//! channel, which also keeps their coverage identical (every covered pixel
//! has at least the ambient term, 0.2 × 200 = 40 in red, so a pixel covered
//! in one image and background in the other differs by far more).
//!
//! After a deliberate change, regenerate them with
//! `BLESS=1 cargo test --release --test golden` and look at every new image.

use std::path::{Path, PathBuf};

use shadelab_core::{render, Image, Rasterizer, Rgb8, BUILTIN_MODELS};
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
/// `None` when the scene asks for a mode only the scanline rasterizer draws
/// (fixed point, a palette, whole polygons) and `rasterizer` is the tiled one.
fn render_case(scene: &str, rasterizer: Rasterizer) -> Option<Image> {
    let file = SceneFile::parse(scene, "golden scene").expect("golden scene parses");
    let (scene, mut options) = file.resolve(Path::new(".")).expect("golden scene resolves");
    if rasterizer == Rasterizer::Tiled && options.needs_scanline() {
        return None;
    }
    options.rasterizer = rasterizer;
    Some(render(&scene, &options).expect("golden scene renders").0)
}

/// Where `actual` and `expected` first differ by more than `tolerance` in a
/// channel, or `None`.
fn first_difference(
    actual: &Image,
    expected: &Image,
    tolerance: u8,
) -> Option<(u32, u32, Rgb8, Rgb8)> {
    (0..actual.height())
        .flat_map(|y| (0..actual.width()).map(move |x| (x, y)))
        .map(|(x, y)| (x, y, actual.pixel(x, y), expected.pixel(x, y)))
        .find(|(_, _, a, e)| (0..3).any(|k| a.0[k].abs_diff(e.0[k]) > tolerance))
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

/// Compares `actual` with the golden image at `path` (or writes it when
/// blessing): every channel within `tolerance`. A failure is described, and
/// the actual image and an amplified difference are written to a temporary
/// folder for a look.
fn check(name: &str, path: &Path, actual: &Image, tolerance: u8, bless: bool) -> Option<String> {
    if bless {
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        write_png(path, actual).expect("write golden image");
        return None;
    }
    let expected = match read_png(path) {
        Ok(image) => image,
        Err(e) => {
            return Some(format!(
                "{}: {e} (run with BLESS=1 to create it)",
                path.display()
            ))
        }
    };
    let same_size = (actual.width(), actual.height()) == (expected.width(), expected.height());
    let difference = if same_size {
        first_difference(actual, &expected, tolerance)
    } else {
        None
    };
    if same_size && difference.is_none() {
        return None;
    }
    let out = std::env::temp_dir().join(format!("shadelab-golden-{name}"));
    std::fs::create_dir_all(&out).unwrap();
    write_png(&out.join("actual.png"), actual).unwrap();
    if same_size {
        write_png(&out.join("diff.png"), &diff_image(actual, &expected)).unwrap();
    }
    Some(format!(
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
    ))
}

#[test]
fn golden_images_match() {
    let bless = std::env::var_os("BLESS").is_some();
    let failures: Vec<String> = CASES
        .iter()
        .filter_map(|(name, scene)| {
            let actual = render_case(scene, Rasterizer::Scanline).expect("drawn");
            check(
                name,
                &golden_dir().join(format!("{name}.png")),
                &actual,
                0,
                bless,
            )
        })
        .collect();
    assert!(
        failures.is_empty(),
        "golden images differ:\n{}",
        failures.join("\n")
    );
}

/// The options that differ from the defaults, one at a time, as scene-file
/// lines: (name, `[model]` lines, `[render]` lines, `[camera]` lines).
const OPTIONS: &[(&str, &str, &str, &str)] = &[
    ("blinn", "", "specular = \"blinn-phong\"\n", ABOVE),
    ("fixed-point", "", "fixed_point_bits = 8\n", ABOVE),
    ("palette", "", "palette_shades = 8\n", ABOVE),
    ("area-weights", "normals = \"area\"\n", "", ABOVE),
    (
        "angle-weights-crease",
        "normals = \"angle\"\ncrease_angle = 40\n",
        "",
        ABOVE,
    ),
    ("uniform-weights", "normals = \"uniform\"\n", "", ABOVE),
    (
        "screen-interpolation",
        "",
        "interpolation = \"screen\"\n",
        ABOVE,
    ),
    ("no-cull", "", "cull_backfaces = false\n", INSIDE),
    ("whole-polygons", "", "polygons = \"whole\"\n", ABOVE),
    ("gouraud-specular", "", "gouraud_specular = true\n", ABOVE),
];

/// The torus from above and aside, its hole in view.
const ABOVE: &str = "eye = [1.2, 2.0, 2.6]\n";

/// Inside the torus's tube, looking along it: every face in view is a back
/// face, so with culling the picture would be black.
const INSIDE: &str =
    "eye = [1.0, 0.0, 0.0]\ntarget = [0.7, 0.1, -0.7]\nfov_y = 90\nnear = 0.05\nfar = 10\n";

/// The matrix: (name, scene) for every built-in model × method (framed,
/// turned 30° and tilted 25°), and every option of [`OPTIONS`] × method on
/// the torus (curved, quads, silhouettes).
fn matrix() -> Vec<(String, String)> {
    let size = "width = 96\nheight = 72\n";
    let mut cases = Vec::new();
    for method in ["flat", "gouraud", "phong"] {
        for model in BUILTIN_MODELS {
            let name = format!("{}-{method}", model.name);
            let scene = format!(
                "[model]\nsource = \"{}\"\n[render]\n{size}yaw = 30\npitch = 25\n\
                 shading = \"{method}\"\n",
                model.name
            );
            cases.push((name, scene));
        }
        for (option, model_lines, render_lines, camera_lines) in OPTIONS {
            let name = format!("torus-{option}-{method}");
            let scene = format!(
                "[model]\nsource = \"torus\"\ndetail = 12\n{model_lines}[render]\n{size}\
                 shading = \"{method}\"\n{render_lines}[camera]\n{camera_lines}"
            );
            cases.push((name, scene));
        }
    }
    cases
}

/// The lock on the pixels: both rasterizers, every model, method and option.
#[test]
fn the_matrix_of_models_methods_options_and_rasterizers_is_unchanged() {
    let bless = std::env::var_os("BLESS").is_some();
    let dir = golden_dir().join("matrix");
    let mut failures = Vec::new();
    let mut scanline_only = 0;
    let cases = matrix();
    for (name, scene) in &cases {
        for (rasterizer, label, tolerance) in [
            (Rasterizer::Scanline, "scanline", 0),
            (Rasterizer::Tiled, "tiled", 1),
        ] {
            let Some(actual) = render_case(scene, rasterizer) else {
                scanline_only += 1;
                continue;
            };
            let name = format!("{name}-{label}");
            let path = dir.join(format!("{name}.png"));
            failures.extend(check(&name, &path, &actual, tolerance, bless));
        }
    }
    assert_eq!(cases.len(), 3 * (BUILTIN_MODELS.len() + OPTIONS.len()));
    // Fixed point, palette and whole polygons, each × the three methods.
    assert_eq!(
        scanline_only,
        3 * 3,
        "cases only the scanline rasterizer draws"
    );
    assert!(
        failures.is_empty(),
        "{} of the matrix images differ:\n{}",
        failures.len(),
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
        let actual = render_case(scene, Rasterizer::Tiled).expect("drawn tiled");
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
