//! The inner loop: one band of image rows, its triangles, blocks of 8 pixels.
//!
//! A band has a depth buffer and a packed-colour buffer for its rows (one
//! set per thread, reused band after band, so they stay in cache), whose
//! rows start on cache lines (`depth_buffer.rs`). Only the
//! columns its triangles' boxes reach are read back; the rest of its rows
//! is written as background directly (a dense model in a wide image leaves
//! most of each band empty: clearing and reading back whole rows was a
//! fifth of the bunny's 1920×1080 flat frame). The depths read back are set
//! to 1 again as each row is written out, while they are in the first-level
//! cache, so the next band starts cleared: a pass of its own over a
//! 1920-pixel band (123 KB of depths, in the second-level cache) was 7 % of
//! the full-screen Gouraud quad. For each
//! triangle binned to the band, in submission order, each row of its
//! bounding box within the band is walked in blocks of 8 pixels aligned to
//! multiples of 8, in one of two ways chosen at setup (`setup::Walk`):
//!
//! * **blocks** (small triangles, nearly all of a dense mesh): the three
//!   edge functions in 8 × `i32` lanes, one add per edge and block, a lane
//!   in when all three are ≥ 0 (the top-left bias is in `c`). `i32` is exact
//!   here because setup checked the functions' range over the box;
//! * **spans** (large triangles): per row, each edge's boundary column is
//!   found exactly (see `span` in `walk.rs`) and the span between them is filled with
//!   no edge arithmetic per pixel, the columns stepped in vectors. Nearly
//!   all of a span's blocks are whole: flat and Gouraud draw them, two at
//!   a time in 16 lanes (`pairs.rs`), and Phong lights such pairs in place,
//!   a row's run of them at once; when all lanes pass the depth test, the
//!   colours are stored without reading back the old ones.
//!
//! Then per block: depth test "less" (depth from its plane), and shading
//! specialised per method by the [`crate::shade::Shader`] type parameter. Phong does not
//! interpolate or shade block by block: small triangles leave most lanes of
//! a block empty (a 12-pixel triangle fills 2 lanes per block on average),
//! so the positions of the fragments that pass the depth test are packed
//! into whole lanes and interpolated 8 at a time (whole blocks of large
//! triangles skip the packing), with the same operations as a block would
//! use, so the values do not depend on the packing. The interpolated
//! fragments go into a second queue and are lit 64 at a time (four groups
//! of 16 lanes lit together, so that their long dependency chains overlap;
//! 16 in WebAssembly; a function of its own on x86, see `queue.rs`), and
//! their colours written back in the order they were queued (a later
//! fragment of the same pixel is written later, as without the queues; the
//! position queue is emptied at the end of each triangle; eight queued
//! pixels in a row are written with one store, eight scattered ones with
//! one bounds check). New positions join the pending ones in registers
//! (packed, rotated behind them, blended), and the pending ones are kept
//! as whole vectors: appending them to memory at their count and reading
//! 8 back from the front made every read wait for two stores to reach the
//! cache, 3–7 % of a dense mesh's Phong frame. A triangle whose box is one
//! or two blocks wide and at most 64 pixels in blocks does not pend row by
//! row: its passes are gathered as the bits of one `u64` and packed after
//! its last row (`gather.rs`). Phong's large triangles' spans run in a
//! function of their own (`Simd::apart`), so that the small triangles'
//! walk, compiled beside them, does not take their loop's registers.
//!
//! Other shaders evaluate their planes once per row (only the depth plane
//! for Phong, whose eight planes would mostly be evaluated for rows whose
//! blocks are hidden).
//!
//! The three methods at once ([`crate::shade::Shader::ALL_METHODS`]): Phong's walk as
//! above, and each block that passes the depth test also gets flat's and
//! Gouraud's colours, computed as their own blocks would compute them and
//! blended into two more colour buffers; `finish` then reads each buffer
//! into its image (the depth, and so what is background, is the same).
//!
//! In an image larger than a core's second-level cache, `finish` writes
//! a band's rows four blocks (96 bytes) at a time, as three aligned 32-byte
//! streaming stores: they do not read the image's lines into the caches
//! first, nor push out what the next frame needs there (the mesh, the
//! bins, the band buffers). On a dense mesh at 1920×1080 that takes 2–8 %
//! off the frame; the full-screen quad, which has nothing else to keep in
//! the caches, loses a little (BENCHMARKS.md, "Streaming the image out").
//!
//! Nothing here allocates. Everything is `#[inline(always)]` so that
//! [`crate::simd::dispatch`] compiles it for AVX2 and for the portable path.
//!
//! This file holds a band's storage, its start and its finish (colours and
//! counts out to the image); `walk.rs` a triangle's walk over the band
//! (rows, blocks, spans, the depth test, flat's and Gouraud's blocks);
//! `pairs.rs` a span's blocks two at a time (flat, Gouraud);
//! `phong_span.rs` Phong's spans, their whole pairs lit in place;
//! `gather.rs` Phong's small triangles' passes in one mask; `queue.rs`
//! Phong's queues.

