//! The frame pipeline: per-vertex transform, per-polygon clipping, culling
//! and projection, rasterization, and one of the three shading methods.
//!
//! The methods differ only in what they attach to a polygon's corners and
//! what they do per fragment:
//!
//! | method  | lighting evaluated          | interpolated            |
//! |---------|-----------------------------|-------------------------|
//! | flat    | once per polygon (centroid) | nothing but depth       |
//! | Gouraud | once per distinct vertex    | the vertex colours      |
//! | Phong   | once per pixel              | normal, world position  |
//!
//! Facing is decided from the snapped window polygon, as OpenGL does. A
//! back-facing polygon drawn with culling off is lit with its normals turned
//! towards the viewer and re-wound, so the rasterizer only ever sees
//! counter-clockwise polygons.
//!
//! Two modes of old hardware are drawn by the scanline rasterizer only:
//! fixed-point attribute stepping ([`RenderOptions::fixed_point_bits`]) and
//! the indexed palette ([`RenderOptions::palette`]). A probe (`probe.rs`)
//! watches one frame through [`Target`]'s hooks, which default to nothing.

use std::collections::HashMap;

use glam::{Mat4, Vec3, Vec4};
use rayon::prelude::*;

use crate::camera::{Camera, CameraError};
use crate::clip::{clip_polygon, ClipVertex};
use crate::color::{Rgb, Rgb8};
use crate::image::Image;
use crate::lighting::{Light, Lighting, Material, Specular, Terms};
use crate::limits::{MAX_IMAGE_PIXELS, MAX_IMAGE_SIDE};
use crate::mesh::{CornerNormals, Mesh};
use crate::normals::face_normals;
use crate::palette::Palette;
use crate::raster::scanline::{
    rasterize_fan_with, rasterize_polygon_with, ScanlineOptions, SpanTrace, MAX_FRACTION_BITS,
    MIN_FRACTION_BITS,
};
use crate::raster::{signed_area_ccw, snap, FragmentSink, Interpolation, ScreenVertex};
use crate::simd::SimdLevel;
use crate::tiled::TiledRasterizer;

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
            | RenderError::NonFinite(_) => None,
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

/// Renders a frame: [`Renderer::render_into`] with a new renderer and image.
///
/// # Errors
/// [`RenderError`] when the options, camera, normals or lighting are invalid.
pub fn render(scene: &Scene, options: &RenderOptions) -> Result<(Image, RenderStats), RenderError> {
    let mut image = Image::filled(1, 1, options.background);
    let stats = Renderer::new().render_into(scene, options, &mut image)?;
    Ok((image, stats))
}

/// How many polygons cover each pixel, row by row, with no depth test: the
/// geometry stage of [`render`] with the colour left out. A closed convex
/// mesh seen from outside covers its silhouette exactly once.
///
/// # Errors
/// As [`render`].
pub fn coverage(scene: &Scene, options: &RenderOptions) -> Result<Vec<u32>, RenderError> {
    Renderer::new().coverage(scene, options)
}

/// Renders frames, keeping its working buffers from one frame to the next
/// (the tiled rasterizer allocates nothing per frame once warmed up).
///
/// Work is spread over rayon's current thread pool; run it inside
/// `ThreadPool::install` to choose the number of threads.
#[derive(Debug)]
pub struct Renderer {
    tiled: TiledRasterizer,
    /// The frame's lighting, rebuilt in place each frame.
    lighting: Lighting,
}

impl Default for Renderer {
    fn default() -> Renderer {
        Renderer::new()
    }
}

impl Renderer {
    /// A renderer using the best SIMD level of this CPU.
    pub fn new() -> Renderer {
        Renderer::with_simd(SimdLevel::detect())
    }

    /// A renderer using `level` (or the portable path if the CPU lacks it).
    pub fn with_simd(level: SimdLevel) -> Renderer {
        Renderer {
            tiled: TiledRasterizer::new(level),
            lighting: Lighting {
                ambient: Rgb::default(),
                lights: Vec::new(),
                material: Material::default(),
                eye: Vec3::ZERO,
                specular: Specular::default(),
            },
        }
    }

