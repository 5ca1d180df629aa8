//! The portable backend: arrays of 8, plain safe Rust.

use super::{Pair, Simd, Vf};

/// For each 8-bit mask, the indices of its set lanes in order, then zeros:
/// the permutation that packs the selected lanes to the front.
pub(super) const COMPRESS: [[i32; 8]; 256] = {
    let mut table = [[0i32; 8]; 256];
    let mut mask = 0;
    while mask < 256 {
        let (mut lane, mut k) = (0, 0);
        while lane < 8 {
            if (mask >> lane) & 1 == 1 {
                table[mask][k] = lane;
                k += 1;
            }
            lane += 1;
        }
        mask += 1;
    }
    table
};

/// For each shift `by` (0..8), the lanes that [`Simd::i_rotate`] reads:
/// lane `i` takes lane `(i − by) mod 8`.
pub(super) const ROTATE: [[i32; 8]; 8] = {
    let mut table = [[0i32; 8]; 8];
    let mut by = 0;
    while by < 8 {
        let mut lane = 0;
        while lane < 8 {
            table[by][lane] = ((lane + 8 - by) % 8) as i32;
            lane += 1;
        }
        by += 1;
    }
    table
};

/// The portable backend: arrays, one lane after the other.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Portable;

/// `[e(0), e(1), …, e(7)]`, written out rather than looped: inlined into
/// the rasterizer, the portable backend's every operation would otherwise
/// be a loop of its own, and LLVM's loop passes grow with the number of
/// loops times the size of the function (thousands of loops in one band
/// kernel made the crate take minutes to compile).
macro_rules! lanes {
    (|$i:ident| $e:expr) => {
        lanes!(@ $i, $e, 0 1 2 3 4 5 6 7)
    };
    (@ $i:ident, $e:expr, $($n:literal)*) => {
        [$({
            let $i = $n;
            $e
        }),*]
    };
}

impl Simd for Portable {
    type F = [f32; 8];
    type I = [i32; 8];

    type F16 = Pair<Vf<Self>>;
    #[inline(always)]
    fn f16_load(self, src: &[f32; 16]) -> Pair<Vf<Self>> {
        Pair::load(self, src)
    }

    #[inline(always)]
    fn f_splat(self, v: f32) -> [f32; 8] {
        [v; 8]
    }
    #[inline(always)]
    fn f_add(self, a: [f32; 8], b: [f32; 8]) -> [f32; 8] {
        lanes!(|i| a[i] + b[i])
    }
    #[inline(always)]
    fn f_sub(self, a: [f32; 8], b: [f32; 8]) -> [f32; 8] {
        lanes!(|i| a[i] - b[i])
    }
    #[inline(always)]
    fn f_mul(self, a: [f32; 8], b: [f32; 8]) -> [f32; 8] {
        lanes!(|i| a[i] * b[i])
    }
    #[inline(always)]
    fn f_mul_add(self, a: [f32; 8], b: [f32; 8], c: [f32; 8]) -> [f32; 8] {
        lanes!(|i| a[i] * b[i] + c[i])
    }
    #[inline(always)]
    fn f_min(self, a: [f32; 8], b: [f32; 8]) -> [f32; 8] {
        lanes!(|i| if a[i] < b[i] { a[i] } else { b[i] })
    }
    #[inline(always)]
    fn f_max(self, a: [f32; 8], b: [f32; 8]) -> [f32; 8] {
        lanes!(|i| if a[i] > b[i] { a[i] } else { b[i] })
    }
    #[inline(always)]
    fn f_rsqrt(self, a: [f32; 8]) -> [f32; 8] {
        lanes!(|i| 1.0 / a[i].sqrt())
    }
    #[inline(always)]
    fn f_recip(self, a: [f32; 8]) -> [f32; 8] {
        lanes!(|i| 1.0 / a[i])
    }
    #[inline(always)]
    fn f_floor(self, a: [f32; 8]) -> [f32; 8] {
        lanes!(|i| a[i].floor())
    }
    #[inline(always)]
    fn f_lt(self, a: [f32; 8], b: [f32; 8]) -> [i32; 8] {
        lanes!(|i| -i32::from(a[i] < b[i]))
    }
    #[inline(always)]
    fn f_gt(self, a: [f32; 8], b: [f32; 8]) -> [i32; 8] {
        lanes!(|i| -i32::from(a[i] > b[i]))
    }
    #[inline(always)]
    fn f_select(self, m: [i32; 8], a: [f32; 8], b: [f32; 8]) -> [f32; 8] {
        lanes!(|i| if m[i] < 0 { a[i] } else { b[i] })
    }
    #[inline(always)]
    fn f_load(self, src: &[f32; 8]) -> [f32; 8] {
        *src
    }
    #[inline(always)]
    fn f_store(self, v: [f32; 8], dst: &mut [f32; 8]) {
        *dst = v;
    }
    #[inline(always)]
    fn f_to_i(self, a: [f32; 8]) -> [i32; 8] {
        lanes!(|i| a[i] as i32)
    }
    #[inline(always)]
    fn f_bits(self, a: [f32; 8]) -> [i32; 8] {
        lanes!(|i| a[i].to_bits() as i32)
    }
    #[inline(always)]
    fn f_from_i(self, a: [i32; 8]) -> [f32; 8] {
        lanes!(|i| a[i] as f32)
    }
    #[inline(always)]
    fn f_from_bits(self, a: [i32; 8]) -> [f32; 8] {
        lanes!(|i| f32::from_bits(a[i] as u32))
    }
    #[inline(always)]
    fn f_lanes(self) -> [f32; 8] {
        [0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0]
    }