// Loops over the three edges, channels and planes index several arrays at once.
#![allow(clippy::needless_range_loop)]

mod depth_buffer;
mod gather;
mod pairs;
mod phong_span;
mod queue;
mod walk;

use std::ops::Range;

use self::depth_buffer::{DepthBuffer, STRIDE_PIXELS};
use super::setup::BAND_ROWS;
use crate::shade::MAX_ATTRS;
use crate::simd::{Simd, Vf, Vi};

/// A band's working storage, kept between frames.
///
/// Aligned to 128 bytes (two cache lines, the unit the processor's
/// prefetcher pairs): the bands of different threads sit side by side in
/// one vector, and their counters are written per block; sharing a line
/// made two threads three times slower than one on the full-screen quad.
#[derive(Debug, Default)]
#[repr(align(128))]
pub(crate) struct Band {
    /// Row stride of the buffers: the image width rounded up to
    /// [`STRIDE_PIXELS`].
    stride: usize,
    /// The columns this frame's triangles may draw, in whole blocks of 8.
    columns: Range<usize>,
    depth: DepthBuffer,
    /// Whether every depth in `depth` is 1 (cleared): the last
    /// [`Band::finish`] of a band sets back to 1 the depths it read, while
    /// they are in the first-level cache, so that the next band need not
    /// clear its rows in a pass of its own.
    depth_clear: bool,
    /// Packed colours; pixel `i`'s is at `color_at + i` (see [`skew`]).
    color: Vec<i32>,
    color_at: usize,
    /// Flat's and Gouraud's packed colours when the shader draws the three
    /// methods at once ([`crate::shade::Shader::ALL_METHODS`]); pixel `i`'s at
    /// `others_at[k] + i`.
    others: [Vec<i32>; 2],
    others_at: [usize; 2],
    /// Coverage counts (coverage pass only).
    pub counts: Vec<u32>,
    /// Polygon stamps for self-crossing polygons, cleared when first used in a frame.
    stamp: Vec<u32>,
    stamp_clean: bool,
    /// Positions of the current triangle's fragments waiting to be
    /// interpolated, then fragments waiting to be lit (deferred shaders).
    pending: Pending,
    queue: Queue,
    /// Fragments that passed the depth test this frame.
    pub fragments: u64,
    /// Pixels drawn this frame.
    pub covered: u64,
    /// Whether a fragment met a depth equal to one a fragment of another
    /// triangle stored this frame ([`Band::ties`]).
    ties: bool,
    /// Whether the depth tests look for ties at all ([`Band::watch_ties`]).
    watch_ties: bool,
}

/// The most queued fragments a deferred shader lights at once: the
/// queue's capacity. Each backend lights `16 · Simd::LIT_GROUPS`.
const QUEUE_LIT: usize = 16 * crate::simd::MAX_LIT_GROUPS;

/// The queue's room past [`QUEUE_LIT`]: the most fragments queued at once
/// (a pair of whole blocks, `phong_span.rs`), and so the most left over once
/// the queue is lit.
const QUEUE_ROOM: usize = 16;

/// Fragments of a deferred shader, packed into whole lanes: their
/// attributes and buffer indices, in the order they passed the depth test.
///
/// Aligned to a cache line, and each attribute's row is whole lines long,
/// so that a group of 16 (one 512-bit vector, the unit of
/// [`Band::shade_queue`] and of `phong_span.rs`'s appends) never straddles two
/// lines. Without the alignment the queue sat 48 bytes past a line in
/// `Band`, every 512-bit load and store of it touched two, and the Zen 4
/// EPYC lit the full-screen quad 3–5 % slower (BENCHMARKS.md, "The
/// lighting queue on cache lines").
#[derive(Debug)]
#[repr(align(64))]
struct Queue {
    attrs: [[f32; QUEUE_LIT + QUEUE_ROOM]; MAX_ATTRS],
    at: [i32; QUEUE_LIT + QUEUE_ROOM],
    len: usize,
    /// Whether the queue may hold fragments of triangles before the one
    /// being drawn, which must be lit before any of its pixels are lit in
    /// place (`phong_span.rs`, `Band::light_pairs`).
    older: bool,
}

// Each attribute's row, and the indices after them, start on a line.
const _: () = assert!(((QUEUE_LIT + QUEUE_ROOM) * 4).is_multiple_of(64));

