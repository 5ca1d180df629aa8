//! `shadelab compare`: flat, Gouraud and Phong side by side, labelled, in one
//! image — or, with `--orbit N`, in each of N frames of one full orbit of
//! the camera, written as an animated PNG (for slides).
//!
//! The sheet: a label band of [`LABEL_BAND`] pixels above the panels, which
//! stand [`GAP`] pixels apart, as the viewer's "Save PNG" lays them out.
//! English labels are drawn with the 8×8 bitmap font (so that the sheet's
//! pixels stay those of earlier versions); labels in another language, which
//! need letters outside ASCII, with the embedded DejaVu Sans. Files are
//! written through [`shadelab_io::write_atomic`], as every output is.

use std::path::Path;

use anyhow::Context;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use shadelab_core::limits::COMPARE_BYTES_PER_PIXEL;
use shadelab_core::{Image, RenderOptions, RenderStats, Rgb8, Scene, Shading};
use shadelab_lab::{draw_overlays, Overlays, Texts};

use crate::cli::CompareArgs;
use crate::plot::{draw_on, err, font};
use crate::{
    check_output, input_error, output_error, read_scene, report, resolve, timed_render, Failure,
};

/// Height of the label band above each panel.
pub const LABEL_BAND: u32 = 28;
/// Width of the gap between panels.
pub const GAP: u32 = 4;
/// The most frames an orbit may have.
pub const MAX_ORBIT_FRAMES: u32 = 720;

/// Runs `shadelab compare`.
pub fn run(args: &CompareArgs) -> Result<(), Failure> {
    let scene_path = args.scene.as_deref();
    let mut file = read_scene(scene_path)?;
    // Panels default to a square that three fit side by side on a laptop screen.
    if file.render.width.is_none() && file.render.height.is_none() {
        file.render.width = Some(480);
        file.render.height = Some(480);
    }
    args.overrides
        .apply(&mut file, scene_path.is_some())
        .map_err(input_error)?;
    let texts = Texts::new(args.lang.into());
    if let Some(frames) = args.orbit {
        check_orbit(frames, args.delay, &args.output)?;
        let yaw = file.render.yaw.unwrap_or(0.0);
        let (scene, options, inputs) = resolve(&file, scene_path)?;
        check_output(&args.output, &inputs)?;
        check_memory(&scene, &options)?;
        drop(scene);
        let (w, h) = sheet_size(&options);
        // Frames are drawn while the file is written (only one is held at a
        // time); a frame that cannot be drawn stops the write, and nothing
        // is left behind.
        let mut failed = None;
        let written = shadelab_io::write_atomic(&args.output, |out| {
            let mut encoder = png::Encoder::new(out, w, h);
            encoder.set_color(png::ColorType::Rgb);
            encoder.set_depth(png::BitDepth::Eight);
            encoder
                .set_animated(frames, 0)
                .map_err(std::io::Error::other)?;
            encoder
                .set_frame_delay(args.delay, 1000)
                .map_err(std::io::Error::other)?;
            let mut writer = encoder.write_header().map_err(std::io::Error::other)?;
            for k in 0..frames {
                file.render.yaw = Some(yaw + 360.0 * k as f32 / frames as f32);
                let frame = resolve(&file, scene_path).and_then(|(scene, options, _)| {
                    sheet(&scene, &options, args.overlay.overlay, &texts)
                });
                match frame {
                    Ok((image, _)) => writer
                        .write_image_data(&image.to_rgb_bytes())
                        .map_err(std::io::Error::other)?,
                    Err(f) => {
                        failed = Some(f);
                        return Err(std::io::Error::other("a frame could not be drawn"));
                    }
                }
            }
            writer.finish().map_err(std::io::Error::other)
        });
        if let Some(f) = failed {
            return Err(f);
        }
        written
            .with_context(|| format!("cannot write {}", args.output.display()))
            .map_err(output_error)?;
        let line = texts.fill(
            "cli.orbit_written",
            &[
                ("frames", &frames.to_string()),
                ("width", &w.to_string()),
                ("height", &h.to_string()),
                ("delay", &args.delay.to_string()),
                ("path", &args.output.display().to_string()),
            ],
        );
        crate::warn(&format!("{line}\n"));
        return Ok(());
    }
    let (scene, options, inputs) = resolve(&file, scene_path)?;
    check_output(&args.output, &inputs)?;
    check_memory(&scene, &options)?;
    let (sheet, reports) = sheet(&scene, &options, args.overlay.overlay, &texts)?;
    shadelab_io::write_png(&args.output, &sheet)
        .with_context(|| format!("cannot write {}", args.output.display()))
        .map_err(output_error)?;
    for (shading, options, stats, ms) in reports {
        report(&texts, shading, &options, &stats, ms);
    }
    Ok(())
}

