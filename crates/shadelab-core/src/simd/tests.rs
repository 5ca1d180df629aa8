use super::*;

struct Pow([f32; 8], f32);

impl Kernel for Pow {
    type Output = [f32; 8];
    #[inline(always)]
    fn run<S: Simd>(self, s: S) -> [f32; 8] {
        let mut out = [0.0; 8];
        pow_unit(Vf::load(s, &self.0), self.1).store(&mut out);
        out
    }
}

#[test]
fn pow_unit_matches_powf() {
    for level in SimdLevel::supported() {
        for p in [0.5f32, 1.0, 2.0, 7.5, 32.0, 128.0, 1000.0] {
            let mut worst = 0f32;
            for k in 0..=500 {
                let xs: [f32; 8] = std::array::from_fn(|i| (k * 8 + i) as f32 / 4000.0);
                let got = dispatch(level, Pow(xs, p));
                for i in 0..8 {
                    worst = worst.max((got[i] - xs[i].powf(p)).abs());
                }
            }
            assert!(
                worst < 2e-5,
                "{level:?}, p = {p}: worst absolute error {worst}"
            );
        }
    }
}

#[test]
fn both_levels_agree() {
    let x = [0.0, 0.1, 0.25, 0.5, 0.75, 0.9, 0.99, 1.0];
    let portable = dispatch(SimdLevel::Portable, Pow(x, 32.0));
    let best = dispatch(SimdLevel::detect(), Pow(x, 32.0));
    for i in 0..8 {
        assert!(
            (portable[i] - best[i]).abs() <= 1e-6,
            "{portable:?} vs {best:?}"
        );
    }
}

struct Lanes;

impl Kernel for Lanes {
    type Output = ([f32; 8], u32, u32, [i32; 8]);
    #[inline(always)]
    fn run<S: Simd>(self, s: S) -> ([f32; 8], u32, u32, [i32; 8]) {
        let mask = Vi::from_mask_bits(s, 0b1010_0110);
        let values = Vf::load(s, &[0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0]);
        let mut packed = [0.0; 8];
        values.compress(0b1010_0110).store(&mut packed);
        let ramp = Vi::ramp(s) * Vi::splat(s, 3);
        let mut above = [0; 8];
        s.i_store(ramp.gt(Vi::splat(s, 7)).0, &mut above);
        (
            packed,
            mask.mask_bits(),
            (Vi::splat(s, -1) & mask).mask_bits(),
            above,
        )
    }
}

struct Bytes([f32; 8]);

impl Kernel for Bytes {
    type Output = [i32; 8];
    #[inline(always)]
    fn run<S: Simd>(self, s: S) -> [i32; 8] {
        let v = Vf::load(s, &self.0);
        let mut out = [0; 8];
        let packed = Vf::to_bytes(v, v + Vf::splat(s, 1.0), Vf::splat(s, 7.9));
        s.i_store(packed.0, &mut out);
        out
    }
}

/// A channel in byte units as the backends store it: truncated, NaN and
/// negatives to 0, 255 and above to 255.
fn byte(c: f32) -> i32 {
    if c >= 255.0 {
        255
    } else if c >= 0.0 {
        c as i32
    } else {
        0
    }
}

#[test]
fn to_bytes_truncates_and_saturates() {
    let v = [0.49, 0.5, 254.99, 255.5, 256.0, -3.0, f32::NAN, 3e9];
    for level in SimdLevel::supported() {
        let got = dispatch(level, Bytes(v));
        let want = v.map(|r| byte(r) | byte(r + 1.0) << 8 | 7 << 16);
        assert_eq!(got, want, "{level:?}");
    }
}

/// The same through the 16 lanes Phong's queue and the pairs of blocks
/// store ([`Lanes::store_bytes`] of [`Simd::F16`]), each byte in every
/// position; with `true`, [`Lanes::store_bytes_below`].
struct Bytes16([f32; 16], bool);

impl Kernel for Bytes16 {
    type Output = [i32; 16];
    #[inline(always)]
    fn run<S: Simd>(self, s: S) -> [i32; 16] {
        let r = s.f16_load(&self.0);
        let g = s.f16_load(&std::array::from_fn(|i| self.0[(i + 5) % 16]));
        let b = s.f16_load(&std::array::from_fn(|i| self.0[(i + 11) % 16]));
        let mut out = [0; 16];
        if self.1 {
            <S::F16 as crate::simd::Lanes>::store_bytes_below(r, g, b, &mut out);
        } else {
            <S::F16 as crate::simd::Lanes>::store_bytes(r, g, b, &mut out);
        }
        out
    }
}

