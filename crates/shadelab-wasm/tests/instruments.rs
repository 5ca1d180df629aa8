//! The instruments as a panel's engine answers them, run natively: each
//! answer equals what the `shadelab-lab` functions behind the command line
//! (`explain`, `profile`, `errors`, `--overlay`, `quad`) give for the same
//! scene text, so the viewer and the command line cannot drift apart.

mod common;

use std::path::Path;

use common::rgba;
use shadelab_core::{render, RenderOptions, Scene, Shading};
use shadelab_io::SceneFile;
use shadelab_lab::{
    draw_overlays, error_maps, exact_image, heat_bar, heat_scale, inspect, inspection_text,
    profile, quad_study, CurveKind, Lang, Overlays, ProfileLine, Surface, Texts,
};
use shadelab_wasm::{
    abi, Engine, ErrorsRequest, HeatRequest, InspectRequest, OverlaysRequest, ProfileRequest,
    QuadRequest, TextsRequest,
};

fn scene_text(model: &str, shading: &str, extra: &str) -> String {
    format!(
        "[model]\n{model}\n[render]\nwidth = 120\nheight = 100\nshading = \"{shading}\"\n{extra}"
    )
}

/// The scene as `shadelab` reads the same text.
fn resolved(toml: &str) -> (SceneFile, Scene, RenderOptions) {
    let file = SceneFile::parse(toml, "scene").unwrap();
    let (scene, options) = file.resolve(Path::new("")).unwrap();
    (file, scene, options)
}

#[test]
fn the_inspector_tells_what_shadelab_explain_tells() {
    let mut engine = Engine::new();
    for (extra, pixel) in [
        ("", (60, 45)),
        (
            "interpolation = \"screen\"\npolygons = \"whole\"\nspecular = \"blinn-phong\"\n",
            (70, 40),
        ),
        ("fixed_point_bits = 6\npalette_shades = 8\n", (55, 50)),
        ("", (2, 2)),
    ] {
        let toml = scene_text("source = \"sphere\"\ndetail = 8", "phong", extra);
        let (_, scene, options) = resolved(&toml);
        for lang in Lang::ALL {
            let texts = Texts::new(lang);
            let want = inspection_text(
                &inspect(&scene, &options, pixel.0, pixel.1, &Shading::ALL).unwrap(),
                &texts,
            );
            // All three from one engine, and each from its own panel's engine.
            let all = engine
                .inspect(&InspectRequest {
                    scene: toml.clone(),
                    x: pixel.0,
                    y: pixel.1,
                    lang: lang.code().into(),
                    methods: Some(vec!["flat".into(), "gouraud".into(), "phong".into()]),
                })
                .unwrap();
            let joined = std::iter::once(all.header.clone())
                .chain(all.methods.iter().map(|m| m.text.clone()))
                .collect::<Vec<_>>()
                .join("\n");
            assert_eq!(joined, want, "{toml} {lang:?}");
            for (k, shading) in ["flat", "gouraud", "phong"].into_iter().enumerate() {
                let panel = engine
                    .inspect(&InspectRequest {
                        scene: toml.replace("\"phong\"\n", &format!("\"{shading}\"\n")),
                        x: pixel.0,
                        y: pixel.1,
                        lang: lang.code().into(),
                        methods: None,
                    })
                    .unwrap();
                assert_eq!(panel.header, all.header);
                assert_eq!(panel.methods, vec![all.methods[k].clone()]);
            }
        }
        // The marks: the colour drawn, the scanline through the pixel, P left of O left of Q.
        let answer = engine
            .inspect(&InspectRequest {
                scene: toml.clone(),
                x: pixel.0,
                y: pixel.1,
                lang: String::new(),
                methods: None,
            })
            .unwrap();
        engine.render(&toml).unwrap();
        let drawn = engine.image().unwrap().pixel(pixel.0, pixel.1).0;
        let m = &answer.methods[0];
        assert_eq!(m.color, drawn);
        if m.covered {
            assert_eq!(m.row, Some(pixel.1));
            let (p, q) = (m.p.unwrap(), m.q.unwrap());
            let o = f64::from(pixel.0) + 0.5;
            assert!(p[0] <= o && o <= q[0], "{p:?} {o} {q:?}");
            assert!(m.walked.len() >= 3);
        } else {
            assert!(m.walked.is_empty() && m.row.is_none());
        }
    }
    let err = engine
        .inspect(&InspectRequest {
            scene: scene_text("source = \"cube\"", "flat", ""),
            x: 120,
            y: 0,
            lang: "en".into(),
            methods: None,
        })
        .unwrap_err();
    assert_eq!(err.0, "pixel (120, 0) is outside the 120x100 image");
}

