//! The exports JavaScript calls: plain `extern "C"` functions over one
//! [`Engine`] per WebAssembly instance (one instance per worker).
//!
//! Bytes cross the boundary only through buffers that Rust owns: JavaScript
//! asks [`shadelab_input`] for an input buffer of the size it needs, copies
//! its bytes there, then makes a request; it reads the answer from the
//! result and pixel buffers whose addresses and lengths the other exports
//! give. A buffer's address is valid until the next call, which may grow the
//! memory, so JavaScript makes a new view of `memory.buffer` after each call.
//!
//! Every request returns [`OK`] or [`FAILED`]; the result buffer then holds
//! the answer's JSON, or `{"error": "..."}`.

use std::cell::RefCell;

use serde::de::DeserializeOwned;
use serde::Serialize;

use crate::engine::{Engine, EngineError};

/// A request succeeded.
pub const OK: u32 = 0;
/// A request failed; the result is `{"error": "..."}`.
pub const FAILED: u32 = 1;

/// One instance's state.
#[derive(Default)]
struct Instance {
    engine: Engine,
    input: Vec<u8>,
    result: Vec<u8>,
    /// Bytes a request made for JavaScript to take (the shared mesh).
    output: Vec<u8>,
}

thread_local! {
    static INSTANCE: RefCell<Instance> = RefCell::new(Instance::default());
}

#[derive(Serialize)]
struct ErrorJson<'a> {
    error: &'a str,
}

impl Instance {
    /// Stores `answer` as the result and returns the status.
    fn answer<T: Serialize>(&mut self, answer: Result<T, EngineError>) -> u32 {
        self.result.clear();
        let (status, written) = match &answer {
            Ok(value) => (OK, serde_json::to_writer(&mut self.result, value)),
            Err(e) => (
                FAILED,
                serde_json::to_writer(&mut self.result, &ErrorJson { error: &e.0 }),
            ),
        };
        // Serializing these plain structs into a Vec cannot fail; should it,
        // say so rather than hand back half a JSON text.
        if written.is_err() {
            self.result.clear();
            self.result.extend_from_slice(
                br#"{"error":"internal error: the answer could not be encoded"}"#,
            );
            return FAILED;
        }
        status
    }
}

fn with<R>(f: impl FnOnce(&mut Instance) -> R) -> R {
    INSTANCE.with_borrow_mut(f)
}

/// Makes the input buffer `len` bytes long (zeroed) and returns its address,
/// for JavaScript to fill before the next request.
#[no_mangle]
pub extern "C" fn shadelab_input(len: usize) -> *mut u8 {
    with(|i| {
        i.input.clear();
        i.input.resize(len, 0);
        i.input.as_mut_ptr()
    })
}

/// The built-in models ([`Engine::models`]) as JSON.
#[no_mangle]
pub extern "C" fn shadelab_models() -> u32 {
    with(|i| i.answer(Ok(Engine::models())))
}

/// Loads the user's file: the input buffer holds its name (`name_len` bytes
/// of UTF-8), then its bytes ([`Engine::load_file`]).
#[no_mangle]
pub extern "C" fn shadelab_load_file(name_len: usize) -> u32 {
    named_input(name_len, Engine::load_file)
}

/// Reads the input buffer as a file name (`name_len` bytes of UTF-8)
/// followed by the file's bytes, and hands both to `f`.
fn named_input<T: Serialize>(
    name_len: usize,
    f: impl FnOnce(&mut Engine, &str, &[u8]) -> Result<T, EngineError>,
) -> u32 {
    with(|i| {
        let input = std::mem::take(&mut i.input);
        let answer = match input.split_at_checked(name_len) {
            Some((name, bytes)) => match std::str::from_utf8(name) {
                Ok(name) => f(&mut i.engine, name, bytes),
                Err(_) => Err(EngineError("the file name is not UTF-8".into())),
            },
            None => Err(EngineError("the file name is longer than the input".into())),
        };
        i.input = input;
        i.answer(answer)
    })
}

/// Puts the loaded file's mesh, as bytes for [`shadelab_adopt_file`], at
/// [`shadelab_output`] ([`Engine::shared_file`]); fails when no file is loaded.
#[no_mangle]
pub extern "C" fn shadelab_share_file() -> u32 {
    with(|i| match i.engine.shared_file() {
        Some(bytes) => {
            i.output = bytes;
            i.answer(Ok(()))
        }
        None => i.answer::<()>(Err(EngineError("no file is loaded".into()))),
    })
}

/// Takes a mesh another instance parsed: the input buffer holds its name
/// (`name_len` bytes of UTF-8), then the bytes [`shadelab_share_file`]
/// gave there ([`Engine::adopt_file`]).
#[no_mangle]
pub extern "C" fn shadelab_adopt_file(name_len: usize) -> u32 {
    named_input(name_len, Engine::adopt_file)
}

/// How often this instance parsed, prepared and drew ([`Engine::counts`]).
#[no_mangle]
pub extern "C" fn shadelab_counts() -> u32 {
    with(|i| {
        let counts = i.engine.counts();
        i.answer(Ok(counts))
    })
}

/// Address of the bytes the last request made for JavaScript.
#[no_mangle]
pub extern "C" fn shadelab_output() -> *const u8 {
    with(|i| i.output.as_ptr())
}

/// Length of the bytes at [`shadelab_output`].
#[no_mangle]
pub extern "C" fn shadelab_output_len() -> usize {
    with(|i| i.output.len())
}

/// Renders the scene whose TOML text is in the input buffer
/// ([`Engine::render`]); the pixels are then at [`shadelab_pixels`].
#[no_mangle]
pub extern "C" fn shadelab_render() -> u32 {
    with(|i| {
        let answer = match std::str::from_utf8(&i.input) {
            Ok(text) => i.engine.render(text),
            Err(_) => Err(EngineError("the scene text is not UTF-8".into())),
        };
        i.answer(answer)
    })
}

