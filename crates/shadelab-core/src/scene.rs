//! What a frame is asked for: the scene (mesh, normals, camera, lights,
//! material), the options (size, method, rasterizer, modes), and what comes
//! back (statistics, errors). Plain data with its checks, so every layer —
//! the rasterizers below the frame and the formats above the core — speaks
//! the same words.

use crate::camera::{Camera, CameraError};
use crate::color::{Rgb, Rgb8};
use crate::light::{Light, Material, Specular};
use crate::limits::{MAX_IMAGE_PIXELS, MAX_IMAGE_SIDE};
use crate::mesh::{CornerNormals, Mesh};
use crate::palette::Palette;

/// The three classic shading methods: the one definition every layer uses
/// (names and help declared below, see [`crate::choice`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Shading {
    /// One lighting evaluation per polygon.
    Flat,
    /// Lighting per vertex, colours interpolated.
    Gouraud,
    /// Normals interpolated and lit per pixel.
    #[default]
    Phong,
}

choices!(Shading, "shading method", {
    Flat => "flat": "one lighting evaluation per polygon",
    Gouraud => "gouraud": "lighting per vertex, colours interpolated",
    Phong => "phong": "normals interpolated, lighting per pixel",
});

impl Shading {
    /// The display name ("Flat", "Gouraud", "Phong").
    pub fn title(self) -> &'static str {
        match self {
            Shading::Flat => "Flat",
            Shading::Gouraud => "Gouraud",
            Shading::Phong => "Phong",
        }
    }
}

/// How attributes are interpolated across a polygon.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Interpolation {
    /// Perspective-correct: attributes divided by w are linear in window space.
    #[default]
    Perspective,
    /// The textbook's screen-space linear interpolation along edges and spans.
    Screen,
}

choices!(Interpolation, "interpolation", {
    Perspective => "perspective": "perspective-correct: attributes divided by w, linear on the screen",
    Screen => "screen": "linear in screen space along edges and spans, as in the textbook",
});

/// The fewest fraction bits fixed-point stepping accepts.
pub const MIN_FRACTION_BITS: u32 = 1;
/// The most fraction bits fixed-point stepping accepts (sums stay exact in `f64`).
pub const MAX_FRACTION_BITS: u32 = 30;

/// Which rasterizer draws the frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Rasterizer {
    /// The textbook scanline algorithm: the reference, one thread.
    Scanline,
    /// Edge functions over bands of rows, SIMD blocks, all threads.
    #[default]
    Tiled,
}

choices!(Rasterizer, "rasterizer", {
    Scanline => "scanline": "the textbook scanline algorithm: the reference, one thread",
    Tiled => "tiled": "edge functions over bands of rows, SIMD blocks, all threads",
});

/// How polygons with more than three vertices are interpolated.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Polygons {
    /// As a fan of triangles from the first vertex, each interpolated as a
    /// plane: what GPUs do. Both rasterizers draw this.
    #[default]
    Fans,
    /// Whole, along edges and spans as the textbook does (scanline only):
    /// Gouraud over a quad then depends on its orientation on screen.
    Whole,
}

choices!(Polygons, "polygon interpolation", {
    Fans => "fans": "each polygon a fan of triangles, each interpolated as a plane (as GPUs do)",
    Whole => "whole": "whole polygons along edges and spans, as the textbook does (scanline only)",
});

/// What to draw: a mesh with its vertex normals, a camera and the lighting.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// The model.
    pub mesh: Mesh,
    /// One normal per corner of `mesh` (see [`crate::vertex_normals`]).
    pub normals: CornerNormals,
    /// The viewer.
    pub camera: Camera,
    /// Ambient light, colour times intensity (`Ia`).
    pub ambient: Rgb,
    /// Point and directional lights.
    pub lights: Vec<Light>,
    /// The surface.
    pub material: Material,
}

