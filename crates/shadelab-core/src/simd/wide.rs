//! Lanes of any width for the reflection model: [`Lanes`], what
//! `shade/lanes.rs` needs of a vector of `f32`, and [`Pair`], 16 lanes as
//! two vectors of 8.
//!
//! The rasterizer's blocks are 8 pixels wide ([`Vf`]), but Phong's queued
//! fragments are lit 16 at a time ([`Simd::F16`]): one AVX-512 register
//! where the processor has two 512-bit FMA units (Intel's server cores do
//! the work of two 256-bit operations in the time of one), else a [`Pair`]
//! of the backend's 8 lanes, which compiles to exactly what two blocks of
//! 8 lit side by side did before. Every width computes the same operations
//! in the same order, so the colours are bit for bit the same.

use std::ops::{Add, BitAnd, Mul, Sub};

use super::{pow_unit, Simd, Vf, Vi};

/// A vector of `f32` lanes with what the reflection model needs.
pub(crate) trait Lanes:
    Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + Mul<f32, Output = Self>
{
    /// One truth value per lane, from comparisons.
    type Mask: Copy + BitAnd<Output = Self::Mask>;
    /// How many lanes.
    const LANES: usize;
    /// `v` in every lane.
    fn splat_like(self, v: f32) -> Self;
    /// `v[0]` in the first half of the lanes, `v[1]` in the second.
    fn halves(self, v: [f32; 2]) -> Self;
    /// `self·m + a`, fused where the backend can.
    fn mul_add(self, m: Self, a: Self) -> Self;
    /// `self < o ? self : o` (so a NaN in `self` gives `o`).
    fn min(self, o: Self) -> Self;
    /// `self > o ? self : o` (so a NaN in `self` gives `o`).
    fn max(self, o: Self) -> Self;
    /// `1 / √self`, see [`Simd::f_rsqrt`].
    fn rsqrt(self) -> Self;
    /// `1 / self`, see [`Simd::f_recip`].
    fn recip(self) -> Self;
    /// Where `self > o`.
    fn gt(self, o: Self) -> Self::Mask;
    /// Bit `i` set where lane `i` of `mask` is true.
    fn mask_bits(mask: Self::Mask) -> u32;
    /// Lanes of `yes` where `mask` is set, of `no` elsewhere.
    fn select(mask: Self::Mask, yes: Self, no: Self) -> Self;
    /// [`pow_unit`] of each lane.
    fn pow_unit(self, p: f32) -> Self;
    /// `f` of each lane, one at a time (for rare cases).
    fn map(self, f: impl Fn(f32) -> f32) -> Self;
    /// The lanes into `dst`, `LANES` long. Only the AVX-512 lanes and the
    /// tests call it: unused in a WebAssembly build.
    #[cfg_attr(not(any(test, target_arch = "x86_64")), allow(dead_code))]
    fn store_to(self, dst: &mut [f32]);
    /// Channels in byte units plus one half to packed colours (see
    /// [`Simd::f_to_bytes`]), stored into `dst`, `LANES` long.
    fn store_bytes(r: Self, g: Self, b: Self, dst: &mut [i32]);
    /// As [`Lanes::store_bytes`], for channels whose lanes are all below
    /// 2^31 or NaN (never +∞), see [`Simd::f_to_bytes_below`].
    fn store_bytes_below(r: Self, g: Self, b: Self, dst: &mut [i32]);
    /// Whether [`Lanes::store_bytes_within`] is cheaper than
    /// [`Lanes::store_bytes_below`] here (it shifts where the packs
    /// shuffle): only then does `fill_span` look for rows of bytes, and
    /// give the span's blocks of 8 the row's w (see
    /// `raster/tiled/band/pairs.rs`). Forced onto the AVX2 lanes, those
    /// made the 1080p Gouraud quad 10 % slower there.
    const SHIFTS_BYTES: bool = false;
    /// As [`Lanes::store_bytes`], for channels whose every lane lies in
    /// `[0, 256)`: each truncates to its byte, with nothing to saturate, so
    /// backends whose packs shuffle may shift the bytes into place instead
    /// (the AVX-512 lanes). See `fill_span` in
    /// `raster/tiled/band/pairs.rs` for who may call it.
    #[inline(always)]
    fn store_bytes_within(r: Self, g: Self, b: Self, dst: &mut [i32]) {
        Self::store_bytes_below(r, g, b, dst)
    }
}

