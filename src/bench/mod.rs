//! `shadelab bench`: the standard scenes, timed frame by frame.
//!
//! Every row renders one standard scene (a model framed by the standard
//! camera, see [`standard_scene`]) at one size, with one shading method, one
//! rasterizer and a rayon pool of a given number of threads. Warm-up frames
//! (a few, and for at least `--warmup-time`) fill the caches and the
//! renderer's reusable buffers and wake the pool's threads; then frames
//! are timed one by one (until `--frames` are done or the row's time budget
//! is spent) and the median is reported, with the covered pixels and the
//! mesh's triangles per second at that median, and the processor cycles
//! per covered pixel: threads × time × clock, where the clock is measured
//! (see [`report::measure_clock_mhz`]; virtual machines often hide the cycle
//! counters from `perf`).
//!
//! `--export DIR` writes the same scenes for another renderer instead: the
//! exact triangles, vertex normals, flat-shading inputs, camera, light and
//! material, and the tiled rasterizer's image of each; `bench/llvmpipe/`
//! feeds them to Mesa's llvmpipe.

use std::io::Write as _;
use std::path::PathBuf;
use std::time::{Duration, Instant};

use anyhow::Context;
use clap::{Args, ValueEnum};
use shadelab_core::limits::{MAX_BENCH_BUDGET_SECONDS, MAX_THREADS, RENDER_BYTES_PER_PIXEL};
use shadelab_core::{Image, Rasterizer, RenderOptions, Renderer, Scene, Shading, SimdLevel};

use crate::cli::whole;
use crate::{input_error, output_error, Failure};

mod cores;
mod export;
mod report;
mod scene;

use export::export;
use report::{json, Machine};
use scene::{full_screen_quad, load_models, standard_scene, BACKGROUND};

/// `shadelab bench`
#[derive(Debug, Args)]
pub struct BenchArgs {
    /// Models to run (comma-separated or repeated): teapot, sphere, bunny, dragon, quad. Default: all.
    #[arg(long, value_enum, value_delimiter = ',')]
    pub model: Vec<BenchModel>,
    /// Image sizes, WIDTHxHEIGHT (comma-separated or repeated). Default: 512x512,1920x1080.
    #[arg(long, value_delimiter = ',', value_parser = parse_size, allow_hyphen_values = true)]
    pub size: Vec<(u32, u32)>,
    /// Shading methods (comma-separated or repeated). Default: all three.
    #[arg(long, value_parser = crate::cli::choice::<Shading>(), value_delimiter = ',')]
    pub shading: Vec<Shading>,
    /// Thread counts (comma-separated or repeated), each a rayon pool. Default: 1,2.
    #[arg(long, value_delimiter = ',', value_parser = whole::<u32, 1, { MAX_THREADS as u64 }>, allow_hyphen_values = true)]
    pub threads: Vec<u32>,
    /// Rasterizers (comma-separated or repeated). Default: tiled,scanline.
    #[arg(long, value_parser = crate::cli::choice::<Rasterizer>(), value_delimiter = ',')]
    pub rasterizer: Vec<Rasterizer>,
    /// Timed frames per row (fewer if the row's time budget runs out first).
    #[arg(long, default_value_t = 31, value_parser = whole::<u32, 1, 100_000>, allow_hyphen_values = true)]
    pub frames: u32,
    /// Untimed frames before timing (at least this many, and for at least --warmup-time).
    #[arg(long, default_value_t = 3, value_parser = whole::<u32, 0, 100_000>, allow_hyphen_values = true)]
    pub warmup: u32,
    /// Untimed warm-up per row, seconds, at least: a thread pool that has just been idle
    /// (the row before ran on another pool) can take tens of milliseconds to run at full
    /// speed again, which a few warm-up frames do not cover.
    #[arg(long, default_value_t = 0.25, allow_negative_numbers = true)]
    pub warmup_time: f64,
    /// Time budget per row, seconds (at least 3 frames are timed whatever it is).
    #[arg(long, default_value_t = 3.0, allow_negative_numbers = true)]
    pub budget: f64,
    /// The tiled rasterizer's SIMD level; default: the best this CPU has.
    #[arg(long, value_parser = crate::cli::choice::<SimdLevel>())]
    pub simd: Option<SimdLevel>,
    /// Where the bunny and dragon meshes are; default ../shared/models.
    #[arg(long)]
    pub models_dir: Option<PathBuf>,
    /// Print JSON (one object: machine, then one record per row, with each
    /// timed frame's milliseconds in the order they ran) instead of a table.
    #[arg(long)]
    pub json: bool,
    /// Write the scenes' geometry and images for another renderer to DIR, and time nothing.
    #[arg(long, value_name = "DIR")]
    pub export: Option<PathBuf>,
}

