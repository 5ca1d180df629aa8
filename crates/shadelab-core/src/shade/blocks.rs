//! The three shading methods on blocks of 8 fragments.
//!
//! A [`Shader`] turns a block's interpolated attributes into packed colours.
//! The band walk is generic over it, so each method gets its own inner
//! loop. Constants (light position, colours, eye) are splatted into lanes
//! once per band ([`Shader::Lanes`]), not once per block. Phong with one
//! point light, the common case, has its own shader with no loop over
//! lights; any other light set goes through the general one.
//!
//! Every shader computes what [`Lighting::eval`] computes, in f32 lanes, so
//! colours agree with the scanline rasterizer within 1/255.

// Loops over channels index several arrays at once.
#![allow(clippy::needless_range_loop)]

use glam::Vec3;

use super::model::{LightKind, Lighting, Specular};
use crate::simd::{pow_unit, pow_whole, pow_whole_groups, Simd, Vf, Vi};

/// The most attributes a method interpolates (Phong: normal and position).
pub(crate) const MAX_ATTRS: usize = 6;

/// Per-method colouring of a block of fragments.
pub(crate) trait Shader: Sync {
    /// How many attributes the method interpolates.
    const ATTRS: usize;
    /// The method's constants, in lanes.
    type Lanes<S: Simd>: Copy;
    /// Splats the constants, once per band.
    fn lanes<S: Simd>(&self, s: S) -> Self::Lanes<S>;
    /// Whether fragments are queued and shaded 8 at a time with
    /// [`Shader::light`] (worth it when shading costs far more than
    /// queueing: Phong), rather than block by block with [`Shader::shade`].
    const DEFERRED: bool = false;
    /// Colours of 8 queued fragments whose attributes are final (normals
    /// already turned for back faces). Only called when `DEFERRED`.
    fn light<S: Simd>(&self, lanes: &Self::Lanes<S>, s: S, attrs: &[Vf<S>; MAX_ATTRS]) -> Vi<S> {
        let _ = (lanes, attrs);
        Vi::splat(s, 0)
    }
    /// [`Shader::light`] of 16 queued fragments, as two blocks of 8.
    #[inline(always)]
    fn light_pair<S: Simd>(
        &self,
        lanes: &Self::Lanes<S>,
        s: S,
        a: &[Vf<S>; MAX_ATTRS],
        b: &[Vf<S>; MAX_ATTRS],
    ) -> [Vi<S>; 2] {
        [self.light(lanes, s, a), self.light(lanes, s, b)]
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
}

/// A vertex colour channel in [0, 1] as Gouraud interpolates it: in byte
/// units plus one half, `255·c + 0.5`, so that each pixel only truncates
/// (interpolation commutes with this affine map, so the pixel's value is
/// `255·c + 0.5` of its interpolated colour `c`, as [`pack`] would round it).
#[inline(always)]
pub(crate) fn byte_units<S: Simd>(c: Vf<S>) -> Vf<S> {
    c * 255.0 + c.splat_like(0.5)
}

/// Gouraud shading: the vertex colours, interpolated.
pub(crate) struct GouraudShader;

impl Shader for GouraudShader {
    const ATTRS: usize = 3;
    type Lanes<S: Simd> = ();
    #[inline(always)]
    fn lanes<S: Simd>(&self, _: S) {}
    /// The interpolated colours are in byte units plus one half (see
    /// [`byte_units`]): only truncation and saturation are left.
    #[inline(always)]
    fn shade<S: Simd>(&self, _: &(), _: S, _: u32, _: f32, a: &[Vf<S>; MAX_ATTRS]) -> Vi<S> {
        Vf::to_bytes(a[0], a[1], a[2])
    }
}

/// One light, prepared for 8 lanes.
#[derive(Debug, Clone, Copy)]
struct LaneLight {
    /// Point light position, or `None` for a directional light.
    position: Option<Vec3>,
    /// Unit vector towards a directional light.
    towards: Vec3,
    /// `Id·Kd` per channel.
    diffuse: [f32; 3],
    /// `Is·Ks` per channel.
    specular: [f32; 3],
}

/// Phong shading: the reflection model per pixel, as [`Lighting::eval`].
#[derive(Debug, Default)]
pub(crate) struct PhongShader {
    /// One point light: what [`OnePointLight`] needs.
    pub one_point_light: Option<OnePointLight>,
    ambient: [f32; 3],
    eye: Vec3,
    lights: Vec<LaneLight>,
    shininess: f32,
    power: Power,
    blinn: bool,
}

/// How `max(0, r·v)^p` is computed for the material's `p`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
enum Power {
    /// A whole `p` in 1..=1024: repeated squaring.
    Whole(u32),
    /// Other `p` in (0, 4096]: exp2(p·log2(x)) by polynomials.
    Fraction,
    /// Anything else (0, negative, huge): `powf` lane by lane.
    #[default]
    Scalar,
}

impl PhongShader {
    /// Becomes the shader for `lighting`, reusing its storage (no
    /// allocation once it has held as many lights).
    pub fn update(&mut self, lighting: &Lighting) {
        let m = &lighting.material;
        let mut lights = std::mem::take(&mut self.lights);
        lights.clear();
        lights.extend(lighting.lights.iter().map(|light| {
            let i = light.color * light.intensity;
            let (position, towards) = match light.kind {
                LightKind::Point { position } => (Some(position), Vec3::ZERO),
                LightKind::Directional { direction } => (None, (-direction).normalize_or_zero()),
            };
            LaneLight {
                position,
                towards,
                diffuse: (i * m.kd).to_array(),
                specular: (i * m.ks).to_array(),
            }
        }));
        let p = m.shininess;
        let power = if p.fract() == 0.0 && (1.0..=1024.0).contains(&p) {
            Power::Whole(p as u32)
        } else if p > 0.0 && p <= 4096.0 {
            Power::Fraction
        } else {
            Power::Scalar
        };
        let one_point_light = match lights[..] {
            [LaneLight {
                position: Some(position),
                diffuse,
                specular,
                ..
            }] => Some(OnePointLight {
                position,
                diffuse,
                specular,
                ambient: (lighting.ambient * m.ka).to_array(),
                eye: lighting.eye,
                shininess: p,
                power,
                blinn: lighting.specular == Specular::BlinnPhong,
            }),
            _ => None,
        };
        *self = PhongShader {
            one_point_light,
            ambient: (lighting.ambient * m.ka).to_array(),
            eye: lighting.eye,
            lights,
            shininess: p,
            power,
            blinn: lighting.specular == Specular::BlinnPhong,
        };
    }

