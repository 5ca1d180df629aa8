//! The three panels in one call (`Engine::render_methods`, export
//! `shadelab_render_methods`): the same pixels and the same frame reports
//! as three engines drawing the three panels' texts, for built-in models,
//! a user's file and modes only the scanline rasterizer draws; the text's
//! own method's frame is the engine's last frame afterwards (the
//! instruments draw on it); a bad scene is refused and changes nothing.

mod common;

use common::rgba;
use shadelab_wasm::{abi, Engine, OverlaysRequest};

const OCTAHEDRON: &[u8] = b"v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n\
f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6\n";

const METHODS: [&str; 3] = ["flat", "gouraud", "phong"];

fn scene(model: &str, shading: &str, extra: &str) -> String {
    format!("[model]\n{model}\n[render]\nwidth = 96\nheight = 80\nshading = \"{shading}\"\n{extra}")
}

#[test]
fn three_panels_in_one_call_draw_what_three_engines_draw() {
    let mut together = Engine::new();
    together.load_file("octahedron.obj", OCTAHEDRON).unwrap();
    let mut apart: Vec<Engine> = (0..3).map(|_| Engine::new()).collect();
    for engine in &mut apart {
        engine.load_file("octahedron.obj", OCTAHEDRON).unwrap();
    }
    for model in [
        "source = \"teapot\"",
        "source = \"torus\"\nnormals = \"angle\"\ncrease_angle = 20",
        "source = \"octahedron.obj\"",
    ] {
        for extra in [
            "",
            "yaw = 33\npitch = -12\nzoom = 1.7\nspecular = \"blinn-phong\"\ncull_backfaces = false\ngouraud_specular = true\n",
            "interpolation = \"screen\"\n",
            "rasterizer = \"scanline\"\npolygons = \"whole\"\n",
        ] {
            for (own, own_method) in METHODS.into_iter().enumerate() {
                let toml = scene(model, own_method, extra);
                let frames = together.render_methods(&toml).unwrap();
                for (k, method) in METHODS.into_iter().enumerate() {
                    let text = scene(model, method, extra);
                    let frame = apart[k].render(&text).unwrap();
                    let want = apart[k].image().unwrap();
                    assert_eq!(frames[k], frame, "{text}");
                    assert_eq!(together.images()[k], rgba(want), "{text}");
                }
                // The text's own method's frame is the last frame.
                assert_eq!(together.image().unwrap(), apart[own].image().unwrap(), "{toml}");
                assert_eq!(together.rgba(), apart[own].rgba());
            }
        }
    }
    assert_eq!(together.counts().frames, 3 * 3 * 4 * 3);
}

#[test]
fn instruments_draw_on_the_own_methods_frame() {
    let toml = scene("source = \"sphere\"", "gouraud", "");
    let overlays = OverlaysRequest {
        overlays: "wireframe,light".into(),
    };
    let mut together = Engine::new();
    together.render_methods(&toml).unwrap();
    together.overlays(&overlays).unwrap();
    let mut alone = Engine::new();
    alone.render(&toml).unwrap();
    alone.overlays(&overlays).unwrap();
    assert_eq!(together.rgba(), alone.rgba());
}

#[test]
fn a_bad_scene_is_refused_and_changes_nothing() {
    let mut engine = Engine::new();
    let good = scene("source = \"cube\"", "phong", "");
    engine.render_methods(&good).unwrap();
    let (image, images) = (engine.image().unwrap().clone(), engine.images().to_vec());
    for bad in [
        scene("source = \"cube\"", "phong", "width = 0\n"),
        scene("source = \"nothing-here\"", "flat", ""),
        scene("source = \"cube\"", "phong", "palette_offset = 3\n"),
    ] {
        let err = engine.render_methods(&bad).unwrap_err();
        assert!(!err.0.is_empty());
        assert_eq!(engine.image().unwrap(), &image, "{bad}");
        assert_eq!(engine.images(), &images[..], "{bad}");
    }
}

