//! Scanline profiles: the intensity along a row (or any line) of the image
//! for flat, Gouraud and Phong shading and the exact surface, with its
//! derivative.
//!
//! The eye exaggerates a change of slope in intensity into a light or dark
//! stripe (Mach bands). Flat shading's profile is a staircase: jumps at
//! polygon edges. Gouraud's is continuous but piecewise linear (in screen
//! interpolation), so its derivative is a staircase: the kinks at the edges
//! are the bands seen on a Gouraud-shaded sphere. Phong's and the exact
//! surface's derivatives are continuous.
//!
//! Values come from the renderer itself through a probe of every pixel of
//! the line: the light each method computed before clamping and rounding,
//! so the plot shows the interpolation, not 8-bit steps. The intensity of
//! a colour is the mean of its clamped channels, in 0–255 units.

use shadelab_core::{probe, ProbeRequest, RenderError, RenderOptions, Rgb, Scene, Shading};

use crate::exact::{exact_pixel, Rays, Surface};
use crate::lighting_of;

/// Where to take the profile.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ProfileLine {
    /// A whole pixel row, left to right.
    Row(u32),
    /// A segment between two window points (pixels), sampled once per
    /// pixel along its longer axis.
    Segment {
        /// Start (x, y).
        from: (f64, f64),
        /// End (x, y).
        to: (f64, f64),
    },
}

impl ProfileLine {
    /// The pixels along the line, in order, each once, inside a `width` × `height` image.
    pub fn pixels(&self, width: u32, height: u32) -> Vec<(u32, u32)> {
        match *self {
            ProfileLine::Row(y) if y < height => (0..width).map(|x| (x, y)).collect(),
            ProfileLine::Row(_) => Vec::new(),
            ProfileLine::Segment { from, to } => {
                let (dx, dy) = (to.0 - from.0, to.1 - from.1);
                let steps = dx.abs().max(dy.abs()).ceil().clamp(1.0, 1e6) as u32;
                let mut out: Vec<(u32, u32)> = Vec::new();
                for k in 0..=steps {
                    let f = f64::from(k) / f64::from(steps);
                    let (x, y) = ((from.0 + dx * f).floor(), (from.1 + dy * f).floor());
                    if x < 0.0 || y < 0.0 || x >= f64::from(width) || y >= f64::from(height) {
                        continue;
                    }
                    let p = (x as u32, y as u32);
                    if out.last() != Some(&p) {
                        out.push(p);
                    }
                }
                out
            }
        }
    }
}

/// What a curve shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum CurveKind {
    /// A shading method, as rendered.
    Method(Shading),
    /// The exact surface.
    Exact,
}

/// Intensity along the line for one method or the exact surface.
#[derive(Debug, Clone, PartialEq)]
pub struct Curve {
    /// What it shows.
    pub kind: CurveKind,
    /// Per sample: the intensity (0–255, unrounded), or `None` where nothing is drawn.
    pub values: Vec<Option<f64>>,
    /// Per sample: the mesh polygon drawn there (methods only).
    pub faces: Vec<Option<usize>>,
    /// Per sample: which convex piece the scanline walk filled it from (the
    /// whole polygon, or one triangle of its fan), as a key equal for
    /// samples of the same piece (methods only).
    pub pieces: Vec<Option<u64>>,
    /// Per gap between samples `k` and `k + 1`: the intensity's change,
    /// where both are drawn.
    pub derivative: Vec<Option<f64>>,
}

impl Curve {
    fn new(
        kind: CurveKind,
        values: Vec<Option<f64>>,
        faces: Vec<Option<usize>>,
        pieces: Vec<Option<u64>>,
    ) -> Curve {
        let derivative = values
            .windows(2)
            .map(|w| match (w[0], w[1]) {
                (Some(a), Some(b)) => Some(b - a),
                _ => None,
            })
            .collect();
        Curve {
            kind,
            values,
            faces,
            pieces,
            derivative,
        }
    }

    /// Indices `k` where the line crosses an edge between samples `k` and
    /// `k + 1`: of a polygon, or of a fan triangle inside one.
    pub fn edges(&self) -> Vec<usize> {
        changes(&self.pieces)
    }

    /// Indices `k` where the mesh polygon changes between samples `k` and `k + 1`.
    pub fn polygon_edges(&self) -> Vec<usize> {
        changes(&self.faces)
    }
}

