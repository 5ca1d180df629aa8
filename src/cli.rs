//! The command line: subcommands and the flags that override a scene file.

use std::path::{Path, PathBuf};

use clap::builder::TypedValueParser as _;
use clap::{Args, Parser, Subcommand, ValueEnum};
use shadelab_core::limits::{MAX_COST_RUNS, MAX_QUAD_SIZE, MIN_QUAD_SIZE};
use shadelab_core::{
    Choice, Interpolation, Polygons, Rasterizer, Shading, Specular, MAX_IMAGE_PIXELS,
    MAX_IMAGE_SIDE,
};
use shadelab_io::{NormalsChoice, SceneFile};

use crate::param_flags::ParamFlags;

/// Flat, Gouraud and Phong shading on an exact CPU rasterizer.
#[derive(Debug, Parser)]
#[command(name = "shadelab", version, about, long_about = None)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Render one image with one shading method.
    Render(RenderArgs),
    /// Render flat, Gouraud and Phong side by side, labelled, in one image.
    Compare(CompareArgs),
    /// List the built-in models.
    Models(ModelsArgs),
    /// Explain one pixel: for each method, the polygon, the scanline, P, Q,
    /// the interpolation parameters and values, and the colour.
    Explain(ExplainArgs),
    /// Plot the intensity along a row (or a line) for flat, Gouraud, Phong
    /// and the exact surface, with its derivative: the Mach bands made visible.
    Profile(ProfileArgs),
    /// Error maps against the exact surface (sphere, torus, cylinder, cone):
    /// the exact image and each method's per-pixel error as a heat map.
    Errors(ErrorsArgs),
    /// Each method's error against the exact surface as the tessellation grows: a table and a plot.
    Accuracy(AccuracyArgs),
    /// Gouraud shading of a quad drawn whole and as triangles, turned on the screen.
    Quad(QuadArgs),
    /// Render time and lighting evaluations (per polygon, vertex, pixel) of each method.
    Cost(CostArgs),
    /// Serve the interactive viewer (flat | Gouraud | Phong, live) in the browser.
    View(ViewArgs),
    /// Time the standard scenes: ms/frame, Mpixel/s, Mtriangles/s per model, size, method, rasterizer, threads.
    Bench(crate::bench::BenchArgs),
    /// Render many meshes (a JSON Lines or CSV manifest): views, modes, PNGs and an index; resumable, shardable.
    Batch(crate::batch::BatchArgs),
}

/// `--lang`
#[derive(Debug, Clone, Copy, ValueEnum, Default)]
pub enum LangArg {
    /// English.
    #[default]
    En,
    /// Russian.
    Ru,
    /// Slovak.
    Sk,
    /// Czech.
    Cs,
}

impl LangArg {
    /// The language's code, as links and `Lang::code` spell it.
    pub fn code(self) -> &'static str {
        shadelab_lab::Lang::from(self).code()
    }
}

impl From<LangArg> for shadelab_lab::Lang {
    fn from(l: LangArg) -> shadelab_lab::Lang {
        match l {
            LangArg::En => shadelab_lab::Lang::En,
            LangArg::Ru => shadelab_lab::Lang::Ru,
            LangArg::Sk => shadelab_lab::Lang::Sk,
            LangArg::Cs => shadelab_lab::Lang::Cs,
        }
    }
}

/// `shadelab models`
#[derive(Debug, Args)]
pub struct ModelsArgs {
    /// Language of the table.
    #[arg(long, value_enum, default_value = "en")]
    pub lang: LangArg,
}

/// `shadelab explain`
#[derive(Debug, Args)]
pub struct ExplainArgs {
    /// Scene file (TOML); flags override its values.
    pub scene: Option<PathBuf>,
    /// The pixel, X,Y (column, row; row 0 at the top).
    #[arg(long, value_parser = parse_pixel, allow_hyphen_values = true)]
    pub pixel: (u32, u32),
    /// Only this method (default: all three).
    #[arg(long, value_parser = choice::<Shading>())]
    pub shading: Option<Shading>,
    /// Language of the explanation.
    #[arg(long, value_enum, default_value = "en")]
    pub lang: LangArg,
    /// Scene overrides.
    #[command(flatten)]
    pub overrides: SceneOverrides,
}