impl Default for Queue {
    fn default() -> Queue {
        Queue {
            attrs: [[0.0; QUEUE_LIT + QUEUE_ROOM]; MAX_ATTRS],
            at: [0; QUEUE_LIT + QUEUE_ROOM],
            len: 0,
            older: false,
        }
    }
}

/// Fragments of the triangle being drawn that passed the depth test, packed
/// into whole lanes: column from the triangle's first, rows from its first
/// row, buffer index; the first `len` (at most 7) lanes hold them. Written
/// and read as whole vectors: a load that spans two earlier stores at
/// different offsets waits for both to reach the cache (no store-to-load
/// forwarding), and appending at `len` then reading from lane 0 did that
/// once per 8 fragments.
#[derive(Debug, Default)]
#[repr(align(32))]
struct Pending {
    x: [f32; 8],
    dy: [f32; 8],
    at: [i32; 8],
    len: usize,
}

/// How [`Band::finish`] writes image rows out.
#[derive(Debug, Clone, Copy)]
pub(crate) struct RowWrite {
    /// The background colour, packed as in the band.
    pub background: i32,
    /// Whether the rows are written with streaming stores (the frame's
    /// choice: `streams` in `tiled/mod.rs`).
    pub stream: bool,
}

/// Which of a band's colour buffers [`Band::finish`] reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Colors {
    /// The shader's own.
    Shader,
    /// Flat's, drawn beside Phong's ([`crate::shade::Shader::ALL_METHODS`]).
    Flat,
    /// Gouraud's, drawn beside Phong's.
    Gouraud,
}

/// Whether [`Band::finish`] leaves the depths it read as they are, for
/// another colour buffer's read, or sets them back to 1: its last read.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Depths {
    /// Left as drawn: another of the band's colour buffers is read next.
    Keep,
    /// Set back to 1 as they are read: the band's last read.
    Clear,
}

/// What a band pass does with covered pixels.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Pass {
    /// Depth-test, shade and write.
    Shade,
    /// Count fragments per pixel, no depth test.
    Count,
}

impl Band {
    /// Makes room for the buffers of bands `width` pixels wide. Called for
    /// every thread's band before a frame: which thread draws which band
    /// varies, and a thread that drew none for many frames would otherwise
    /// allocate when it first does (a frame after the first must not).
    /// `all_methods`: room for flat's and Gouraud's colours too.
    pub fn reserve(&mut self, width: u32, all_methods: bool) {
        fn room<T>(buffer: &mut Vec<T>, len: usize) {
            buffer.reserve(len.saturating_sub(buffer.len()));
        }
        let len = (width as usize).next_multiple_of(STRIDE_PIXELS) * BAND_ROWS as usize;
        self.depth.reserve(len);
        room(&mut self.color, len + SKEW_ROOM);
        room(&mut self.stamp, len);
        if all_methods {
            for buffer in &mut self.others {
                room(buffer, len + SKEW_ROOM);
            }
        }
    }

    /// Prepares the buffers for a frame of `width` pixels per row, whose
    /// triangles' boxes lie within `columns`. Only the blocks of 8 that
    /// hold those columns are drawn, and [`Band::finish`] reads back only
    /// those (the rest is background); their depths are cleared here unless
    /// the last band's `finish` left them cleared. The colour buffer is not cleared:
    /// `finish` takes the background wherever the depth is still 1.
    /// `all_methods`: flat's and Gouraud's buffers are drawn too.
    pub fn begin(
        &mut self,
        width: u32,
        rows: u32,
        pass: Pass,
        columns: Range<usize>,
        all_methods: bool,
    ) {
        self.stride = (width as usize).next_multiple_of(STRIDE_PIXELS);
        let len = self.stride * rows as usize;
        self.fragments = 0;
        self.covered = 0;
        self.ties = false;
        self.queue.len = 0;
        self.pending.len = 0;
        self.stamp_clean = false;
        match pass {
            Pass::Shade => {
                self.columns =
                    (columns.start & !7)..columns.end.next_multiple_of(8).min(self.stride);
                self.color.resize(len + SKEW_ROOM, 0);
                // Rows past the last frame's are 1; so is all the rest when
                // the last band was finished (`depth_clear`).
                self.depth.resize(len);
                self.color_at = skew(&self.depth, &self.color);
                if all_methods {
                    for (buffer, at) in self.others.iter_mut().zip(&mut self.others_at) {
                        buffer.resize(len + SKEW_ROOM, 0);
                        *at = skew(&self.depth, buffer);
                    }
                }
                if !self.depth_clear {
                    for row in self.depth.chunks_exact_mut(self.stride) {
                        row[self.columns.clone()].fill(1.0);
                    }
                }
                // Until `finish` has read them back.
                self.depth_clear = false;
            }
            Pass::Count => {
                self.counts.clear();
                self.counts.resize(len, 0);
            }
        }
    }

