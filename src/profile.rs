//! `shadelab profile`: intensity along a scanline for each method and the
//! exact surface, with its change from pixel to pixel below, as a PNG plot.

use std::io::Write;

use anyhow::Context;
use plotters::prelude::*;
use shadelab_core::limits::RENDER_BYTES_PER_PIXEL;
use shadelab_core::{render, Image, RenderOptions, Rgb8, Shading};
use shadelab_io::write_png;
use shadelab_lab::{profile, CurveKind, Profile, ProfileLine, Texts};

use crate::cli::ProfileArgs;
use crate::lab::{exact_surface, load};
use crate::plot::{draw_on, err, font, CURVE_COLORS};
use crate::{check_output, input_error, output_error, Failure};

/// Plot size.
const WIDTH: u32 = 1000;
const HEIGHT: u32 = 720;

/// Writes the plot; prints a summary (and the values with `--table`).
pub fn run(args: &ProfileArgs) -> Result<(), Failure> {
    let loaded = load(
        args.scene.as_deref(),
        &args.overrides,
        Some((480, 480)),
        None,
    )?;
    check_output(&args.output, &loaded.inputs)?;
    loaded.check_memory("profile", RENDER_BYTES_PER_PIXEL)?;
    let options = loaded.options;
    let line = match (args.row, args.line) {
        (_, Some([x0, y0, x1, y1])) => ProfileLine::Segment {
            from: (x0, y0),
            to: (x1, y1),
        },
        (Some(row), None) => ProfileLine::Row(row),
        (None, None) => ProfileLine::Row(options.height / 2),
    };
    if let ProfileLine::Row(row) = line {
        if row >= options.height {
            return Err(input_error(anyhow::anyhow!(
                "row {row} is outside the {}x{} image",
                options.width,
                options.height
            )));
        }
    }
    let surface = exact_surface(&loaded.file);
    let data = profile(&loaded.scene, &options, line, surface.as_ref()).map_err(input_error)?;
    if data.pixels.is_empty() {
        return Err(input_error(anyhow::anyhow!(
            "the line does not cross the image"
        )));
    }
    let texts = Texts::new(args.lang.into());
    let title = match line {
        ProfileLine::Row(row) => texts.fill("plot.profile_title", &[("row", &row.to_string())]),
        ProfileLine::Segment { from, to } => format!(
            "({:.1}, {:.1}) → ({:.1}, {:.1})",
            from.0, from.1, to.0, to.1
        ),
    };
    let plot = draw_profile(&data, &texts, &title, matches!(line, ProfileLine::Row(_)))
        .map_err(output_error)?;
    // Beside the plot, the Gouraud image with the profiled line marked.
    let (mut picture, _) = render(
        &loaded.scene,
        &RenderOptions {
            shading: Shading::Gouraud,
            ..options
        },
    )
    .map_err(input_error)?;
    for &(x, y) in &data.pixels {
        picture.set_pixel(x, y, MARK);
    }
    let plot = with_thumbnail(&plot, &picture);
    write_png(&args.output, &plot)
        .with_context(|| format!("cannot write {}", args.output.display()))
        .map_err(output_error)?;
    summary(&data, &texts, args.table).map_err(output_error)
}

fn label(kind: CurveKind, texts: &Texts) -> String {
    match kind {
        CurveKind::Method(s) => texts.get(&format!("method.{}", s.name())).to_owned(),
        CurveKind::Exact => texts.get("method.exact").to_owned(),
    }
}

fn summary(data: &Profile, texts: &Texts, table: bool) -> std::io::Result<()> {
    let mut out = std::io::stdout().lock();
    for curve in &data.curves {
        let drawn = curve.values.iter().flatten().count();
        let steepest = curve
            .derivative
            .iter()
            .flatten()
            .fold(0f64, |m, d| m.max(d.abs()));
        writeln!(
            out,
            "{:<16} {drawn:>5} pixels drawn, {:>3} polygon edges crossed, largest change per pixel {steepest:.2}",
            label(curve.kind, texts),
            curve.edges().len(),
        )?;
    }
    if table {
        write!(out, "x\ty")?;
        for curve in &data.curves {
            write!(out, "\t{}", label(curve.kind, texts))?;
        }
        writeln!(out)?;
        for (k, (x, y)) in data.pixels.iter().enumerate() {
            write!(out, "{x}\t{y}")?;
            for curve in &data.curves {
                match curve.values[k] {
                    Some(v) => write!(out, "\t{v:.3}")?,
                    None => write!(out, "\t-")?,
                }
            }
            writeln!(out)?;
        }
    }
    Ok(())
}