/// How to draw it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RenderOptions {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Shading method.
    pub shading: Shading,
    /// Colour where nothing is drawn.
    pub background: Rgb8,
    /// Skip polygons facing away from the viewer.
    pub cull_backfaces: bool,
    /// Let Gouraud shading include the specular term at the vertices.
    pub gouraud_specular: bool,
    /// Perspective-correct or screen-linear attributes.
    pub interpolation: Interpolation,
    /// Which rasterizer draws.
    pub rasterizer: Rasterizer,
    /// Polygons as triangle fans or whole.
    pub polygons: Polygons,
    /// Phong's `r·v` or Blinn's `n·h` in the specular term.
    pub specular: Specular,
    /// Step attributes in fixed point with this many fraction bits
    /// (scanline only); `None`: floating point.
    pub fixed_point_bits: Option<u32>,
    /// Draw with an indexed palette of shades of the material colour
    /// (scanline only); `None`: true colour.
    pub palette: Option<Palette>,
}

impl RenderOptions {
    /// Whether these options ask for something only the scanline rasterizer
    /// draws: whole polygons, fixed-point stepping or a palette.
    pub fn needs_scanline(&self) -> bool {
        self.polygons == Polygons::Whole
            || self.fixed_point_bits.is_some()
            || self.palette.is_some()
    }

    /// The one check of the options, whoever set them (the scene file, the
    /// command line, the page or a program): the image size, the modes only
    /// the scanline rasterizer draws, the fixed-point bits and the palette.
    /// Each error names the scene-file key at fault ([`RenderError::key`]).
    ///
    /// # Errors
    /// The first problem found: the size, whole polygons on the tiled
    /// rasterizer, the bits, the palette, then fixed point or a palette on
    /// the tiled rasterizer.
    pub fn check(&self) -> Result<(), RenderError> {
        let (w, h) = (self.width, self.height);
        if w == 0
            || h == 0
            || w > MAX_IMAGE_SIDE
            || h > MAX_IMAGE_SIDE
            || u64::from(w) * u64::from(h) > MAX_IMAGE_PIXELS
        {
            return Err(RenderError::ImageSize {
                width: w,
                height: h,
            });
        }
        let tiled = self.rasterizer == Rasterizer::Tiled;
        if tiled && self.polygons == Polygons::Whole {
            return Err(RenderError::WholePolygonsNeedScanline);
        }
        if let Some(bits) = self.fixed_point_bits {
            if !(MIN_FRACTION_BITS..=MAX_FRACTION_BITS).contains(&bits) {
                return Err(RenderError::FractionBits(bits));
            }
        }
        if let Some(p) = self.palette {
            if !p.is_valid() {
                return Err(RenderError::Palette {
                    shades: p.shades,
                    offset: p.offset,
                });
            }
        }
        if tiled && self.fixed_point_bits.is_some() {
            return Err(RenderError::ScanlineOnly("render.fixed_point_bits"));
        }
        if tiled && self.palette.is_some() {
            return Err(RenderError::ScanlineOnly("render.palette_shades"));
        }
        Ok(())
    }
}

impl Default for RenderOptions {
    fn default() -> RenderOptions {
        RenderOptions {
            width: 800,
            height: 600,
            shading: Shading::Phong,
            background: Rgb8::new(0, 0, 0),
            cull_backfaces: true,
            gouraud_specular: false,
            interpolation: Interpolation::Perspective,
            rasterizer: Rasterizer::Tiled,
            polygons: Polygons::Fans,
            specular: Specular::Phong,
            fixed_point_bits: None,
            palette: None,
        }
    }
}

