//! The frame: checks a request, sets up the frame's lighting and its
//! polygons (the window transform, `window.rs`, and polygon assembly,
//! `assemble.rs`: facing, culling, clipping), and hands them to the
//! rasterizer it names. Both rasterizers implement [`Rasterize`] and
//! receive the polygons as a [`crate::raster::VertexStage`]; what they share
//! below the frame (snapping, fans) lives in `raster/`, the shading
//! methods in `shade/`.
//!
//! Facing is decided from the snapped window polygon, as OpenGL does. A
//! back-facing polygon drawn with culling off is lit with its normals turned
//! towards the viewer and re-wound, so the rasterizers only ever see
//! counter-clockwise polygons.
//!
//! Two modes of old hardware are drawn by the scanline rasterizer only:
//! fixed-point attribute stepping ([`RenderOptions::fixed_point_bits`]) and
//! the indexed palette ([`RenderOptions::palette`]). A probe (`probe.rs`)
//! watches one frame through the scanline rasterizer's `Target` hooks,
//! which default to nothing.

mod assemble;
mod window;

pub(crate) use self::assemble::Geometry;
pub use self::window::to_window;

use glam::Vec3;

use crate::color::Rgb;
use crate::image::Image;
use crate::light::{LightKind, Material, Specular};
use crate::raster::scanline::ScanlineRasterizer;
use crate::raster::tiled::TiledRasterizer;
use crate::raster::Rasterize;
use crate::scene::{Rasterizer, RenderError, RenderOptions, RenderStats, Scene, Shading};
use crate::shade::Lighting;
use crate::simd::SimdLevel;

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

/// The row alignment of [`Renderer::render_methods_rows`]' parts: the
/// tiled rasterizer's bands.
pub const ROW_ALIGN: u32 = crate::raster::tiled::BAND_ROWS;

/// Rows of part `part` of `parts` of an image `height` rows high, for
/// [`Renderer::render_methods_rows`]: the parts are consecutive, cover the
/// image, start at multiples of [`ROW_ALIGN`] and differ by at most
/// [`ROW_ALIGN`] rows; a part is empty when there are more parts than
/// runs of [`ROW_ALIGN`] rows (or `part >= parts`).
pub fn part_rows(height: u32, part: u32, parts: u32) -> std::ops::Range<u32> {
    if part >= parts {
        return height..height;
    }
    let runs = u64::from(height.div_ceil(ROW_ALIGN));
    let edge = |k: u32| {
        let run = (runs * u64::from(k) / u64::from(parts)) as u32;
        (run * ROW_ALIGN).min(height)
    };
    edge(part)..edge(part + 1)
}

/// Whether [`Renderer::render_methods_rows`] draws only the rows it is
/// given for `options`: false for the modes only the scanline rasterizer
/// draws, which it draws whole whatever the rows (so one part of a frame
/// is enough for them).
pub fn draws_in_parts(options: &RenderOptions) -> bool {
    options.rasterizer != Rasterizer::Scanline
        && Shading::ALL.iter().all(|&shading| {
            !RenderOptions {
                shading,
                ..*options
            }
            .needs_scanline()
        })
}

/// Renders frames, keeping its working buffers from one frame to the next
/// (the tiled rasterizer allocates nothing per frame once warmed up).
///
/// Work is spread over rayon's current thread pool; run it inside
/// `ThreadPool::install` to choose the number of threads.
#[derive(Debug)]
pub struct Renderer {
    tiled: TiledRasterizer,
    scanline: ScanlineRasterizer,
    /// The frame's face normals and window positions.
    geometry: Geometry,
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
        let tiled = TiledRasterizer::new(level);
        Renderer {
            geometry: Geometry::with_simd(tiled.simd()),
            tiled,
            scanline: ScanlineRasterizer,
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
        let mut frame = self.geometry.frame(scene, options);
        let lighting = &self.lighting;
        Ok(match options.rasterizer {
            Rasterizer::Tiled => self
                .tiled
                .render(&mut frame, scene, options, lighting, image),
            Rasterizer::Scanline => self
                .scanline
                .render(&mut frame, scene, options, lighting, image),
        })
    }

