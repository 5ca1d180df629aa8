//! The three shading methods on blocks of 8 fragments.
//!
//! A [`Shader`] turns a block's interpolated attributes into packed colours.
//! The band walk is generic over it, so each method gets its own inner
//! loop. Constants (light position, colours, eye) are splatted into lanes
//! once per band ([`Shader::Lanes`]), not once per block. Phong with one
//! point light, the common case, has its own shader with no loop over
//! lights; any other light set goes through the general one.
//!
//! Phong's shaders light queued fragments 16 at a time ([`Simd::F16`]: one
//! AVX-512 vector where the processor has it, else two of 8).
//!
//! Every shader computes what [`Lighting::eval`] computes, in f32 lanes, so
//! colours agree with the scanline rasterizer within 1/255.

// Loops over channels index several arrays at once.
#![allow(clippy::needless_range_loop)]

use super::lanes::{pack, unit_normal, LaneLight, PlainPoint, Surface, SurfaceLanes, ToLanes};
use super::model::Lighting;
use crate::simd::{Lanes, Simd, Vf, Vi};

/// The most attributes a method interpolates (Phong: normal and position).
pub(crate) const MAX_ATTRS: usize = 6;

/// What is known of the attributes [`Shader::shade_lanes`] gets: chosen
/// per row of a span (`fill_span` in `raster/tiled/band/pairs.rs`), so
/// that the conversion to bytes does only what the row needs.
pub(crate) mod known {
    /// Nothing: any value, NaN and infinities included.
    pub(crate) const ANYTHING: u8 = 0;
    /// Every lane below 2^31 or NaN ([`crate::simd::Lanes::store_bytes_below`]).
    pub(crate) const BELOW_2_31: u8 = 1;
    /// Every lane in `[0, 256)` ([`crate::simd::Lanes::store_bytes_within`]).
    pub(crate) const BYTES: u8 = 2;
}

/// Per-method colouring of a block of fragments.
pub(crate) trait Shader: Sync {
    /// How many attributes the method interpolates.
    const ATTRS: usize;
    /// How many of the first attributes are used only after normalising
    /// (Phong's normal, `unit_normal`): in perspective they are left
    /// divided by `w`, a positive factor the normalisation removes, which
    /// saves three multiplications per 8 fragments.
    const SCALE_FREE: usize = 0;
    /// The method's constants, in lanes.
    type Lanes<S: Simd>: Copy;
    /// Splats the constants, once per band.
    fn lanes<S: Simd>(&self, s: S) -> Self::Lanes<S>;
    /// Whether fragments are queued and shaded 16 at a time with
    /// [`Shader::light_queue`] (worth it when shading costs far more than
    /// queueing: Phong), rather than block by block with [`Shader::shade`].
    const DEFERRED: bool = false;
    /// Whether the band also writes flat's and Gouraud's colours of the
    /// fragments this (deferred) shader's triangles pass the depth test
    /// with: the three methods in one walk of each triangle
    /// ([`AllMethods`]).
    const ALL_METHODS: bool = false;
    /// Colours of `16·G` queued fragments whose attributes are final
    /// (normals already turned for back faces), packed into `colors`:
    /// attribute `k` of fragments `16·g..16·g + 16` is `attrs[g][k]`. The
    /// `G` groups are lit together, so that their long dependency chains
    /// overlap. Only called when `DEFERRED`.
    fn light_queue<S: Simd, const G: usize>(
        &self,
        lanes: &Self::Lanes<S>,
        s: S,
        attrs: &[[S::F16; MAX_ATTRS]; G],
        colors: &mut [[i32; 16]; G],
    ) {
        let _ = (lanes, s, attrs, colors);
    }
    /// As [`Shader::shade`] on `L::LANES` fragments at once (a span's
    /// blocks two at a time, see `raster/tiled/band/pairs.rs`), with the
    /// same operations lane by lane, the colours stored into `colors`
    /// (`L::LANES` long). Only called when not `DEFERRED`. `KNOWN`: what is
    /// known of the attributes, one of [`known`]'s, so the conversion to
    /// bytes may drop its guard ([`Lanes::store_bytes_below`]) or its
    /// shuffles ([`Lanes::store_bytes_within`]).
    fn shade_lanes<L: Lanes, const KNOWN: u8>(
        &self,
        color: u32,
        attrs: &[L; MAX_ATTRS],
        colors: &mut [i32],
    ) {
        let _ = (color, attrs, colors);
    }
    /// Colours of 8 fragments of one triangle, packed `r | g << 8 | b << 16`:
    /// `color` is the triangle's flat colour (packed), `flip` −1 for a back
    /// face drawn with culling off (its normals turn), else 1.
    fn shade<S: Simd>(
        &self,
        lanes: &Self::Lanes<S>,
        s: S,
        color: u32,
        flip: f32,
        attrs: &[Vf<S>; MAX_ATTRS],
    ) -> Vi<S>;
}

/// Flat shading: the triangle's polygon was lit once, at setup.
pub(crate) struct FlatShader;