/// The models of the standard set.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum BenchModel {
    /// The built-in Utah teapot at its default detail.
    Teapot,
    /// The built-in UV sphere at its default detail.
    Sphere,
    /// The Stanford bunny (stanford-bunny.obj), when the models folder has it.
    Bunny,
    /// The 100k-triangle Asian dragon (dragon_100k.obj), when the models folder has it.
    Dragon,
    /// Two triangles covering the whole image.
    Quad,
}

impl BenchModel {
    const ALL: [BenchModel; 5] = [
        BenchModel::Teapot,
        BenchModel::Sphere,
        BenchModel::Bunny,
        BenchModel::Dragon,
        BenchModel::Quad,
    ];

    fn name(self) -> &'static str {
        match self {
            BenchModel::Teapot => "teapot",
            BenchModel::Sphere => "sphere",
            BenchModel::Bunny => "bunny",
            BenchModel::Dragon => "dragon",
            BenchModel::Quad => "quad",
        }
    }

    /// The mesh file in the models folder, for the models that have one.
    fn file(self) -> Option<&'static str> {
        match self {
            BenchModel::Bunny => Some("stanford-bunny.obj"),
            BenchModel::Dragon => Some("dragon_100k.obj"),
            _ => None,
        }
    }
}

fn parse_size(s: &str) -> Result<(u32, u32), String> {
    crate::cli::parse_size(s)
}

/// The defaults where a filter was not given.
fn or_all<T: Copy>(given: &[T], all: &[T]) -> Vec<T> {
    if given.is_empty() {
        all.to_vec()
    } else {
        given.to_vec()
    }
}

/// One timed row.
struct Row {
    model: &'static str,
    triangles: usize,
    width: u32,
    height: u32,
    shading: Shading,
    rasterizer: Rasterizer,
    threads: u32,
    median_ms: f64,
    min_ms: f64,
    /// Each timed frame's milliseconds, in the order they ran: a machine
    /// whose speed changes in phases (BENCHMARKS.md, "The same code on an
    /// AMD EPYC") shows it here, where the median hides it.
    frame_ms: Vec<f64>,
    covered_pixels: u64,
    fragments: u64,
}

impl Row {
    fn mpixels_per_s(&self) -> f64 {
        self.covered_pixels as f64 / self.median_ms / 1e3
    }

    /// Cycles of all the row's threads per covered pixel at the median
    /// time, for a clock of `mhz`.
    fn cycles_per_pixel(&self, mhz: f64) -> f64 {
        f64::from(self.threads) * self.median_ms * 1e3 * mhz / self.covered_pixels.max(1) as f64
    }

    fn mtriangles_per_s(&self) -> f64 {
        self.triangles as f64 / self.median_ms / 1e3
    }
}