    /// Whether a fragment of this frame met a depth equal to the one stored
    /// at its pixel by an earlier triangle: the depth test "less" then
    /// kept the first drawn, so the pixel may depend on the order the
    /// triangles were drawn in. Without a tie it does not: at every pixel
    /// one fragment is nearer than all others, whatever the order. (A
    /// fragment at exactly the cleared depth, 1, counts too: never drawn,
    /// a false alarm, but no constant for the loops to keep.)
    pub fn ties(&self) -> bool {
        self.ties
    }

    /// Whether this band's depth tests look for ties ([`Band::ties`]; if
    /// not, it stays false). Only a frame drawn in another order than the
    /// scene's needs to know, and the look cost a full-screen Gouraud
    /// triangle's fill 5–17 % when every frame watched (BENCHMARKS.md,
    /// "Ties watched only where they matter"): every other frame skips it.
    pub fn watch_ties(&mut self, on: bool) {
        self.watch_ties = on;
    }

    /// Copies the finished band's `colors` into its rows of the image,
    /// `out`, rows of `width` pixels (`write.background` where the depth
    /// is still 1, or outside the drawn columns; streaming stores if
    /// `write.stream`), and counts the pixels drawn.
    ///
    /// With [`Depths::Clear`] (the band's last read) each row's drawn
    /// columns, the only depths a triangle may write, are set back to 1
    /// right after the row is read, while they are in the first-level
    /// cache, and the next band skips its clearing pass.
    #[inline(always)]
    pub fn finish<S: Simd>(
        &mut self,
        s: S,
        out: &mut [crate::color::Rgb8],
        width: u32,
        write: RowWrite,
        colors: Colors,
        depths: Depths,
    ) {
        let RowWrite { background, stream } = write;
        let clear = depths == Depths::Clear;
        let (color, color_at) = match colors {
            Colors::Shader => (&self.color, self.color_at),
            Colors::Flat => (&self.others[0], self.others_at[0]),
            Colors::Gouraud => (&self.others[1], self.others_at[1]),
        };
        let width = width as usize;
        let mut covered = 0;
        let background = Vi::splat(s, background);
        let mut bg = [0; 8];
        s.i_store(background.0, &mut bg);
        // Whole blocks of 8 pixels (the drawn ones from the buffers, the
        // others background); in a large image four at a time from the
        // first whose bytes start at a multiple of 32, so that each four
        // fill three aligned streaming stores; the last `width % 8` pixels
        // one by one.
        let whole = width / 8;
        let drawn = (self.columns.start / 8).min(whole)..(self.columns.end / 8).min(whole);
        for (row, pixels) in out.chunks_mut(width).enumerate() {
            let start = row * self.stride;
            let bytes: &mut [u8] = bytemuck::cast_slice_mut(pixels);
            let (blocks, rest) = bytes.split_at_mut(24 * whole);
            let blocks = blocks.as_chunks_mut::<24>().0;
            // Not a closure: see `Surface::radiance`.
            let block = BlockColors {
                s,
                depth: &self.depth[start..],
                color: &color[color_at + start..],
                drawn: drawn.clone(),
                background,
            };
            if stream {
                let address = blocks.as_ptr() as usize;
                let head = (0..4).find(|h| (address + 24 * h).is_multiple_of(32));
                let head = head.unwrap_or(0).min(whole);
                let fours = (whole - head) / 4;
                for b in (0..head).chain(head + 4 * fours..whole) {
                    s.i_store_rgb(block.at(b, &mut covered).0, &mut blocks[b]);
                }
                let groups = blocks[head..head + 4 * fours].chunks_exact_mut(4);
                for (k, four) in groups.enumerate() {
                    let b = head + 4 * k;
                    let v = [
                        block.at(b, &mut covered).0,
                        block.at(b + 1, &mut covered).0,
                        block.at(b + 2, &mut covered).0,
                        block.at(b + 3, &mut covered).0,
                    ];
                    s.i_stream_rgb(v, four.as_flattened_mut().try_into().unwrap());
                }
            } else {
                // Background, the drawn blocks, background: no test per block.
                for b in (0..drawn.start).chain(drawn.end..whole) {
                    s.i_store_rgb(background.0, &mut blocks[b]);
                }
                for b in drawn.clone() {
                    s.i_store_rgb(block.drawn(b, &mut covered).0, &mut blocks[b]);
                }
            }
            let done = 8 * whole;
            for (j, dst) in rest.chunks_exact_mut(3).enumerate() {
                let at = start + done + j;
                let c = if self.columns.contains(&(done + j)) && self.depth[at] < 1.0 {
                    covered += 1;
                    color[color_at + at]
                } else {
                    bg[0]
                };
                dst.copy_from_slice(&c.to_le_bytes()[..3]);
            }
            if clear {
                self.depth[start..start + self.stride][self.columns.clone()].fill(1.0);
            }
        }
        // Every row was read: `out` holds the band's rows.
        debug_assert_eq!(out.len() / width, self.depth.len() / self.stride);
        self.depth_clear = clear;
        if stream {
            s.store_fence();
        }
        self.covered = u64::from(covered);
    }