impl Shader for FlatShader {
    const ATTRS: usize = 0;
    type Lanes<S: Simd> = ();
    #[inline(always)]
    fn lanes<S: Simd>(&self, _: S) {}
    #[inline(always)]
    fn shade<S: Simd>(&self, _: &(), s: S, color: u32, _: f32, _: &[Vf<S>; MAX_ATTRS]) -> Vi<S> {
        Vi::splat(s, color as i32)
    }
    #[inline(always)]
    fn shade_lanes<L: Lanes, const KNOWN: u8>(
        &self,
        color: u32,
        _: &[L; MAX_ATTRS],
        colors: &mut [i32],
    ) {
        colors.fill(color as i32);
    }
}

/// Gouraud shading: the vertex colours, interpolated.
pub(crate) struct GouraudShader;

impl Shader for GouraudShader {
    const ATTRS: usize = 3;
    type Lanes<S: Simd> = ();
    #[inline(always)]
    fn lanes<S: Simd>(&self, _: S) {}
    /// The interpolated colours are in byte units plus one half (see
    /// `lanes::byte_units`): only truncation and saturation are left.
    #[inline(always)]
    fn shade<S: Simd>(&self, _: &(), _: S, _: u32, _: f32, a: &[Vf<S>; MAX_ATTRS]) -> Vi<S> {
        Vf::to_bytes(a[0], a[1], a[2])
    }
    #[inline(always)]
    fn shade_lanes<L: Lanes, const KNOWN: u8>(
        &self,
        _: u32,
        a: &[L; MAX_ATTRS],
        colors: &mut [i32],
    ) {
        match KNOWN {
            known::BYTES => L::store_bytes_within(a[0], a[1], a[2], colors),
            known::BELOW_2_31 => L::store_bytes_below(a[0], a[1], a[2], colors),
            _ => L::store_bytes(a[0], a[1], a[2], colors),
        }
    }
}

/// Phong shading: the reflection model per pixel ([`Surface::radiance`]),
/// with any lights.
#[derive(Debug, Default)]
pub(crate) struct PhongShader {
    /// One point light: what [`OnePointLight`] needs.
    pub one_point_light: Option<OnePointLight>,
    surface: Surface,
    lights: Vec<LaneLight>,
}

impl PhongShader {
    /// Becomes the shader for `lighting`, reusing its storage (no
    /// allocation once it has held as many lights).
    pub fn update(&mut self, lighting: &Lighting) {
        let surface = Surface::of(lighting);
        let mut lights = std::mem::take(&mut self.lights);
        lights.clear();
        lights
            .extend((lighting.lights.iter()).map(|light| LaneLight::of(light, &lighting.material)));
        let one_point_light = match lights[..] {
            [light] if light.is_plain_point() => Some(OnePointLight { surface, light }),
            _ => None,
        };
        *self = PhongShader {
            one_point_light,
            surface,
            lights,
        };
    }

    /// The reflection model at the points `a[3..6]` with normals `a[0..3]`
    /// (normalized here), packed into `dst` (as many as the lanes).
    #[inline(always)]
    pub fn light<V: Lanes>(&self, a: &[V; MAX_ATTRS], dst: &mut [i32]) {
        pack(self.radiance(a, true), dst)
    }

    /// The reflected light per channel, unclamped, at the points `a[3..6]`
    /// with normals `a[0..3]` (normalized here); without the specular term
    /// unless `specular` (as [`Lighting::eval`] with its `Terms`).
    #[inline(always)]
    pub fn radiance<V: Lanes>(&self, a: &[V; MAX_ATTRS], specular: bool) -> [V; 3] {
        let n = unit_normal([a[0], a[1], a[2]], 1.0);
        let k = self.surface.lanes(a[0]);
        let [out] = (self.surface).radiance(&k, &self.lights, [n], [[a[3], a[4], a[5]]], specular);
        out
    }
}

impl Shader for PhongShader {
    const ATTRS: usize = 6;
    const SCALE_FREE: usize = 3;
    const DEFERRED: bool = true;
    type Lanes<S: Simd> = ();
    #[inline(always)]
    fn lanes<S: Simd>(&self, _: S) {}
    #[inline(always)]
    fn light_queue<S: Simd, const G: usize>(
        &self,
        _: &(),
        _: S,
        a: &[[S::F16; MAX_ATTRS]; G],
        colors: &mut [[i32; 16]; G],
    ) {
        let k = self.surface.lanes(a[0][0]);
        let out = lit_groups(&self.surface, &k, &self.lights, 1.0, a.each_ref());
        for g in 0..G {
            pack(out[g], &mut colors[g]);
        }
    }
    #[inline(always)]
    fn shade<S: Simd>(&self, _: &(), s: S, _: u32, flip: f32, a: &[Vf<S>; MAX_ATTRS]) -> Vi<S> {
        let mut colors = [0; 8];
        self.light(
            &[a[0] * flip, a[1] * flip, a[2] * flip, a[3], a[4], a[5]],
            &mut colors,
        );
        Vi(s.i_load(&colors), s)
    }
}

