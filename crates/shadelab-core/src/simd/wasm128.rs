//! The WebAssembly SIMD backend: each 8-lane operation as two 128-bit
//! `simd128` instructions.
//!
//! Compiled only when the module is built with `-C target-feature=+simd128`
//! (as `build.rs` builds the viewer's), so every browser that loads the
//! module runs these instructions; there is nothing to detect at run time.
//! The portable backend, which LLVM vectorizes only in part (its selects,
//! lane masks, packing of colours and compress become scalar code), stays
//! the reference: this one computes the same IEEE single-precision results
//! lane for lane (exact division and square root, no fused multiply-add),
//! so both give identical pixels.

use std::arch::wasm32::*;

use super::portable::{COMPRESS, ROTATE};
use super::{Pair, Simd, Vf};

/// The `simd128` backend (WebAssembly built with `+simd128` only).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Wasm128;

/// Per lane mask and output half, the byte indices that gather the mask's
/// lanes (`COMPRESS`) from the low half (`[.][h][0]`) and the high half
/// (`[.][h][1]`) of an 8-lane vector; an index of 0xff picks zero, so the
/// two gathers are ORed.
const COMPRESS_BYTES: [[[[u8; 16]; 2]; 2]; 256] = byte_orders(&COMPRESS);

/// As `COMPRESS_BYTES`, for each shift of [`Simd::i_rotate`] (`ROTATE`).
const ROTATE_BYTES: [[[[u8; 16]; 2]; 2]; 8] = byte_orders(&ROTATE);

/// Lane permutations (`orders[k][lane]` is the source lane) as the byte
/// indices of two swizzles per output half (see `COMPRESS_BYTES`).
const fn byte_orders<const N: usize>(orders: &[[i32; 8]; N]) -> [[[[u8; 16]; 2]; 2]; N] {
    let mut table = [[[[0xffu8; 16]; 2]; 2]; N];
    let mut k = 0;
    while k < N {
        let mut lane = 0;
        while lane < 8 {
            let source = orders[k][lane] as usize;
            let (half, slot) = (lane / 4, lane % 4);
            let (from, within) = (source / 4, source % 4);
            let mut byte = 0;
            while byte < 4 {
                table[k][half][from][4 * slot + byte] = (4 * within + byte) as u8;
                byte += 1;
            }
            lane += 1;
        }
        k += 1;
    }
    table
}

/// `v`'s lanes gathered as `table` says (see `COMPRESS_BYTES`).
#[inline(always)]
fn gather_lanes(v: [v128; 2], table: &[[[u8; 16]; 2]; 2]) -> [v128; 2] {
    let gather = |half: &[[u8; 16]; 2]| {
        let from_low = u8x16_swizzle(v[0], bytes(&half[0]));
        let from_high = u8x16_swizzle(v[1], bytes(&half[1]));
        v128_or(from_low, from_high)
    };
    [gather(&table[0]), gather(&table[1])]
}

/// Applies a 4-lane operation to both halves (a macro, not a function
/// taking a closure: the intrinsics are `target_feature` functions, which
/// are not `Fn`).
macro_rules! each {
    ($a:expr, $op:expr) => {{
        let a = $a;
        [$op(a[0]), $op(a[1])]
    }};
}

/// Applies a 4-lane operation to both halves of two operands.
macro_rules! pair {
    ($a:expr, $b:expr, $op:expr) => {{
        let (a, b) = ($a, $b);
        [$op(a[0], b[0]), $op(a[1], b[1])]
    }};
}

impl Simd for Wasm128 {
    type F = [v128; 2];
    type I = [v128; 2];

    type F16 = Pair<Vf<Self>>;
    #[inline(always)]
    fn f16_load(self, src: &[f32; 16]) -> Pair<Vf<Self>> {
        Pair::load(self, src)
    }

