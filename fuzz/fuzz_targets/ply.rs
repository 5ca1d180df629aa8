#![no_main]
//! PLY bytes: a mesh or a typed error, never a panic (nor a hang: an element
//! without properties used to be read past for ever). An ASCII file with
//! every LF made CR reads alike.
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let plain = shadelab_io::parse_ply(data, "fuzz.ply");
    let ascii = data.starts_with(b"ply\nformat ascii ");
    if ascii && !data.contains(&b'\r') {
        let cr: Vec<u8> = data.iter().map(|&b| if b == b'\n' { b'\r' } else { b }).collect();
        let cr = shadelab_io::parse_ply(&cr, "fuzz.ply");
        match (&plain, &cr) {
            (Ok(a), Ok(b)) => assert_eq!(a, b),
            (Err(_), Err(_)) => {}
            _ => panic!("CR line ends changed whether the file loads"),
        }
    }
});
