//! The AVX2 backend: one AVX2/FMA instruction per lane operation.

use std::arch::x86_64::*;
use std::marker::PhantomData;

use super::{Apart, Pair, PlaneSolve, Simd, SolvedPlane, Vf, SOLVE_LANES};

/// The AVX2 backend; a value proves the CPU has AVX2 and FMA (and
/// POPCNT, BMI1 and BMI2, which every AVX2 processor has), and whatever
/// its lighting lanes `W` need.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Avx2<W: Width = Ymm>(PhantomData<W>);

/// What [`Simd::F16`] is for an [`Avx2`] backend: the one thing in which
/// its AVX-512 build ([`super::avx512::Zmm`]) differs from its AVX2 one.
pub(crate) trait Width: Copy + Send + Sync + 'static {
    /// The 16 lanes.
    type F16: super::Lanes;
    /// Whether the CPU has what the lanes need (beyond AVX2).
    fn supported() -> bool;
    /// 16 lanes from memory.
    fn load(s: Avx2<Self>, src: &[f32; 16]) -> Self::F16;
    /// [`Simd::apart`]: `work` in a function of its own with this
    /// backend's target features.
    fn apart<K: Apart<Avx2<Self>>>(s: Avx2<Self>, work: K) -> K::Output;
}

/// Lighting in two 256-bit vectors: plain AVX2.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Ymm;

impl Width for Ymm {
    type F16 = Pair<Vf<Avx2<Ymm>>>;
    fn supported() -> bool {
        true
    }
    #[inline(always)]
    fn load(s: Avx2<Ymm>, src: &[f32; 16]) -> Self::F16 {
        Pair::load(s, src)
    }
    #[inline(always)]
    fn apart<K: Apart<Avx2<Ymm>>>(s: Avx2<Ymm>, work: K) -> K::Output {
        #[inline(never)]
        #[target_feature(enable = "avx2,fma,popcnt,bmi1,bmi2")]
        unsafe fn apart<K: Apart<Avx2<Ymm>>>(s: Avx2<Ymm>, work: K) -> K::Output {
            work.run(s)
        }
        // SAFETY: `s` is an `Avx2`: the CPU has AVX2, FMA, POPCNT, BMI1
        // and BMI2, the only requirement of a `target_feature` function.
        unsafe { apart(s, work) }
    }
}

impl<W: Width> Avx2<W> {
    /// Each lane's low three bytes (a pixel's RGB) packed to the front of
    /// its 128-bit half: 12 bytes per half, then 4 zero bytes.
    #[inline(always)]
    fn compact_rgb(self, v: __m256i) -> __m256i {
        // SAFETY: as for the `Simd` impl below: `self` is an `Avx2`.
        unsafe {
            let compact = _mm256_setr_epi8(
                0, 1, 2, 4, 5, 6, 8, 9, 10, 12, 13, 14, -1, -1, -1, -1, //
                0, 1, 2, 4, 5, 6, 8, 9, 10, 12, 13, 14, -1, -1, -1, -1,
            );
            _mm256_shuffle_epi8(v, compact)
        }
    }

    /// Truncated channels, saturated to bytes (0..=255) and packed per
    /// lane as `r | g << 8 | b << 16`: the end of [`Simd::f_to_bytes`].
    #[inline(always)]
    fn pack_bytes(self, r: __m256i, g: __m256i, b: __m256i) -> __m256i {
        // SAFETY: as for the `Simd` impl below: `self` is an `Avx2`.
        unsafe {
            // Per 128-bit half, as bytes with saturation: r0..r3 g0..g3
            // b0..b3 b0..b3 (lanes 4..7 in the upper half), then
            // gathered per pixel.
            let rg = _mm256_packs_epi32(r, g);
            let bb = _mm256_packs_epi32(b, b);
            let planar = _mm256_packus_epi16(rg, bb);
            let per_pixel = _mm256_setr_epi8(
                0, 4, 8, -1, 1, 5, 9, -1, 2, 6, 10, -1, 3, 7, 11, -1, //
                0, 4, 8, -1, 1, 5, 9, -1, 2, 6, 10, -1, 3, 7, 11, -1,
            );
            _mm256_shuffle_epi8(planar, per_pixel)
        }
    }

    pub fn new() -> Option<Avx2<W>> {
        (std::is_x86_feature_detected!("avx2")
            && std::is_x86_feature_detected!("fma")
            && std::is_x86_feature_detected!("popcnt")
            && std::is_x86_feature_detected!("bmi1")
            && std::is_x86_feature_detected!("bmi2")
            && W::supported())
        .then_some(Avx2(PhantomData))
    }
}

