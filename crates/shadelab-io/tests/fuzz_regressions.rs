//! The fuzz targets' seed and regression corpus (`fuzz/corpus/`) replayed
//! through the same entry points as the targets, as ordinary tests: no file
//! there may make a loader or the scene parser panic. (`.ci/run` also replays
//! it through the instrumented targets themselves, rasterizer targets
//! included.) Each crash the fuzzers found also has a test named after it.

use std::path::{Path, PathBuf};

use shadelab_io::{parse_gltf, parse_obj, parse_obj_file, parse_ply, parse_stl, SceneFile};

fn corpus(target: &str) -> Vec<(PathBuf, Vec<u8>)> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fuzz/corpus")
        .join(target);
    let mut files: Vec<(PathBuf, Vec<u8>)> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| {
            let path = e.unwrap().path();
            let bytes = std::fs::read(&path).unwrap();
            (path, bytes)
        })
        .collect();
    files.sort();
    assert!(!files.is_empty(), "{} is empty", dir.display());
    files
}

#[test]
fn mesh_corpora_load_or_fail_cleanly() {
    for (path, bytes) in corpus("obj") {
        let (obj, mtl) = match bytes.iter().position(|&b| b == 0) {
            Some(k) => (&bytes[..k], Some(&bytes[k + 1..])),
            None => (&bytes[..], None),
        };
        let Ok(text) = std::str::from_utf8(obj) else {
            continue;
        };
        let plain = parse_obj(text, "corpus.obj").map_err(|e| e.to_string());
        let file = parse_obj_file(text, "corpus.obj", &mut |_| {
            mtl.map(|m| String::from_utf8_lossy(m).into_owned())
        })
        .map_err(|e| e.to_string());
        assert_eq!(plain, file.map(|f| f.mesh), "{}", path.display());
    }
    for (_, bytes) in corpus("stl") {
        let _ = parse_stl(&bytes, "corpus.stl");
    }
    for (_, bytes) in corpus("ply") {
        let _ = parse_ply(&bytes, "corpus.ply");
    }
    for (_, bytes) in corpus("gltf") {
        let _ = parse_gltf(&bytes, "corpus.gltf", None);
    }
}

#[test]
fn scene_corpus_resolves_or_fails_cleanly() {
    for (_, bytes) in corpus("scene") {
        let Ok(text) = std::str::from_utf8(&bytes) else {
            continue;
        };
        if let Ok(scene) = SceneFile::parse(text, "corpus.toml") {
            let _ = scene.resolve(Path::new("/nonexistent-corpus-dir"));
        }
    }
}

/// Found by the `gltf` target: `gltf-json` 1.4.1's validation indexes the
/// accessors with a primitive's `POSITION` before checking it, and panicked
/// when it named an accessor that does not exist.
#[test]
fn gltf_position_naming_a_missing_accessor_is_an_error() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fuzz/corpus/gltf/regression-position-names-missing-accessor.gltf");
    let bytes = std::fs::read(path).unwrap();
    let error = parse_gltf(&bytes, "found.gltf", None)
        .unwrap_err()
        .to_string();
    assert!(error.contains("POSITION names accessor"), "{error}");
}

fn corpus_file(path: &str) -> Vec<u8> {
    std::fs::read(
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../fuzz/corpus")
            .join(path),
    )
    .unwrap()
}

/// A PLY element with no properties and a count of 2^64 − 1 took no bytes
/// per element and was read past for ever.
#[test]
fn ply_element_without_properties_is_an_error() {
    let error = parse_ply(
        &corpus_file("ply/regression-element-without-properties.ply"),
        "x.ply",
    )
    .unwrap_err()
    .to_string();
    assert!(
        error.contains("`junk`") && error.contains("no properties"),
        "{error}"
    );
}

/// A 49 KB glTF file drawing one mesh from 2700 nodes: 17,280,000 triangles
/// after instancing, refused from the JSON's counts before any buffer is
/// decoded (it used to gather gigabytes first).
#[test]
fn gltf_instancing_beyond_the_triangle_limit_is_an_error() {
    let bytes = corpus_file("gltf/regression-instancing-beyond-the-triangle-limit.gltf");
    let error = parse_gltf(&bytes, "x.gltf", None).unwrap_err().to_string();
    assert!(
        error.contains("17280000 triangles after instancing (2700 nodes draw a mesh)"),
        "{error}"
    );
}

/// `position = [1, 2, 3, 4]` lost its fourth number in silence.
#[test]
fn scene_array_with_an_extra_element_is_an_error() {
    let text = String::from_utf8(corpus_file("scene/regression-extra-array-element.toml")).unwrap();
    let error = SceneFile::parse(&text, "x.toml").unwrap_err().to_string();
    assert!(
        error.contains("lights[0].position") && error.contains("line 3"),
        "{error}"
    );
}

/// Files whose lines end with a lone CR read as if they ended with LF.
#[test]
fn cr_line_ends_read_as_lf() {
    let lf = |bytes: Vec<u8>| -> Vec<u8> {
        bytes
            .into_iter()
            .map(|b| if b == b'\r' { b'\n' } else { b })
            .collect()
    };
    let ply = corpus_file("ply/regression-cr-line-ends.ply");
    assert_eq!(
        parse_ply(&ply, "x.ply").unwrap(),
        parse_ply(&lf(ply.clone()), "x.ply").unwrap()
    );
    let stl = corpus_file("stl/regression-cr-line-ends.stl");
    assert_eq!(
        parse_stl(&stl, "x.stl").unwrap(),
        parse_stl(&lf(stl.clone()), "x.stl").unwrap()
    );
    let obj = corpus_file("obj/regression-cr-line-ends.obj");
    let (text, library) = obj.split_at(obj.iter().position(|&b| b == 0).unwrap());
    let text = std::str::from_utf8(text).unwrap();
    let library = String::from_utf8_lossy(&library[1..]).into_owned();
    let file = parse_obj_file(text, "x.obj", &mut |_| Some(library.clone())).unwrap();
    assert_eq!(file.mesh.polygon_count(), 4);
    let blue = file.material.expect("the library's material").kd.unwrap();
    assert_eq!((blue.r, blue.g, blue.b), (0.0, 0.0, 1.0));
    let scene = String::from_utf8(corpus_file("scene/regression-cr-line-ends.toml")).unwrap();
    assert_eq!(
        SceneFile::parse(&scene, "x.toml").unwrap(),
        SceneFile::parse(&scene.replace('\r', "\n"), "x.toml").unwrap()
    );
}
