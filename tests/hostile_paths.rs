//! Files named by files, and files that are not files (issue items 1 and
//! 11): a glTF file reads only inside its folder and never shows what lies
//! outside; an OBJ file's `mtllib` outside its folder or not a regular file
//! is passed over with a warning; scene and model inputs that are FIFOs,
//! devices or directories are refused at once, and every read is capped.

mod support;

use std::path::Path;
use std::process::Stdio;
use std::time::Duration;

use support::*;

const SOON: Duration = Duration::from_secs(30);

/// A folder `model/` holding `model.gltf` whose buffer URI is `uri`, beside
/// a file `secret.bin` outside it whose bytes would make a triangle.
fn gltf_setup(dir: &Path, uri: &str, extra: &str) -> std::path::PathBuf {
    std::fs::create_dir_all(dir.join("model")).unwrap();
    // Marker bytes that a message must never repeat, then a triangle.
    let mut secret = b"TOPSECRETTOPSECRETTOPSECRETTOPSECRE".to_vec();
    secret.push(b'T');
    assert_eq!(secret.len(), 36);
    write(dir, "secret.bin", &secret);
    write(dir, "model/triangle.bin", triangle_buffer());
    write(dir, "model/model.gltf", gltf_doc(uri, 36, 3, 1, 1, extra))
}

fn render_model(dir: &Path, model: &Path) -> std::process::Output {
    let model = model.to_str().unwrap();
    run_within(
        command(
            dir,
            &[
                "render", "--model", model, "--size", "16x16", "-o", "out.png",
            ],
        ),
        SOON,
    )
}

#[test]
fn gltf_buffers_outside_the_folder_are_refused_without_showing_them() {
    let dir = tempfile::tempdir().unwrap();
    let absolute = dir.path().join("secret.bin").display().to_string();
    let encoded = absolute.replace('/', "%2F");
    for uri in [
        "../secret.bin".to_owned(),
        "sub/../../secret.bin".to_owned(),
        absolute.clone(),
        encoded,
        "file:///etc/passwd".to_owned(),
        "link.bin".to_owned(),
    ] {
        let model = gltf_setup(dir.path(), &uri, "");
        // A link inside the folder that points out of it.
        let _ = std::os::unix::fs::symlink(
            dir.path().join("secret.bin"),
            dir.path().join("model/link.bin"),
        );
        let out = render_model(dir.path(), &model);
        assert_input_error(&out, &["model.gltf", "buffer 0"]);
        let err = stderr(&out);
        assert!(!err.contains("TOPSECRET"), "{uri}: {err}");
        assert!(
            err.contains("outside") || err.contains("only relative"),
            "{uri}: {err}"
        );
    }
}

#[test]
fn gltf_images_outside_the_folder_are_refused_and_inside_ones_are_not() {
    let dir = tempfile::tempdir().unwrap();
    let model = gltf_setup(
        dir.path(),
        "triangle.bin",
        r#""images":[{"uri":"../../../../etc/passwd"}]"#,
    );
    let out = render_model(dir.path(), &model);
    assert_input_error(&out, &["image 0", "../../../../etc/passwd", "outside"]);
    // Inside the folder, a data: URI, and a missing texture (never read) are fine.
    for extra in [
        r#""images":[{"uri":"texture.png"}]"#,
        r#""images":[{"uri":"data:image/png;base64,AAAA"}]"#,
    ] {
        let model = gltf_setup(dir.path(), "triangle.bin", extra);
        assert_ok(&render_model(dir.path(), &model));
    }
    let model = gltf_setup(dir.path(), &data_uri(&triangle_buffer()), "");
    assert_ok(&render_model(dir.path(), &model));
}

/// A tetrahedron that takes its colour from `lib.mtl`'s material `green`.
fn tetra_with_material() -> String {
    format!("mtllib lib.mtl\nusemtl green\n{TETRA}")
}

/// The most common colour of the drawn (non-black) pixels of `out.png`.
fn main_colour(dir: &Path) -> [u8; 3] {
    let bytes = std::fs::read(dir.join("out.png")).unwrap();
    let mut reader = png::Decoder::new(std::io::Cursor::new(bytes))
        .read_info()
        .unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    let mut green = 0;
    let mut red = 0;
    for p in buf[..info.buffer_size()].chunks(3) {
        if p[1] > p[0] {
            green += 1;
        } else if p[0] > p[1] {
            red += 1;
        }
    }
    if green > red {
        [0, 255, 0]
    } else {
        [255, 0, 0]
    }
}

