//! Messages and answers for hostile or unusual values (issue items 5, 13,
//! 14, 18, 19 and 20): control characters are escaped and long tokens cut;
//! enormous coordinates are framed or refused clearly; arrays of the wrong
//! length and empty values name their key; negative numbers say the range
//! allowed; a message repeats the value the user gave.

mod support;

use support::*;

/// Runs `render` with the scene `text` (and `args`), expecting exit 2.
fn scene_error(text: &str, args: &[&str]) -> String {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "scene.toml", text);
    let mut all = vec!["render", "scene.toml", "--size", "16x16", "-o", "out.png"];
    all.extend_from_slice(args);
    let out = run(dir.path(), &all);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(!stderr(&out).contains("panicked"), "{}", stderr(&out));
    stderr(&out)
}

#[test]
fn control_characters_are_escaped_and_long_tokens_cut() {
    let dir = tempfile::tempdir().unwrap();
    let escape = "\u{1b}[2J\u{1b}]0;owned\u{7}\u{202e}";
    // A token of a model file.
    write(dir.path(), "esc.obj", format!("v 0 0 {escape}\nf 1 1 1\n"));
    // A ten-megabyte token.
    let huge = "9".repeat(10 << 20) + "x";
    write(dir.path(), "huge.obj", format!("v 0 0 {huge}\nf 1 1 1\n"));
    // A file name, a scene value and a command-line value.
    let name = format!("{escape}.obj");
    write(dir.path(), &name, "v 0 0 0\n");
    write(
        dir.path(),
        "scene.toml",
        format!("[model]\nsource = \"{}\"\n", "\\u001b[31m.obj"),
    );
    for args in [
        vec!["render", "--model", "esc.obj", "-o", "o.png"],
        vec!["render", "--model", "huge.obj", "-o", "o.png"],
        vec!["render", "--model", name.as_str(), "-o", "o.png"],
        vec!["render", "scene.toml", "-o", "o.png"],
        vec!["render", "--shading", escape, "-o", "o.png"],
        vec!["render", "--size", escape, "-o", "o.png"],
    ] {
        let out = run(dir.path(), &args);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {}", stderr(&out));
        let err = stderr(&out);
        assert!(
            !err.chars()
                .any(|c| c.is_control() && c != '\n' || c == '\u{202e}'),
            "{args:?}: unescaped control characters in {err:?}"
        );
        assert!(err.len() < 4096, "{args:?}: a {} byte message", err.len());
    }
    let out = run(dir.path(), &["render", "--model", "esc.obj", "-o", "o.png"]);
    assert!(stderr(&out).contains("\\u{1b}[2J"), "{}", stderr(&out));
    let out = run(
        dir.path(),
        &["render", "--model", "huge.obj", "-o", "o.png"],
    );
    assert!(stderr(&out).contains("more characters"), "{}", stderr(&out));
}

/// The tetrahedron with every coordinate multiplied by `scale`.
fn tetra_scaled(scale: &str) -> String {
    TETRA
        .lines()
        .map(|line| match line.strip_prefix("v ") {
            Some(coords) => {
                let scaled: Vec<String> = coords
                    .split(' ')
                    .map(|c| {
                        if c == "1" {
                            scale.to_owned()
                        } else {
                            c.to_owned()
                        }
                    })
                    .collect();
                format!("v {}\n", scaled.join(" "))
            }
            None => format!("{line}\n"),
        })
        .collect()
}

#[test]
fn huge_and_tiny_models_are_framed_and_refused_clearly_under_a_camera() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "unit.obj", TETRA);
    // Powers of two: the framed model is exactly the unit one.
    write(
        dir.path(),
        "huge.obj",
        tetra_scaled(&format!("{}", 2f64.powi(70))),
    );
    write(
        dir.path(),
        "tiny.obj",
        tetra_scaled(&format!("{:e}", 2f64.powi(-100))),
    );
    write(dir.path(), "big.obj", tetra_scaled("1e20"));
    let render = |model: &str, out: &str| {
        assert_ok(&run(
            dir.path(),
            &[
                "render", "--model", model, "--size", "64x64", "--yaw", "30", "-o", out,
            ],
        ));
        std::fs::read(dir.path().join(out)).unwrap()
    };
    let unit = render("unit.obj", "unit.png");
    assert_eq!(render("huge.obj", "huge.png"), unit);
    assert_eq!(render("tiny.obj", "tiny.png"), unit);
    // 1e20 is not a power of two times 1: the same picture but for rounding.
    let big = render("big.obj", "big.png");
    let decode = |bytes: &[u8]| {
        let mut r = png::Decoder::new(std::io::Cursor::new(bytes.to_vec()))
            .read_info()
            .unwrap();
        let mut buf = vec![0; r.output_buffer_size()];
        r.next_frame(&mut buf).unwrap();
        buf
    };
    let drawn = decode(&big).chunks(3).filter(|p| *p != [0, 0, 0]).count();
    assert!(drawn > 500, "only {drawn} pixels drawn");
    // Drawn in its own coordinates, a model that large is a clear error.
    write(
        dir.path(),
        "camera.toml",
        "[model]\nsource = \"big.obj\"\n[camera]\neye = [0, 0, 3e20]\nnear = 1e19\nfar = 1e21\n",
    );
    let out = run(dir.path(), &["render", "camera.toml", "-o", "c.png"]);
    assert_input_error(&out, &["model.source", "1e20", "[camera]"]);
}

