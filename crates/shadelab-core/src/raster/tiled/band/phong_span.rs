//! Phong's span of a large triangle (see `mod.rs`): its whole pairs of
//! blocks (`pairs.rs`) lit in place, the rest queued (`queue.rs`).
//!
//! A row's run of whole pairs is depth-tested and its depths stored first
//! ([`Pairs::whole_run`]), then lit in groups of `16 · Simd::LIT_GROUPS`
//! by a function of its own ([`LightPairs`]) that interpolates each pair
//! and writes its colours straight to the band. The queue lit them from
//! six stored attributes and an index per fragment, read back: for the
//! full-screen 1080p quad, 7 512-bit stores and as many loads per 16
//! fragments, and a test for 8 in a row before each colour store. Lit in
//! place, the quad's 1080p frames are 13–16 % faster on the Zen 4 EPYC,
//! the meshes' the same within the noise, and the bytes the same
//! (BENCHMARKS.md, "Phong's whole pairs lit in place"). What is left of
//! a run, fewer than a group, joins the queue, as do the blocks of pairs
//! that are not whole.
//!
//! The depths and the lighting are two loops: the lighting needs every
//! register, and with it in the depth loop's body the pairs' constants
//! and counters lived on the stack.

use super::pairs::{blocks_and_head, inside, Pairs, Span};
use super::walk::{Fill, Row};
use super::Band;
use crate::shade::{Shader, MAX_ATTRS};
use crate::simd::{Apart, Simd, MAX_LIT_GROUPS};

impl Band {
    /// Draws one row's span for a deferred shader (Phong), its blocks as
    /// `pairs.rs`'s `fill_span` takes them; `row_start` is the row's
    /// buffer index.
    #[inline(always)]
    pub(super) fn queue_span<S: Simd, Sh: Shader>(
        &mut self,
        s: S,
        f: &Fill<'_, S, Sh>,
        row: &Row,
        row_start: usize,
        (x, left, right): Span,
    ) -> u32 {
        let (blocks, head) = blocks_and_head(x, right);
        let mut fragments = self.queue_blocks(s, f, row, row_start, (x, left, right), head);
        let mut x = x + 8 * head as i32;
        let mut pairs = Pairs::new(s, f, row, (x, left, right));
        let w = pairs.row_w(f, row);
        let (count, mut k) = ((blocks - head) / 2, 0);
        while k < count {
            // A run of whole pairs: their depths, then their lighting.
            let at = row_start + x as usize;
            let (run, pass) = pairs.whole_run(s, &mut self.depth[at..at + 16 * (count - k)]);
            if run > 0 {
                let column = pairs.column;
                self.light_pairs(s, f, &pairs, (column, w), at, run);
                fragments += 16 * run as u32;
                // Exact: integers below 2^24.
                pairs.column = column + pairs.sixteen * (run as f32);
                x += 16 * run as i32;
                k += run;
            }
            if k == count {
                break;
            }
            // A pair not whole (partly outside the span, or partly or
            // wholly hidden): its blocks one by one, which redo the test.
            if pass != 0 {
                fragments += self.queue_blocks(s, f, row, row_start, (x, left, right), 2);
            } else if f.watch_ties {
                let at = row_start + x as usize;
                pairs.note_ties(s, f, (&self.depth[at..at + 16]).try_into().unwrap());
            }
            pairs.step();
            x += 16;
            k += 1;
        }
        if self.queue_full::<S>() {
            self.shade_queue(s, f.shader, f.shader_lanes);
        }
        let rest = (blocks - head) % 2;
        fragments + self.queue_blocks(s, f, row, row_start, (x, left, right), rest)
    }

