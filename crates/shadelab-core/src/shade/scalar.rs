//! The three methods on one fragment at a time, as the scanline rasterizer
//! and the probe draw them: what each attaches to a polygon's corners and
//! what it computes per fragment, over the scalar reflection model.

use std::collections::HashMap;
use std::ops::Range;

use glam::Vec3;

use super::model::{Lighting, Terms};
use crate::color::{Rgb, Rgb8};
use crate::mesh::{CornerNormals, Mesh};
use crate::palette::Palette;
use crate::scene::Shading;

/// What a shading method attaches to corners and computes per fragment.
pub(crate) trait Method<const N: usize> {
    /// The attributes at corner `corner` (vertex `vertex`), lit as a front
    /// face or, with `back`, with the normal reversed.
    fn corner(&mut self, corner: usize, vertex: u32, back: bool) -> [f32; N];
    /// Called before polygon `face` is rasterized.
    fn begin_polygon(&mut self, face: usize, corners: Range<usize>, back: bool);
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

/// What the methods read of a scene: the mesh, its corner normals, its
/// face normals (`None`: degenerate) and centroids, and the frame's lighting.
pub(crate) struct SceneRefs<'a> {
    /// The model.
    pub mesh: &'a Mesh,
    /// One normal per corner.
    pub normals: &'a CornerNormals,
    /// One normal per polygon, `None` where its area is zero.
    pub faces: &'a [Option<Vec3>],
    /// Each polygon's centroid (flat shading's lit point).
    pub centroids: &'a [Vec3],
    /// The frame's lighting.
    pub lighting: Lighting,
}

/// Receives the method a frame shades with: a generic callback, since each
/// method has its own number of attributes `N`.
pub(crate) trait MethodVisitor {
    /// What the callback returns.
    type Out;
    /// Draws with `method`.
    fn visit<const N: usize, M: Method<N>>(self, method: &mut M) -> Self::Out;
}

/// Calls `visitor` with the method `shading` (Gouraud with or without its
/// specular term, per `gouraud_specular`), reading `scene`.
pub(crate) fn with_method<V: MethodVisitor>(
    shading: Shading,
    gouraud_specular: bool,
    scene: &SceneRefs<'_>,
    visitor: V,
) -> V::Out {
    match shading {
        Shading::Flat => visitor.visit(&mut FlatMethod {
            scene,
            color: Rgb::BLACK,
            pixel: Rgb8::default(),
            evaluations: 0,
        }),
        Shading::Gouraud => visitor.visit(&mut GouraudMethod {
            scene,
            terms: if gouraud_specular {
                Terms::Full
            } else {
                Terms::AmbientDiffuse
            },
            lit: HashMap::new(),
        }),
        Shading::Phong => visitor.visit(&mut PhongMethod {
            scene,
            flip: 1.0,
            evaluations: 0,
        }),
    }
}

impl SceneRefs<'_> {
    fn corner_normal(&self, corner: usize) -> Vec3 {
        self.normals.normals[self.normals.corner()[corner] as usize]
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

    fn begin_polygon(&mut self, face: usize, _: Range<usize>, back: bool) {
        let centroid = self.scene.centroids[face];
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
        let normal_index = scene.normals.corner()[corner];
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

    fn begin_polygon(&mut self, _: usize, _: Range<usize>, _: bool) {}

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

    fn begin_polygon(&mut self, _: usize, _: Range<usize>, back: bool) {
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
pub(crate) trait Output: Copy {
    /// The pixel of light `lit` that `method` computed.
    fn pixel<const N: usize, M: Method<N>>(&self, method: &M, lit: Rgb) -> Rgb8;
}

#[derive(Clone, Copy)]
pub(crate) struct TrueColor;

impl Output for TrueColor {
    #[inline(always)]
    fn pixel<const N: usize, M: Method<N>>(&self, method: &M, lit: Rgb) -> Rgb8 {
        method.pixel(lit)
    }
}

/// The palette and the material colour its shades are of.
#[derive(Clone, Copy)]
pub(crate) struct Indexed(pub Palette, pub Rgb);

impl Output for Indexed {
    fn pixel<const N: usize, M: Method<N>>(&self, _: &M, lit: Rgb) -> Rgb8 {
        self.0.shade(lit, self.1).color
    }
}
