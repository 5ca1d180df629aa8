//! Eight lanes of `f32`, `i32` and `i64`: the only place with `unsafe`.
//!
//! The tiled rasterizer works on blocks of 8 pixels. Its hot code is written
//! once, generic over a [`Simd`] backend, with the lane types [`Vf`] (8 ×
//! f32) and [`Vi`] (8 × i32, also used as lane masks) giving it ordinary
//! operators. Three backends exist:
//!
//! * [`Portable`]: arrays of 8, each operation written out lane by lane
//!   (not looped: see `portable.rs`), plain safe Rust that compiles for
//!   any target (LLVM vectorizes some of it: SSE2, or `simd128` on
//!   WebAssembly when enabled);
//! * [`Avx2`](avx2::Avx2) (x86-64): one AVX2 instruction per operation. A
//!   value of this type exists only once the CPU is known to have AVX2 and
//!   FMA, which is what makes its `unsafe` intrinsic calls sound;
//! * `Wasm128` (WebAssembly built with `+simd128`, as the viewer's module
//!   is): two 128-bit instructions per operation, chosen at compile time
//!   (a WebAssembly module cannot ask its host what it supports: one built
//!   with `simd128` does not load without it). It computes exactly what
//!   the portable backend computes, which LLVM vectorizes only in part.
//!
//! [`dispatch`] runs a [`Kernel`] with the best backend inside a
//! `#[target_feature(enable = "avx2,fma")]` function, so that the inlined
//! intrinsics compile to VEX code. Where the CPU also has AVX-512 (F, VL,
//! BW, DQ), the same AVX2 backend is compiled a second time with those
//! features enabled ([`SimdLevel::Avx512`]): the blocks stay 8 wide, but
//! the compiler gets 32 vector registers instead of 16 (the inner loops
//! spilled plane values to the stack), mask registers for compares and
//! blends, and three-operand logic; and Phong's queued fragments are lit
//! 16 at a time in 512-bit registers ([`Simd::F16`], `avx512.rs`), as are
//! flat's and Gouraud's whole pairs of span blocks, which other backends
//! do as two vectors of 8 (`wide.rs`). Each operation is
//! the same IEEE operation on more lanes, so the results are bit for bit
//! those of [`SimdLevel::Avx2`] (tests check it). The tiled rasterizer uses
//! that build for its bands (the pixels); its per-vertex and per-triangle
//! work runs the AVX2 build, which was faster there
//! (`SimdLevel::without_avx512`).
//!
//! All backends compute in IEEE single precision; the x86 ones differ from
//! the portable one in the last bits only, where AVX2 fuses
//! multiply-adds and uses its reciprocal estimates refined by a Newton step
//! (22+ bits instead of an exact division, which costs 5–10 times more), so
//! colours agree within 1/255. Tests check both, and
//! [`SimdLevel::Portable`] can be forced.

#[cfg(target_arch = "x86_64")]
mod avx2;
#[cfg(target_arch = "x86_64")]
mod avx512;
mod lines;
mod planes;
mod portable;
#[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
mod wasm128;
mod wide;

use std::ops::{Add, BitAnd, BitOr, Mul, Sub};

pub(crate) use self::lines::{prefetch, ReleaseLines, WritePrefetch};
pub(crate) use self::planes::{solve_planes, PlaneSolve, SolvedPlane, SOLVE_LANES};
pub(crate) use self::portable::Portable;
pub(crate) use self::wide::{Lanes, Pair};

/// Which instruction set the tiled rasterizer's inner loops use.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SimdLevel {
    /// Plain Rust, vectorized by the compiler where it can.
    Portable,
    /// 8-lane AVX2 (x86-64 only, chosen when the CPU has it).
    Avx2,
    /// The AVX2 lanes compiled for AVX-512 (F, VL, BW, DQ): same results,
    /// more registers (x86-64 only, chosen when the CPU has it).
    Avx512,
    /// Two 4-lane WebAssembly `simd128` vectors (only in a module built
    /// with `+simd128`, where it is always chosen).
    Simd128,
}