    #[inline(always)]
    fn i_splat(self, v: i32) -> [i32; 8] {
        [v; 8]
    }
    #[inline(always)]
    fn i_add(self, a: [i32; 8], b: [i32; 8]) -> [i32; 8] {
        lanes!(|i| a[i].wrapping_add(b[i]))
    }
    #[inline(always)]
    fn i_sub(self, a: [i32; 8], b: [i32; 8]) -> [i32; 8] {
        lanes!(|i| a[i].wrapping_sub(b[i]))
    }
    #[inline(always)]
    fn i_and(self, a: [i32; 8], b: [i32; 8]) -> [i32; 8] {
        lanes!(|i| a[i] & b[i])
    }
    #[inline(always)]
    fn i_or(self, a: [i32; 8], b: [i32; 8]) -> [i32; 8] {
        lanes!(|i| a[i] | b[i])
    }
    #[inline(always)]
    fn i_max(self, a: [i32; 8], b: [i32; 8]) -> [i32; 8] {
        lanes!(|i| a[i].max(b[i]))
    }
    #[inline(always)]
    fn i_mul(self, a: [i32; 8], b: [i32; 8]) -> [i32; 8] {
        lanes!(|i| a[i].wrapping_mul(b[i]))
    }
    #[inline(always)]
    fn i_gt(self, a: [i32; 8], b: [i32; 8]) -> [i32; 8] {
        lanes!(|i| -i32::from(a[i] > b[i]))
    }
    #[inline(always)]
    fn i_lanes(self) -> [i32; 8] {
        [0, 1, 2, 3, 4, 5, 6, 7]
    }
    #[inline(always)]
    fn i_shl(self, a: [i32; 8], bits: u32) -> [i32; 8] {
        lanes!(|i| a[i] << bits)
    }
    #[inline(always)]
    fn i_sra(self, a: [i32; 8], bits: u32) -> [i32; 8] {
        lanes!(|i| a[i] >> bits)
    }
    #[inline(always)]
    fn i_select(self, m: [i32; 8], a: [i32; 8], b: [i32; 8]) -> [i32; 8] {
        lanes!(|i| (a[i] & m[i]) | (b[i] & !m[i]))
    }
    #[inline(always)]
    fn i_load(self, src: &[i32; 8]) -> [i32; 8] {
        *src
    }
    #[inline(always)]
    fn i_store(self, v: [i32; 8], dst: &mut [i32; 8]) {
        *dst = v;
    }
    #[inline(always)]
    fn i_bits(self, a: [i32; 8]) -> u32 {
        (0..8).fold(0, |acc, i| acc | ((a[i] as u32) >> 31) << i)
    }
    #[inline(always)]
    fn i_from_bits(self, bits: u32) -> [i32; 8] {
        lanes!(|i| -(((bits >> i) & 1) as i32))
    }

    #[inline(always)]
    fn f_compress(self, v: [f32; 8], bits: u32) -> [f32; 8] {
        let order = &COMPRESS[bits as usize & 255];
        lanes!(|i| v[order[i] as usize])
    }
    #[inline(always)]
    fn i_compress(self, v: [i32; 8], bits: u32) -> [i32; 8] {
        let order = &COMPRESS[bits as usize & 255];
        lanes!(|i| v[order[i] as usize])
    }
    #[inline(always)]
    fn i_rotate(self, v: [i32; 8], by: usize) -> [i32; 8] {
        let order = &ROTATE[by & 7];
        lanes!(|i| v[order[i] as usize])
    }

    #[inline(always)]
    fn f_to_bytes(self, r: [f32; 8], g: [f32; 8], b: [f32; 8]) -> [i32; 8] {
        lanes!(|i| i32::from(r[i] as u8) | i32::from(g[i] as u8) << 8 | i32::from(b[i] as u8) << 16)
    }

    #[inline(always)]
    fn i_store_rgb(self, v: [i32; 8], dst: &mut [u8; 24]) {
        for (i, pixel) in dst.chunks_exact_mut(3).enumerate() {
            pixel.copy_from_slice(&v[i].to_le_bytes()[..3]);
        }
    }
}
