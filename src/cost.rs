//! `shadelab cost`: what each method costs, in time and lighting evaluations.

use std::io::Write;
use std::time::Instant;

use shadelab_core::limits::RENDER_BYTES_PER_PIXEL;
use shadelab_core::Shading;
use shadelab_lab::measure_cost;

use crate::cli::CostArgs;
use crate::lab::load;
use crate::{input_error, output_error, Failure};

/// Prints a table: per method the median time and the evaluation counts.
pub fn run(args: &CostArgs) -> Result<(), Failure> {
    let loaded = load(
        args.scene.as_deref(),
        &args.overrides,
        Some((480, 480)),
        None,
    )?;
    loaded.check_memory("cost", RENDER_BYTES_PER_PIXEL)?;
    let start = Instant::now();
    let costs = measure_cost(
        &loaded.scene,
        &loaded.options,
        &Shading::ALL,
        args.runs,
        || start.elapsed().as_secs_f64() * 1e3,
    )
    .map_err(input_error)?;
    let o = &loaded.options;
    let mut out = std::io::stdout().lock();
    let mut print = || -> std::io::Result<()> {
        writeln!(
            out,
            "{}x{}, {} rasterizer, median of {} runs",
            o.width,
            o.height,
            o.rasterizer.name(),
            args.runs.max(1)
        )?;
        writeln!(
            out,
            "{:<8} {:>10} {:>9} {:>11} {:>12} {:>12} {:>12}",
            "method", "time (ms)", "polygons", "pixels", "per polygon", "per vertex", "per pixel"
        )?;
        for c in &costs {
            writeln!(
                out,
                "{:<8} {:>10.2} {:>9} {:>11} {:>12} {:>12} {:>12}",
                c.shading.title(),
                c.millis,
                c.stats.rasterized,
                c.stats.fragments_shaded,
                c.per_polygon,
                c.per_vertex,
                c.per_pixel
            )?;
        }
        Ok(())
    };
    print().map_err(output_error)
}
