#![no_main]
//! STL bytes, ASCII or binary: a mesh or a typed error, never a panic.
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = shadelab_io::parse_stl(data, "fuzz.stl");
});