    /// Renders `scene` with each shading method, flat, Gouraud and Phong
    /// (in that order, into `images`; `options.shading` is not read): the
    /// same images and statistics as three calls of
    /// [`Renderer::render_into`]. The tiled rasterizer transforms, sets up
    /// and bins the geometry once for the three (the viewer's three panels
    /// and `compare` share everything but the method); the scanline one,
    /// and modes only it draws, render three frames.
    ///
    /// # Errors
    /// As [`Renderer::render_into`], for any of the three methods.
    pub fn render_methods(
        &mut self,
        scene: &Scene,
        options: &RenderOptions,
        images: [&mut Image; 3],
    ) -> Result<[RenderStats; 3], RenderError> {
        let rows = 0..options.height;
        let (stats, _) = self.render_methods_rows(scene, options, rows, images)?;
        Ok(stats)
    }

    /// [`Renderer::render_methods`] for the image rows `rows` only (see
    /// [`part_rows`]): each image becomes those rows of the frame, `width ×
    /// rows.len()` pixels, so that two threads of their own (the viewer's
    /// two workers) can each draw a part of one frame. Triangles outside
    /// the rows are counted but not set up; the bytes are those of the
    /// whole frame's rows.
    ///
    /// Each part's statistics count the whole frame's polygons (and
    /// Gouraud's lighting evaluations, per vertex) and its own rows' pixels:
    /// `fragments_shaded`, `covered_pixels` and Phong's
    /// `lighting_evaluations` of the parts add up to the frame's. So do
    /// flat's `lighting_evaluations`: a polygon's is counted by the part
    /// holding the top row of its pixels (by the first part for a polygon
    /// that needed clipping or is drawn as a back face), so that no part
    /// sets up triangles outside its rows to count them.
    ///
    /// The modes only the scanline rasterizer draws are drawn whole: the
    /// rows drawn are returned (then `0..height`, with the frame's counts).
    ///
    /// # Errors
    /// As [`Renderer::render_methods`], and [`RenderError::Rows`] when
    /// `rows` is empty, leaves the image, or does not start (and end, but
    /// at the image's last row) at a multiple of [`ROW_ALIGN`].
    pub fn render_methods_rows(
        &mut self,
        scene: &Scene,
        options: &RenderOptions,
        rows: std::ops::Range<u32>,
        mut images: [&mut Image; 3],
    ) -> Result<([RenderStats; 3], std::ops::Range<u32>), RenderError> {
        let height = options.height;
        let aligned = |y: u32| y.is_multiple_of(ROW_ALIGN);
        if rows.is_empty()
            || rows.end > height
            || !aligned(rows.start)
            || !(aligned(rows.end) || rows.end == height)
        {
            return Err(RenderError::Rows {
                start: rows.start,
                end: rows.end,
                height,
                align: ROW_ALIGN,
            });
        }
        let each = Shading::ALL.map(|shading| RenderOptions {
            shading,
            ..*options
        });
        if !draws_in_parts(options) {
            let mut stats = [RenderStats::default(); 3];
            for ((options, image), stats) in each.iter().zip(images).zip(&mut stats) {
                *stats = self.render_into(scene, options, image)?;
            }
            return Ok((stats, 0..height));
        }
        for options in &each {
            options.check()?;
        }
        validate(scene, options)?;
        let part_height = rows.end - rows.start;
        for image in images.iter_mut() {
            if image.width() != options.width || image.height() != part_height {
                **image = Image::filled(options.width, part_height, options.background);
            }
        }
        set_lighting(&mut self.lighting, scene, options);
        let mut frame = self.geometry.frame(scene, options);
        let lighting = &self.lighting;
        let stats =
            (self.tiled).render_methods(&mut frame, scene, options, lighting, &rows, images);
        Ok((stats, rows))
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
        // Coverage needs no colour: the cheapest method.
        let options = RenderOptions {
            shading: Shading::Flat,
            ..*options
        };
        let mut frame = self.geometry.frame(scene, &options);
        Ok(match options.rasterizer {
            Rasterizer::Tiled => self.tiled.coverage(&mut frame, scene, &options, &lighting),
            Rasterizer::Scanline => self
                .scanline
                .coverage(&mut frame, scene, &options, &lighting),
        })
    }
}