fn changes<T: PartialEq>(keys: &[Option<T>]) -> Vec<usize> {
    keys.windows(2)
        .enumerate()
        .filter(|(_, w)| w[0].is_some() && w[1].is_some() && w[0] != w[1])
        .map(|(k, _)| k)
        .collect()
}

/// A profile: the sampled pixels and a curve per method (and the exact surface).
#[derive(Debug, Clone, PartialEq)]
pub struct Profile {
    /// The pixels sampled, in order.
    pub pixels: Vec<(u32, u32)>,
    /// Flat, Gouraud, Phong, then the exact surface when one was given.
    pub curves: Vec<Curve>,
}

/// A key for the piece a span was walked on: its vertices' window positions.
fn piece_key(span: &shadelab_core::SpanRecord) -> u64 {
    use std::hash::{Hash, Hasher};
    let mut h = std::collections::hash_map::DefaultHasher::new();
    for v in &span.polygon {
        v.x.to_bits().hash(&mut h);
        v.y.to_bits().hash(&mut h);
    }
    h.finish()
}

/// The intensity of a light: mean of its channels clamped to 0–1, times 255.
pub fn intensity(lit: Rgb) -> f64 {
    let c = lit.clamped();
    (f64::from(c.r) + f64::from(c.g) + f64::from(c.b)) / 3.0 * 255.0
}

/// The profile of `scene` along `line`, for the three methods drawn with
/// `options` (by the scanline rasterizer) and, if given, the exact surface.
///
/// With a palette, a method's value is its palette colour's intensity.
///
/// # Errors
/// As [`shadelab_core::render`].
pub fn profile(
    scene: &Scene,
    options: &RenderOptions,
    line: ProfileLine,
    surface: Option<&Surface>,
) -> Result<Profile, RenderError> {
    let pixels = line.pixels(options.width, options.height);
    let mut curves = Vec::new();
    for shading in Shading::ALL {
        let records = probe(
            scene,
            &RenderOptions {
                shading,
                ..*options
            },
            ProbeRequest {
                pixels: &pixels,
                trace: true,
            },
        )?;
        let values = records
            .iter()
            .map(|r| {
                r.as_ref().map(|r| match options.palette {
                    Some(_) => intensity(r.color.to_rgb()),
                    None => intensity(r.lit),
                })
            })
            .collect();
        let faces = records.iter().map(|r| r.as_ref().map(|r| r.face)).collect();
        let pieces = records
            .iter()
            .map(|r| r.as_ref().and_then(|r| r.span.as_ref()).map(piece_key))
            .collect();
        curves.push(Curve::new(
            CurveKind::Method(shading),
            values,
            faces,
            pieces,
        ));
    }
    if let Some(surface) = surface {
        let rays = Rays::new(&scene.camera, options.width, options.height);
        let lighting = lighting_of(scene, options);
        let values = pixels
            .iter()
            .map(|&(x, y)| {
                exact_pixel(surface, &rays, &lighting, x, y).map(|(_, lit)| intensity(lit))
            })
            .collect();
        curves.push(Curve::new(
            CurveKind::Exact,
            values,
            vec![None; pixels.len()],
            vec![None; pixels.len()],
        ));
    }
    Ok(Profile { pixels, curves })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segments_visit_each_pixel_once_in_order() {
        let line = ProfileLine::Segment {
            from: (0.5, 0.5),
            to: (10.5, 5.5),
        };
        let px = line.pixels(20, 20);
        assert_eq!(px.first(), Some(&(0, 0)));
        assert_eq!(px.last(), Some(&(10, 5)));
        assert_eq!(px.len(), 11);
        for w in px.windows(2) {
            assert_eq!(w[1].0, w[0].0 + 1);
            assert!(w[1].1 - w[0].1 <= 1);
        }
        assert_eq!(
            ProfileLine::Row(3).pixels(4, 4),
            vec![(0, 3), (1, 3), (2, 3), (3, 3)]
        );
        assert!(ProfileLine::Row(4).pixels(4, 4).is_empty());
        let clipped = ProfileLine::Segment {
            from: (-5.0, 1.5),
            to: (30.0, 1.5),
        };
        assert_eq!(clipped.pixels(8, 4).len(), 8);
    }
}
