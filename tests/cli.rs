//! The `shadelab` binary end to end: each test runs it in a fresh temporary
//! directory and reads back what it wrote.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// A decoded 8-bit RGB image.
#[derive(PartialEq)]
struct Png {
    width: u32,
    height: u32,
    rgb: Vec<u8>,
}

/// Short, so that a failed comparison does not print every pixel.
impl std::fmt::Debug for Png {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let drawn = self.rgb.chunks(3).filter(|p| *p != [0, 0, 0]).count();
        write!(
            f,
            "Png {{ {}x{}, {} non-black pixels, byte sum {} }}",
            self.width,
            self.height,
            drawn,
            self.rgb.iter().map(|&c| u64::from(c)).sum::<u64>()
        )
    }
}

impl Png {
    /// How many pixels differ from `background`.
    fn drawn(&self, background: [u8; 3]) -> usize {
        self.rgb.chunks(3).filter(|p| *p != background).count()
    }

    fn read(path: &Path) -> Png {
        let file = std::fs::File::open(path)
            .unwrap_or_else(|e| panic!("cannot open {}: {e}", path.display()));
        let decoder = png::Decoder::new(std::io::BufReader::new(file));
        let mut reader = decoder.read_info().expect("a PNG header");
        let mut buf = vec![0; reader.output_buffer_size()];
        let info = reader.next_frame(&mut buf).expect("a PNG frame");
        assert_eq!(info.color_type, png::ColorType::Rgb);
        assert_eq!(info.bit_depth, png::BitDepth::Eight);
        buf.truncate(info.buffer_size());
        Png {
            width: info.width,
            height: info.height,
            rgb: buf,
        }
    }

    fn pixel(&self, x: u32, y: u32) -> [u8; 3] {
        assert!(x < self.width && y < self.height, "({x}, {y}) is outside");
        let at = (y as usize * self.width as usize + x as usize) * 3;
        [self.rgb[at], self.rgb[at + 1], self.rgb[at + 2]]
    }

    /// The pixels of the rectangle at (`x`, `y`) of size `w` × `h`.
    fn region(&self, x: u32, y: u32, w: u32, h: u32) -> Vec<[u8; 3]> {
        (y..y + h)
            .flat_map(|py| (x..x + w).map(move |px| (px, py)))
            .map(|(px, py)| self.pixel(px, py))
            .collect()
    }
}

/// Runs the binary with `args` in `dir`.
fn run(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_shadelab"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the binary runs")
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// Asserts success and returns nothing; shows stderr on failure.
fn assert_ok(out: &Output) {
    assert!(
        out.status.success(),
        "exit {:?}, stderr:\n{}",
        out.status.code(),
        stderr(out)
    );
    assert!(!stderr(out).contains("panicked"), "{}", stderr(out));
}