// Every level, from the plainest (`ALL`), with the names `shadelab bench
// --simd` and its JSON use.
choices!(SimdLevel, "SIMD level", {
    Portable => "portable": "plain Rust, vectorized by the compiler where it can",
    Simd128 => "simd128": "WebAssembly simd128 (only inside a module built with it)",
    Avx2 => "avx2": "8-lane AVX2 and FMA (x86-64)",
    Avx512 => "avx512": "the AVX2 lanes compiled for AVX-512 F/VL/BW/DQ (x86-64)",
});

impl SimdLevel {
    /// The best level this CPU supports.
    pub fn detect() -> SimdLevel {
        SimdLevel::supported().last().unwrap_or(SimdLevel::Portable)
    }

    /// The levels this CPU can run, from the plainest.
    pub fn supported() -> impl Iterator<Item = SimdLevel> {
        SimdLevel::ALL
            .into_iter()
            .filter(|level| level.is_supported())
    }

    /// This level with the AVX-512 build replaced by the AVX2 one (the same
    /// bytes), for work that AVX-512 made slower. The tiled rasterizer keeps
    /// AVX-512 for its bands (the pixels, `band_pass`); its per-vertex and
    /// per-triangle work (vertex lighting, setup and binning, flat's polygon
    /// lighting) runs the AVX2 build. On an Intel Xeon with AVX-512 the
    /// geometry compiled for it made the bunny's and the dragon's Gouraud and
    /// Phong frames up to 5 % slower, while Phong's fill was 7–9 % faster
    /// (BENCHMARKS.md, "AVX-512 for Phong's pixels only"); measured again
    /// after the bands moved to AVX-512, it was neutral (1.001 over 36 rows),
    /// so it stays on AVX2 ("Flat's and Gouraud's bands on AVX-512").
    pub(crate) fn without_avx512(self) -> SimdLevel {
        match self {
            SimdLevel::Avx512 => SimdLevel::Avx2,
            level => level,
        }
    }

    /// Whether this CPU can run this level.
    pub fn is_supported(self) -> bool {
        match self {
            SimdLevel::Portable => true,
            #[cfg(target_arch = "x86_64")]
            SimdLevel::Avx2 => avx2::Avx2::<avx2::Ymm>::new().is_some(),
            #[cfg(target_arch = "x86_64")]
            SimdLevel::Avx512 => avx2::Avx2::<avx512::Zmm>::new().is_some(),
            #[cfg(not(target_arch = "x86_64"))]
            SimdLevel::Avx2 | SimdLevel::Avx512 => false,
            SimdLevel::Simd128 => cfg!(all(target_arch = "wasm32", target_feature = "simd128")),
        }
    }
}

/// A piece of work compiled once per backend. `run` and everything it calls
/// in its hot loops must be `#[inline(always)]`.
pub(crate) trait Kernel {
    /// What the work produces.
    type Output;
    /// Does the work with backend `S`.
    fn run<S: Simd>(self, simd: S) -> Self::Output;
}

/// Work compiled for one backend `S` and run apart from its caller
/// ([`Simd::apart`]). `run` and what it calls must be `#[inline(always)]`.
pub(crate) trait Apart<S: Simd> {
    /// What the work produces.
    type Output;
    /// Does the work.
    fn run(self, simd: S) -> Self::Output;
}