#[test]
fn profiles_are_the_command_line_profiles() {
    let mut engine = Engine::new();
    for (model, line) in [
        ("source = \"sphere\"\ndetail = 10", ProfileLine::Row(50)),
        (
            "source = \"torus\"",
            ProfileLine::Segment {
                from: (10.5, 20.5),
                to: (100.5, 80.5),
            },
        ),
        ("source = \"teapot\"", ProfileLine::Row(60)),
    ] {
        let toml = scene_text(model, "gouraud", "interpolation = \"screen\"\n");
        let (file, scene, options) = resolved(&toml);
        let surface = Surface::for_builtin(
            file.model.source.as_deref().unwrap(),
            file.model.detail,
            true,
        );
        let want = profile(&scene, &options, line, surface.as_ref()).unwrap();
        let (row, segment) = match line {
            ProfileLine::Row(y) => (Some(y), None),
            ProfileLine::Segment { from, to } => (None, Some([from.0, from.1, to.0, to.1])),
        };
        let got = engine
            .profile(&ProfileRequest {
                scene: toml.clone(),
                row,
                line: segment,
            })
            .unwrap();
        assert_eq!(
            got.pixels,
            want.pixels.iter().map(|&(x, y)| [x, y]).collect::<Vec<_>>()
        );
        assert_eq!(got.curves.len(), want.curves.len());
        assert_eq!(got.curves.len(), if surface.is_some() { 4 } else { 3 });
        for (g, w) in got.curves.iter().zip(&want.curves) {
            let kind = match w.kind {
                CurveKind::Method(s) => s.name(),
                CurveKind::Exact => "exact",
            };
            assert_eq!(g.kind, kind);
            assert_eq!(g.values, w.values);
            assert_eq!(g.derivative, w.derivative);
            assert_eq!(g.edges, w.edges());
            assert_eq!(g.polygon_edges, w.polygon_edges());
        }
    }
    let toml = scene_text("source = \"cube\"", "flat", "");
    for (row, line, message) in [
        (Some(100), None, "row 100 is outside the 120x100 image"),
        (None, None, "a profile takes either a row or a line"),
        (
            Some(1),
            Some([0.0; 4]),
            "a profile takes either a row or a line",
        ),
        (
            None,
            Some([0.0, 0.0, f64::NAN, 1.0]),
            "is not a line in the image",
        ),
    ] {
        let err = engine
            .profile(&ProfileRequest {
                scene: toml.clone(),
                row,
                line,
            })
            .unwrap_err();
        assert!(err.0.contains(message), "{}", err.0);
    }
}