#[test]
fn arrays_of_the_wrong_length_name_their_key_and_line() {
    let err = scene_error(
        "[[lights]]\nkind = \"point\"\nposition = [1, 2, 3, 4]\n",
        &[],
    );
    for needle in ["lights[0].position", "line 3", "exactly 3"] {
        assert!(err.contains(needle), "{needle:?} in {err}");
    }
    let err = scene_error("[camera]\neye = [0, 0, 3, 0]\n", &[]);
    assert!(
        err.contains("camera.eye") && err.contains("line 2"),
        "{err}"
    );
    let err = scene_error("[material]\nkd = [255, 0]\n", &[]);
    assert!(
        err.contains("material.kd") && err.contains("exactly 3"),
        "{err}"
    );
    let err = scene_error("[render]\nbackground = [0, 0, 0, 0, 0]\n", &[]);
    assert!(err.contains("render.background"), "{err}");
}

#[test]
fn empty_values_name_their_key() {
    for (text, key) in [
        ("[model]\nsource = \"\"\n", "model.source"),
        ("[render]\nshading = \"\"\n", "render.shading"),
        ("[model]\nnormals = \"\"\n", "model.normals"),
        ("[[lights]]\nkind = \"\"\n", "lights[0].kind"),
        ("[render]\nrasterizer = \"\"\n", "render.rasterizer"),
        ("[camera]\neye = []\n", "camera.eye"),
    ] {
        let err = scene_error(text, &[]);
        assert!(err.contains(key), "{text:?} should name {key}: {err}");
    }
    let dir = tempfile::tempdir().unwrap();
    let out = run(dir.path(), &["render", "--model", "", "-o", "o.png"]);
    assert_input_error(&out, &["--model", "must not be empty"]);
    let out = run(dir.path(), &["render", "-o", ""]);
    assert_input_error(&out, &["--output", "must not be empty"]);
}

#[test]
fn negative_numbers_are_told_the_range_allowed() {
    let dir = tempfile::tempdir().unwrap();
    for (args, range) in [
        (vec!["render", "-o", "o.png", "--size", "-5x5"], "1..=16384"),
        (
            vec!["render", "-o", "o.png", "--detail", "-3"],
            "model.detail: must be 0..=1024",
        ),
        (
            vec!["render", "-o", "o.png", "--ambient", "-1,0,0"],
            "0..=255",
        ),
        (vec!["render", "-o", "o.png", "--kd", "0,-5,0"], "0..=255"),
        (
            vec!["render", "-o", "o.png", "--crease-angle", "-5"],
            "0..=180",
        ),
        (
            vec!["render", "-o", "o.png", "--fixed-point", "-1"],
            "1..=30",
        ),
        (vec!["render", "-o", "o.png", "--palette", "-2"], "2..=256"),
        (
            vec!["render", "-o", "o.png", "--shininess", "-1"],
            "0..=10000",
        ),
        (vec!["explain", "--pixel", "-1,5"], "≥ 0"),
        (vec!["profile", "-o", "o.png", "--row", "-1"], "≥ 0"),
        (vec!["accuracy", "--details", "6,-12"], "≥ 0"),
        (vec!["quad", "-o", "o.png", "--size", "-9"], "9..=1024"),
        (vec!["cost", "--runs", "-1"], "1..=1000"),
        (vec!["view", "--port", "-1"], "0..=65535"),
        (vec!["bench", "--threads", "-2"], "1..=256"),
        (vec!["bench", "--frames", "-1"], "1..=100000"),
        (vec!["bench", "--budget", "-1"], "0..=3600"),
        (vec!["bench", "--warmup-time", "-1"], "0..=3600"),
        (vec!["bench", "--warmup-time", "nan"], "0..=3600"),
        (vec!["bench", "--size", "-5x5"], "1..=16384"),
    ] {
        let out = run(dir.path(), &args);
        assert_input_error(&out, &[range]);
        assert!(!stderr(&out).contains("unexpected argument"), "{args:?}");
    }
}

#[test]
fn messages_repeat_the_value_given() {
    let err = scene_error("[camera]\neye = [0, 0, 1e-30]\n", &[]);
    assert!(err.contains("1e-30") && !err.contains("equals"), "{err}");
    let err = scene_error("[camera]\neye = [0, 0, 1e20]\nfar = 1e21\n", &[]);
    assert!(err.contains("1e20") && !err.contains("equals"), "{err}");
    let err = scene_error(
        "[camera]\neye = [0, 0, 3]\nfov_y = 179.9999\n[render]\nzoom = 0.1\n",
        &[],
    );
    for needle in ["render.zoom", "0.1", "179.9999"] {
        assert!(err.contains(needle), "{needle:?} in {err}");
    }
    assert!(!err.contains("got 180"), "{err}");
    let err = scene_error(
        "[camera]\neye = [0, 0, 3]\nnear = 1e-40\nfar = 1e-41\n",
        &[],
    );
    assert!(err.contains("near = 1e-40"), "{err}");
    let err = scene_error("[camera]\neye = [0, 0, 3]\nfar = -1e-40\n", &[]);
    assert!(
        err.contains("camera.far") && err.contains("got -1e-40"),
        "{err}"
    );
}
