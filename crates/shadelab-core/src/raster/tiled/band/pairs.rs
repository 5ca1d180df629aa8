//! A large triangle's span, its blocks two at a time in 16 lanes
//! ([`Simd::F16`]): flat and Gouraud colour them (here), Phong lights
//! them (`phong_span.rs`).
//!
//! Inside a large triangle nearly every pair of blocks lies wholly in the
//! span and passes the depth test whole. With AVX-512 such a pair is one
//! 512-bit vector per value: the depth test, 1/w and the interpolated
//! attributes, Gouraud's conversion to bytes and the stores take one
//! instruction for 16 pixels where blocks of 8 took two (Intel's server
//! cores run 512-bit multiply-adds on two ports, as many per cycle as
//! 256-bit ones). Other backends get a [`crate::simd::Pair`] of their 8
//! lanes: the two blocks side by side.
//!
//! Each lane gets the operations a block of 8 would give it: the columns
//! are exact integers in `f32`, the multiply-adds are the same, and the
//! AVX-512 reciprocal is estimated per half of 8 with the AVX2 instruction
//! (`simd/avx512.rs`). So the bytes are those of blocks of 8, which
//! `tests/methods.rs` checks against the three-methods frame (still drawn
//! in blocks of 8) close up. A pair that is not whole, partly outside the
//! span or partly hidden, goes block by block (`shade_block`,
//! `Band::block`), which redoes its depth test: nothing was stored yet.
//! Pairs start at a multiple of 16 columns, a cache line of the buffers
//! (`depth_buffer.rs`), after a lone first block where needed.
//!
//! A row's whole pairs run in one of seven instances of one loop, chosen
//! once per row so that no pair tests anything but its depths. w per
//! pixel; or w for the whole row, or none (screen mode, which takes the
//! full-screen quad too: `Triangle::interpolated`), each of these two in
//! three: as they are; without Gouraud's guard before its conversion to
//! bytes, where [`planes_below`] shows that no lane of the row can reach
//! 2^31 (the guard's only effect is on such values, so the bytes are the
//! same); and, where the row's colours are all in `[0, 256)` (nearly every
//! row of a large triangle, shown the same way), without the saturation
//! either, which lets the AVX-512 lanes shift each byte into place where
//! the packs shuffled ([`crate::simd::Lanes::store_bytes_within`]).
//!
//! Phong's spans use the same pairs (`phong_span.rs`).

use super::walk::{
    all_in_bytes, interpolate_planes, needs_w, planes_below, row_w, shade_block, Fill, Row,
};
use crate::raster::tiled::setup::plane_count;
use crate::shade::{known, Shader, MAX_ATTRS};
use crate::simd::{Lanes, Simd, Vf, Vi};

/// What a row's pairs of blocks need, in 16 lanes, and the columns of the
/// current pair.
pub(super) struct Pairs<S: Simd> {
    /// Columns relative to the triangle's first, as the planes take them:
    /// integers below 2^24, so the compares and steps are exact.
    pub(super) column: S::F16,
    /// The span, `from < column < to`, in the same terms.
    from: S::F16,
    to: S::F16,
    pub(super) sixteen: S::F16,
    dx: [S::F16; 2 + MAX_ATTRS],
    at_row: [S::F16; 2 + MAX_ATTRS],
}

impl<S: Simd> Pairs<S> {
    /// The pairs of row `row`'s span `left..right` (image columns) from the
    /// one at column `x`.
    #[inline(always)]
    pub(super) fn new<Sh: Shader>(
        s: S,
        f: &Fill<'_, S, Sh>,
        row: &Row,
        (x, left, right): Span,
    ) -> Self {
        let x0 = f.t.x0;
        let ramp = s.f16_load(&std::array::from_fn(|i| i as f32));
        let mut dx = [ramp; 2 + MAX_ATTRS];
        let mut at_row = [ramp; 2 + MAX_ATTRS];
        for j in 0..plane_count(Sh::ATTRS) {
            dx[j] = ramp.splat_like(f.planes[j].dx);
            at_row[j] = ramp.splat_like(row.values[j]);
        }
        Pairs {
            column: ramp + ramp.splat_like((x - x0) as f32),
            from: ramp.splat_like((left - 1 - x0) as f32),
            to: ramp.splat_like((right - x0) as f32),
            sixteen: ramp.splat_like(16.0),
            dx,
            at_row,
        }
    }