/// `shadelab profile`
#[derive(Debug, Args)]
pub struct ProfileArgs {
    /// Scene file (TOML); flags override its values.
    pub scene: Option<PathBuf>,
    /// The row to profile (default: the middle row).
    #[arg(long, conflicts_with = "line", value_parser = whole::<u32, 0, { u32::MAX as u64 }>, allow_hyphen_values = true)]
    pub row: Option<u32>,
    /// A line instead of a row: X0,Y0,X1,Y1 in pixels.
    #[arg(long, value_parser = parse_line, allow_hyphen_values = true)]
    pub line: Option<[f64; 4]>,
    /// Output PNG file (the plot; `-`: standard output).
    #[arg(short, long, value_parser = output_path)]
    pub output: PathBuf,
    /// Also print the values, one sample per line.
    #[arg(long)]
    pub table: bool,
    /// Language of the plot's labels.
    #[arg(long, value_enum, default_value = "en")]
    pub lang: LangArg,
    /// Scene overrides (`--size` is the rendered frame's size).
    #[command(flatten)]
    pub overrides: SceneOverrides,
}

/// `shadelab errors`
#[derive(Debug, Args)]
pub struct ErrorsArgs {
    /// Scene file (TOML); flags override its values.
    pub scene: Option<PathBuf>,
    /// Output PNG file: the exact image and the three heat maps (`-`: standard output).
    #[arg(short, long, value_parser = output_path)]
    pub output: PathBuf,
    /// The error at the top of the colour scale, 0–255 (default: the largest error).
    #[arg(long, allow_negative_numbers = true)]
    pub scale: Option<f32>,
    /// Language of the labels.
    #[arg(long, value_enum, default_value = "en")]
    pub lang: LangArg,
    /// Scene overrides (`--size` is the size of each panel).
    #[command(flatten)]
    pub overrides: SceneOverrides,
}

/// `shadelab accuracy`
#[derive(Debug, Args)]
pub struct AccuracyArgs {
    /// Scene file (TOML); flags override its values. The model must be a
    /// sphere, torus, cylinder or cone (default sphere).
    pub scene: Option<PathBuf>,
    /// Tessellation levels, comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "6,12,24,48,96", value_parser = whole::<u32, 0, { u32::MAX as u64 }>, allow_hyphen_values = true)]
    pub details: Vec<u32>,
    /// Output PNG file for the plot (the table is always printed).
    #[arg(short, long, value_parser = output_path)]
    pub output: Option<PathBuf>,
    /// Language of the plot's labels.
    #[arg(long, value_enum, default_value = "en")]
    pub lang: LangArg,
    /// Scene overrides (`--size` is the rendered frame's size).
    #[command(flatten)]
    pub overrides: SceneOverrides,
}

/// `shadelab quad`
#[derive(Debug, Args)]
pub struct QuadArgs {
    /// Output PNG file (`-`: standard output).
    #[arg(short, long, value_parser = output_path)]
    pub output: PathBuf,
    /// Turns of the quad on the screen, degrees, comma-separated.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "0,15,30,45,60,75,90",
        allow_hyphen_values = true
    )]
    pub angles: Vec<f32>,
    /// Size of each panel in pixels (odd puts a pixel centre on the quad's centre).
    #[arg(long, default_value_t = 121, value_parser = whole::<u32, { MIN_QUAD_SIZE as u64 }, { MAX_QUAD_SIZE as u64 }>, allow_hyphen_values = true)]
    pub size: u32,
    /// Language of the labels and the table.
    #[arg(long, value_enum, default_value = "en")]
    pub lang: LangArg,
}

/// `shadelab cost`
#[derive(Debug, Args)]
pub struct CostArgs {
    /// Scene file (TOML); flags override its values.
    pub scene: Option<PathBuf>,
    /// Renders per method; the median time is reported.
    #[arg(long, default_value_t = 5, value_parser = whole::<u32, 1, { MAX_COST_RUNS as u64 }>, allow_hyphen_values = true)]
    pub runs: u32,
    /// Language of the table.
    #[arg(long, value_enum, default_value = "en")]
    pub lang: LangArg,
    /// Scene overrides.
    #[command(flatten)]
    pub overrides: SceneOverrides,
}

/// `--overlay`, on `render` and `compare`.
#[derive(Debug, Args, Default)]
pub struct OverlayArgs {
    /// Draw over the image: wireframe, face-normals, vertex-normals, light (comma-separated), or all.
    #[arg(long, value_parser = parse_overlays)]
    pub overlay: Option<shadelab_lab::Overlays>,
}

fn parse_overlays(s: &str) -> Result<shadelab_lab::Overlays, String> {
    shadelab_lab::Overlays::parse(s)
}

fn parse_pixel(s: &str) -> Result<(u32, u32), String> {
    let [x, y]: [u32; 2] = parse_numbers(s, "pixel coordinates")
        .map_err(|_| format!("expected X,Y, two whole numbers ≥ 0 (column, row), got {s:?}"))?;
    Ok((x, y))
}