#[test]
fn error_maps_are_the_command_line_error_maps() {
    let mut engine = Engine::new();
    for (model, extra) in [
        ("source = \"sphere\"\ndetail = 12", ""),
        (
            "source = \"cone\"",
            "yaw = 20\npitch = 30\nrasterizer = \"scanline\"\n",
        ),
        (
            "source = \"torus\"\ndetail = 10",
            "gouraud_specular = true\n",
        ),
    ] {
        let compare = scene_text(model, "phong", extra);
        let (file, scene, options) = resolved(&compare);
        let surface = Surface::for_builtin(
            file.model.source.as_deref().unwrap(),
            file.model.detail,
            true,
        )
        .unwrap();
        let (exact, maps) = error_maps(&scene, &options, &surface).unwrap();
        let largest = maps.iter().map(|m| m.map.max).fold(0.0, f32::max);
        let scale = heat_scale(largest);
        for m in &maps {
            let toml = compare.replace("\"phong\"\n", &format!("\"{}\"\n", m.shading.name()));
            engine.render(&toml).unwrap();
            let answer = engine
                .errors(&ErrorsRequest {
                    scale: Some(scale),
                    exact: true,
                    overlays: String::new(),
                    bar: Some([12, 200]),
                })
                .unwrap();
            assert_eq!(answer.mean, m.map.mean);
            assert_eq!(answer.max, m.map.max);
            assert_eq!(answer.max_at, m.map.max_at.map(|(x, y)| [x, y]));
            assert_eq!(
                (answer.compared, answer.mesh_only, answer.surface_only),
                (m.map.compared, m.map.mesh_only, m.map.surface_only)
            );
            assert_eq!(answer.scale, scale);
            let names: Vec<_> = answer.images.iter().map(|i| i.name).collect();
            assert_eq!(names, ["heat", "exact", "bar"]);
            assert_eq!(engine.images()[2], rgba(&heat_bar(12, 200)));
            let heat = m.map.heat_image(scale, &exact, options.background);
            assert_eq!(engine.images()[0], rgba(&heat));
            assert_eq!(
                engine.images()[1],
                rgba(&exact_image(&exact, options.background))
            );
            // Without a scale, its own round number; then coloured again on another.
            let own = engine
                .errors(&ErrorsRequest {
                    scale: None,
                    exact: false,
                    overlays: String::new(),
                    bar: None,
                })
                .unwrap();
            assert_eq!(own.scale, heat_scale(m.map.max));
            assert_eq!(own.images.len(), 1);
            let again = engine
                .heat(&HeatRequest {
                    scale: 7.5,
                    overlays: String::new(),
                })
                .unwrap();
            assert_eq!(again.scale, 7.5);
            assert_eq!(
                engine.images()[0],
                rgba(&m.map.heat_image(7.5, &exact, options.background))
            );
            // Overlays over the heat map are those of the command line.
            engine
                .heat(&HeatRequest {
                    scale,
                    overlays: "wireframe".into(),
                })
                .unwrap();
            let mut with = heat.clone();
            let wire = Overlays::parse("wireframe").unwrap();
            let panel_options = RenderOptions {
                shading: m.shading,
                ..options
            };
            draw_overlays(&mut with, &scene, &panel_options, wire).unwrap();
            assert_eq!(engine.images()[0], rgba(&with));
        }
    }
    let mut engine = Engine::new();
    assert_eq!(
        engine
            .errors(&ErrorsRequest {
                scale: None,
                exact: false,
                overlays: String::new(),
                bar: None,
            })
            .unwrap_err()
            .0,
        "no frame has been rendered yet"
    );
    engine
        .render(&scene_text("source = \"teapot\"", "phong", ""))
        .unwrap();
    let err = engine
        .errors(&ErrorsRequest {
            scale: None,
            exact: false,
            overlays: String::new(),
            bar: None,
        })
        .unwrap_err();
    assert!(
        err.0.contains("\"teapot\" has no exact surface"),
        "{}",
        err.0
    );
    engine
        .render(&scene_text("source = \"sphere\"", "phong", ""))
        .unwrap();
    for scale in [0.0, -1.0, f32::NAN] {
        assert!(engine
            .errors(&ErrorsRequest {
                scale: Some(scale),
                exact: false,
                overlays: String::new(),
                bar: Some([0, 10]),
            })
            .is_err());
    }
    // A new frame forgets the last frame's map.
    assert!(engine
        .heat(&HeatRequest {
            scale: 1.0,
            overlays: String::new()
        })
        .is_err());
}

#[test]
fn overlays_are_those_of_shadelab_render() {
    let mut engine = Engine::new();
    for list in [
        "wireframe",
        "face-normals",
        "vertex-normals",
        "light",
        "all",
    ] {
        for shading in ["flat", "phong"] {
            let toml = scene_text("source = \"torus\"\ndetail = 10", shading, "pitch = 30\n");
            let (_, scene, options) = resolved(&toml);
            let (mut want, _) = render(&scene, &options).unwrap();
            draw_overlays(&mut want, &scene, &options, Overlays::parse(list).unwrap()).unwrap();
            engine.render(&toml).unwrap();
            let plain = engine.rgba().to_vec();
            // An instrument request about another scene in between changes nothing.
            engine
                .inspect(&InspectRequest {
                    scene: scene_text("source = \"cube\"", "flat", ""),
                    x: 1,
                    y: 1,
                    lang: String::new(),
                    methods: None,
                })
                .unwrap();
            engine
                .overlays(&OverlaysRequest {
                    overlays: list.into(),
                })
                .unwrap();
            assert_eq!(engine.image().unwrap(), &want, "{list} {shading}");
            assert_eq!(engine.rgba(), rgba(&want));
            assert_ne!(engine.rgba(), plain, "{list} drew something");
        }
    }
    let err = engine
        .overlays(&OverlaysRequest {
            overlays: "grid".into(),
        })
        .unwrap_err();
    assert!(err.0.contains("unknown overlay \"grid\""), "{}", err.0);
}

