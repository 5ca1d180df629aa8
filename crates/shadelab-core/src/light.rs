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

/// A light source; `Id = Is = color · intensity / attenuation`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Light {
    /// Position or direction.
    pub kind: LightKind,
    /// Colour.
    pub color: Rgb,
    /// Intensity multiplying the colour.
    pub intensity: f32,
    /// A point light's fall-off with distance `d`, as OpenGL's fixed
    /// pipeline: its light is divided by `k[0] + k[1]·d + k[2]·d²`
    /// (constant, linear, quadratic). [`NO_ATTENUATION`], `[1, 0, 0]`, is
    /// none; directional lights have none.
    pub attenuation: [f32; 3],
}

/// No fall-off with distance: [`Light::attenuation`]'s default.
pub const NO_ATTENUATION: [f32; 3] = [1.0, 0.0, 0.0];

impl Light {
    /// What the light's colour and intensity are multiplied by at `point`:
    /// `1 / (k[0] + k[1]·d + k[2]·d²)` for a point light at distance `d`,
    /// exactly 1 without attenuation.
    pub fn attenuation_at(&self, point: Vec3) -> f32 {
        match self.kind {
            LightKind::Point { position } if self.attenuation != NO_ATTENUATION => {
                let [constant, linear, quadratic] = self.attenuation;
                let d = position.distance(point);
                1.0 / (constant + linear * d + quadratic * d * d)
            }
            _ => 1.0,
        }
    }

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

/// A light's kind as a scene names it (`kind` of `[[lights]]`); the
/// light itself, with its position or direction, is a [`LightKind`].
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash)]
pub enum LightKindName {
    /// At a position.
    #[default]
    Point,
    /// At infinity, along a direction.
    Directional,
}

choices!(LightKindName, "light kind", {
    Point => "point": "a light at a position, shining every way",
    Directional => "directional": "a light at infinity, its rays parallel along a direction",
});
