//! Eight lanes of `f32`, `i32` and `i64`: the only place with `unsafe`.
//!
//! The tiled rasterizer works on blocks of 8 pixels. Its hot code is written
//! once, over these lane types, whose operations are plain loops over arrays
//! of 8 and always inlined. The same code is then compiled twice:
//!
//! * inside a function with `#[target_feature(enable = "avx2,fma")]`, where
//!   LLVM turns each loop into one AVX2 instruction (8 × f32 in a `ymm`), and
//! * as ordinary portable code, which LLVM vectorizes for whatever the target
//!   has (SSE2 on any x86-64, `simd128` on WebAssembly when enabled).
//!
//! [`SimdLevel`] picks one at run time; [`SimdLevel::Portable`] can be forced
//! so that the fallback stays tested. Both produce the same results: the
//! operations are IEEE single precision with no fused multiply-add, so the
//! two builds agree bit for bit.

use std::ops::{Add, BitAnd, BitOr, Mul, Neg, Sub};

/// Which instruction set the tiled rasterizer's inner loops use.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SimdLevel {
    /// Plain Rust, vectorized by the compiler for the build target.
    Portable,
    /// 8-lane AVX2 (x86-64 only, chosen when the CPU has it).
    Avx2,
}

impl SimdLevel {
    /// The best level this CPU supports.
    pub fn detect() -> SimdLevel {
        #[cfg(target_arch = "x86_64")]
        {
            if std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma") {
                return SimdLevel::Avx2;
            }
        }
        SimdLevel::Portable
    }

    /// Whether this CPU can run this level.
    pub fn is_supported(self) -> bool {
        match self {
            SimdLevel::Portable => true,
            SimdLevel::Avx2 => SimdLevel::detect() == SimdLevel::Avx2,
        }
    }

    /// "avx2" or "portable".
    pub fn name(self) -> &'static str {
        match self {
            SimdLevel::Portable => "portable",
            SimdLevel::Avx2 => "avx2",
        }
    }
}

/// A piece of work to compile once per [`SimdLevel`]. `run` must be
/// `#[inline(always)]`, and so must everything it calls in its hot loops,
/// for the AVX2 build to reach them.
pub(crate) trait Kernel {
    /// What the work produces.
    type Output;
    /// Does the work.
    fn run(self) -> Self::Output;
}

/// Runs `kernel`, compiled for `level` (portable when the CPU lacks it).
pub(crate) fn dispatch<K: Kernel>(level: SimdLevel, kernel: K) -> K::Output {
    #[cfg(target_arch = "x86_64")]
    {
        #[target_feature(enable = "avx2,fma")]
        unsafe fn with_avx2<K: Kernel>(kernel: K) -> K::Output {
            kernel.run()
        }
        if level == SimdLevel::Avx2 && level.is_supported() {
            // SAFETY: the CPU supports AVX2 and FMA (checked just above), the
            // only requirement of a `target_feature` function.
            return unsafe { with_avx2(kernel) };
        }
    }
    let _ = level;
    kernel.run()
}

/// Eight `f32` lanes.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(32))]
pub(crate) struct F32x8(pub [f32; 8]);

/// Eight lane masks: all bits set (true) or clear (false).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(C, align(32))]
pub(crate) struct Mask8(pub [i32; 8]);

/// Eight `i64` lanes, for edge functions whose products need 64 bits.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(C, align(64))]
pub(crate) struct I64x8(pub [i64; 8]);

macro_rules! lanewise {
    ($a:expr, $b:expr, |$x:ident, $y:ident| $e:expr) => {{
        let (a, b) = ($a, $b);
        let mut out = [Default::default(); 8];
        for i in 0..8 {
            let ($x, $y) = (a[i], b[i]);
            out[i] = $e;
        }
        out
    }};
}

impl F32x8 {
    pub const LANE_INDEX: F32x8 = F32x8([0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0]);

    #[inline(always)]
    pub fn splat(v: f32) -> F32x8 {
        F32x8([v; 8])
    }

    #[inline(always)]
    pub fn load(src: &[f32]) -> F32x8 {
        let mut out = [0.0; 8];
        out.copy_from_slice(&src[..8]);
        F32x8(out)
    }

    #[inline(always)]
    pub fn store(self, dst: &mut [f32]) {
        dst[..8].copy_from_slice(&self.0);
    }

    #[inline(always)]
    pub fn min(self, o: F32x8) -> F32x8 {
        F32x8(lanewise!(self.0, o.0, |a, b| if a < b { a } else { b }))
    }

    #[inline(always)]
    pub fn max(self, o: F32x8) -> F32x8 {
        F32x8(lanewise!(self.0, o.0, |a, b| if a > b { a } else { b }))
    }