/// Runs of consecutive samples that have a value, as (x, value) points.
fn runs(xs: &[f64], values: &[Option<f64>]) -> Vec<Vec<(f64, f64)>> {
    let mut out = Vec::new();
    let mut run = Vec::new();
    for (x, v) in xs.iter().zip(values) {
        match v {
            Some(v) => run.push((*x, *v)),
            None if !run.is_empty() => out.push(std::mem::take(&mut run)),
            None => {}
        }
    }
    if !run.is_empty() {
        out.push(run);
    }
    out
}

/// The colour of the profiled line on the thumbnail.
const MARK: Rgb8 = Rgb8::new(230, 20, 20);

/// Width of the column beside the plot that shows the image.
const THUMB: u32 = 300;

/// `plot` with `picture` scaled into a column on its right.
fn with_thumbnail(plot: &Image, picture: &Image) -> Image {
    let mut out = Image::filled(
        plot.width() + THUMB,
        plot.height(),
        Rgb8::new(255, 255, 255),
    );
    out.blit(plot, 0, 0);
    let side = THUMB - 24;
    let scale = (f64::from(side) / f64::from(picture.width().max(picture.height()))).min(1.0);
    let (w, h) = (
        ((f64::from(picture.width()) * scale) as u32).max(1),
        ((f64::from(picture.height()) * scale) as u32).max(1),
    );
    // Nearest-neighbour, keeping any marked pixel of each block visible.
    let mut thumb = Image::filled(w, h, Rgb8::default());
    for ty in 0..h {
        for tx in 0..w {
            let (x0, y0) = (
                (f64::from(tx) / scale) as u32,
                (f64::from(ty) / scale) as u32,
            );
            let (x1, y1) = (
                ((f64::from(tx + 1) / scale) as u32).clamp(x0 + 1, picture.width()),
                ((f64::from(ty + 1) / scale) as u32).clamp(y0 + 1, picture.height()),
            );
            let mut c = picture.pixel(x0.min(picture.width() - 1), y0.min(picture.height() - 1));
            for y in y0..y1 {
                for x in x0..x1 {
                    if picture.pixel(x, y) == MARK {
                        c = MARK;
                    }
                }
            }
            thumb.set_pixel(tx, ty, c);
        }
    }
    out.blit(&thumb, plot.width() + (THUMB - w) / 2, 60);
    out
}