impl<S: Simd> Lanes for Vf<S> {
    type Mask = Vi<S>;
    const LANES: usize = 8;
    #[inline(always)]
    fn splat_like(self, v: f32) -> Self {
        Vf::splat(self.1, v)
    }
    #[inline(always)]
    fn halves(self, v: [f32; 2]) -> Self {
        Vf::load(self.1, &std::array::from_fn(|i| v[i / 4]))
    }
    #[inline(always)]
    fn mul_add(self, m: Self, a: Self) -> Self {
        Vf(self.1.f_mul_add(self.0, m.0, a.0), self.1)
    }
    #[inline(always)]
    fn min(self, o: Self) -> Self {
        Vf(self.1.f_min(self.0, o.0), self.1)
    }
    #[inline(always)]
    fn max(self, o: Self) -> Self {
        Vf(self.1.f_max(self.0, o.0), self.1)
    }
    #[inline(always)]
    fn rsqrt(self) -> Self {
        Vf(self.1.f_rsqrt(self.0), self.1)
    }
    #[inline(always)]
    fn recip(self) -> Self {
        Vf(self.1.f_recip(self.0), self.1)
    }
    #[inline(always)]
    fn gt(self, o: Self) -> Vi<S> {
        Vi(self.1.f_gt(self.0, o.0), self.1)
    }
    #[inline(always)]
    fn mask_bits(mask: Vi<S>) -> u32 {
        mask.mask_bits()
    }
    #[inline(always)]
    fn select(mask: Vi<S>, yes: Self, no: Self) -> Self {
        Vf(yes.1.f_select(mask.0, yes.0, no.0), yes.1)
    }
    #[inline(always)]
    fn pow_unit(self, p: f32) -> Self {
        pow_unit(self, p)
    }
    #[inline(always)]
    fn map(self, f: impl Fn(f32) -> f32) -> Self {
        let mut lanes = [0.0; 8];
        self.store(&mut lanes);
        Vf::load(self.1, &lanes.map(f))
    }
    #[inline(always)]
    fn store_to(self, dst: &mut [f32]) {
        self.store(dst.try_into().unwrap())
    }
    #[inline(always)]
    fn store_bytes(r: Self, g: Self, b: Self, dst: &mut [i32]) {
        let s = r.1;
        s.i_store(s.f_to_bytes(r.0, g.0, b.0), dst.try_into().unwrap());
    }
    #[inline(always)]
    fn store_bytes_below(r: Self, g: Self, b: Self, dst: &mut [i32]) {
        let s = r.1;
        s.i_store(s.f_to_bytes_below(r.0, g.0, b.0), dst.try_into().unwrap());
    }
}

/// Twice the lanes of `V`: each operation done on both halves.
#[derive(Clone, Copy)]
pub(crate) struct Pair<V>(pub V, pub V);

impl<S: Simd> Pair<Vf<S>> {
    /// 16 lanes from memory, as two vectors of 8.
    #[inline(always)]
    pub fn load(s: S, src: &[f32; 16]) -> Self {
        let (low, high) = src.split_at(8);
        Pair(
            Vf::load(s, low.try_into().unwrap()),
            Vf::load(s, high.try_into().unwrap()),
        )
    }
}