/// Runs `kernel` with the backend for `level` (portable when the CPU lacks it).
pub(crate) fn dispatch<K: Kernel>(level: SimdLevel, kernel: K) -> K::Output {
    #[cfg(target_arch = "x86_64")]
    {
        use self::{avx2::Avx2, avx512::Zmm};
        #[target_feature(enable = "avx2,fma,popcnt,bmi1,bmi2")]
        unsafe fn with_avx2<K: Kernel>(kernel: K, simd: Avx2) -> K::Output {
            kernel.run(simd)
        }
        #[target_feature(enable = "avx2,fma,popcnt,bmi1,bmi2,avx512f,avx512vl,avx512bw,avx512dq")]
        unsafe fn with_avx512<K: Kernel>(kernel: K, simd: Avx2<Zmm>) -> K::Output {
            kernel.run(simd)
        }
        if level == SimdLevel::Avx512 {
            if let Some(simd) = Avx2::<Zmm>::new() {
                // SAFETY: `Avx2::<Zmm>::new` succeeded, so the CPU has AVX2,
                // FMA, POPCNT, BMI1, BMI2 and AVX-512 F, VL, BW and DQ, the
                // only requirement of a `target_feature` function.
                return unsafe { with_avx512(kernel, simd) };
            }
        }
        if level == SimdLevel::Avx2 || level == SimdLevel::Avx512 {
            if let Some(simd) = Avx2::new() {
                // SAFETY: `Avx2::new` succeeded, so the CPU has AVX2, FMA,
                // POPCNT, BMI1 and BMI2, the only requirement of a
                // `target_feature` function.
                return unsafe { with_avx2(kernel, simd) };
            }
        }
    }
    #[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
    {
        if level == SimdLevel::Simd128 {
            return kernel.run(wasm128::Wasm128);
        }
    }
    let _ = level;
    kernel.run(Portable)
}

/// `dst[at[i]] = values[i]` for the 8 lanes in order (a later lane wins
/// where two indices are the same), with one bounds check for the eight:
/// Phong's write-back of queued fragments, whose indices are scattered.
///
/// # Panics
/// If an index is negative or not below `dst.len()`.
#[inline(always)]
pub(crate) fn scatter(values: &[i32; 8], at: &[i32; 8], dst: &mut [i32]) {
    // As unsigned, a negative index is larger than any length.
    let largest = at.iter().fold(0u32, |m, &i| m.max(i as u32));
    assert!(
        (largest as usize) < dst.len(),
        "scatter index out of bounds"
    );
    for i in 0..8 {
        // SAFETY: every `at[i]`, as unsigned, is at most `largest`, which is
        // below `dst.len()`.
        unsafe { *dst.get_unchecked_mut(at[i] as u32 as usize) = values[i] };
    }
}

/// The operations the rasterizer needs on 8 lanes.
pub(crate) trait Simd: Copy + Send + Sync {
    /// 8 × f32.
    type F: Copy;
    /// 8 × i32; masks are all ones (true) or zero per lane.
    type I: Copy;

    fn f_splat(self, v: f32) -> Self::F;
    fn f_add(self, a: Self::F, b: Self::F) -> Self::F;
    fn f_sub(self, a: Self::F, b: Self::F) -> Self::F;
    fn f_mul(self, a: Self::F, b: Self::F) -> Self::F;
    /// `a·b + c`, fused where the backend can (AVX2 FMA), else two roundings.
    fn f_mul_add(self, a: Self::F, b: Self::F, c: Self::F) -> Self::F;
    /// `a < b ? a : b` (so a NaN in `a` gives `b`).
    fn f_min(self, a: Self::F, b: Self::F) -> Self::F;
    /// `a > b ? a : b` (so a NaN in `a` gives `b`).
    fn f_max(self, a: Self::F, b: Self::F) -> Self::F;
    /// `1 / √a` to at least 22 bits (exact in the portable backend); any
    /// value where `a` is zero, negative or not finite.
    fn f_rsqrt(self, a: Self::F) -> Self::F;
    /// `1 / a` to at least 22 bits (exact in the portable backend) for
    /// finite non-zero `a`.
    fn f_recip(self, a: Self::F) -> Self::F;
    fn f_floor(self, a: Self::F) -> Self::F;
    fn f_lt(self, a: Self::F, b: Self::F) -> Self::I;
    fn f_gt(self, a: Self::F, b: Self::F) -> Self::I;
    /// Lanes of `a` where `mask` is set, of `b` elsewhere.
    fn f_select(self, mask: Self::I, a: Self::F, b: Self::F) -> Self::F;
    fn f_load(self, src: &[f32; 8]) -> Self::F;
    fn f_store(self, v: Self::F, dst: &mut [f32; 8]);
    /// Truncation towards zero; lanes must lie within ±2^31.
    fn f_to_i(self, a: Self::F) -> Self::I;
    fn f_bits(self, a: Self::F) -> Self::I;
    fn f_from_i(self, a: Self::I) -> Self::F;
    fn f_from_bits(self, a: Self::I) -> Self::F;
    fn f_lanes(self) -> Self::F;

