//! The Phong reflection model, evaluated in world space.
//!
//! `I = Ia·Ka + Σ [Id·Kd·max(0, n·l) + Is·Ks·max(0, r·v)^p]` per RGB channel,
//! with `l` towards the light, `v` towards the eye, `r = 2(n·l)n − l`, and the
//! specular term only where `n·l > 0`. This one function is what all three
//! shading methods call; they differ only in where and how often.
//!
//! Blinn's variant ([`Specular::BlinnPhong`]) replaces `r·v` with `n·h`,
//! `h = normalize(l + v)`: what OpenGL's fixed pipeline and most engines use.

use glam::Vec3;

use crate::color::Rgb;

/// Surface reflectances and the specular exponent.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    /// Ambient reflectance.
    pub ka: Rgb,
    /// Diffuse reflectance.
    pub kd: Rgb,
    /// Specular reflectance.
    pub ks: Rgb,
    /// Specular exponent `p`.
    pub shininess: f32,
}

/// The default material: a red of Ka = Kd = (200, 60, 60) with a white
/// specular term. Under the default lighting (ambient 0.2, one white light of
/// intensity 1) the brightest diffuse red is 0.2·200 + 200 = 240 < 255, so no
/// channel clips outside the specular highlight and the three methods'
/// differences show at first sight (a Kd red of 255 clipped over a large area).
impl Default for Material {
    fn default() -> Material {
        Material {
            ka: Rgb::new(200.0 / 255.0, 60.0 / 255.0, 60.0 / 255.0),
            kd: Rgb::new(200.0 / 255.0, 60.0 / 255.0, 60.0 / 255.0),
            ks: Rgb::WHITE,
            shininess: 32.0,
        }
    }
}

/// Where a light is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LightKind {
    /// A point light at a world position.
    Point {
        /// World position.
        position: Vec3,
    },
    /// A light at infinity whose rays travel along `direction`.
    Directional {
        /// The direction the light travels in (from the light to the scene).
        direction: Vec3,
    },
}

/// A light source; `Id = Is = color · intensity`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Light {
    /// Position or direction.
    pub kind: LightKind,
    /// Colour.
    pub color: Rgb,
    /// Intensity multiplying the colour.
    pub intensity: f32,
}

impl Light {
    /// The unit vector from `point` towards the light, or zero if undefined.
    pub fn direction_from(&self, point: Vec3) -> Vec3 {
        match self.kind {
            LightKind::Point { position } => (position - point).normalize_or_zero(),
            LightKind::Directional { direction } => (-direction).normalize_or_zero(),
        }
    }
}

/// The specular term's angle: Phong's reflection vector or Blinn's halfway vector.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Specular {
    /// `max(0, r·v)^p` with `r = 2(n·l)n − l` (Phong, 1975).
    #[default]
    Phong,
    /// `max(0, n·h)^p` with `h = normalize(l + v)` (Blinn, 1977).
    BlinnPhong,
}

choices!(Specular, "specular term", {
    Phong => "phong": "max(0, r·v)^p with r the mirrored light direction (Phong, 1975)",
    BlinnPhong => "blinn-phong": "max(0, n·h)^p with h halfway between light and eye (Blinn, 1977)",
});

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
    /// `Id = Is`: colour times intensity.
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

impl Lighting {
    /// The terms of the model at `point` with unit normal `normal`, summed in
    /// the same order as [`Lighting::eval`], so `total` equals its result exactly.
    pub fn explain(&self, point: Vec3, normal: Vec3, terms: Terms) -> LightingTerms {
        let m = &self.material;
        let ambient = self.ambient * m.ka;
        let mut out = ambient;
        let view = (self.eye - point).normalize_or_zero();
        let mut lights = Vec::with_capacity(self.lights.len());
        for light in &self.lights {
            let l = light.direction_from(point);
            let n_dot_l = normal.dot(l);
            let i = light.color * light.intensity;
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
            lights.push(term);
        }
        LightingTerms {
            view,
            ambient,
            lights,
            total: out,
        }
    }

    /// The reflected light at `point` with unit normal `normal`, unclamped.
    pub fn eval(&self, point: Vec3, normal: Vec3, terms: Terms) -> Rgb {
        let m = &self.material;
        let mut out = self.ambient * m.ka;
        let view = (self.eye - point).normalize_or_zero();
        for light in &self.lights {
            let l = light.direction_from(point);
            let n_dot_l = normal.dot(l);
            if n_dot_l <= 0.0 {
                continue;
            }
            let i = light.color * light.intensity;
            out += i * m.kd * n_dot_l;
            if terms == Terms::Full {
                let cosine = match self.specular {
                    Specular::Phong => (normal * (2.0 * n_dot_l) - l).dot(view),
                    Specular::BlinnPhong => normal.dot((l + view).normalize_or_zero()),
                };
                out += i * m.ks * cosine.max(0.0).powf(m.shininess);
            }
        }
        out
    }
}
