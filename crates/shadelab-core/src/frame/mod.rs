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
mod spatial;
mod window;

pub(crate) use self::assemble::Geometry;
use self::spatial::SpatialScene;
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
    /// A large mesh with its polygons in a spatial order, for the tiled
    /// rasterizer (`spatial.rs`).
    spatial: SpatialScene,
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
            spatial: SpatialScene::with_simd(tiled.simd()),
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
    /// From the second frame in a row of a mesh of many polygons, the tiled
    /// rasterizer draws a copy that lists them in a spatial order
    /// (`spatial.rs`), faster to set up; a frame of it that meets a depth
    /// tie is drawn again from `scene`, so the pixels are always `scene`'s.
    /// Of the counts, only the fragments that passed the depth test on
    /// their way (and so Phong's lighting evaluations) depend on the order.
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
        if options.rasterizer == Rasterizer::Tiled {
            let drawn = draw_spatial(
                &mut self.spatial,
                &mut self.tiled,
                (scene, &mut self.geometry),
                |tiled, copy, geometry| {
                    let mut frame = geometry.frame(copy, options);
                    tiled.render(&mut frame, copy, options, lighting, image)
                },
            );
            if let Some(stats) = drawn {
                return Ok(stats);
            }
        }
        let mut frame = self.geometry.frame(scene, options);
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
    /// `lighting_evaluations` of the parts add up to the frame's (drawn in
    /// the same order: see [`Renderer::render_into`] on a spatial one). So do
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
        let lighting = &self.lighting;
        let drawn = draw_spatial(
            &mut self.spatial,
            &mut self.tiled,
            (scene, &mut self.geometry),
            |tiled, copy, geometry| {
                let mut frame = geometry.frame(copy, options);
                let [a, b, c] = &mut images;
                tiled.render_methods(&mut frame, copy, options, lighting, &rows, [a, b, c])
            },
        );
        if let Some(stats) = drawn {
            return Ok((stats, rows));
        }
        let mut frame = self.geometry.frame(scene, options);
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

