//! What lights a scene and what it lights: lights (point and directional),
//! the material, and the specular term's kind. Plain data; the reflection
//! model that evaluates it is `shade/model.rs`.

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