/// The lighting of `scene` drawn with `options`.
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
    // The indices' maximum is found once, when they are made: a frame
    // reads none of them here.
    let largest = scene.normals.largest_index();
    if scene.normals.corner().len() != scene.mesh.corners().len()
        || (!scene.normals.corner().is_empty() && largest as usize >= scene.normals.normals.len())
    {
        return Err(RenderError::NormalsMismatch {
            normals: scene.normals.corner().len(),
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
            LightKind::Point { position } => position.is_finite(),
            LightKind::Directional { direction } => direction.is_finite(),
        };
        if !(position_ok && rgb_finite(light.color) && light.intensity.is_finite()) {
            return Err(RenderError::NonFinite("light"));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::Renderer;
    use crate::camera::Camera;
    use crate::color::{Rgb, Rgb8};
    use crate::image::Image;
    use crate::light::{Light, LightKind, Material, NO_ATTENUATION};
    use crate::models::builtin_model;
    use crate::normals::{vertex_normals, NormalWeighting};
    use crate::scene::{RenderOptions, Scene, Shading};
    use crate::simd::SimdLevel;

    /// Bands that hand back the bins set up on the other thread (as where
    /// the two threads' cores are apart: every line of those bins flushed
    /// once read) draw the same bytes, with the same counts, as bands that
    /// do not, at every SIMD level, for one method and for the three at
    /// once.
    #[test]
    fn bins_handed_back_change_nothing() {
        let mesh = builtin_model("teapot", None).unwrap();
        let normals = vertex_normals(&mesh, NormalWeighting::Uniform, None);
        let (low, high) = mesh.bounds();
        let camera =
            Camera::framing_sphere((low + high) / 2.0, (high - low).length() / 2.0, 40.0, 1.5);
        let scene = Scene {
            mesh,
            normals,
            camera: camera.orbit(30.0, 20.0),
            ambient: Rgb::new(0.1, 0.1, 0.1),
            lights: vec![Light {
                kind: LightKind::Point {
                    position: Vec3::new(3.0, 4.0, 6.0),
                },
                color: Rgb::new(1.0, 0.95, 0.9),
                intensity: 0.9,
                attenuation: NO_ATTENUATION,
            }],
            material: Material {
                ka: Rgb::new(0.9, 0.4, 0.3),
                kd: Rgb::new(0.8, 0.45, 0.3),
                ks: Rgb::new(0.6, 0.6, 0.6),
                shininess: 12.0,
            },
        };
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap();
        let draw = |level: SimdLevel, apart: Vec<bool>| {
            pool.install(|| {
                let mut renderer = Renderer::with_simd(level);
                let mut frames = Vec::new();
                // Twice each: the second frame's setup writes the lines the
                // first frame's bands handed back.
                for _ in 0..2 {
                    renderer.tiled.assume_apart(apart.clone());
                    for shading in Shading::ALL {
                        let options = RenderOptions {
                            width: 300,
                            height: 200,
                            shading,
                            background: Rgb8::new(0, 255, 0),
                            ..RenderOptions::default()
                        };
                        let mut image = Image::filled(1, 1, options.background);
                        let stats = renderer.render_into(&scene, &options, &mut image).unwrap();
                        frames.push((image, stats));
                    }
                    let mut images: [Image; 3] =
                        std::array::from_fn(|_| Image::filled(1, 1, Rgb8::new(0, 0, 0)));
                    let options = RenderOptions {
                        width: 300,
                        height: 200,
                        ..RenderOptions::default()
                    };
                    let [a, b, c] = &mut images;
                    let stats = renderer
                        .render_methods(&scene, &options, [a, b, c])
                        .unwrap();
                    frames.extend(images.into_iter().zip(stats));
                }
                frames
            })
        };
        for level in SimdLevel::supported() {
            let kept = draw(level, vec![false, false]);
            let handed_back = draw(level, vec![false, true]);
            assert_eq!(kept.len(), handed_back.len());
            for (k, (a, b)) in kept.iter().zip(&handed_back).enumerate() {
                assert!(a.0 == b.0, "{}: frame {k} differs", level.name());
                assert_eq!(a.1, b.1, "{}: frame {k}'s counts", level.name());
            }
            // Something was drawn: the teapot covers many pixels.
            assert!(kept[0].1.covered_pixels > 2_000);
        }
    }
}