    #[inline(always)]
    fn power<S: Simd>(&self, x: Vf<S>) -> Vf<S> {
        match self.power {
            Power::Whole(p) => pow_whole(x, p),
            Power::Fraction => pow_unit(x, self.shininess),
            Power::Scalar => power_scalar(x, self.shininess),
        }
    }
}

/// `x^p` lane by lane with `powf`, for exponents outside `pow_unit`'s range.
#[cold]
fn power_scalar<S: Simd>(x: Vf<S>, p: f32) -> Vf<S> {
    let mut lanes = [0.0; 8];
    x.store(&mut lanes);
    for v in &mut lanes {
        *v = v.powf(p);
    }
    Vf::load(x.1, &lanes)
}

/// `v / |v|`. Where `|v|` is zero the lanes become NaN; `light` keeps
/// those out of the colour exactly where glam's `normalize_or_zero` would
/// give zero: a NaN `n·l` fails the `n·l > 0` test (unlit, as `n·l = 0`),
/// and a NaN specular cosine is taken to 0 by `max(cos, 0)` (the second
/// operand wins on NaN in both backends).
#[inline(always)]
fn normalize<S: Simd>(v: [Vf<S>; 3]) -> [Vf<S>; 3] {
    let len2 = v[0].mul_add(v[0], v[1].mul_add(v[1], v[2] * v[2]));
    let scale = len2.rsqrt();
    [v[0] * scale, v[1] * scale, v[2] * scale]
}

impl Shader for PhongShader {
    const ATTRS: usize = 6;
    const DEFERRED: bool = true;
    type Lanes<S: Simd> = ();
    #[inline(always)]
    fn lanes<S: Simd>(&self, _: S) {}
    #[inline(always)]
    fn light<S: Simd>(&self, _: &(), s: S, a: &[Vf<S>; MAX_ATTRS]) -> Vi<S> {
        PhongShader::light(self, s, a)
    }
    #[inline(always)]
    fn shade<S: Simd>(&self, _: &(), s: S, _: u32, flip: f32, a: &[Vf<S>; MAX_ATTRS]) -> Vi<S> {
        self.light(
            s,
            &[a[0] * flip, a[1] * flip, a[2] * flip, a[3], a[4], a[5]],
        )
    }
}

impl PhongShader {
    /// The reflection model at 8 points `a[3..6]` with normals `a[0..3]`
    /// (normalized here), as packed colours.
    #[inline(always)]
    pub fn light<S: Simd>(&self, s: S, a: &[Vf<S>; MAX_ATTRS]) -> Vi<S> {
        let [r, g, b] = self.radiance(s, a, true);
        pack(r, g, b)
    }