// Every method below calls AVX/AVX2 intrinsics. SAFETY (for each
// `unsafe` block in this impl): `self` is an `Avx2`, which only
// `Avx2::new` creates after checking that the CPU has AVX2 and FMA;
// loads and stores go through references to exactly 8 lanes.
impl<W: Width> Simd for Avx2<W> {
    #[inline(always)]
    fn apart<K: Apart<Self>>(self, work: K) -> K::Output {
        W::apart(self, work)
    }

    type F = __m256;
    type I = __m256i;
    type F16 = W::F16;
    /// Four: with 512-bit lanes the full-screen quad's Phong was 7–10 %
    /// faster than with two, the meshes within 1 % (with 8-lane groups,
    /// eight were faster on the quad but slower on the meshes, so the
    /// queue held four of 8).
    const LIT_GROUPS: usize = super::MAX_LIT_GROUPS;

    /// Four planes per vector of `f64`, with [`super::solve_planes`]'s
    /// operations (multiplies and adds, not fused) in its order, and the
    /// same rounding to `f32` (to nearest): the same bits.
    #[inline(always)]
    fn solve_planes(self, p: &PlaneSolve, out: &mut [SolvedPlane]) {
        // SAFETY: see the impl; each load reads 4 lanes of an array of
        // `SOLVE_LANES` from a multiple of 4 below it (the assert), each
        // store writes a `[f32; 4]`.
        unsafe {
            let splat = _mm256_set1_pd;
            let (gx1, gx2) = (splat(p.gx[0]), splat(p.gx[1]));
            let (gy1, gy2) = (splat(p.gy[0]), splat(p.gy[1]));
            let (ox, oy) = (splat(p.origin[0]), splat(p.origin[1]));
            let count = out.len().min(SOLVE_LANES);
            for base in (0..count).step_by(4) {
                assert!(base + 4 <= SOLVE_LANES);
                let q0 = _mm256_loadu_pd(p.q[0][base..].as_ptr());
                let q1 = _mm256_loadu_pd(p.q[1][base..].as_ptr());
                let q2 = _mm256_loadu_pd(p.q[2][base..].as_ptr());
                let (d1, d2) = (_mm256_sub_pd(q1, q0), _mm256_sub_pd(q2, q0));
                let dx = _mm256_add_pd(_mm256_mul_pd(d1, gx1), _mm256_mul_pd(d2, gx2));
                let dy = _mm256_add_pd(_mm256_mul_pd(d1, gy1), _mm256_mul_pd(d2, gy2));
                let at = _mm256_add_pd(
                    _mm256_add_pd(q0, _mm256_mul_pd(dx, ox)),
                    _mm256_mul_pd(dy, oy),
                );
                let mut lanes = [[0f32; 4]; 3];
                _mm_storeu_ps(lanes[0].as_mut_ptr(), _mm256_cvtpd_ps(at));
                _mm_storeu_ps(lanes[1].as_mut_ptr(), _mm256_cvtpd_ps(dx));
                _mm_storeu_ps(lanes[2].as_mut_ptr(), _mm256_cvtpd_ps(dy));
                for (i, out) in out[base..count].iter_mut().take(4).enumerate() {
                    *out = [lanes[0][i], lanes[1][i], lanes[2][i]];
                }
            }
        }
    }

    #[inline(always)]
    fn f16_load(self, src: &[f32; 16]) -> W::F16 {
        W::load(self, src)
    }