    #[inline(always)]
    pub fn div(self, o: F32x8) -> F32x8 {
        F32x8(lanewise!(self.0, o.0, |a, b| a / b))
    }

    #[inline(always)]
    pub fn sqrt(self) -> F32x8 {
        let mut out = self.0;
        for v in &mut out {
            *v = v.sqrt();
        }
        F32x8(out)
    }

    #[inline(always)]
    pub fn floor(self) -> F32x8 {
        let mut out = self.0;
        for v in &mut out {
            *v = v.floor();
        }
        F32x8(out)
    }

    #[inline(always)]
    pub fn lt(self, o: F32x8) -> Mask8 {
        Mask8(lanewise!(self.0, o.0, |a, b| -i32::from(a < b)))
    }

    #[inline(always)]
    pub fn gt(self, o: F32x8) -> Mask8 {
        Mask8(lanewise!(self.0, o.0, |a, b| -i32::from(a > b)))
    }

    /// Lanes of `self` where `mask` is set, of `other` elsewhere.
    #[inline(always)]
    pub fn select(mask: Mask8, yes: F32x8, no: F32x8) -> F32x8 {
        let mut out = no.0;
        for i in 0..8 {
            out[i] = f32::from_bits(
                (yes.0[i].to_bits() & mask.0[i] as u32) | (no.0[i].to_bits() & !mask.0[i] as u32),
            );
        }
        F32x8(out)
    }

    /// The bits of each lane as an integer.
    #[inline(always)]
    pub fn to_bits(self) -> [i32; 8] {
        self.0.map(|v| v.to_bits() as i32)
    }

    /// Lanes made from bit patterns.
    #[inline(always)]
    pub fn from_bits(bits: [i32; 8]) -> F32x8 {
        F32x8(bits.map(|b| f32::from_bits(b as u32)))
    }

    /// Converts lanes in [0, 255.5) to bytes, truncating.
    #[inline(always)]
    pub fn to_i32_truncated(self) -> [i32; 8] {
        let mut out = [0; 8];
        for i in 0..8 {
            // The callers clamp first, so the saturating cast never saturates.
            out[i] = self.0[i] as i32;
        }
        out
    }
}

impl Add for F32x8 {
    type Output = F32x8;
    #[inline(always)]
    fn add(self, o: F32x8) -> F32x8 {
        F32x8(lanewise!(self.0, o.0, |a, b| a + b))
    }
}

impl Sub for F32x8 {
    type Output = F32x8;
    #[inline(always)]
    fn sub(self, o: F32x8) -> F32x8 {
        F32x8(lanewise!(self.0, o.0, |a, b| a - b))
    }
}

impl Mul for F32x8 {
    type Output = F32x8;
    #[inline(always)]
    fn mul(self, o: F32x8) -> F32x8 {
        F32x8(lanewise!(self.0, o.0, |a, b| a * b))
    }
}

impl Mul<f32> for F32x8 {
    type Output = F32x8;
    #[inline(always)]
    fn mul(self, o: f32) -> F32x8 {
        self * F32x8::splat(o)
    }
}

impl Neg for F32x8 {
    type Output = F32x8;
    #[inline(always)]
    fn neg(self) -> F32x8 {
        F32x8(self.0.map(|v| -v))
    }
}

impl Mask8 {
    /// Lanes `i` with `i < count` set.
    #[inline(always)]
    pub fn first(count: i64) -> Mask8 {
        let mut out = [0; 8];
        for (i, m) in out.iter_mut().enumerate() {
            *m = -i32::from((i as i64) < count);
        }
        Mask8(out)
    }

    #[inline(always)]
    pub fn any(self) -> bool {
        self.0.iter().fold(0, |acc, &m| acc | m) != 0
    }

    /// Set lanes, as bits 0..8.
    #[inline(always)]
    pub fn bits(self) -> u32 {
        let mut out = 0;
        for (i, &m) in self.0.iter().enumerate() {
            out |= ((m as u32) >> 31) << i;
        }
        out
    }
}

impl BitAnd for Mask8 {
    type Output = Mask8;
    #[inline(always)]
    fn bitand(self, o: Mask8) -> Mask8 {
        Mask8(lanewise!(self.0, o.0, |a, b| a & b))
    }
}

impl BitOr for Mask8 {
    type Output = Mask8;
    #[inline(always)]
    fn bitor(self, o: Mask8) -> Mask8 {
        Mask8(lanewise!(self.0, o.0, |a, b| a | b))
    }
}

impl I64x8 {
    /// `start + step·i` in lane `i`.
    #[inline(always)]
    pub fn ramp(start: i64, step: i64) -> I64x8 {
        let mut out = [0; 8];
        for (i, v) in out.iter_mut().enumerate() {
            *v = start + step * i as i64;
        }
        I64x8(out)
    }