/// Asserts exit code 2, no panic, and that stderr mentions every needle.
fn assert_input_error(out: &Output, needles: &[&str]) {
    let err = stderr(out);
    assert_eq!(out.status.code(), Some(2), "stderr:\n{err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(!err.trim().is_empty(), "no message on stderr");
    for needle in needles {
        assert!(
            err.contains(needle),
            "stderr should mention {needle:?}:\n{err}"
        );
    }
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// Names in `dir`, sorted.
fn entries(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

fn assert_no_temporary_files(dir: &Path) {
    let names = entries(dir);
    assert!(
        names.iter().all(|n| !n.ends_with(".tmp")),
        "temporary file left behind: {names:?}"
    );
}

const TETRA: &str = "\
v 0 0 0
v 1 0 0
v 0 1 0
v 0 0 1
f 1 3 2
f 1 2 4
f 1 4 3
f 2 3 4
";

const BLACK: [u8; 3] = [0, 0, 0];

// ---- render ----

#[test]
fn render_a_builtin_model() {
    let dir = tempfile::tempdir().unwrap();
    let out = run(
        dir.path(),
        &[
            "render",
            "--model",
            "sphere",
            "--shading",
            "phong",
            "--size",
            "64x48",
            "-o",
            "out.png",
        ],
    );
    assert_ok(&out);
    let image = Png::read(&dir.path().join("out.png"));
    assert_eq!((image.width, image.height), (64, 48));
    assert_ne!(image.pixel(32, 24), BLACK, "the sphere covers the centre");
    for (x, y) in [(0, 0), (63, 0), (0, 47), (63, 47)] {
        assert_eq!(image.pixel(x, y), BLACK, "corner ({x}, {y})");
    }
    // The summary line goes to stderr.
    assert!(stderr(&out).contains("64x48"), "{}", stderr(&out));
    assert_eq!(entries(dir.path()), vec!["out.png".to_owned()]);
}

#[test]
fn render_uses_the_scene_file() {
    let dir = tempfile::tempdir().unwrap();
    write(
        dir.path(),
        "scene.toml",
        "[model]\nsource = \"sphere\"\n[render]\nwidth = 40\nheight = 30\nbackground = [10, 20, 30]\nshading = \"flat\"\n",
    );
    let out = run(dir.path(), &["render", "scene.toml", "-o", "out.png"]);
    assert_ok(&out);
    let image = Png::read(&dir.path().join("out.png"));
    assert_eq!((image.width, image.height), (40, 30));
    assert_eq!(image.pixel(0, 0), [10, 20, 30]);
    assert_eq!(image.pixel(39, 29), [10, 20, 30]);
    assert_ne!(image.pixel(20, 15), [10, 20, 30]);
    assert!(stderr(&out).starts_with("Flat"), "{}", stderr(&out));
}

#[test]
fn flags_override_the_scene_file() {
    let dir = tempfile::tempdir().unwrap();
    let scene = "[model]\nsource = \"sphere\"\n[render]\nwidth = 40\nheight = 30\nbackground = [10, 20, 30]\n";
    write(dir.path(), "scene.toml", scene);
    write(
        dir.path(),
        "cube.toml",
        &scene.replace("\"sphere\"", "\"cube\""),
    );

    // --size and --background.
    let out = run(
        dir.path(),
        &[
            "render",
            "scene.toml",
            "--size",
            "24x20",
            "--background",
            "200,100,50",
            "-o",
            "sized.png",
        ],
    );
    assert_ok(&out);
    let sized = Png::read(&dir.path().join("sized.png"));
    assert_eq!((sized.width, sized.height), (24, 20));
    assert_eq!(sized.pixel(0, 0), [200, 100, 50]);

    // --model: the same as a scene that names the cube, unlike the sphere.
    assert_ok(&run(
        dir.path(),
        &["render", "scene.toml", "--model", "cube", "-o", "flag.png"],
    ));
    assert_ok(&run(dir.path(), &["render", "cube.toml", "-o", "file.png"]));
    assert_ok(&run(
        dir.path(),
        &["render", "scene.toml", "-o", "sphere.png"],
    ));
    let flag = Png::read(&dir.path().join("flag.png"));
    let file = Png::read(&dir.path().join("file.png"));
    let sphere = Png::read(&dir.path().join("sphere.png"));
    assert_eq!(flag, file);
    assert_ne!(flag, sphere);
    // The scene's other keys still apply.
    assert_eq!(flag.pixel(0, 0), [10, 20, 30]);
    assert_eq!((flag.width, flag.height), (40, 30));

    // --shading overrides the scene's shading.
    assert_ok(&run(
        dir.path(),
        &[
            "render",
            "scene.toml",
            "--shading",
            "flat",
            "-o",
            "flat.png",
        ],
    ));
    assert_ne!(Png::read(&dir.path().join("flat.png")), sphere);
}

#[test]
fn scene_obj_path_is_relative_to_the_scene_file() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir_all(dir.path().join("scenes/meshes")).unwrap();
    write(dir.path(), "scenes/meshes/tetra.obj", TETRA);
    write(
        dir.path(),
        "scenes/tetra.toml",
        "[model]\nsource = \"meshes/tetra.obj\"\n[render]\nwidth = 32\nheight = 32\n",
    );
    let out = run(
        dir.path(),
        &["render", "scenes/tetra.toml", "-o", "tetra.png"],
    );
    assert_ok(&out);
    let image = Png::read(&dir.path().join("tetra.png"));
    assert!(image.rgb.chunks(3).any(|p| p != BLACK), "nothing drawn");
}

#[test]
fn model_flag_path_is_relative_to_the_working_directory() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir_all(dir.path().join("scenes")).unwrap();
    write(dir.path(), "tetra.obj", TETRA);
    write(
        dir.path(),
        "scenes/plain.toml",
        "[render]\nwidth = 32\nheight = 32\n",
    );
    let out = run(
        dir.path(),
        &[
            "render",
            "scenes/plain.toml",
            "--model",
            "tetra.obj",
            "-o",
            "tetra.png",
        ],
    );
    assert_ok(&out);
    let image = Png::read(&dir.path().join("tetra.png"));
    assert!(image.rgb.chunks(3).any(|p| p != BLACK), "nothing drawn");
}

#[test]
fn render_an_obj_given_on_the_command_line() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "tetra.obj", TETRA);
    let out = run(
        dir.path(),
        &[
            "render",
            "--model",
            "tetra.obj",
            "--size",
            "32x32",
            "-o",
            "out.png",
        ],
    );
    assert_ok(&out);
    let image = Png::read(&dir.path().join("out.png"));
    assert!(image.drawn(BLACK) > 50, "{image:?}");
}

#[test]
fn every_option_is_accepted() {
    let dir = tempfile::tempdir().unwrap();
    write(
        dir.path(),
        "scene.toml",
        "[model]\nsource = \"sphere\"\n[render]\nwidth = 10\nheight = 10\n",
    );
    let overrides = [
        "--model",
        "torus",
        "--detail",
        "12",
        "--size",
        "40x30",
        "--ambient",
        "10,20,30",
        "--ambient-intensity",
        "0.3",
        "--light-pos",
        "-2,3,4",
        "--light-color",
        "255,200,100",
        "--light-intensity",
        "0.9",
        "--ka",
        "100,50,50",
        "--kd",
        "200,100,100",
        "--ks",
        "255,255,255",
        "--shininess",
        "16",
        "--yaw",
        "-30",
        "--pitch",
        "15",
        "--normals",
        "area",
        "--crease-angle",
        "45",
        "--interpolation",
        "screen",
        "--no-cull",
        "--gouraud-specular",
        "--background",
        "5,6,7",
        "--rasterizer",
        "scanline",
        "--polygons",
        "whole",
        "--specular",
        "blinn-phong",
    ];
    let mut args = vec!["render", "scene.toml", "--shading", "gouraud"];
    args.extend_from_slice(&overrides);
    args.extend_from_slice(&["--output", "render.png"]);
    assert_ok(&run(dir.path(), &args));
    let image = Png::read(&dir.path().join("render.png"));
    assert_eq!((image.width, image.height), (40, 30));
    assert_eq!(image.pixel(0, 0), [5, 6, 7]);
    assert!(image.rgb.chunks(3).any(|p| p != [5, 6, 7]), "nothing drawn");

    let mut args = vec!["compare", "scene.toml", "-o", "compare.png"];
    args.extend_from_slice(&overrides);
    assert_ok(&run(dir.path(), &args));
    let sheet = Png::read(&dir.path().join("compare.png"));
    assert_eq!((sheet.width, sheet.height), (3 * 40 + 2 * 4, 30 + 28));
}