#[test]
fn the_export_answers_three_frames_and_three_images() {
    let parse = |s: String| -> serde_json::Value { serde_json::from_str(&s).unwrap() };
    abi::set_input(b"[render]\nwidth = 20\nheight = 10\nshading = \"phong\"\n");
    assert_eq!(abi::shadelab_render_methods(), abi::OK);
    let answer = parse(abi::result_text());
    let frames = answer["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 3);
    for (k, frame) in frames.iter().enumerate() {
        assert_eq!(
            (frame["width"].as_u64(), frame["height"].as_u64()),
            (Some(20), Some(10))
        );
        assert_eq!(abi::shadelab_image_len(k), 20 * 10 * 4);
        assert!(!abi::shadelab_image(k).is_null());
    }
    // Flat lights per polygon, Gouraud per vertex, Phong per pixel.
    assert!(frames[0]["cost"]["per_polygon"].as_u64().unwrap() > 0);
    assert!(frames[1]["cost"]["per_vertex"].as_u64().unwrap() > 0);
    assert!(frames[2]["cost"]["per_pixel"].as_u64().unwrap() > 0);
    assert_eq!(abi::shadelab_image_len(3), 0);

    abi::set_input(b"[render]\nheight = 0\n");
    assert_eq!(abi::shadelab_render_methods(), abi::FAILED);
    assert!(parse(abi::result_text())["error"]
        .as_str()
        .unwrap()
        .contains("height"));
    abi::set_input(b"\xff");
    assert_eq!(abi::shadelab_render_methods(), abi::FAILED);
}

/// Two or three engines each drawing a part of the rows
/// (`Engine::render_methods_part`): the parts' rows, one under the other,
/// are the whole frames' pixels; each part's frame report is the whole
/// frame's but for its rows' pixel counts and flat's evaluations, which add
/// up to the frame's; a
/// mode only the scanline rasterizer draws is drawn whole by the first part
/// and not at all by the others.
#[test]
fn parts_of_the_rows_drawn_by_engines_of_their_own_make_the_frames() {
    let mut whole = Engine::new();
    for model in ["source = \"teapot\"", "source = \"sphere\""] {
        for extra in [
            "",
            "yaw = 33\npitch = -12\nzoom = 1.7\ncull_backfaces = false\n",
            "rasterizer = \"scanline\"\n",
        ] {
            let toml = scene(model, "phong", extra);
            let want = whole.render_methods(&toml).unwrap();
            let want_images = whole.images().to_vec();
            for parts in [2, 3] {
                let mut engines: Vec<Engine> = (0..parts).map(|_| Engine::new()).collect();
                let answers: Vec<_> = (0..parts)
                    .map(|k| {
                        let answer = engines[k as usize]
                            .render_methods_part(&toml, k, parts)
                            .unwrap();
                        (answer, engines[k as usize].images().to_vec())
                    })
                    .collect();
                for m in 0..3 {
                    let ((first, rows), _) = &answers[0];
                    if *rows == [0, 80] {
                        // Drawn whole (scanline) by the first part: it is
                        // the frame, and the others draw nothing.
                        assert_eq!(first[m], want[m], "{toml}");
                        assert_eq!(answers[0].1[m], want_images[m], "{toml}");
                        for ((_, rows), images) in &answers[1..] {
                            assert_eq!(*rows, [80, 80], "{toml}");
                            assert!(images[m].is_empty(), "{toml}");
                        }
                        continue;
                    }
                    let mut pixels = Vec::new();
                    let (mut fragments, mut covered, mut per_pixel, mut per_polygon) = (0, 0, 0, 0);
                    for ((frames, rows), images) in &answers {
                        assert_eq!(images[m].len(), 96 * 4 * (rows[1] - rows[0]) as usize);
                        assert_eq!(rows[0] as usize, pixels.len() / (96 * 4), "{toml}");
                        pixels.extend_from_slice(&images[m]);
                        let f = &frames[m];
                        assert_eq!((f.width, f.height, f.view), (96, 80, want[m].view));
                        assert_eq!(f.stats.rasterized, want[m].stats.rasterized);
                        assert_eq!(f.cost.per_vertex, want[m].cost.per_vertex);
                        fragments += f.stats.fragments_shaded;
                        covered += f.stats.covered_pixels;
                        per_pixel += f.cost.per_pixel;
                        per_polygon += f.cost.per_polygon;
                    }
                    assert_eq!(pixels, want_images[m], "{toml}, {parts} parts");
                    let w = &want[m];
                    assert_eq!(fragments, w.stats.fragments_shaded, "{toml}");
                    assert_eq!(covered, w.stats.covered_pixels, "{toml}");
                    assert_eq!(per_pixel, w.cost.per_pixel, "{toml}");
                    assert_eq!(per_polygon, w.cost.per_polygon, "{toml}");
                    let per_vertex = first[m].cost.per_vertex;
                    assert_eq!(
                        per_polygon + per_vertex + per_pixel,
                        w.stats.lighting_evaluations
                    );
                }
                let whole = answers[0].0 .1 == [0, 80];
                for (k, engine) in engines.iter().enumerate() {
                    let drew = k == 0 || !whole;
                    assert_eq!(engine.counts().frames, if drew { 3 } else { 0 });
                    // A part is no frame for the instruments.
                    assert!(engine.image().is_none());
                }
            }
        }
    }
    // More parts than runs of rows: the extra parts draw nothing.
    let tiny = "[render]\nwidth = 8\nheight = 12\n";
    let mut engine = Engine::new();
    let (_, rows) = engine.render_methods_part(tiny, 0, 2).unwrap();
    assert_eq!(rows[0], rows[1]);
    assert!(engine.images().iter().all(Vec::is_empty));
    let (_, rows) = engine.render_methods_part(tiny, 1, 2).unwrap();
    assert_eq!(rows, [0, 12]);
    let error = engine.render_methods_part(tiny, 2, 2).unwrap_err();
    assert!(error.to_string().contains("part 2 of 2"), "{error}");
    // Drawn whole by the first part, however few the rows.
    let tiny = "[render]\nwidth = 8\nheight = 12\nrasterizer = \"scanline\"\n";
    let (_, rows) = engine.render_methods_part(tiny, 0, 2).unwrap();
    assert_eq!(rows, [0, 12]);
    assert!(engine.images().iter().all(|i| i.len() == 8 * 12 * 4));
    let (_, rows) = engine.render_methods_part(tiny, 1, 2).unwrap();
    assert_eq!(rows, [12, 12]);
    assert!(engine.images().iter().all(Vec::is_empty));
}

#[test]
fn the_part_export_answers_rows_and_their_images() {
    let parse = |s: String| -> serde_json::Value { serde_json::from_str(&s).unwrap() };
    abi::set_input(b"[render]\nwidth = 20\nheight = 40\nshading = \"phong\"\n");
    assert_eq!(abi::shadelab_render_methods_part(1, 2), abi::OK);
    let answer = parse(abi::result_text());
    assert_eq!(answer["rows"], serde_json::json!([16, 40]));
    for k in 0..3 {
        assert_eq!(abi::shadelab_image_len(k), 20 * 24 * 4);
    }
    assert_eq!(answer["frames"][2]["height"], 40);
    assert_eq!(abi::shadelab_render_methods_part(2, 2), abi::FAILED);
}