    /// The SIMD level the tiled rasterizer uses.
    pub fn simd(&self) -> SimdLevel {
        self.tiled.simd()
    }

    /// Renders `scene` into `image`, which is replaced by a new image when
    /// its size is not the requested one.
    ///
    /// # Errors
    /// [`RenderError`] when the options, camera, normals or lighting are invalid.
    pub fn render_into(
        &mut self,
        scene: &Scene,
        options: &RenderOptions,
        image: &mut Image,
    ) -> Result<RenderStats, RenderError> {
        validate(scene, options)?;
        if image.width() != options.width || image.height() != options.height {
            *image = Image::filled(options.width, options.height, options.background);
        }
        set_lighting(&mut self.lighting, scene, options);
        let lighting = &self.lighting;
        Ok(match options.rasterizer {
            Rasterizer::Tiled => self.tiled.render(scene, options, lighting, image),
            Rasterizer::Scanline => {
                let mut frame = Frame {
                    color: std::mem::replace(image, Image::filled(1, 1, options.background)),
                    depth: vec![1.0; options.width as usize * options.height as usize],
                    width: options.width,
                };
                frame.color.pixels_mut().fill(options.background);
                let mut stats = draw(scene, options, lighting, &mut frame);
                stats.covered_pixels = frame.depth.iter().filter(|&&d| d < 1.0).count() as u64;
                *image = frame.color;
                stats
            }
        })
    }

    /// How many polygons cover each pixel, row by row, with no depth test.
    ///
    /// # Errors
    /// As [`Renderer::render_into`].
    pub fn coverage(
        &mut self,
        scene: &Scene,
        options: &RenderOptions,
    ) -> Result<Vec<u32>, RenderError> {
        validate(scene, options)?;
        let lighting = lighting(scene, options);
        Ok(match options.rasterizer {
            Rasterizer::Tiled => self.tiled.coverage(scene, options, &lighting),
            Rasterizer::Scanline => {
                let mut counter = CoverageCounter {
                    counts: vec![0; options.width as usize * options.height as usize],
                    width: options.width,
                };
                let options = RenderOptions {
                    shading: Shading::Flat,
                    ..*options
                };
                draw(scene, &options, &lighting, &mut counter);
                counter.counts
            }
        })
    }
}

pub(crate) fn lighting(scene: &Scene, options: &RenderOptions) -> Lighting {
    let mut lighting = Lighting {
        ambient: scene.ambient,
        lights: Vec::new(),
        material: scene.material,
        eye: scene.camera.eye,
        specular: options.specular,
    };
    set_lighting(&mut lighting, scene, options);
    lighting
}

/// Makes `lighting` the scene's, reusing its list of lights.
fn set_lighting(lighting: &mut Lighting, scene: &Scene, options: &RenderOptions) {
    lighting.ambient = scene.ambient;
    lighting.lights.clear();
    lighting.lights.extend_from_slice(&scene.lights);
    lighting.material = scene.material;
    lighting.eye = scene.camera.eye;
    lighting.specular = options.specular;
}

pub(crate) fn validate(scene: &Scene, options: &RenderOptions) -> Result<(), RenderError> {
    options.check()?;
    scene.camera.validate()?;
    // A maximum over all corners (no early exit, so the loop vectorizes),
    // in parallel: it runs every frame over every corner.
    let largest = scene
        .normals
        .corner
        .par_chunks(1 << 15)
        .map(|chunk| chunk.iter().fold(0, |m, &i| m.max(i)))
        .max()
        .unwrap_or(0);
    if scene.normals.corner.len() != scene.mesh.corners().len()
        || (!scene.normals.corner.is_empty() && largest as usize >= scene.normals.normals.len())
    {
        return Err(RenderError::NormalsMismatch {
            normals: scene.normals.corner.len(),
            corners: scene.mesh.corners().len(),
        });
    }
    let m = &scene.material;
    let rgb_finite = |c: Rgb| c.to_array().iter().all(|v| v.is_finite());
    if !rgb_finite(scene.ambient) {
        return Err(RenderError::NonFinite("ambient"));
    }
    if !(rgb_finite(m.ka) && rgb_finite(m.kd) && rgb_finite(m.ks) && m.shininess.is_finite()) {
        return Err(RenderError::NonFinite("material"));
    }
    for light in &scene.lights {
        let position_ok = match light.kind {
            crate::lighting::LightKind::Point { position } => position.is_finite(),
            crate::lighting::LightKind::Directional { direction } => direction.is_finite(),
        };
        if !(position_ok && rgb_finite(light.color) && light.intensity.is_finite()) {
            return Err(RenderError::NonFinite("light"));
        }
    }
    Ok(())
}

