//! The user's file is parsed by one panel's engine and handed to the others
//! as the mesh it became: the engines that adopt it draw exactly the pixels
//! of the one that parsed it, nothing they are sent can make them panic, and
//! a frame that changes only the camera prepares nothing again.

use std::path::Path;

use shadelab_core::Image;
use shadelab_wasm::{abi, Engine};

const OCTAHEDRON: &str = "v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n\
f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6\n";

/// A quad, a pentagon and triangles, with normals of awkward lengths at
/// every corner and two smoothing groups.
const WITH_NORMALS: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 1.5 0.3\nv -0.4 0.7 0.6\n\
vn 0.3 0.1 0.9\nvn -0.2 0.7 3.1\nvn 0.01 0.02 0.03\nvn 5 1 7\n\
s 1\nf 1//1 2//2 3//3 4//4\ns 2\nf 4//2 3//4 5//1\nf 1//3 4//1 6//4\n";

fn scene(source: &str, shading: &str, extra: &str) -> String {
    format!("[model]\nsource = \"{source}\"\n[render]\nwidth = 120\nheight = 96\nshading = \"{shading}\"\n{extra}")
}

fn image(engine: &mut Engine, toml: &str) -> Image {
    engine.render(toml).unwrap();
    engine.image().unwrap().clone()
}

/// Engine `a` parses `name`; a second engine adopts the mesh `a` shares.
fn parsed_and_adopted(name: &str, bytes: &[u8]) -> (Engine, Engine) {
    let mut a = Engine::new();
    let parsed = a.load_file(name, bytes).unwrap();
    let shared = a.shared_file().expect("a file is loaded");
    let mut b = Engine::new();
    let adopted = b.adopt_file(name, &shared).unwrap();
    assert_eq!(parsed, adopted);
    (a, b)
}

fn assert_same_pixels(name: &str, bytes: &[u8], extras: &[&str]) {
    let (mut a, mut b) = parsed_and_adopted(name, bytes);
    for shading in ["flat", "gouraud", "phong"] {
        for extra in extras {
            let toml = scene(name, shading, extra);
            assert!(image(&mut a, &toml) == image(&mut b, &toml), "{toml}");
        }
    }
    assert_eq!((a.counts().files_parsed, a.counts().files_adopted), (1, 0));
    assert_eq!((b.counts().files_parsed, b.counts().files_adopted), (0, 1));
}

const EXTRAS: [&str; 4] = [
    "yaw = 30\npitch = 20\n",
    "rasterizer = \"scanline\"\npolygons = \"whole\"\n",
    "yaw = 200\ncull_backfaces = false\n",
    "[ambient]\nintensity = 0.6\n",
];

#[test]
fn an_adopted_mesh_draws_the_parsed_ones_pixels() {
    assert_same_pixels("octahedron.obj", OCTAHEDRON.as_bytes(), &EXTRAS);
}

#[test]
fn file_normals_and_smoothing_groups_survive_the_trip_exactly() {
    let with_choices = [
        "yaw = 20\n",
        "rasterizer = \"scanline\"\n",
        "gouraud_specular = true\n",
    ];
    assert_same_pixels("normals.obj", WITH_NORMALS.as_bytes(), &with_choices);
    let (_, mut b) = parsed_and_adopted("normals.obj", WITH_NORMALS.as_bytes());
    // Computed normals honour the smoothing groups in the adopted mesh too.
    let (mut a, _) = parsed_and_adopted("normals.obj", WITH_NORMALS.as_bytes());
    let toml = scene("normals.obj", "phong", "").replace(
        "[render]",
        "normals = \"angle\"\ncrease_angle = 80\n[render]",
    );
    assert!(image(&mut a, &toml) == image(&mut b, &toml));
}

#[test]
fn the_shared_meshes_draw_alike() {
    let beside = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/models");
    let files = ["suzanne.obj", "stanford-bunny.obj"];
    let Some(shared) = [beside.as_path(), Path::new("/work/shared/models")]
        .into_iter()
        .find(|d| files.iter().all(|f| d.join(f).exists()))
    else {
        eprintln!(
            "note: {} is missing; the shared meshes were not tried",
            beside.display()
        );
        return;
    };
    for f in files {
        let bytes = std::fs::read(shared.join(f)).unwrap();
        assert_same_pixels(f, &bytes, &["yaw = 35\n"]);
    }
}

#[test]
fn malformed_shared_bytes_are_errors_and_the_previous_file_stays() {
    let mut a = Engine::new();
    a.load_file("normals.obj", WITH_NORMALS.as_bytes()).unwrap();
    let good = a.shared_file().unwrap();
    let mut b = Engine::new();
    b.adopt_file("normals.obj", &good).unwrap();
    let toml = scene("normals.obj", "phong", "");
    let before = image(&mut b, &toml);
    let word = |bytes: &mut Vec<u8>, k: usize, w: u32| {
        bytes[4 * k..4 * k + 4].copy_from_slice(&w.to_le_bytes())
    };
    let mut cases: Vec<(&str, Vec<u8>)> = vec![
        ("empty", Vec::new()),
        ("truncated", good[..good.len() - 4].to_vec()),
        ("longer", [&good[..], &[0, 0, 0, 0]].concat()),
        ("not a multiple of four", good[..good.len() - 1].to_vec()),
    ];
    let mut magic = good.clone();
    word(&mut magic, 0, 7);
    cases.push(("magic", magic));
    let mut huge = good.clone();
    word(&mut huge, 1, u32::MAX);
    cases.push(("huge count", huge));
    // Offsets start after the header (6), positions (6·3) and corners (4+3+3).
    let offsets = 6 + 18 + 10;
    let mut order = good.clone();
    word(&mut order, offsets + 1, 9);
    cases.push(("offsets out of order", order));
    let mut index = good.clone();
    word(&mut index, 6 + 18, 99);
    cases.push(("index out of range", index));
    let mut nan = good.clone();
    word(&mut nan, 6, f32::NAN.to_bits());
    cases.push(("a position not finite", nan));
    let mut normal = good.clone();
    let normal_indices = offsets + 4 + 4 * 3;
    word(&mut normal, normal_indices, 1000);
    cases.push(("normal index out of range", normal));
    for (what, bytes) in cases {
        let err = b.adopt_file("other.obj", &bytes).unwrap_err().to_string();
        assert!(
            err.contains("malformed") || err.contains("mesh"),
            "{what}: {err}"
        );
        assert!(image(&mut b, &toml) == before, "{what} changed the model");
    }
    assert!(b
        .adopt_file("teapot", &good)
        .unwrap_err()
        .0
        .contains("built-in"));
    assert_eq!(b.counts().files_adopted, 1);
}