/// [`Bytes16`] of `v` against [`byte`], with the guard and, if `below`,
/// without it too.
fn check_bytes16(v: [f32; 16], below: bool) {
    let want: [i32; 16] = std::array::from_fn(|i| {
        byte(v[i]) | byte(v[(i + 5) % 16]) << 8 | byte(v[(i + 11) % 16]) << 16
    });
    for level in SimdLevel::supported() {
        assert_eq!(dispatch(level, Bytes16(v, false)), want, "{level:?}");
        if below {
            assert_eq!(dispatch(level, Bytes16(v, true)), want, "{level:?}, below");
        }
    }
}

#[test]
fn store_bytes_truncates_and_saturates_in_16_lanes() {
    let v = [
        0.49,
        0.5,
        254.99,
        255.5,
        256.0,
        -3.0,
        f32::NAN,
        3e9,
        1.0,
        17.75,
        128.0,
        -0.0,
        99.9,
        f32::INFINITY,
        f32::NEG_INFINITY,
        200.5,
    ];
    check_bytes16(v, false);
    // Without the guard, for channels below 2^31 or NaN (what
    // `planes_below` vouches for): the same bytes, up to the largest `f32`
    // below 2^31 and down past -2^31.
    let mut below = v;
    (below[7], below[10], below[13]) = (2_147_483_520.0, 65_536.5, -3e9);
    check_bytes16(below, true);
}

/// [`Lanes::store_bytes_within`] of 16 lanes, and [`Lanes::halves`].
struct BytesWithin([[f32; 16]; 3]);

impl Kernel for BytesWithin {
    type Output = ([i32; 16], [f32; 16]);
    #[inline(always)]
    fn run<S: Simd>(self, s: S) -> ([i32; 16], [f32; 16]) {
        use crate::simd::Lanes;
        let [r, g, b] = self.0.map(|v| s.f16_load(&v));
        let mut out = [0; 16];
        <S::F16 as Lanes>::store_bytes_within(r, g, b, &mut out);
        let mut halves = [0.0; 16];
        r.halves([1.5, -2.0]).store_to(&mut halves);
        (out, halves)
    }
}

#[test]
fn store_bytes_within_gives_the_bytes_of_channels_in_0_256() {
    let edges = [
        0.0,
        -0.0,
        f32::from_bits(1),
        1e-40,
        0.49,
        0.5,
        0.999_999_94,
        1.0,
        17.75,
        127.996,
        128.0,
        254.99,
        255.0,
        255.5,
        255.999_98,
        200.5,
    ];
    // Each edge in every lane of each channel, then a sweep of [0, 256)
    // in steps of 1/64 (each byte with fractions near both its ends).
    let mut cases: Vec<[f32; 16]> = (0..16)
        .map(|k| std::array::from_fn(|i| edges[(i + k) % 16]))
        .collect();
    cases.extend((0..1024).map(|k| std::array::from_fn(|i| (k * 16 + i) as f32 / 64.0)));
    let halves: [f32; 16] = std::array::from_fn(|i| if i < 8 { 1.5 } else { -2.0 });
    for level in SimdLevel::supported() {
        for (k, &r) in cases.iter().enumerate() {
            let (g, b) = (cases[(k + 1) % cases.len()], cases[(k + 7) % cases.len()]);
            let want: [i32; 16] =
                std::array::from_fn(|i| byte(r[i]) | byte(g[i]) << 8 | byte(b[i]) << 16);
            let got = dispatch(level, BytesWithin([r, g, b]));
            assert_eq!(got, (want, halves), "{level:?}, case {k}");
        }
    }
}

#[test]
fn lane_operations() {
    for level in SimdLevel::supported() {
        let (packed, bits, and, above) = dispatch(level, Lanes);
        assert_eq!(packed[..4], [1.0, 2.0, 5.0, 7.0], "{level:?}");
        assert_eq!((bits, and), (0b1010_0110, 0b1010_0110), "{level:?}");
        assert_eq!(above, [0, 0, 0, -1, -1, -1, -1, -1], "{level:?}");
    }
}

struct Compress(u32);

impl Kernel for Compress {
    type Output = ([f32; 8], [i32; 8]);
    #[inline(always)]
    fn run<S: Simd>(self, s: S) -> ([f32; 8], [i32; 8]) {
        let (mut f, mut i) = ([0.0; 8], [0; 8]);
        Vf::lanes(s).compress(self.0).store(&mut f);
        s.i_store((Vi::ramp(s) * Vi::splat(s, -3)).compress(self.0).0, &mut i);
        (f, i)
    }
}

