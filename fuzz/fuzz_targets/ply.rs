#![no_main]
//! PLY bytes: a mesh or a typed error, never a panic.
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = shadelab_io::parse_ply(data, "fuzz.ply");
});
