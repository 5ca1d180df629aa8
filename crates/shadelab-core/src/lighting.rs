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

impl Default for Material {
    fn default() -> Material {
        Material {
            ka: Rgb::new(1.0, 60.0 / 255.0, 60.0 / 255.0),
            kd: Rgb::new(1.0, 60.0 / 255.0, 60.0 / 255.0),
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

impl Specular {
    /// The lower-case name used in files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Specular::Phong => "phong",
            Specular::BlinnPhong => "blinn-phong",
        }
    }
}

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

impl Lighting {
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