/// A whole number in `LO..=HI`, or a message that says the range.
pub fn whole<T: TryFrom<u64>, const LO: u64, const HI: u64>(s: &str) -> Result<T, String> {
    s.trim()
        .parse::<u64>()
        .ok()
        .filter(|v| (LO..=HI).contains(v))
        .and_then(|v| T::try_from(v).ok())
        .ok_or_else(|| {
            if HI == u64::from(u32::MAX) {
                format!("must be a whole number ≥ {LO}, got {s:?}")
            } else {
                format!("must be a whole number in {LO}..={HI}, got {s:?}")
            }
        })
}

/// A value that is not empty.
fn non_empty(s: &str) -> Result<String, String> {
    if s.trim().is_empty() {
        Err("must not be empty".to_owned())
    } else {
        Ok(s.to_owned())
    }
}

/// An output path: not empty (`-` is standard output).
fn output_path(s: &str) -> Result<PathBuf, String> {
    if s.is_empty() {
        Err("must not be empty: name a file, or `-` for standard output".to_owned())
    } else {
        Ok(PathBuf::from(s))
    }
}

fn parse_line(s: &str) -> Result<[f64; 4], String> {
    let v: [f64; 4] = parse_numbers(s, "numbers")?;
    if v.iter().any(|c| !c.is_finite()) {
        return Err(format!("coordinates must be finite, got {s:?}"));
    }
    Ok(v)
}

/// `shadelab view`
#[derive(Debug, Args)]
pub struct ViewArgs {
    /// Address to listen on; the default serves this machine only.
    #[arg(long, default_value = "127.0.0.1")]
    pub host: std::net::IpAddr,
    /// Port to listen on (0: any free port).
    #[arg(long, default_value_t = 8080, value_parser = whole::<u16, 0, 65535>, allow_hyphen_values = true)]
    pub port: u16,
    /// Do not open a browser.
    #[arg(long)]
    pub no_open: bool,
    /// Write the viewer as static files into this new or empty directory instead of serving it.
    #[arg(long, value_name = "DIR")]
    pub export: Option<PathBuf>,
    /// Language of these messages and of the page it opens (default: the browser's).
    #[arg(long, value_enum)]
    pub lang: Option<LangArg>,
}

/// `shadelab render`
#[derive(Debug, Args)]
pub struct RenderArgs {
    /// Scene file (TOML); flags override its values.
    pub scene: Option<PathBuf>,
    /// Shading method.
    #[arg(long, value_parser = choice::<Shading>())]
    pub shading: Option<Shading>,
    /// Output PNG file (`-`: standard output).
    #[arg(short, long, value_parser = output_path)]
    pub output: PathBuf,
    /// Language of the line printed.
    #[arg(long, value_enum, default_value = "en")]
    pub lang: LangArg,
    /// Scene overrides.
    #[command(flatten)]
    pub overrides: SceneOverrides,
    /// Overlays.
    #[command(flatten)]
    pub overlay: OverlayArgs,
}

/// `shadelab compare`
#[derive(Debug, Args)]
pub struct CompareArgs {
    /// Scene file (TOML); flags override its values.
    pub scene: Option<PathBuf>,
    /// Output file: a PNG, or with `--orbit` an animated PNG (.apng or .png).
    #[arg(short, long, value_parser = output_path)]
    pub output: PathBuf,
    /// One full orbit of the camera in this many frames, as an animated PNG.
    #[arg(long, value_name = "FRAMES")]
    pub orbit: Option<u32>,
    /// With `--orbit`: how long each frame is shown, in milliseconds.
    #[arg(long, value_name = "MS", default_value_t = 80, requires = "orbit")]
    pub delay: u16,
    /// Language of the labels and the lines printed.
    #[arg(long, value_enum, default_value = "en")]
    pub lang: LangArg,
    /// Scene overrides (`--size` is the size of each panel).
    #[command(flatten)]
    pub overrides: SceneOverrides,
    /// Overlays, on every panel.
    #[command(flatten)]
    pub overlay: OverlayArgs,
}

