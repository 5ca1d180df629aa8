//! The inner loop: one band of image rows, its triangles, blocks of 8 pixels.
//!
//! A band owns a depth buffer and a packed-colour buffer for its rows, so
//! bands run in parallel with no sharing and the buffers stay in cache. For
//! each triangle binned to the band, in submission order, each row of its
//! bounding box is walked in blocks of 8 pixels aligned to multiples of 8:
//!
//! 1. coverage: the three edge functions in 8 × `i64` lanes, one add per
//!    block, a lane in when all three are ≥ 0 (the bias is in `c`);
//! 2. depth test "less" against the band's buffer, depth from its plane;
//! 3. shading, specialised per method by the [`Shader`] type parameter:
//!    flat writes a constant, Gouraud converts interpolated colours, Phong
//!    evaluates the reflection model in 8 lanes.
//!
//! Nothing here allocates. Everything is `#[inline(always)]` so that
//! [`crate::simd::dispatch`] compiles it for AVX2 and for the portable path.

use glam::Vec3;

use super::setup::{Plane, Triangle, BAND_ROWS};
use crate::lighting::{LightKind, Lighting};
use crate::raster::{Interpolation, SUBPIXEL_HALF, SUBPIXEL_ONE};
use crate::simd::{pow_unit, F32x8, I64x8, Mask8};

/// The most attributes a method interpolates (Phong: normal and position).
pub(crate) const MAX_ATTRS: usize = 6;

/// Per-method colouring of a block of fragments.
pub(crate) trait Shader: Sync {
    /// How many attributes the method interpolates.
    const ATTRS: usize;
    /// Colours of 8 fragments, packed `r | g << 8 | b << 16`.
    fn shade(&self, triangle: &Triangle, attrs: &[F32x8; MAX_ATTRS]) -> [i32; 8];
}

/// Flat shading: the triangle's polygon was lit once, at setup.
pub(crate) struct FlatShader;

impl Shader for FlatShader {
    const ATTRS: usize = 0;
    #[inline(always)]
    fn shade(&self, triangle: &Triangle, _: &[F32x8; MAX_ATTRS]) -> [i32; 8] {
        [triangle.color as i32; 8]
    }
}

/// Gouraud shading: the vertex colours, interpolated.
pub(crate) struct GouraudShader;