    fn i_splat(self, v: i32) -> Self::I;
    fn i_add(self, a: Self::I, b: Self::I) -> Self::I;
    fn i_sub(self, a: Self::I, b: Self::I) -> Self::I;
    fn i_and(self, a: Self::I, b: Self::I) -> Self::I;
    fn i_or(self, a: Self::I, b: Self::I) -> Self::I;
    fn i_max(self, a: Self::I, b: Self::I) -> Self::I;
    /// Wrapping multiplication (the low 32 bits of the product).
    fn i_mul(self, a: Self::I, b: Self::I) -> Self::I;
    /// All ones where `a > b`, signed.
    fn i_gt(self, a: Self::I, b: Self::I) -> Self::I;
    /// `i` in lane `i`.
    fn i_lanes(self) -> Self::I;
    fn i_shl(self, a: Self::I, bits: u32) -> Self::I;
    fn i_sra(self, a: Self::I, bits: u32) -> Self::I;
    /// Lanes of `a` where `mask` is set, of `b` elsewhere.
    fn i_select(self, mask: Self::I, a: Self::I, b: Self::I) -> Self::I;
    fn i_load(self, src: &[i32; 8]) -> Self::I;
    fn i_store(self, v: Self::I, dst: &mut [i32; 8]);
    /// The sign bit of each lane, as bits 0..8.
    fn i_bits(self, a: Self::I) -> u32;
    /// A mask from bits 0..8.
    fn i_from_bits(self, bits: u32) -> Self::I;

    /// The lanes whose bit is set in `bits` (0..256), moved to the front
    /// in order; the other lanes are unspecified.
    fn f_compress(self, v: Self::F, bits: u32) -> Self::F;
    /// As [`Simd::f_compress`], for `i32` lanes.
    fn i_compress(self, v: Self::I, bits: u32) -> Self::I;
    /// The lanes moved up by `by` (0..8), those past lane 7 wrapping round
    /// to the front: lane `i` of the result is lane `(i − by) mod 8` of `v`.
    fn i_rotate(self, v: Self::I, by: usize) -> Self::I;

    /// Three channels in byte units plus one half (`255·c + 0.5`), each
    /// truncated and saturated to 0..=255 (NaN to 0, as Rust's `as u8`),
    /// packed per lane as `r | g << 8 | b << 16`.
    fn f_to_bytes(self, r: Self::F, g: Self::F, b: Self::F) -> Self::I;
    /// As [`Simd::f_to_bytes`], for channels whose lanes are all below
    /// 2^31 or NaN (never +∞): the same result, without the guard some
    /// backends take for larger values (`avx2.rs`). See `fill_span` in
    /// `raster/tiled/band/pairs.rs` for who may call it.
    #[inline(always)]
    fn f_to_bytes_below(self, r: Self::F, g: Self::F, b: Self::F) -> Self::I {
        self.f_to_bytes(r, g, b)
    }