    /// The current pair's depths, and a bit per lane inside the span whose
    /// depth is less than `stored` (as a block's `z < stored`).
    #[inline(always)]
    pub(super) fn depth_test(&self, s: S, stored: &[f32; 16]) -> (S::F16, u32) {
        let (span, depth) = ((self.from, self.to), (self.dx[0], self.at_row[0]));
        depth_test_at(s, self.column, span, depth, stored)
    }

    /// Marks in `f` a tie ([`Band::ties`](super::Band::ties)) at the
    /// current pair, whose lanes all failed [`Pairs::depth_test`] (their
    /// blocks are not tested again): a lane inside the span whose depth
    /// equals the stored one. As the blocks' `depth_test` does.
    #[inline(always)]
    pub(super) fn note_ties<Sh: Shader>(&self, s: S, f: &Fill<'_, S, Sh>, stored: &[f32; 16]) {
        let bits = <S::F16 as Lanes>::mask_bits;
        let (column, from, to) = (self.column, self.from, self.to);
        let z = column.mul_add(self.dx[0], self.at_row[0]);
        let stored = s.f16_load(stored);
        let inside = column.gt(from) & to.gt(column);
        if bits(inside) & !(bits(stored.gt(z)) | bits(z.gt(stored))) != 0 {
            f.ties.set(true);
        }
    }

    /// How many pairs from the current one are whole, each lane inside
    /// the span and passing the depth test, with their depths stored in
    /// `depth` (which holds theirs and the rest of the row's pairs'); and
    /// the first other pair's bits from [`Pairs::depth_test`] (0xffff if
    /// there is none). Does not step.
    ///
    /// Its own loop, with what it needs in locals: in `queue_span`'s, the
    /// column and the pair count lived on the stack, written back per pair.
    #[inline(always)]
    pub(super) fn whole_run(&self, s: S, depth: &mut [f32]) -> (usize, u32) {
        let (from, to, sixteen) = (self.from, self.to, self.sixteen);
        let (dz, z0) = (self.dx[0], self.at_row[0]);
        let mut column = self.column;
        let depth = depth.as_chunks_mut::<16>().0;
        for (k, stored) in depth.iter_mut().enumerate() {
            let (z, pass) = depth_test_at(s, column, (from, to), (dz, z0), stored);
            if pass != 0xffff {
                return (k, pass);
            }
            z.store_to(stored);
            column = column + sixteen;
        }
        (depth.len(), 0xffff)
    }

    /// w for the row's pairs where it is the same along the row
    /// ([`row_w`]), else `None`.
    #[inline(always)]
    pub(super) fn row_w<Sh: Shader>(&self, f: &Fill<'_, S, Sh>, row: &Row) -> Option<S::F16> {
        fill_row_w(f, row, self.sixteen)
    }

    /// The current pair's attributes (normals not yet turned for back
    /// faces), with w for the row if the caller has it ([`Pairs::row_w`]).
    #[inline(always)]
    fn attributes<Sh: Shader>(
        &self,
        f: &Fill<'_, S, Sh>,
        w: Option<S::F16>,
    ) -> [S::F16; MAX_ATTRS] {
        self.attributes_at(f, self.column, w)
    }

    /// As [`Pairs::attributes`], for the pair at `column`.
    #[inline(always)]
    pub(super) fn attributes_at<Sh: Shader>(
        &self,
        f: &Fill<'_, S, Sh>,
        column: S::F16,
        w: Option<S::F16>,
    ) -> [S::F16; MAX_ATTRS] {
        let (dx, at_row) = (&self.dx, &self.at_row);
        interpolate_planes(
            f.interpolation,
            (Sh::ATTRS, Sh::SCALE_FREE),
            column,
            |j| dx[j],
            |j| at_row[j],
            w,
        )
    }