#[test]
fn each_flag_changes_the_image() {
    let dir = tempfile::tempdir().unwrap();
    let base = ["render", "--model", "sphere", "--size", "32x32"];
    let render = |name: &str, extra: &[&str]| -> Png {
        let mut args: Vec<&str> = base.to_vec();
        args.extend_from_slice(extra);
        let file = format!("{name}.png");
        args.extend_from_slice(&["-o", &file]);
        assert_ok(&run(dir.path(), &args));
        Png::read(&dir.path().join(&file))
    };
    let plain = render("plain", &[]);
    let cases: &[(&str, &[&str])] = &[
        ("detail", &["--detail", "5"]),
        ("ambient", &["--ambient", "0,0,255"]),
        ("ambient-intensity", &["--ambient-intensity", "0.8"]),
        ("light-pos", &["--light-pos", "-2,3,4"]),
        ("light-color", &["--light-color", "0,255,0"]),
        ("light-intensity", &["--light-intensity", "0.3"]),
        ("ka", &["--ka", "0,0,255"]),
        ("kd", &["--kd", "0,255,0"]),
        ("ks", &["--ks", "0,0,0"]),
        ("shininess", &["--shininess", "2"]),
        ("yaw", &["--yaw", "-60"]),
        ("pitch", &["--pitch", "40"]),
        ("background", &["--background", "0,0,1"]),
        ("shading", &["--shading", "flat"]),
    ];
    for (name, extra) in cases {
        let image = render(name, extra);
        assert_ne!(image, plain, "{extra:?} changed nothing");
    }
    // Normals, compared with the same sphere with default normals.
    let coarse = render("coarse", &["--detail", "6"]);
    for (name, extra) in [
        (
            "crease-angle",
            &["--detail", "6", "--crease-angle", "5"][..],
        ),
        ("normals-area", &["--detail", "6", "--normals", "area"][..]),
        (
            "normals-angle",
            &["--detail", "6", "--normals", "angle"][..],
        ),
    ] {
        assert_ne!(render(name, extra), coarse, "{extra:?} changed nothing");
    }
    let uniform = render(
        "normals-uniform",
        &["--detail", "6", "--normals", "uniform"],
    );
    assert_eq!(uniform, coarse, "uniform is the default for a built-in");
    // Gouraud-specific flags, compared with Gouraud otherwise alike. The
    // finer sphere has a vertex close enough to the highlight to catch it.
    let fine = ["--shading", "gouraud", "--detail", "48"];
    let gouraud = render("gouraud", &fine);
    let specular = render(
        "gouraud-specular",
        &[&fine[..], &["--gouraud-specular"]].concat(),
    );
    assert_ne!(specular, gouraud, "--gouraud-specular changed nothing");
    let screen = render(
        "screen",
        &[&fine[..], &["--interpolation", "screen"]].concat(),
    );
    assert_ne!(screen, gouraud, "--interpolation screen changed nothing");
    let perspective = render(
        "perspective",
        &[&fine[..], &["--interpolation", "perspective"]].concat(),
    );
    assert_eq!(perspective, gouraud, "perspective is the default");

    // The specular term's shape, on Phong's highlight.
    let blinn = render("blinn", &["--specular", "blinn-phong"]);
    assert_ne!(blinn, plain, "--specular blinn-phong changed nothing");
    // Whole quads differ from fans under Gouraud; the tiled rasterizer
    // draws fans only, so whole polygons need the scanline one.
    let coarse_gouraud = ["--shading", "gouraud", "--detail", "6", "--yaw", "20"];
    let fans = render(
        "fans",
        &[&coarse_gouraud[..], &["--rasterizer", "scanline"]].concat(),
    );
    let whole = render(
        "whole",
        &[
            &coarse_gouraud[..],
            &["--rasterizer", "scanline", "--polygons", "whole"],
        ]
        .concat(),
    );
    assert_ne!(whole, fans, "--polygons whole changed nothing");
    let tiled = render(
        "tiled",
        &[&coarse_gouraud[..], &["--rasterizer", "tiled"]].concat(),
    );
    assert_eq!(tiled.drawn(BLACK), fans.drawn(BLACK), "same coverage");
}

#[test]
fn no_cull_draws_back_faces() {
    let dir = tempfile::tempdir().unwrap();
    // Inside the cube every face is a back face.
    write(
        dir.path(),
        "inside.toml",
        "[model]\nsource = \"cube\"\n[camera]\neye = [0.1, 0.1, 0.2]\ntarget = [1, 0.4, -1]\nfov_y = 90\nnear = 0.05\nfar = 10\n[render]\nwidth = 24\nheight = 24\n",
    );
    assert_ok(&run(
        dir.path(),
        &["render", "inside.toml", "-o", "culled.png"],
    ));
    assert_ok(&run(
        dir.path(),
        &["render", "inside.toml", "--no-cull", "-o", "drawn.png"],
    ));
    let culled = Png::read(&dir.path().join("culled.png"));
    let drawn = Png::read(&dir.path().join("drawn.png"));
    assert!(culled.rgb.iter().all(|&c| c == 0), "culled: all background");
    assert!(
        drawn.rgb.chunks(3).all(|p| p != BLACK),
        "no-cull: all walls"
    );
}

