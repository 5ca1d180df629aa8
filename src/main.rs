//! The `shadelab` command: render a scene with one shading method, or all
//! three side by side.
//!
//! Exit codes: 0 on success; 2 for invalid input (arguments, scene file,
//! model file, out-of-range values); 1 when the output cannot be written.

mod accuracy;
mod batch;
mod bench;
mod cli;
mod compare;
mod cost;
mod errors;
mod explain;
mod lab;
mod label;
mod memory;
mod param_flags;
mod plot;
mod profile;
mod quad;
mod server;
mod site;
mod view;

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use anyhow::Context;
use clap::Parser as _;
use shadelab_core::limits::{MAX_THREADS, RENDER_BYTES_PER_PIXEL};
use shadelab_core::{
    escape_message, escape_token, render, Image, RenderOptions, RenderStats, Scene, Shading,
    BUILTIN_MODELS,
};
use shadelab_io::{model_path, write_png, SceneFile};
use shadelab_lab::{draw_overlays, Texts};

use cli::{Cli, Command};

/// A failure and the exit code it maps to.
struct Failure {
    code: u8,
    error: anyhow::Error,
}

fn input_error(error: impl Into<anyhow::Error>) -> Failure {
    Failure {
        code: 2,
        error: error.into(),
    }
}

fn output_error(error: impl Into<anyhow::Error>) -> Failure {
    Failure {
        code: 1,
        error: error.into(),
    }
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) if e.use_stderr() => {
            // The arguments are repeated in clap's message: escaped like
            // every other message.
            warn(&e.render().to_string());
            return ExitCode::from(2);
        }
        // Help and version, on standard output.
        Err(e) => {
            return match e.print() {
                Ok(()) => ExitCode::SUCCESS,
                Err(io) if io.kind() == std::io::ErrorKind::BrokenPipe => ExitCode::SUCCESS,
                Err(io) => {
                    warn(&format!("error: cannot write to standard output: {io}\n"));
                    ExitCode::from(1)
                }
            };
        }
    };
    match configure_threads().and_then(|()| run(cli)) {
        Ok(()) => ExitCode::SUCCESS,
        Err(f) => {
            if is_broken_pipe(&f.error) {
                return ExitCode::SUCCESS;
            }
            warn(&format!("error: {}\n", message(&f.error)));
            ExitCode::from(f.code)
        }
    }
}

/// Writes `text` to standard error, escaped ([`escape_message`]); a
/// standard error that is closed or full loses it, and nothing panics.
pub(crate) fn warn(text: &str) {
    let _ = std::io::stderr().write_all(escape_message(text).as_bytes());
}

/// Starts rayon's global pool with the number of threads
/// `RAYON_NUM_THREADS` asks for (0 or unset: one per core), at most
/// [`MAX_THREADS`], so that a wrong value is an error rather than a panic
/// inside the first frame.
fn configure_threads() -> Result<(), Failure> {
    let threads = match std::env::var("RAYON_NUM_THREADS") {
        Err(std::env::VarError::NotPresent) => 0,
        Ok(v) => match v.trim().parse::<usize>() {
            Ok(n) if n <= MAX_THREADS => n,
            _ => {
                return Err(input_error(anyhow::anyhow!(
                    "RAYON_NUM_THREADS={}: must be a whole number of threads, 0..={MAX_THREADS} \
                     (0: one per core)",
                    escape_token(&v)
                )));
            }
        },
        Err(std::env::VarError::NotUnicode(_)) => {
            return Err(input_error(anyhow::anyhow!(
                "RAYON_NUM_THREADS is not text: must be a whole number of threads, \
                 0..={MAX_THREADS}"
            )));
        }
    };
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build_global()
        .with_context(|| format!("cannot start {threads} threads"))
        .map_err(output_error)
}

/// The error and its causes, joined with ": " as `{:#}` does, but leaving out
/// a cause whose text is already shown (the I/O errors of `shadelab-io` both
/// display their source and return it from `source()`).
fn message(e: &anyhow::Error) -> String {
    let mut out = String::new();
    for cause in e.chain() {
        let text = cause.to_string();
        if out.contains(&text) {
            continue;
        }
        if !out.is_empty() {
            out.push_str(": ");
        }
        out.push_str(&text);
    }
    out
}

fn is_broken_pipe(e: &anyhow::Error) -> bool {
    e.chain()
        .filter_map(|c| c.downcast_ref::<std::io::Error>())
        .any(|io| io.kind() == std::io::ErrorKind::BrokenPipe)
}

