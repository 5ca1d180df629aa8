//! Error maps: how far each method's pixels are from the exact surface's.
//!
//! A pixel's error is the mean over R, G, B of `|drawn − 255·clamp(exact)|`,
//! in 0–255 units, where both the mesh and the exact surface are seen.
//! Pixels seen by only one of them (the silhouettes differ: the mesh is
//! inscribed in the surface) are counted apart and left out of the mean.
//! The heat map shows the error on a fixed colour scale so panels compare.

use shadelab_core::{render, Image, RenderError, RenderOptions, Rgb8, Scene, Shading};

use crate::exact::{ExactImage, Surface};

/// Per-pixel error of one image against the exact surface.
#[derive(Debug, Clone, PartialEq)]
pub struct ErrorMap {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Row by row: the error where both are seen, else `None`.
    pub errors: Vec<Option<f32>>,
    /// Pixels where only the mesh is drawn.
    pub mesh_only: usize,
    /// Pixels where only the exact surface is seen.
    pub surface_only: usize,
    /// Pixels compared.
    pub compared: usize,
    /// Mean error over the compared pixels.
    pub mean: f64,
    /// Largest error, and where.
    pub max: f32,
    /// The pixel of the largest error.
    pub max_at: Option<(u32, u32)>,
}

impl ErrorMap {
    /// Compares `image` with `exact`; a pixel counts as drawn when it
    /// differs from `background` or `drawn` says so.
    pub fn new(image: &Image, exact: &ExactImage, drawn: &[bool]) -> ErrorMap {
        let (w, h) = (exact.width, exact.height);
        assert_eq!((image.width(), image.height()), (w, h), "image size");
        let mut errors = vec![None; (w * h) as usize];
        let (mut mesh_only, mut surface_only, mut compared) = (0, 0, 0);
        let (mut sum, mut max, mut max_at) = (0f64, 0f32, None);
        for (k, e) in errors.iter_mut().enumerate() {
            match (drawn[k], exact.pixels[k]) {
                (true, Some((_, lit))) => {
                    let want = lit.clamped().to_array().map(|c| c * 255.0);
                    let got = image.pixels()[k].0.map(f32::from);
                    let err = (0..3).map(|c| (got[c] - want[c]).abs()).sum::<f32>() / 3.0;
                    *e = Some(err);
                    compared += 1;
                    sum += f64::from(err);
                    if err > max || max_at.is_none() {
                        max = err;
                        max_at = Some((k as u32 % w, k as u32 / w));
                    }
                }
                (true, None) => mesh_only += 1,
                (false, Some(_)) => surface_only += 1,
                (false, None) => {}
            }
        }
        ErrorMap {
            width: w,
            height: h,
            errors,
            mesh_only,
            surface_only,
            compared,
            mean: if compared > 0 {
                sum / compared as f64
            } else {
                0.0
            },
            max,
            max_at,
        }
    }

    /// The error at pixel (`x`, `y`).
    pub fn at(&self, x: u32, y: u32) -> Option<f32> {
        self.errors[(y * self.width + x) as usize]
    }

    /// The map as a heat image: error 0 → dark, `scale_max` and above →
    /// bright ([`heat_color`]); pixels seen by one side only are grey,
    /// pixels seen by neither are `background`.
    pub fn heat_image(&self, scale_max: f32, exact: &ExactImage, background: Rgb8) -> Image {
        let mut image = Image::filled(self.width, self.height, background);
        for y in 0..self.height {
            for x in 0..self.width {
                let k = (y * self.width + x) as usize;
                let c = match self.errors[k] {
                    Some(e) => heat_color(e / scale_max.max(f32::MIN_POSITIVE)),
                    None if exact.pixels[k].is_some() => SILHOUETTE,
                    None => continue,
                };
                image.set_pixel(x, y, c);
            }
        }
        image
    }
}

/// The colour of pixels where only one of mesh and surface is seen.
pub const SILHOUETTE: Rgb8 = Rgb8::new(90, 90, 90);

/// The heat scale, from 0 (black) through purple, red and orange to 1
/// (pale yellow): monotone in brightness, readable on a projector.
pub fn heat_color(t: f32) -> Rgb8 {
    const STOPS: [[f32; 3]; 6] = [
        [0.0, 0.0, 4.0],
        [60.0, 15.0, 110.0],
        [150.0, 40.0, 100.0],
        [225.0, 80.0, 40.0],
        [250.0, 170.0, 20.0],
        [252.0, 255.0, 164.0],
    ];
    let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
    let x = t * (STOPS.len() - 1) as f32;
    let i = (x as usize).min(STOPS.len() - 2);
    let f = x - i as f32;
    let c = |k: usize| (STOPS[i][k] * (1.0 - f) + STOPS[i + 1][k] * f).round() as u8;
    Rgb8::new(c(0), c(1), c(2))
}

/// A vertical colour bar for [`heat_color`], top = 1, bottom = 0.
pub fn heat_bar(width: u32, height: u32) -> Image {
    let mut bar = Image::filled(width, height, Rgb8::default());
    for y in 0..height {
        let t = 1.0 - (y as f32 + 0.5) / height as f32;
        for x in 0..width {
            bar.set_pixel(x, y, heat_color(t));
        }
    }
    bar
}

/// The scale a heat map of errors up to `largest` uses: the smallest of 1,
/// 2, 2.5, 5 times a power of ten that is at least `largest` (1 for none).
pub fn heat_scale(largest: f32) -> f32 {
    if largest.is_nan() || largest <= 0.0 {
        return 1.0;
    }
    let p = 10f32.powf(largest.log10().floor());
    [1.0, 2.0, 2.5, 5.0, 10.0]
        .into_iter()
        .map(|m| m * p)
        .find(|&c| c >= largest)
        .unwrap_or(10.0 * p)
}