    #[inline(always)]
    fn f_splat(self, v: f32) -> [v128; 2] {
        [f32x4_splat(v); 2]
    }
    #[inline(always)]
    fn f_add(self, a: [v128; 2], b: [v128; 2]) -> [v128; 2] {
        pair!(a, b, f32x4_add)
    }
    #[inline(always)]
    fn f_sub(self, a: [v128; 2], b: [v128; 2]) -> [v128; 2] {
        pair!(a, b, f32x4_sub)
    }
    #[inline(always)]
    fn f_mul(self, a: [v128; 2], b: [v128; 2]) -> [v128; 2] {
        pair!(a, b, f32x4_mul)
    }
    #[inline(always)]
    fn f_mul_add(self, a: [v128; 2], b: [v128; 2], c: [v128; 2]) -> [v128; 2] {
        // Two roundings, as the portable backend (simd128 has no fused form).
        self.f_add(self.f_mul(a, b), c)
    }
    #[inline(always)]
    fn f_min(self, a: [v128; 2], b: [v128; 2]) -> [v128; 2] {
        // pmin(x, y) is `y < x ? y : x`: with (b, a), `a < b ? a : b`.
        pair!(a, b, |a, b| f32x4_pmin(b, a))
    }
    #[inline(always)]
    fn f_max(self, a: [v128; 2], b: [v128; 2]) -> [v128; 2] {
        // pmax(x, y) is `x < y ? y : x`: with (b, a), `a > b ? a : b`.
        pair!(a, b, |a, b| f32x4_pmax(b, a))
    }
    #[inline(always)]
    fn f_rsqrt(self, a: [v128; 2]) -> [v128; 2] {
        let one = f32x4_splat(1.0);
        each!(a, |a| f32x4_div(one, f32x4_sqrt(a)))
    }
    #[inline(always)]
    fn f_recip(self, a: [v128; 2]) -> [v128; 2] {
        let one = f32x4_splat(1.0);
        each!(a, |a| f32x4_div(one, a))
    }
    #[inline(always)]
    fn f_floor(self, a: [v128; 2]) -> [v128; 2] {
        each!(a, f32x4_floor)
    }
    #[inline(always)]
    fn f_lt(self, a: [v128; 2], b: [v128; 2]) -> [v128; 2] {
        pair!(a, b, f32x4_lt)
    }
    #[inline(always)]
    fn f_gt(self, a: [v128; 2], b: [v128; 2]) -> [v128; 2] {
        pair!(a, b, f32x4_gt)
    }
    #[inline(always)]
    fn f_select(self, m: [v128; 2], a: [v128; 2], b: [v128; 2]) -> [v128; 2] {
        // Masks are all ones or zero per lane, so a bitwise select is a lane select.
        [
            v128_bitselect(a[0], b[0], m[0]),
            v128_bitselect(a[1], b[1], m[1]),
        ]
    }
    #[inline(always)]
    fn f_load(self, src: &[f32; 8]) -> [v128; 2] {
        let p = src.as_ptr();
        // SAFETY: `src` holds 8 f32 (32 bytes): the loads read bytes 0..16
        // and 16..32 of it; `v128_load` has no alignment requirement.
        unsafe { [v128_load(p.cast()), v128_load(p.add(4).cast())] }
    }
    #[inline(always)]
    fn f_store(self, v: [v128; 2], dst: &mut [f32; 8]) {
        let p = dst.as_mut_ptr();
        // SAFETY: `dst` holds 8 f32 (32 bytes), borrowed mutably: the
        // stores write bytes 0..16 and 16..32 of it, unaligned allowed.
        unsafe {
            v128_store(p.cast(), v[0]);
            v128_store(p.add(4).cast(), v[1]);
        }
    }
    #[inline(always)]
    fn f_to_i(self, a: [v128; 2]) -> [v128; 2] {
        // Saturating, NaN to 0: Rust's `as i32`, which the portable backend uses.
        each!(a, i32x4_trunc_sat_f32x4)
    }
    #[inline(always)]
    fn f_bits(self, a: [v128; 2]) -> [v128; 2] {
        a
    }
    #[inline(always)]
    fn f_from_i(self, a: [v128; 2]) -> [v128; 2] {
        each!(a, f32x4_convert_i32x4)
    }
    #[inline(always)]
    fn f_from_bits(self, a: [v128; 2]) -> [v128; 2] {
        a
    }
    #[inline(always)]
    fn f_lanes(self) -> [v128; 2] {
        [f32x4(0.0, 1.0, 2.0, 3.0), f32x4(4.0, 5.0, 6.0, 7.0)]
    }

