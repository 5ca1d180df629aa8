//! Sixteen lanes in one AVX-512 register, for lighting Phong's queued
//! fragments and for flat's and Gouraud's span blocks two at a time
//! ([`super::SimdLevel::Avx512`]).
//!
//! Intel's server cores run 512-bit multiply-adds on two ports, as many per
//! cycle as 256-bit ones: a vector of 16 does the work of two of 8 in the
//! time of one. The reflection model is nearly all multiply-adds, so it is
//! written over [`Lanes`] and lit 16 fragments at a time here; so are the
//! whole pairs of blocks of a large triangle's span drawn with flat or
//! Gouraud (`raster/tiled/band/pairs.rs`). The rest of the rasterizer
//! keeps its blocks of 8 ([`Avx2`]).
//!
//! Every operation is the 256-bit one's 512-bit twin, so each lane gets
//! the same bits as in the AVX2 build. The two estimates have no twin
//! (AVX-512's `vrsqrt14ps` and `vrcp14ps` are more precise, so they
//! differ): they are taken on the two halves with the AVX2 instructions,
//! then refined in 512 bits as [`Avx2`] refines them.

use std::arch::x86_64::*;
use std::ops::{Add, Mul, Sub};

use super::avx2::{Avx2, Width};
use super::{pow_unit, Apart, Lanes, Vf};

/// Lighting in 512-bit vectors: the CPU has AVX-512 F, VL, BW and DQ.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Zmm;

impl Width for Zmm {
    type F16 = Wide;
    fn supported() -> bool {
        std::is_x86_feature_detected!("avx512f")
            && std::is_x86_feature_detected!("avx512vl")
            && std::is_x86_feature_detected!("avx512bw")
            && std::is_x86_feature_detected!("avx512dq")
    }
    #[inline(always)]
    fn load(s: Avx2<Zmm>, src: &[f32; 16]) -> Wide {
        // SAFETY: `s` proves AVX-512 F (`Avx2::<Zmm>::new`); `src` is 16 lanes.
        Wide(unsafe { _mm512_loadu_ps(src.as_ptr()) }, s)
    }
    #[inline(always)]
    fn apart<K: Apart<Avx2<Zmm>>>(s: Avx2<Zmm>, work: K) -> K::Output {
        #[inline(never)]
        #[target_feature(enable = "avx2,fma,popcnt,bmi1,bmi2,avx512f,avx512vl,avx512bw,avx512dq")]
        unsafe fn apart<K: Apart<Avx2<Zmm>>>(s: Avx2<Zmm>, work: K) -> K::Output {
            work.run(s)
        }
        // SAFETY: `s` is an `Avx2<Zmm>` (`Avx2::<Zmm>::new`): the CPU has
        // AVX2, FMA, POPCNT, BMI1, BMI2 and AVX-512 F, VL, BW and DQ, the
        // only requirement of a `target_feature` function.
        unsafe { apart(s, work) }
    }
}

/// 16 × f32 in one 512-bit register. The backend value beside it (no
/// bytes) proves the CPU has AVX-512 F and DQ, which makes the `unsafe`
/// intrinsic calls below sound.
#[derive(Clone, Copy)]
pub(crate) struct Wide(__m512, Avx2<Zmm>);

// No closures here: one the compiler does not inline is compiled without
// the backend's target features (see `shade/lanes.rs`).
impl Wide {
    /// The low and the high 8 lanes.
    #[inline(always)]
    fn split(self) -> [Vf<Avx2<Zmm>>; 2] {
        // SAFETY: see `Wide`.
        unsafe {
            [
                Vf(_mm512_castps512_ps256(self.0), self.1),
                Vf(_mm512_extractf32x8_ps::<1>(self.0), self.1),
            ]
        }
    }

    /// The low and the high 8 lanes together.
    #[inline(always)]
    fn join([low, high]: [Vf<Avx2<Zmm>>; 2]) -> Wide {
        // SAFETY: see `Wide`.
        let v = unsafe { _mm512_insertf32x8::<1>(_mm512_castps256_ps512(low.0), high.0) };
        Wide(v, low.1)
    }
}

