#![no_main]
//! Scene TOML: parsed and resolved against built-in models only (no file
//! access: the base directory does not exist), never a panic.
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(scene) = shadelab_io::SceneFile::parse(text, "fuzz.toml") else {
        return;
    };
    // Only built-in models: a path would read the file system.
    let builtin = scene
        .model
        .source
        .as_deref()
        .is_none_or(|s| shadelab_core::builtin_model_info(s).is_some());
    if builtin {
        let _ = scene.resolve(std::path::Path::new("/nonexistent-fuzz-dir"));
    }
});
