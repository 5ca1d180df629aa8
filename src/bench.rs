//! `shadelab bench`: the standard scenes, timed frame by frame.
//!
//! Every row renders one standard scene (a model framed by the standard
//! camera, see [`standard_scene`]) at one size, with one shading method, one
//! rasterizer and a rayon pool of a given number of threads. A few warm-up
//! frames fill the caches and the renderer's reusable buffers; then frames
//! are timed one by one (until `--frames` are done or the row's time budget
//! is spent) and the median is reported, with the covered pixels and the
//! mesh's triangles per second at that median, and the processor cycles
//! per covered pixel: threads × time × clock, where the clock is measured
//! (see [`measure_clock_mhz`]; virtual machines often hide the cycle
//! counters from `perf`).
//!
//! `--export DIR` writes the same scenes for another renderer instead: the
//! exact triangles, vertex normals, flat-shading inputs, camera, light and
//! material, and the tiled rasterizer's image of each; `bench/llvmpipe/`
//! feeds them to Mesa's llvmpipe.

use std::fmt::Write as _;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use anyhow::{bail, Context};
use clap::{Args, ValueEnum};
use glam::Vec3;
use shadelab_core::limits::{MAX_BENCH_BUDGET_SECONDS, MAX_THREADS, RENDER_BYTES_PER_PIXEL};
use shadelab_core::{
    builtin_model, face_normal, vertex_normals, Camera, Image, Light, LightKind, Material, Mesh,
    NormalWeighting, Rasterizer, RenderOptions, Renderer, Rgb, Rgb8, Scene, Shading,
};

use crate::cli::whole;
use crate::{input_error, output_error, Failure};

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
    /// Untimed frames before timing.
    #[arg(long, default_value_t = 3, value_parser = whole::<u32, 0, 100_000>, allow_hyphen_values = true)]
    pub warmup: u32,
    /// Time budget per row, seconds (at least 3 frames are timed whatever it is).
    #[arg(long, default_value_t = 3.0, allow_negative_numbers = true)]
    pub budget: f64,
    /// Where the bunny and dragon meshes are; default ../shared/models.
    #[arg(long)]
    pub models_dir: Option<PathBuf>,
    /// Print JSON (one object: machine, then one record per row) instead of a table.
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

/// The standard material and lights, as 0–1 colours.
const AMBIENT: [u8; 3] = [255, 255, 255];
const AMBIENT_INTENSITY: f32 = 0.2;
const KA: [u8; 3] = [77, 64, 51];
const KD: [u8; 3] = [204, 153, 102];
const KS: [u8; 3] = [128, 128, 128];
const SHININESS: f32 = 32.0;
const BACKGROUND: Rgb8 = Rgb8::new(26, 26, 31);
/// Half the vertical field of view, degrees.
const HALF_FOV: f32 = 22.5;

fn rgb(c: [u8; 3]) -> Rgb {
    Rgb8(c).to_rgb()
}

/// A loaded model of the standard set.
struct Model {
    kind: BenchModel,
    mesh: Mesh,
    /// Where it came from, for the report.
    source: String,
}

/// The standard scene of `mesh` for an image of `aspect` (width / height):
/// camera on +z of the bounding-box centre `c`, 45° vertical field of view,
/// distance `hz + 1.1·max(hy/tan 22.5°, hx/(tan 22.5°·aspect))` (`h` the half
/// extents), near `max(d − 2r, 0.01·d)`, far `d + 2r` (`r = |h|`); one white
/// point light at `c + d·(1, 1.5, 1.2)`; ambient white × 0.2; Ka (77, 64, 51),
/// Kd (204, 153, 102), Ks (128, 128, 128), shininess 32; uniform vertex
/// normals. The full-screen quad instead has its camera at distance 1.
pub fn standard_scene(mesh: Mesh, aspect: f32, full_screen: bool) -> Scene {
    let (lo, hi) = mesh.bounds();
    let centre = (lo + hi) * 0.5;
    let half = (hi - lo) * 0.5;
    let radius = half.length();
    let t = HALF_FOV.to_radians().tan();
    let distance = if full_screen {
        1.0
    } else {
        half.z + 1.1 * (half.y / t).max(half.x / (t * aspect))
    };
    let camera = Camera {
        eye: centre + Vec3::Z * distance,
        target: centre,
        up: Vec3::Y,
        fov_y_degrees: 2.0 * HALF_FOV,
        near: (distance - 2.0 * radius).max(0.01 * distance),
        far: distance + 2.0 * radius,
    };
    let normals = vertex_normals(&mesh, NormalWeighting::Uniform, None);
    Scene {
        mesh,
        normals,
        camera,
        ambient: rgb(AMBIENT) * AMBIENT_INTENSITY,
        lights: vec![Light {
            kind: LightKind::Point {
                position: centre + distance * Vec3::new(1.0, 1.5, 1.2),
            },
            color: Rgb::WHITE,
            intensity: 1.0,
        }],
        material: Material {
            ka: rgb(KA),
            kd: rgb(KD),
            ks: rgb(KS),
            shininess: SHININESS,
        },
    }
}

