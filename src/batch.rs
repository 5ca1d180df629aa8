//! `shadelab batch`: many meshes, several views and modes, into PNGs and an
//! index. The work is `shadelab-batch`'s; this is its command line.
//!
//! Exit codes: 0 when the run finished (even with error rows, unless
//! `--strict`); 2 for invalid input (arguments, scene file, manifest);
//! 1 when the output folder or index cannot be written; 3 with `--strict`
//! when any mesh or manifest line failed.

use std::path::PathBuf;

use clap::{Args, ValueEnum};
use shadelab_batch::{parse_modes, BatchConfig, Progress, Shard, Views};
use shadelab_io::PngCompression;

use crate::cli::SceneOverrides;
use crate::{input_error, output_error, read_scene, Failure};

/// `shadelab batch`
#[derive(Debug, Args)]
pub struct BatchArgs {
    /// The manifest: JSON Lines ({"path": …, "id": …} per line), or CSV with a
    /// `path[,id]` header (by the `.csv` extension). Paths are relative to it.
    pub manifest: PathBuf,
    /// Output folder: DIR/ID/VIEW_MODE.png for each output, and index.jsonl.
    #[arg(short, long, value_name = "DIR")]
    pub output: PathBuf,
    /// Scene file (TOML) with the shared settings; flags override its values.
    #[arg(long, value_name = "FILE")]
    pub scene: Option<PathBuf>,
    /// Views per mesh: N cameras on a ring about the up axis, or `cube` (six sides).
    #[arg(long, default_value = "1", value_parser = parse_views)]
    pub views: Views,
    /// Shading methods: flat, gouraud, phong or all, comma-separated (default: the scene's, else phong).
    #[arg(long, value_parser = parse_modes_arg)]
    pub shading: Option<Modes>,
    /// Only this share of the manifest, I/N (0-based), chosen by a stable hash of each id.
    #[arg(long, value_name = "I/N", value_parser = parse_shard)]
    pub shard: Option<Shard>,
    /// Draw every output again, even those already complete.
    #[arg(long)]
    pub force: bool,
    /// Exit with code 3 when any mesh or manifest line failed.
    #[arg(long)]
    pub strict: bool,
    /// Mesh paths must stay inside this folder (default: the manifest's folder).
    #[arg(long, value_name = "DIR")]
    pub root: Option<PathBuf>,
    /// Meshes drawn at once (default: two per core, so that drawing overlaps writing).
    #[arg(long, default_value_t = 0)]
    pub jobs: usize,
    /// Threads drawing each mesh's frames.
    #[arg(long, default_value_t = 1)]
    pub frame_threads: usize,
    /// Largest mesh file read, in bytes (larger files are error rows).
    #[arg(long, default_value_t = shadelab_io::MAX_MESH_BYTES)]
    pub max_mesh_bytes: u64,
    /// PNG compression: fast (default) or the smaller, slower default of zlib.
    #[arg(long, value_enum, default_value = "fast")]
    pub png: PngArg,
    /// Progress: a bar on a terminal, lines in a log (auto), or none.
    #[arg(long, value_enum, default_value = "auto")]
    pub progress: ProgressArg,
    /// Scene overrides (`--model` and `--detail` do not apply: meshes come from the manifest).
    #[command(flatten)]
    pub overrides: SceneOverrides,
}

/// `--png`
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum PngArg {
    /// Fast deflate, larger files.
    Fast,
    /// zlib's default level, smaller files.
    Small,
}

/// `--progress`
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum ProgressArg {
    /// A bar on a terminal, plain lines otherwise.
    Auto,
    /// Always a bar.
    Bar,
    /// Always plain lines.
    Lines,
    /// Nothing but the summary.
    None,
}

fn parse_views(s: &str) -> Result<Views, String> {
    s.parse()
}

fn parse_shard(s: &str) -> Result<Shard, String> {
    s.parse()
}

/// `--shading`: one or more methods.
#[derive(Debug, Clone)]
pub struct Modes(Vec<shadelab_core::Shading>);

fn parse_modes_arg(s: &str) -> Result<Modes, String> {
    parse_modes(s).map(Modes)
}

/// Runs `shadelab batch`.
pub fn run(args: &BatchArgs) -> Result<(), Failure> {
    if args.overrides.model.is_some() || args.overrides.params.has("model.detail") {
        return Err(input_error(anyhow::anyhow!(
            "--model and --detail do not apply to batch: the meshes come from the manifest"
        )));
    }
    let mut settings = read_scene(args.scene.as_deref())?;
    args.overrides
        .apply(&mut settings, args.scene.is_some())
        .map_err(input_error)?;
    let config = BatchConfig {
        settings,
        views: args.views,
        modes: args.shading.clone().map(|m| m.0),
        shard: args.shard.unwrap_or_default(),
        force: args.force,
        root: args.root.clone(),
        jobs: args.jobs,
        frame_threads: args.frame_threads,
        max_mesh_bytes: args.max_mesh_bytes,
        compression: match args.png {
            PngArg::Fast => PngCompression::Fast,
            PngArg::Small => PngCompression::Default,
        },
        progress: match args.progress {
            ProgressArg::Auto => Progress::Auto,
            ProgressArg::Bar => Progress::Bar,
            ProgressArg::Lines => Progress::Lines,
            ProgressArg::None => Progress::Quiet,
        },
        ..BatchConfig::new(&args.manifest, &args.output)
    };
    let summary = shadelab_batch::run(&config).map_err(|e| {
        if e.is_input_error() {
            input_error(e)
        } else {
            output_error(e)
        }
    })?;
    crate::warn(&format!("{summary}\n"));
    if args.strict && summary.has_errors() {
        return Err(Failure {
            code: 3,
            error: anyhow::anyhow!(
                "{} images and {} manifest lines failed (--strict); see {}",
                summary.failed,
                summary.bad_lines,
                summary.index.display()
            ),
        });
    }
    Ok(())
}