/// Where fragments go: a depth test, then (if it passes) a colour.
///
/// The other methods are hooks for a probe; their defaults do nothing and
/// cost nothing.
pub(crate) trait Target {
    /// Depth-tests pixel (`x`, `y`); true when it should be shaded and written.
    fn test(&mut self, x: u32, y: u32, depth: f32) -> bool;
    /// Writes the shaded colour of a pixel that passed [`Target::test`].
    fn write(&mut self, x: u32, y: u32, color: Rgb8);
    /// Polygon `face` is about to be rasterized (`back`: seen from behind).
    #[inline(always)]
    fn polygon(&mut self, _face: usize, _back: bool) {}
    /// Whether the rasterizer should trace its spans on row `y`.
    #[inline(always)]
    fn wants_trace(&self, _y: u32) -> bool {
        false
    }
    /// A traced span, before its fragments.
    #[inline(always)]
    fn trace<const N: usize>(&mut self, _span: &SpanTrace<'_, N>) {}
    /// Pixel (`x`, `y`) passed the test with interpolated attributes
    /// `attrs`, the method lit it `lit` (unclamped) and it became `color`.
    #[inline(always)]
    fn shaded<const N: usize>(
        &mut self,
        _x: u32,
        _y: u32,
        _attrs: &[f32; N],
        _lit: Rgb,
        _color: Rgb8,
    ) {
    }
}

struct Frame {
    color: Image,
    depth: Vec<f32>,
    width: u32,
}

impl Target for Frame {
    fn test(&mut self, x: u32, y: u32, depth: f32) -> bool {
        let d = &mut self.depth[y as usize * self.width as usize + x as usize];
        // Depth test "less", and the near/far clip keeps depth within [0, 1].
        if depth < *d {
            *d = depth;
            true
        } else {
            false
        }
    }

    fn write(&mut self, x: u32, y: u32, color: Rgb8) {
        self.color.set_pixel(x, y, color);
    }
}

struct CoverageCounter {
    counts: Vec<u32>,
    width: u32,
}

impl Target for CoverageCounter {
    fn test(&mut self, x: u32, y: u32, _depth: f32) -> bool {
        self.counts[y as usize * self.width as usize + x as usize] += 1;
        false
    }

    fn write(&mut self, _x: u32, _y: u32, _color: Rgb8) {}
}

/// What a shading method attaches to corners and computes per fragment.
trait Method<const N: usize> {
    /// The attributes at corner `corner` (vertex `vertex`), lit as a front
    /// face or, with `back`, with the normal reversed.
    fn corner(&mut self, corner: usize, vertex: u32, back: bool) -> [f32; N];
    /// Called before polygon `face` is rasterized.
    fn begin_polygon(&mut self, face: usize, corners: std::ops::Range<usize>, back: bool);
    /// The light of a fragment with interpolated attributes `attrs`, before
    /// clamping and rounding.
    fn shade(&mut self, attrs: &[f32; N]) -> Rgb;
    /// The pixel for light `lit` from [`Method::shade`]: `Rgb8::from_rgb`,
    /// which a method with one colour per polygon computes once.
    #[inline(always)]
    fn pixel(&self, lit: Rgb) -> Rgb8 {
        Rgb8::from_rgb(lit)
    }
    /// Lighting evaluations so far.
    fn evaluations(&self) -> u64;
}

struct SceneRefs<'a> {
    mesh: &'a Mesh,
    normals: &'a CornerNormals,
    faces: Vec<Option<Vec3>>,
    lighting: Lighting,
}