    /// The low three bytes of each lane, packed: 8 RGB pixels.
    fn i_store_rgb(self, v: Self::I, dst: &mut [u8; 24]);
    /// Four blocks' RGB pixels (as [`Simd::i_store_rgb`]), 32 in a row,
    /// with non-temporal (streaming) stores where the backend has them and
    /// `dst` is 32-byte aligned: they go to memory without first reading
    /// the lines into the caches, and without pushing out what is there.
    /// Call [`Simd::store_fence`] before anything else touches `dst`.
    #[inline(always)]
    fn i_stream_rgb(self, v: [Self::I; 4], dst: &mut [u8; 96]) {
        let (a, b) = dst.split_at_mut(48);
        let [a0, a1] = a.as_chunks_mut::<24>().0 else {
            unreachable!()
        };
        let [b0, b1] = b.as_chunks_mut::<24>().0 else {
            unreachable!()
        };
        self.i_store_rgb(v[0], a0);
        self.i_store_rgb(v[1], a1);
        self.i_store_rgb(v[2], b0);
        self.i_store_rgb(v[3], b1);
    }
    /// Orders the streaming stores of [`Simd::i_stream_rgb`] before
    /// whatever this thread does next (nothing where there are none).
    #[inline(always)]
    fn store_fence(self) {}

    /// Runs `work` in a function of its own, compiled for this backend
    /// and never inlined into the caller (inline where a backend has no
    /// target features to keep): the caller's loops keep their registers
    /// whatever `work` holds, and the other way round.
    #[inline(always)]
    fn apart<K: Apart<Self>>(self, work: K) -> K::Output
    where
        Self: Sized,
    {
        work.run(self)
    }

    /// 16 lanes of `f32` for lighting Phong's queued fragments: one
    /// AVX-512 vector ([`SimdLevel::Avx512`]) or a [`Pair`] of this
    /// backend's 8 (see `wide.rs`).
    type F16: Lanes;
    /// 16 lanes from memory.
    fn f16_load(self, src: &[f32; 16]) -> Self::F16;
    /// How many groups of 16 queued fragments a deferred shader lights
    /// together, so that their dependency chains overlap: 1 or
    /// [`MAX_LIT_GROUPS`] (checked where the queue is lit). Four
    /// only where the registers hold them (the x86 backends); the portable
    /// backend's lanes are scalar code that four groups would unroll into
    /// functions too large to compile in reasonable time.
    const LIT_GROUPS: usize = 1;

    /// The first `out.len()` planes (at most [`SOLVE_LANES`]) of a
    /// triangle's setup into `out` (`planes.rs`), bit for bit those of
    /// [`solve_planes`], which this is unless the backend has vectors of
    /// `f64`.
    #[inline(always)]
    fn solve_planes(self, p: &PlaneSolve, out: &mut [SolvedPlane]) {
        solve_planes(p, out);
    }
}

/// The most groups of 16 any backend lights together ([`Simd::LIT_GROUPS`]):
/// the size of the lighting queue.
pub(crate) const MAX_LIT_GROUPS: usize = 4;

/// 8 × f32 with operators, for backend `S`.
#[derive(Clone, Copy)]
pub(crate) struct Vf<S: Simd>(pub S::F, pub S);

/// 8 × i32 (or lane masks) with operators, for backend `S`.
#[derive(Clone, Copy)]
pub(crate) struct Vi<S: Simd>(pub S::I, pub S);

impl<S: Simd> Vf<S> {
    #[inline(always)]
    pub fn splat(s: S, v: f32) -> Self {
        Vf(s.f_splat(v), s)
    }
    #[inline(always)]
    pub fn lanes(s: S) -> Self {
        Vf(s.f_lanes(), s)
    }
    #[inline(always)]
    pub fn load(s: S, src: &[f32; 8]) -> Self {
        Vf(s.f_load(src), s)
    }
    #[inline(always)]
    pub fn store(self, dst: &mut [f32; 8]) {
        self.1.f_store(self.0, dst)
    }
    #[inline(always)]
    pub fn floor(self) -> Self {
        Vf(self.1.f_floor(self.0), self.1)
    }
    #[inline(always)]
    pub fn lt(self, o: Self) -> Vi<S> {
        Vi(self.1.f_lt(self.0, o.0), self.1)
    }
    /// The lanes set in `bits`, packed to the front.
    #[inline(always)]
    pub fn compress(self, bits: u32) -> Self {
        Vf(self.1.f_compress(self.0, bits), self.1)
    }
    /// See [`Simd::i_rotate`].
    #[inline(always)]
    pub fn rotate(self, by: usize) -> Self {
        self.bits().rotate(by).bits_to_f()
    }
    /// Truncates towards zero; lanes must lie within ±2^31.
    #[inline(always)]
    pub fn to_i(self) -> Vi<S> {
        Vi(self.1.f_to_i(self.0), self.1)
    }
    #[inline(always)]
    pub fn bits(self) -> Vi<S> {
        Vi(self.1.f_bits(self.0), self.1)
    }
    /// Channels in byte units plus one half to packed colours, see
    /// [`Simd::f_to_bytes`].
    #[inline(always)]
    pub fn to_bytes(r: Self, g: Self, b: Self) -> Vi<S> {
        Vi(r.1.f_to_bytes(r.0, g.0, b.0), r.1)
    }
}