/// Which pixels of a render were drawn: those of `coverage` > 0.
pub fn drawn_mask(scene: &Scene, options: &RenderOptions) -> Result<Vec<bool>, RenderError> {
    Ok(shadelab_core::coverage(scene, options)?
        .into_iter()
        .map(|c| c > 0)
        .collect())
}

/// One method's render and its error map.
#[derive(Debug, Clone)]
pub struct MethodErrors {
    /// The method.
    pub shading: Shading,
    /// What it drew.
    pub image: Image,
    /// Its errors.
    pub map: ErrorMap,
}

/// Each of flat, Gouraud and Phong rendered with `options` and compared
/// with the exact surface; also returns the exact image.
///
/// # Errors
/// As [`render`].
pub fn error_maps(
    scene: &Scene,
    options: &RenderOptions,
    surface: &Surface,
) -> Result<(ExactImage, Vec<MethodErrors>), RenderError> {
    let exact = ExactImage::render(surface, scene, options);
    let drawn = drawn_mask(scene, options)?;
    let maps = Shading::ALL
        .into_iter()
        .map(|shading| {
            let (image, _) = render(
                scene,
                &RenderOptions {
                    shading,
                    ..*options
                },
            )?;
            let map = ErrorMap::new(&image, &exact, &drawn);
            Ok(MethodErrors {
                shading,
                image,
                map,
            })
        })
        .collect::<Result<Vec<_>, RenderError>>()?;
    Ok((exact, maps))
}

/// The exact image as pixels, `round(255·clamp(I))`, `background` elsewhere.
pub fn exact_image(exact: &ExactImage, background: Rgb8) -> Image {
    let mut image = Image::filled(exact.width, exact.height, background);
    for y in 0..exact.height {
        for x in 0..exact.width {
            if let Some(lit) = exact.lit(x, y) {
                image.set_pixel(x, y, Rgb8::from_rgb(lit));
            }
        }
    }
    image
}

/// One row of an accuracy table: the mean and largest error of each method
/// at one tessellation level.
#[derive(Debug, Clone, PartialEq)]
pub struct AccuracyRow {
    /// The model's detail.
    pub detail: u32,
    /// Polygons in the mesh.
    pub polygons: usize,
    /// Per method, in [`Shading::ALL`] order: (mean, max).
    pub errors: [(f64, f32); 3],
    /// Pixels compared (both seen).
    pub compared: usize,
}

/// The error of each method as the tessellation grows: for each detail,
/// `setup` gives the scene, the options and the exact surface.
///
/// # Errors
/// Whatever `setup` fails with, or a render error converted into it.
pub fn accuracy<E: From<RenderError>>(
    details: &[u32],
    mut setup: impl FnMut(u32) -> Result<(Scene, RenderOptions, Surface), E>,
) -> Result<Vec<AccuracyRow>, E> {
    details
        .iter()
        .map(|&detail| {
            let (scene, options, surface) = setup(detail)?;
            let (_, maps) = error_maps(&scene, &options, &surface)?;
            Ok(AccuracyRow {
                detail,
                polygons: scene.mesh.polygon_count(),
                errors: [0, 1, 2].map(|m| (maps[m].map.mean, maps[m].map.max)),
                compared: maps[0].map.compared,
            })
        })
        .collect()
}

/// Differences between two renders of the same frame, in 0–255 units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImageDiff {
    /// Largest difference of any channel.
    pub max: u8,
    /// Mean over pixels of the largest channel difference.
    pub mean: f64,
    /// Pixels that differ at all.
    pub differing: usize,
}

/// How `a` and `b` differ, pixel by pixel.
///
/// # Panics
/// If their sizes differ.
pub fn image_diff(a: &Image, b: &Image) -> ImageDiff {
    assert_eq!((a.width(), a.height()), (b.width(), b.height()));
    let mut max = 0u8;
    let mut sum = 0u64;
    let mut differing = 0;
    for (p, q) in a.pixels().iter().zip(b.pixels()) {
        let d = (0..3).map(|c| p.0[c].abs_diff(q.0[c])).max().unwrap_or(0);
        max = max.max(d);
        sum += u64::from(d);
        differing += usize::from(d > 0);
    }
    ImageDiff {
        max,
        mean: sum as f64 / a.pixels().len().max(1) as f64,
        differing,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn heat_scale_brightens_monotonically() {
        let lum =
            |c: Rgb8| 0.3 * f32::from(c.0[0]) + 0.59 * f32::from(c.0[1]) + 0.11 * f32::from(c.0[2]);
        let mut last = -1.0;
        for k in 0..=100 {
            let l = lum(heat_color(k as f32 / 100.0));
            assert!(l > last, "{k}");
            last = l;
        }
        assert_eq!(heat_color(-3.0), heat_color(0.0));
        assert_eq!(heat_color(9.0), heat_color(1.0));
        assert_eq!(heat_color(f32::NAN), heat_color(0.0));
    }

    #[test]
    fn heat_scales_are_round_numbers_above_the_largest_error() {
        for (largest, scale) in [
            (0.0, 1.0),
            (0.7, 1.0),
            (1.0, 1.0),
            (1.2, 2.0),
            (2.2, 2.5),
            (3.0, 5.0),
            (7.0, 10.0),
            (134.3, 200.0),
            (157.3, 200.0),
            (255.0, 500.0),
        ] {
            assert_eq!(heat_scale(largest), scale, "{largest}");
        }
    }
}