#[test]
fn a_material_library_outside_the_folder_or_not_a_file_is_passed_over_with_a_warning() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("model")).unwrap();
    write(dir.path(), "outside.mtl", "newmtl green\nKd 0 1 0\n");
    let model = dir.path().join("model/tetra.obj");
    // Inside: read and used.
    write(dir.path(), "model/lib.mtl", "newmtl green\nKd 0 1 0\n");
    write(dir.path(), "model/tetra.obj", tetra_with_material());
    let out = render_model(dir.path(), &model);
    assert_ok(&out);
    assert!(!stderr(&out).contains("warning"), "{}", stderr(&out));
    assert_eq!(main_colour(dir.path()), [0, 255, 0]);
    std::fs::remove_file(dir.path().join("model/lib.mtl")).unwrap();

    let outside = dir.path().join("outside.mtl").display().to_string();
    let fifo = dir.path().join("model/fifo.mtl");
    mkfifo(&fifo);
    std::os::unix::fs::symlink(
        dir.path().join("outside.mtl"),
        dir.path().join("model/link.mtl"),
    )
    .unwrap();
    for (library, why) in [
        ("../outside.mtl", "outside"),
        (outside.as_str(), "outside"),
        ("link.mtl", "outside"),
        ("/dev/stdin", "outside"),
        ("fifo.mtl", "a FIFO, not a regular file"),
        ("missing.mtl", "does not exist"),
    ] {
        write(
            dir.path(),
            "model/tetra.obj",
            tetra_with_material().replace("lib.mtl", library),
        );
        // Standard input left open: reading it would wait for ever.
        let mut c = command(
            dir.path(),
            &[
                "render",
                "--model",
                model.to_str().unwrap(),
                "--size",
                "16x16",
                "-o",
                "out.png",
            ],
        );
        c.stdin(Stdio::piped());
        let out = run_within(c, SOON);
        assert_ok(&out);
        let err = stderr(&out);
        assert!(
            err.contains("warning:") && err.contains(why),
            "{library}: {err}"
        );
        assert_eq!(main_colour(dir.path()), [255, 0, 0], "{library}");
    }
}

#[test]
fn inputs_that_are_not_regular_files_are_refused_at_once() {
    let dir = tempfile::tempdir().unwrap();
    mkfifo(&dir.path().join("pipe.obj"));
    mkfifo(&dir.path().join("pipe.toml"));
    std::os::unix::fs::symlink("/dev/zero", dir.path().join("zero.toml")).unwrap();
    std::os::unix::fs::symlink("/dev/zero", dir.path().join("zero.stl")).unwrap();
    std::fs::create_dir(dir.path().join("folder.ply")).unwrap();
    for (args, why) in [
        (
            vec!["render", "--model", "pipe.obj", "-o", "o.png"],
            "a FIFO, not a regular file",
        ),
        (
            vec!["render", "pipe.toml", "-o", "o.png"],
            "a FIFO, not a regular file",
        ),
        (
            vec!["render", "zero.toml", "-o", "o.png"],
            "a device, not a regular file",
        ),
        (
            vec!["render", "--model", "zero.stl", "-o", "o.png"],
            "a device, not a regular file",
        ),
        (
            vec!["compare", "--model", "folder.ply", "-o", "o.png"],
            "a directory, not a regular file",
        ),
    ] {
        let out = run_within(command(dir.path(), &args), SOON);
        assert_input_error(&out, &[why]);
    }
}

#[test]
fn a_scene_file_is_read_up_to_its_limit() {
    let dir = tempfile::tempdir().unwrap();
    // Two MiB of comments: valid TOML, but no scene is that large.
    let comment = "# padding padding padding padding padding padding padding padding\n";
    let text = comment.repeat((2 << 20) / comment.len() + 1);
    write(dir.path(), "big.toml", text);
    let out = run(dir.path(), &["render", "big.toml", "-o", "o.png"]);
    assert_input_error(&out, &["big.toml", "more than the limit of 1048576 bytes"]);
}
