//! The scanline rasterizer's frame: the frame's polygon assembly
//! (`frame/assemble.rs`, walked through [`PolygonSource`]) hands over each
//! polygon in order, clipped and in window space, and the
//! rasterizer fills it through a shading method (`shade::scalar`) into a
//! [`Target`] (the image and depth buffer, a coverage counter, or a probe).

use glam::Vec3;

use super::{rasterize_fan_with, rasterize_polygon_with, ScanlineOptions, SpanTrace};
use crate::color::{Rgb, Rgb8};
use crate::image::Image;
use crate::mesh::Mesh;
use crate::palette::Palette;
use crate::raster::{
    FragmentSink, PolygonSink, PolygonSource, Rasterize, Scratch, ScreenVertex, VertexStage,
};
use crate::scene::{Polygons, RenderOptions, RenderStats, Scene};
use crate::shade::{
    with_method, Indexed, Lighting, Method, MethodVisitor, Output, SceneRefs, TrueColor,
};

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

/// The reference rasterizer: one thread, polygon after polygon, span after
/// span (`mod.rs`), every mode of old hardware included.
#[derive(Debug, Default)]
pub(crate) struct ScanlineRasterizer;

impl Rasterize for ScanlineRasterizer {
    fn render<V: VertexStage>(
        &mut self,
        frame: &mut V,
        scene: &Scene,
        options: &RenderOptions,
        lighting: &Lighting,
        image: &mut Image,
    ) -> RenderStats {
        let mut target = Buffers {
            color: std::mem::replace(image, Image::filled(1, 1, options.background)),
            depth: vec![1.0; options.width as usize * options.height as usize],
            width: options.width,
        };
        target.color.pixels_mut().fill(options.background);
        let mut stats = draw(&frame.project(), scene, options, lighting, &mut target);
        stats.covered_pixels = target.depth.iter().filter(|&&d| d < 1.0).count() as u64;
        *image = target.color;
        stats
    }

    fn coverage<V: VertexStage>(
        &mut self,
        frame: &mut V,
        scene: &Scene,
        options: &RenderOptions,
        lighting: &Lighting,
    ) -> Vec<u32> {
        let mut counter = CoverageCounter {
            counts: vec![0; options.width as usize * options.height as usize],
            width: options.width,
        };
        draw(&frame.project(), scene, options, lighting, &mut counter);
        counter.counts
    }
}

/// The image and its depth buffer.
struct Buffers {
    color: Image,
    depth: Vec<f32>,
    width: u32,
}

impl Target for Buffers {
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

/// Draws a frame's `polygons` with the scanline rasterizer into `target`.
pub(crate) fn draw<P: PolygonSource>(
    polygons: &P,
    scene: &Scene,
    options: &RenderOptions,
    lighting: &Lighting,
    target: &mut impl Target,
) -> RenderStats {
    let refs = SceneRefs {
        mesh: &scene.mesh,
        normals: &scene.normals,
        faces: polygons.faces(),
        centroids: polygons.centroids(),
        lighting: lighting.clone(),
    };
    let draw = Draw {
        polygons,
        scene: &refs,
        options,
        target,
    };
    with_method(options.shading, options.gouraud_specular, &refs, draw)
}

/// [`draw_with`] waiting for its method.
struct Draw<'a, P, T> {
    polygons: &'a P,
    scene: &'a SceneRefs<'a>,
    options: &'a RenderOptions,
    target: &'a mut T,
}

impl<P: PolygonSource, T: Target> MethodVisitor for Draw<'_, P, T> {
    type Out = RenderStats;
    fn visit<const N: usize, M: Method<N>>(self, method: &mut M) -> RenderStats {
        draw_with(self.polygons, self.scene, self.options, method, self.target)
    }
}

/// The scanline rasterizer's end of polygon assembly: each polygon
/// rasterized whole (or as its fan) through the method into the target.
struct Fill<'a, const N: usize, M, T> {
    mesh: &'a Mesh,
    options: &'a RenderOptions,
    walk: ScanlineOptions,
    /// The palette, and the material colour its shades are of.
    palette: Option<(Palette, Rgb)>,
    method: &'a mut M,
    target: &'a mut T,
    shaded: u64,
}

impl<const N: usize, M: Method<N>, T: Target> PolygonSink<N> for Fill<'_, N, M, T> {
    fn corner(&mut self, corner: usize, vertex: u32, back: bool) -> [f32; N] {
        self.method.corner(corner, vertex, back)
    }

    fn polygon(&mut self, face: usize, _: Vec3, back: bool, window: &[ScreenVertex<N>]) {
        self.method
            .begin_polygon(face, self.mesh.corner_range(face), back);
        self.target.polygon(face, back);
        self.shaded += match self.palette {
            None => self.fill(window, TrueColor),
            Some((palette, kd)) => self.fill(window, Indexed(palette, kd)),
        };
    }
}

impl<const N: usize, M: Method<N>, T: Target> Fill<'_, N, M, T> {
    /// Rasterizes one window polygon through the method into the target;
    /// returns the fragments shaded.
    fn fill<O: Output>(&mut self, window: &[ScreenVertex<N>], output: O) -> u64 {
        let (width, height) = (self.options.width, self.options.height);
        let mut sink = ShadingSink {
            method: &mut *self.method,
            target: &mut *self.target,
            shaded: 0,
            output,
        };
        let walk = &self.walk;
        match self.options.polygons {
            Polygons::Fans => rasterize_fan_with(window, width, height, walk, &mut sink),
            Polygons::Whole => rasterize_polygon_with(window, width, height, walk, &mut sink),
        }
        sink.shaded
    }
}

fn draw_with<const N: usize, P: PolygonSource, M: Method<N>, T: Target>(
    polygons: &P,
    scene: &SceneRefs<'_>,
    options: &RenderOptions,
    method: &mut M,
    target: &mut T,
) -> RenderStats {
    let mesh = scene.mesh;
    let mut stats = RenderStats {
        polygons: polygons.count() as u64,
        ..RenderStats::default()
    };
    let mut fill = Fill {
        mesh,
        options,
        walk: ScanlineOptions {
            interpolation: options.interpolation,
            fraction_bits: options.fixed_point_bits,
        },
        palette: options.palette.map(|p| (p, scene.lighting.material.kd)),
        method,
        target,
        shaded: 0,
    };
    let faces = 0..polygons.count();
    polygons.walk(faces, &mut Scratch::default(), &mut fill, &mut stats);
    stats.fragments_shaded = fill.shaded;
    stats.lighting_evaluations = fill.method.evaluations();
    stats
}
