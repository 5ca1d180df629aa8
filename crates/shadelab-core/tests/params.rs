//! The table of parameters (`shadelab_core::params`): every default within
//! its range, the core's defaults, the messages, and the schema the page
//! reads.

use serde_json::{json, Value as Json};
use shadelab_core::params::{all, get, schema, schema_json, Kind, Value};
use shadelab_core::Shading;

#[test]
fn every_default_and_typical_value_is_within_its_range() {
    for p in all() {
        assert!(p.min <= p.max, "{}", p.key);
        assert!(!p.help.is_empty() && p.help.ends_with('.'), "{}", p.key);
        assert!(
            p.default.is_some() == p.absent.is_empty(),
            "{}: a default or what absence means, not both",
            p.key
        );
        for v in p.default.iter().chain(&p.typical) {
            match (p.kind, *v) {
                (Kind::Number, Value::Number(x)) => {
                    assert!(p.check(x as f32).is_ok(), "{}", p.key)
                }
                (Kind::Integer, Value::Number(x)) => {
                    assert_eq!(x.fract(), 0.0, "{}", p.key);
                    assert!(p.check_whole(x as i64).is_ok(), "{}", p.key);
                }
                (Kind::Rgb, Value::Three(c)) => {
                    assert!(p.check_rgb(c.map(|x| x as i64)).is_ok(), "{}", p.key)
                }
                (Kind::Vec3, Value::Three(c)) => {
                    assert!(p.check_vec3(c.map(|x| x as f32)).is_ok(), "{}", p.key)
                }
                (Kind::Bool, Value::Bool(_)) => {}
                (Kind::Text, Value::Text(t)) => assert!(!t.is_empty()),
                (kind, v) => panic!("{}: a {kind:?} with a default {v:?}", p.key),
            }
        }
    }
    let mut keys: Vec<_> = all().iter().map(|p| p.key).collect();
    keys.sort_unstable();
    keys.dedup();
    assert_eq!(keys.len(), all().len(), "keys repeat");
}

#[test]
fn bounds_are_the_decimals_written() {
    assert_eq!(get("render.zoom").min, 0.1);
    assert_eq!(get("lights.position").max, 1e30);
}

#[test]
fn the_defaults_are_the_cores() {
    assert_eq!(get("material.kd").default_rgb(), [200, 60, 60]);
    assert_eq!(get("material.shininess").default_number(), 32.0);
    assert_eq!(get("render.width").default_number(), 800.0);
    assert!(get("render.cull_backfaces").default_bool());
}

#[test]
fn messages_say_the_range_and_the_value() {
    let crease = get("model.crease_angle");
    assert_eq!(
        crease.check(200.0).unwrap_err(),
        "must be 0..=180 degrees, got 200"
    );
    assert_eq!(
        get("render.zoom").check(0.0).unwrap_err(),
        "must be 0.1..=100, got 0"
    );
    assert_eq!(
        get("material.ka").check_rgb([0, 256, 0]).unwrap_err(),
        "each channel must be 0..=255, got 256"
    );
    assert_eq!(
        get("lights.position")
            .check_vec3([0.0, f32::NAN, 1.0])
            .unwrap_err(),
        "must be finite and within ±1e30, got [0, NaN, 1]"
    );
    assert!(get("ambient.intensity").check(f32::NAN).is_err());
}

#[test]
fn the_schema_round_trips_and_holds_every_key_and_choice() {
    let text = schema_json();
    let read: Json = serde_json::from_str(&text).unwrap();
    assert_eq!(read, schema());
    let params = read["params"].as_array().unwrap();
    assert_eq!(params.len(), all().len());
    for (p, j) in all().iter().zip(params) {
        assert_eq!(j["key"], p.key);
        assert_eq!(j["kind"], p.kind.name());
        assert_eq!(j["min"].as_f64(), Some(p.min), "{}", p.key);
        assert_eq!(j["max"].as_f64(), Some(p.max), "{}", p.key);
        assert_eq!(j["help"], p.help);
        assert_eq!(j["default"].is_null(), p.default.is_none(), "{}", p.key);
    }
    let kd = params.iter().find(|j| j["key"] == "material.kd").unwrap();
    assert_eq!(kd["default"], json!([200, 60, 60]));
    let choices = read["choices"].as_array().unwrap();
    let shading = choices
        .iter()
        .find(|c| c["key"] == "render.shading")
        .unwrap();
    assert_eq!(shading["default"], "phong");
    let names: Vec<_> = shading["values"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v["name"].clone())
        .collect();
    assert_eq!(names, Shading::ALL.map(|s| json!(s.name())));
}

#[test]
fn every_parameter_has_a_label_its_parts_and_a_flag_of_its_own() {
    let mut flags = std::collections::HashSet::new();
    for p in all() {
        assert!(!p.label.is_empty(), "{} has no label", p.key);
        let three = matches!(p.kind, Kind::Rgb | Kind::Vec3);
        assert_eq!(p.parts.len(), if three { 3 } else { 0 }, "{}", p.key);
        if !p.flag.is_empty() {
            assert!(flags.insert(p.flag), "{} repeats --{}", p.key, p.flag);
            assert!(
                p.flag.bytes().all(|b| b.is_ascii_lowercase() || b == b'-'),
                "--{}",
                p.flag
            );
        }
    }
}