/// The reflected light of `G` groups of points `a[g][3..6]` with normals
/// `a[g][0..3]` turned by `flip`: each step done for all of them before
/// the next, so that their dependency chains (three square roots, the
/// power's squarings) overlap in the processor instead of waiting one
/// after the other.
#[inline(always)]
fn lit_groups<V: Lanes, L: ToLanes<V>, const G: usize>(
    surface: &Surface,
    k: &SurfaceLanes<V>,
    lights: &[L],
    flip: f32,
    a: [&[V; MAX_ATTRS]; G],
) -> [[V; 3]; G] {
    // Loops, not closures: see `Surface::radiance`.
    let (mut n, mut p) = ([[a[0][0]; 3]; G], [[a[0][0]; 3]; G]);
    for g in 0..G {
        let a = a[g];
        n[g] = unit_normal([a[0], a[1], a[2]], flip);
        p[g] = [a[3], a[4], a[5]];
    }
    surface.radiance(k, lights, n, p, true)
}

/// Phong shading lit by exactly one point light without attenuation, the
/// common case: the model with no loop over lights, no test of the light's
/// kind, and every constant already in lanes.
#[derive(Debug, Clone, Copy)]
pub(crate) struct OnePointLight {
    surface: Surface,
    light: LaneLight,
}

/// [`OnePointLight`]'s constants in lanes `V`.
#[derive(Clone, Copy)]
pub(crate) struct OneLightLanes<V> {
    surface: SurfaceLanes<V>,
    light: PlainPoint<V>,
}

impl OnePointLight {
    /// The constants in lanes like `s`.
    #[inline(always)]
    fn lanes_like<V: Lanes>(&self, s: V) -> OneLightLanes<V> {
        OneLightLanes {
            surface: self.surface.lanes(s),
            light: PlainPoint::new(&self.light, s),
        }
    }
}

impl Shader for OnePointLight {
    const ATTRS: usize = 6;
    const SCALE_FREE: usize = 3;
    const DEFERRED: bool = true;
    type Lanes<S: Simd> = OneLightLanes<S::F16>;

    #[inline(always)]
    fn lanes<S: Simd>(&self, s: S) -> OneLightLanes<S::F16> {
        self.lanes_like(s.f16_load(&[0.0; 16]))
    }

    #[inline(always)]
    fn light_queue<S: Simd, const G: usize>(
        &self,
        k: &OneLightLanes<S::F16>,
        _: S,
        a: &[[S::F16; MAX_ATTRS]; G],
        colors: &mut [[i32; 16]; G],
    ) {
        let out = lit_groups(&self.surface, &k.surface, &[k.light], 1.0, a.each_ref());
        for g in 0..G {
            pack(out[g], &mut colors[g]);
        }
    }

    /// Not the hot path (the band queues Phong's fragments): the constants
    /// are splatted into 8 lanes here.
    #[inline(always)]
    fn shade<S: Simd>(
        &self,
        _: &OneLightLanes<S::F16>,
        s: S,
        _: u32,
        flip: f32,
        a: &[Vf<S>; MAX_ATTRS],
    ) -> Vi<S> {
        let k = self.lanes_like(a[0]);
        let [out] = lit_groups(&self.surface, &k.surface, &[k.light], flip, [a]);
        let mut colors = [0; 8];
        pack(out, &mut colors);
        Vi(s.i_load(&colors), s)
    }
}

/// A Phong shader `P` whose band also writes flat's and Gouraud's colours
/// of the same fragments, each into its own buffer: the three methods of
/// one scene share coverage and depth, so each triangle is walked and
/// depth-tested once for the three (see `raster/tiled/band`).
pub(crate) struct AllMethods<'a, P>(pub &'a P);

impl<P: Shader> Shader for AllMethods<'_, P> {
    const ATTRS: usize = P::ATTRS;
    const SCALE_FREE: usize = P::SCALE_FREE;
    const DEFERRED: bool = P::DEFERRED;
    const ALL_METHODS: bool = true;
    type Lanes<S: Simd> = P::Lanes<S>;

    #[inline(always)]
    fn lanes<S: Simd>(&self, s: S) -> P::Lanes<S> {
        self.0.lanes(s)
    }

    #[inline(always)]
    fn light_queue<S: Simd, const G: usize>(
        &self,
        k: &P::Lanes<S>,
        s: S,
        a: &[[S::F16; MAX_ATTRS]; G],
        colors: &mut [[i32; 16]; G],
    ) {
        self.0.light_queue(k, s, a, colors)
    }

    #[inline(always)]
    fn shade<S: Simd>(
        &self,
        k: &P::Lanes<S>,
        s: S,
        color: u32,
        flip: f32,
        a: &[Vf<S>; MAX_ATTRS],
    ) -> Vi<S> {
        self.0.shade(k, s, color, flip, a)
    }
}
