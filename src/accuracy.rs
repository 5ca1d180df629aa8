//! `shadelab accuracy`: each method's mean error against the exact surface
//! as the tessellation grows, as a table and a log–log plot.

use std::io::Write;

use anyhow::Context;
use plotters::prelude::*;
use shadelab_core::limits::{ACCURACY_BYTES_PER_PIXEL, MAX_ACCURACY_DETAILS};
use shadelab_core::{Image, Rgb8, Shading};
use shadelab_io::write_png;
use shadelab_lab::{accuracy, AccuracyRow, Texts};

use crate::cli::{AccuracyArgs, SceneOverrides};
use crate::lab::{load, require_exact_surface};
use crate::plot::{draw_on, err, font, CURVE_COLORS};
use crate::{check_output, input_error, output_error, Failure};

/// Prints the table and writes the plot.
pub fn run(args: &AccuracyArgs) -> Result<(), Failure> {
    if args.details.is_empty() || args.details.len() > MAX_ACCURACY_DETAILS {
        return Err(input_error(anyhow::anyhow!(
            "--details needs 1..={MAX_ACCURACY_DETAILS} levels, got {}",
            args.details.len()
        )));
    }
    let first = load(
        args.scene.as_deref(),
        &args.overrides,
        Some((240, 240)),
        Some("sphere"),
    )?;
    require_exact_surface(&first.file)?;
    first.check_memory("accuracy", ACCURACY_BYTES_PER_PIXEL)?;
    if let Some(out) = &args.output {
        check_output(out, &first.inputs)?;
    }
    let model = first.file.model.source.clone().unwrap_or_default();
    let rows = accuracy(&args.details, |detail| -> Result<_, Failure> {
        let overrides = SceneOverrides {
            params: args
                .overrides
                .params
                .with("model.detail", toml::Value::Integer(i64::from(detail))),
            ..args.overrides.clone()
        };
        let loaded = load(
            args.scene.as_deref(),
            &overrides,
            Some((240, 240)),
            Some("sphere"),
        )?;
        let surface = require_exact_surface(&loaded.file)?;
        loaded.check_memory("accuracy", ACCURACY_BYTES_PER_PIXEL)?;
        Ok((loaded.scene, loaded.options, surface))
    })?;
    let texts = Texts::new(args.lang.into());
    print_table(&model, &first.options, &rows, &texts).map_err(output_error)?;
    if let Some(out) = &args.output {
        let plot = draw_plot(&model, &rows, &texts).map_err(output_error)?;
        write_png(out, &plot)
            .with_context(|| format!("cannot write {}", out.display()))
            .map_err(output_error)?;
    }
    Ok(())
}

fn print_table(
    model: &str,
    options: &shadelab_core::RenderOptions,
    rows: &[AccuracyRow],
    texts: &Texts,
) -> std::io::Result<()> {
    let mut out = std::io::stdout().lock();
    writeln!(
        out,
        "{model}, {}x{}: mean (max) error against the exact surface, 0–255 units",
        options.width, options.height
    )?;
    write!(out, "{:>7} {:>9}", "detail", "polygons")?;
    for s in Shading::ALL {
        write!(out, " {:>22}", texts.get(&format!("method.{}", s.name())))?;
    }
    writeln!(out, " {:>9}", "pixels")?;
    for r in rows {
        write!(out, "{:>7} {:>9}", r.detail, r.polygons)?;
        for (mean, max) in r.errors {
            write!(out, " {:>22}", format!("{mean:.3} ({max:.1})"))?;
        }
        writeln!(out, " {:>9}", r.compared)?;
    }
    Ok(())
}

/// 1, 2 and 5 times the powers of ten between `lo` and `hi`.
fn y_keys(lo: f64, hi: f64) -> Vec<f64> {
    let mut keys = Vec::new();
    let mut p = 10f64.powf(lo.log10().floor());
    while p <= hi {
        for m in [1.0, 2.0, 5.0] {
            let v = m * p;
            if (lo..=hi).contains(&v) {
                keys.push((v * 1e6).round() / 1e6);
            }
        }
        p *= 10.0;
    }
    keys
}

fn draw_plot(model: &str, rows: &[AccuracyRow], texts: &Texts) -> anyhow::Result<Image> {
    let xs: Vec<f64> = rows.iter().map(|r| f64::from(r.detail)).collect();
    let errors = rows
        .iter()
        .flat_map(|r| r.errors.iter().map(|e| e.0))
        .filter(|e| *e > 0.0);
    let (lo, hi) = errors.fold((f64::INFINITY, 0f64), |(a, b), e| (a.min(e), b.max(e)));
    let (lo, hi) = if lo.is_finite() {
        (lo / 1.5, hi * 1.5)
    } else {
        (0.01, 1.0)
    };
    let x_lo = xs.iter().copied().fold(f64::INFINITY, f64::min) / 1.3;
    let x_hi = xs.iter().copied().fold(0f64, f64::max) * 1.3;
    let canvas = Image::filled(820, 560, Rgb8::new(255, 255, 255));
    draw_on(&canvas, |root| {
        let title = texts.fill("plot.accuracy_title", &[("model", model)]);
        let mut chart = ChartBuilder::on(root)
            .caption(title, font(22.0, BLACK))
            .margin(16)
            .x_label_area_size(40)
            .y_label_area_size(64)
            .build_cartesian_2d(
                (x_lo..x_hi).log_scale().with_key_points(xs.clone()),
                (lo..hi).log_scale().with_key_points(y_keys(lo, hi)),
            )
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc(texts.get("plot.detail"))
            .x_label_formatter(&|x| format!("{x}"))
            .y_label_formatter(&|y| format!("{y}"))
            .y_desc(texts.get("plot.mean_error"))
            .label_style(font(14.0, BLACK))
            .axis_desc_style(font(15.0, BLACK))
            .light_line_style(RGBColor(245, 245, 245))
            .draw()
            .map_err(err)?;
        for (m, shading) in Shading::ALL.into_iter().enumerate() {
            let color = CURVE_COLORS[m];
            let points: Vec<(f64, f64)> = rows
                .iter()
                .map(|r| (f64::from(r.detail), r.errors[m].0))
                .filter(|p| p.1 > 0.0)
                .collect();
            chart
                .draw_series(LineSeries::new(
                    points.clone(),
                    ShapeStyle::from(color).stroke_width(2),
                ))
                .map_err(err)?
                .label(texts.get(&format!("method.{}", shading.name())))
                .legend(move |(x, y)| {
                    PathElement::new([(x, y), (x + 22, y)], color.stroke_width(3))
                });
            chart
                .draw_series(points.iter().map(|&p| Circle::new(p, 4, color.filled())))
                .map_err(err)?;
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.85))
            .border_style(RGBColor(180, 180, 180))
            .label_font(font(15.0, BLACK))
            .draw()
            .map_err(err)?;
        Ok(())
    })
}
