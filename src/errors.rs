//! `shadelab errors`: the exact surface and each method's error map, side
//! by side on one colour scale, with the mean and largest error.

use std::io::Write;

use anyhow::Context;
use plotters::prelude::*;
use shadelab_core::limits::ERRORS_BYTES_PER_PIXEL;
use shadelab_core::{Image, Rgb8};
use shadelab_io::write_png;
use shadelab_lab::{error_maps, exact_image, heat_bar, heat_scale, Texts};

use crate::cli::ErrorsArgs;
use crate::lab::{load, require_exact_surface};
use crate::plot::{draw_on, err, font};
use crate::{check_output, input_error, output_error, Failure};

const TITLE_BAND: u32 = 34;
const CAPTION_BAND: u32 = 30;
const GAP: u32 = 6;
const BAR_AREA: u32 = 90;
const BAND: Rgb8 = Rgb8::new(32, 32, 40);

/// Writes the sheet and prints each method's mean and largest error.
pub fn run(args: &ErrorsArgs) -> Result<(), Failure> {
    let loaded = load(
        args.scene.as_deref(),
        &args.overrides,
        Some((320, 320)),
        Some("sphere"),
    )?;
    check_output(&args.output, &loaded.inputs)?;
    loaded.check_memory("errors", ERRORS_BYTES_PER_PIXEL)?;
    let surface = require_exact_surface(&loaded.file)?;
    if let Some(s) = args.scale {
        if !(s.is_finite() && s > 0.0) {
            return Err(input_error(anyhow::anyhow!(
                "--scale must be a positive number, got {s}"
            )));
        }
    }
    let options = loaded.options;
    let (exact, maps) = error_maps(&loaded.scene, &options, &surface).map_err(input_error)?;
    let texts = Texts::new(args.lang.into());
    let largest = maps.iter().map(|m| m.map.max).fold(0f32, f32::max);
    let scale = args.scale.unwrap_or_else(|| heat_scale(largest));

    let (w, h) = (options.width, options.height);
    let sheet_w = 4 * w + 3 * GAP + BAR_AREA;
    let sheet_h = TITLE_BAND + h + CAPTION_BAND;
    let mut sheet = Image::filled(sheet_w, sheet_h, BAND);
    sheet.blit(&exact_image(&exact, options.background), 0, TITLE_BAND);
    for (k, m) in maps.iter().enumerate() {
        let heat = m.map.heat_image(scale, &exact, options.background);
        sheet.blit(&heat, (k as u32 + 1) * (w + GAP), TITLE_BAND);
    }
    let bar_h = h.saturating_sub(20).max(10);
    let bar_x = 4 * w + 3 * GAP + 14;
    let bar_y = TITLE_BAND + (h - bar_h) / 2;
    sheet.blit(&heat_bar(18, bar_h), bar_x, bar_y);

    let sheet = draw_on(&sheet, |root| {
        let white = RGBColor(240, 240, 240);
        let title = |text: &str, k: u32| -> anyhow::Result<()> {
            let style = font(18.0, white).pos(plotters::style::text_anchor::Pos::new(
                plotters::style::text_anchor::HPos::Center,
                plotters::style::text_anchor::VPos::Center,
            ));
            root.draw(&Text::new(
                text.to_owned(),
                ((k * (w + GAP) + w / 2) as i32, (TITLE_BAND / 2) as i32),
                style,
            ))
            .map_err(err)
        };
        title(texts.get("method.exact"), 0)?;
        for (k, m) in maps.iter().enumerate() {
            title(
                texts.get(&format!("method.{}", m.shading.name())),
                k as u32 + 1,
            )?;
            let caption = format!(
                "{}   {}",
                texts.fill("plot.mean", &[("value", &format!("{:.2}", m.map.mean))]),
                texts.fill("plot.max", &[("value", &format!("{:.1}", m.map.max))])
            );
            let style = font(15.0, white).pos(plotters::style::text_anchor::Pos::new(
                plotters::style::text_anchor::HPos::Center,
                plotters::style::text_anchor::VPos::Center,
            ));
            root.draw(&Text::new(
                caption,
                (
                    ((k as u32 + 1) * (w + GAP) + w / 2) as i32,
                    (TITLE_BAND + h + CAPTION_BAND / 2) as i32,
                ),
                style,
            ))
            .map_err(err)?;
        }
        // The colour scale's ticks.
        for k in 0..=4 {
            let f = k as f32 / 4.0;
            let y = bar_y as f32 + (1.0 - f) * bar_h as f32;
            root.draw(&PathElement::new(
                [
                    ((bar_x + 18) as i32, y as i32),
                    ((bar_x + 23) as i32, y as i32),
                ],
                white,
            ))
            .map_err(err)?;
            root.draw(&Text::new(
                format!("{:.0}", f * scale),
                ((bar_x + 26) as i32, y as i32 - 7),
                font(13.0, white),
            ))
            .map_err(err)?;
        }
        root.draw(&Text::new(
            texts.get("plot.error_scale").to_owned(),
            ((bar_x - 8) as i32, (TITLE_BAND / 2 - 8) as i32),
            font(12.0, white),
        ))
        .map_err(err)?;
        Ok(())
    })
    .map_err(output_error)?;
    write_png(&args.output, &sheet)
        .with_context(|| format!("cannot write {}", args.output.display()))
        .map_err(output_error)?;

    let mut out = std::io::stdout().lock();
    let mut print = || -> std::io::Result<()> {
        writeln!(
            out,
            "error against the exact surface, mean of |R|, |G|, |B| differences in 0–255 units"
        )?;
        writeln!(
            out,
            "{:<10} {:>8} {:>8} {:>12} {:>9} {:>9}",
            "method", "mean", "max", "at", "compared", "mesh only"
        )?;
        for m in &maps {
            let at = m
                .map
                .max_at
                .map_or("-".to_owned(), |(x, y)| format!("({x}, {y})"));
            writeln!(
                out,
                "{:<10} {:>8.3} {:>8.2} {:>12} {:>9} {:>9}",
                m.shading.title(),
                m.map.mean,
                m.map.max,
                at,
                m.map.compared,
                m.map.mesh_only
            )?;
        }
        writeln!(
            out,
            "surface only (outside the mesh's silhouette): {} pixels; colour scale 0–{scale}",
            maps.first().map_or(0, |m| m.map.surface_only)
        )
    };
    print().map_err(output_error)
}