impl Shader for GouraudShader {
    const ATTRS: usize = 3;
    #[inline(always)]
    fn shade(&self, _: &Triangle, a: &[F32x8; MAX_ATTRS]) -> [i32; 8] {
        pack(a[0], a[1], a[2])
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
pub(crate) struct PhongShader {
    ambient: [f32; 3],
    eye: Vec3,
    lights: Vec<LaneLight>,
    shininess: f32,
}

impl PhongShader {
    pub fn new(lighting: &Lighting) -> PhongShader {
        let m = &lighting.material;
        let lights = lighting
            .lights
            .iter()
            .map(|light| {
                let i = light.color * light.intensity;
                let (position, towards) = match light.kind {
                    LightKind::Point { position } => (Some(position), Vec3::ZERO),
                    LightKind::Directional { direction } => {
                        (None, (-direction).normalize_or_zero())
                    }
                };
                LaneLight {
                    position,
                    towards,
                    diffuse: (i * m.kd).to_array(),
                    specular: (i * m.ks).to_array(),
                }
            })
            .collect();
        PhongShader {
            ambient: (lighting.ambient * m.ka).to_array(),
            eye: lighting.eye,
            lights,
            shininess: m.shininess,
        }
    }

    #[inline(always)]
    fn power(&self, x: F32x8) -> F32x8 {
        let p = self.shininess;
        if p > 0.0 && p <= 4096.0 {
            pow_unit(x, p)
        } else {
            F32x8(x.0.map(|v| v.powf(p)))
        }
    }
}

/// `v / |v|`, or zero where `|v|` is zero or not finite (glam's `normalize_or_zero`).
#[inline(always)]
fn normalize_or_zero(v: [F32x8; 3]) -> [F32x8; 3] {
    let len2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    let recip = F32x8::splat(1.0).div(len2.sqrt());
    let ok = recip.gt(F32x8::splat(0.0)) & recip.lt(F32x8::splat(f32::INFINITY));
    let scale = F32x8::select(ok, recip, F32x8::splat(0.0));
    v.map(|c| c * scale)
}

impl Shader for PhongShader {
    const ATTRS: usize = 6;
    #[inline(always)]
    fn shade(&self, triangle: &Triangle, a: &[F32x8; MAX_ATTRS]) -> [i32; 8] {
        let n = normalize_or_zero([a[0], a[1], a[2]].map(|c| c * triangle.flip));
        let p = [a[3], a[4], a[5]];
        let eye = self.eye.to_array();
        let view = normalize_or_zero([0, 1, 2].map(|k| F32x8::splat(eye[k]) - p[k]));
        let mut out = self.ambient.map(F32x8::splat);
        let zero = F32x8::splat(0.0);
        for light in &self.lights {
            let l = match light.position {
                Some(q) => {
                    let q = q.to_array();
                    normalize_or_zero([0, 1, 2].map(|k| F32x8::splat(q[k]) - p[k]))
                }
                None => light.towards.to_array().map(F32x8::splat),
            };
            let n_dot_l = n[0] * l[0] + n[1] * l[1] + n[2] * l[2];
            let lit = n_dot_l.gt(zero);
            let twice = n_dot_l * 2.0;
            let r = [0, 1, 2].map(|k| n[k] * twice - l[k]);
            let r_dot_v = (r[0] * view[0] + r[1] * view[1] + r[2] * view[2]).max(zero);
            let s = self.power(r_dot_v);
            for k in 0..3 {
                let add =
                    F32x8::splat(light.diffuse[k]) * n_dot_l + F32x8::splat(light.specular[k]) * s;
                out[k] = out[k] + F32x8::select(lit, add, zero);
            }
        }
        pack(out[0], out[1], out[2])
    }
}

/// Colours in [0, 1] (clamped) to packed bytes, rounding as [`crate::Rgb8::from_rgb`].
#[inline(always)]
fn pack(r: F32x8, g: F32x8, b: F32x8) -> [i32; 8] {
    let byte = |c: F32x8| {
        (c.max(F32x8::splat(0.0)).min(F32x8::splat(1.0)) * 255.0 + F32x8::splat(0.5))
            .to_i32_truncated()
    };
    let (r, g, b) = (byte(r), byte(g), byte(b));
    let mut out = [0; 8];
    for i in 0..8 {
        out[i] = r[i] | (g[i] << 8) | (b[i] << 16);
    }
    out
}

/// A band's working storage, kept between frames.
#[derive(Debug, Default)]
pub(crate) struct Band {
    /// Row stride of the buffers: the image width rounded up to 8.
    stride: usize,
    depth: Vec<f32>,
    color: Vec<i32>,
    /// Coverage counts (coverage pass only).
    pub counts: Vec<u32>,
    /// Polygon stamps for self-crossing polygons, cleared when first used in a frame.
    stamp: Vec<u32>,
    stamp_clean: bool,
    /// Fragments that passed the depth test this frame.
    pub fragments: u64,
    /// Pixels drawn this frame.
    pub covered: u64,
}

/// What a band pass does with covered pixels.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Pass {
    /// Depth-test, shade and write.
    Shade,
    /// Count fragments per pixel, no depth test.
    Count,
}

impl Band {
    /// Prepares the buffers for a frame of `width` pixels per row.
    pub fn begin(&mut self, width: u32, rows: u32, background: i32, pass: Pass) {
        self.stride = (width as usize).next_multiple_of(8);
        let len = self.stride * rows as usize;
        self.fragments = 0;
        self.covered = 0;
        self.stamp_clean = false;
        match pass {
            Pass::Shade => {
                self.depth.clear();
                self.depth.resize(len, 1.0);
                self.color.clear();
                self.color.resize(len, background);
            }
            Pass::Count => {
                self.counts.clear();
                self.counts.resize(len, 0);
            }
        }
    }

    /// Copies the finished band into its rows of the image and counts the
    /// pixels drawn.
    pub fn finish(&mut self, out: &mut [crate::color::Rgb8], width: u32) {
        let width = width as usize;
        let mut covered = 0;
        for (row, pixels) in out.chunks_mut(width).enumerate() {
            let start = row * self.stride;
            let colors = &self.color[start..start + width];
            let depths = &self.depth[start..start + width];
            for ((pixel, &c), &d) in pixels.iter_mut().zip(colors).zip(depths) {
                *pixel = crate::color::Rgb8([c as u8, (c >> 8) as u8, (c >> 16) as u8]);
                covered += u64::from(d < 1.0);
            }
        }
        self.covered = covered;
    }

    /// Copies coverage counts into their rows of `out`.
    pub fn finish_counts(&self, out: &mut [u32], width: u32) {
        let width = width as usize;
        for (row, counts) in out.chunks_mut(width).enumerate() {
            let start = row * self.stride;
            counts.copy_from_slice(&self.counts[start..start + width]);
        }
    }

    fn stamps(&mut self) -> &mut [u32] {
        if !self.stamp_clean {
            self.stamp.clear();
            self.stamp
                .resize(self.depth.len().max(self.counts.len()), 0);
            self.stamp_clean = true;
        }
        &mut self.stamp
    }