fn run(cli: Cli) -> Result<(), Failure> {
    match cli.command {
        Command::Render(args) => {
            let mut file = read_scene(args.scene.as_deref())?;
            args.overrides
                .apply(&mut file, args.scene.is_some())
                .map_err(input_error)?;
            if let Some(s) = args.shading {
                file.render.shading = Some(s);
            }
            let (scene, options, inputs) = resolve(&file, args.scene.as_deref())?;
            check_output(&args.output, &inputs)?;
            memory::check(
                "render",
                Some(&scene.mesh),
                pixels(&options),
                RENDER_BYTES_PER_PIXEL,
            )?;
            let (mut image, stats, ms) = timed_render(&scene, &options)?;
            if let Some(overlays) = args.overlay.overlay {
                draw_overlays(&mut image, &scene, &options, overlays).map_err(input_error)?;
            }
            write_png(&args.output, &image)
                .with_context(|| format!("cannot write {}", args.output.display()))
                .map_err(output_error)?;
            report(
                &Texts::new(args.lang.into()),
                options.shading,
                &options,
                &stats,
                ms,
            );
            Ok(())
        }
        Command::Compare(args) => compare::run(&args),
        Command::Explain(args) => explain::run(&args),
        Command::Profile(args) => profile::run(&args),
        Command::Errors(args) => errors::run(&args),
        Command::Accuracy(args) => accuracy::run(&args),
        Command::Quad(args) => quad::run(&args),
        Command::Cost(args) => cost::run(&args),
        Command::Bench(args) => bench::run(&args),
        Command::Batch(args) => batch::run(&args),
        Command::Models(args) => {
            let texts = Texts::new(args.lang.into());
            let mut out = std::io::stdout().lock();
            let mut list = || -> std::io::Result<()> {
                writeln!(
                    out,
                    "{:<10} {:>7}  {:<48} {}",
                    texts.get("cli.models_name"),
                    texts.get("cli.models_default"),
                    texts.get("cli.models_description"),
                    texts.get("cli.models_detail")
                )?;
                for m in BUILTIN_MODELS {
                    let description = format!("model.{}", m.name);
                    let meaning = format!("model.{}_detail", m.name);
                    writeln!(
                        out,
                        "{:<10} {:>7}  {:<48} {} ({}..={})",
                        m.name,
                        m.default_detail,
                        texts.get(&description),
                        texts.get(&meaning),
                        m.detail_range.0,
                        m.detail_range.1
                    )?;
                }
                Ok(())
            };
            list().map_err(output_error)
        }
        Command::View(args) => view::view(&view::ViewRequest {
            host: args.host,
            port: args.port,
            open: !args.no_open,
            export: args.export.as_deref(),
            lang: args.lang,
        })
        .map_err(output_error),
    }
}

fn read_scene(path: Option<&Path>) -> Result<SceneFile, Failure> {
    match path {
        Some(p) => SceneFile::load(p).map_err(input_error),
        None => Ok(SceneFile::default()),
    }
}

/// The scene and options, and the files they were read from.
fn resolve(
    file: &SceneFile,
    scene_path: Option<&Path>,
) -> Result<(Scene, RenderOptions, Vec<PathBuf>), Failure> {
    let base_dir = scene_path
        .and_then(Path::parent)
        .map(Path::to_path_buf)
        .unwrap_or_default();
    let mut warnings = Vec::new();
    let result = file.resolve_reporting(&base_dir, &mut warnings);
    for w in &warnings {
        warn(&format!("warning: {w}\n"));
    }
    let (scene, options) = result.map_err(input_error)?;
    let mut inputs: Vec<PathBuf> = scene_path.map(Path::to_path_buf).into_iter().collect();
    if let Some(source) = &file.model.source {
        let model = model_path(source, &base_dir);
        // Its material libraries and external buffers are the user's too.
        inputs.extend(shadelab_io::companion_files(&model));
        inputs.push(model);
    }
    Ok((scene, options, inputs))
}

/// Refuses to write the image over one of the command's own inputs (the
/// scene file, the model, and the files the model reads).
fn check_output(output: &Path, inputs: &[PathBuf]) -> Result<(), Failure> {
    let Ok(out) = output.canonicalize() else {
        return Ok(());
    };
    for input in inputs {
        if input.canonicalize().is_ok_and(|i| i == out) {
            return Err(input_error(anyhow::anyhow!(
                "refusing to write the image over its own input {}",
                input.display()
            )));
        }
    }
    Ok(())
}

/// The pixels of one frame of `options`.
fn pixels(options: &RenderOptions) -> u64 {
    u64::from(options.width) * u64::from(options.height)
}

fn timed_render(
    scene: &Scene,
    options: &RenderOptions,
) -> Result<(Image, RenderStats, f64), Failure> {
    let start = Instant::now();
    let (image, stats) = render(scene, options).map_err(input_error)?;
    Ok((image, stats, start.elapsed().as_secs_f64() * 1e3))
}

/// Prints what a render cost, in the language of `texts`.
fn report(texts: &Texts, shading: Shading, options: &RenderOptions, stats: &RenderStats, ms: f64) {
    let method = format!("{:<8}", texts.get(compare::title_id(shading)));
    warn(&format!(
        "{}\n",
        texts.fill(
            "cli.report",
            &[
                ("method", &method),
                ("size", &format!("{}x{}", options.width, options.height)),
                ("ms", &format!("{ms:>8.2}")),
                ("rasterized", &stats.rasterized.to_string()),
                ("culled", &stats.culled.to_string()),
                ("pixels", &stats.fragments_shaded.to_string()),
                ("evaluations", &stats.lighting_evaluations.to_string()),
            ],
        )
    ));
}
