#![no_main]
//! OBJ text, and a material library after the first NUL byte: any input
//! gives a mesh or a typed error, never a panic, and the library never makes
//! loading fail. Lone CR line ends read as LF ones: the same text with every
//! LF made CR gives the same mesh or the same error (line numbers included).
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let (obj, mtl) = match data.iter().position(|&b| b == 0) {
        Some(k) => (&data[..k], Some(&data[k + 1..])),
        None => (data, None),
    };
    let Ok(text) = std::str::from_utf8(obj) else {
        return;
    };
    let plain = shadelab_io::parse_obj(text, "fuzz.obj");
    let with_library = shadelab_io::parse_obj_file(text, "fuzz.obj", &mut |_| {
        mtl.map(|m| String::from_utf8_lossy(m).into_owned())
    });
    if !text.contains('\r') {
        let cr = shadelab_io::parse_obj(&text.replace('\n', "\r"), "fuzz.obj");
        match (&plain, &cr) {
            (Ok(a), Ok(b)) => assert_eq!(a, b),
            (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string()),
            _ => panic!("CR line ends changed whether the file loads"),
        }
    }
    match (plain, with_library) {
        (Ok(mesh), Ok(file)) => assert_eq!(mesh, file.mesh),
        (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string()),
        _ => panic!("the material library changed whether the file loads"),
    }
});