    #[inline(always)]
    pub fn add_scalar(self, v: i64) -> I64x8 {
        I64x8(self.0.map(|x| x + v))
    }

    /// Lanes where all three values are non-negative.
    #[inline(always)]
    pub fn all_non_negative(a: I64x8, b: I64x8, c: I64x8) -> Mask8 {
        let mut out = [0; 8];
        for (i, m) in out.iter_mut().enumerate() {
            // The sign bit of the OR is set when any of the three is negative.
            *m = !(((a.0[i] | b.0[i] | c.0[i]) >> 63) as i32);
        }
        Mask8(out)
    }
}

/// `x^p` for `x` in [0, 1] and `p > 0`, to about 1e-6 relative error: the
/// specular power, which the scalar path computes with `powf`.
#[inline(always)]
pub(crate) fn pow_unit(x: F32x8, p: f32) -> F32x8 {
    // log2(x) = e + log2(m), m in [√½, √2): with t = (m − 1)/(m + 1),
    // log2(m) = 2/ln2 · (t + t³/3 + t⁵/5 + t⁷/7 + t⁹/9), |t| ≤ 0.172.
    let bits = x.to_bits();
    let mut exponent = [0f32; 8];
    let mut mantissa_bits = [0i32; 8];
    for i in 0..8 {
        // Reduce the mantissa to [√½, √2) by borrowing from the exponent.
        let adjusted = bits[i] - 0x3f35_04f3; // bits of √½
        let e = adjusted >> 23;
        exponent[i] = e as f32;
        mantissa_bits[i] = bits[i] - (e << 23);
    }
    let m = F32x8::from_bits(mantissa_bits);
    let one = F32x8::splat(1.0);
    let t = (m - one).div(m + one);
    let t2 = t * t;
    let series = ((((t2 * (1.0 / 9.0) + F32x8::splat(1.0 / 7.0)) * t2 + F32x8::splat(1.0 / 5.0))
        * t2
        + F32x8::splat(1.0 / 3.0))
        * t2
        + one)
        * t;
    let log2 = F32x8(exponent) + series * (2.0 / std::f32::consts::LN_2);
    // 2^y = 2^i · 2^f with i = round(y), f in [−½, ½], by the Taylor series
    // of e^(f·ln2) to degree 6 (truncation error below 2e-7).
    let y = (log2 * p).max(F32x8::splat(-127.0));
    let i = (y + F32x8::splat(0.5)).floor();
    let f = y - i;
    const C: [f32; 6] = [
        0.693_147_2,
        0.240_226_5,
        5.550_411e-2,
        9.618_129e-3,
        1.333_356e-3,
        1.540_353e-4,
    ];
    let poly = (((((f * C[5] + F32x8::splat(C[4])) * f + F32x8::splat(C[3])) * f
        + F32x8::splat(C[2]))
        * f
        + F32x8::splat(C[1]))
        * f
        + F32x8::splat(C[0]))
        * f
        + one;
    let scale = i.to_i32_truncated().map(|e| (e + 127).max(0) << 23);
    let result = poly * F32x8::from_bits(scale);
    // Exact zeros stay zero; so does anything below 2^-126.
    F32x8::select(
        x.gt(F32x8::splat(0.0)) & y.gt(F32x8::splat(-126.0)),
        result,
        F32x8::splat(0.0),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pow_unit_matches_powf() {
        for p in [0.5f32, 1.0, 2.0, 7.5, 32.0, 128.0, 1000.0] {
            let mut worst = 0f32;
            for k in 0..=4000 {
                let x = k as f32 / 4000.0;
                let got = pow_unit(F32x8::splat(x), p).0[0];
                let want = x.powf(p);
                worst = worst.max((got - want).abs());
            }
            assert!(worst < 2e-5, "p = {p}: worst absolute error {worst}");
        }
    }

    struct Pow(F32x8);

    impl Kernel for Pow {
        type Output = F32x8;
        #[inline(always)]
        fn run(self) -> F32x8 {
            pow_unit(self.0, 32.0)
        }
    }

    #[test]
    fn both_levels_agree() {
        let x = F32x8([0.0, 0.1, 0.25, 0.5, 0.75, 0.9, 0.99, 1.0]);
        let portable = dispatch(SimdLevel::Portable, Pow(x));
        let best = dispatch(SimdLevel::detect(), Pow(x));
        assert_eq!(portable, best);
    }

    #[test]
    fn edge_masks() {
        let a = I64x8::ramp(-3, 1);
        let b = I64x8::ramp(0, 0);
        let c = I64x8::ramp(1 << 40, -(1 << 38));
        assert_eq!(I64x8::all_non_negative(a, b, c).bits(), 0b0001_1000);
        assert_eq!(Mask8::first(3).bits(), 0b111);
    }
}
