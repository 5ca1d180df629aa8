#![no_main]
//! OBJ text: any input gives a mesh or a typed error, never a panic.
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        let _ = shadelab_io::parse_obj(text, "fuzz.obj");
    }
});
