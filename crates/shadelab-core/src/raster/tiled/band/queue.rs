//! Phong's deferred shading in a band: the positions of fragments that
//! passed the depth test packed into whole lanes, interpolated 8 at a time,
//! queued, lit `16 · Simd::LIT_GROUPS` at a time and written back in queue
//! order (see `mod.rs`).
//!
//! The lighting that a small triangle's fragments fill the queue for runs
//! in a function of its own ([`Simd::apart`]), called once per
//! `16 · Simd::LIT_GROUPS` fragments. Inlined, it was copied into each
//! place of the walk that queues fragments (the pending lanes, the
//! gathered mask, whole blocks, a triangle's last few): Phong's band
//! kernel took 123 KB of AVX-512 code, 33 KB with the lighting apart.
//! Against f7b3cb7 on the Zen 5 EPYC, the meshes' 1080p Phong rows 1–1.5 %
//! faster and the quad's 2–3 %, the same pictures (BENCHMARKS.md, "The
//! queue's lighting in a function of its own"). Large triangles' runs of
//! whole pairs skip the queue: `phong_span.rs` lights them in place.

use super::walk::{interpolate, Fill, Row};
use super::Band;
use crate::shade::{Shader, MAX_ATTRS};
use crate::simd::{scatter, Apart, Lanes, Simd, Vf, Vi, MAX_LIT_GROUPS};

impl Band {
    /// Keeps the positions of the lanes in `bits` (columns `x` from the
    /// triangle's first, `dy` rows down; block at buffer index `at`) for
    /// interpolation 8 at a time: packed, moved up behind the pending ones
    /// in registers, and interpolated once 8 are there.
    #[inline(always)]
    pub(super) fn pend<S: Simd, Sh: Shader>(
        &mut self,
        s: S,
        f: &Fill<'_, S, Sh>,
        x: Vf<S>,
        dy: f32,
        bits: u32,
        at: usize,
    ) {
        let p = &mut self.pending;
        let len = p.len;
        let index = Vi::ramp(s) + Vi::splat(s, at as i32);
        // The new positions from lane `len` on; those past lane 7 wrap
        // round to the front, where they are what stays pending.
        let (new_x, new_dy) = (x.compress(bits).rotate(len), Vf::splat(s, dy));
        let new_at = index.compress(bits).rotate(len);
        let old = Vi::splat(s, len as i32).gt(Vi::ramp(s));
        let full_x = Vf::select(old, Vf::load(s, &p.x), new_x);
        let full_dy = Vf::select(old, Vf::load(s, &p.dy), new_dy);
        let full_at = Vi::select(old, Vi(s.i_load(&p.at), s), new_at);
        let total = len + bits.count_ones() as usize;
        if total < 8 {
            full_x.store(&mut p.x);
            full_dy.store(&mut p.dy);
            s.i_store(full_at.0, &mut p.at);
            p.len = total;
        } else {
            new_x.store(&mut p.x);
            new_dy.store(&mut p.dy);
            s.i_store(new_at.0, &mut p.at);
            p.len = total - 8;
            self.interpolate_and_queue(s, f, full_x, full_dy, full_at.0, 8);
        }
    }

    /// Interpolates the pending fragments (fewer than 8, at the end of a
    /// triangle) and queues them for lighting. Each plane is evaluated as in
    /// a block (`origin + dy·rows`, then `x·dx +` that), so the values are
    /// those of an 8-pixel block.
    #[inline(always)]
    pub(super) fn interpolate_pending<S: Simd, Sh: Shader>(&mut self, s: S, f: &Fill<'_, S, Sh>) {
        let p = &mut self.pending;
        let (x, dy, index) = (Vf::load(s, &p.x), Vf::load(s, &p.dy), s.i_load(&p.at));
        let count = p.len;
        p.len = 0;
        self.interpolate_and_queue(s, f, x, dy, index, count);
    }