/// Why a frame could not be rendered.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum RenderError {
    /// The image size is zero or too large.
    #[error("{}: {}", self.key().unwrap_or("render"), self.problem())]
    ImageSize {
        /// Requested width.
        width: u32,
        /// Requested height.
        height: u32,
    },
    /// The camera is unusable.
    #[error(transparent)]
    Camera(#[from] CameraError),
    /// The normals do not belong to the mesh.
    #[error("the scene has {normals} corner normals for {corners} face corners")]
    NormalsMismatch {
        /// Corner normals given.
        normals: usize,
        /// Corners in the mesh.
        corners: usize,
    },
    /// A light or material value is not a finite number.
    #[error("{0} is not a finite number")]
    NonFinite(&'static str),
    /// The tiled rasterizer draws polygons as fans only.
    #[error("{}: {}", self.key().unwrap_or("render"), self.problem())]
    WholePolygonsNeedScanline,
    /// A mode of the scanline rasterizer was asked of the tiled one: the
    /// scene-file key of the mode.
    #[error("{}: {}", self.key().unwrap_or("render"), self.problem())]
    ScanlineOnly(&'static str),
    /// The fixed-point fraction bits are out of range.
    #[error("{}: {}", self.key().unwrap_or("render"), self.problem())]
    FractionBits(u32),
    /// The palette run does not fit a 256-entry palette.
    #[error("{}: {}", self.key().unwrap_or("render"), self.problem())]
    Palette {
        /// Shades asked for.
        shades: u32,
        /// First entry asked for.
        offset: u32,
    },
    /// Rows asked of a part of a frame that are not a run of whole bands
    /// within the image (`Renderer::render_methods_rows`).
    #[error(
        "rows {start}..{end} of an image {height} rows high: a part must be non-empty, within \
         the image, and start (and end, but at the last row) at a multiple of {align} rows"
    )]
    Rows {
        /// First row asked for.
        start: u32,
        /// One past the last row asked for.
        end: u32,
        /// The image's height.
        height: u32,
        /// The rows a part starts at a multiple of.
        align: u32,
    },
}

impl RenderError {
    /// The scene-file key an error of the options is about
    /// (`render.width`, `render.fixed_point_bits`, ...); `None` for the
    /// scene's own errors (camera, normals, non-finite values).
    pub fn key(&self) -> Option<&'static str> {
        match *self {
            RenderError::ImageSize { width, height } => {
                Some(if !(1..=MAX_IMAGE_SIDE).contains(&width) {
                    "render.width"
                } else if !(1..=MAX_IMAGE_SIDE).contains(&height) {
                    "render.height"
                } else {
                    "render"
                })
            }
            RenderError::WholePolygonsNeedScanline => Some("render.polygons"),
            RenderError::ScanlineOnly(key) => Some(key),
            RenderError::FractionBits(_) => Some("render.fixed_point_bits"),
            RenderError::Palette { .. } => Some("render.palette_shades"),
            RenderError::Camera(_)
            | RenderError::NormalsMismatch { .. }
            | RenderError::NonFinite(_)
            | RenderError::Rows { .. } => None,
        }
    }

    /// What is wrong, without the [`key`](RenderError::key).
    pub fn problem(&self) -> String {
        match *self {
            RenderError::ImageSize { width, height } => match self.key() {
                Some("render.width") => format!("must be 1..={MAX_IMAGE_SIDE}, got {width}"),
                Some("render.height") => format!("must be 1..={MAX_IMAGE_SIDE}, got {height}"),
                _ => format!("{width}x{height} exceeds {MAX_IMAGE_PIXELS} pixels"),
            },
            RenderError::WholePolygonsNeedScanline => {
                "\"whole\" needs rasterizer = \"scanline\"; the tiled rasterizer draws fans".into()
            }
            RenderError::ScanlineOnly(_) => {
                "needs rasterizer = \"scanline\"; the tiled rasterizer does not draw it".into()
            }
            RenderError::FractionBits(bits) => {
                format!("must be {MIN_FRACTION_BITS}..={MAX_FRACTION_BITS}, got {bits}")
            }
            RenderError::Palette { shades, offset } => format!(
                "needs 2..=256 shades with palette_offset + palette_shades ≤ 256, got {shades} at offset {offset}"
            ),
            _ => self.to_string(),
        }
    }
}

/// What a frame cost and what it did.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct RenderStats {
    /// Polygons in the mesh.
    pub polygons: u64,
    /// Polygons skipped because their area is zero in 3D.
    pub degenerate: u64,
    /// Polygons entirely outside the view volume, or of zero area on screen.
    pub invisible: u64,
    /// Polygons culled as back faces.
    pub culled: u64,
    /// Polygons rasterized.
    pub rasterized: u64,
    /// Pixels that passed the depth test and were shaded.
    pub fragments_shaded: u64,
    /// Evaluations of the reflection model.
    pub lighting_evaluations: u64,
    /// Pixels where the model was drawn.
    pub covered_pixels: u64,
}