impl SceneRefs<'_> {
    fn corner_normal(&self, corner: usize) -> Vec3 {
        self.normals.normals[self.normals.corner[corner] as usize]
    }
}

struct FlatMethod<'a> {
    scene: &'a SceneRefs<'a>,
    color: Rgb,
    pixel: Rgb8,
    evaluations: u64,
}

impl Method<0> for FlatMethod<'_> {
    fn corner(&mut self, _: usize, _: u32, _: bool) -> [f32; 0] {
        []
    }

    fn begin_polygon(&mut self, face: usize, corners: std::ops::Range<usize>, back: bool) {
        let mesh = self.scene.mesh;
        let count = corners.len() as f32;
        let centroid = corners
            .map(|c| mesh.positions()[mesh.corners()[c] as usize])
            .sum::<Vec3>()
            / count;
        let normal = self.scene.faces[face].unwrap_or(Vec3::Z);
        let normal = if back { -normal } else { normal };
        self.evaluations += 1;
        self.color = self.scene.lighting.eval(centroid, normal, Terms::Full);
        self.pixel = Rgb8::from_rgb(self.color);
    }

    fn shade(&mut self, _: &[f32; 0]) -> Rgb {
        self.color
    }

    fn pixel(&self, _: Rgb) -> Rgb8 {
        self.pixel
    }

    fn evaluations(&self) -> u64 {
        self.evaluations
    }
}

struct GouraudMethod<'a> {
    scene: &'a SceneRefs<'a>,
    terms: Terms,
    /// Colour per distinct (vertex, normal, facing): lit once per frame.
    lit: HashMap<(u32, u32, bool), [f32; 3]>,
}

impl Method<3> for GouraudMethod<'_> {
    fn corner(&mut self, corner: usize, vertex: u32, back: bool) -> [f32; 3] {
        let scene = self.scene;
        let terms = self.terms;
        let normal_index = scene.normals.corner[corner];
        *self
            .lit
            .entry((vertex, normal_index, back))
            .or_insert_with(|| {
                let n = scene.corner_normal(corner);
                let n = if back { -n } else { n };
                let p = scene.mesh.positions()[vertex as usize];
                scene.lighting.eval(p, n, terms).clamped().to_array()
            })
    }

    fn begin_polygon(&mut self, _: usize, _: std::ops::Range<usize>, _: bool) {}

    fn shade(&mut self, attrs: &[f32; 3]) -> Rgb {
        Rgb::from_array(*attrs)
    }

    fn evaluations(&self) -> u64 {
        self.lit.len() as u64
    }
}

struct PhongMethod<'a> {
    scene: &'a SceneRefs<'a>,
    flip: f32,
    evaluations: u64,
}

impl Method<6> for PhongMethod<'_> {
    fn corner(&mut self, corner: usize, vertex: u32, _: bool) -> [f32; 6] {
        let n = self.scene.corner_normal(corner);
        let p = self.scene.mesh.positions()[vertex as usize];
        [n.x, n.y, n.z, p.x, p.y, p.z]
    }

    fn begin_polygon(&mut self, _: usize, _: std::ops::Range<usize>, back: bool) {
        self.flip = if back { -1.0 } else { 1.0 };
    }

    fn shade(&mut self, a: &[f32; 6]) -> Rgb {
        let n = (Vec3::new(a[0], a[1], a[2]) * self.flip).normalize_or_zero();
        let p = Vec3::new(a[3], a[4], a[5]);
        self.evaluations += 1;
        self.scene.lighting.eval(p, n, Terms::Full)
    }

    fn evaluations(&self) -> u64 {
        self.evaluations
    }
}

