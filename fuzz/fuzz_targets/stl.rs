#![no_main]
//! STL bytes, ASCII or binary: a mesh or a typed error, never a panic. An
//! ASCII file with every LF made CR reads alike.
use libfuzzer_sys::fuzz_target;

/// Whether the length matches the binary triangle count at byte 80, which
/// makes a file binary whatever its first word.
fn sized_as_binary(data: &[u8]) -> bool {
    data.len() >= 84 && {
        let count = u32::from_le_bytes([data[80], data[81], data[82], data[83]]);
        84 + 50 * u64::from(count) == data.len() as u64
    }
}

fuzz_target!(|data: &[u8]| {
    let plain = shadelab_io::parse_stl(data, "fuzz.stl");
    if data.starts_with(b"solid") && !data.contains(&b'\r') && !sized_as_binary(data) {
        let cr: Vec<u8> = data.iter().map(|&b| if b == b'\n' { b'\r' } else { b }).collect();
        if sized_as_binary(&cr) {
            return;
        }
        let cr = shadelab_io::parse_stl(&cr, "fuzz.stl");
        if let (Ok(a), Ok(b)) = (&plain, &cr) {
            assert_eq!(a, b);
        }
        assert_eq!(plain.is_ok(), cr.is_ok(), "CR line ends changed whether the file loads");
    }
});