    #[inline(always)]
    fn f_splat(self, v: f32) -> __m256 {
        // SAFETY: see the impl.
        unsafe { _mm256_set1_ps(v) }
    }
    #[inline(always)]
    fn f_add(self, a: __m256, b: __m256) -> __m256 {
        // SAFETY: see the impl.
        unsafe { _mm256_add_ps(a, b) }
    }
    #[inline(always)]
    fn f_sub(self, a: __m256, b: __m256) -> __m256 {
        // SAFETY: see the impl.
        unsafe { _mm256_sub_ps(a, b) }
    }
    #[inline(always)]
    fn f_mul(self, a: __m256, b: __m256) -> __m256 {
        // SAFETY: see the impl.
        unsafe { _mm256_mul_ps(a, b) }
    }
    #[inline(always)]
    fn f_mul_add(self, a: __m256, b: __m256, c: __m256) -> __m256 {
        // SAFETY: see the impl (FMA is checked with AVX2).
        unsafe { _mm256_fmadd_ps(a, b, c) }
    }
    #[inline(always)]
    fn f_min(self, a: __m256, b: __m256) -> __m256 {
        // vminps returns the second operand when either is NaN: `a < b ? a : b`.
        // SAFETY: see the impl.
        unsafe { _mm256_min_ps(a, b) }
    }
    #[inline(always)]
    fn f_max(self, a: __m256, b: __m256) -> __m256 {
        // SAFETY: see the impl.
        unsafe { _mm256_max_ps(a, b) }
    }
    #[inline(always)]
    fn f_rsqrt(self, a: __m256) -> __m256 {
        // The 12-bit estimate and one Newton step: (r/2)·(3 − a·r·r),
        // the bracket in one fused step.
        // SAFETY: see the impl (FMA is checked with AVX2).
        unsafe {
            let r = _mm256_rsqrt_ps(a);
            let three_minus = _mm256_fnmadd_ps(_mm256_mul_ps(a, r), r, _mm256_set1_ps(3.0));
            _mm256_mul_ps(_mm256_mul_ps(r, _mm256_set1_ps(0.5)), three_minus)
        }
    }
    #[inline(always)]
    fn f_recip(self, a: __m256) -> __m256 {
        // The 12-bit estimate and one Newton step, r·(2 − a·r), as
        // r + r·(1 − a·r): two fused steps.
        // SAFETY: see the impl (FMA is checked with AVX2).
        unsafe {
            let r = _mm256_rcp_ps(a);
            let error = _mm256_fnmadd_ps(a, r, _mm256_set1_ps(1.0));
            _mm256_fmadd_ps(r, error, r)
        }
    }
    #[inline(always)]
    fn f_floor(self, a: __m256) -> __m256 {
        // SAFETY: see the impl.
        unsafe { _mm256_floor_ps(a) }
    }
    #[inline(always)]
    fn f_lt(self, a: __m256, b: __m256) -> __m256i {
        // SAFETY: see the impl.
        unsafe { _mm256_castps_si256(_mm256_cmp_ps::<_CMP_LT_OQ>(a, b)) }
    }
    #[inline(always)]
    fn f_gt(self, a: __m256, b: __m256) -> __m256i {
        // SAFETY: see the impl.
        unsafe { _mm256_castps_si256(_mm256_cmp_ps::<_CMP_GT_OQ>(a, b)) }
    }
    #[inline(always)]
    fn f_select(self, m: __m256i, a: __m256, b: __m256) -> __m256 {
        // SAFETY: see the impl.
        unsafe { _mm256_blendv_ps(b, a, _mm256_castsi256_ps(m)) }
    }
    #[inline(always)]
    fn f_load(self, src: &[f32; 8]) -> __m256 {
        // SAFETY: see the impl.
        unsafe { _mm256_loadu_ps(src.as_ptr()) }
    }
    #[inline(always)]
    fn f_store(self, v: __m256, dst: &mut [f32; 8]) {
        // SAFETY: see the impl.
        unsafe { _mm256_storeu_ps(dst.as_mut_ptr(), v) }
    }
    #[inline(always)]
    fn f_to_i(self, a: __m256) -> __m256i {
        // SAFETY: see the impl.
        unsafe { _mm256_cvttps_epi32(a) }
    }
    #[inline(always)]
    fn f_bits(self, a: __m256) -> __m256i {
        // SAFETY: see the impl.
        unsafe { _mm256_castps_si256(a) }
    }
    #[inline(always)]
    fn f_from_i(self, a: __m256i) -> __m256 {
        // SAFETY: see the impl.
        unsafe { _mm256_cvtepi32_ps(a) }
    }
    #[inline(always)]
    fn f_from_bits(self, a: __m256i) -> __m256 {
        // SAFETY: see the impl.
        unsafe { _mm256_castsi256_ps(a) }
    }
    #[inline(always)]
    fn f_lanes(self) -> __m256 {
        // SAFETY: see the impl.
        unsafe { _mm256_setr_ps(0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0) }
    }