#[test]
fn negative_numbers_are_accepted_as_values() {
    let dir = tempfile::tempdir().unwrap();
    assert_ok(&run(
        dir.path(),
        &[
            "render",
            "--model",
            "sphere",
            "--size",
            "16x16",
            "--light-pos",
            "-2,3,4",
            "--yaw",
            "-45",
            "--pitch",
            "-10",
            "-o",
            "out.png",
        ],
    ));
    assert!(dir.path().join("out.png").exists());
    // Long form with `=` too.
    assert_ok(&run(
        dir.path(),
        &[
            "render",
            "--model=sphere",
            "--size=16x16",
            "--light-pos=-2,-3,-4",
            "-o",
            "eq.png",
        ],
    ));
}

// ---- compare ----

#[test]
fn compare_draws_three_labelled_panels() {
    let dir = tempfile::tempdir().unwrap();
    let out = run(
        dir.path(),
        &[
            "compare",
            "--model",
            "sphere",
            "--size",
            "100x100",
            "-o",
            "three.png",
        ],
    );
    assert_ok(&out);
    let sheet = Png::read(&dir.path().join("three.png"));
    assert_eq!((sheet.width, sheet.height), (3 * 100 + 2 * 4, 100 + 28));

    let panels: Vec<Vec<[u8; 3]>> = (0..3)
        .map(|k| sheet.region(k * 104, 28, 100, 100))
        .collect();
    for (k, panel) in panels.iter().enumerate() {
        let drawn = panel.iter().filter(|&&p| p != BLACK).count();
        assert!(drawn > 1000, "panel {k} has only {drawn} drawn pixels");
        assert_eq!(panel[0], BLACK, "panel {k}'s corner is background");
    }
    assert_ne!(panels[0], panels[2], "flat and Phong differ");
    assert_ne!(panels[0], panels[1], "flat and Gouraud differ");
    assert_ne!(panels[1], panels[2], "Gouraud and Phong differ");

    // The label band: mostly the band colour, with light text over each panel.
    for k in 0..3 {
        let band = sheet.region(k * 104, 0, 100, 28);
        let light = band.iter().filter(|p| p.iter().all(|&c| c >= 200)).count();
        assert!(light > 20, "panel {k}'s label has {light} light pixels");
        assert!(light < band.len() / 2);
    }
    // The gaps between panels are not image.
    for x in [100, 103, 204, 207] {
        for y in [30, 78, 127] {
            assert_ne!(sheet.pixel(x, y), BLACK, "gap at ({x}, {y})");
        }
    }
    // The three summary lines.
    let err = stderr(&out);
    for title in ["Flat", "Gouraud", "Phong"] {
        assert!(err.contains(title), "{err}");
    }
}

#[test]
fn compare_panels_match_single_renders() {
    let dir = tempfile::tempdir().unwrap();
    assert_ok(&run(
        dir.path(),
        &[
            "compare", "--model", "cube", "--size", "30x20", "--yaw", "30", "-o", "c.png",
        ],
    ));
    let sheet = Png::read(&dir.path().join("c.png"));
    for (k, shading) in ["flat", "gouraud", "phong"].iter().enumerate() {
        let name = format!("{shading}.png");
        assert_ok(&run(
            dir.path(),
            &[
                "render",
                "--model",
                "cube",
                "--size",
                "30x20",
                "--yaw",
                "30",
                "--shading",
                shading,
                "-o",
                &name,
            ],
        ));
        let single = Png::read(&dir.path().join(&name));
        let panel: Vec<u8> = sheet
            .region(k as u32 * 34, 28, 30, 20)
            .into_iter()
            .flatten()
            .collect();
        assert_eq!(panel, single.rgb, "{shading} panel");
    }
}

#[test]
fn compare_default_panel_size_and_tiny_panels() {
    let dir = tempfile::tempdir().unwrap();
    // A scene without a size: panels are 480 × 480.
    write(
        dir.path(),
        "s.toml",
        "[model]\nsource = \"cube\"\ndetail = 1\n",
    );
    assert_ok(&run(dir.path(), &["compare", "s.toml", "-o", "big.png"]));
    let sheet = Png::read(&dir.path().join("big.png"));
    assert_eq!((sheet.width, sheet.height), (3 * 480 + 8, 480 + 28));
    // Panels narrower than their labels.
    assert_ok(&run(
        dir.path(),
        &[
            "compare", "--model", "cube", "--size", "3x2", "-o", "tiny.png",
        ],
    ));
    let tiny = Png::read(&dir.path().join("tiny.png"));
    assert_eq!((tiny.width, tiny.height), (3 * 3 + 8, 2 + 28));
}

// ---- models ----

#[test]
fn models_lists_all_builtins() {
    let dir = tempfile::tempdir().unwrap();
    let out = run(dir.path(), &["models"]);
    assert_ok(&out);
    let text = String::from_utf8(out.stdout).unwrap();
    let names: Vec<&str> = text
        .lines()
        .skip(1)
        .filter_map(|l| l.split_whitespace().next())
        .collect();
    assert_eq!(
        names,
        [
            "cube",
            "sphere",
            "icosphere",
            "torus",
            "cylinder",
            "cone",
            "teapot"
        ]
    );
    assert!(text.lines().next().unwrap().starts_with("name"));
}

// ---- errors ----

/// Runs `render` with `args` and `-o out.png`, expecting an input error that
/// mentions every needle and no output file.
fn assert_render_fails(dir: &Path, args: &[&str], needles: &[&str]) {
    let mut all = vec!["render"];
    all.extend_from_slice(args);
    all.extend_from_slice(&["-o", "out.png"]);
    let out = run(dir, &all);
    assert_input_error(&out, needles);
    assert!(!dir.join("out.png").exists(), "{args:?} created the output");
    assert_no_temporary_files(dir);
}