    /// Lights `run` whole pairs from buffer index `at`, whose depths are
    /// stored, the first at `column` (`pairs` gives the row's planes; `w`
    /// as [`Pairs::row_w`]): whole groups of `16 · S::LIT_GROUPS` in
    /// place ([`LightPairs`]), the rest queued.
    ///
    /// The colours lit in place are written before the queue's, so the
    /// queue first lights what earlier triangles left in it: one of their
    /// fragments at a pixel of this run would otherwise be written over
    /// this one's (`tests/tiled.rs`' overlapping layers fail without it).
    /// This triangle's own fragments in the queue lie elsewhere.
    #[inline(always)]
    fn light_pairs<S: Simd, Sh: Shader>(
        &mut self,
        s: S,
        f: &Fill<'_, S, Sh>,
        pairs: &Pairs<S>,
        (column, w): (S::F16, Option<S::F16>),
        at: usize,
        run: usize,
    ) {
        let in_place = run - run % S::LIT_GROUPS;
        if in_place > 0 {
            if self.queue.older {
                while self.queue.len > 0 {
                    self.shade_queue(s, f.shader, f.shader_lanes);
                }
                self.queue.older = false;
            }
            let start = self.color_at + at;
            let light = LightPairs {
                fill: f,
                pairs,
                column,
                w,
                color: &mut self.color[start..start + 16 * in_place],
            };
            s.apart(light);
        }
        let mut column = column + pairs.sixteen * (in_place as f32);
        for p in in_place..run {
            if self.queue_full::<S>() {
                self.shade_queue(s, f.shader, f.shader_lanes);
            }
            let attrs = pairs.attributes_at(f, column, w);
            self.append_pair(s, &attrs[..Sh::ATTRS], at + 16 * p);
            column = column + pairs.sixteen;
        }
        // Every other append needs the queue not full.
        if self.queue_full::<S>() {
            self.shade_queue(s, f.shader, f.shader_lanes);
        }
    }

    /// `count` blocks from column `x` of the span, one by one
    /// ([`Band::block`]).
    #[inline(always)]
    fn queue_blocks<S: Simd, Sh: Shader>(
        &mut self,
        s: S,
        f: &Fill<'_, S, Sh>,
        row: &Row,
        row_start: usize,
        (x, left, right): Span,
        count: usize,
    ) -> u32 {
        let mut fragments = 0;
        for k in 0..count {
            let x = x + 8 * k as i32;
            let inside = inside(s, (x, left, right));
            fragments += self.block::<S, Sh, true>(s, f, inside, row_start + x as usize, x, row);
        }
        fragments
    }
}

/// A run of whole pairs lit in place ([`Band::light_pairs`]), apart from
/// the walk ([`Simd::apart`]): `16 · S::LIT_GROUPS` fragments lit together,
/// as the queue lights them ([`Band::shade_queue`]), from the
/// same attributes ([`Pairs::attributes_at`]), so the bytes are the same.
struct LightPairs<'a, 'f, S: Simd, Sh: Shader> {
    fill: &'a Fill<'f, S, Sh>,
    pairs: &'a Pairs<S>,
    /// The first pair's columns.
    column: S::F16,
    w: Option<S::F16>,
    /// The run's colours: a whole number of groups.
    color: &'a mut [i32],
}

impl<S: Simd, Sh: Shader> LightPairs<'_, '_, S, Sh> {
    /// The run in groups of `G` pairs.
    #[inline(always)]
    fn groups<const G: usize>(self, s: S) {
        let (f, pairs, w) = (self.fill, self.pairs, self.w);
        let mut column = self.column;
        let (groups, rest) = self.color.as_chunks_mut::<16>().0.as_chunks_mut::<G>();
        debug_assert!(rest.is_empty());
        for colors in groups {
            let mut attrs = [[column; MAX_ATTRS]; G];
            for a in &mut attrs {
                *a = pairs.attributes_at(f, column, w);
                column = column + pairs.sixteen;
            }
            f.shader.light_queue(f.shader_lanes, s, &attrs, colors);
        }
    }
}

impl<S: Simd, Sh: Shader> Apart<S> for LightPairs<'_, '_, S, Sh> {
    type Output = ();
    #[inline(always)]
    fn run(self, s: S) {
        // As in `Band::shade_queue`: the condition is a constant of the
        // backend.
        if S::LIT_GROUPS == MAX_LIT_GROUPS {
            self.groups::<MAX_LIT_GROUPS>(s);
        } else {
            self.groups::<1>(s);
        }
    }
}
