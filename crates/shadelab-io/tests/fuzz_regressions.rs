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
