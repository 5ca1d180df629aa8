//! The reflection model in SIMD lanes: `model.rs`'s [`Lighting::eval`] for
//! a vector of points at a time (8, or 16 for Phong's queue: see
//! [`Lanes`]), or for `G` vectors whose dependency chains the processor
//! overlaps.
//!
//! Written once: the tiled rasterizer's Phong shaders (one point light or
//! any lights), its Gouraud vertex stage and its flat polygon stage all end
//! in [`Surface::radiance`]. Constants are prepared once per frame
//! ([`Surface`], [`LaneLight`]) and splatted into lanes once per band
//! ([`SurfaceLanes`], [`LightLanes`]) or per call. Generic over the
//! lanes' width, so the one model serves the 8-lane blocks and the 16-lane
//! groups, with the same operations in the same order.
//!
//! Agreement with the scalar model is within f32 rounding (and the
//! polynomial power, about 1e-6 relative): checked by the tests at the end
//! of this file against [`Lighting::eval`], and by the two rasterizers'
//! equivalence tests within 1/255.

// Loops over channels index several arrays at once.
#![allow(clippy::needless_range_loop)]

use glam::Vec3;

use super::model::Lighting;
use crate::light::{Light, LightKind, Material, Specular, NO_ATTENUATION};
use crate::simd::{pow_whole_groups, Lanes};

/// The least whole power of a cosine [`Surface::power`] computes; below
/// it the term is 0.
const POWER_FLOOR: f64 = 1.0 / (1u128 << 100) as f64;

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

/// What the model needs besides the lights and the point: `Ia·Ka`, the
/// eye, the specular exponent and the specular term's kind.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Surface {
    ambient: [f32; 3],
    eye: Vec3,
    shininess: f32,
    power: Power,
    /// For a whole exponent: the cosines at or below this are taken as 0
    /// before the power (see [`Surface::power`]).
    floor: f32,
    blinn: bool,
}

/// [`Surface`]'s vectors in lanes.
#[derive(Clone, Copy)]
pub(crate) struct SurfaceLanes<V> {
    ambient: [V; 3],
    eye: [V; 3],
}

/// One light prepared for the lanes.
#[derive(Debug, Clone, Copy)]
pub(crate) struct LaneLight {
    /// Point light position, or `None` for a directional light.
    position: Option<Vec3>,
    /// Unit vector towards a directional light.
    towards: Vec3,
    /// `Id·Kd` per channel.
    diffuse: [f32; 3],
    /// `Is·Ks` per channel.
    specular: [f32; 3],
    /// A point light's attenuation `[k0, k1, k2]`, `None` when it has none.
    attenuation: Option<[f32; 3]>,
}

/// [`LaneLight`] in lanes.
#[derive(Clone, Copy)]
pub(crate) struct LightLanes<V> {
    /// A point light's position, or the unit vector towards a directional one.
    at: [V; 3],
    point: bool,
    diffuse: [V; 3],
    specular: [V; 3],
    attenuation: Option<[V; 3]>,
}

/// `v` in lanes like `like`.
#[inline(always)]
fn splat3<V: Lanes>(like: V, v: Vec3) -> [V; 3] {
    splat_each(like, v.to_array())
}

impl LaneLight {
    /// `light` on `material`.
    pub fn of(light: &Light, material: &Material) -> LaneLight {
        let i = light.color * light.intensity;
        let (position, towards) = match light.kind {
            LightKind::Point { position } => (Some(position), Vec3::ZERO),
            LightKind::Directional { direction } => (None, (-direction).normalize_or_zero()),
        };
        LaneLight {
            position,
            towards,
            diffuse: (i * material.kd).to_array(),
            specular: (i * material.ks).to_array(),
            attenuation: (position.is_some() && light.attenuation != NO_ATTENUATION)
                .then_some(light.attenuation),
        }
    }

    /// Whether it is a point light.
    pub fn is_point(&self) -> bool {
        self.position.is_some()
    }

    /// Whether it is a point light with no attenuation.
    pub fn is_plain_point(&self) -> bool {
        self.position.is_some() && self.attenuation.is_none()
    }

    /// The light in lanes like `s`.
    #[inline(always)]
    pub fn lanes<V: Lanes>(&self, s: V) -> LightLanes<V> {
        // No closure (`Option::map`): see `Surface::radiance`.
        #[allow(clippy::manual_map)]
        let attenuation = match self.attenuation {
            Some(k) => Some(splat_each(s, k)),
            None => None,
        };
        LightLanes {
            at: splat3(s, self.position.unwrap_or(self.towards)),
            point: self.position.is_some(),
            diffuse: splat_each(s, self.diffuse),
            specular: splat_each(s, self.specular),
            attenuation,
        }
    }
}

