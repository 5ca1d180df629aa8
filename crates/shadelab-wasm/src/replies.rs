//! What the engine answers the page, besides pixels: the built-in models'
//! list, a loaded file's summary, a frame's size, counts and cost, and the
//! engine's own counts. Each is serialised to JSON for the ABI (`abi.rs`).

use serde::Serialize;
use shadelab_core::{RenderOptions, RenderStats, Scene};

/// One built-in model, as the page lists it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ModelEntry {
    /// The name a scene gives as `model.source`.
    pub name: &'static str,
    /// One line about it.
    pub description: &'static str,
    /// What its detail means.
    pub detail_meaning: &'static str,
    /// Detail used when none is given.
    pub default_detail: u32,
    /// Smallest detail.
    pub detail_min: u32,
    /// Largest detail.
    pub detail_max: u32,
    /// Crease angle used when the scene gives none, degrees.
    pub default_crease: Option<f32>,
}

/// What a loaded file holds.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FileSummary {
    /// The file's name, which scenes give as `model.source` to draw it.
    pub name: String,
    /// Distinct vertex positions.
    pub vertices: usize,
    /// Polygons.
    pub polygons: usize,
    /// Triangles once polygons are split into fans.
    pub triangles: usize,
    /// Whether the file gives a normal at every face corner.
    pub has_normals: bool,
}

/// What a frame was: its size, who drew it and what it cost.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FrameInfo {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// The rasterizer that drew it: `"tiled"` or `"scanline"` (which the
    /// scanline-only modes choose).
    pub rasterizer: &'static str,
    /// The renderer's counts.
    #[serde(serialize_with = "serialize_stats")]
    pub stats: RenderStats,
    /// The lighting evaluations split by where the method makes them.
    pub cost: Evaluations,
    /// The camera's view matrix (world to eye space), column-major: the page
    /// places the lights' markers with it.
    pub view: [f32; 16],
}

/// Lighting evaluations by granularity: each method evaluates the model at
/// one of them only ([`shadelab_lab::Cost`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Evaluations {
    /// Once per polygon drawn (flat).
    pub per_polygon: u64,
    /// Once per distinct vertex (Gouraud).
    pub per_vertex: u64,
    /// Once per shaded pixel (Phong).
    pub per_pixel: u64,
}

fn serialize_stats<S: serde::Serializer>(s: &RenderStats, out: S) -> Result<S::Ok, S::Error> {
    #[derive(Serialize)]
    struct Stats {
        polygons: u64,
        degenerate: u64,
        invisible: u64,
        culled: u64,
        rasterized: u64,
        fragments_shaded: u64,
        lighting_evaluations: u64,
        covered_pixels: u64,
    }
    Stats {
        polygons: s.polygons,
        degenerate: s.degenerate,
        invisible: s.invisible,
        culled: s.culled,
        rasterized: s.rasterized,
        fragments_shaded: s.fragments_shaded,
        lighting_evaluations: s.lighting_evaluations,
        covered_pixels: s.covered_pixels,
    }
    .serialize(out)
}

/// How often the engine did its expensive, rare work: what the page's tests
/// read to check that a file is parsed once and a frame prepares nothing.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
pub struct EngineCounts {
    /// Files parsed from their bytes ([`crate::Engine::load_file`]).
    pub files_parsed: u64,
    /// Meshes taken ready-made from another engine ([`crate::Engine::adopt_file`]).
    pub files_adopted: u64,
    /// Models prepared: the mesh built or copied, its normals computed.
    pub models_prepared: u64,
    /// Scene texts read as a whole (a frame whose text is the last one's
    /// reads none; one that only turns the camera counts in `camera_turns`).
    pub scenes_read: u64,
    /// Scene texts taken as the last one with the camera turned, unread.
    pub camera_turns: u64,
    /// Frames drawn.
    pub frames: u64,
}

/// What [`crate::Engine::render`] says of a frame drawn with `options`.
pub(crate) fn frame_info(scene: &Scene, options: &RenderOptions, stats: RenderStats) -> FrameInfo {
    let split = shadelab_lab::Cost::new(options.shading, stats, 0.0, 1);
    FrameInfo {
        width: options.width,
        height: options.height,
        rasterizer: options.rasterizer.name(),
        stats,
        cost: Evaluations {
            per_polygon: split.per_polygon,
            per_vertex: split.per_vertex,
            per_pixel: split.per_pixel,
        },
        view: scene.camera.view().to_cols_array(),
    }
}
