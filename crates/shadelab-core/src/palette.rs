//! The indexed-palette trick of 8-bit displays: a material owns `N`
//! consecutive entries of a 256-colour palette, shades of its colour from
//! black to full, and a pixel stores `offset + shade` with the shade chosen
//! by the light's intensity. Smooth shading then shows `N` bands.
//!
//! The material's colour is its diffuse reflectance `C = Kd`; entry
//! `offset + k` holds `C · k / (N − 1)`. The intensity of a lit colour `c` is
//! its projection on `C`, `I = (c · C) / (C · C)` (so `c = I·C` when the light
//! is white and `Ka = Kd`), and the shade is `k = min(N − 1, ⌊clamp(I, 0, 1)·N⌋)`.
//! The projection is linear, so projecting Gouraud's interpolated colour is
//! the classic interpolation of the index itself.

use crate::color::{Rgb, Rgb8};

/// A run of palette entries: `shades` shades of the material colour from `offset` on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Palette {
    /// How many shades (`N`), [`Palette::MIN_SHADES`]`..=`[`Palette::ENTRIES`].
    pub shades: u32,
    /// The first entry's index in the 256-entry palette.
    pub offset: u32,
}

/// What the palette made of one lit colour.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PaletteShade {
    /// The intensity `I = (c · C) / (C · C)`, unclamped.
    pub intensity: f32,
    /// The shade `k` in `0..N`.
    pub shade: u32,
    /// The palette entry, `offset + k`.
    pub index: u32,
    /// The entry's colour, `C · k / (N − 1)`.
    pub color: Rgb8,
}

impl Palette {
    /// Entries in the whole palette.
    pub const ENTRIES: u32 = 256;
    /// The fewest shades a run may have.
    pub const MIN_SHADES: u32 = 2;

    /// Whether the run fits the palette: `2 ≤ shades` and `offset + shades ≤ 256`.
    pub fn is_valid(self) -> bool {
        self.shades >= Self::MIN_SHADES && self.offset.saturating_add(self.shades) <= Self::ENTRIES
    }

    /// The intensity of lit colour `lit` relative to the material colour `base`.
    pub fn intensity(lit: Rgb, base: Rgb) -> f32 {
        let dot = |a: Rgb, b: Rgb| a.r * b.r + a.g * b.g + a.b * b.b;
        let norm = dot(base, base);
        if norm > 0.0 {
            dot(lit, base) / norm
        } else {
            0.0
        }
    }

    /// The colour of shade `k` (`0..shades`) of `base`.
    pub fn entry_color(self, k: u32, base: Rgb) -> Rgb8 {
        let top = (self.shades.max(2) - 1) as f32;
        Rgb8::from_rgb(base * (k.min(self.shades - 1) as f32 / top))
    }

    /// The shade and entry for lit colour `lit` of a material of colour `base`.
    pub fn shade(self, lit: Rgb, base: Rgb) -> PaletteShade {
        let intensity = Self::intensity(lit, base);
        let n = self.shades.max(1);
        // NaN clamps to 0 through `as`.
        let k = ((intensity.clamp(0.0, 1.0) * n as f32) as u32).min(n - 1);
        PaletteShade {
            intensity,
            shade: k,
            index: self.offset + k,
            color: self.entry_color(k, base),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn white_light_on_a_matching_material_projects_to_its_factor() {
        let base = Rgb::new(1.0, 60.0 / 255.0, 60.0 / 255.0);
        for f in [0.0f32, 0.2, 0.5, 0.99] {
            assert!((Palette::intensity(base * f, base) - f).abs() < 1e-6);
        }
    }

    #[test]
    fn shades_cover_the_run_and_saturate() {
        let p = Palette {
            shades: 4,
            offset: 32,
        };
        let base = Rgb::WHITE;
        let k = |i: f32| p.shade(Rgb::splat(i), base).shade;
        assert_eq!(
            [
                k(-1.0),
                k(0.0),
                k(0.24),
                k(0.25),
                k(0.5),
                k(0.99),
                k(1.0),
                k(7.0)
            ],
            [0, 0, 0, 1, 2, 3, 3, 3]
        );
        assert_eq!(p.shade(Rgb::splat(0.5), base).index, 34);
        assert_eq!(p.entry_color(0, base), Rgb8::new(0, 0, 0));
        assert_eq!(p.entry_color(3, base), Rgb8::new(255, 255, 255));
        assert_eq!(p.shade(Rgb::splat(f32::NAN), base).shade, 0);
        assert!(p.is_valid());
        assert!(!Palette {
            shades: 1,
            offset: 0
        }
        .is_valid());
        assert!(!Palette {
            shades: 200,
            offset: 100
        }
        .is_valid());
    }
}