    /// Draws one triangle's rows within this band (rows `band_y0..band_y1`
    /// of an image `width` pixels wide).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub fn draw<S: Shader>(
        &mut self,
        t: &Triangle,
        planes: &[Plane],
        shader: &S,
        interpolation: Interpolation,
        band_y0: u32,
        band_y1: u32,
        width: u32,
        pass: Pass,
    ) {
        let rows = (t.y0.max(band_y0 as i32))..(t.y1.min(band_y1 as i32));
        let first_block = t.x0 & !7;
        let block_count = (t.x1 - first_block + 7) / 8;
        let lane_step: [i64; 3] = [0, 1, 2].map(|i| t.a[i] * SUBPIXEL_ONE);
        let lane_offsets = lane_step.map(|s| I64x8::ramp(0, s));
        let block_step = lane_step.map(|s| s * 8);
        let x_start = i64::from(first_block) * SUBPIXEL_ONE + SUBPIXEL_HALF;
        let width_mask_from = i64::from(width) - 8;
        let plane_count = 2 + S::ATTRS;
        let lanes_x = F32x8::LANE_INDEX + F32x8::splat((first_block - t.x0) as f32);

        for y in rows {
            let y_centre = i64::from(y) * SUBPIXEL_ONE + SUBPIXEL_HALF;
            let mut e: [i64; 3] = [0, 1, 2].map(|i| t.a[i] * x_start + t.b[i] * y_centre + t.c[i]);
            let dy = (y - t.y0) as f32;
            let mut row_value = [0f32; 2 + MAX_ATTRS];
            for j in 0..plane_count {
                row_value[j] = planes[j].at_origin + planes[j].dy * dy;
            }
            let row_start = (y as u32 - band_y0) as usize * self.stride;
            for block in 0..block_count {
                let mut mask = I64x8::all_non_negative(
                    lane_offsets[0].add_scalar(e[0]),
                    lane_offsets[1].add_scalar(e[1]),
                    lane_offsets[2].add_scalar(e[2]),
                );
                for i in 0..3 {
                    e[i] += block_step[i];
                }
                let bx = first_block + block * 8;
                if i64::from(bx) > width_mask_from {
                    mask = mask & Mask8::first(i64::from(width) - i64::from(bx));
                }
                if !mask.any() {
                    continue;
                }
                let at = row_start + bx as usize;
                if t.once != 0 {
                    mask = self.once_per_pixel(mask, at, t.once);
                }
                if pass == Pass::Count {
                    for (i, count) in self.counts[at..at + 8].iter_mut().enumerate() {
                        *count += (mask.0[i] as u32) >> 31;
                    }
                    continue;
                }
                let x = lanes_x + F32x8::splat((block * 8) as f32);
                let value = |j: usize| F32x8::splat(row_value[j]) + x * planes[j].dx;
                let depth = value(0);
                let stored = F32x8::load(&self.depth[at..at + 8]);
                let pass_mask = mask & depth.lt(stored);
                if !pass_mask.any() {
                    continue;
                }
                F32x8::select(pass_mask, depth, stored).store(&mut self.depth[at..at + 8]);
                self.fragments += u64::from(pass_mask.bits().count_ones());

                let mut attrs = [F32x8::splat(0.0); MAX_ATTRS];
                match interpolation {
                    Interpolation::Perspective if S::ATTRS > 0 => {
                        let w = F32x8::splat(1.0).div(value(1));
                        for (k, attr) in attrs.iter_mut().enumerate().take(S::ATTRS) {
                            *attr = value(2 + k) * w;
                        }
                    }
                    _ => {
                        for (k, attr) in attrs.iter_mut().enumerate().take(S::ATTRS) {
                            *attr = value(2 + k);
                        }
                    }
                }
                let colors = shader.shade(t, &attrs);
                let old = &mut self.color[at..at + 8];
                for i in 0..8 {
                    old[i] = (colors[i] & pass_mask.0[i]) | (old[i] & !pass_mask.0[i]);
                }
            }
        }
    }

    /// Drops the lanes a self-crossing polygon already drew, and marks the rest.
    #[cold]
    fn once_per_pixel(&mut self, mask: Mask8, at: usize, polygon: u32) -> Mask8 {
        let stamps = self.stamps();
        let mut out = mask;
        for i in 0..8 {
            if mask.0[i] != 0 {
                if stamps[at + i] == polygon {
                    out.0[i] = 0;
                } else {
                    stamps[at + i] = polygon;
                }
            }
        }
        out
    }
}

/// Rows `y0..y1` of the image: the band with index `band`.
pub(crate) fn band_rows(band: usize, height: u32) -> (u32, u32) {
    let y0 = band as u32 * BAND_ROWS;
    (y0, (y0 + BAND_ROWS).min(height))
}