#[test]
fn missing_scene_file() {
    let dir = tempfile::tempdir().unwrap();
    assert_render_fails(dir.path(), &["absent.toml"], &["absent.toml"]);
}

#[test]
fn missing_files_are_reported_once() {
    // The OS error appears once, not once per level of the error chain.
    let dir = tempfile::tempdir().unwrap();
    for args in [
        &["render", "absent.toml", "-o", "out.png"][..],
        &["render", "--model", "absent.obj", "-o", "out.png"][..],
        &["compare", "--model", "absent.obj", "-o", "out.png"][..],
        &["render", "--model", "cube", "-o", "no/dir/out.png"][..],
    ] {
        let err = stderr(&run(dir.path(), args));
        assert_eq!(err.matches("os error").count(), 1, "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
    }
}

#[test]
fn malformed_scene_file() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "bad.toml", "[render\nwidth = 10\n");
    assert_render_fails(dir.path(), &["bad.toml"], &["bad.toml", "line 1"]);
}

#[test]
fn unknown_key_in_the_scene() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "bad.toml", "[render]\nwidht = 10\n");
    assert_render_fails(dir.path(), &["bad.toml"], &["bad.toml", "widht"]);
}

#[test]
fn out_of_range_value_in_the_scene() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "bad.toml", "[material]\nshininess = -3\n");
    assert_render_fails(dir.path(), &["bad.toml"], &["material.shininess"]);
    write(dir.path(), "bad2.toml", "[[lights]]\nkind = \"point\"\n");
    assert_render_fails(dir.path(), &["bad2.toml"], &["lights[0].position"]);
}

#[test]
fn out_of_range_override() {
    let dir = tempfile::tempdir().unwrap();
    assert_render_fails(
        dir.path(),
        &["--model", "sphere", "--shininess", "-1"],
        &["material.shininess"],
    );
    assert_render_fails(
        dir.path(),
        &["--model", "sphere", "--detail", "1"],
        &["model.detail"],
    );
    assert_render_fails(
        dir.path(),
        &["--model", "cube", "--crease-angle", "200"],
        &["model.crease_angle"],
    );
    assert_render_fails(
        dir.path(),
        &["--model", "cube", "--normals", "file"],
        &["model.normals"],
    );
}

#[test]
fn missing_obj() {
    let dir = tempfile::tempdir().unwrap();
    assert_render_fails(dir.path(), &["--model", "absent.obj"], &["absent.obj"]);
    write(dir.path(), "s.toml", "[model]\nsource = \"gone.obj\"\n");
    assert_render_fails(dir.path(), &["s.toml"], &["gone.obj"]);
}

#[test]
fn obj_with_a_syntax_error() {
    let dir = tempfile::tempdir().unwrap();
    write(
        dir.path(),
        "bad.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 oops\nf 1 2 3\n",
    );
    assert_render_fails(dir.path(), &["--model", "bad.obj"], &["bad.obj:3:", "oops"]);
}

#[test]
fn obj_with_an_index_out_of_range() {
    let dir = tempfile::tempdir().unwrap();
    write(
        dir.path(),
        "bad.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 4\n",
    );
    assert_render_fails(
        dir.path(),
        &["--model", "bad.obj"],
        &["bad.obj:5:", "out of range"],
    );
    write(
        dir.path(),
        "neg.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n",
    );
    assert_render_fails(
        dir.path(),
        &["--model", "neg.obj"],
        &["neg.obj:4:", "out of range"],
    );
}

#[test]
fn obj_with_nan() {
    let dir = tempfile::tempdir().unwrap();
    write(
        dir.path(),
        "bad.obj",
        "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n",
    );
    assert_render_fails(
        dir.path(),
        &["--model", "bad.obj"],
        &["bad.obj:2:", "finite"],
    );
}

#[test]
fn obj_without_faces() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    assert_render_fails(
        dir.path(),
        &["--model", "bad.obj"],
        &["bad.obj", "no faces"],
    );
}

#[test]
fn unknown_model_name() {
    let dir = tempfile::tempdir().unwrap();
    assert_render_fails(
        dir.path(),
        &["--model", "dodecahedron"],
        &[
            "dodecahedron",
            "cube",
            "sphere",
            "icosphere",
            "torus",
            "cylinder",
            "cone",
            "teapot",
        ],
    );
}

#[test]
fn bad_size() {
    let dir = tempfile::tempdir().unwrap();
    assert_render_fails(
        dir.path(),
        &["--model", "cube", "--size", "0x10"],
        &["1..=16384", "\"0x10\""],
    );
    assert_render_fails(
        dir.path(),
        &["--model", "cube", "--size", "10x0"],
        &["1..=16384", "\"10x0\""],
    );
    assert_render_fails(dir.path(), &["--model", "cube", "--size", "abc"], &["abc"]);
    assert_render_fails(
        dir.path(),
        &["--model", "cube", "--size", "10x"],
        &["--size"],
    );
    assert_render_fails(
        dir.path(),
        &["--model", "cube", "--size", "20000x10"],
        &["1..=16384", "\"20000x10\""],
    );
}