/// Runs `shadelab bench`.
pub fn run(args: &BenchArgs) -> Result<(), Failure> {
    for (flag, seconds) in [
        ("--budget", args.budget),
        ("--warmup-time", args.warmup_time),
    ] {
        if !(seconds.is_finite() && (0.0..=MAX_BENCH_BUDGET_SECONDS).contains(&seconds)) {
            return Err(input_error(anyhow::anyhow!(
                "{flag} must be a number of seconds in 0..={MAX_BENCH_BUDGET_SECONDS}, got {seconds}"
            )));
        }
    }
    let simd = args.simd.unwrap_or_else(SimdLevel::detect);
    if !simd.is_supported() {
        let can: Vec<&str> = SimdLevel::supported().map(SimdLevel::name).collect();
        return Err(input_error(anyhow::anyhow!(
            "--simd {simd}: this CPU cannot run it (it can run {})",
            can.join(", ")
        )));
    }
    let selected = or_all(&args.model, &BenchModel::ALL);
    let sizes = or_all(&args.size, &[(512, 512), (1920, 1080)]);
    let shadings = or_all(
        &args.shading,
        &[Shading::Flat, Shading::Gouraud, Shading::Phong],
    );
    let threads = or_all(&args.threads, &[1, 2]);
    let rasterizers = or_all(&args.rasterizer, &[Rasterizer::Tiled, Rasterizer::Scanline]);
    let models = load_models(args, &selected).map_err(input_error)?;
    for model in &models {
        for &(width, height) in &sizes {
            crate::memory::check(
                "bench",
                Some(&model.mesh),
                u64::from(width) * u64::from(height),
                RENDER_BYTES_PER_PIXEL,
            )?;
        }
    }
    if let Some(dir) = &args.export {
        return export(dir, &models, &sizes, &shadings).map_err(output_error);
    }

    let mut pools = Vec::new();
    for &n in &threads {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(n as usize)
            .build()
            .context("cannot start a thread pool")
            .map_err(output_error)?;
        pools.push((n, pool));
    }
    let machine = Machine::detect(simd);
    let mut out = std::io::stdout().lock();
    if !args.json {
        let mut heading = || -> std::io::Result<()> {
            writeln!(
                out,
                "shadelab bench: {} ({} cores, clock {:.0} MHz measured{}), tiled rasterizer SIMD {}; median of up to {} frames after {} warm-up frames and at least {} s of them",
                machine.cpu,
                machine.cores,
                machine.clock_mhz,
                machine
                    .round_trip_ns
                    .map_or_else(String::new, |ns| format!(", a cache line's round trip between two cores {ns:.0} ns")),
                machine.simd,
                args.frames,
                args.warmup,
                args.warmup_time
            )?;
            for m in &models {
                writeln!(
                    out,
                    "  {:<7} {:>7} triangles  {}",
                    m.kind.name(),
                    m.mesh.triangle_count(),
                    m.source
                )?;
            }
            writeln!(out)?;
            writeln!(out, "{}", Row::header())?;
            out.flush()
        };
        heading().map_err(output_error)?;
    }
    let mut rows = Vec::new();
    for model in &models {
        for &(width, height) in &sizes {
            let aspect = width as f32 / height as f32;
            let mesh = match model.kind {
                BenchModel::Quad => full_screen_quad(aspect),
                _ => model.mesh.clone(),
            };
            let triangles = mesh.triangle_count();
            let scene = standard_scene(mesh, aspect, model.kind == BenchModel::Quad);
            for &shading in &shadings {
                for &rasterizer in &rasterizers {
                    for (threads, pool) in &pools {
                        let options = options(width, height, shading, rasterizer);
                        let row =
                            time_row(args, pool, simd, &scene, &options).map_err(input_error)?;
                        let row = Row {
                            model: model.kind.name(),
                            triangles,
                            threads: *threads,
                            ..row
                        };
                        if !args.json {
                            writeln!(out, "{}", row.line(machine.clock_mhz))
                                .and_then(|()| out.flush())
                                .map_err(output_error)?;
                        }
                        rows.push(row);
                    }
                }
            }
        }
    }
    if args.json {
        writeln!(out, "{}", json(&machine, args, &rows))
            .and_then(|()| out.flush())
            .map_err(output_error)?;
    }
    Ok(())
}

fn options(width: u32, height: u32, shading: Shading, rasterizer: Rasterizer) -> RenderOptions {
    RenderOptions {
        width,
        height,
        shading,
        rasterizer,
        background: BACKGROUND,
        cull_backfaces: true,
        ..RenderOptions::default()
    }
}

