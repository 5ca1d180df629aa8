//! `shadelab quad`: one square, one bright vertex, turned on the screen;
//! Gouraud shading walked over it whole (top row) and over its two
//! triangles (bottom row), with the value at its centre.

use std::io::Write;

use anyhow::Context;
use plotters::prelude::*;
use shadelab_core::limits::{
    MAX_QUAD_ANGLES, MAX_QUAD_DEGREES, MAX_QUAD_SIZE, MIN_QUAD_SIZE, QUAD_BYTES_PER_PIXEL,
};
use shadelab_core::{format_number, Image, RenderError, Rgb8};
use shadelab_io::write_png;
use shadelab_lab::quad_study;

use crate::cli::QuadArgs;
use crate::plot::{draw_on, err, font};
use crate::{input_error, output_error, Failure};

const LABEL_W: u32 = 110;
const TITLE_BAND: u32 = 30;
const CAPTION_BAND: u32 = 26;
const GAP: u32 = 6;

/// Writes the sheet and prints the centre values.
pub fn run(args: &QuadArgs) -> Result<(), Failure> {
    if !(1..=MAX_QUAD_ANGLES).contains(&args.angles.len()) {
        return Err(input_error(anyhow::anyhow!(
            "--angles takes 1..={MAX_QUAD_ANGLES} turns, got {}",
            args.angles.len()
        )));
    }
    if let Some(a) = args
        .angles
        .iter()
        .find(|a| !(a.is_finite() && a.abs() <= MAX_QUAD_DEGREES))
    {
        return Err(input_error(anyhow::anyhow!(
            "--angles: each turn must be a number of degrees in -{MAX_QUAD_DEGREES}..={MAX_QUAD_DEGREES}, got {}",
            format_number(*a)
        )));
    }
    if !(MIN_QUAD_SIZE..=MAX_QUAD_SIZE).contains(&args.size) {
        return Err(input_error(anyhow::anyhow!(
            "--size must be {MIN_QUAD_SIZE}..={MAX_QUAD_SIZE}, got {}",
            args.size
        )));
    }
    let panel = u64::from(args.size) * u64::from(args.size);
    crate::memory::check(
        "quad",
        None,
        2 * args.angles.len() as u64 * panel,
        QUAD_BYTES_PER_PIXEL,
    )?;
    let samples = quad_study(&args.angles, args.size).map_err(|e: RenderError| input_error(e))?;
    let texts = shadelab_lab::Texts::new(args.lang.into());
    let s = args.size;
    let cols = samples.len() as u32;
    let row_h = s + CAPTION_BAND;
    let sheet_w = LABEL_W + cols * (s + GAP);
    let sheet_h = TITLE_BAND + 2 * row_h;
    let mut sheet = Image::filled(sheet_w, sheet_h, Rgb8::new(32, 32, 40));
    for (k, q) in samples.iter().enumerate() {
        let x = LABEL_W + k as u32 * (s + GAP);
        sheet.blit(&q.whole, x, TITLE_BAND);
        sheet.blit(&q.fans, x, TITLE_BAND + row_h);
    }
    let sheet = draw_on(&sheet, |root| {
        let white = RGBColor(240, 240, 240);
        let centred = |size: f64| {
            font(size, white).pos(plotters::style::text_anchor::Pos::new(
                plotters::style::text_anchor::HPos::Center,
                plotters::style::text_anchor::VPos::Center,
            ))
        };
        for (k, q) in samples.iter().enumerate() {
            let cx = (LABEL_W + k as u32 * (s + GAP) + s / 2) as i32;
            root.draw(&Text::new(
                format!("{}°", q.angle_degrees),
                (cx, (TITLE_BAND / 2) as i32),
                centred(16.0),
            ))
            .map_err(err)?;
            for (row, v) in [(0, q.whole_centre), (1, q.fans_centre)] {
                let y = TITLE_BAND + row * row_h + s + CAPTION_BAND / 2;
                root.draw(&Text::new(
                    format!("I = {v:.3}"),
                    (cx, y as i32),
                    centred(14.0),
                ))
                .map_err(err)?;
            }
        }
        for (row, label) in [
            (0, texts.get("cli.quad_whole")),
            (1, texts.get("cli.quad_triangles")),
        ] {
            let y = TITLE_BAND + row * row_h + s / 2;
            root.draw(&Text::new(
                label,
                ((LABEL_W / 2) as i32, y as i32),
                centred(16.0),
            ))
            .map_err(err)?;
        }
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
            "{:>8} {:>14} {:>14}",
            texts.get("cli.quad_angle"),
            texts.get("cli.quad_centre_whole"),
            texts.get("cli.quad_centre_fans")
        )?;
        for q in &samples {
            writeln!(
                out,
                "{:>8} {:>14.4} {:>14.4}",
                q.angle_degrees, q.whole_centre, q.fans_centre
            )?;
        }
        Ok(())
    };
    print().map_err(output_error)
}