impl Surface {
    /// The frame's `lighting` (its lights apart: [`LaneLight::of`]).
    pub fn of(lighting: &Lighting) -> Surface {
        let p = lighting.material.shininess;
        let power = if p.fract() == 0.0 && (1.0..=1024.0).contains(&p) {
            Power::Whole(p as u32)
        } else if p > 0.0 && p <= 4096.0 {
            Power::Fraction
        } else {
            Power::Scalar
        };
        Surface {
            ambient: (lighting.ambient * lighting.material.ka).to_array(),
            eye: lighting.eye,
            shininess: p,
            power,
            floor: match power {
                Power::Whole(p) => POWER_FLOOR.powf(1.0 / f64::from(p)) as f32,
                _ => 0.0,
            },
            blinn: lighting.specular == Specular::BlinnPhong,
        }
    }

    /// The vectors in lanes like `s`.
    #[inline(always)]
    pub fn lanes<V: Lanes>(&self, s: V) -> SurfaceLanes<V> {
        SurfaceLanes {
            ambient: splat_each(s, self.ambient),
            eye: splat3(s, self.eye),
        }
    }

    /// `x^p` for `G` blocks at once.
    ///
    /// A whole power of a small cosine is subnormal (0.06^32 < 2^-126; a
    /// surface lit from one side has many such pixels), and on Intel cores
    /// a vector multiplication with a subnormal result or operand takes a
    /// microcode assist (without this, Phong's full-screen quad took 16–18 %
    /// longer on the KVM Xeon of BENCHMARKS.md). So
    /// cosines whose power would be below [`POWER_FLOOR`] are taken as 0
    /// first: their term is then 0 instead of less than 2^-100, which
    /// rounds every colour to the same bytes (a channel of 1/510 or more
    /// has an ulp of 2^-32 or more).
    #[inline(always)]
    fn power<V: Lanes, const G: usize>(&self, mut x: [V; G]) -> [V; G] {
        match self.power {
            Power::Whole(p) => {
                let zero = x[0].splat_like(0.0);
                let floor = x[0].splat_like(self.floor);
                for x in &mut x {
                    *x = V::select(x.gt(floor), *x, zero);
                }
                return pow_whole_groups(x, p);
            }
            Power::Fraction => {
                for x in &mut x {
                    *x = x.pow_unit(self.shininess);
                }
            }
            Power::Scalar => {
                for x in &mut x {
                    *x = power_scalar(*x, self.shininess);
                }
            }
        }
        x
    }

    /// The reflected light per channel, unclamped, at `G` blocks of 8 points
    /// `p` with unit normals `n` (see [`unit_normal`]), lit by `lights`;
    /// without the specular term unless `specular`. As [`Lighting::eval`]:
    /// `Ia·Ka + Σ [Id·Kd·(n·l) + Is·Ks·max(0, r·v)^p]` over the lights with
    /// `n·l > 0` (`n·h` for Blinn's variant), each point light's terms divided
    /// by its attenuation when it has one.
    #[inline(always)]
    pub fn radiance<V: Lanes, L: ToLanes<V>, const G: usize>(
        &self,
        k: &SurfaceLanes<V>,
        lights: &[L],
        n: [[V; 3]; G],
        p: [[V; 3]; G],
        specular: bool,
    ) -> [[V; 3]; G] {
        // Loops, not closures: a closure the compiler does not inline is
        // compiled without the backend's target features, and each lane
        // operation in it becomes a call.
        let zero = k.eye[0].splat_like(0.0);
        let mut view = [[zero; 3]; G];
        for g in 0..G {
            view[g] = towards(&k.eye, &p[g]);
        }
        let mut out = [k.ambient; G];
        for light in lights {
            let light = light.lanes(zero);
            let attenuated = !L::PLAIN_POINT && light.attenuation.is_some();
            let mut l = [light.at; G];
            if L::PLAIN_POINT || light.point {
                for g in 0..G {
                    l[g] = towards(&light.at, &p[g]);
                }
            }
            let mut n_dot_l = [zero; G];
            for g in 0..G {
                n_dot_l[g] = dot(&n[g], &l[g]);
            }
            let mut spec = [zero; G];
            if specular {
                let mut cosine = [zero; G];
                for g in 0..G {
                    let (n, l, v) = (&n[g], &l[g], &view[g]);
                    cosine[g] = if self.blinn {
                        dot(n, &normalize([l[0] + v[0], l[1] + v[1], l[2] + v[2]]))
                    } else {
                        // r·v with r = 2(n·l)n − l.
                        let twice = n_dot_l[g] * 2.0;
                        let r = [
                            n[0] * twice - l[0],
                            n[1] * twice - l[1],
                            n[2] * twice - l[2],
                        ];
                        dot(&r, v)
                    }
                    .max(zero);
                }
                spec = self.power(cosine);
            }
            // A point light's 1 / (k0 + k1·d + k2·d²), when it has attenuation.
            let mut fade = [zero; G];
            if let (true, Some([k0, k1, k2])) = (attenuated, light.attenuation) {
                let q = &light.at;
                for g in 0..G {
                    let v = [q[0] - p[g][0], q[1] - p[g][1], q[2] - p[g][2]];
                    let d2 = dot(&v, &v);
                    let d = d2 * d2.rsqrt();
                    fade[g] = d2.mul_add(k2, d.mul_add(k1, k0)).recip();
                }
            }
            for g in 0..G {
                let lit = n_dot_l[g].gt(zero);
                for c in 0..3 {
                    let mut add = n_dot_l[g].mul_add(light.diffuse[c], spec[g] * light.specular[c]);
                    if attenuated {
                        add = add * fade[g];
                    }
                    out[g][c] = out[g][c] + V::select(lit, add, zero);
                }
            }
        }
        out
    }
}