/// How a fragment's light becomes a pixel: true colour, or a palette entry.
/// A type parameter rather than a branch, so true colour pays nothing.
trait Output: Copy {
    fn pixel<const N: usize, M: Method<N>>(&self, method: &M, lit: Rgb) -> Rgb8;
}

#[derive(Clone, Copy)]
struct TrueColor;

impl Output for TrueColor {
    #[inline(always)]
    fn pixel<const N: usize, M: Method<N>>(&self, method: &M, lit: Rgb) -> Rgb8 {
        method.pixel(lit)
    }
}

/// The palette and the material colour its shades are of.
#[derive(Clone, Copy)]
struct Indexed(Palette, Rgb);

impl Output for Indexed {
    fn pixel<const N: usize, M: Method<N>>(&self, _: &M, lit: Rgb) -> Rgb8 {
        self.0.shade(lit, self.1).color
    }
}

/// Connects the rasterizer to a target and a shading method.
struct ShadingSink<'a, const N: usize, M, T, O> {
    method: &'a mut M,
    target: &'a mut T,
    shaded: u64,
    output: O,
}

impl<const N: usize, M: Method<N>, T: Target, O: Output> FragmentSink<N>
    for ShadingSink<'_, N, M, T, O>
{
    // Inlined into the span loop, as it was before the probe's hooks made
    // it look bigger to the compiler (the hooks compile to nothing).
    #[inline]
    fn fragment(&mut self, x: u32, y: u32, depth: f32, attrs: &[f32; N]) {
        if self.target.test(x, y, depth) {
            self.shaded += 1;
            let lit = self.method.shade(attrs);
            let color = self.output.pixel(&*self.method, lit);
            self.target.shaded(x, y, attrs, lit, color);
            self.target.write(x, y, color);
        }
    }

    #[inline(always)]
    fn wants_trace(&self, y: u32) -> bool {
        self.target.wants_trace(y)
    }

    #[inline(always)]
    fn trace(&mut self, span: &SpanTrace<'_, N>) {
        self.target.trace(span);
    }
}

/// The guard band, in NDC units, that keeps window coordinates within ±2^20
/// pixels, so snapped edge arithmetic fits in `i64` with room to spare.
pub(crate) fn guard_band(width: u32, height: u32) -> f32 {
    ((1u32 << 20) as f32 / width.max(height) as f32 - 1.0).max(1.0)
}

/// The perspective divide and viewport transform, then snapping: where a
/// clip-space vertex lands in the window, as both rasterizers place it.
pub fn to_window<const N: usize>(v: &ClipVertex<N>, width: u32, height: u32) -> ScreenVertex<N> {
    let inv_w = 1.0 / f64::from(v.clip.w);
    let x = (f64::from(v.clip.x) * inv_w + 1.0) * 0.5 * f64::from(width);
    let y = (1.0 - f64::from(v.clip.y) * inv_w) * 0.5 * f64::from(height);
    let depth = (f64::from(v.clip.z) * inv_w + 1.0) * 0.5;
    // Clipping keeps vertices within the guard band (±2^19 pixels) unless an
    // edge's ends are both so far away (beyond about 1e20) that f32 cannot
    // place the cut; the clamp keeps the edge arithmetic from overflowing then.
    let limit = f64::from(1u32 << 21);
    ScreenVertex {
        x: snap(x.clamp(-limit, limit)),
        y: snap(y.clamp(-limit, limit)),
        depth: depth as f32,
        inv_w: inv_w as f32,
        attrs: v.attrs,
    }
}

