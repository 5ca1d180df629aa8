//! Cost made visible: for each method, how long a frame took and how often
//! the reflection model was evaluated, per polygon, per vertex or per pixel.
//!
//! The counts come from the renderer's own [`RenderStats`]; each method
//! evaluates the model at one granularity only (flat per polygon, Gouraud
//! per distinct vertex, Phong per shaded pixel), so the total is split
//! accordingly. Timing needs a clock, which WebAssembly has no standard
//! one for: the caller passes one (milliseconds, e.g. `performance.now()`).

use shadelab_core::{Image, RenderError, RenderOptions, RenderStats, Renderer, Scene, Shading};

/// What one method cost on one frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cost {
    /// The method.
    pub shading: Shading,
    /// Median render time over the runs, milliseconds.
    pub millis: f64,
    /// Runs timed.
    pub runs: u32,
    /// The renderer's counts.
    pub stats: RenderStats,
    /// Lighting evaluations made once per polygon (flat).
    pub per_polygon: u64,
    /// Made once per distinct vertex (Gouraud).
    pub per_vertex: u64,
    /// Made once per shaded pixel (Phong).
    pub per_pixel: u64,
}

impl Cost {
    /// Splits `stats`' evaluations by the granularity of `shading`.
    pub fn new(shading: Shading, stats: RenderStats, millis: f64, runs: u32) -> Cost {
        let e = stats.lighting_evaluations;
        let (per_polygon, per_vertex, per_pixel) = match shading {
            Shading::Flat => (e, 0, 0),
            Shading::Gouraud => (0, e, 0),
            Shading::Phong => (0, 0, e),
        };
        Cost {
            shading,
            millis,
            runs,
            stats,
            per_polygon,
            per_vertex,
            per_pixel,
        }
    }
}

/// Renders `scene` with each of `methods`, `runs` times each (at least
/// once), and reports the median time and the counts. `clock` returns a
/// time in milliseconds.
///
/// # Errors
/// As [`shadelab_core::render`].
pub fn measure_cost(
    scene: &Scene,
    options: &RenderOptions,
    methods: &[Shading],
    runs: u32,
    mut clock: impl FnMut() -> f64,
) -> Result<Vec<Cost>, RenderError> {
    let mut renderer = Renderer::new();
    let mut image = Image::filled(1, 1, options.background);
    methods
        .iter()
        .map(|&shading| {
            let options = RenderOptions {
                shading,
                ..*options
            };
            let mut times = Vec::new();
            let mut stats = RenderStats::default();
            for _ in 0..runs.max(1) {
                let start = clock();
                stats = renderer.render_into(scene, &options, &mut image)?;
                times.push(clock() - start);
            }
            times.sort_by(f64::total_cmp);
            Ok(Cost::new(
                shading,
                stats,
                times[times.len() / 2],
                runs.max(1),
            ))
        })
        .collect()
}