#[test]
fn the_quad_study_is_the_command_line_one() {
    let mut engine = Engine::new();
    let answer = engine
        .quad(&QuadRequest {
            angle: 30.0,
            size: 101,
            curve: vec![0.0, 45.0, 90.0],
        })
        .unwrap();
    let want = &quad_study(&[30.0], 101).unwrap()[0];
    assert_eq!(answer.whole_centre, want.whole_centre);
    assert_eq!(answer.fans_centre, want.fans_centre);
    assert_eq!(engine.images()[0], rgba(&want.whole));
    assert_eq!(engine.images()[1], rgba(&want.fans));
    // Upright, the centre takes a quarter of the bright vertex; on a corner, none or half.
    assert!(
        (answer.curve[0][1] - 0.25).abs() < 0.02,
        "{:?}",
        answer.curve
    );
    assert!(
        (answer.curve[1][1] - 0.25).abs() > 0.2,
        "{:?}",
        answer.curve
    );
    assert!(answer.curve.iter().all(|c| (c[2] - 0.5).abs() < 0.02));
    for size in [0, 2, 513] {
        assert!(engine
            .quad(&QuadRequest {
                angle: 0.0,
                size,
                curve: vec![]
            })
            .is_err());
    }
}

#[test]
fn texts_come_in_four_languages_with_the_same_ids() {
    let en = Engine::texts(&TextsRequest { lang: "en".into() }).unwrap();
    assert!(en["about.gouraud"].starts_with("Gouraud shading evaluates"));
    for lang in ["ru", "sk-SK", "cs"] {
        let other = Engine::texts(&TextsRequest { lang: lang.into() }).unwrap();
        assert_eq!(
            other.keys().collect::<Vec<_>>(),
            en.keys().collect::<Vec<_>>()
        );
        assert_ne!(other["about.gouraud"], en["about.gouraud"]);
    }
    assert!(Engine::texts(&TextsRequest { lang: "de".into() })
        .unwrap_err()
        .0
        .contains("unknown language \"de\""));
}

#[test]
fn instrument_exports_speak_json() {
    let parse = |s: String| -> serde_json::Value { serde_json::from_str(&s).unwrap() };
    let scene = scene_text("source = \"sphere\"", "gouraud", "");
    let request = serde_json::json!({ "scene": scene, "x": 60, "y": 50, "lang": "cs" });
    abi::set_input(request.to_string().as_bytes());
    assert_eq!(abi::shadelab_inspect(), abi::OK);
    let answer = parse(abi::result_text());
    assert!(answer["header"]
        .as_str()
        .unwrap()
        .starts_with("Pixel (60, 50)"));
    assert!(answer["methods"][0]["text"]
        .as_str()
        .unwrap()
        .starts_with("== Gouraudovo stínování"));

    abi::set_input(scene.as_bytes());
    assert_eq!(abi::shadelab_render(), abi::OK);
    assert!(
        parse(abi::result_text())["cost"]["per_vertex"]
            .as_u64()
            .unwrap()
            > 0
    );
    abi::set_input(br#"{"scale": 50, "exact": true}"#);
    assert_eq!(abi::shadelab_errors(), abi::OK);
    let answer = parse(abi::result_text());
    assert_eq!(answer["images"][1]["name"], "exact");
    assert_eq!(abi::shadelab_image_len(0), 120 * 100 * 4);
    assert_eq!(abi::shadelab_image_len(1), 120 * 100 * 4);
    assert_eq!(abi::shadelab_image_len(2), 0);
    assert!(abi::shadelab_image(2).is_null());

    abi::set_input(br#"{"overlays": "wireframe", "colour": 1}"#);
    assert_eq!(abi::shadelab_overlays(), abi::FAILED);
    let error = parse(abi::result_text())["error"]
        .as_str()
        .unwrap()
        .to_owned();
    assert!(
        error.starts_with("bad request: unknown field `colour`"),
        "{error}"
    );

    abi::set_input(br#"{"lang": "sk"}"#);
    assert_eq!(abi::shadelab_texts(), abi::OK);
    assert_eq!(
        parse(abi::result_text())["method.flat"],
        "Konštantné tieňovanie"
    );
}