    /// Interpolates a whole block and queues it for lighting, from the row's
    /// values when it has them (spans), else as `interpolate_and_queue` does.
    #[inline(always)]
    pub(super) fn queue_block<S: Simd, Sh: Shader>(
        &mut self,
        s: S,
        f: &Fill<'_, S, Sh>,
        x: Vf<S>,
        row: &Row,
        index: S::I,
    ) {
        if !row.all {
            return self.interpolate_and_queue(s, f, x, Vf::splat(s, row.dy), index, 8);
        }
        let at_row = |j: usize| Vf::splat(s, row.values[j]);
        let attrs = interpolate(f, x, at_row);
        self.queue_lit(s, f, &attrs, index, 8);
    }

    /// Appends a pair of whole blocks from buffer index `at`, interpolated
    /// in 16 lanes (`phong_span.rs`), to the lighting queue, as
    /// [`Band::queue_lit`] would append the two blocks, but does not light
    /// it: the caller does once [`Band::queue_full`] says so. The queue must
    /// not be full.
    #[inline(always)]
    pub(super) fn append_pair<S: Simd>(&mut self, s: S, attrs: &[S::F16], at: usize) {
        let q = &mut self.queue;
        let len = q.len;
        for (k, a) in attrs.iter().enumerate() {
            a.store_to(&mut q.attrs[k][len..len + 16]);
        }
        let index = Vi::ramp(s) + Vi::splat(s, at as i32);
        s.i_store(index.0, (&mut q.at[len..len + 8]).try_into().unwrap());
        let index = index + Vi::splat(s, 8);
        s.i_store(index.0, (&mut q.at[len + 8..len + 16]).try_into().unwrap());
        q.len = len + 16;
    }

    /// Whether the queue holds the `16 · S::LIT_GROUPS` fragments that
    /// [`Band::shade_queue`] lights: the point at which every append
    /// but [`Band::append_pair`]'s lights them.
    #[inline(always)]
    pub(super) fn queue_full<S: Simd>(&self) -> bool {
        self.queue.len >= 16 * S::LIT_GROUPS
    }

    /// Interpolates the fragments at columns `x`, `dy` rows down (buffer
    /// indices `index`), and queues the first `count` of them for lighting.
    #[inline(always)]
    pub(super) fn interpolate_and_queue<S: Simd, Sh: Shader>(
        &mut self,
        s: S,
        f: &Fill<'_, S, Sh>,
        x: Vf<S>,
        dy: Vf<S>,
        index: S::I,
        count: usize,
    ) {
        let at_row = |j: usize| {
            let plane = &f.planes[j];
            Vf::splat(s, plane.at_origin) + Vf::splat(s, plane.dy) * dy
        };
        let attrs = interpolate(f, x, at_row);
        self.queue_lit(s, f, &attrs, index, count);
    }

    /// Appends the first `count` lanes of `attrs` (buffer indices `index`)
    /// to the lighting queue, and lights them once there are
    /// `16 · S::LIT_GROUPS`, in a function of its own ([`LightApart`]).
    #[inline(always)]
    pub(super) fn queue_lit<S: Simd, Sh: Shader>(
        &mut self,
        s: S,
        f: &Fill<'_, S, Sh>,
        attrs: &[Vf<S>; MAX_ATTRS],
        index: S::I,
        count: usize,
    ) {
        let q = &mut self.queue;
        let len = q.len;
        for k in 0..Sh::ATTRS {
            attrs[k].store((&mut q.attrs[k][len..len + 8]).try_into().unwrap());
        }
        s.i_store(index, (&mut q.at[len..len + 8]).try_into().unwrap());
        q.len = len + count;
        if self.queue_full::<S>() {
            let light = LightApart {
                band: self,
                shader: f.shader,
                lanes: f.shader_lanes,
            };
            s.apart(light);
        }
    }

