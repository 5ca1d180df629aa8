#![no_main]
//! Scene TOML: parsed and resolved against built-in models only (no file
//! access: the base directory does not exist), never a panic. Lone CR line
//! ends read as LF ones: the same text with every LF made CR parses alike.
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let parsed = shadelab_io::SceneFile::parse(text, "fuzz.toml");
    if !text.contains('\r') {
        let cr = shadelab_io::SceneFile::parse(&text.replace('\n', "\r"), "fuzz.toml");
        match (&parsed, &cr) {
            (Ok(a), Ok(b)) => assert_eq!(a, b),
            (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string()),
            _ => panic!("CR line ends changed whether the scene parses"),
        }
    }
    let Ok(scene) = parsed else {
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