fn draw_profile(data: &Profile, texts: &Texts, title: &str, row: bool) -> anyhow::Result<Image> {
    let n = data.pixels.len();
    // Sample positions: pixel centres along a row, or the sample index along a line.
    let xs: Vec<f64> = if row {
        data.pixels.iter().map(|p| f64::from(p.0) + 0.5).collect()
    } else {
        (0..n).map(|k| k as f64).collect()
    };
    let dxs: Vec<f64> = xs.windows(2).map(|w| (w[0] + w[1]) / 2.0).collect();
    // Plot the drawn part of the line, with a little margin.
    let drawn: Vec<usize> = (0..n)
        .filter(|&k| data.curves.iter().any(|c| c.values[k].is_some()))
        .collect();
    let (lo, hi) = match (drawn.first(), drawn.last()) {
        (Some(&a), Some(&b)) => (xs[a], xs[b]),
        _ => (xs[0], xs[n - 1]),
    };
    let pad = ((hi - lo) * 0.03).max(2.0);
    let x_range = (lo - pad)..(hi + pad);
    let max_value = data
        .curves
        .iter()
        .flat_map(|c| c.values.iter().flatten())
        .fold(0f64, |m, &v| m.max(v));
    let y_range = 0.0..(max_value * 1.08).max(10.0);
    let slope = data
        .curves
        .iter()
        .flat_map(|c| c.derivative.iter().flatten())
        .fold(0f64, |m, &d| m.max(d.abs()))
        .max(0.5);
    // Flat's jumps dwarf the others' slopes: clip the axis to show the kinks.
    let smooth_slope = data
        .curves
        .iter()
        .filter(|c| c.kind != CurveKind::Method(Shading::Flat))
        .flat_map(|c| c.derivative.iter().flatten())
        .fold(0f64, |m, &d| m.max(d.abs()))
        .max(0.5);
    let d_lim = (smooth_slope * 1.6).min(slope * 1.05);
    let d_range = -d_lim..d_lim;
    // Gouraud's polygon edges, where the kinks are.
    let gouraud = data
        .curves
        .iter()
        .find(|c| c.kind == CurveKind::Method(Shading::Gouraud));
    let edges: Vec<f64> = gouraud
        .map(|c| c.edges().iter().map(|&k| dxs[k]).collect())
        .unwrap_or_default();

    let canvas = Image::filled(WIDTH, HEIGHT, Rgb8::new(255, 255, 255));
    draw_on(&canvas, |root| {
        let (top, bottom) = root.split_vertically(HEIGHT * 3 / 5);
        let mut chart = ChartBuilder::on(&top)
            .caption(title, font(22.0, BLACK))
            .margin(12)
            .x_label_area_size(34)
            .y_label_area_size(56)
            .build_cartesian_2d(x_range.clone(), y_range.clone())
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc(texts.get("plot.position"))
            .y_desc(texts.get("plot.intensity"))
            .x_label_formatter(&|v| format!("{v:.0}"))
            .y_label_formatter(&|v| format!("{v:.0}"))
            .label_style(font(13.0, BLACK))
            .axis_desc_style(font(14.0, BLACK))
            .light_line_style(TRANSPARENT)
            .bold_line_style(RGBColor(236, 236, 236))
            .draw()
            .map_err(err)?;
        let edge_style = ShapeStyle::from(RGBColor(150, 150, 150)).stroke_width(1);
        for &x in &edges {
            chart
                .draw_series(LineSeries::new(
                    [(x, y_range.start), (x, y_range.end)],
                    edge_style,
                ))
                .map_err(err)?;
        }
        for (k, curve) in data.curves.iter().enumerate() {
            let color = CURVE_COLORS[k.min(3)];
            let style = ShapeStyle::from(color).stroke_width(2);
            let mut first = true;
            for run in runs(&xs, &curve.values) {
                let series = chart
                    .draw_series(LineSeries::new(staircase(&run, curve.kind), style))
                    .map_err(err)?;
                if first {
                    series
                        .label(label(curve.kind, texts))
                        .legend(move |(x, y)| {
                            PathElement::new([(x, y), (x + 22, y)], color.stroke_width(3))
                        });
                    first = false;
                }
            }
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.85))
            .border_style(RGBColor(180, 180, 180))
            .label_font(font(14.0, BLACK))
            .draw()
            .map_err(err)?;

        let mut lower = ChartBuilder::on(&bottom)
            .caption(texts.get("plot.derivative_title"), font(17.0, BLACK))
            .margin(12)
            .x_label_area_size(34)
            .y_label_area_size(56)
            .build_cartesian_2d(x_range.clone(), d_range.clone())
            .map_err(err)?;
        lower
            .configure_mesh()
            .x_desc(texts.get("plot.position"))
            .y_desc(texts.get("plot.derivative"))
            .x_label_formatter(&|v| format!("{v:.0}"))
            .y_label_formatter(&|v| format!("{v:.1}"))
            .label_style(font(13.0, BLACK))
            .axis_desc_style(font(14.0, BLACK))
            .light_line_style(TRANSPARENT)
            .bold_line_style(RGBColor(236, 236, 236))
            .draw()
            .map_err(err)?;
        for &x in &edges {
            lower
                .draw_series(LineSeries::new(
                    [(x, d_range.start), (x, d_range.end)],
                    edge_style,
                ))
                .map_err(err)?;
        }
        for (k, curve) in data.curves.iter().enumerate() {
            let style = ShapeStyle::from(CURVE_COLORS[k.min(3)]).stroke_width(2);
            let clipped: Vec<Option<f64>> = curve
                .derivative
                .iter()
                .map(|d| d.map(|d| d.clamp(d_range.start, d_range.end)))
                .collect();
            for run in runs(&dxs, &clipped) {
                lower
                    .draw_series(LineSeries::new(run, style))
                    .map_err(err)?;
            }
        }
        Ok(())
    })
}

/// Flat shading's values as steps (constant across each pixel), so its
/// jumps show as jumps; other curves as they are.
fn staircase(run: &[(f64, f64)], kind: CurveKind) -> Vec<(f64, f64)> {
    if kind != CurveKind::Method(Shading::Flat) {
        return run.to_vec();
    }
    let mut out = Vec::with_capacity(run.len() * 2);
    for &(x, v) in run {
        out.push((x - 0.5, v));
        out.push((x + 0.5, v));
    }
    out
}