    /// Shades the first (up to) `16 · S::LIT_GROUPS` queued fragments, as
    /// groups of 16 lit together, and writes their colours.
    #[inline(always)]
    pub(super) fn shade_queue<S: Simd, Sh: Shader>(
        &mut self,
        s: S,
        shader: &Sh,
        lanes: &Sh::Lanes<S>,
    ) {
        // Any other count would light fewer than were queued (and the
        // queue keeps only 8 for later): refuse it at compile time.
        const { assert!(S::LIT_GROUPS == 1 || S::LIT_GROUPS == MAX_LIT_GROUPS) };
        // The condition is a constant of the backend: the other arm is
        // dead code for it.
        if S::LIT_GROUPS == MAX_LIT_GROUPS {
            self.shade_groups::<S, Sh, MAX_LIT_GROUPS>(s, shader, lanes);
        } else {
            self.shade_groups::<S, Sh, 1>(s, shader, lanes);
        }
    }

    /// [`Band::shade_queue`] for `G` groups.
    #[inline(always)]
    fn shade_groups<S: Simd, Sh: Shader, const G: usize>(
        &mut self,
        s: S,
        shader: &Sh,
        lanes: &Sh::Lanes<S>,
    ) {
        let q = &mut self.queue;
        let zero = s.f16_load(&[0.0; 16]);
        let mut groups = [[zero; MAX_ATTRS]; G];
        for (g, group) in groups.iter_mut().enumerate() {
            for k in 0..Sh::ATTRS {
                group[k] = s.f16_load(q.attrs[k][16 * g..16 * g + 16].try_into().unwrap());
            }
        }
        let mut colors = [[0; 16]; G];
        shader.light_queue(lanes, s, &groups, &mut colors);
        let colors = colors.as_flattened();
        let count = q.len.min(16 * G);
        let image = &mut self.color[self.color_at..];
        for b in 0..count.div_ceil(8) {
            let n = (count - 8 * b).min(8);
            let colors: &[i32; 8] = colors[8 * b..8 * b + 8].try_into().unwrap();
            let at: &[i32; 8] = q.at[8 * b..8 * b + 8].try_into().unwrap();
            let in_a_row = Vi(s.i_load(at), s).eq_bits(Vi::ramp(s) + Vi::splat(s, at[0]));
            if n < 8 {
                // The last few, when the band is done.
                for i in 0..n {
                    image[at[i] as usize] = colors[i];
                }
            } else if in_a_row == 0xff {
                // Eight fragments in a row (a whole block): one store.
                image[at[0] as usize..][..8].copy_from_slice(colors);
            } else {
                scatter(colors, at, image);
            }
        }
        // Later fragments (fewer than `QUEUE_ROOM`) move to the front,
        // keeping their order, 8 lanes at a time (as `queue_lit` stored
        // them, so that each load gets its data straight from the store
        // before it); the second 8 only when a pair was queued last.
        q.len -= count;
        for to in [0, 8] {
            if to > 0 && q.len <= 8 {
                break;
            }
            let from = 16 * G + to;
            for k in 0..Sh::ATTRS {
                let rest = Vf::load(s, q.attrs[k][from..from + 8].try_into().unwrap());
                rest.store((&mut q.attrs[k][to..to + 8]).try_into().unwrap());
            }
            let rest = s.i_load(q.at[from..from + 8].try_into().unwrap());
            s.i_store(rest, (&mut q.at[to..to + 8]).try_into().unwrap());
        }
    }

    /// Shades whatever is still queued; called once the band's triangles are drawn.
    #[inline(always)]
    pub fn flush<S: Simd, Sh: Shader>(&mut self, s: S, shader: &Sh, lanes: &Sh::Lanes<S>) {
        if Sh::DEFERRED && self.queue.len > 0 {
            self.shade_queue(s, shader, lanes);
        }
    }
}

/// The queue's lighting ([`Band::shade_queue`]), run apart from the walk
/// that filled it ([`Simd::apart`]): one copy of it in the band kernel
/// instead of one per place that queues fragments.
struct LightApart<'a, S: Simd, Sh: Shader> {
    band: &'a mut Band,
    shader: &'a Sh,
    lanes: &'a Sh::Lanes<S>,
}

impl<S: Simd, Sh: Shader> Apart<S> for LightApart<'_, S, Sh> {
    type Output = ();
    #[inline(always)]
    fn run(self, s: S) {
        self.band.shade_queue(s, self.shader, self.lanes);
    }
}