macro_rules! pair_operator {
    ($trait:ident, $method:ident) => {
        impl<V: $trait<Output = V>> $trait for Pair<V> {
            type Output = Self;
            #[inline(always)]
            fn $method(self, o: Self) -> Self {
                Pair(self.0.$method(o.0), self.1.$method(o.1))
            }
        }
    };
}
pair_operator!(Add, add);
pair_operator!(Sub, sub);
pair_operator!(Mul, mul);
pair_operator!(BitAnd, bitand);

impl<V: Lanes> Mul<f32> for Pair<V> {
    type Output = Self;
    #[inline(always)]
    fn mul(self, o: f32) -> Self {
        Pair(self.0 * o, self.1 * o)
    }
}

impl<V: Lanes> Lanes for Pair<V> {
    type Mask = Pair<V::Mask>;
    const LANES: usize = 2 * V::LANES;
    #[inline(always)]
    fn splat_like(self, v: f32) -> Self {
        Pair(self.0.splat_like(v), self.1.splat_like(v))
    }
    #[inline(always)]
    fn halves(self, v: [f32; 2]) -> Self {
        Pair(self.0.splat_like(v[0]), self.1.splat_like(v[1]))
    }
    #[inline(always)]
    fn mul_add(self, m: Self, a: Self) -> Self {
        Pair(self.0.mul_add(m.0, a.0), self.1.mul_add(m.1, a.1))
    }
    #[inline(always)]
    fn min(self, o: Self) -> Self {
        Pair(self.0.min(o.0), self.1.min(o.1))
    }
    #[inline(always)]
    fn max(self, o: Self) -> Self {
        Pair(self.0.max(o.0), self.1.max(o.1))
    }
    #[inline(always)]
    fn rsqrt(self) -> Self {
        Pair(self.0.rsqrt(), self.1.rsqrt())
    }
    #[inline(always)]
    fn recip(self) -> Self {
        Pair(self.0.recip(), self.1.recip())
    }
    #[inline(always)]
    fn gt(self, o: Self) -> Self::Mask {
        Pair(self.0.gt(o.0), self.1.gt(o.1))
    }
    #[inline(always)]
    fn mask_bits(mask: Self::Mask) -> u32 {
        V::mask_bits(mask.0) | V::mask_bits(mask.1) << V::LANES
    }
    #[inline(always)]
    fn select(mask: Self::Mask, yes: Self, no: Self) -> Self {
        Pair(
            V::select(mask.0, yes.0, no.0),
            V::select(mask.1, yes.1, no.1),
        )
    }
    #[inline(always)]
    fn pow_unit(self, p: f32) -> Self {
        Pair(self.0.pow_unit(p), self.1.pow_unit(p))
    }
    #[inline(always)]
    fn map(self, f: impl Fn(f32) -> f32) -> Self {
        Pair(self.0.map(&f), self.1.map(&f))
    }
    #[inline(always)]
    fn store_to(self, dst: &mut [f32]) {
        let (low, high) = dst.split_at_mut(V::LANES);
        self.0.store_to(low);
        self.1.store_to(high);
    }
    #[inline(always)]
    fn store_bytes(r: Self, g: Self, b: Self, dst: &mut [i32]) {
        let (low, high) = dst.split_at_mut(V::LANES);
        V::store_bytes(r.0, g.0, b.0, low);
        V::store_bytes(r.1, g.1, b.1, high);
    }
    #[inline(always)]
    fn store_bytes_below(r: Self, g: Self, b: Self, dst: &mut [i32]) {
        let (low, high) = dst.split_at_mut(V::LANES);
        V::store_bytes_below(r.0, g.0, b.0, low);
        V::store_bytes_below(r.1, g.1, b.1, high);
    }
    const SHIFTS_BYTES: bool = V::SHIFTS_BYTES;
    #[inline(always)]
    fn store_bytes_within(r: Self, g: Self, b: Self, dst: &mut [i32]) {
        let (low, high) = dst.split_at_mut(V::LANES);
        V::store_bytes_within(r.0, g.0, b.0, low);
        V::store_bytes_within(r.1, g.1, b.1, high);
    }
}