/// Draws `scene`'s copy in a spatial order (`spatial.rs`), if it has one
/// (made from `scene` and its own geometry, whose face normals and
/// centroids the copy takes over), with `draw` (given the rasterizer, the
/// copy and the copy's geometry),
/// the depth tests watching for ties. What `draw` returned; `None` when
/// there is no copy, or when the frame met a tie: its pixels may differ
/// from the scene's, so the caller draws the scene, and does from now on
/// for this mesh.
fn draw_spatial<T>(
    spatial: &mut SpatialScene,
    tiled: &mut TiledRasterizer,
    (scene, geometry): (&Scene, &mut Geometry),
    draw: impl FnOnce(&mut TiledRasterizer, &Scene, &mut Geometry) -> T,
) -> Option<T> {
    let (copy, geometry) = spatial.update(scene, geometry)?;
    tiled.watch_ties(true);
    let drawn = draw(tiled, copy, geometry);
    tiled.watch_ties(false);
    if !tiled.met_ties() {
        return Some(drawn);
    }
    spatial.met_tie();
    None
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::Renderer;
    use crate::camera::Camera;
    use crate::color::{Rgb, Rgb8};
    use crate::image::Image;
    use crate::light::{Light, LightKind, Material, NO_ATTENUATION};
    use crate::mesh::{CornerNormals, Mesh};
    use crate::models::builtin_model;
    use crate::normals::{vertex_normals, NormalWeighting};
    use crate::raster::Rasterize;
    use crate::scene::{RenderOptions, RenderStats, Scene, Shading};
    use crate::simd::SimdLevel;

    /// `mesh` with `normals`, seen from `camera`, lit by one point light.
    pub(super) fn lit_scene(mesh: Mesh, normals: CornerNormals, camera: Camera) -> Scene {
        Scene {
            mesh,
            normals,
            camera,
            ambient: Rgb::new(0.1, 0.1, 0.1),
            lights: vec![Light {
                kind: LightKind::Point {
                    position: Vec3::new(2.0, 3.0, 5.0),
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
        }
    }

    /// A square of `n × n` cells in the plane z = 0 drawn twice: first
    /// split along one diagonal with normals facing +z, then along the
    /// other with normals tilted. Every pixel it covers is a depth tie,
    /// which the depth test "less" gives to the first copy; a spatial
    /// order mixes the two.
    fn plane_drawn_twice(n: u32) -> Scene {
        let at = |i: u32, j: u32| j * (n + 1) + i;
        let positions = (0..=n)
            .flat_map(|j| (0..=n).map(move |i| (i, j)))
            .map(|(i, j)| Vec3::new(i as f32 / n as f32 - 0.5, j as f32 / n as f32 - 0.5, 0.0))
            .collect();
        let mut triangles = Vec::new();
        for second in [false, true] {
            for (i, j) in (0..n).flat_map(|j| (0..n).map(move |i| (i, j))) {
                let [a, b, c, d] = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
                if second {
                    triangles.extend([[a, b, d], [b, c, d]]);
                } else {
                    triangles.extend([[a, b, c], [a, c, d]]);
                }
            }
        }
        let half = triangles.len() / 2;
        let corner = (0..triangles.len())
            .flat_map(|k| [u32::from(k >= half); 3])
            .collect();
        let normals = vec![Vec3::Z, Vec3::new(0.5, 0.2, 0.8).normalize()];
        let mesh = Mesh::from_polygons(positions, triangles).unwrap();
        let camera = Camera::framing_sphere(Vec3::ZERO, 0.8, 40.0, 1.0).orbit(10.0, 5.0);
        lit_scene(mesh, CornerNormals::new(normals, corner), camera)
    }

    /// A frame and the counts the order does not change.
    type Drawn = (Image, (u64, u64, u64, u64, u64));

    /// Frames of `scene` with each method, then with the three at once,
    /// `frames` times in a row from one renderer.
    fn frames_of(scene: &Scene, frames: usize, cull_backfaces: bool) -> Vec<Vec<Drawn>> {
        let mut renderer = Renderer::new();
        let counts = |s: RenderStats| {
            let kept = (s.polygons, s.degenerate, s.culled, s.rasterized);
            (kept.0, kept.1, kept.2, kept.3, s.covered_pixels)
        };
        (0..frames)
            .map(|_| {
                let options = RenderOptions {
                    width: 160,
                    height: 120,
                    cull_backfaces,
                    background: Rgb8::new(0, 40, 0),
                    ..RenderOptions::default()
                };
                let mut frame = Vec::new();
                for shading in Shading::ALL {
                    let options = RenderOptions { shading, ..options };
                    let mut image = Image::filled(1, 1, options.background);
                    let stats = renderer.render_into(scene, &options, &mut image).unwrap();
                    frame.push((image, counts(stats)));
                }
                let mut images: [Image; 3] =
                    std::array::from_fn(|_| Image::filled(1, 1, Rgb8::new(0, 0, 0)));
                let [a, b, c] = &mut images;
                let stats = renderer.render_methods(scene, &options, [a, b, c]).unwrap();
                frame.extend(images.into_iter().zip(stats.map(counts)));
                frame
            })
            .collect()
    }

    /// A large mesh is drawn from its spatial copy from the second frame
    /// on, with the first frame's pixels and counts (but for the fragments
    /// that passed the depth test on their way): a torus seen at a slant,
    /// its far side behind its near side, culling on and off.
    #[test]
    fn a_large_mesh_in_a_spatial_order_draws_the_same_frames() {
        let mesh = builtin_model("torus", Some(256)).unwrap();
        assert!(mesh.polygon_count() >= super::spatial::SPATIAL_POLYGONS);
        let normals = vertex_normals(&mesh, NormalWeighting::Uniform, None);
        let (low, high) = mesh.bounds();
        let camera =
            Camera::framing_sphere((low + high) / 2.0, (high - low).length() / 2.0, 40.0, 1.5);
        let scene = lit_scene(mesh, normals, camera.orbit(20.0, 35.0));
        for cull in [true, false] {
            let frames = frames_of(&scene, 3, cull);
            for (k, (first, later)) in frames[0].iter().zip(&frames[2]).enumerate() {
                assert!(first.0 == later.0, "cull {cull}: image {k} differs");
                assert_eq!(first.1, later.1, "cull {cull}: image {k}'s counts");
                assert!(first.1 .4 > 2_000, "{}", first.1 .4);
            }
        }
        // The copy was drawn, with no tie.
        let mut renderer = Renderer::new();
        let options = RenderOptions::default();
        let mut image = Image::filled(1, 1, options.background);
        for _ in 0..2 {
            renderer.render_into(&scene, &options, &mut image).unwrap();
        }
        assert!(renderer.spatial.has_copy() && !renderer.tiled.met_ties());
    }

    /// The spatial copy numbers the normals its own way: when the scene's
    /// normals take other values under the same indices (another
    /// weighting), the copy's follow, and the frames drawn from it are
    /// those of a renderer that never saw the old values.
    #[test]
    fn a_spatial_copy_follows_new_values_of_the_normals() {
        let mesh = builtin_model("torus", Some(256)).unwrap();
        let uniform = vertex_normals(&mesh, NormalWeighting::Uniform, None);
        let area = vertex_normals(&mesh, NormalWeighting::Area, None);
        assert_eq!(uniform.normals.len(), area.normals.len());
        assert!(uniform.normals != area.normals);
        let (low, high) = mesh.bounds();
        let camera =
            Camera::framing_sphere((low + high) / 2.0, (high - low).length() / 2.0, 40.0, 1.5);
        let mut scene = lit_scene(mesh, uniform, camera.orbit(20.0, 35.0));
        let options = RenderOptions {
            width: 160,
            height: 120,
            shading: Shading::Gouraud,
            ..RenderOptions::default()
        };
        let mut renderer = Renderer::new();
        let mut image = Image::filled(1, 1, options.background);
        for _ in 0..2 {
            renderer.render_into(&scene, &options, &mut image).unwrap();
        }
        assert!(renderer.spatial.has_copy());
        let indices = scene.normals.indices_id();
        scene.normals.normals.clone_from(&area.normals);
        assert_eq!(scene.normals.indices_id(), indices);
        for shading in Shading::ALL {
            let options = RenderOptions { shading, ..options };
            renderer.render_into(&scene, &options, &mut image).unwrap();
            assert!(renderer.spatial.has_copy());
            let mut fresh = Image::filled(1, 1, options.background);
            Renderer::new()
                .render_into(&scene, &options, &mut fresh)
                .unwrap();
            assert!(image == fresh, "{shading:?}: the copy kept the old normals");
        }
    }

    /// A frame of the spatial copy that meets depth ties is drawn again
    /// from the scene, and must be: the copy's pixels differ. Later frames
    /// of the mesh are drawn from the scene alone.
    #[test]
    fn a_spatial_copy_that_meets_a_tie_is_drawn_again_in_the_meshs_order() {
        let scene = plane_drawn_twice(96);
        assert!(scene.mesh.polygon_count() >= super::spatial::SPATIAL_POLYGONS);
        let frames = frames_of(&scene, 3, true);
        for later in &frames[1..] {
            for (k, (first, later)) in frames[0].iter().zip(later).enumerate() {
                assert!(first.0 == later.0, "image {k} differs");
                assert_eq!(first.1, later.1, "image {k}'s counts");
            }
        }
        // The copy alone, drawn as the renderer would on its second frame.
        let options = RenderOptions::default();
        let mut renderer = Renderer::new();
        let mut image = Image::filled(1, 1, options.background);
        renderer.render_into(&scene, &options, &mut image).unwrap();
        let mut copy_image = image.clone();
        let (copy, geometry) = (renderer.spatial)
            .update(&scene, &mut renderer.geometry)
            .unwrap();
        let mut frame = geometry.frame(copy, &options);
        let lighting = super::lighting(copy, &options);
        // Unwatched, as every frame of a scene in its own order: no tie seen.
        (renderer.tiled).render(&mut frame, copy, &options, &lighting, &mut copy_image);
        assert!(!renderer.tiled.met_ties());
        assert!(copy_image != image, "the order made no difference");
        renderer.tiled.watch_ties(true);
        let mut frame = geometry.frame(copy, &options);
        (renderer.tiled).render(&mut frame, copy, &options, &lighting, &mut copy_image);
        assert!(renderer.tiled.met_ties());
        renderer.spatial.met_tie();
        assert!(!renderer.spatial.has_copy());
    }

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
        let scene = lit_scene(mesh, normals, camera.orbit(30.0, 20.0));
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