/// A light as [`Surface::radiance`] takes it: prepared ([`LaneLight`],
/// splatted at each use) or already in lanes ([`LightLanes`]).
pub(crate) trait ToLanes<V> {
    /// Known to be a point light without attenuation, so that the model
    /// compiles with neither test (the common case: one such light).
    const PLAIN_POINT: bool = false;
    /// The light in lanes like `s`.
    fn lanes(&self, s: V) -> LightLanes<V>;
}

impl<V: Lanes> ToLanes<V> for LaneLight {
    #[inline(always)]
    fn lanes(&self, s: V) -> LightLanes<V> {
        LaneLight::lanes(self, s)
    }
}

/// A point light without attenuation, in lanes (see [`ToLanes::PLAIN_POINT`]).
#[derive(Clone, Copy)]
pub(crate) struct PlainPoint<V>(LightLanes<V>);

impl<V: Lanes> PlainPoint<V> {
    /// `light` in lanes like `s`, which must be a point light without
    /// attenuation.
    #[inline(always)]
    pub fn new(light: &LaneLight, s: V) -> PlainPoint<V> {
        debug_assert!(light.is_point() && light.attenuation.is_none());
        PlainPoint(light.lanes(s))
    }
}

impl<V: Copy> ToLanes<V> for PlainPoint<V> {
    const PLAIN_POINT: bool = true;
    #[inline(always)]
    fn lanes(&self, _: V) -> LightLanes<V> {
        self.0
    }
}

/// Each of three numbers in lanes like `s`.
#[inline(always)]
fn splat_each<V: Lanes>(s: V, c: [f32; 3]) -> [V; 3] {
    [s.splat_like(c[0]), s.splat_like(c[1]), s.splat_like(c[2])]
}

/// `x^p` lane by lane with `powf`, for exponents outside `pow_unit`'s range.
#[cold]
fn power_scalar<V: Lanes>(x: V, p: f32) -> V {
    x.map(|v| v.powf(p))
}

/// `a·b` over three lanes.
#[inline(always)]
fn dot<V: Lanes>(a: &[V; 3], b: &[V; 3]) -> V {
    a[0].mul_add(b[0], a[1].mul_add(b[1], a[2] * b[2]))
}

/// `v / |v|`. Where `|v|` is zero the lanes become NaN; the model keeps
/// those out of the colour exactly where glam's `normalize_or_zero` would
/// give zero: a NaN `n·l` fails the `n·l > 0` test (unlit, as `n·l = 0`),
/// and a NaN specular cosine is taken to 0 by `max(cos, 0)` (the second
/// operand wins on NaN in both backends).
#[inline(always)]
fn normalize<V: Lanes>(v: [V; 3]) -> [V; 3] {
    unit_normal(v, 1.0)
}

/// The interpolated normal `v` re-normalized and, with `flip` = −1 (a back
/// face drawn), turned: `flip · v / |v|`.
#[inline(always)]
pub(crate) fn unit_normal<V: Lanes>(v: [V; 3], flip: f32) -> [V; 3] {
    let scale = dot(&v, &v).rsqrt() * flip;
    [v[0] * scale, v[1] * scale, v[2] * scale]
}

/// The unit vectors from points `p` towards `q` (NaN where they coincide).
#[inline(always)]
fn towards<V: Lanes>(q: &[V; 3], p: &[V; 3]) -> [V; 3] {
    normalize([q[0] - p[0], q[1] - p[1], q[2] - p[2]])
}

