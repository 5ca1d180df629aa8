//! A band's depth buffer, its first pixel at the start of a cache line.
//!
//! A band's rows are a multiple of 16 pixels long ([`STRIDE_PIXELS`]), so
//! with the first pixel on a 64-byte boundary every row starts on one too:
//! a block of 8 depths (32 bytes) then never straddles two cache lines,
//! and a pair of blocks (`pairs.rs`, one 512-bit vector on AVX-512) fills
//! exactly one. The colour buffers are placed half a page from the depths
//! (`skew` in `mod.rs`), so they get the same alignment. A `Vec<f32>`
//! starts wherever the allocator puts it, only sure to be 16-byte aligned:
//! 16 bytes past a line, half the blocks of 8 and every pair straddle two
//! lines (BENCHMARKS.md, "Span blocks in pairs, and rows on cache lines").

use std::ops::{Deref, DerefMut};

/// Pixels per row of a band's buffers are a multiple of this: 64 bytes of
/// `f32`.
pub(super) const STRIDE_PIXELS: usize = 16;

/// The depths, `len` of them, from a 64-byte boundary of `buffer`.
#[derive(Debug, Default)]
pub(super) struct DepthBuffer {
    buffer: Vec<f32>,
    start: usize,
    len: usize,
}

/// Room before the first pixel to reach a 64-byte boundary.
const PAD: usize = STRIDE_PIXELS - 1;

impl DepthBuffer {
    /// Makes room for `len` depths (see `Band::reserve`).
    pub fn reserve(&mut self, len: usize) {
        let total = len + PAD;
        self.buffer.reserve(total.saturating_sub(self.buffer.len()));
    }

    /// Holds `len` depths: the ones it held stay where they were, new ones
    /// are 1. Where growing moved the buffer to another alignment, every
    /// depth is 1 (pixel `i`'s old depth is no longer at index `i`).
    pub fn resize(&mut self, len: usize) {
        self.buffer.resize(len + PAD, 1.0);
        let address = self.buffer.as_ptr() as usize;
        // `f32`s are 4-byte aligned, so the distance is whole depths.
        let start = (64 - address % 64) % 64 / 4;
        if start != self.start {
            self.buffer.fill(1.0);
            self.start = start;
        }
        self.len = len;
    }
}

impl Deref for DepthBuffer {
    type Target = [f32];
    #[inline(always)]
    fn deref(&self) -> &[f32] {
        &self.buffer[self.start..][..self.len]
    }
}

impl DerefMut for DepthBuffer {
    #[inline(always)]
    fn deref_mut(&mut self) -> &mut [f32] {
        &mut self.buffer[self.start..][..self.len]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_first_depth_is_on_a_cache_line_and_new_ones_are_one() {
        let mut depths = DepthBuffer::default();
        for len in [0, 1, 16, 100, 4096, 30_000, 17] {
            depths.resize(len);
            assert_eq!(depths.len(), len);
            assert!((depths.as_ptr() as usize).is_multiple_of(64) || len == 0);
            assert!(depths.iter().all(|&d| d == 1.0));
        }
    }

    #[test]
    fn depths_stay_where_they_were_when_the_buffer_does_not_move() {
        let mut depths = DepthBuffer::default();
        depths.reserve(1000);
        depths.resize(100);
        depths[7] = 0.25;
        depths.resize(1000);
        assert_eq!(depths[7], 0.25);
        assert_eq!(depths[99..].iter().filter(|&&d| d != 1.0).count(), 0);
    }
}