    #[inline(always)]
    fn i_splat(self, v: i32) -> [v128; 2] {
        [i32x4_splat(v); 2]
    }
    #[inline(always)]
    fn i_add(self, a: [v128; 2], b: [v128; 2]) -> [v128; 2] {
        pair!(a, b, i32x4_add)
    }
    #[inline(always)]
    fn i_sub(self, a: [v128; 2], b: [v128; 2]) -> [v128; 2] {
        pair!(a, b, i32x4_sub)
    }
    #[inline(always)]
    fn i_and(self, a: [v128; 2], b: [v128; 2]) -> [v128; 2] {
        pair!(a, b, v128_and)
    }
    #[inline(always)]
    fn i_or(self, a: [v128; 2], b: [v128; 2]) -> [v128; 2] {
        pair!(a, b, v128_or)
    }
    #[inline(always)]
    fn i_max(self, a: [v128; 2], b: [v128; 2]) -> [v128; 2] {
        pair!(a, b, i32x4_max)
    }
    #[inline(always)]
    fn i_mul(self, a: [v128; 2], b: [v128; 2]) -> [v128; 2] {
        pair!(a, b, i32x4_mul)
    }
    #[inline(always)]
    fn i_gt(self, a: [v128; 2], b: [v128; 2]) -> [v128; 2] {
        pair!(a, b, i32x4_gt)
    }
    #[inline(always)]
    fn i_lanes(self) -> [v128; 2] {
        [i32x4(0, 1, 2, 3), i32x4(4, 5, 6, 7)]
    }
    #[inline(always)]
    fn i_shl(self, a: [v128; 2], bits: u32) -> [v128; 2] {
        each!(a, |a| i32x4_shl(a, bits))
    }
    #[inline(always)]
    fn i_sra(self, a: [v128; 2], bits: u32) -> [v128; 2] {
        each!(a, |a| i32x4_shr(a, bits))
    }
    #[inline(always)]
    fn i_select(self, m: [v128; 2], a: [v128; 2], b: [v128; 2]) -> [v128; 2] {
        [
            v128_bitselect(a[0], b[0], m[0]),
            v128_bitselect(a[1], b[1], m[1]),
        ]
    }
    #[inline(always)]
    fn i_load(self, src: &[i32; 8]) -> [v128; 2] {
        let p = src.as_ptr();
        // SAFETY: as `f_load`: 32 readable bytes, no alignment needed.
        unsafe { [v128_load(p.cast()), v128_load(p.add(4).cast())] }
    }
    #[inline(always)]
    fn i_store(self, v: [v128; 2], dst: &mut [i32; 8]) {
        let p = dst.as_mut_ptr();
        // SAFETY: as `f_store`: 32 writable bytes, no alignment needed.
        unsafe {
            v128_store(p.cast(), v[0]);
            v128_store(p.add(4).cast(), v[1]);
        }
    }
    #[inline(always)]
    fn i_bits(self, a: [v128; 2]) -> u32 {
        u32::from(i32x4_bitmask(a[0])) | u32::from(i32x4_bitmask(a[1])) << 4
    }
    #[inline(always)]
    fn i_from_bits(self, bits: u32) -> [v128; 2] {
        let all = i32x4_splat(bits as i32);
        let low = i32x4(1, 2, 4, 8);
        let high = i32x4(16, 32, 64, 128);
        [
            i32x4_eq(v128_and(all, low), low),
            i32x4_eq(v128_and(all, high), high),
        ]
    }

    #[inline(always)]
    fn f_compress(self, v: [v128; 2], bits: u32) -> [v128; 2] {
        self.i_compress(v, bits)
    }
    #[inline(always)]
    fn i_compress(self, v: [v128; 2], bits: u32) -> [v128; 2] {
        gather_lanes(v, &COMPRESS_BYTES[bits as usize & 255])
    }
    #[inline(always)]
    fn i_rotate(self, v: [v128; 2], by: usize) -> [v128; 2] {
        gather_lanes(v, &ROTATE_BYTES[by & 7])
    }

    #[inline(always)]
    fn f_to_bytes(self, r: [v128; 2], g: [v128; 2], b: [v128; 2]) -> [v128; 2] {
        // Truncation saturates and takes NaN to 0, then 0..=255 by clamping:
        // Rust's `c as u8`, lane for lane.
        let (zero, top) = (i32x4_splat(0), i32x4_splat(255));
        let byte = |c: v128| i32x4_min(i32x4_max(i32x4_trunc_sat_f32x4(c), zero), top);
        let pack = |h: usize| {
            v128_or(
                byte(r[h]),
                v128_or(i32x4_shl(byte(g[h]), 8), i32x4_shl(byte(b[h]), 16)),
            )
        };
        [pack(0), pack(1)]
    }

    #[inline(always)]
    fn i_store_rgb(self, v: [v128; 2], dst: &mut [u8; 24]) {
        // Each half's four pixels as 12 bytes at the front of its vector.
        let compact = |x: v128| {
            u8x16_swizzle(
                x,
                u8x16(
                    0, 1, 2, 4, 5, 6, 8, 9, 10, 12, 13, 14, 0xff, 0xff, 0xff, 0xff,
                ),
            )
        };
        let (low, high) = (compact(v[0]), compact(v[1]));
        let p = dst.as_mut_ptr();
        // SAFETY: `dst` is 24 writable bytes: the stores write 0..16 (the
        // last 4 written again below), 12..20 and 20..24; none needs alignment.
        unsafe {
            v128_store(p.cast(), low);
            v128_store64_lane::<0>(high, p.add(12).cast());
            v128_store32_lane::<2>(high, p.add(20).cast());
        }
    }
}

/// Sixteen bytes as a vector.
#[inline(always)]
fn bytes(b: &[u8; 16]) -> v128 {
    // SAFETY: `b` is 16 readable bytes; `v128_load` needs no alignment.
    unsafe { v128_load(b.as_ptr().cast()) }
}
