//! `shadelab render` end to end: each test runs the binary in a fresh
//! temporary directory and reads back what it wrote.

mod support;

use support::*;

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
        scene.replace("\"sphere\"", "\"cube\""),
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

/// `--light-attenuation` is `[[lights]] attenuation` of the first light: the
/// same picture either way, darker than without, and a directional light
/// with attenuation is refused naming the key.
#[test]
fn light_attenuation_from_the_flag_or_the_scene_file() {
    let dir = tempfile::tempdir().unwrap();
    let light = "[[lights]]\nkind = \"point\"\nposition = [2.0, 2.0, 3.0]\n";
    let scene = format!("[model]\nsource = \"sphere\"\n[render]\nwidth = 48\nheight = 36\n{light}");
    write(dir.path(), "plain.toml", &scene);
    write(
        dir.path(),
        "faded.toml",
        format!("{scene}attenuation = [1.0, 0.0, 0.25]\n"),
    );
    for (args, out) in [
        (vec!["plain.toml"], "plain.png"),
        (vec!["faded.toml"], "file.png"),
        (
            vec!["plain.toml", "--light-attenuation", "1,0,0.25"],
            "flag.png",
        ),
    ] {
        let mut all = vec!["render"];
        all.extend(args);
        all.extend(["-o", out]);
        assert_ok(&run(dir.path(), &all));
    }
    let read = |name: &str| Png::read(&dir.path().join(name));
    let (plain, file, flag) = (read("plain.png"), read("file.png"), read("flag.png"));
    assert_eq!(file, flag);
    let sum = |p: &Png| -> u64 { p.rgb.iter().map(|&c| u64::from(c)).sum() };
    assert!(
        sum(&file) < sum(&plain) * 3 / 4,
        "{} vs {}",
        sum(&file),
        sum(&plain)
    );

    let directional = "[[lights]]\nkind = \"directional\"\ndirection = [-1.0, -1.0, -1.0]\nattenuation = [1.0, 0.1, 0.0]\n";
    write(dir.path(), "bad.toml", directional);
    let out = run(dir.path(), &["render", "bad.toml", "-o", "bad.png"]);
    assert!(!out.status.success());
    assert!(
        stderr(&out).contains("lights[0].attenuation: only a point light has attenuation"),
        "{}",
        stderr(&out)
    );
}

/// A value of `p` other than its default, within its range, as a flag's
/// text and as the scene file's TOML.
fn another_value(p: &shadelab_core::params::Param) -> (String, String) {
    use shadelab_core::params::{Kind, Value};
    let near = |d: f64, step: f64| {
        if d + step <= p.max {
            d + step
        } else {
            (d + p.min) / 2.0
        }
    };
    match (p.kind, p.default.or(p.typical)) {
        (Kind::Bool, Some(Value::Bool(b))) => (String::new(), (!b).to_string()),
        (Kind::Number, Some(Value::Number(d))) => {
            let v = near(d, 0.5);
            (v.to_string(), format!("{v:?}"))
        }
        (Kind::Number, None) => {
            let v = p.min + (p.max - p.min) / 32.0;
            (v.to_string(), format!("{v:?}"))
        }
        (Kind::Integer, Some(Value::Number(d))) => {
            let v = near(d, 2.0) as i64;
            (v.to_string(), v.to_string())
        }
        (Kind::Rgb, _) => ("10,200,90".into(), "[10, 200, 90]".into()),
        (Kind::Vec3, Some(Value::Three(d))) => {
            let v = [near(d[0], 0.5), near(d[1], 0.25), near(d[2], 0.125)];
            (
                v.map(|c| c.to_string()).join(","),
                format!("[{:?}, {:?}, {:?}]", v[0], v[1], v[2]),
            )
        }
        other => panic!("{}: no value to try for {other:?}", p.key),
    }
}

#[test]
fn every_parameter_flag_sets_what_its_scene_file_key_sets() {
    let dir = tempfile::tempdir().unwrap();
    let base =
        "[model]\nsource = \"torus\"\n[render]\nwidth = 40\nheight = 30\nshading = \"phong\"\n";
    write(dir.path(), "base.toml", base);
    assert_ok(&run(dir.path(), &["render", "base.toml", "-o", "base.png"]));
    let plain = Png::read(&dir.path().join("base.png"));
    let mut tried = 0;
    for p in shadelab_core::params::all() {
        // The detail's range is each model's own (tests/input_errors.rs).
        if p.flag.is_empty() || p.key == "model.detail" {
            continue;
        }
        let (flag_value, toml_value) = another_value(p);
        let (section, key) = p.key.split_once('.').unwrap();
        let mut model = String::from("[model]\nsource = \"torus\"\n");
        let mut render = String::from("[render]\nwidth = 40\nheight = 30\nshading = \"phong\"\n");
        let mut other = String::new();
        let mut args = vec!["render".to_owned(), "base.toml".to_owned()];
        // A key that needs another (the palette's offset) is tried with it.
        if !p.needs.is_empty() {
            let needed = shadelab_core::params::get(p.needs);
            let (_, needed_key) = needed.key.split_once('.').unwrap();
            render.push_str(&format!("{needed_key} = 8\n"));
            args.extend([format!("--{}", needed.flag), "8".to_owned()]);
        }
        let line = format!("{key} = {toml_value}\n");
        match section {
            "model" => model.push_str(&line),
            "render" => render.push_str(&line),
            "lights" if key == "position" => {
                other.push_str(&format!("[[lights]]\nkind = \"point\"\n{line}"));
            }
            "lights" => other.push_str(&format!(
                "[[lights]]\nkind = \"point\"\nposition = [2.0, 2.0, 3.0]\n{line}"
            )),
            _ => other.push_str(&format!("[{section}]\n{line}")),
        }
        let scene = format!("{model}{render}{other}");
        write(dir.path(), "scene.toml", &scene);
        args.push(format!("--{}", p.flag));
        if !flag_value.is_empty() {
            args.push(flag_value.clone());
        }
        args.extend(["-o".to_owned(), "flag.png".to_owned()]);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        assert_ok(&run(dir.path(), &args));
        assert_ok(&run(
            dir.path(),
            &["render", "scene.toml", "-o", "file.png"],
        ));
        let (flag, file) = (
            Png::read(&dir.path().join("flag.png")),
            Png::read(&dir.path().join("file.png")),
        );
        assert_eq!(flag, file, "--{} {flag_value} against {}", p.flag, p.key);
        // Gouraud's specular acts in Gouraud shading only.
        if p.key != "render.gouraud_specular" {
            assert_ne!(flag, plain, "--{} {flag_value} changed nothing", p.flag);
        }
        tried += 1;
    }
    assert!(tried >= 18, "{tried}");
}