#[test]
fn bad_colour_and_vector_flags() {
    let dir = tempfile::tempdir().unwrap();
    assert_render_fails(
        dir.path(),
        &["--model", "cube", "--ka", "300,0,0"],
        &["--ka"],
    );
    assert_render_fails(dir.path(), &["--model", "cube", "--kd", "1,2"], &["--kd"]);
    assert_render_fails(
        dir.path(),
        &["--model", "cube", "--background=-1,0,0"],
        &["--background"],
    );
    // Without `=`, a leading minus reads as a flag; still a clean usage error.
    assert_render_fails(
        dir.path(),
        &["--model", "cube", "--background", "-1,0,0"],
        &["-1"],
    );
    assert_render_fails(
        dir.path(),
        &["--model", "cube", "--light-pos", "nan,0,0"],
        &["--light-pos"],
    );
    assert_render_fails(
        dir.path(),
        &["--model", "cube", "--shading", "glossy"],
        &["glossy"],
    );
}

#[test]
fn compare_errors_exit_2_without_output() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "bad.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\n");
    let out = run(
        dir.path(),
        &["compare", "--model", "bad.obj", "-o", "three.png"],
    );
    assert_input_error(&out, &["bad.obj:3:"]);
    assert!(!dir.path().join("three.png").exists());
    let out = run(dir.path(), &["compare", "--size", "0x5", "-o", "three.png"]);
    assert_input_error(&out, &["--size", "1..=16384", "\"0x5\""]);
    assert!(!dir.path().join("three.png").exists());
}

#[test]
fn missing_output_flag_and_unknown_subcommand() {
    let dir = tempfile::tempdir().unwrap();
    assert_input_error(
        &run(dir.path(), &["render", "--model", "cube"]),
        &["--output"],
    );
    assert_input_error(&run(dir.path(), &["paint"]), &["paint"]);
    assert_input_error(&run(dir.path(), &[]), &["Usage"]);
}

#[test]
fn unwritable_output_exits_1() {
    let dir = tempfile::tempdir().unwrap();
    let out = run(
        dir.path(),
        &[
            "render",
            "--model",
            "cube",
            "--size",
            "8x8",
            "-o",
            "no/such/dir/out.png",
        ],
    );
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("cannot write"), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(entries(dir.path()).is_empty(), "{:?}", entries(dir.path()));
}

// ---- inputs and outputs ----

#[test]
fn render_refuses_to_overwrite_the_scene_file() {
    let dir = tempfile::tempdir().unwrap();
    let text = "[model]\nsource = \"cube\"\n[render]\nwidth = 8\nheight = 8\n";
    let scene = write(dir.path(), "scene.toml", text);
    for output in ["scene.toml", "./scene.toml"] {
        let out = run(dir.path(), &["render", "scene.toml", "-o", output]);
        assert_input_error(&out, &["scene.toml"]);
        assert_eq!(std::fs::read_to_string(&scene).unwrap(), text);
        let out = run(dir.path(), &["compare", "scene.toml", "-o", output]);
        assert_input_error(&out, &["scene.toml"]);
        assert_eq!(std::fs::read_to_string(&scene).unwrap(), text);
    }
    assert_eq!(entries(dir.path()), vec!["scene.toml".to_owned()]);
}

#[test]
fn render_refuses_to_overwrite_the_obj() {
    let dir = tempfile::tempdir().unwrap();
    let obj = write(dir.path(), "tetra.obj", TETRA);
    let out = run(
        dir.path(),
        &[
            "render",
            "--model",
            "tetra.obj",
            "--size",
            "8x8",
            "-o",
            "tetra.obj",
        ],
    );
    assert_input_error(&out, &["tetra.obj"]);
    assert_eq!(std::fs::read_to_string(&obj).unwrap(), TETRA);

    // Named by a scene file in a subdirectory, written from elsewhere.
    std::fs::create_dir(dir.path().join("sub")).unwrap();
    let nested = write(&dir.path().join("sub"), "m.obj", TETRA);
    write(
        &dir.path().join("sub"),
        "s.toml",
        "[model]\nsource = \"m.obj\"\n[render]\nwidth = 8\nheight = 8\n",
    );
    let out = run(dir.path(), &["render", "sub/s.toml", "-o", "sub/m.obj"]);
    assert_input_error(&out, &["m.obj"]);
    assert_eq!(std::fs::read_to_string(&nested).unwrap(), TETRA);
}

#[test]
fn render_refuses_to_overwrite_a_material_library_or_external_buffer() {
    let dir = tempfile::tempdir().unwrap();
    let obj_text = format!("mtllib  my lib.mtl\nusemtl red\n{TETRA}");
    write(dir.path(), "tetra.obj", &obj_text);
    let mtl_text = "newmtl red\nKd 1 0 0\n";
    for library in ["my lib.mtl", "lib.mtl"] {
        let path = write(dir.path(), library, mtl_text);
        let out = run(
            dir.path(),
            &[
                "render",
                "--model",
                "tetra.obj",
                "--size",
                "8x8",
                "-o",
                library,
            ],
        );
        assert_input_error(&out, &[library]);
        assert_eq!(std::fs::read_to_string(&path).unwrap(), mtl_text);
    }

    // A glTF file whose buffer lives in a file beside it.
    let positions: Vec<u8> = [0f32, 0., 0., 1., 0., 0., 0., 1., 0.]
        .iter()
        .flat_map(|v| v.to_le_bytes())
        .collect();
    let bin = dir.path().join("tri.bin");
    std::fs::write(&bin, &positions).unwrap();
    let gltf = r#"{"asset":{"version":"2.0"},"buffers":[{"uri":"tri.bin","byteLength":36}],
        "bufferViews":[{"buffer":0,"byteLength":36}],
        "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3",
        "min":[0,0,0],"max":[1,1,0]}],
        "meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
        "nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],"scene":0}"#;
    write(dir.path(), "tri.gltf", gltf);
    assert_ok(&run(
        dir.path(),
        &[
            "render", "--model", "tri.gltf", "--size", "8x8", "-o", "tri.png",
        ],
    ));
    let out = run(
        dir.path(),
        &[
            "render", "--model", "tri.gltf", "--size", "8x8", "-o", "tri.bin",
        ],
    );
    assert_input_error(&out, &["tri.bin"]);
    assert_eq!(std::fs::read(&bin).unwrap(), positions);
}