macro_rules! wide_operator {
    ($trait:ident, $method:ident, $intrinsic:ident) => {
        impl $trait for Wide {
            type Output = Wide;
            #[inline(always)]
            fn $method(self, o: Wide) -> Wide {
                // SAFETY: see `Wide`.
                Wide(unsafe { $intrinsic(self.0, o.0) }, self.1)
            }
        }
    };
}
wide_operator!(Add, add, _mm512_add_ps);
wide_operator!(Sub, sub, _mm512_sub_ps);
wide_operator!(Mul, mul, _mm512_mul_ps);

impl Mul<f32> for Wide {
    type Output = Wide;
    #[inline(always)]
    fn mul(self, o: f32) -> Wide {
        self * self.splat_like(o)
    }
}

impl Lanes for Wide {
    type Mask = __mmask16;
    const LANES: usize = 16;
    #[inline(always)]
    fn splat_like(self, v: f32) -> Wide {
        // SAFETY: see `Wide`.
        Wide(unsafe { _mm512_set1_ps(v) }, self.1)
    }
    #[inline(always)]
    fn mul_add(self, m: Wide, a: Wide) -> Wide {
        // SAFETY: see `Wide`.
        Wide(unsafe { _mm512_fmadd_ps(self.0, m.0, a.0) }, self.1)
    }
    #[inline(always)]
    fn halves(self, v: [f32; 2]) -> Wide {
        // SAFETY: see `Wide`.
        let v = unsafe { _mm512_mask_blend_ps(0xff00, _mm512_set1_ps(v[0]), _mm512_set1_ps(v[1])) };
        Wide(v, self.1)
    }
    #[inline(always)]
    fn min(self, o: Wide) -> Wide {
        // As `vminps` of 256 bits: the second operand when either is NaN.
        // SAFETY: see `Wide`.
        Wide(unsafe { _mm512_min_ps(self.0, o.0) }, self.1)
    }
    #[inline(always)]
    fn max(self, o: Wide) -> Wide {
        // SAFETY: see `Wide`.
        Wide(unsafe { _mm512_max_ps(self.0, o.0) }, self.1)
    }
    #[inline(always)]
    fn rsqrt(self) -> Wide {
        // AVX2's estimate per half, then its Newton step (see `Avx2`).
        let [low, high] = self.split();
        // SAFETY: see `Wide` (AVX-512 implies AVX).
        let r = unsafe { [_mm256_rsqrt_ps(low.0), _mm256_rsqrt_ps(high.0)] };
        let r = Wide::join([Vf(r[0], self.1), Vf(r[1], self.1)]);
        // SAFETY: see `Wide`.
        unsafe {
            let three_minus =
                _mm512_fnmadd_ps(_mm512_mul_ps(self.0, r.0), r.0, _mm512_set1_ps(3.0));
            Wide(
                _mm512_mul_ps(_mm512_mul_ps(r.0, _mm512_set1_ps(0.5)), three_minus),
                self.1,
            )
        }
    }
    #[inline(always)]
    fn recip(self) -> Wide {
        // AVX2's estimate per half, then its Newton step (see `Avx2`).
        let [low, high] = self.split();
        // SAFETY: see `Wide` (AVX-512 implies AVX).
        let r = unsafe { [_mm256_rcp_ps(low.0), _mm256_rcp_ps(high.0)] };
        let r = Wide::join([Vf(r[0], self.1), Vf(r[1], self.1)]);
        // SAFETY: see `Wide`.
        unsafe {
            let error = _mm512_fnmadd_ps(self.0, r.0, _mm512_set1_ps(1.0));
            Wide(_mm512_fmadd_ps(r.0, error, r.0), self.1)
        }
    }
    #[inline(always)]
    fn gt(self, o: Wide) -> __mmask16 {
        // SAFETY: see `Wide`.
        unsafe { _mm512_cmp_ps_mask::<_CMP_GT_OQ>(self.0, o.0) }
    }
    #[inline(always)]
    fn mask_bits(mask: __mmask16) -> u32 {
        u32::from(mask)
    }
    #[inline(always)]
    fn select(mask: __mmask16, yes: Wide, no: Wide) -> Wide {
        // SAFETY: see `Wide`.
        Wide(unsafe { _mm512_mask_blend_ps(mask, no.0, yes.0) }, yes.1)
    }
    #[inline(always)]
    fn pow_unit(self, p: f32) -> Wide {
        let [low, high] = self.split();
        Wide::join([pow_unit(low, p), pow_unit(high, p)])
    }
    #[inline(always)]
    fn map(self, f: impl Fn(f32) -> f32) -> Wide {
        let mut lanes = [0.0; 16];
        self.store_to(&mut lanes);
        Zmm::load(self.1, &lanes.map(f))
    }
    #[inline(always)]
    fn store_to(self, dst: &mut [f32]) {
        let dst: &mut [f32; 16] = dst.try_into().unwrap();
        // SAFETY: see `Wide`; `dst` is 16 lanes.
        unsafe { _mm512_storeu_ps(dst.as_mut_ptr(), self.0) };
    }
    #[inline(always)]
    fn store_bytes(r: Wide, g: Wide, b: Wide, dst: &mut [i32]) {
        // As `Avx2::f_to_bytes`: `min(255.5, c)` keeps NaN, which
        // truncates to i32::MIN; the packs saturate to 0..=255.
        let top = r.splat_like(255.5);
        Wide::store_bytes_below(top.min(r), top.min(g), top.min(b), dst)
    }
    #[inline(always)]
    fn store_bytes_below(r: Wide, g: Wide, b: Wide, dst: &mut [i32]) {
        let dst: &mut [i32; 16] = dst.try_into().unwrap();
        // SAFETY: see `Wide`; `dst` is 16 lanes.
        unsafe {
            // Per 128-bit quarter, the truncated lanes (below 2^31, or
            // NaN or at most -2^31, which give i32::MIN) saturate to
            // 0..=255 in the packs into r0..r3 g0..g3 b0..b3 b0..b3 of
            // four pixels, then are gathered per pixel.
            let [r, g, b] = truncated([r, g, b]);
            let planar = _mm512_packus_epi16(_mm512_packs_epi32(r, g), _mm512_packs_epi32(b, b));
            let quarter = _mm_setr_epi8(0, 4, 8, -1, 1, 5, 9, -1, 2, 6, 10, -1, 3, 7, 11, -1);
            let packed = _mm512_shuffle_epi8(planar, _mm512_broadcast_i32x4(quarter));
            _mm512_storeu_si512(dst.as_mut_ptr().cast(), packed);
        }
    }
    /// Two shifts and one three-way or in place of the packs' four
    /// shuffles, which all wait for one port: with w once per row for the
    /// blocks of 8 too, 3–6 % off the full-screen Gouraud quad
    /// (BENCHMARKS.md, "Bytes shifted into place").
    const SHIFTS_BYTES: bool = true;
    #[inline(always)]
    fn store_bytes_within(r: Wide, g: Wide, b: Wide, dst: &mut [i32]) {
        let dst: &mut [i32; 16] = dst.try_into().unwrap();
        // SAFETY: see `Wide`; `dst` is 16 lanes.
        unsafe {
            // Each channel truncates to 0..=255: r | g << 8 | b << 16
            // (`0xfe`: the or of the three operands).
            let [r, g, b] = truncated([r, g, b]);
            let (g, b) = (_mm512_slli_epi32::<8>(g), _mm512_slli_epi32::<16>(b));
            let rgb = _mm512_ternarylogic_epi32::<0xfe>(r, g, b);
            _mm512_storeu_si512(dst.as_mut_ptr().cast(), rgb);
        }
    }
}

/// Each lane of each channel truncated to `i32` (`i32::MIN` for NaN and
/// what does not fit).
#[inline(always)]
fn truncated([r, g, b]: [Wide; 3]) -> [__m512i; 3] {
    // SAFETY: see `Wide`. No closure: it would not take the caller's
    // target features.
    unsafe {
        [
            _mm512_cvttps_epi32(r.0),
            _mm512_cvttps_epi32(g.0),
            _mm512_cvttps_epi32(b.0),
        ]
    }
}