    /// As [`Pairs::attributes_at`] given w for the row if `TIMES_W`, else
    /// where w is not needed: the same bits, without a test per pair.
    ///
    /// The loops repeat [`interpolate_planes`]' on purpose: one helper
    /// shared by both (a4a03dc) compiled the blocks of 8 worse and made the
    /// meshes' 1080p Gouraud frames 9–11 % slower (BENCHMARKS.md, "The
    /// pairs' attributes from walk.rs's own helper").
    #[inline(always)]
    fn attributes_times<Sh: Shader, const TIMES_W: bool>(
        &self,
        column: S::F16,
        w: S::F16,
    ) -> [S::F16; MAX_ATTRS] {
        let mut attrs = [w.splat_like(0.0); MAX_ATTRS];
        for k in 0..Sh::ATTRS {
            attrs[k] = column.mul_add(self.dx[2 + k], self.at_row[2 + k]);
        }
        if TIMES_W {
            for a in &mut attrs[Sh::SCALE_FREE..Sh::ATTRS] {
                *a = *a * w;
            }
        }
        attrs
    }

    /// Whether every lane the row's whole pairs hand to
    /// [`Shader::shade_lanes`] with [`Pairs::attributes_times`] and the
    /// row's w (1 where w is not needed: `a·1 = a` exactly) lies in
    /// `[0, 256)`, given the span `left..right`, in which all of a whole
    /// pair's lanes lie: [`known::BYTES`].
    ///
    /// Each attribute is `x·dx + at_row`, then times w, in correctly
    /// rounded steps of the one variable x, so monotonic in x (as in
    /// [`planes_below`]): its values between the span's ends lie between
    /// its values there, computed here with the same operations, both ends
    /// in one vector (the first in lanes 0..8, the last in the rest).
    #[inline(always)]
    fn in_bytes<Sh: Shader>(
        &self,
        f: &Fill<'_, S, Sh>,
        w: S::F16,
        (left, right): (i32, i32),
    ) -> bool {
        let x0 = f.t.x0;
        let ends = [left - x0, right - 1 - x0].map(|x| x as f32);
        let both = self.sixteen.halves(ends);
        all_in_bytes(Sh::ATTRS, &self.attributes_times::<Sh, true>(both, w))
    }

    /// Whether every lane the row's whole pairs hand to
    /// [`Shader::shade_lanes`] has attributes below 2^31 or NaN
    /// ([`planes_below`]), given the row's w ([`Pairs::row_w`]) and the
    /// span `left..right`, in which all of a whole pair's lanes lie.
    #[inline(always)]
    fn below<Sh: Shader>(
        &self,
        f: &Fill<'_, S, Sh>,
        w: Option<S::F16>,
        (left, right): (i32, i32),
    ) -> bool {
        let x0 = f.t.x0;
        let ends = (
            self.sixteen.splat_like((left - x0) as f32),
            self.sixteen.splat_like((right - 1 - x0) as f32),
        );
        let (dx, at_row) = (&self.dx, &self.at_row);
        let planes = (Sh::ATTRS, Sh::SCALE_FREE);
        planes_below(f.interpolation, planes, ends, |j| dx[j], |j| at_row[j], w)
    }

    /// On to the next pair.
    #[inline(always)]
    pub(super) fn step(&mut self) {
        self.column = self.column + self.sixteen;
    }
}

/// [`Pairs::depth_test`] of the pair at `column`, given the span `(from,
/// to)` and the depth plane `(dz, z0)`: in values, so that
/// [`Pairs::whole_run`] can keep them in locals.
#[inline(always)]
fn depth_test_at<S: Simd>(
    s: S,
    column: S::F16,
    (from, to): (S::F16, S::F16),
    (dz, z0): (S::F16, S::F16),
    stored: &[f32; 16],
) -> (S::F16, u32) {
    let inside = column.gt(from) & to.gt(column);
    let z = column.mul_add(dz, z0);
    let pass = inside & s.f16_load(stored).gt(z);
    (z, <S::F16 as Lanes>::mask_bits(pass))
}

/// A pair's first column `x`, and the span `left..right`.
pub(super) type Span = (i32, i32, i32);

/// How many blocks of 8 the span has from column `x`, and how many of them
/// go alone first so that the pairs start at a multiple of 16 (0 or 1).
#[inline(always)]
pub(super) fn blocks_and_head(x: i32, right: i32) -> (usize, usize) {
    let blocks = ((right - x).max(0) as usize).div_ceil(8);
    (blocks, usize::from(x % 16 != 0).min(blocks))
}