    /// Copies coverage counts into their rows of `out`.
    #[inline(always)]
    pub fn finish_counts(&self, out: &mut [u32], width: u32) {
        let width = width as usize;
        for (row, counts) in out.chunks_mut(width).enumerate() {
            let start = row * self.stride;
            counts.copy_from_slice(&self.counts[start..start + width]);
        }
    }

    fn stamps(&mut self) -> &mut [u32] {
        if !self.stamp_clean {
            self.stamp.clear();
            self.stamp
                .resize(self.depth.len().max(self.counts.len()), 0);
            self.stamp_clean = true;
        }
        &mut self.stamp
    }
}

/// One row's blocks of 8 pixels as [`Band::finish`] writes them out.
struct BlockColors<'a, S: Simd> {
    s: S,
    /// The row's depths and colours.
    depth: &'a [f32],
    color: &'a [i32],
    /// The blocks drawn; the others are background.
    drawn: Range<usize>,
    background: Vi<S>,
}

impl<S: Simd> BlockColors<'_, S> {
    /// Block `b`'s colours, packed, counting its pixels drawn into `covered`.
    #[inline(always)]
    fn at(&self, b: usize, covered: &mut u32) -> Vi<S> {
        if self.drawn.contains(&b) {
            self.drawn(b, covered)
        } else {
            self.background
        }
    }

    /// Block `b`'s colours, one of the drawn blocks.
    #[inline(always)]
    fn drawn(&self, b: usize, covered: &mut u32) -> Vi<S> {
        let s = self.s;
        let depth = Vf::load(s, self.depth[8 * b..8 * b + 8].try_into().unwrap());
        let drawn = depth.lt(Vf::splat(s, 1.0));
        *covered += drawn.mask_bits().count_ones();
        let color = Vi(
            s.i_load(self.color[8 * b..8 * b + 8].try_into().unwrap()),
            s,
        );
        Vi::select(drawn, color, self.background)
    }
}

/// Room for [`skew`]'s offset: a page of `i32`.
const SKEW_ROOM: usize = 1024;

/// Where pixel 0's colour goes in `color` so that a pixel's colour and
/// its depth are half a page apart modulo 4 KiB.
///
/// Both buffers are large allocations, which start at the same offset in
/// their pages; with equal lengths, the colour of pixel `i` and its depth
/// then shared their address's low 12 bits, which is all the processor
/// compares to decide whether a load may depend on an earlier store ("4K
/// aliasing"): every colour load waited for the depth store just before it.
fn skew(depth: &[f32], color: &[i32]) -> usize {
    let apart = (depth.as_ptr() as usize).wrapping_sub(color.as_ptr() as usize) % 4096;
    // Bytes to add to the colour's address: half a page past the depth's.
    let shift = (apart + 2048) % 4096;
    shift / 4
}