/// Flags that override the scene file, key by key: the table's parameters
/// ([`ParamFlags`]) and the choices and switches declared here.
#[derive(Debug, Clone, Args, Default)]
pub struct SceneOverrides {
    /// Built-in model name or mesh file (.obj, .stl, .ply, .gltf, .glb); `shadelab models` lists the built-ins.
    #[arg(long, value_parser = non_empty)]
    pub model: Option<String>,
    /// Image size, WIDTHxHEIGHT.
    #[arg(long, value_parser = parse_size, allow_hyphen_values = true)]
    pub size: Option<(u32, u32)>,
    /// Every parameter of the core's table that has a flag (`--ka`,
    /// `--shininess`, `--light-pos`, ...).
    #[command(flatten)]
    pub params: ParamFlags,
    /// Vertex normals.
    #[arg(long, value_parser = choice::<NormalsChoice>())]
    pub normals: Option<NormalsChoice>,
    /// Attribute interpolation.
    #[arg(long, value_parser = choice::<Interpolation>())]
    pub interpolation: Option<Interpolation>,
    /// Draw back faces too (lit with reversed normals).
    #[arg(long)]
    pub no_cull: bool,
    /// Which rasterizer draws: the tiled SIMD one (default) or the scanline reference.
    #[arg(long, value_parser = choice::<Rasterizer>())]
    pub rasterizer: Option<Rasterizer>,
    /// Polygons of more than three vertices as triangle fans, or whole (textbook, scanline only).
    #[arg(long, value_parser = choice::<Polygons>())]
    pub polygons: Option<Polygons>,
    /// The specular term: Phong's r·v or Blinn's n·h.
    #[arg(long, value_parser = choice::<Specular>())]
    pub specular: Option<Specular>,
}

/// A flag that takes one of core's [`Choice`]s (`--shading`,
/// `--rasterizer`, ...): its names and their help come from core.
pub fn choice<T: Choice + Send + Sync + Clone>() -> impl clap::builder::TypedValueParser<Value = T>
{
    let values = T::VALUES
        .iter()
        .map(|v| clap::builder::PossibleValue::new(v.name()).help(v.help()));
    clap::builder::PossibleValuesParser::new(values)
        .map(|name| T::from_name(&name).expect("a possible value is a name"))
}

fn parse_numbers<const N: usize, T: std::str::FromStr>(
    s: &str,
    what: &str,
) -> Result<[T; N], String> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    if parts.len() != N {
        return Err(format!("expected {N} comma-separated {what}, got {s:?}"));
    }
    let mut out = Vec::with_capacity(N);
    for p in parts {
        out.push(
            p.parse::<T>()
                .map_err(|_| format!("{p:?} is not a valid {what}"))?,
        );
    }
    out.try_into()
        .map_err(|_| unreachable!("length checked above"))
}

/// `WIDTHxHEIGHT`, each side 1..=[`MAX_IMAGE_SIDE`] and at most
/// [`MAX_IMAGE_PIXELS`] in all.
pub fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let range = || {
        format!(
            "expected WIDTHxHEIGHT, each a whole number in 1..={MAX_IMAGE_SIDE} and at most \
             {MAX_IMAGE_PIXELS} pixels in all, got {s:?}"
        )
    };
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(range)?;
    let side = |v: &str| {
        v.trim()
            .parse::<u32>()
            .ok()
            .filter(|v| (1..=MAX_IMAGE_SIDE).contains(v))
    };
    match (side(w), side(h)) {
        (Some(w), Some(h)) if u64::from(w) * u64::from(h) <= MAX_IMAGE_PIXELS => Ok((w, h)),
        _ => Err(range()),
    }
}

impl SceneOverrides {
    /// Writes every flag that was given into `scene`.
    ///
    /// # Errors
    /// As [`ParamFlags::apply`].
    pub fn apply(
        &self,
        scene: &mut SceneFile,
        scene_given: bool,
    ) -> Result<(), shadelab_io::SceneError> {
        if let Some(m) = &self.model {
            // A file named on the command line is relative to the working
            // directory, not to the scene file.
            let is_builtin = shadelab_core::builtin_model_info(m).is_some();
            scene.model.source = Some(match std::path::absolute(m) {
                Ok(path) if !is_builtin && Path::new(m).is_relative() && scene_given => {
                    path.to_string_lossy().into_owned()
                }
                _ => m.clone(),
            });
            // A different model has different (or no) details.
            scene.model.detail = None;
        }
        if let Some((w, h)) = self.size {
            scene.render.width = Some(w);
            scene.render.height = Some(h);
        }
        self.params.apply(scene)?;
        if self.normals.is_some() {
            scene.model.normals = self.normals;
        }
        if self.interpolation.is_some() {
            scene.render.interpolation = self.interpolation;
        }
        if self.no_cull {
            scene.render.cull_backfaces = Some(false);
        }
        if self.rasterizer.is_some() {
            scene.render.rasterizer = self.rasterizer;
        }
        if self.polygons.is_some() {
            scene.render.polygons = self.polygons;
        }
        if self.specular.is_some() {
            scene.render.specular = self.specular;
        }
        Ok(())
    }
}