/// Fills one row's span (flat, Gouraud): columns `left..right` (image
/// columns), whose blocks of 8 start at column `x` (a multiple of 8, at
/// most `left`; the buffers' rows are a multiple of 16 long), with the
/// depths and colours from there in `depth` and `color` (whole blocks up
/// to `right`). Returns how many pixels passed the depth test.
#[inline(always)]
pub(super) fn fill_span<S: Simd, Sh: Shader>(
    s: S,
    f: &Fill<'_, S, Sh>,
    row: &Row,
    (x, left, right): Span,
    depth: &mut [f32],
    color: &mut [i32],
) -> u32 {
    // w for the row's blocks of 8 too, where it is the row's: the same
    // bits as per pixel, without a reciprocal per block. With the rows of
    // bytes below, only where those pay (`Lanes::SHIFTS_BYTES`).
    let shifts = <S::F16 as Lanes>::SHIFTS_BYTES;
    let row = &(
        row,
        if shifts {
            fill_row_w(f, row, Vf::splat(s, 1.0))
        } else {
            None
        },
    );
    let head = 8 * blocks_and_head(x, right).1;
    let (depth_head, depth) = depth.split_at_mut(head);
    let (color_head, color) = color.split_at_mut(head);
    let mut fragments = blocks(s, f, row, (x, left, right), depth_head, color_head);
    let x = x + head as i32;
    let mut pairs = Pairs::new(s, f, row.0, (x, left, right));
    // w for the whole row, none needed (then 1), or per pixel (then not
    // this one, which is unused). The loop below is compiled for each
    // case, with no test per pair.
    let (w, from) = match pairs.row_w(f, row.0) {
        Some(w) => (w, w_from::ROW),
        None if needs_w(f.interpolation, (Sh::ATTRS, Sh::SCALE_FREE)) => {
            (pairs.sixteen, w_from::PIXEL)
        }
        None => (pairs.sixteen.splat_like(1.0), w_from::NONE),
    };
    let (depth_pairs, depth_rest) = depth.as_chunks_mut::<16>();
    let (color_pairs, color_rest) = color.as_chunks_mut::<16>();
    let count = depth_pairs.len();
    let buffers = (depth_pairs, color_pairs);
    let span = (x, left, right);
    let known = (shifts, w);
    fragments += match from {
        w_from::ROW => {
            known_pairs::<S, Sh, { w_from::ROW }>(s, f, row, &mut pairs, known, span, buffers)
        }
        w_from::NONE => {
            known_pairs::<S, Sh, { w_from::NONE }>(s, f, row, &mut pairs, known, span, buffers)
        }
        _ => whole_pairs::<S, Sh, { known::ANYTHING }, { w_from::PIXEL }>(
            s, f, row, &mut pairs, w, span, buffers,
        ),
    };
    let x = x + 16 * count as i32;
    fragments + blocks(s, f, row, (x, left, right), depth_rest, color_rest)
}

/// How a row's whole pairs take w ([`whole_pairs`]' `W`).
mod w_from {
    /// Per pixel, the reciprocal of the 1/w plane there.
    pub(super) const PIXEL: u8 = 0;
    /// The row's ([`super::Pairs::row_w`]), one value for the whole row.
    pub(super) const ROW: u8 = 1;
    /// Not needed: screen mode, or no attribute divided by w.
    pub(super) const NONE: u8 = 2;
}

/// [`whole_pairs`] with w the row's or not needed (`W`; `w` is then 1),
/// and what is known of the attributes from the span's ends.
///
/// Gouraud's conversion to bytes guards against values of 2^31 and more
/// (a sliver's planes can reach them), and gathers each pixel's bytes with
/// shuffles. A row whose attributes are bytes everywhere (nearly all rows
/// of a large triangle with w the same along them) takes a loop with
/// neither where the lanes allow (`shifts`, [`Pairs::in_bytes`]); else
/// one whose attributes stay below 2^31, without the guard: the same
/// bytes. Worth a check from a few pairs on.
#[inline(always)]
fn known_pairs<S: Simd, Sh: Shader, const W: u8>(
    s: S,
    f: &Fill<'_, S, Sh>,
    row: &BlockRow<S>,
    pairs: &mut Pairs<S>,
    (shifts, w): (bool, S::F16),
    span: Span,
    buffers: (&mut [[f32; 16]], &mut [[i32; 16]]),
) -> u32 {
    use known::{ANYTHING, BELOW_2_31, BYTES};
    let (_, left, right) = span;
    let some = buffers.0.len() >= 4;
    if some && shifts && pairs.in_bytes(f, w, (left, right)) {
        whole_pairs::<S, Sh, BYTES, W>(s, f, row, pairs, w, span, buffers)
    } else if some && pairs.below(f, Some(w), (left, right)) {
        whole_pairs::<S, Sh, BELOW_2_31, W>(s, f, row, pairs, w, span, buffers)
    } else {
        whole_pairs::<S, Sh, ANYTHING, W>(s, f, row, pairs, w, span, buffers)
    }
}

