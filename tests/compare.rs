//! `shadelab compare` (still images) and `shadelab models` end to end.

mod support;

use support::*;

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
