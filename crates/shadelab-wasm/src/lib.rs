//! shadelab's renderer for the browser: the viewer's Web Workers each load
//! this crate compiled to `wasm32-unknown-unknown` and draw one panel with it.
//!
//! The panel is described by the same TOML scene text as `shadelab render`
//! reads ([`shadelab_io::SceneFile`]), so a panel and the command line given
//! the same scene draw the same pixels. [`Engine`] does the work and is an
//! ordinary Rust type (tested natively); [`abi`] exports it to JavaScript as
//! a handful of plain `extern "C"` functions that exchange bytes through
//! buffers the engine owns, so no pointer from JavaScript is ever
//! dereferenced and the crate needs no `unsafe` and no binding generator.
//!
//! The protocol, one export per request (`web/js/shadelab.js` is its
//! JavaScript side):
//!
//! | export | input buffer | result (JSON) | pixels |
//! |---|---|---|---|
//! | `shadelab_models` | — | the built-in models | — |
//! | `shadelab_load_file(name_len)` | file name, then the file's bytes | a summary of the mesh | — |
//! | `shadelab_render` | scene TOML | size and [`shadelab_core::RenderStats`] | RGBA, row 0 at the top |
//!
//! Each returns 0 on success or 1 with `{"error": "..."}` as its result.
#![warn(missing_docs)]

pub mod abi;
mod engine;

pub use engine::{Engine, EngineError, FileSummary, FrameInfo, ModelEntry, MAX_FILE_BYTES};
