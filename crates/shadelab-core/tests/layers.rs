//! The core's layers depend one way, top to bottom (`docs/architecture.md`):
//!
//! | layer  | modules                                     | may use          |
//! |--------|---------------------------------------------|------------------|
//! | frame  | `frame`, `probe`                            | everything below |
//! | raster | `raster` (scanline, tiled)                  | shade, simd, data|
//! | shade  | `shade` (methods, reflection model)         | simd, data       |
//! | simd   | `simd`                                      | data             |
//! | data   | scene, light, mesh, camera, clip, colour, … | data             |
//!
//! This test reads every source file of the crate and checks each
//! `crate::module` it names in code against the table, so a cycle cannot
//! come back unnoticed. A new module must be given its layer here. A
//! second test keeps the window transform and clipping in the frame: the
//! rasterizers receive polygons already clipped and in window space.

use std::fs;
use std::path::{Path, PathBuf};

/// The layer of each top-level module; higher uses lower, never the reverse.
fn layer(module: &str) -> Option<u8> {
    Some(match module {
        "frame" | "probe" => 4,
        "raster" => 3,
        "shade" => 2,
        "simd" => 1,
        "camera" | "choice" | "clip" | "color" | "cores" | "image" | "light" | "limits"
        | "mesh" | "models" | "normals" | "palette" | "params" | "scene" | "text" => 0,
        _ => return None,
    })
}

fn sources(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            sources(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The top-level modules a line of code names as `crate::module`, also
/// inside `use crate::{a, b::c}`.
fn named_modules(code: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = code;
    while let Some(at) = rest.find("crate::") {
        let before = rest[..at].chars().next_back();
        rest = &rest[at + "crate::".len()..];
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == '$') {
            continue; // `$crate::` in a macro, or part of a longer name
        }
        if let Some(group) = rest.strip_prefix('{') {
            // The first name of each item at the group's own depth.
            let (mut depth, mut expect_name) = (0, true);
            for (i, c) in group.char_indices() {
                match c {
                    '{' => depth += 1,
                    '}' if depth == 0 => break,
                    '}' => depth -= 1,
                    ',' if depth == 0 => expect_name = true,
                    c if expect_name && (c.is_alphanumeric() || c == '_') => {
                        expect_name = false;
                        out.push(
                            group[i..]
                                .chars()
                                .take_while(|c| c.is_alphanumeric() || *c == '_')
                                .collect(),
                        );
                    }
                    _ => {}
                }
            }
        } else {
            out.push(
                rest.chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect(),
            );
        }
    }
    out
}

#[test]
fn modules_depend_only_on_layers_below_or_their_own() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    sources(&src, &mut files);
    files.sort();
    let mut wrong = Vec::new();
    let mut checked = 0;
    for file in &files {
        let relative = file.strip_prefix(&src).unwrap();
        let first = relative.components().next().unwrap();
        let module = first.as_os_str().to_str().unwrap().trim_end_matches(".rs");
        if module == "lib" {
            continue; // the table of contents names everything
        }
        let own = layer(module)
            .unwrap_or_else(|| panic!("module `{module}` has no layer in tests/layers.rs"));
        for (number, line) in fs::read_to_string(file).unwrap().lines().enumerate() {
            let code = line.trim_start();
            if code.starts_with("//") {
                continue; // documentation may point anywhere
            }
            for used in named_modules(code) {
                checked += 1;
                match layer(&used) {
                    Some(other) if other <= own => {}
                    Some(other) => wrong.push(format!(
                        "{}:{}: `{module}` (layer {own}) uses `{used}` (layer {other})",
                        relative.display(),
                        number + 1
                    )),
                    None => wrong.push(format!(
                        "{}:{}: `crate::{used}` is not a module path: name the module \
                         (crate::module::item) so its layer can be checked",
                        relative.display(),
                        number + 1
                    )),
                }
            }
        }
    }
    assert!(
        checked > 50,
        "only {checked} uses found: is the scan broken?"
    );
    assert!(
        wrong.is_empty(),
        "uses against the layers:\n{}",
        wrong.join("\n")
    );
}

/// The code lines (not comments) of the source files under `src/dir`, with
/// their file and line number.
fn code_lines(dir: &str) -> Vec<(String, usize, String)> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    sources(&src.join(dir), &mut files);
    files.sort();
    let mut out = Vec::new();
    for file in &files {
        let name = file.strip_prefix(&src).unwrap().display().to_string();
        for (number, line) in fs::read_to_string(file).unwrap().lines().enumerate() {
            if !line.trim_start().starts_with("//") {
                out.push((name.clone(), number + 1, line.to_string()));
            }
        }
    }
    out
}

/// What only the frame does to a frame's positions and polygons.
const FRAME_ONLY: [&str; 6] = [
    "clip_polygon(",
    "is_inside(",
    "to_window(",
    "project_vertices(",
    "guard_band(",
    ".projection(",
];

#[test]
fn the_window_transform_and_clipping_are_the_frames_alone() {
    let raster = code_lines("raster");
    assert!(
        raster.len() > 1000,
        "only {} lines under src/raster",
        raster.len()
    );
    let wrong: Vec<String> = raster
        .iter()
        .filter(|(_, _, line)| FRAME_ONLY.iter().any(|call| line.contains(call)))
        .map(|(file, number, line)| format!("{file}:{number}: {}", line.trim()))
        .collect();
    assert!(
        wrong.is_empty(),
        "the raster layer transforms or clips (the frame's job, frame/):\n{}",
        wrong.join("\n")
    );
    // And the frame does each of them.
    let frame = code_lines("frame");
    for call in FRAME_ONLY {
        assert!(
            frame.iter().any(|(_, _, line)| line.contains(call)),
            "`{call}` not found under src/frame: is the scan broken?"
        );
    }
}

#[test]
fn the_scan_finds_grouped_and_nested_uses() {
    assert_eq!(
        named_modules("use crate::{scene::Scene, shade::{Lighting, Terms}};"),
        ["scene", "shade"]
    );
    assert_eq!(
        named_modules("x: crate::raster::Foo, $crate::choice::X"),
        ["raster"]
    );
    assert_eq!(
        named_modules("let a = mycrate::frame::x;"),
        Vec::<String>::new()
    );
}