/// Times one row: warm-up, then frames until the count or the budget is reached.
///
/// The warm-up is timed as well as counted: on a virtual machine, the first
/// tens of milliseconds on a pool whose threads were idle (the row before
/// ran on the 1-thread pool) ran at about one thread's speed, so a 31-frame
/// row's median mixed the two (bunny 512² flat, 2 threads: 2.6 ms with 3
/// warm-up frames, 1.45 ms after 40).
fn time_row(
    args: &BenchArgs,
    pool: &rayon::ThreadPool,
    simd: SimdLevel,
    scene: &Scene,
    options: &RenderOptions,
) -> anyhow::Result<Row> {
    pool.install(|| time_frames(args, simd, scene, options))
}

/// [`time_row`]'s frames, run on one of the pool's threads, as `shadelab
/// batch` renders (each of its workers installs its pool once, then renders
/// mesh after mesh inside it). A frame's parallel work then starts and ends
/// on a thread that takes part in it.
///
/// Timed from outside the pool, every frame also paid for waking the
/// sleeping caller: 20–40 µs on the KVM AMD EPYC of BENCHMARKS.md, which
/// was a third of the 512² quad's one-thread frame (0.12 ms against 0.073
/// ms timed here) and no part of rendering.
fn time_frames(
    args: &BenchArgs,
    simd: SimdLevel,
    scene: &Scene,
    options: &RenderOptions,
) -> anyhow::Result<Row> {
    let mut renderer = Renderer::with_simd(simd);
    let mut image = Image::filled(options.width, options.height, options.background);
    let mut stats = Default::default();
    let warmup_time = Duration::from_secs_f64(args.warmup_time);
    let warm = Instant::now();
    let mut warmed = 0;
    while warmed < args.warmup || warm.elapsed() < warmup_time {
        stats = renderer.render_into(scene, options, &mut image)?;
        warmed += 1;
    }
    let budget = Duration::from_secs_f64(args.budget.max(0.0));
    let start = Instant::now();
    let mut times = Vec::with_capacity(args.frames as usize);
    while times.len() < args.frames as usize && (times.len() < 3 || start.elapsed() < budget) {
        let t = Instant::now();
        stats = renderer.render_into(scene, options, &mut image)?;
        times.push(t.elapsed().as_secs_f64() * 1e3);
    }
    let frame_ms = times.clone();
    times.sort_by(f64::total_cmp);
    let n = times.len();
    let median = if n % 2 == 1 {
        times[n / 2]
    } else {
        (times[n / 2 - 1] + times[n / 2]) / 2.0
    };
    Ok(Row {
        model: "",
        triangles: 0,
        width: options.width,
        height: options.height,
        shading: options.shading,
        rasterizer: options.rasterizer,
        threads: 0,
        median_ms: median,
        min_ms: times[0],
        frame_ms,
        covered_pixels: stats.covered_pixels,
        fragments: stats.fragments_shaded,
    })
}

impl Row {
    fn header() -> String {
        format!(
            "{:<7} {:>7} {:>10} {:<8} {:<9} {:>3} {:>9} {:>9} {:>9} {:>8} {:>7} {:>6}",
            "model",
            "tris",
            "size",
            "shading",
            "raster",
            "thr",
            "ms/frame",
            "min ms",
            "Mpix/s",
            "Mtri/s",
            "cyc/px",
            "frames"
        )
    }

    fn line(&self, mhz: f64) -> String {
        format!(
            "{:<7} {:>7} {:>10} {:<8} {:<9} {:>3} {:>9.3} {:>9.3} {:>9.1} {:>8.2} {:>7.1} {:>6}",
            self.model,
            self.triangles,
            format!("{}x{}", self.width, self.height),
            self.shading.name(),
            self.rasterizer.name(),
            self.threads,
            self.median_ms,
            self.min_ms,
            self.mpixels_per_s(),
            self.mtriangles_per_s(),
            self.cycles_per_pixel(mhz),
            self.frame_ms.len()
        )
    }
}
