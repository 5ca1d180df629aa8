//! A large triangle's span, its blocks two at a time in 16 lanes
//! ([`Simd::F16`]), for the shaders that colour blocks as they go (flat,
//! Gouraud).
//!
//! Inside a large triangle nearly every pair of blocks lies wholly in the
//! span and passes the depth test whole. With AVX-512 such a pair is one
//! 512-bit vector per value: the depth test, Gouraud's 1/w and colours, the
//! conversion to bytes and the stores take one instruction for 16 pixels
//! where blocks of 8 took two (Intel's server cores run 512-bit
//! multiply-adds on two ports, as many per cycle as 256-bit ones). Other
//! backends get a [`crate::simd::Pair`] of their 8 lanes: the two blocks
//! side by side.
//!
//! Each lane gets the operations `shade_block` would give it: the columns
//! are exact integers in `f32`, the multiply-adds are the same, and the
//! AVX-512 reciprocal is estimated per half of 8 with the AVX2 instruction
//! (`simd/avx512.rs`). So the bytes are those of blocks of 8, which
//! `tests/tiled.rs` checks against every other level and rasterizer. A
//! pair that is not whole, partly outside the span or partly hidden, goes
//! to `shade_block` block by block, which redoes its depth test (nothing
//! was stored yet).

use super::walk::{interpolate_planes, shade_block, Fill, Row};
use crate::raster::tiled::setup::plane_count;
use crate::shade::{Shader, MAX_ATTRS};
use crate::simd::{Lanes, Simd, Vi};

/// Fills one row's span: columns `left..right` (image columns), whose
/// blocks of 8 start at column `x` (a multiple of 8, at most `left`; the
/// buffers' rows are a multiple of 16 long), with
/// the depths and colours from there in `depth` and `color` (whole blocks
/// up to `right`). Returns how many pixels passed the depth test.
#[inline(always)]
pub(super) fn fill_span<S: Simd, Sh: Shader>(
    s: S,
    f: &Fill<'_, S, Sh>,
    row: &Row,
    (x, left, right): (i32, i32, i32),
    depth: &mut [f32],
    color: &mut [i32],
) -> u32 {
    // A lone first block, so that the pairs start at a multiple of 16
    // columns: a cache line of the buffers (`depth_buffer.rs`).
    let head = if x % 16 == 0 { 0 } else { depth.len().min(8) };
    let (depth_head, depth) = depth.split_at_mut(head);
    let (color_head, color) = color.split_at_mut(head);
    let mut fragments = blocks(s, f, row, (x, left, right), depth_head, color_head);
    let x = x + head as i32;
    let x0 = f.t.x0;
    let ramp = s.f16_load(&std::array::from_fn(|i| i as f32));
    // Columns relative to the triangle's first, as the planes take them:
    // integers below 2^24, so the compares and steps are exact.
    let mut column = ramp + ramp.splat_like((x - x0) as f32);
    let from = ramp.splat_like((left - 1 - x0) as f32);
    let to = ramp.splat_like((right - x0) as f32);
    let sixteen = ramp.splat_like(16.0);
    let mut dx = [ramp; 2 + MAX_ATTRS];
    let mut at_row = [ramp; 2 + MAX_ATTRS];
    for j in 0..plane_count(Sh::ATTRS) {
        dx[j] = ramp.splat_like(f.planes[j].dx);
        at_row[j] = ramp.splat_like(row.values[j]);
    }
    let (depth_pairs, depth_rest) = depth.as_chunks_mut::<16>();
    let (color_pairs, color_rest) = color.as_chunks_mut::<16>();
    let mut x = x;
    for (depth, color) in depth_pairs.iter_mut().zip(color_pairs) {
        let inside = column.gt(from) & to.gt(column);
        let z = column.mul_add(dx[0], at_row[0]);
        // `stored > z` is the blocks' `z < stored`, NaN false in both.
        let pass = <S::F16 as Lanes>::mask_bits(inside & s.f16_load(depth).gt(z));
        if pass == 0xffff {
            z.store_to(depth);
            let attrs =
                interpolate_planes(f.interpolation, Sh::ATTRS, column, |j| dx[j], |j| at_row[j]);
            f.shader.shade_lanes(f.color, &attrs, color);
            fragments += 16;
        } else if pass != 0 {
            fragments += blocks(s, f, row, (x, left, right), depth, color);
        }
        column = column + sixteen;
        x += 16;
    }
    fragments + blocks(s, f, row, (x, left, right), depth_rest, color_rest)
}

/// As [`fill_span`], block by block with `shade_block`: a pair that is not
/// whole, or the last block of an odd count.
#[inline(always)]
fn blocks<S: Simd, Sh: Shader>(
    s: S,
    f: &Fill<'_, S, Sh>,
    row: &Row,
    (x, left, right): (i32, i32, i32),
    depth: &mut [f32],
    color: &mut [i32],
) -> u32 {
    let (from, to) = (Vi::splat(s, left - 1), Vi::splat(s, right));
    let depth = depth.as_chunks_mut::<8>().0;
    let color = color.as_chunks_mut::<8>().0;
    let mut fragments = 0;
    for (k, (depth, color)) in depth.iter_mut().zip(color).enumerate() {
        let x = x + 8 * k as i32;
        let lanes = Vi::ramp(s) + Vi::splat(s, x);
        let inside = lanes.gt(from) & to.gt(lanes);
        fragments += shade_block::<S, Sh, true>(s, f, inside, f.column(x), row, depth, color);
    }
    fragments
}