#[test]
fn a_camera_change_prepares_nothing_again() {
    let mut engine = Engine::new();
    engine
        .load_file("octahedron.obj", OCTAHEDRON.as_bytes())
        .unwrap();
    image(&mut engine, &scene("octahedron.obj", "phong", ""));
    assert_eq!(engine.counts().models_prepared, 1);
    for yaw in [5, 10, 15] {
        let extra = format!("yaw = {yaw}\nzoom = 1.5\n[material]\nshininess = 12.0\n");
        image(&mut engine, &scene("octahedron.obj", "phong", &extra));
    }
    // The first of them changed the material (read as a whole); the other
    // two only turned the camera (not read again).
    let counts = engine.counts();
    assert_eq!(
        (
            counts.models_prepared,
            counts.frames,
            counts.scenes_read,
            counts.camera_turns
        ),
        (1, 4, 2, 2)
    );
    // The same text again is not even looked at.
    image(
        &mut engine,
        &scene(
            "octahedron.obj",
            "phong",
            "yaw = 15\nzoom = 1.5\n[material]\nshininess = 12.0\n",
        ),
    );
    assert_eq!(
        (engine.counts().scenes_read, engine.counts().camera_turns),
        (2, 2)
    );
    // Other normals are another model.
    let toml =
        scene("octahedron.obj", "phong", "").replace("[render]", "normals = \"area\"\n[render]");
    image(&mut engine, &toml);
    assert_eq!(engine.counts().models_prepared, 2);
    assert_eq!(engine.counts().files_parsed, 1);
}

#[test]
fn a_turned_camera_draws_what_a_scene_read_anew_draws() {
    let texts: Vec<String> = [
        "yaw = 0.0\npitch = 0.0\nzoom = 1.0\n",
        "yaw = 12.5\npitch = 0.0\nzoom = 1.0\n",
        "yaw = 12.5\npitch = -30.0\nzoom = 2.25\n",
        "yaw = 400\npitch = 89.0\nzoom = 8.0\n",
        // Refused: the error names the key, and the last good frame stays.
        "yaw = 400\npitch = 89.0\nzoom = 0.001\n",
        "yaw = 1e1\npitch = 89.0\nzoom = 0.25\n",
    ]
    .iter()
    .map(|camera| scene("teapot", "gouraud", camera))
    .collect();
    let mut turning = Engine::new();
    for (k, toml) in texts.iter().enumerate() {
        let mut fresh = Engine::new();
        match fresh.render(toml) {
            Ok(_) => {
                assert!(
                    image(&mut turning, toml) == *fresh.image().unwrap(),
                    "{toml}"
                );
            }
            Err(e) => {
                let before = turning.image().unwrap().clone();
                assert_eq!(turning.render(toml).unwrap_err(), e, "{toml}");
                assert!(e.0.contains("render.zoom"), "{e}");
                assert!(*turning.image().unwrap() == before);
            }
        }
        assert_eq!(turning.counts().models_prepared, 1, "frame {k}");
    }
    // Frames 1, 2 and 3 turned the camera; frame 0 was read, so was the
    // refused one (to say why), and so was the next, which had no good text
    // to be compared with.
    let counts = turning.counts();
    assert_eq!((counts.camera_turns, counts.scenes_read), (3, 3));
}

#[test]
fn the_exports_share_and_adopt() {
    let name = b"octahedron.obj";
    abi::set_input(&[&name[..], OCTAHEDRON.as_bytes()].concat());
    assert_eq!(abi::shadelab_load_file(name.len()), abi::OK);
    assert_eq!(abi::shadelab_share_file(), abi::OK);
    let shared = abi::output_bytes();
    assert!(shared.starts_with(b"SLM1"));
    abi::set_input(&[&b"again.obj"[..], &shared].concat());
    assert_eq!(abi::shadelab_adopt_file(9), abi::OK);
    let summary: serde_json::Value = serde_json::from_str(&abi::result_text()).unwrap();
    assert_eq!(summary["name"], "again.obj");
    assert_eq!(summary["triangles"], 8);
    assert_eq!(abi::shadelab_counts(), abi::OK);
    let counts: serde_json::Value = serde_json::from_str(&abi::result_text()).unwrap();
    assert_eq!(
        (
            counts["files_parsed"].as_u64(),
            counts["files_adopted"].as_u64()
        ),
        (Some(1), Some(1))
    );
    abi::set_input(b"x.objSLM0");
    assert_eq!(abi::shadelab_adopt_file(5), abi::FAILED);
    assert!(abi::result_text().contains("malformed"));
}