/// Every mask packs the same lanes in every backend (the best one here is
/// AVX2 natively, `simd128` in a WebAssembly build with it).
#[test]
fn compress_every_mask() {
    for bits in 0..256u32 {
        let n = bits.count_ones() as usize;
        let (f, i) = dispatch(SimdLevel::detect(), Compress(bits));
        let want: Vec<i32> = (0..8).filter(|k| bits >> k & 1 == 1).collect();
        assert_eq!(
            f[..n],
            want.iter().map(|&k| k as f32).collect::<Vec<_>>()[..],
            "{bits:#b}"
        );
        assert_eq!(
            i[..n],
            want.iter().map(|&k| -3 * k).collect::<Vec<_>>()[..],
            "{bits:#b}"
        );
    }
}

struct Rotate(usize);

impl Kernel for Rotate {
    type Output = ([f32; 8], [i32; 8]);
    #[inline(always)]
    fn run<S: Simd>(self, s: S) -> ([f32; 8], [i32; 8]) {
        let (mut f, mut i) = ([0.0; 8], [0; 8]);
        (Vf::lanes(s) + Vf::splat(s, 0.5))
            .rotate(self.0)
            .store(&mut f);
        s.i_store((Vi::ramp(s) * Vi::splat(s, -3)).rotate(self.0).0, &mut i);
        (f, i)
    }
}

/// Every shift moves the lanes up and wraps the last ones round to the
/// front, in every backend.
#[test]
fn rotate_every_shift() {
    for level in SimdLevel::supported() {
        for by in 0..8 {
            let (f, i) = dispatch(level, Rotate(by));
            let source: [usize; 8] = std::array::from_fn(|lane| (lane + 8 - by) % 8);
            assert_eq!(f, source.map(|k| k as f32 + 0.5), "{level:?}, by {by}");
            assert_eq!(i, source.map(|k| -3 * k as i32), "{level:?}, by {by}");
        }
    }
}

#[test]
fn scatter_writes_in_lane_order() {
    let mut dst = [0; 12];
    scatter(
        &[1, 2, 3, 4, 5, 6, 7, 8],
        &[11, 0, 5, 5, 3, 0, 9, 2],
        &mut dst,
    );
    assert_eq!(dst, [6, 0, 8, 5, 0, 4, 0, 0, 0, 7, 0, 1]);
}

#[test]
#[should_panic(expected = "scatter index out of bounds")]
fn scatter_checks_the_largest_index() {
    scatter(&[0; 8], &[0, 1, 2, 3, 12, 5, 6, 7], &mut [0; 12]);
}

#[test]
#[should_panic(expected = "scatter index out of bounds")]
fn scatter_refuses_negative_indices() {
    scatter(&[0; 8], &[0, 1, 2, -1, 4, 5, 6, 7], &mut [0; 12]);
}

struct Solve(PlaneSolve, usize);

impl Kernel for Solve {
    type Output = Vec<SolvedPlane>;
    #[inline(always)]
    fn run<S: Simd>(self, s: S) -> Vec<SolvedPlane> {
        let mut out = vec![[0.0; 3]; self.1];
        s.solve_planes(&self.0, &mut out);
        out
    }
}

#[test]
fn every_level_solves_planes_bit_for_bit() {
    // Values of every magnitude and sign, some of them such that products
    // round (or overflow to infinity) and sums cancel, and every count.
    let mut seed = 0x2545_f491_4f6c_dd1du64;
    let mut next = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        let mantissa = (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
        let exponent = (seed % 80) as i32 - 40;
        mantissa * 2f64.powi(exponent)
    };
    for round in 0..2000 {
        let mut p = PlaneSolve {
            q: std::array::from_fn(|_| std::array::from_fn(|_| next())),
            gx: [next(), next()],
            gy: [next(), next()],
            origin: [next(), next()],
        };
        if round % 7 == 0 {
            // Nearly equal corners: the differences cancel.
            p.q[1] = p.q[0].map(|v| v * (1.0 + 1e-12));
        }
        if round % 11 == 0 {
            p.gx[0] = 1e300;
        }
        let count = round % (SOLVE_LANES + 1);
        let mut expected = vec![[0.0; 3]; count];
        solve_planes(&p, &mut expected);
        for level in SimdLevel::supported() {
            let got = dispatch(level, Solve(p, count));
            for k in 0..count {
                let bits = |v: [f32; 3]| v.map(f32::to_bits);
                assert_eq!(
                    bits(got[k]),
                    bits(expected[k]),
                    "{level:?}, plane {k} of {count}"
                );
            }
        }
    }
}