impl<S: Simd> Vi<S> {
    #[inline(always)]
    pub fn splat(s: S, v: i32) -> Self {
        Vi(s.i_splat(v), s)
    }
    #[inline(always)]
    pub fn from_mask_bits(s: S, bits: u32) -> Self {
        Vi(s.i_from_bits(bits), s)
    }
    /// 0, 1, … 7.
    #[inline(always)]
    pub fn ramp(s: S) -> Self {
        Vi(s.i_lanes(), s)
    }
    /// All ones where `self > o`.
    #[inline(always)]
    pub fn gt(self, o: Self) -> Self {
        Vi(self.1.i_gt(self.0, o.0), self.1)
    }
    /// Bits 0..8 of the lanes where `self == o`.
    #[inline(always)]
    pub fn eq_bits(self, o: Self) -> u32 {
        let s = self.1;
        !(Vi(s.i_gt(self.0, o.0), s) | Vi(s.i_gt(o.0, self.0), s)).mask_bits() & 0xff
    }
    /// The lanes set in `bits`, packed to the front.
    #[inline(always)]
    pub fn compress(self, bits: u32) -> Self {
        Vi(self.1.i_compress(self.0, bits), self.1)
    }
    /// See [`Simd::i_rotate`].
    #[inline(always)]
    pub fn rotate(self, by: usize) -> Self {
        Vi(self.1.i_rotate(self.0, by), self.1)
    }
    #[inline(always)]
    pub fn mask_bits(self) -> u32 {
        self.1.i_bits(self.0)
    }
    #[inline(always)]
    pub fn shl(self, bits: u32) -> Self {
        Vi(self.1.i_shl(self.0, bits), self.1)
    }
    #[inline(always)]
    pub fn sra(self, bits: u32) -> Self {
        Vi(self.1.i_sra(self.0, bits), self.1)
    }
    #[inline(always)]
    pub fn max(self, o: Self) -> Self {
        Vi(self.1.i_max(self.0, o.0), self.1)
    }
    #[inline(always)]
    pub fn to_f(self) -> Vf<S> {
        Vf(self.1.f_from_i(self.0), self.1)
    }
    #[inline(always)]
    pub fn bits_to_f(self) -> Vf<S> {
        Vf(self.1.f_from_bits(self.0), self.1)
    }
    /// Lanes of `yes` where `mask` is set, of `no` elsewhere.
    #[inline(always)]
    pub fn select(mask: Self, yes: Self, no: Self) -> Self {
        Vi(yes.1.i_select(mask.0, yes.0, no.0), yes.1)
    }
}

macro_rules! binary {
    ($ty:ident, $trait:ident, $method:ident, $op:ident) => {
        impl<S: Simd> $trait for $ty<S> {
            type Output = Self;
            #[inline(always)]
            fn $method(self, o: Self) -> Self {
                $ty(self.1.$op(self.0, o.0), self.1)
            }
        }
    };
}
binary!(Vf, Add, add, f_add);
binary!(Vf, Sub, sub, f_sub);
binary!(Vf, Mul, mul, f_mul);
binary!(Vi, Add, add, i_add);
binary!(Vi, Sub, sub, i_sub);
binary!(Vi, Mul, mul, i_mul);
binary!(Vi, BitAnd, bitand, i_and);
binary!(Vi, BitOr, bitor, i_or);