    /// The reflected light per channel, unclamped, at 8 points `a[3..6]`
    /// with normals `a[0..3]` (normalized here); without the specular term
    /// unless `specular` (as [`Lighting::eval`] with its `Terms`).
    #[inline(always)]
    pub fn radiance<S: Simd>(&self, s: S, a: &[Vf<S>; MAX_ATTRS], specular: bool) -> [Vf<S>; 3] {
        let n = normalize([a[0], a[1], a[2]]);
        let p = [a[3], a[4], a[5]];
        let view = towards(s, self.eye, &p);
        let mut out = [
            Vf::splat(s, self.ambient[0]),
            Vf::splat(s, self.ambient[1]),
            Vf::splat(s, self.ambient[2]),
        ];
        let zero = Vf::splat(s, 0.0);
        for light in &self.lights {
            let l = match light.position {
                Some(q) => towards(s, q, &p),
                None => [
                    Vf::splat(s, light.towards.x),
                    Vf::splat(s, light.towards.y),
                    Vf::splat(s, light.towards.z),
                ],
            };
            let n_dot_l = n[0].mul_add(l[0], n[1].mul_add(l[1], n[2] * l[2]));
            let lit = n_dot_l.gt(zero);
            let spec = if specular {
                let cosine = if self.blinn {
                    let h = normalize([l[0] + view[0], l[1] + view[1], l[2] + view[2]]);
                    n[0].mul_add(h[0], n[1].mul_add(h[1], n[2] * h[2]))
                } else {
                    let twice = n_dot_l * 2.0;
                    let r = [
                        n[0] * twice - l[0],
                        n[1] * twice - l[1],
                        n[2] * twice - l[2],
                    ];
                    r[0].mul_add(view[0], r[1].mul_add(view[1], r[2] * view[2]))
                };
                self.power(cosine.max(zero))
            } else {
                zero
            };
            for k in 0..3 {
                let add = n_dot_l.mul_add(Vf::splat(s, light.diffuse[k]), spec * light.specular[k]);
                out[k] = out[k] + Vf::select(lit, add, zero);
            }
        }
        out
    }
}

/// The unit vectors from points `p` towards `q` (NaN where they coincide).
#[inline(always)]
fn towards<S: Simd>(s: S, q: Vec3, p: &[Vf<S>; 3]) -> [Vf<S>; 3] {
    normalize([
        Vf::splat(s, q.x) - p[0],
        Vf::splat(s, q.y) - p[1],
        Vf::splat(s, q.z) - p[2],
    ])
}

/// Colours in [0, 1] (clamped) to packed bytes, rounding as
/// [`crate::Rgb8::from_rgb`]: `255·c + 0.5` truncated, which for `c` in
/// [0, 1] is the same arithmetic, and saturates as the clamp would.
#[inline(always)]
fn pack<S: Simd>(r: Vf<S>, g: Vf<S>, b: Vf<S>) -> Vi<S> {
    Vf::to_bytes(byte_units(r), byte_units(g), byte_units(b))
}

/// Phong shading lit by exactly one point light: the general shader with
/// the loop over lights unrolled and every constant already in lanes.
#[derive(Debug, Clone, Copy)]
pub(crate) struct OnePointLight {
    position: Vec3,
    diffuse: [f32; 3],
    specular: [f32; 3],
    ambient: [f32; 3],
    eye: Vec3,
    shininess: f32,
    power: Power,
    blinn: bool,
}

/// [`OnePointLight`]'s constants in lanes.
#[derive(Clone, Copy)]
pub(crate) struct OneLightLanes<S: Simd> {
    light: [Vf<S>; 3],
    eye: [Vf<S>; 3],
    ambient: [Vf<S>; 3],
    diffuse: [Vf<S>; 3],
    specular: [Vf<S>; 3],
}

impl Shader for OnePointLight {
    const ATTRS: usize = 6;
    const DEFERRED: bool = true;
    type Lanes<S: Simd> = OneLightLanes<S>;

    #[inline(always)]
    fn light<S: Simd>(&self, k: &OneLightLanes<S>, s: S, a: &[Vf<S>; MAX_ATTRS]) -> Vi<S> {
        self.lit(k, s, 1.0, a)
    }

