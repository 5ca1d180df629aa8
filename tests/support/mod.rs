//! What the binary's integration tests share: running the real binary in a
//! temporary directory and reading what it said and wrote.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::Duration;

/// The binary under test: this build's, or the one `SHADELAB_HOSTILE_BIN`
/// names (to see these tests fail against an older build).
pub fn bin() -> PathBuf {
    std::env::var_os("SHADELAB_HOSTILE_BIN")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_BIN_EXE_shadelab")))
}

/// A command for the binary with `args`, run in `dir`.
pub fn command(dir: &Path, args: &[&str]) -> Command {
    let mut c = Command::new(bin());
    c.args(args).current_dir(dir).stdin(Stdio::null());
    c
}

/// Runs the binary with `args` in `dir`, standard input empty.
pub fn run(dir: &Path, args: &[&str]) -> Output {
    command(dir, args).output().expect("the binary runs")
}

/// Runs `command`, killing it if it has not ended within `limit` (a hang
/// fails the test instead of stalling the suite).
pub fn run_within(mut command: Command, limit: Duration) -> Output {
    let child = command
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary runs");
    let id = child.id();
    let (send, receive) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let _ = send.send(child.wait_with_output());
    });
    match receive.recv_timeout(limit) {
        Ok(out) => out.expect("the binary's output"),
        Err(_) => {
            let _ = Command::new("kill").args(["-9", &id.to_string()]).status();
            panic!("the command did not end within {limit:?}");
        }
    }
}

pub fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

pub fn stdout(out: &Output) -> String {
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// Asserts success without a panic; shows stderr on failure.
pub fn assert_ok(out: &Output) {
    assert!(
        out.status.success(),
        "exit {:?}, stderr:\n{}",
        out.status.code(),
        stderr(out)
    );
    assert!(!stderr(out).contains("panicked"), "{}", stderr(out));
}

/// Asserts exit code `code`, no panic, and that stderr mentions every needle.
pub fn assert_fails(out: &Output, code: i32, needles: &[&str]) {
    let err = stderr(out);
    assert_eq!(out.status.code(), Some(code), "stderr:\n{err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(!err.trim().is_empty(), "no message on stderr");
    for needle in needles {
        assert!(
            err.contains(needle),
            "stderr should mention {needle:?}:\n{err}"
        );
    }
}

/// Asserts exit code 2 (invalid input) with every needle in the message.
pub fn assert_input_error(out: &Output, needles: &[&str]) {
    assert_fails(out, 2, needles);
}

pub fn write(dir: &Path, name: &str, bytes: impl AsRef<[u8]>) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

/// Names in `dir`, sorted.
pub fn entries(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// Makes a FIFO at `path` (with the system's `mkfifo`).
pub fn mkfifo(path: &Path) {
    let status = Command::new("mkfifo")
        .arg(path)
        .status()
        .expect("mkfifo runs");
    assert!(status.success(), "mkfifo {}", path.display());
}

/// Whether `bytes` begin with the PNG signature.
pub fn is_png(bytes: &[u8]) -> bool {
    bytes.starts_with(b"\x89PNG\r\n\x1a\n")
}

/// A tetrahedron, as OBJ text.
pub const TETRA: &str = "\
v 0 0 0
v 1 0 0
v 0 1 0
v 0 0 1
f 1 3 2
f 1 2 4
f 1 4 3
f 2 3 4
";

/// The bytes of `floats`, little-endian.
pub fn f32_bytes(floats: &[f32]) -> Vec<u8> {
    floats.iter().flat_map(|f| f.to_le_bytes()).collect()
}

/// One triangle's three positions, as a glTF buffer (36 bytes).
pub fn triangle_buffer() -> Vec<u8> {
    f32_bytes(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0])
}

/// `bytes` as a base64 `data:` URI.
pub fn data_uri(bytes: &[u8]) -> String {
    const TABLE: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::from("data:application/octet-stream;base64,");
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            *chunk.get(1).unwrap_or(&0),
            *chunk.get(2).unwrap_or(&0),
        ];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(TABLE[(n >> (18 - 6 * k)) as usize & 63] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// A glTF document drawing triangles from one buffer of `byte_length`
/// bytes at `uri`: `primitives` primitives per mesh, all using accessor 0
/// (`vertices` positions, not indexed), and `nodes` nodes each drawing the
/// mesh; `extra` is spliced in at the top level (`"images":[…]`).
pub fn gltf_doc(
    uri: &str,
    byte_length: usize,
    vertices: usize,
    primitives: usize,
    nodes: usize,
    extra: &str,
) -> String {
    let primitive = r#"{"attributes":{"POSITION":0},"mode":4}"#;
    let prims = vec![primitive; primitives].join(",");
    let node_list = vec![r#"{"mesh":0}"#; nodes].join(",");
    let roots = (0..nodes)
        .map(|k| k.to_string())
        .collect::<Vec<_>>()
        .join(",");
    let extra = if extra.is_empty() {
        String::new()
    } else {
        format!(",{extra}")
    };
    format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[{roots}]}}],
"nodes":[{node_list}],"meshes":[{{"primitives":[{prims}]}}],
"buffers":[{{"uri":"{uri}","byteLength":{byte_length}}}],
"bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":{byte_length}}}],
"accessors":[{{"bufferView":0,"componentType":5126,"count":{vertices},"type":"VEC3","min":[0,0,0],"max":[1,1,0]}}]{extra}}}"#
    )
}