/// [`Simd::apart`] runs its work with the caller's backend: the same
/// lanes as the work run inline, on every level.
struct PowApart([f32; 8], f32);

impl<S: Simd> Apart<S> for Pow {
    type Output = [f32; 8];
    #[inline(always)]
    fn run(self, s: S) -> [f32; 8] {
        Kernel::run(self, s)
    }
}

impl Kernel for PowApart {
    type Output = ([f32; 8], [f32; 8]);
    #[inline(always)]
    fn run<S: Simd>(self, s: S) -> Self::Output {
        let apart = s.apart(Pow(self.0, self.1));
        (apart, Kernel::run(Pow(self.0, self.1), s))
    }
}

#[test]
fn apart_runs_the_work_with_the_callers_backend() {
    let x = [0.0, 0.1, 0.25, 0.5, 0.75, 0.9, 0.99, 1.0];
    for level in SimdLevel::supported() {
        let (apart, inline) = dispatch(level, PowApart(x, 7.5));
        let bits = |v: [f32; 8]| v.map(f32::to_bits);
        assert_eq!(bits(apart), bits(inline), "{level:?}");
    }
}

/// Prefetching for writing runs on this processor, however it was detected
/// (a `PREFETCHW` it lacked would stop the test with an illegal
/// instruction), writes nothing, and the same way is found every time.
#[test]
fn prefetching_for_writing_changes_no_memory() {
    let ahead = WritePrefetch::detect();
    assert_eq!(ahead, WritePrefetch::detect());
    let lines: Vec<u64> = (0..1024).collect();
    for value in &lines {
        ahead.line(value);
    }
    assert!(lines.iter().copied().eq(0..1024));
}

/// Handing lines back runs on this processor, however it was detected (a
/// `CLFLUSHOPT` it lacked would stop the test with an illegal
/// instruction), changes no value (lines just written, whole slices, parts
/// starting and ending mid-line, an empty one), and the same way is found
/// every time.
#[test]
fn releasing_lines_changes_no_memory() {
    let release = ReleaseLines::detect();
    assert_eq!(release, ReleaseLines::detect());
    let mut values: Vec<u32> = (0..4099).collect();
    for round in 0..3u32 {
        for v in &mut values {
            *v += round;
        }
        release.slice(&values);
        release.slice(&values[1..2]);
        release.slice(&values[13..4000]);
        release.slice(&values[..0]);
        release.slice::<u8>(&[]);
    }
    assert!(values.iter().copied().eq((0..4099).map(|v| v + 3)));
}

struct StoreRgb(usize);

impl Kernel for StoreRgb {
    type Output = [u8; 40];
    #[inline(always)]
    fn run<S: Simd>(self, s: S) -> [u8; 40] {
        // Pixel i: r = 10 i + 1, g = r + 1, b = r + 2, and 0xaa in the top byte.
        let pixels: [i32; 8] = std::array::from_fn(|i| {
            let r = 10 * i as i32 + 1;
            (0xaa << 24) | r | (r + 1) << 8 | (r + 2) << 16
        });
        let mut out = [0xee; 40];
        let at = self.0;
        s.i_store_rgb(
            s.i_load(&pixels),
            (&mut out[at..at + 24]).try_into().unwrap(),
        );
        out
    }
}

/// Each backend's `i_store_rgb` writes a block's 24 bytes of RGB, at any
/// offset, and not a byte around them (the AVX-512 build's store is
/// masked, the AVX2 one's three overlap).
#[test]
fn rgb_stores_write_their_24_bytes_and_no_more() {
    for level in SimdLevel::supported() {
        for at in 0..=16 {
            let out = dispatch(level, StoreRgb(at));
            let rgb: Vec<u8> = (0..8u8)
                .flat_map(|i| [10 * i + 1, 10 * i + 2, 10 * i + 3])
                .collect();
            assert_eq!(out[at..at + 24], rgb[..], "{level:?} at {at}");
            assert!(out[..at].iter().all(|&b| b == 0xee), "{level:?} at {at}");
            assert!(
                out[at + 24..].iter().all(|&b| b == 0xee),
                "{level:?} at {at}"
            );
        }
    }
}