#[test]
fn existing_output_is_replaced_atomically() {
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "out.png", "an old file that is not a PNG");
    assert_ok(&run(
        dir.path(),
        &[
            "render", "--model", "cube", "--size", "20x10", "-o", "out.png",
        ],
    ));
    let image = Png::read(&path);
    assert_eq!((image.width, image.height), (20, 10));
    assert_eq!(entries(dir.path()), vec!["out.png".to_owned()]);

    assert_ok(&run(
        dir.path(),
        &[
            "compare", "--model", "cube", "--size", "20x10", "-o", "out.png",
        ],
    ));
    let sheet = Png::read(&path);
    assert_eq!((sheet.width, sheet.height), (68, 38));
    assert_eq!(entries(dir.path()), vec!["out.png".to_owned()]);
}

#[test]
fn failed_render_keeps_an_existing_output() {
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "out.png", "previous contents");
    let out = run(
        dir.path(),
        &["render", "--model", "nosuchmodel", "-o", "out.png"],
    );
    assert_input_error(&out, &["nosuchmodel"]);
    assert_eq!(std::fs::read_to_string(&path).unwrap(), "previous contents");
    assert_eq!(entries(dir.path()), vec!["out.png".to_owned()]);
}

// ---- mesh formats, materials and the robustness list, end to end ----

/// The tetrahedron as ASCII STL, ASCII PLY and glTF with an embedded buffer.
fn tetra_formats(dir: &Path) {
    let p = [[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]];
    let faces = [[0usize, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
    let mut stl = String::from("solid tetra\n");
    for f in faces {
        stl += "facet normal 0 0 0\nouter loop\n";
        for i in f {
            stl += &format!("vertex {} {} {}\n", p[i][0], p[i][1], p[i][2]);
        }
        stl += "endloop\nendfacet\n";
    }
    write(dir, "tetra.stl", &(stl + "endsolid tetra\n"));
    let mut ply = String::from(
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n\
         property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n",
    );
    for v in p {
        ply += &format!("{} {} {}\n", v[0], v[1], v[2]);
    }
    for f in faces {
        ply += &format!("3 {} {} {}\n", f[0], f[1], f[2]);
    }
    write(dir, "tetra.ply", &ply);
    // Positions then u16 indices, base64: written out by hand.
    let mut bin: Vec<u8> = p
        .iter()
        .flatten()
        .flat_map(|c: &f32| c.to_le_bytes())
        .collect();
    bin.extend(
        faces
            .iter()
            .flatten()
            .flat_map(|&i| (i as u16).to_le_bytes()),
    );
    let b64 = base64_encode(&bin);
    let gltf = format!(
        r#"{{"asset":{{"version":"2.0"}},"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],
        "meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}},"indices":1}}]}}],
        "buffers":[{{"byteLength":{},"uri":"data:application/octet-stream;base64,{b64}"}}],
        "bufferViews":[{{"buffer":0,"byteLength":48}},{{"buffer":0,"byteOffset":48,"byteLength":24}}],
        "accessors":[{{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[0,0,0],"max":[1,1,1]}},
        {{"bufferView":1,"componentType":5123,"count":12,"type":"SCALAR"}}]}}"#,
        bin.len()
    );
    write(dir, "tetra.gltf", &gltf);
}