    #[inline(always)]
    fn light_pair<S: Simd>(
        &self,
        k: &OneLightLanes<S>,
        s: S,
        a: &[Vf<S>; MAX_ATTRS],
        b: &[Vf<S>; MAX_ATTRS],
    ) -> [Vi<S>; 2] {
        self.lit_groups(k, s, 1.0, [a, b])
    }

    #[inline(always)]
    fn lanes<S: Simd>(&self, s: S) -> OneLightLanes<S> {
        let v = |v: Vec3| [Vf::splat(s, v.x), Vf::splat(s, v.y), Vf::splat(s, v.z)];
        let c = |c: [f32; 3]| c.map(|c| Vf::splat(s, c));
        OneLightLanes {
            light: v(self.position),
            eye: v(self.eye),
            ambient: c(self.ambient),
            diffuse: c(self.diffuse),
            specular: c(self.specular),
        }
    }

    #[inline(always)]
    fn shade<S: Simd>(
        &self,
        k: &OneLightLanes<S>,
        s: S,
        _: u32,
        flip: f32,
        a: &[Vf<S>; MAX_ATTRS],
    ) -> Vi<S> {
        self.lit(k, s, flip, a)
    }
}

impl OnePointLight {
    /// As `PhongShader::light`, with `flip` folded into the normal's scale.
    #[inline(always)]
    fn lit<S: Simd>(&self, k: &OneLightLanes<S>, s: S, flip: f32, a: &[Vf<S>; MAX_ATTRS]) -> Vi<S> {
        let [c] = self.lit_groups(k, s, flip, [a]);
        c
    }

    /// [`OnePointLight::lit`] of `G` blocks at once, each step done for all
    /// of them before the next: the blocks' dependency chains (three square
    /// roots, the power's squarings) overlap in the processor instead of
    /// waiting one after the other.
    #[inline(always)]
    fn lit_groups<S: Simd, const G: usize>(
        &self,
        k: &OneLightLanes<S>,
        s: S,
        flip: f32,
        a: [&[Vf<S>; MAX_ATTRS]; G],
    ) -> [Vi<S>; G] {
        let zero = Vf::splat(s, 0.0);
        let mut n = [[zero; 3]; G];
        let mut l = [[zero; 3]; G];
        let mut v = [[zero; 3]; G];
        let mut n_dot_l = [zero; G];
        for g in 0..G {
            let a = a[g];
            let len2 = a[0].mul_add(a[0], a[1].mul_add(a[1], a[2] * a[2]));
            let scale = len2.rsqrt() * flip;
            n[g] = [a[0] * scale, a[1] * scale, a[2] * scale];
            let p = [a[3], a[4], a[5]];
            l[g] = normalize([k.light[0] - p[0], k.light[1] - p[1], k.light[2] - p[2]]);
            v[g] = normalize([k.eye[0] - p[0], k.eye[1] - p[1], k.eye[2] - p[2]]);
            let (n, l) = (n[g], l[g]);
            n_dot_l[g] = n[0].mul_add(l[0], n[1].mul_add(l[1], n[2] * l[2]));
        }
        let mut cosine = [zero; G];
        if self.blinn {
            for g in 0..G {
                let (n, l, v) = (n[g], l[g], v[g]);
                let h = normalize([l[0] + v[0], l[1] + v[1], l[2] + v[2]]);
                cosine[g] = n[0]
                    .mul_add(h[0], n[1].mul_add(h[1], n[2] * h[2]))
                    .max(zero);
            }
        } else {
            for g in 0..G {
                // r·v with r = 2(n·l)n − l.
                let (n, l, v) = (n[g], l[g], v[g]);
                let twice = n_dot_l[g] * 2.0;
                let r = [
                    n[0] * twice - l[0],
                    n[1] * twice - l[1],
                    n[2] * twice - l[2],
                ];
                cosine[g] = r[0]
                    .mul_add(v[0], r[1].mul_add(v[1], r[2] * v[2]))
                    .max(zero);
            }
        }
        let spec = match self.power {
            Power::Whole(p) => pow_whole_groups(cosine, p),
            Power::Fraction => cosine.map(|c| pow_unit(c, self.shininess)),
            Power::Scalar => cosine.map(|c| power_scalar(c, self.shininess)),
        };
        let mut colors = [Vi::splat(s, 0); G];
        for g in 0..G {
            let lit = n_dot_l[g].gt(zero);
            let mut out = k.ambient;
            for c in 0..3 {
                let add = n_dot_l[g].mul_add(k.diffuse[c], spec[g] * k.specular[c]);
                out[c] = out[c] + Vf::select(lit, add, zero);
            }
            colors[g] = pack(out[0], out[1], out[2]);
        }
        colors
    }
}