/// Rows `y0..y1` of the image: the band with index `band`.
pub(crate) fn band_rows(band: usize, height: u32) -> (u32, u32) {
    let y0 = band as u32 * BAND_ROWS;
    (y0, (y0 + BAND_ROWS).min(height))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::color::Rgb8;
    use crate::simd::{dispatch, Kernel, SimdLevel};

    /// A band of `width` pixels per row whose drawn columns are `columns`,
    /// with a depth and a colour per pixel (some still at depth 1, and
    /// stale depths outside the drawn columns), written out at `offset`
    /// pixels into a larger buffer, with streaming stores if `stream`.
    struct Finish {
        width: u32,
        columns: Range<usize>,
        offset: usize,
        stream: bool,
    }

    const BACKGROUND: i32 = 0x0030_2010;

    impl Kernel for Finish {
        type Output = (Vec<Rgb8>, u64, Vec<Rgb8>, u64);
        fn run<S: Simd>(self, s: S) -> Self::Output {
            let rows = 5;
            let mut band = Band::default();
            band.begin(self.width, rows, Pass::Shade, self.columns, false);
            let stride = band.stride;
            let mut want = Vec::new();
            let mut covered = 0;
            for y in 0..rows as usize {
                for x in 0..self.width as usize {
                    let at = y * stride + x;
                    let near = (x * 7 + y * 3) % 5 != 0;
                    // Outside the drawn columns, depths from another frame.
                    if near || !band.columns.contains(&x) {
                        band.depth[at] = 0.5;
                    }
                    let color = (x as i32 * 37 + y as i32 * 101) & 0xff_ffff;
                    band.color[band.color_at + at] = color;
                    let drawn = near && band.columns.contains(&x);
                    covered += u64::from(drawn);
                    let c = if drawn { color } else { BACKGROUND };
                    want.push(Rgb8::new(c as u8, (c >> 8) as u8, (c >> 16) as u8));
                }
            }
            let len = (self.width * rows) as usize;
            let mut out = vec![Rgb8::new(1, 2, 3); len + 64];
            let image = &mut out[self.offset..self.offset + len];
            let write = RowWrite {
                background: BACKGROUND,
                stream: self.stream,
            };
            band.finish(s, image, self.width, write, Colors::Shader, Depths::Clear);
            (image.to_vec(), band.covered, want, covered)
        }
    }

    /// Perspective interpolation with Phong's normal scale-free
    /// ([`crate::shade::Shader::SCALE_FREE`]): the normal is its plane's
    /// value (`n/w`), whose direction is that of `n/w · w` within f32
    /// rounding, and the position is `p/w · w`.
    struct ScaleFree;

    impl Kernel for ScaleFree {
        type Output = ();
        fn run<S: Simd>(self, s: S) {
            use crate::raster::Interpolation;
            use crate::simd::Vf;
            // Planes 0 (depth), 1 (1/w), then n/w and p/w: gradients and
            // values at the row's first column, 1/w from 1/2 down to 1/40.
            let dx = [0.0, -0.0006, 0.002, -0.001, 0.0007, 0.01, -0.02, 0.003];
            let row = [0.5, 0.5, 0.3, -0.2, 0.4, 1.5, 0.25, -3.0];
            let x = Vf::load(s, &std::array::from_fn(|i| (i * 101) as f32));
            let attrs = walk::interpolate_planes(
                Interpolation::Perspective,
                (6, 3),
                x,
                |j| Vf::splat(s, dx[j]),
                |j| Vf::splat(s, row[j]),
                None,
            );
            let lanes = |v: Vf<S>| {
                let mut out = [0f32; 8];
                v.store(&mut out);
                out
            };
            let got = attrs.map(lanes);
            for i in 0..8 {
                let x = (i * 101) as f32;
                let plane = |j: usize| x.mul_add(dx[j], row[j]);
                let inv_w = plane(1);
                assert!(inv_w > 0.02, "lane {i}: 1/w = {inv_w}");
                let w = f64::from(inv_w).recip();
                // The normal: the plane's value (a backend's multiply-add
                // may round twice), not multiplied by w.
                for k in 0..3 {
                    let want = plane(2 + k);
                    let error = (got[k][i] - want).abs() / want.abs();
                    assert!(
                        error < 1e-6,
                        "lane {i}, normal {k}: {} for {want}",
                        got[k][i]
                    );
                }
                // Its direction against n = (n/w)·w in f64.
                let n: [f64; 3] = std::array::from_fn(|k| f64::from(plane(2 + k)) * w);
                let length = n.iter().map(|c| c * c).sum::<f64>().sqrt();
                let got_length = (0..3)
                    .map(|k| f64::from(got[k][i]).powi(2))
                    .sum::<f64>()
                    .sqrt();
                for k in 0..3 {
                    let error = (f64::from(got[k][i]) / got_length - n[k] / length).abs();
                    assert!(
                        error < 1e-6,
                        "lane {i}, normal {k}: direction off by {error}"
                    );
                }
                // The position: (p/w)·w with w from the backend's reciprocal.
                for k in 3..6 {
                    let want = f64::from(plane(2 + k)) * w;
                    let error = (f64::from(got[k][i]) - want).abs() / want.abs();
                    assert!(error < 1e-5, "lane {i}, position {k}: off by {error}");
                }
            }
        }
    }

    #[test]
    fn phong_normals_interpolate_without_w() {
        for level in SimdLevel::supported() {
            dispatch(level, ScaleFree);
        }
    }

    /// w taken once per row ([`walk::row_w`]) gives the same bits as w per
    /// pixel wherever it is taken, and is not taken elsewhere.
    struct RowW;

    impl Kernel for RowW {
        type Output = ();
        fn run<S: Simd>(self, s: S) {
            use crate::raster::Interpolation::{Perspective, Screen};
            use crate::simd::Vf;
            let bits = |attrs: [Vf<S>; MAX_ATTRS]| {
                attrs.map(|v| {
                    let mut out = [0f32; 8];
                    v.store(&mut out);
                    out.map(f32::to_bits)
                })
            };
            let columns = [
                [0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0],
                [-9.0, 4093.0, 1e6, -0.0, 0.5, 17.0, 1919.0, -3.5],
            ];
            for inv_w in [
                1.0,
                0.5,
                1.0 / 3.0,
                1.0 / 40.0,
                7.25e-3,
                3.0e-7,
                1.0e30,
                -0.25,
            ] {
                for dx1 in [0.0, -0.0] {
                    for x in columns {
                        let x = Vf::load(s, &x);
                        let dx = [0.0, dx1, 0.01, -0.02, 0.003];
                        let row = [0.5, inv_w, 0.25, 0.75, -0.125];
                        let w = walk::row_w(Perspective, (3, 0), dx1, inv_w, x);
                        assert!(w.is_some(), "1/w = {inv_w}, dx = {dx1}");
                        let at = |w| {
                            walk::interpolate_planes(
                                Perspective,
                                (3, 0),
                                x,
                                |j| Vf::splat(s, dx[j]),
                                |j| Vf::splat(s, row[j]),
                                w,
                            )
                        };
                        assert!(bits(at(w)) == bits(at(None)), "1/w = {inv_w}, dx = {dx1}");
                    }
                }
            }
            let x = Vf::splat(s, 1.0);
            // A 1/w that changes along the row, a zero 1/w, no perspective,
            // or no attribute that needs w.
            assert!(walk::row_w(Perspective, (3, 0), 1e-9, 0.5, x).is_none());
            assert!(walk::row_w(Perspective, (3, 0), 0.0, 0.0, x).is_none());
            assert!(walk::row_w(Screen, (3, 0), 0.0, 0.5, x).is_none());
            assert!(walk::row_w(Perspective, (3, 3), 0.0, 0.5, x).is_none());
        }
    }

    #[test]
    fn w_per_row_is_w_per_pixel() {
        for level in SimdLevel::supported() {
            dispatch(level, RowW);
        }
    }

    /// [`walk::planes_below`] says yes only where the attributes at every
    /// column between the ends are below 2^31 or NaN (checked column by
    /// column, 16 at a time), and says yes to ordinary colours.
    struct PlanesBelow;

    impl Kernel for PlanesBelow {
        type Output = ();
        fn run<S: Simd>(self, s: S) {
            use crate::raster::Interpolation::{self, Perspective, Screen};
            use crate::simd::Lanes;
            let ramp = s.f16_load(&std::array::from_fn(|i| i as f32));
            let splat = |v: f32| ramp.splat_like(v);
            let (first, last) = (3.0, 1002.0);
            let colours = ([0.0, 0.0, 0.1, -0.2, 0.05], [0.5, 0.0, 10.0, 250.0, 128.0]);
            let with = |k: usize, dx: f32, row: f32| {
                let (mut d, mut r) = colours;
                (d[2 + k], r[2 + k]) = (dx, row);
                (d, r)
            };
            // The interpolation, the planes (dx, value at the row), the
            // row's 1/w if any, the attributes (count, scale-free), and
            // the verdict.
            type Case = (
                Interpolation,
                ([f32; 5], [f32; 5]),
                Option<f32>,
                (usize, usize),
                bool,
            );
            let cases: [Case; 13] = [
                (Screen, colours, None, (3, 0), true),
                (Screen, with(0, 3e6, 0.0), None, (3, 0), false),
                (Screen, with(1, 6e6, -3e9), None, (3, 0), false),
                (Screen, with(2, -3e6, 0.0), None, (3, 0), true),
                (Screen, with(0, -1e3, 2.147e9), None, (3, 0), true),
                (Screen, with(1, f32::NAN, 0.0), None, (3, 0), false),
                (Screen, with(2, 0.0, f32::INFINITY), None, (3, 0), false),
                (Screen, colours, None, (0, 0), false),
                (Perspective, colours, None, (3, 0), false),
                (Perspective, colours, None, (3, 3), true),
                (Perspective, colours, Some(0.01), (3, 0), true),
                (Perspective, colours, Some(1e-8), (3, 0), false),
                (Perspective, with(0, -1e4, 0.0), Some(1e-5), (3, 0), true),
            ];
            for (k, (interpolation, (dx, row), inv_w, planes, want)) in
                cases.into_iter().enumerate()
            {
                let w = inv_w.map(|v| splat(v).recip());
                let (dx, row) = (|j| splat(dx[j]), |j| splat(row[j]));
                let got = walk::planes_below(
                    interpolation,
                    planes,
                    (splat(first), splat(last)),
                    dx,
                    row,
                    w,
                );
                assert_eq!(got, want, "case {k}");
                if !got {
                    continue;
                }
                for x in (first as usize..=last as usize).step_by(16) {
                    let x = ramp + splat(x as f32);
                    let attrs = walk::interpolate_planes(interpolation, planes, x, dx, row, w);
                    for a in &attrs[..planes.0] {
                        let mut lanes = [0f32; 16];
                        a.store_to(&mut lanes);
                        assert!(
                            lanes.iter().all(|v| v.is_nan() || *v < 2_147_483_648.0),
                            "case {k}: {lanes:?}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn planes_below_2_31_between_the_ends() {
        for level in SimdLevel::supported() {
            dispatch(level, PlanesBelow);
        }
    }

    /// [`walk::all_in_bytes`] of attributes `x·dx + at_row` times w (as
    /// the pairs of blocks compute them) at a span's two ends says yes
    /// exactly where every column between them is in `[0, 256)` (checked
    /// column by column), and says yes to ordinary colours.
    struct EndsInBytes;

    impl Kernel for EndsInBytes {
        type Output = ();
        fn run<S: Simd>(self, s: S) {
            use crate::simd::Lanes;
            let ramp = s.f16_load(&std::array::from_fn(|i| i as f32));
            let splat = |v: f32| ramp.splat_like(v);
            let (first, last) = (3.0f32, 1002.0f32);
            let colours = ([0.1, -0.2, 0.05], [10.0, 250.0, 128.0]);
            let with = |k: usize, dx: f32, row: f32| {
                let (mut d, mut r) = colours;
                (d[k], r[k]) = (dx, row);
                (d, r)
            };
            // The planes (dx, value at the row), w, and the verdict.
            type Case = (([f32; 3], [f32; 3]), f32, bool);
            let cases: [Case; 12] = [
                (colours, 1.0, true),
                (with(0, -0.02, 10.0), 1.0, false),
                (with(1, 0.01, 250.0), 1.0, false),
                (with(2, 0.0, 255.5), 1.0, true),
                (with(2, 0.0, 256.0), 1.0, false),
                (with(0, 0.0, -0.0), 1.0, true),
                (with(0, -1e-9, 0.0), 1.0, false),
                (with(1, f32::NAN, 0.0), 1.0, false),
                (with(2, 0.0, f32::INFINITY), 1.0, false),
                (([1e-3, 0.0, 2e-4], [0.1, 2.5, 0.0]), 100.0, true),
                (([-1e-6, 0.0, 0.0], [2.5e-3, 2.5, 0.0]), 100.0, true),
                (([0.0; 3], [1e-45; 3]), 1e-3, true),
            ];
            for (k, ((dx, row), w, want)) in cases.into_iter().enumerate() {
                let attributes = |x| {
                    let mut a = [splat(0.0); MAX_ATTRS];
                    for j in 0..3 {
                        a[j] = Lanes::mul_add(x, splat(dx[j]), splat(row[j])) * splat(w);
                    }
                    a
                };
                let got = walk::all_in_bytes(3, &attributes(splat(0.0).halves([first, last])));
                assert_eq!(got, want, "case {k}");
                let mut every = true;
                for x in (first as usize..=last as usize).step_by(16) {
                    let columns = std::array::from_fn(|i| ((x + i) as f32).min(last));
                    let values = attributes(s.f16_load(&columns));
                    for v in &values[..3] {
                        let mut lanes = [0f32; 16];
                        v.store_to(&mut lanes);
                        every &= lanes.iter().all(|&v| (0.0..256.0).contains(&v));
                    }
                }
                assert_eq!(got, every, "case {k}: the ends against every column");
            }
            assert!(!walk::all_in_bytes(0, &[splat(1.0); MAX_ATTRS]));
        }
    }

    #[test]
    fn in_bytes_between_the_ends_exactly_where_every_column_is() {
        for level in SimdLevel::supported() {
            dispatch(level, EndsInBytes);
        }
    }

    /// Every pixel and the count come out right whatever the output's
    /// alignment (each offset of 1 pixel moves it by 3 bytes, so 32
    /// offsets give every address modulo 32), with and without streaming
    /// stores, on every SIMD level this machine has.
    #[test]
    fn finish_writes_every_pixel_at_every_alignment() {
        for level in SimdLevel::supported() {
            // Drawn runs of every length modulo 4 blocks, starting at every
            // block modulo 4; none drawn; rows narrower than four blocks.
            let cases = [
                (203, 0..203),
                (203, 41..150),
                (256, 8..200),
                (67, 60..67),
                (203, 0..0),
                (203, 96..104),
                (203, 100..118),
                (203, 24..58),
                (203, 120..197),
                (29, 3..20),
                (29, 0..29),
                (7, 0..7),
            ];
            for (width, columns) in cases {
                for stream in [false, true] {
                    for offset in 0..32 {
                        let finish = Finish {
                            width,
                            columns: columns.clone(),
                            offset,
                            stream,
                        };
                        let (got, count, want, want_count) = dispatch(level, finish);
                        let case = format!("{level:?}, width {width}, columns {columns:?}, stream {stream}, offset {offset}");
                        assert!(got == want, "{case}: pixels differ");
                        assert_eq!(count, want_count, "{case}: count");
                    }
                }
            }
        }
    }
}