/// The pairs of blocks of [`fill_span`] from column `x`, in `buffers`'
/// depths and colours: with w as [`w_from`] `W` says (`w`: the row's, or
/// 1 where none is needed); with [`Shader::shade_lanes`]'s `KNOWN`.
#[inline(always)]
fn whole_pairs<S: Simd, Sh: Shader, const KNOWN: u8, const W: u8>(
    s: S,
    f: &Fill<'_, S, Sh>,
    row: &BlockRow<S>,
    pairs: &mut Pairs<S>,
    w: S::F16,
    (x, left, right): Span,
    (depth, color): (&mut [[f32; 16]], &mut [[i32; 16]]),
) -> u32 {
    let (mut x, mut fragments) = (x, 0);
    for (depth, color) in depth.iter_mut().zip(color) {
        let (z, pass) = pairs.depth_test(s, depth);
        if pass == 0xffff {
            z.store_to(depth);
            let attrs = match W {
                w_from::ROW => pairs.attributes_times::<Sh, true>(pairs.column, w),
                w_from::NONE => pairs.attributes_times::<Sh, false>(pairs.column, w),
                _ => pairs.attributes(f, None),
            };
            f.shader.shade_lanes::<_, KNOWN>(f.color, &attrs, color);
            fragments += 16;
        } else if pass != 0 || f.watch_ties {
            // Not whole: block by block, which tests again (and sees the
            // ties of a pair hidden whole, `depth_test`).
            fragments += blocks(s, f, row, (x, left, right), depth, color);
        }
        pairs.step();
        x += 16;
    }
    fragments
}

/// A row, and w for its blocks of 8 where it is the row's.
type BlockRow<'a, S> = (&'a Row, Option<Vf<S>>);

/// w for row `row` of `f`'s triangle where it is the same along the row
/// ([`row_w`]), in the lanes of `like`; else `None`.
#[inline(always)]
fn fill_row_w<S: Simd, Sh: Shader, L: Lanes>(f: &Fill<'_, S, Sh>, row: &Row, like: L) -> Option<L> {
    // Flat has no 1/w plane. No closure: see `Surface::radiance`.
    if plane_count(Sh::ATTRS) > 1 {
        let planes = (Sh::ATTRS, Sh::SCALE_FREE);
        row_w(f.interpolation, planes, f.planes[1].dx, row.values[1], like)
    } else {
        None
    }
}

/// As [`fill_span`], block by block with `shade_block`: a pair that is not
/// whole, or a lone block.
#[inline(always)]
fn blocks<S: Simd, Sh: Shader>(
    s: S,
    f: &Fill<'_, S, Sh>,
    &(row, w): &BlockRow<S>,
    (x, left, right): Span,
    depth: &mut [f32],
    color: &mut [i32],
) -> u32 {
    let depth = depth.as_chunks_mut::<8>().0;
    let color = color.as_chunks_mut::<8>().0;
    let mut fragments = 0;
    for (k, (depth, color)) in depth.iter_mut().zip(color).enumerate() {
        let x = x + 8 * k as i32;
        let inside = inside(s, (x, left, right));
        let x = f.column(x);
        fragments += shade_block::<S, Sh, true>(s, f, inside, x, (row, w), depth, color);
    }
    fragments
}

/// The lanes of the block at column `x` that lie in the span `left..right`.
#[inline(always)]
pub(super) fn inside<S: Simd>(s: S, (x, left, right): Span) -> Vi<S> {
    let lanes = Vi::ramp(s) + Vi::splat(s, x);
    lanes.gt(Vi::splat(s, left - 1)) & Vi::splat(s, right).gt(lanes)
}
