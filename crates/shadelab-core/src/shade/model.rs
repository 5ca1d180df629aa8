//! The Phong reflection model, evaluated in world space.
//!
//! `I = Ia·Ka + Σ [Id·Kd·max(0, n·l) + Is·Ks·max(0, r·v)^p]` per RGB channel,
//! with `l` towards the light, `v` towards the eye, `r = 2(n·l)n − l`, and the
//! specular term only where `n·l > 0`. A point light may fall off with its
//! distance `d`: its `Id = Is` divided by `k0 + k1·d + k2·d²`
//! ([`Light::attenuation`], none by default). This one function is what all
//! three shading methods call; they differ only in where and how often.
//!
//! Blinn's variant ([`Specular::BlinnPhong`]) replaces `r·v` with `n·h`,
//! `h = normalize(l + v)`: what OpenGL's fixed pipeline and most engines use.

use glam::Vec3;

use crate::color::Rgb;
use crate::light::{Light, Material, Specular};

/// Everything the reflection model needs besides the surface point.
#[derive(Debug, Clone, PartialEq)]
pub struct Lighting {
    /// Ambient colour times intensity: `Ia`.
    pub ambient: Rgb,
    /// The lights.
    pub lights: Vec<Light>,
    /// The surface.
    pub material: Material,
    /// The viewer's position, for `v`.
    pub eye: Vec3,
    /// Phong's `r·v` or Blinn's `n·h`.
    pub specular: Specular,
}

/// Which terms of the model to evaluate.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Terms {
    /// Ambient, diffuse and specular.
    Full,
    /// Ambient and diffuse only (classic Gouraud shading).
    AmbientDiffuse,
}

/// One light's part in [`Lighting::explain`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LightTerm {
    /// Unit vector towards the light.
    pub l: Vec3,
    /// `n·l`; the light adds nothing when it is not positive.
    pub n_dot_l: f32,
    /// `Id = Is`: colour times intensity, divided by the attenuation.
    pub intensity: Rgb,
    /// `Id·Kd·(n·l)`, zero when `n·l ≤ 0`.
    pub diffuse: Rgb,
    /// `r` (Phong) or `h` (Blinn), when the specular term was evaluated.
    pub reflected: Option<Vec3>,
    /// `r·v` or `n·h`, when the specular term was evaluated.
    pub cosine: Option<f32>,
    /// `Is·Ks·max(0, cosine)^p`, zero when not evaluated.
    pub specular: Rgb,
}

/// The reflection model's terms at one point: [`Lighting::eval`] spelled out.
#[derive(Debug, Clone, PartialEq)]
pub struct LightingTerms {
    /// Unit vector towards the eye, `v`.
    pub view: Vec3,
    /// `Ia·Ka`.
    pub ambient: Rgb,
    /// Each light's diffuse and specular parts.
    pub lights: Vec<LightTerm>,
    /// Their sum, unclamped: bit for bit what [`Lighting::eval`] returns.
    pub total: Rgb,
}

/// Where one evaluation's terms go: nowhere ([`Lighting::eval`], where the
/// compiler drops them) or into a list ([`Lighting::explain`]).
trait Record {
    fn light(&mut self, term: LightTerm);
}

impl Record for () {
    #[inline(always)]
    fn light(&mut self, _: LightTerm) {}
}

impl Record for Vec<LightTerm> {
    fn light(&mut self, term: LightTerm) {
        self.push(term);
    }
}

impl Lighting {
    /// The terms of the model at `point` with unit normal `normal`: the
    /// same evaluation as [`Lighting::eval`], so `total` equals its result
    /// exactly.
    pub fn explain(&self, point: Vec3, normal: Vec3, terms: Terms) -> LightingTerms {
        let mut lights = Vec::with_capacity(self.lights.len());
        let (ambient, view, total) = self.model(point, normal, terms, &mut lights);
        LightingTerms {
            view,
            ambient,
            lights,
            total,
        }
    }

    /// The reflected light at `point` with unit normal `normal`, unclamped.
    #[inline]
    pub fn eval(&self, point: Vec3, normal: Vec3, terms: Terms) -> Rgb {
        self.model(point, normal, terms, &mut ()).2
    }

    /// The model, the one scalar writing of it: returns `Ia·Ka`, the unit
    /// vector towards the eye and the total; each light's terms go to `record`.
    #[inline(always)]
    fn model(
        &self,
        point: Vec3,
        normal: Vec3,
        terms: Terms,
        record: &mut impl Record,
    ) -> (Rgb, Vec3, Rgb) {
        let m = &self.material;
        let ambient = self.ambient * m.ka;
        let mut out = ambient;
        let view = (self.eye - point).normalize_or_zero();
        for light in &self.lights {
            let l = light.direction_from(point);
            let n_dot_l = normal.dot(l);
            let i = light.color * (light.intensity * light.attenuation_at(point));
            let mut term = LightTerm {
                l,
                n_dot_l,
                intensity: i,
                diffuse: Rgb::BLACK,
                reflected: None,
                cosine: None,
                specular: Rgb::BLACK,
            };
            if n_dot_l > 0.0 {
                term.diffuse = i * m.kd * n_dot_l;
                out += term.diffuse;
                if terms == Terms::Full {
                    let (reflected, cosine) = match self.specular {
                        Specular::Phong => {
                            let r = normal * (2.0 * n_dot_l) - l;
                            (r, r.dot(view))
                        }
                        Specular::BlinnPhong => {
                            let h = (l + view).normalize_or_zero();
                            (h, normal.dot(h))
                        }
                    };
                    term.reflected = Some(reflected);
                    term.cosine = Some(cosine);
                    term.specular = i * m.ks * cosine.max(0.0).powf(m.shininess);
                    out += term.specular;
                }
            }
            record.light(term);
        }
        (ambient, view, out)
    }
}