fn base64_encode(bytes: &[u8]) -> String {
    const A: &[u8] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::new();
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            *chunk.get(1).unwrap_or(&0),
            *chunk.get(2).unwrap_or(&0),
        ];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(A[(n >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

#[test]
fn every_format_renders_like_its_obj_twin() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "tetra.obj", TETRA);
    tetra_formats(dir.path());
    let render = |model: &str, out: &str| {
        assert_ok(&run(
            dir.path(),
            &[
                "render", "--model", model, "--size", "48x40", "--yaw", "30", "-o", out,
            ],
        ));
        Png::read(&dir.path().join(out))
    };
    let obj = render("tetra.obj", "obj.png");
    assert!(obj.drawn(BLACK) > 100, "{obj:?}");
    for model in ["tetra.stl", "tetra.ply", "tetra.gltf"] {
        assert_eq!(render(model, "other.png"), obj, "{model}");
    }
}

#[test]
fn bad_mesh_files_of_every_format() {
    let dir = tempfile::tempdir().unwrap();
    tetra_formats(dir.path());
    // Binary STL whose header claims 2^31 triangles: refused at byte 80.
    let mut stl = vec![0u8; 84 + 50];
    stl[80..84].copy_from_slice(&(1u32 << 31).to_le_bytes());
    std::fs::write(dir.path().join("lie.stl"), &stl).unwrap();
    assert_render_fails(
        dir.path(),
        &["--model", "lie.stl"],
        &["lie.stl", "byte 80", "2147483648 triangles"],
    );
    // A PLY header promising more faces than follow.
    let ply = std::fs::read_to_string(dir.path().join("tetra.ply"))
        .unwrap()
        .replace("element face 4", "element face 40");
    write(dir.path(), "short.ply", &ply);
    assert_render_fails(
        dir.path(),
        &["--model", "short.ply"],
        &["short.ply", "promises"],
    );
    // A glTF index beyond its vertices.
    let gltf = std::fs::read_to_string(dir.path().join("tetra.gltf"))
        .unwrap()
        .replace(r#""count":4,"type":"VEC3""#, r#""count":3,"type":"VEC3""#);
    write(dir.path(), "range.gltf", &gltf);
    assert_render_fails(
        dir.path(),
        &["--model", "range.gltf"],
        &["range.gltf", "index", "3 vertices"],
    );
    // Truncated and empty files, wrong magic.
    std::fs::write(dir.path().join("empty.glb"), b"").unwrap();
    assert_render_fails(dir.path(), &["--model", "empty.glb"], &["empty.glb"]);
    std::fs::write(dir.path().join("magic.ply"), b"PLY\nformat ascii 1.0\n").unwrap();
    assert_render_fails(
        dir.path(),
        &["--model", "magic.ply"],
        &["magic.ply", "byte 0"],
    );
    // A bad smoothing group names its line.
    write(
        dir.path(),
        "s.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\ns smooth\nf 1 2 3\n",
    );
    assert_render_fails(
        dir.path(),
        &["--model", "s.obj"],
        &["s.obj:4:", "`s` takes"],
    );
}

/// The material an OBJ file uses colours the render where no flag or scene
/// key sets the colours; a missing library is no error.
#[test]
fn obj_materials_colour_the_render() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write(d, "blue.mtl", "newmtl blue\nKa 0.2 0.2 0.6\nKd 0.2 0.6 1\n");
    write(d, "tetra.obj", TETRA);
    write(
        d,
        "blue.obj",
        &format!("mtllib blue.mtl\nusemtl blue\n{TETRA}"),
    );
    write(
        d,
        "lost.obj",
        &format!("mtllib lost.mtl\nusemtl blue\n{TETRA}"),
    );
    let render = |args: &[&str]| {
        let mut all = vec!["render", "--size", "40x40", "--yaw", "30", "-o", "out.png"];
        all.extend_from_slice(args);
        let out = run(d, &all);
        assert_ok(&out);
        // The report line, and for a lost library one warning that names it.
        let lines = stderr(&out).lines().count();
        assert!(
            lines <= 1 || (lines == 2 && stderr(&out).contains("lost.mtl")),
            "{}",
            stderr(&out)
        );
        Png::read(&d.join("out.png"))
    };
    let from_file = render(&["--model", "blue.obj"]);
    let by_flags = render(&[
        "--model",
        "tetra.obj",
        "--ka",
        "51,51,153",
        "--kd",
        "51,153,255",
    ]);
    assert_eq!(from_file, by_flags);
    assert_ne!(from_file, render(&["--model", "tetra.obj"]));
    // A flag wins over the file, key by key.
    let kd_flag = render(&["--model", "blue.obj", "--kd", "255,0,0"]);
    let kd_flag_plain = render(&[
        "--model",
        "tetra.obj",
        "--ka",
        "51,51,153",
        "--kd",
        "255,0,0",
    ]);
    assert_eq!(kd_flag, kd_flag_plain);
    // No library: the default colours, and no warning.
    assert_eq!(
        render(&["--model", "lost.obj"]),
        render(&["--model", "tetra.obj"])
    );
}

/// The camera cases of the robustness list, from a scene file: errors that
/// name the camera key, no output, no temporary file.
#[test]
fn impossible_cameras_in_the_scene() {
    let dir = tempfile::tempdir().unwrap();
    for (k, (camera, needles)) in [
        (
            "eye = [1, 2, 3]\ntarget = [1, 2, 3]",
            &["camera", "eye equals camera.target"][..],
        ),
        ("eye = [0, 0, 3]\nfov_y = 0", &["camera", "fov_y", "0"]),
        ("eye = [0, 0, 3]\nfov_y = 180", &["camera", "fov_y", "180"]),
        (
            "eye = [0, 0, 3]\nnear = 5.0\nfar = 5.0",
            &["camera", "near", "far"],
        ),
        (
            "eye = [0, 0, 3]\nnear = 6.0\nfar = 5.0",
            &["camera", "near", "far"],
        ),
        ("eye = [0, 0, 3]\nup = [0, 0, 1]", &["camera", "up"]),
    ]
    .into_iter()
    .enumerate()
    {
        let name = format!("camera{k}.toml");
        write(
            dir.path(),
            &name,
            &format!("[camera]\n{camera}\n[render]\nwidth = 16\nheight = 16\n"),
        );
        assert_render_fails(dir.path(), &[&name], needles);
    }
}

/// Extreme but valid cameras and an eye inside the model render images of
/// the requested size.
#[test]
fn extreme_cameras_render_the_requested_size() {
    let dir = tempfile::tempdir().unwrap();
    for (k, camera) in [
        "eye = [0, 0, 3]\nfov_y = 0.001",
        "eye = [0, 0, 3]\nfov_y = 179.999",
        "eye = [0, 0, 0]\ntarget = [0, 0, -1]\nnear = 0.001",
        "eye = [0, 0, 3]\nnear = 1e-30\nfar = 1e30",
        "eye = [0, 0, 3]\nnear = 2.9\nfar = 2.9000003",
    ]
    .into_iter()
    .enumerate()
    {
        let name = format!("camera{k}.toml");
        write(
            dir.path(),
            &name,
            &format!("[model]\nsource = \"sphere\"\n[camera]\n{camera}\n[render]\nwidth = 23\nheight = 17\ncull_backfaces = false\n"),
        );
        let out = run(dir.path(), &["render", &name, "-o", "out.png"]);
        assert_ok(&out);
        let png = Png::read(&dir.path().join("out.png"));
        assert_eq!((png.width, png.height), (23, 17), "{camera}");
    }
}