/// A colour channel in [0, 1] in byte units plus one half, `255·c + 0.5`,
/// so that a pixel only truncates. Gouraud interpolates its vertex colours
/// this way: interpolation commutes with the affine map, so the pixel's
/// value is `255·c + 0.5` of its interpolated colour `c`, as [`pack`] would
/// round it.
#[inline(always)]
pub(crate) fn byte_units<V: Lanes>(c: V) -> V {
    c.mul_add(c.splat_like(255.0), c.splat_like(0.5))
}

/// Colours in [0, 1] (clamped) to packed bytes `r | g << 8 | b << 16`,
/// stored into `dst` (as many as the lanes), rounding as
/// [`crate::Rgb8::from_rgb`]: `255·c + 0.5` truncated, which for `c` in
/// [0, 1] is the same arithmetic, and saturates as the clamp would.
#[inline(always)]
pub(crate) fn pack<V: Lanes>([r, g, b]: [V; 3], dst: &mut [i32]) {
    V::store_bytes(byte_units(r), byte_units(g), byte_units(b), dst)
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::color::Rgb;
    use crate::shade::Terms;
    use crate::simd::{dispatch, Kernel, Simd, SimdLevel, Vf};

    /// Random-looking but fixed lightings, points and normals.
    fn lightings() -> Vec<Lighting> {
        let mut out = Vec::new();
        for (k, shininess) in [1.0, 7.0, 32.0, 12.5, 0.0, 5000.0].into_iter().enumerate() {
            for specular in [Specular::Phong, Specular::BlinnPhong] {
                let point = Light {
                    kind: LightKind::Point {
                        position: Vec3::new(2.0, 2.0 - k as f32, 3.0),
                    },
                    color: Rgb::new(1.0, 0.9, 0.8),
                    intensity: 0.7,
                    attenuation: if k >= 3 {
                        [0.5, 0.3, 0.2]
                    } else {
                        NO_ATTENUATION
                    },
                };
                let directional = Light {
                    kind: LightKind::Directional {
                        direction: Vec3::new(-1.0, -0.5, -1.0 + k as f32 * 0.3),
                    },
                    color: Rgb::new(0.5, 0.6, 1.0),
                    intensity: 0.5,
                    attenuation: NO_ATTENUATION,
                };
                out.push(Lighting {
                    ambient: Rgb::new(0.2, 0.2, 0.25),
                    lights: if k % 2 == 0 {
                        vec![point]
                    } else {
                        vec![point, directional]
                    },
                    material: Material {
                        shininess,
                        ..Material::default()
                    },
                    eye: Vec3::new(0.3, 0.5, 4.0),
                    specular,
                });
            }
        }
        out
    }

    struct Compare<'a> {
        lighting: &'a Lighting,
        specular: bool,
    }

    impl Kernel for Compare<'_> {
        type Output = ();
        fn run<S: Simd>(self, s: S) {
            let surface = Surface::of(self.lighting);
            let lights: Vec<LaneLight> = (self.lighting.lights.iter())
                .map(|l| LaneLight::of(l, &self.lighting.material))
                .collect();
            let k = surface.lanes(Vf::splat(s, 0.0));
            let wide = surface.lanes(s.f16_load(&[0.0; 16]));
            for block in 0..16 {
                let values = |i: usize, f: &dyn Fn(f32) -> f32| -> [f32; 8] {
                    std::array::from_fn(|j| f((block * 8 + j) as f32 * 0.37 + i as f32))
                };
                let lane = |i: usize, f: &dyn Fn(f32) -> f32| Vf::load(s, &values(i, f));
                let n = [
                    lane(0, &f32::sin),
                    lane(1, &f32::cos),
                    lane(2, &|t| 0.5 + t.sin()),
                ];
                let p = [
                    lane(3, &|t| t.cos()),
                    lane(4, &|t| 0.3 * t.sin()),
                    lane(5, &|t| 0.1 * t),
                ];
                let [got] =
                    surface.radiance(&k, &lights, [unit_normal(n, 1.0)], [p], self.specular);
                // The same points twice in 16 lanes give the same bits.
                let twice = |v: Vf<S>| {
                    let mut both = [0.0; 16];
                    v.store((&mut both[..8]).try_into().unwrap());
                    v.store((&mut both[8..]).try_into().unwrap());
                    s.f16_load(&both)
                };
                let [wide_got] = surface.radiance(
                    &wide,
                    &lights,
                    [unit_normal(n.map(twice), 1.0)],
                    [p.map(twice)],
                    self.specular,
                );
                for c in 0..3 {
                    let (mut narrow, mut wide) = ([0f32; 8], [0f32; 16]);
                    got[c].store(&mut narrow);
                    wide_got[c].store_to(&mut wide);
                    let bits = |v: &[f32]| v.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
                    assert_eq!(bits(&wide[..8]), bits(&narrow), "channel {c}");
                    assert_eq!(bits(&wide[8..]), bits(&narrow), "channel {c}");
                }
                let (mut packed, mut wide_packed) = ([0; 8], [0; 16]);
                pack(got, &mut packed);
                pack(wide_got, &mut wide_packed);
                assert_eq!(
                    (&wide_packed[..8], &wide_packed[8..]),
                    (&packed[..], &packed[..])
                );
                let (mut nv, mut pv, mut gv) = ([[0.0; 8]; 3], [[0.0; 8]; 3], [[0.0; 8]; 3]);
                for c in 0..3 {
                    n[c].store(&mut nv[c]);
                    p[c].store(&mut pv[c]);
                    got[c].store(&mut gv[c]);
                }
                let terms = if self.specular {
                    Terms::Full
                } else {
                    Terms::AmbientDiffuse
                };
                for j in 0..8 {
                    let normal = Vec3::new(nv[0][j], nv[1][j], nv[2][j]).normalize();
                    let point = Vec3::new(pv[0][j], pv[1][j], pv[2][j]);
                    let want = self.lighting.eval(point, normal, terms).to_array();
                    for c in 0..3 {
                        let tolerance = 1e-4 * want[c].abs().max(1.0);
                        assert!(
                            (gv[c][j] - want[c]).abs() <= tolerance,
                            "lanes {} vs scalar {} (channel {c}, {:?})",
                            gv[c][j],
                            want[c],
                            self.lighting
                        );
                    }
                }
            }
        }
    }

    /// Whole powers of every cosine from 0 to 1 in steps of 2^-16 (and
    /// the floor's neighbours), on every level.
    struct Floor {
        p: u32,
    }

    impl Kernel for Floor {
        type Output = ();
        fn run<S: Simd>(self, s: S) {
            let lighting = Lighting {
                material: Material {
                    shininess: self.p as f32,
                    ..Material::default()
                },
                ..lightings().remove(0)
            };
            let surface = Surface::of(&lighting);
            assert_eq!(surface.power, Power::Whole(self.p));
            let floor = surface.floor;
            let mut cosines: Vec<f32> = (0..=1 << 16).map(|i| i as f32 / 65536.0).collect();
            cosines.extend([floor, f32::from_bits(floor.to_bits() + 1)]);
            cosines.extend([f32::from_bits(floor.to_bits() - 1), f32::MIN_POSITIVE]);
            for x in cosines.chunks(8) {
                let mut lanes = [0.0; 8];
                lanes[..x.len()].copy_from_slice(x);
                let [got] = surface.power([Vf::load(s, &lanes)]);
                let [plain] = pow_whole_groups([Vf::load(s, &lanes)], self.p);
                let (mut got_v, mut plain_v) = ([0f32; 8], [0f32; 8]);
                got.store(&mut got_v);
                plain.store(&mut plain_v);
                for j in 0..x.len() {
                    let (x, got, plain) = (lanes[j], got_v[j], plain_v[j]);
                    if x > floor {
                        // Above the floor: the same bits, and never subnormal.
                        assert_eq!(got.to_bits(), plain.to_bits(), "{x}^{}", self.p);
                        assert!(got.is_normal(), "{x}^{} = {got}", self.p);
                    } else {
                        // At or below it: 0, where the power was negligible.
                        assert_eq!(got, 0.0, "{x}^{}", self.p);
                        assert!(f64::from(plain) <= 1.01 * POWER_FLOOR, "{x}^{}", self.p);
                    }
                }
            }
        }
    }

    /// Cosines whose whole power would be subnormal (slow on Intel cores)
    /// or below 2^-100 give 0; all others the same bits as before.
    #[test]
    fn whole_powers_of_small_cosines_are_zero_never_subnormal() {
        for level in SimdLevel::supported() {
            for p in [1, 2, 3, 5, 7, 32, 100, 255, 1000, 1024] {
                dispatch(level, Floor { p });
            }
        }
    }

    /// The lanes model is the scalar one, the specification, within f32
    /// rounding, on every SIMD level this machine has.
    #[test]
    fn lanes_agree_with_the_scalar_model() {
        for level in SimdLevel::supported() {
            for lighting in &lightings() {
                for specular in [true, false] {
                    dispatch(level, Compare { lighting, specular });
                }
            }
        }
    }
}
