//! shadelab's renderer for the browser: the viewer's Web Workers each load
//! this crate compiled to `wasm32-unknown-unknown` and draw one panel with it.
//! The user's file is parsed by one of them; the others take the mesh it
//! became as bytes (`shadelab_share_file`, `shadelab_adopt_file`).
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
//! | `shadelab_share_file` | — | `null` | the parsed mesh as bytes, at `shadelab_output` |
//! | `shadelab_adopt_file(name_len)` | file name, then bytes `shadelab_share_file` gave | a summary of the mesh | — |
//! | `shadelab_counts` | — | [`EngineCounts`] | — |
//! | `shadelab_render` | scene TOML | size, rasterizer, [`shadelab_core::RenderStats`], [`Evaluations`] | RGBA, row 0 at the top |
//! | `shadelab_overlays` | [`OverlaysRequest`] | `null` | the last frame with overlays |
//! | `shadelab_errors` | [`ErrorsRequest`] | [`ErrorsAnswer`] | images: heat map (and exact surface) |
//! | `shadelab_heat` | [`HeatRequest`] | [`HeatAnswer`] | images: heat map |
//! | `shadelab_inspect` | [`InspectRequest`] | [`InspectAnswer`] | — |
//! | `shadelab_profile` | [`ProfileRequest`] | [`ProfileAnswer`] | — |
//! | `shadelab_quad` | [`QuadRequest`] | [`QuadAnswer`] | images: whole, fans |
//! | `shadelab_texts` | [`TextsRequest`] | `{id: text}` | — |
//!
//! The instruments' requests are JSON (`shadelab_render` takes the scene's
//! text as it is); their images are read with `shadelab_image(k)` and
//! `shadelab_image_len(k)`, in the order the answer's `images` lists them.
//! Each returns 0 on success or 1 with `{"error": "..."}` as its result.
#![warn(missing_docs)]

pub mod abi;
mod camera_patch;
mod engine;
mod instruments;
mod replies;
mod shared_mesh;

pub use engine::{Engine, EngineError, MAX_FILE_BYTES};
pub use instruments::{
    CurveAnswer, ErrorsAnswer, ErrorsRequest, HeatAnswer, HeatRequest, ImageInfo, InspectAnswer,
    InspectRequest, KeptErrors, MethodAnswer, OverlaysRequest, ProfileAnswer, ProfileRequest,
    QuadAnswer, QuadRequest, TextsRequest, MAX_QUAD_SIZE,
};
pub use replies::{EngineCounts, Evaluations, FileSummary, FrameInfo, ModelEntry};