/// Two triangles in the plane z = 0 reaching 2 % past every side of the
/// image seen from the full-screen quad's camera (distance 1, 45°).
fn full_screen_quad(aspect: f32) -> Mesh {
    let hy = HALF_FOV.to_radians().tan() * 1.02;
    let hx = hy * aspect;
    let positions = vec![
        Vec3::new(-hx, -hy, 0.0),
        Vec3::new(hx, -hy, 0.0),
        Vec3::new(hx, hy, 0.0),
        Vec3::new(-hx, hy, 0.0),
    ];
    Mesh::from_polygons(positions, [[0u32, 1, 2], [0, 2, 3]]).expect("a valid quad")
}

/// The models folder: `--models-dir`, else `../shared/models` from the
/// working directory, else beside the source tree.
fn models_dir(args: &BenchArgs) -> Option<PathBuf> {
    if let Some(dir) = &args.models_dir {
        return Some(dir.clone());
    }
    let candidates = [
        PathBuf::from("../shared/models"),
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/models"),
    ];
    candidates.into_iter().find(|d| d.is_dir())
}

/// Loads the selected models, noting on stderr the ones that are missing
/// when none was asked for by name; a missing `--models-dir`, or a model
/// asked for by name whose file is missing, is an error.
fn load_models(args: &BenchArgs, selected: &[BenchModel]) -> anyhow::Result<Vec<Model>> {
    if let Some(dir) = &args.models_dir {
        if !dir.is_dir() {
            bail!("--models-dir {}: no such directory", dir.display());
        }
    }
    let dir = models_dir(args);
    let mut models = Vec::new();
    for &kind in selected {
        let (mesh, source) = match (kind, kind.file()) {
            (BenchModel::Quad, _) => (full_screen_quad(1.0), "two triangles".to_string()),
            (_, None) => (
                builtin_model(kind.name(), None).context("built-in model")?,
                format!("built-in {}", kind.name()),
            ),
            (_, Some(file)) => {
                let Some(path) = dir.as_ref().map(|d| d.join(file)).filter(|p| p.is_file()) else {
                    let place = dir.as_ref().map_or_else(
                        || "../shared/models (not found)".to_string(),
                        |d| d.display().to_string(),
                    );
                    if !args.model.is_empty() {
                        bail!(
                            "{} was asked for, but there is no {file} in {place}",
                            kind.name()
                        );
                    }
                    crate::warn(&format!(
                        "note: {} skipped: no {file} in {place}\n",
                        kind.name()
                    ));
                    continue;
                };
                let mesh = shadelab_io::load_mesh(&path)
                    .with_context(|| format!("cannot load {}", path.display()))?;
                (mesh, path.display().to_string())
            }
        };
        models.push(Model { kind, mesh, source });
    }
    Ok(models)
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
    frames: usize,
    median_ms: f64,
    min_ms: f64,
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
    if !(args.budget.is_finite() && (0.0..=MAX_BENCH_BUDGET_SECONDS).contains(&args.budget)) {
        return Err(input_error(anyhow::anyhow!(
            "--budget must be a number of seconds in 0..={MAX_BENCH_BUDGET_SECONDS}, got {}",
            args.budget
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
    let machine = Machine::detect();
    let mut out = std::io::stdout().lock();
    if !args.json {
        let mut heading = || -> std::io::Result<()> {
            writeln!(
                out,
                "shadelab bench: {} ({} cores, clock {:.0} MHz measured), tiled rasterizer SIMD {}; median of up to {} frames after {} warm-up",
                machine.cpu, machine.cores, machine.clock_mhz, machine.simd, args.frames, args.warmup
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
                        let row = time_row(args, pool, &scene, &options).map_err(input_error)?;
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
fn time_row(
    args: &BenchArgs,
    pool: &rayon::ThreadPool,
    scene: &Scene,
    options: &RenderOptions,
) -> anyhow::Result<Row> {
    let mut renderer = Renderer::new();
    let mut image = Image::filled(options.width, options.height, options.background);
    let mut stats = Default::default();
    for _ in 0..args.warmup {
        stats = pool.install(|| renderer.render_into(scene, options, &mut image))?;
    }
    let budget = Duration::from_secs_f64(args.budget.max(0.0));
    let start = Instant::now();
    let mut times = Vec::with_capacity(args.frames as usize);
    while times.len() < args.frames as usize && (times.len() < 3 || start.elapsed() < budget) {
        let t = Instant::now();
        stats = pool.install(|| renderer.render_into(scene, options, &mut image))?;
        times.push(t.elapsed().as_secs_f64() * 1e3);
    }
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
        frames: n,
        median_ms: median,
        min_ms: times[0],
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
            self.frames
        )
    }
}

/// What the numbers were measured on.
struct Machine {
    cpu: String,
    cores: usize,
    simd: &'static str,
    /// The core clock while running, measured.
    clock_mhz: f64,
}

impl Machine {
    fn detect() -> Machine {
        let cpu = std::fs::read_to_string("/proc/cpuinfo")
            .ok()
            .and_then(|text| {
                text.lines()
                    .find(|l| l.starts_with("model name"))
                    .and_then(|l| l.split_once(':'))
                    .map(|(_, name)| name.trim().to_string())
            })
            .unwrap_or_else(|| std::env::consts::ARCH.to_string());
        Machine {
            cpu,
            cores: std::thread::available_parallelism().map_or(1, |n| n.get()),
            simd: Renderer::new().simd().name(),
            clock_mhz: measure_clock_mhz(),
        }
    }
}

/// The clock of the core this runs on, in MHz, estimated from the time a
/// chain of dependent steps `x = x·x + 1` takes: one 64-bit multiplication
/// and one addition, 3 + 1 cycles of latency on x86-64 processors since
/// 2008 (Intel Nehalem, AMD Zen) and on 64-bit Arm cores. Each step needs
/// the one before, so neither the processor nor the compiler can overlap
/// or fold them. The fastest of 20 runs of about a millisecond is kept: on
/// a shared or virtual machine a run can only be slowed down (preempted),
/// never sped up.
fn measure_clock_mhz() -> f64 {
    const STEPS: u64 = 1 << 20;
    const CYCLES_PER_STEP: f64 = 4.0;
    let mut best = f64::INFINITY;
    for _ in 0..20 {
        let mut x = std::hint::black_box(3u64);
        let start = Instant::now();
        for _ in 0..STEPS {
            x = x.wrapping_mul(x).wrapping_add(1);
        }
        std::hint::black_box(x);
        best = best.min(start.elapsed().as_secs_f64());
    }
    STEPS as f64 * CYCLES_PER_STEP / best / 1e6
}

/// A JSON string literal.
fn quote(s: &str) -> String {
    let mut out = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if (c as u32) < 0x20 => {
                let _ = write!(out, "\\u{:04x}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

fn json(machine: &Machine, args: &BenchArgs, rows: &[Row]) -> String {
    let mut s = String::new();
    let _ = write!(
        s,
        "{{\"machine\":{{\"cpu\":{},\"cores\":{},\"simd\":{},\"clock_mhz\":{:.0}}},\"warmup\":{},\"frames\":{},\"rows\":[",
        quote(&machine.cpu),
        machine.cores,
        quote(machine.simd),
        machine.clock_mhz,
        args.warmup,
        args.frames
    );
    for (i, r) in rows.iter().enumerate() {
        if i > 0 {
            s.push(',');
        }
        let _ = write!(
            s,
            "{{\"model\":{},\"triangles\":{},\"width\":{},\"height\":{},\"shading\":{},\"rasterizer\":{},\"threads\":{},\"frames\":{},\"median_ms\":{:.4},\"min_ms\":{:.4},\"covered_pixels\":{},\"fragments\":{},\"mpixels_per_s\":{:.2},\"mtriangles_per_s\":{:.3},\"cycles_per_pixel\":{:.2}}}",
            quote(r.model),
            r.triangles,
            r.width,
            r.height,
            quote(r.shading.name()),
            quote(r.rasterizer.name()),
            r.threads,
            r.frames,
            r.median_ms,
            r.min_ms,
            r.covered_pixels,
            r.fragments,
            r.mpixels_per_s(),
            r.mtriangles_per_s(),
            r.cycles_per_pixel(machine.clock_mhz)
        );
    }
    s.push_str("]}");
    s
}

/// Writes each model's standard scene for another renderer, per size:
///
/// * `MODEL-WxH.json`: camera, light, material, background, counts;
/// * `MODEL-WxH.vertices.f32`: distinct (position, normal) vertices, 6 floats each;
/// * `MODEL-WxH.indices.u32`: their triangles (polygons as fans from their
///   first corner, as both rasterizers draw them), counter-clockwise;
/// * `MODEL-WxH.flat.f32`: per triangle, its polygon's unit face normal and
///   centroid (6 floats), what flat shading lights;
/// * `MODEL-WxH-SHADING.png`: the tiled rasterizer's image.
///
/// All little-endian.
fn export(
    dir: &Path,
    models: &[Model],
    sizes: &[(u32, u32)],
    shadings: &[Shading],
) -> anyhow::Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let mut renderer = Renderer::new();
    for model in models {
        for &(width, height) in sizes {
            let aspect = width as f32 / height as f32;
            let mesh = match model.kind {
                BenchModel::Quad => full_screen_quad(aspect),
                _ => model.mesh.clone(),
            };
            let scene = standard_scene(mesh, aspect, model.kind == BenchModel::Quad);
            let stem = format!("{}-{width}x{height}", model.kind.name());
            let counts = write_geometry(dir, &stem, &scene)?;
            let c = &scene.camera;
            let LightKind::Point { position: light } = scene.lights[0].kind else {
                bail!("the standard light is a point light");
            };
            let v = |v: Vec3| format!("[{},{},{}]", v.x, v.y, v.z);
            let c3 = |c: [u8; 3]| format!("[{},{},{}]", c[0], c[1], c[2]);
            let description = format!(
                "{{\"model\":{},\"width\":{width},\"height\":{height},\"vertices\":{},\"triangles\":{},\
                 \"eye\":{},\"target\":{},\"up\":{},\"fov_y\":{},\"near\":{},\"far\":{},\
                 \"light\":{},\"light_color\":[255,255,255],\"ambient\":{},\"ambient_intensity\":{},\
                 \"ka\":{},\"kd\":{},\"ks\":{},\"shininess\":{},\"background\":{}}}",
                quote(model.kind.name()),
                counts.0,
                counts.1,
                v(c.eye),
                v(c.target),
                v(c.up),
                c.fov_y_degrees,
                c.near,
                c.far,
                v(light),
                c3(AMBIENT),
                AMBIENT_INTENSITY,
                c3(KA),
                c3(KD),
                c3(KS),
                SHININESS,
                c3(BACKGROUND.0),
            );
            write_file(&dir.join(format!("{stem}.json")), description.as_bytes())?;
            for &shading in shadings {
                let options = options(width, height, shading, Rasterizer::Tiled);
                let mut image = Image::filled(width, height, BACKGROUND);
                renderer.render_into(&scene, &options, &mut image)?;
                let path = dir.join(format!("{stem}-{}.png", shading.name()));
                shadelab_io::write_png(&path, &image)
                    .with_context(|| format!("cannot write {}", path.display()))?;
            }
            crate::warn(&format!("exported {stem}\n"));
        }
    }
    Ok(())
}

fn write_file(path: &Path, bytes: &[u8]) -> anyhow::Result<()> {
    shadelab_io::write_atomic(path, |out| out.write_all(bytes))
        .with_context(|| format!("cannot write {}", path.display()))
}

/// Writes the vertex, index and flat arrays; returns (vertices, triangles).
fn write_geometry(dir: &Path, stem: &str, scene: &Scene) -> anyhow::Result<(usize, usize)> {
    let mesh = &scene.mesh;
    let normals = &scene.normals;
    let mut ids = std::collections::HashMap::new();
    let (mut vertices, mut indices, mut flat) = (Vec::<f32>::new(), Vec::<u32>::new(), Vec::new());
    let mut points = Vec::new();
    for face in 0..mesh.polygon_count() {
        let corners = mesh.corner_range(face);
        points.clear();
        points.extend(
            mesh.polygon(face)
                .iter()
                .map(|&p| mesh.positions()[p as usize]),
        );
        // Degenerate polygons are not drawn by either rasterizer.
        let Some(n) = face_normal(&points) else {
            continue;
        };
        let centroid = points.iter().sum::<Vec3>() / points.len() as f32;
        let polygon: Vec<u32> = corners
            .map(|c| {
                let key = (mesh.corners()[c], normals.corner[c]);
                *ids.entry(key).or_insert_with(|| {
                    let p = mesh.positions()[key.0 as usize];
                    let n = normals.normals[key.1 as usize];
                    vertices.extend_from_slice(&[p.x, p.y, p.z, n.x, n.y, n.z]);
                    (vertices.len() / 6 - 1) as u32
                })
            })
            .collect();
        for k in 1..polygon.len() - 1 {
            indices.extend_from_slice(&[polygon[0], polygon[k], polygon[k + 1]]);
            flat.extend_from_slice(&[n.x, n.y, n.z, centroid.x, centroid.y, centroid.z]);
        }
    }
    let bytes = |v: &[f32]| v.iter().flat_map(|x| x.to_le_bytes()).collect::<Vec<u8>>();
    write_file(&dir.join(format!("{stem}.vertices.f32")), &bytes(&vertices))?;
    write_file(&dir.join(format!("{stem}.flat.f32")), &bytes(&flat))?;
    let index_bytes: Vec<u8> = indices.iter().flat_map(|i| i.to_le_bytes()).collect();
    write_file(&dir.join(format!("{stem}.indices.u32")), &index_bytes)?;
    Ok((vertices.len() / 6, indices.len() / 3))
}