/// Draws a frame with the scanline rasterizer into `target`.
pub(crate) fn draw(
    scene: &Scene,
    options: &RenderOptions,
    lighting: &Lighting,
    target: &mut impl Target,
) -> RenderStats {
    let aspect = options.width as f32 / options.height as f32;
    let view_projection = scene.camera.projection(aspect) * scene.camera.view();
    let refs = SceneRefs {
        mesh: &scene.mesh,
        normals: &scene.normals,
        faces: face_normals(&scene.mesh),
        lighting: lighting.clone(),
    };
    match options.shading {
        Shading::Flat => {
            let mut m = FlatMethod {
                scene: &refs,
                color: Rgb::BLACK,
                pixel: Rgb8::default(),
                evaluations: 0,
            };
            draw_with(&refs, options, view_projection, &mut m, target)
        }
        Shading::Gouraud => {
            let terms = if options.gouraud_specular {
                Terms::Full
            } else {
                Terms::AmbientDiffuse
            };
            let mut m = GouraudMethod {
                scene: &refs,
                terms,
                lit: HashMap::new(),
            };
            draw_with(&refs, options, view_projection, &mut m, target)
        }
        Shading::Phong => {
            let mut m = PhongMethod {
                scene: &refs,
                flip: 1.0,
                evaluations: 0,
            };
            draw_with(&refs, options, view_projection, &mut m, target)
        }
    }
}

/// Rasterizes one window polygon through the method into the target;
/// returns the fragments shaded.
fn fill<const N: usize, M: Method<N>, T: Target, O: Output>(
    window: &[ScreenVertex<N>],
    options: &RenderOptions,
    walk: &ScanlineOptions,
    method: &mut M,
    target: &mut T,
    output: O,
) -> u64 {
    let (width, height) = (options.width, options.height);
    let mut sink = ShadingSink {
        method,
        target,
        shaded: 0,
        output,
    };
    match options.polygons {
        Polygons::Fans => rasterize_fan_with(window, width, height, walk, &mut sink),
        Polygons::Whole => rasterize_polygon_with(window, width, height, walk, &mut sink),
    }
    sink.shaded
}

fn draw_with<const N: usize, M: Method<N>, T: Target>(
    scene: &SceneRefs<'_>,
    options: &RenderOptions,
    view_projection: Mat4,
    method: &mut M,
    target: &mut T,
) -> RenderStats {
    let (width, height) = (options.width, options.height);
    let mesh = scene.mesh;
    let clip_positions: Vec<Vec4> = mesh
        .positions()
        .iter()
        .map(|p| view_projection * p.extend(1.0))
        .collect();
    let guard = guard_band(width, height);
    let mut stats = RenderStats {
        polygons: mesh.polygon_count() as u64,
        ..RenderStats::default()
    };
    let (mut input, mut clipped, mut scratch) = (Vec::new(), Vec::new(), Vec::new());
    let mut window: Vec<ScreenVertex<N>> = Vec::new();
    let mut shaded = 0;
    let walk = ScanlineOptions {
        interpolation: options.interpolation,
        fraction_bits: options.fixed_point_bits,
    };

    let mut project =
        |method: &mut M, face: usize, back: bool, window: &mut Vec<ScreenVertex<N>>| {
            input.clear();
            for c in mesh.corner_range(face) {
                let vertex = mesh.corners()[c];
                input.push(ClipVertex {
                    clip: clip_positions[vertex as usize],
                    attrs: method.corner(c, vertex, back),
                });
            }
            clip_polygon(&input, guard, &mut clipped, &mut scratch);
            window.clear();
            window.extend(clipped.iter().map(|v| to_window(v, width, height)));
        };

    for face in 0..mesh.polygon_count() {
        if scene.faces[face].is_none() {
            stats.degenerate += 1;
            continue;
        }
        project(method, face, false, &mut window);
        let area = signed_area_ccw(&window);
        if window.len() < 3 || area == 0 {
            stats.invisible += 1;
            continue;
        }
        let back = area < 0;
        if back {
            if options.cull_backfaces {
                stats.culled += 1;
                continue;
            }
            project(method, face, true, &mut window);
            window.reverse();
        }
        stats.rasterized += 1;
        method.begin_polygon(face, mesh.corner_range(face), back);
        target.polygon(face, back);
        shaded += match options.palette {
            None => fill(&window, options, &walk, method, target, TrueColor),
            Some(p) => {
                let output = Indexed(p, scene.lighting.material.kd);
                fill(&window, options, &walk, method, target, output)
            }
        };
    }
    stats.fragments_shaded = shaded;
    stats.lighting_evaluations = method.evaluations();
    stats
}
