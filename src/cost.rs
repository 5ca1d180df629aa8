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
    let texts = shadelab_lab::Texts::new(args.lang.into());
    let t = |id: &str| texts.get(id).to_owned();
    let mut out = std::io::stdout().lock();
    let mut print = || -> std::io::Result<()> {
        let rasterizer = t(&format!("cli.rasterizer_{}", o.rasterizer.name()));
        writeln!(
            out,
            "{}",
            texts.fill(
                "cli.cost_title",
                &[
                    ("size", &format!("{}x{}", o.width, o.height)),
                    ("rasterizer", &rasterizer),
                    ("runs", &args.runs.max(1).to_string()),
                ],
            )
        )?;
        writeln!(
            out,
            "{:<8} {:>10} {:>9} {:>11} {:>12} {:>12} {:>12}",
            t("cli.cost_method"),
            t("cli.cost_time"),
            t("cli.cost_polygons"),
            t("cli.cost_pixels"),
            t("cli.cost_per_polygon"),
            t("cli.cost_per_vertex"),
            t("cli.cost_per_pixel")
        )?;
        for c in &costs {
            writeln!(
                out,
                "{:<8} {:>10.2} {:>9} {:>11} {:>12} {:>12} {:>12}",
                t(crate::compare::title_id(c.shading)),
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