    #[inline(always)]
    fn i_splat(self, v: i32) -> __m256i {
        // SAFETY: see the impl.
        unsafe { _mm256_set1_epi32(v) }
    }
    #[inline(always)]
    fn i_add(self, a: __m256i, b: __m256i) -> __m256i {
        // SAFETY: see the impl.
        unsafe { _mm256_add_epi32(a, b) }
    }
    #[inline(always)]
    fn i_sub(self, a: __m256i, b: __m256i) -> __m256i {
        // SAFETY: see the impl.
        unsafe { _mm256_sub_epi32(a, b) }
    }
    #[inline(always)]
    fn i_and(self, a: __m256i, b: __m256i) -> __m256i {
        // SAFETY: see the impl.
        unsafe { _mm256_and_si256(a, b) }
    }
    #[inline(always)]
    fn i_or(self, a: __m256i, b: __m256i) -> __m256i {
        // SAFETY: see the impl.
        unsafe { _mm256_or_si256(a, b) }
    }
    #[inline(always)]
    fn i_max(self, a: __m256i, b: __m256i) -> __m256i {
        // SAFETY: see the impl.
        unsafe { _mm256_max_epi32(a, b) }
    }
    #[inline(always)]
    fn i_mul(self, a: __m256i, b: __m256i) -> __m256i {
        // SAFETY: see the impl.
        unsafe { _mm256_mullo_epi32(a, b) }
    }
    #[inline(always)]
    fn i_gt(self, a: __m256i, b: __m256i) -> __m256i {
        // SAFETY: see the impl.
        unsafe { _mm256_cmpgt_epi32(a, b) }
    }
    #[inline(always)]
    fn i_lanes(self) -> __m256i {
        // SAFETY: see the impl.
        unsafe { _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7) }
    }
    #[inline(always)]
    fn i_shl(self, a: __m256i, bits: u32) -> __m256i {
        // SAFETY: see the impl.
        unsafe { _mm256_sll_epi32(a, _mm_cvtsi32_si128(bits as i32)) }
    }
    #[inline(always)]
    fn i_sra(self, a: __m256i, bits: u32) -> __m256i {
        // SAFETY: see the impl.
        unsafe { _mm256_sra_epi32(a, _mm_cvtsi32_si128(bits as i32)) }
    }
    #[inline(always)]
    fn i_select(self, m: __m256i, a: __m256i, b: __m256i) -> __m256i {
        // SAFETY: see the impl.
        unsafe { _mm256_blendv_epi8(b, a, m) }
    }
    #[inline(always)]
    fn i_load(self, src: &[i32; 8]) -> __m256i {
        // SAFETY: see the impl.
        unsafe { _mm256_loadu_si256(src.as_ptr().cast()) }
    }
    #[inline(always)]
    fn i_store(self, v: __m256i, dst: &mut [i32; 8]) {
        // SAFETY: see the impl.
        unsafe { _mm256_storeu_si256(dst.as_mut_ptr().cast(), v) }
    }
    #[inline(always)]
    fn i_bits(self, a: __m256i) -> u32 {
        // SAFETY: see the impl.
        unsafe { _mm256_movemask_ps(_mm256_castsi256_ps(a)) as u32 }
    }
    #[inline(always)]
    fn i_from_bits(self, bits: u32) -> __m256i {
        // SAFETY: see the impl.
        unsafe {
            let lane_bits = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
            let set = _mm256_and_si256(_mm256_set1_epi32(bits as i32), lane_bits);
            _mm256_cmpeq_epi32(set, lane_bits)
        }
    }

    #[inline(always)]
    fn f_compress(self, v: __m256, bits: u32) -> __m256 {
        let order = &super::portable::COMPRESS[bits as usize & 255];
        // SAFETY: see the impl; `order` is 8 lanes.
        unsafe { _mm256_permutevar8x32_ps(v, _mm256_loadu_si256(order.as_ptr().cast())) }
    }
    #[inline(always)]
    fn i_compress(self, v: __m256i, bits: u32) -> __m256i {
        let order = &super::portable::COMPRESS[bits as usize & 255];
        // SAFETY: see the impl; `order` is 8 lanes.
        unsafe { _mm256_permutevar8x32_epi32(v, _mm256_loadu_si256(order.as_ptr().cast())) }
    }
    #[inline(always)]
    fn i_rotate(self, v: __m256i, by: usize) -> __m256i {
        let order = &super::portable::ROTATE[by & 7];
        // SAFETY: see the impl; `order` is 8 lanes.
        unsafe { _mm256_permutevar8x32_epi32(v, _mm256_loadu_si256(order.as_ptr().cast())) }
    }

    #[inline(always)]
    fn f_to_bytes(self, r: __m256, g: __m256, b: __m256) -> __m256i {
        // SAFETY: see the impl.
        unsafe {
            // `min(top, v)` keeps NaN (the second operand wins when
            // either is NaN), which truncates to i32::MIN and so
            // saturates to 0; values past 255.5 become 255.5, so the
            // truncation stays within i32.
            let top = _mm256_set1_ps(255.5);
            let [r, g, b] = [r, g, b].map(|c| _mm256_cvttps_epi32(_mm256_min_ps(top, c)));
            self.pack_bytes(r, g, b)
        }
    }

    #[inline(always)]
    fn f_to_bytes_below(self, r: __m256, g: __m256, b: __m256) -> __m256i {
        // SAFETY: see the impl.
        unsafe {
            // No guard: below 2^31 the truncation stays within i32 (NaN
            // and anything at or below -2^31 give i32::MIN, saturated to
            // 0 as with the guard).
            let [r, g, b] = [
                _mm256_cvttps_epi32(r),
                _mm256_cvttps_epi32(g),
                _mm256_cvttps_epi32(b),
            ];
            self.pack_bytes(r, g, b)
        }
    }

    #[inline(always)]
    fn i_store_rgb(self, v: __m256i, dst: &mut [u8; 24]) {
        // SAFETY: see the impl; the first store writes bytes 0..16, the
        // second and third 12..20 and 20..24, all within `dst`.
        unsafe {
            let packed = self.compact_rgb(v);
            let low = _mm256_castsi256_si128(packed);
            let high = _mm256_extracti128_si256::<1>(packed);
            let p = dst.as_mut_ptr();
            _mm_storeu_si128(p.cast(), low);
            _mm_storel_epi64(p.add(12).cast(), high);
            (p.add(20) as *mut i32).write_unaligned(_mm_extract_epi32::<2>(high));
        }
    }

    #[inline(always)]
    fn i_stream_rgb(self, v: [__m256i; 4], dst: &mut [u8; 96]) {
        // SAFETY: see the impl; the three 32-byte stores write bytes
        // 0..96 of `dst`, the streaming ones only at a 32-byte aligned
        // address, as they require.
        unsafe {
            // (No closures here: see `Surface::radiance`.)
            let (c0, c1) = (self.compact_rgb(v[0]), self.compact_rgb(v[1]));
            let (c2, c3) = (self.compact_rgb(v[2]), self.compact_rgb(v[3]));
            // Each block's 24 bytes are its dwords 0, 1, 2, 4, 5, 6 now.
            // Bytes 0..32: block 0 whole, block 1's first 8 bytes.
            let out0 = _mm256_blend_epi32::<0b1100_0000>(
                _mm256_permutevar8x32_epi32(c0, _mm256_setr_epi32(0, 1, 2, 4, 5, 6, 0, 0)),
                _mm256_permutevar8x32_epi32(c1, _mm256_setr_epi32(0, 0, 0, 0, 0, 0, 0, 1)),
            );
            // 32..64: block 1's last 16 bytes, block 2's first 16.
            let out1 = _mm256_blend_epi32::<0b1111_0000>(
                _mm256_permutevar8x32_epi32(c1, _mm256_setr_epi32(2, 4, 5, 6, 0, 0, 0, 0)),
                _mm256_permutevar8x32_epi32(c2, _mm256_setr_epi32(0, 0, 0, 0, 0, 1, 2, 4)),
            );
            // 64..96: block 2's last 8 bytes, block 3 whole.
            let out2 = _mm256_blend_epi32::<0b1111_1100>(
                _mm256_permutevar8x32_epi32(c2, _mm256_setr_epi32(5, 6, 0, 0, 0, 0, 0, 0)),
                _mm256_permutevar8x32_epi32(c3, _mm256_setr_epi32(0, 0, 0, 1, 2, 4, 5, 6)),
            );
            let p = dst.as_mut_ptr().cast::<__m256i>();
            if (p as usize).is_multiple_of(32) {
                _mm256_stream_si256(p, out0);
                _mm256_stream_si256(p.add(1), out1);
                _mm256_stream_si256(p.add(2), out2);
            } else {
                _mm256_storeu_si256(p, out0);
                _mm256_storeu_si256(p.add(1), out1);
                _mm256_storeu_si256(p.add(2), out2);
            }
        }
    }

    #[inline(always)]
    fn store_fence(self) {
        // SAFETY: see the impl (SSE, which every AVX2 processor has).
        unsafe { _mm_sfence() }
    }
}
