#![no_main]
//! glTF JSON or GLB bytes (no external buffers): a mesh or a typed error.
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = shadelab_io::parse_gltf(data, "fuzz.glb", None);
});