impl<S: Simd> Mul<f32> for Vf<S> {
    type Output = Self;
    #[inline(always)]
    fn mul(self, o: f32) -> Self {
        self * self.splat_like(o)
    }
}

/// `x^p` for a whole exponent `p` in 1..=1024: with `p = m·2^k`, `m` odd,
/// `x^m` by repeated squaring, then `k` squarings (for the usual powers of
/// two no other multiplication; at most 19 in all, exact to a few ulps),
/// for `G` vectors at once, step by step, so that their chains of squarings
/// overlap.
#[inline(always)]
pub(crate) fn pow_whole_groups<V: Lanes, const G: usize>(x: [V; G], p: u32) -> [V; G] {
    let k = p.trailing_zeros();
    let mut m = p >> k >> 1;
    let mut result = x;
    let mut base = x;
    while m > 0 {
        for g in 0..G {
            base[g] = base[g] * base[g];
            if m & 1 == 1 {
                result[g] = result[g] * base[g];
            }
        }
        m >>= 1;
    }
    for _ in 0..k {
        for r in &mut result {
            *r = *r * *r;
        }
    }
    result
}

/// `x^p` for `x` in [0, 1] and `p > 0`, to about 1e-6 relative error: the
/// specular power, which the scalar path computes with `powf`.
#[inline(always)]
pub(crate) fn pow_unit<S: Simd>(x: Vf<S>, p: f32) -> Vf<S> {
    let s = x.1;
    let one = Vf::splat(s, 1.0);
    // log2(x) = e + log2(m), m in [√½, √2): with t = (m − 1)/(m + 1),
    // log2(m) = 2/ln2 · (t + t³/3 + t⁵/5 + t⁷/7 + t⁹/9), |t| ≤ 0.172.
    let bits = x.bits();
    let sqrt_half = Vi::splat(s, 0x3f35_04f3);
    let exponent = (bits - sqrt_half).sra(23);
    let m = (bits - exponent.shl(23)).bits_to_f();
    let t = (m - one) * (m + one).recip();
    let t2 = t * t;
    let series = ((((t2 * (1.0 / 9.0) + Vf::splat(s, 1.0 / 7.0)) * t2 + Vf::splat(s, 1.0 / 5.0))
        * t2
        + Vf::splat(s, 1.0 / 3.0))
        * t2
        + one)
        * t;
    let log2 = exponent.to_f() + series * (2.0 / std::f32::consts::LN_2);
    // 2^y = 2^i · 2^f with i = round(y), f in [−½, ½], by the Taylor series
    // of e^(f·ln2) to degree 6 (truncation error below 2e-7).
    let y = (log2 * p)
        .max(Vf::splat(s, -127.0))
        .min(Vf::splat(s, 127.0));
    let i = (y + Vf::splat(s, 0.5)).floor();
    let f = y - i;
    const C: [f32; 6] = [
        std::f32::consts::LN_2,
        0.240_226_5,
        5.550_411e-2,
        9.618_129e-3,
        1.333_356e-3,
        1.540_353e-4,
    ];
    let poly = (((((f * C[5] + Vf::splat(s, C[4])) * f + Vf::splat(s, C[3])) * f
        + Vf::splat(s, C[2]))
        * f
        + Vf::splat(s, C[1]))
        * f
        + Vf::splat(s, C[0]))
        * f
        + one;
    let scale = (i.to_i() + Vi::splat(s, 127)).max(Vi::splat(s, 0)).shl(23);
    let result = poly * scale.bits_to_f();
    // Exact zeros stay zero; so does anything below 2^-126.
    let keep = x.gt(Vf::splat(s, 0.0)) & y.gt(Vf::splat(s, -126.0));
    Vf::select(keep, result, Vf::splat(s, 0.0))
}

#[cfg(test)]
mod tests;
