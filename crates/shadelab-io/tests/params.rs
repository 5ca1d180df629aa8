//! The scene file against the core's table of parameters, entry by entry:
//! every default (or typical value) is accepted, and a value just outside
//! the range is refused with a message naming the key. Generated from the
//! table, so a new parameter is tested as soon as it is declared.

use std::path::Path;

use shadelab_core::params::{self, Kind, Open, Param, Value};
use shadelab_io::SceneFile;

/// `value` of `p` as TOML.
fn toml_value(p: &Param, value: &Value) -> String {
    let one = |x: f64| match p.kind {
        Kind::Integer | Kind::Rgb => format!("{}", x as i64),
        _ => format!("{x:?}"),
    };
    match *value {
        Value::Number(x) => one(x),
        Value::Three(c) => format!("[{}]", c.map(one).join(", ")),
        Value::Bool(b) => b.to_string(),
        Value::Text(t) => format!("{t:?}"),
    }
}

/// A scene setting `p` to `value` (TOML text): a light's key in a light of
/// the kind that takes it, and the key `p` needs set to its smallest value.
fn scene(p: &Param, value: &str) -> String {
    let (section, name) = p.key.split_once('.').expect("keys are section.name");
    if section == "lights" {
        let kind = if name == "direction" {
            "directional"
        } else {
            "point"
        };
        let position = if kind == "point" && name != "position" {
            "position = [2, 2, 3]\n"
        } else {
            ""
        };
        return format!("[[lights]]\nkind = \"{kind}\"\n{position}{name} = {value}\n");
    }
    let mut text = format!("[{section}]\n{name} = {value}\n");
    if section == "camera" && name != "eye" {
        // A [camera] must say where the eye is.
        text.push_str("eye = [0, 0, 3]\n");
    }
    if !p.needs.is_empty() {
        let needed = params::get(p.needs);
        let (needed_section, needed_name) = needed.key.split_once('.').unwrap();
        assert_eq!(
            needed_section, section,
            "{} needs a key of its own section",
            p.key
        );
        text.push_str(&format!("{needed_name} = {}\n", needed.min));
    }
    text
}

fn resolve(text: &str) -> Result<(), String> {
    SceneFile::parse(text, "test.toml")
        .and_then(|f| f.resolve(Path::new(".")))
        .map(|_| ())
        .map_err(|e| e.to_string())
}

/// The key as a message names it: the first light's for a light's key.
fn shown_key(p: &Param) -> String {
    p.key.replacen("lights.", "lights[0].", 1)
}

/// Values just outside `p`'s range, as TOML.
fn outside(p: &Param) -> Vec<String> {
    let step = |bound: f64| match p.kind {
        Kind::Integer | Kind::Rgb => 1.0,
        _ => (bound.abs() * 1e-3).max(1e-3),
    };
    let (below, above) = (p.min - step(p.min), p.max + step(p.max));
    let number = |x: f64| toml_value(p, &Value::Number(x));
    let three = |x: f64| toml_value(p, &Value::Three([p.min.max(0.0), x, p.min.max(0.0)]));
    // An open bound is itself outside.
    let open = match p.open {
        Open::Neither => vec![],
        Open::Min => vec![number(p.min)],
        Open::Both => vec![number(p.min), number(p.max)],
    };
    match p.kind {
        Kind::Number | Kind::Integer => [vec![number(below), number(above)], open].concat(),
        Kind::Rgb | Kind::Vec3 => vec![three(below), three(above)],
        Kind::Bool | Kind::Text => Vec::new(),
    }
}

#[test]
fn the_scene_file_accepts_every_default_and_refuses_every_range_edge_crossed() {
    for p in params::all() {
        if let Some(value) = p.default.as_ref().or(p.typical.as_ref()) {
            let text = scene(p, &toml_value(p, value));
            if let Err(e) = resolve(&text) {
                panic!("{}'s default is refused: {e}\n{text}", p.key);
            }
        }
        for value in outside(p) {
            let text = scene(p, &value);
            match resolve(&text) {
                Ok(()) => panic!("{} = {value} is accepted\n{text}", p.key),
                Err(e) => assert!(e.contains(&shown_key(p)), "{e} does not name {}", p.key),
            }
        }
    }
}

#[test]
fn range_errors_say_the_tables_range() {
    for (text, message) in [
        (
            "[render]\nzoom = 200.0\n",
            "render.zoom: must be 0.1..=100, got 200",
        ),
        (
            "[material]\nshininess = -1.0\n",
            "material.shininess: must be 0..=10000, got -1",
        ),
        (
            "[model]\ncrease_angle = 181.0\n",
            "model.crease_angle: must be 0..=180 degrees, got 181",
        ),
        (
            "[ambient]\nintensity = 101.0\n",
            "ambient.intensity: must be 0..=100, got 101",
        ),
        (
            "[render]\npalette_shades = 2\npalette_offset = 255\n",
            "render.palette_offset: must be 0..=254, got 255",
        ),
    ] {
        assert_eq!(resolve(text).unwrap_err(), message);
    }
}
