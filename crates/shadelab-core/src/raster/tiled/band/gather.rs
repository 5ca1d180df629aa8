//! Phong's small triangles gathered (a deferred shader drawing one method,
//! see `mod.rs`): the fragments of a triangle whose box is one or two
//! blocks wide and at most 64 pixels in whole blocks (8 rows of one
//! block, 4 of two) that pass the depth test are kept as the bits of one
//! `u64`, row after row, and packed into whole lanes after its last row.
//!
//! Why: the rows of other triangles pend their passes (`Band::pend`): per
//! row, a compress, a rotation behind the pending lanes, three blends and
//! a branch on whether 8 are there, each row chained to the one before.
//! Here a row only adds its bits to the mask; the triangle's fragments
//! are then taken from it 8 at a time, each lane's position from a bit's
//! index (eight fixed `trailing_zeros` steps, no branch per row). Against
//! 41fbd89 on the Zen 5 EPYC, with Phong's spans apart (`Simd::apart`):
//! the bunny's and the dragon's Phong rows 1–5 % faster, the quad's the
//! same (BENCHMARKS.md, "Phong's spans apart; a small triangle's passes
//! in one mask").
//!
//! The values are the pending path's: a fragment's column and row from
//! the triangle's first are small integers, exact in `f32` as a block
//! computes them (`Fill::column`, `Fill::row`), and `interpolate_and_queue`
//! evaluates each lane with the same operations. Only which fragments
//! share a vector differs, which changes no lane.

use super::walk::{depth_test, inside_then_step, Fill};
use super::Band;
use crate::shade::Shader;
use crate::simd::{Simd, Vi};

/// Whether a triangle walked in blocks, `blocks` per row over `rows` rows,
/// has its passes gathered: a deferred shader drawing one method, and a
/// box of at most 64 pixels in one or two blocks per row.
#[inline(always)]
pub(super) fn gathers<Sh: Shader>(blocks: i32, rows: usize) -> bool {
    Sh::DEFERRED && !Sh::ALL_METHODS && blocks <= 2 && rows * 8 * blocks as usize <= 64
}

impl Band {
    /// `Band::walk_rows` for a triangle that [`gathers`]: the same
    /// walk and depth test, the passes kept in a mask, then interpolated
    /// and queued 8 at a time.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub(super) fn walk_gathered<S: Simd, Sh: Shader>(
        &mut self,
        s: S,
        f: &Fill<'_, S, Sh>,
        rows: std::ops::Range<i32>,
        band_y0: u32,
        blocks: i32,
        mut row_e: [Vi<S>; 3],
        right_start: Vi<S>,
        (block_step, row_step, right_step): ([Vi<S>; 3], [Vi<S>; 3], Vi<S>),
    ) {
        let first_block = f.t.x0 & !7;
        // Bit `8·blocks·r + 8·b + i`: lane `i` of block `b` of row `r`.
        let (mut mask, mut shift, row_len) = (0u64, 0, 8 * blocks as u32);
        let mut fragments = 0;
        let start = rows.start;
        for y in rows {
            let row_start = (y as u32 - band_y0) as usize * self.stride;
            let (mut e, mut right) = (row_e, right_start);
            let mut row = None;
            for block in 0..blocks {
                let inside = inside_then_step(&mut e, &mut right, &block_step, right_step);
                if inside.mask_bits() != 0 {
                    let x = first_block + block * 8;
                    let row = *row.get_or_insert_with(|| f.row(y));
                    let at = row_start + x as usize;
                    let depth: &mut [f32; 8] = (&mut self.depth[at..at + 8]).try_into().unwrap();
                    let bits = depth_test(s, f, inside, f.column(x), &row, depth).mask_bits();
                    fragments += bits.count_ones();
                    mask |= u64::from(bits) << (shift + 8 * block as u32);
                }
            }
            shift += row_len;
            for i in 0..3 {
                row_e[i] = row_e[i] + row_step[i];
            }
        }
        self.fragments += u64::from(fragments);
        // Each bit's column in the box, its row from the box's first, and
        // its buffer index.
        let row_bits = row_len.trailing_zeros();
        let first_at = (start as u32 - band_y0) as usize * self.stride + first_block as usize;
        let (first_at, stride) = (
            Vi::splat(s, first_at as i32),
            Vi::splat(s, self.stride as i32),
        );
        while mask != 0 {
            let count = mask.count_ones().min(8) as usize;
            // The next 8 set bits' indices (64 for none, past the last).
            let mut bits = [0i32; 8];
            for bit in &mut bits {
                *bit = mask.trailing_zeros() as i32;
                mask &= mask.wrapping_sub(1);
            }
            let bits = Vi(s.i_load(&bits), s);
            let column = bits & Vi::splat(s, row_len as i32 - 1);
            let row = bits.sra(row_bits);
            let x = (column + Vi::splat(s, first_block - f.t.x0)).to_f();
            let dy = (row + Vi::splat(s, start - f.t.y0)).to_f();
            let at = first_at + row * stride + column;
            self.interpolate_and_queue(s, f, x, dy, at.0, count);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::gathers;
    use crate::shade::{FlatShader, GouraudShader, PhongShader};

    /// Phong's boxes of one or two blocks and at most 64 pixels in blocks
    /// are gathered; larger boxes and the other methods are not.
    #[test]
    fn gathers_phongs_boxes_of_at_most_64_pixels() {
        type Phong = PhongShader;
        for (blocks, rows, want) in [
            (1, 1, true),
            (1, 8, true),
            (1, 9, false),
            (2, 1, true),
            (2, 4, true),
            (2, 5, false),
            (3, 1, false),
        ] {
            assert_eq!(gathers::<Phong>(blocks, rows), want, "{blocks} × {rows}");
        }
        assert!(!gathers::<FlatShader>(1, 1));
        assert!(!gathers::<GouraudShader>(1, 1));
    }
}