/// Asserts that no temporary file was left in `dir`.
pub fn assert_no_temporary_files(dir: &Path) {
    let names = entries(dir);
    assert!(
        names.iter().all(|n| !n.ends_with(".tmp")),
        "temporary file left behind: {names:?}"
    );
}

/// Runs `render` with `args` and `-o out.png` in `dir`, expecting an input
/// error that mentions every needle, and no output file.
pub fn assert_render_fails(dir: &Path, args: &[&str], needles: &[&str]) {
    let mut all = vec!["render"];
    all.extend_from_slice(args);
    all.extend_from_slice(&["-o", "out.png"]);
    let out = run(dir, &all);
    assert_input_error(&out, needles);
    assert!(!dir.join("out.png").exists(), "{args:?} created the output");
    assert_no_temporary_files(dir);
}

/// The background of a render.
pub const BLACK: [u8; 3] = [0, 0, 0];

/// A decoded 8-bit RGB image.
#[derive(PartialEq)]
pub struct Png {
    pub width: u32,
    pub height: u32,
    pub rgb: Vec<u8>,
}

/// Short, so that a failed comparison does not print every pixel.
impl std::fmt::Debug for Png {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let drawn = self.rgb.chunks(3).filter(|p| *p != [0, 0, 0]).count();
        write!(
            f,
            "Png {{ {}x{}, {} non-black pixels, byte sum {} }}",
            self.width,
            self.height,
            drawn,
            self.rgb.iter().map(|&c| u64::from(c)).sum::<u64>()
        )
    }
}

impl Png {
    /// How many pixels differ from `background`.
    pub fn drawn(&self, background: [u8; 3]) -> usize {
        self.rgb.chunks(3).filter(|p| *p != background).count()
    }

    pub fn read(path: &Path) -> Png {
        let file = std::fs::File::open(path)
            .unwrap_or_else(|e| panic!("cannot open {}: {e}", path.display()));
        let decoder = png::Decoder::new(std::io::BufReader::new(file));
        let mut reader = decoder.read_info().expect("a PNG header");
        let mut buf = vec![0; reader.output_buffer_size()];
        let info = reader.next_frame(&mut buf).expect("a PNG frame");
        assert_eq!(info.color_type, png::ColorType::Rgb);
        assert_eq!(info.bit_depth, png::BitDepth::Eight);
        buf.truncate(info.buffer_size());
        Png {
            width: info.width,
            height: info.height,
            rgb: buf,
        }
    }

    pub fn pixel(&self, x: u32, y: u32) -> [u8; 3] {
        assert!(x < self.width && y < self.height, "({x}, {y}) is outside");
        let at = (y as usize * self.width as usize + x as usize) * 3;
        [self.rgb[at], self.rgb[at + 1], self.rgb[at + 2]]
    }

    /// The pixels of the rectangle at (`x`, `y`) of size `w` × `h`.
    pub fn region(&self, x: u32, y: u32, w: u32, h: u32) -> Vec<[u8; 3]> {
        (y..y + h)
            .flat_map(|py| (x..x + w).map(move |px| (px, py)))
            .map(|(px, py)| self.pixel(px, py))
            .collect()
    }
}