/// The memory a sheet of three panels needs, estimated before any is drawn.
fn check_memory(scene: &Scene, options: &RenderOptions) -> Result<(), Failure> {
    crate::memory::check(
        "compare",
        Some(&scene.mesh),
        crate::pixels(options),
        COMPARE_BYTES_PER_PIXEL,
    )
}

/// An orbit's frame count, delay and file name, checked before anything is drawn.
fn check_orbit(frames: u32, delay: u16, output: &Path) -> Result<(), Failure> {
    if !(1..=MAX_ORBIT_FRAMES).contains(&frames) {
        return Err(input_error(anyhow::anyhow!(
            "--orbit must be 1..={MAX_ORBIT_FRAMES} frames, got {frames}"
        )));
    }
    if delay == 0 {
        return Err(input_error(anyhow::anyhow!(
            "--delay must be at least 1 ms"
        )));
    }
    let extension = output
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    match extension.as_deref() {
        Some("apng" | "png") => Ok(()),
        Some("webp") => Err(input_error(anyhow::anyhow!(
            "{}: animated WebP is not supported (no well-kept Rust crate writes it without \
             libwebp); write an animated PNG instead: -o {}",
            output.display(),
            output.with_extension("apng").display()
        ))),
        _ => Err(input_error(anyhow::anyhow!(
            "{}: an orbit is written as an animated PNG: name the file .apng (or .png)",
            output.display()
        ))),
    }
}

/// The size of the sheet for panels of `options`' size.
fn sheet_size(options: &RenderOptions) -> (u32, u32) {
    (3 * options.width + 2 * GAP, options.height + LABEL_BAND)
}

/// What one panel reports: its method, options, counts and time.
type PanelReport = (Shading, RenderOptions, RenderStats, f64);

/// The three panels side by side under their labels, and what each reports.
fn sheet(
    scene: &Scene,
    options: &RenderOptions,
    overlays: Option<Overlays>,
    texts: &Texts,
) -> Result<(Image, Vec<PanelReport>), Failure> {
    let w = options.width;
    let (total_width, total_height) = sheet_size(options);
    let band = Rgb8::new(32, 32, 40);
    let white = Rgb8::new(240, 240, 240);
    let mut sheet = Image::filled(total_width, total_height, band);
    let mut reports = Vec::with_capacity(3);
    let mut titles = Vec::with_capacity(3);
    for (k, shading) in Shading::ALL.into_iter().enumerate() {
        let options = RenderOptions {
            shading,
            ..*options
        };
        let (mut panel, stats, ms) = timed_render(scene, &options)?;
        if let Some(overlays) = overlays {
            draw_overlays(&mut panel, scene, &options, overlays).map_err(input_error)?;
        }
        let x = k as u32 * (w + GAP);
        sheet.blit(&panel, x, LABEL_BAND);
        let title = texts.get(title_id(shading));
        if title.is_ascii() {
            let scale = if crate::label::text_width(title, 2) + 8 <= w {
                2
            } else {
                1
            };
            let tx = x + w.saturating_sub(crate::label::text_width(title, scale)) / 2;
            crate::label::draw_text(
                &mut sheet,
                title,
                tx,
                (LABEL_BAND - 8 * scale) / 2,
                scale,
                white,
            );
        } else {
            titles.push((title.to_owned(), x + w / 2));
        }
        reports.push((shading, options, stats, ms));
    }
    if !titles.is_empty() {
        sheet = draw_on(&sheet, |root| {
            let style =
                font(18.0, RGBColor(240, 240, 240)).pos(Pos::new(HPos::Center, VPos::Center));
            for (title, cx) in &titles {
                root.draw(&Text::new(
                    title.as_str(),
                    (*cx as i32, (LABEL_BAND / 2) as i32),
                    style.clone(),
                ))
                .map_err(err)?;
            }
            Ok(())
        })
        .map_err(output_error)?;
    }
    Ok((sheet, reports))
}

/// The text id of a method's short name.
pub fn title_id(shading: Shading) -> &'static str {
    match shading {
        Shading::Flat => "cli.flat",
        Shading::Gouraud => "cli.gouraud",
        Shading::Phong => "cli.phong",
    }
}