/// Renders the scene whose TOML text is in the input buffer with the three
/// methods at once ([`Engine::render_methods`]): the answer is
/// `{"frames": [flat, gouraud, phong]}`, each as [`shadelab_render`]'s, and
/// their pixels are images 0, 1 and 2 at [`shadelab_image`].
#[no_mangle]
pub extern "C" fn shadelab_render_methods() -> u32 {
    #[derive(Serialize)]
    struct Frames {
        frames: [crate::replies::FrameInfo; 3],
    }
    with(|i| {
        let answer = match std::str::from_utf8(&i.input) {
            Ok(text) => i
                .engine
                .render_methods(text)
                .map(|frames| Frames { frames }),
            Err(_) => Err(EngineError("the scene text is not UTF-8".into())),
        };
        i.answer(answer)
    })
}

/// Part `part` of `parts` of [`shadelab_render_methods`]
/// ([`Engine::render_methods_part`]): the answer is `{"frames": [flat,
/// gouraud, phong], "rows": [first, end]}`, and images 0, 1 and 2 at
/// [`shadelab_image`] hold those rows of the three frames.
#[no_mangle]
pub extern "C" fn shadelab_render_methods_part(part: u32, parts: u32) -> u32 {
    #[derive(Serialize)]
    struct Part {
        frames: [crate::replies::FrameInfo; 3],
        rows: [u32; 2],
    }
    with(|i| {
        let answer = match std::str::from_utf8(&i.input) {
            Ok(text) => i
                .engine
                .render_methods_part(text, part, parts)
                .map(|(frames, rows)| Part { frames, rows }),
            Err(_) => Err(EngineError("the scene text is not UTF-8".into())),
        };
        i.answer(answer)
    })
}

/// Answers a request whose input buffer holds its JSON.
fn json_request<Q: DeserializeOwned, A: Serialize>(
    f: impl FnOnce(&mut Engine, &Q) -> Result<A, EngineError>,
) -> u32 {
    with(|i| {
        let answer = match serde_json::from_slice::<Q>(&i.input) {
            Ok(request) => f(&mut i.engine, &request),
            Err(e) => Err(EngineError(format!("bad request: {e}"))),
        };
        i.answer(answer)
    })
}

/// Draws overlays over the last frame ([`Engine::overlays`]); its pixels
/// are then at [`shadelab_pixels`].
#[no_mangle]
pub extern "C" fn shadelab_overlays() -> u32 {
    json_request(Engine::overlays)
}

/// The last frame's error against the exact surface ([`Engine::errors`]);
/// the heat map (and the exact image) are then at [`shadelab_image`].
#[no_mangle]
pub extern "C" fn shadelab_errors() -> u32 {
    json_request(Engine::errors)
}

/// The last error map on another scale ([`Engine::heat`]).
#[no_mangle]
pub extern "C" fn shadelab_heat() -> u32 {
    json_request(Engine::heat)
}

/// The pixel inspector ([`Engine::inspect`]).
#[no_mangle]
pub extern "C" fn shadelab_inspect() -> u32 {
    json_request(Engine::inspect)
}

/// A scanline profile ([`Engine::profile`]).
#[no_mangle]
pub extern "C" fn shadelab_profile() -> u32 {
    json_request(Engine::profile)
}

/// The quad study ([`Engine::quad`]); its images are at [`shadelab_image`].
#[no_mangle]
pub extern "C" fn shadelab_quad() -> u32 {
    json_request(Engine::quad)
}

/// The instruments' texts in one language ([`Engine::texts`]).
#[no_mangle]
pub extern "C" fn shadelab_texts() -> u32 {
    json_request(|_, request| Engine::texts(request))
}

/// Address of image `k` of the last instrument request (RGBA; null past the last).
#[no_mangle]
pub extern "C" fn shadelab_image(k: usize) -> *const u8 {
    with(|i| {
        i.engine
            .images()
            .get(k)
            .map_or(std::ptr::null(), |v| v.as_ptr())
    })
}

/// Length of image `k` of the last instrument request, bytes (0 past the last).
#[no_mangle]
pub extern "C" fn shadelab_image_len(k: usize) -> usize {
    with(|i| i.engine.images().get(k).map_or(0, Vec::len))
}

/// Address of the last request's result (JSON).
#[no_mangle]
pub extern "C" fn shadelab_result() -> *const u8 {
    with(|i| i.result.as_ptr())
}

/// Length of the last request's result, bytes.
#[no_mangle]
pub extern "C" fn shadelab_result_len() -> usize {
    with(|i| i.result.len())
}

/// Address of the last frame's RGBA pixels.
#[no_mangle]
pub extern "C" fn shadelab_pixels() -> *const u8 {
    with(|i| i.engine.rgba().as_ptr())
}

/// Length of the last frame's RGBA pixels, bytes (4 per pixel).
#[no_mangle]
pub extern "C" fn shadelab_pixels_len() -> usize {
    with(|i| i.engine.rgba().len())
}

/// The result of the last request as text, for native tests.
pub fn result_text() -> String {
    with(|i| String::from_utf8_lossy(&i.result).into_owned())
}

/// The bytes at [`shadelab_output`], for native tests.
pub fn output_bytes() -> Vec<u8> {
    with(|i| i.output.clone())
}

/// Copies `bytes` into the input buffer, as JavaScript does, for native tests.
pub fn set_input(bytes: &[u8]) {
    with(|i| {
        i.input.clear();
        i.input.extend_from_slice(bytes);
    })
}
