//! A triangle's walk over one band (see `mod.rs`): its rows, in blocks of
//! 8 pixels or in spans, the depth test, and each block's colours (flat,
//! Gouraud) or its place in Phong's queue (`queue.rs`).

use std::cell::Cell;

use super::gather::gathers;
use super::pairs::{fill_span, inside};
use super::{Band, Pass};
use crate::raster::tiled::setup::{plane_count, Plane, Triangle, Walk, GOURAUD_OF_ALL, PLANES};
use crate::raster::{Interpolation, SUBPIXEL_HALF, SUBPIXEL_ONE};
use crate::shade::{FlatShader, GouraudShader, Shader, MAX_ATTRS};
use crate::simd::{Apart, Lanes, Simd, Vf, Vi};

impl Band {
    /// Draws one triangle's rows within this band (rows `band_y0..band_y1`),
    /// `color` its flat colour (packed).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub fn draw<S: Simd, Sh: Shader>(
        &mut self,
        s: S,
        t: &Triangle,
        color: u32,
        planes: &[Plane],
        shader: &Sh,
        lanes: &Sh::Lanes<S>,
        interpolation: Interpolation,
        band_y0: u32,
        band_y1: u32,
        pass: Pass,
    ) {
        let rows = t.y0.max(band_y0 as i32)..t.y1.min(band_y1 as i32);
        if rows.is_empty() {
            return;
        }
        // Only a back face drawn pays for the copy.
        let turned;
        let planes = if Sh::DEFERRED && t.flip != 1.0 {
            turned = turn_normals(planes, t.flip);
            &turned[..planes.len()]
        } else {
            planes
        };
        let mut dx = [Vf::splat(s, 0.0); 2 + MAX_ATTRS];
        let (mut origin, mut dy) = ([0f32; 2 + MAX_ATTRS], [0f32; 2 + MAX_ATTRS]);
        for j in 0..plane_count(Sh::ATTRS) {
            dx[j] = Vf::splat(s, planes[j].dx);
            origin[j] = planes[j].at_origin;
            dy[j] = planes[j].dy;
        }
        let ties = Cell::new(false);
        let fill = Fill {
            t,
            color,
            planes,
            shader,
            shader_lanes: lanes,
            interpolation,
            pass,
            dx,
            origin: Vf::load(s, &origin),
            dy: Vf::load(s, &dy),
            lanes: Vf::lanes(s),
            ties: &ties,
            watch_ties: self.watch_ties,
        };
        // Nearly every triangle is drawn once per pixel in a shading pass:
        // its blocks skip the two tests for the other cases. The others
        // (self-crossing polygons' triangles, counting passes) are rare and
        // all take spans, exact for any triangle, so that only one more walk
        // is compiled.
        let plain = t.once == 0 && pass == Pass::Shade;
        match (t.walk, plain) {
            (Walk::Blocks, true) => self.walk_blocks(s, &fill, rows, band_y0),
            // Phong's spans in a function of their own: their loop keeps
            // its registers whatever the blocks' walk holds (BENCHMARKS.md,
            // "Phong's spans apart; a small triangle's passes in one mask").
            (Walk::Spans, true) if Sh::DEFERRED && !Sh::ALL_METHODS => {
                let spans = PhongSpans {
                    band: self,
                    fill: &fill,
                    rows,
                    band_y0,
                };
                s.apart(spans)
            }
            (Walk::Spans, true) => self.walk_spans::<S, Sh, true>(s, &fill, rows, band_y0),
            (_, false) => self.walk_spans::<S, Sh, false>(s, &fill, rows, band_y0),
        }
        if Sh::DEFERRED && self.pending.len > 0 {
            self.interpolate_pending(s, &fill);
        }
        self.ties |= ties.get();
    }

    /// Blocks of 8 pixels along each row of the bounding box, with the edge
    /// functions in `i32` lanes: one add per edge per block, no multiply (a
    /// shading pass of a triangle drawn once per pixel, see `draw`).
    #[inline(always)]
    fn walk_blocks<S: Simd, Sh: Shader>(
        &mut self,
        s: S,
        f: &Fill<'_, S, Sh>,
        rows: std::ops::Range<i32>,
        band_y0: u32,
    ) {
        let t = f.t;
        let first_block = t.x0 & !7;
        let block_count = (t.x1 - first_block + 7) / 8;
        let x_start = i64::from(first_block) * SUBPIXEL_ONE + SUBPIXEL_HALF;
        let y_start = i64::from(rows.start) * SUBPIXEL_ONE + SUBPIXEL_HALF;
        let lane_index = Vi::ramp(s);
        let mut row_e = [Vi::splat(s, 0); 3];
        let mut block_step = [Vi::splat(s, 0); 3];
        let mut row_step = [Vi::splat(s, 0); 3];
        for i in 0..3 {
            // `Triangle::edges` checked that these stay within i32 over the box.
            let at_start = i64::from(t.a[i]) * x_start + i64::from(t.b[i]) * y_start + t.c[i];
            let a = t.a[i] * SUBPIXEL_ONE as i32;
            row_e[i] = Vi::splat(s, at_start as i32) + lane_index * Vi::splat(s, a);
            block_step[i] = Vi::splat(s, a * 8);
            row_step[i] = Vi::splat(s, t.b[i] * SUBPIXEL_ONE as i32);
        }
        // A fourth function, `x1 - 1 - x`, keeps out the lanes past the box
        // (and so maybe past the image) in the last block.
        let right_start = Vi::splat(s, t.x1 - 1 - first_block) - lane_index;
        let steps = (block_step, row_step, Vi::splat(s, 8));
        // Boxes one or two blocks wide (most triangles of a dense mesh seen
        // small) get the blocks of a row unrolled: no loop over blocks,
        // whose exit would often be mispredicted.
        match block_count {
            1 => self.walk_rows(s, f, rows, band_y0, 1, row_e, right_start, steps),
            2 => self.walk_rows(s, f, rows, band_y0, 2, row_e, right_start, steps),
            blocks => self.walk_rows(s, f, rows, band_y0, blocks, row_e, right_start, steps),
        }
    }

    /// [`Band::walk_blocks`]'s rows, `blocks` blocks each, from the edge
    /// functions at the first block of the first row; a row's planes are
    /// evaluated only once one of its blocks has a lane inside.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn walk_rows<S: Simd, Sh: Shader>(
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
        if gathers::<Sh>(blocks, rows.len()) {
            let steps = (block_step, row_step, right_step);
            return self.walk_gathered(s, f, rows, band_y0, blocks, row_e, right_start, steps);
        }
        let first_block = f.t.x0 & !7;
        // Counted here, in a register: adding to `self.fragments` per block
        // chained every block to the last one's store.
        let mut fragments = 0;
        for y in rows {
            let row_start = (y as u32 - band_y0) as usize * self.stride;
            let (mut e, mut right) = (row_e, right_start);
            let mut row = None;
            for block in 0..blocks {
                let inside = inside_then_step(&mut e, &mut right, &block_step, right_step);
                if inside.mask_bits() != 0 {
                    let x = first_block + block * 8;
                    let row = *row.get_or_insert_with(|| f.row(y));
                    fragments +=
                        self.block::<S, Sh, true>(s, f, inside, row_start + x as usize, x, &row);
                }
            }
            for i in 0..3 {
                row_e[i] = row_e[i] + row_step[i];
            }
        }
        self.fragments += u64::from(fragments);
    }

    /// Each row's covered span `[left, right)`, found exactly per edge, then
    /// filled in blocks of 8 with no edge arithmetic per pixel.
    #[inline(always)]
    fn walk_spans<S: Simd, Sh: Shader, const PLAIN: bool>(
        &mut self,
        s: S,
        f: &Fill<'_, S, Sh>,
        rows: std::ops::Range<i32>,
        band_y0: u32,
    ) {
        let t = f.t;
        let mut fragments = 0;
        for y in rows {
            let Some((left, right)) = span(t, y) else {
                continue;
            };
            let row_start = (y as u32 - band_y0) as usize * self.stride;
            let row = f.row_all(y);
            let mut x = left & !7;
            if PLAIN && !Sh::DEFERRED {
                // The row's blocks as whole chunks of its buffers, two at a
                // time (`pairs.rs`).
                let first = x as usize;
                let blocks = (right as usize - first).div_ceil(8);
                let (depth, color) = self.row_buffers(row_start + first, 8 * blocks);
                fragments += fill_span(s, f, &row, (x, left, right), depth, color);
                continue;
            }
            if PLAIN && !Sh::ALL_METHODS {
                // Phong's (the three methods at once keep blocks of 8).
                fragments += self.queue_span(s, f, &row, row_start, (x, left, right));
                continue;
            }
            while x < right {
                let inside = inside(s, (x, left, right));
                fragments +=
                    self.block::<S, Sh, PLAIN>(s, f, inside, row_start + x as usize, x, &row);
                x += 8;
            }
        }
        self.fragments += u64::from(fragments);
    }

    /// Depth-tests, shades and writes the lanes of `inside` in the block at
    /// column `x` (buffer index `at`) of `row`, and returns how many passed
    /// the depth test. `PLAIN`: a shading pass of a triangle that is not
    /// part of a self-crossing polygon.
    #[inline(always)]
    pub(super) fn block<S: Simd, Sh: Shader, const PLAIN: bool>(
        &mut self,
        s: S,
        f: &Fill<'_, S, Sh>,
        inside: Vi<S>,
        at: usize,
        x: i32,
        row: &Row,
    ) -> u32 {
        let mut inside = inside;
        if !PLAIN && f.t.once != 0 {
            let bits = self.once_per_pixel(inside.mask_bits(), at, f.t.once);
            inside = Vi::from_mask_bits(s, bits);
        }
        if !PLAIN && f.pass == Pass::Count {
            let bits = inside.mask_bits();
            for (i, count) in self.counts[at..at + 8].iter_mut().enumerate() {
                *count += (bits >> i) & 1;
            }
            return 0;
        }
        let x = f.column(x);
        if !Sh::DEFERRED {
            let (depth, color) = self.row_buffers(at, 8);
            let (depth, color) = ((&mut depth[..8]).try_into(), (&mut color[..8]).try_into());
            return shade_block::<S, Sh, false>(
                s,
                f,
                inside,
                x,
                (row, None),
                depth.unwrap(),
                color.unwrap(),
            );
        }
        let depth_slot: &mut [f32; 8] = (&mut self.depth[at..at + 8]).try_into().unwrap();
        let pass = depth_test(s, f, inside, x, row, depth_slot);
        self.passed(s, f, x, pass, at, row)
    }

    /// What follows a block's depth test: the lanes `pass` (columns `x`
    /// from the triangle's first, buffer index `at`) queued for a deferred
    /// shader, whole or packed; returns how many passed.
    #[inline(always)]
    fn passed<S: Simd, Sh: Shader>(
        &mut self,
        s: S,
        f: &Fill<'_, S, Sh>,
        x: Vf<S>,
        pass: Vi<S>,
        at: usize,
        row: &Row,
    ) -> u32 {
        let bits = pass.mask_bits();
        if bits == 0 {
            return 0;
        }
        if Sh::ALL_METHODS {
            self.flat_and_gouraud(s, f, x, row.dy, pass, at);
        }
        if bits == 0xff {
            // A whole block (inside large triangles): no packing needed.
            let index = Vi::ramp(s) + Vi::splat(s, at as i32);
            self.queue_block(s, f, x, row, index.0);
        } else {
            self.pend(s, f, x, row.dy, bits, at);
        }
        bits.count_ones()
    }

    /// Flat's and Gouraud's colours of the lanes `pass` of a block (columns
    /// `x` from the triangle's first, `dy` rows down, buffer index `at`) of
    /// a triangle set up for the three methods at once: with the
    /// operations of their own frames' blocks (`shade_block`, the planes'
    /// values at the row as `origin + dy·rows`), so the bytes are the same.
    #[inline(always)]
    fn flat_and_gouraud<S: Simd, Sh: Shader>(
        &mut self,
        s: S,
        f: &Fill<'_, S, Sh>,
        x: Vf<S>,
        dy: f32,
        pass: Vi<S>,
        at: usize,
    ) {
        let none = [Vf::splat(s, 0.0); MAX_ATTRS];
        let flat = FlatShader.shade(&(), s, f.color, f.t.flip, &none);
        let plane = |j: usize| &f.planes[GOURAUD_OF_ALL[j]];
        let colors = interpolate_planes(
            f.interpolation,
            (3, 0),
            x,
            |j| Vf::splat(s, plane(j).dx),
            |j| Vf::splat(s, plane(j).at_origin + plane(j).dy * dy),
            None,
        );
        let gouraud = GouraudShader.shade(&(), s, f.color, f.t.flip, &colors);
        for (k, colors) in [flat, gouraud].into_iter().enumerate() {
            let slot = &mut self.others[k][self.others_at[k] + at..][..8];
            let slot: &mut [i32; 8] = slot.try_into().unwrap();
            let old = Vi(s.i_load(slot), s);
            s.i_store(Vi::select(pass, colors, old).0, slot);
        }
    }

    /// The depth and colour buffers from buffer index `at`, `len` pixels.
    #[inline(always)]
    fn row_buffers(&mut self, at: usize, len: usize) -> (&mut [f32], &mut [i32]) {
        let color = &mut self.color[self.color_at + at..][..len];
        (&mut self.depth[at..][..len], color)
    }

    /// Drops the lanes a self-crossing polygon already drew, and marks the rest.
    #[cold]
    fn once_per_pixel(&mut self, bits: u32, at: usize, polygon: u32) -> u32 {
        let stamps = self.stamps();
        let mut out = bits;
        for i in 0..8 {
            if bits & (1 << i) != 0 {
                if stamps[at + i] == polygon {
                    out &= !(1 << i);
                } else {
                    stamps[at + i] = polygon;
                }
            }
        }
        out
    }
}

/// A deferred shader's spans ([`Band::walk_spans`]), run apart from the
/// rest of the band ([`Simd::apart`]).
struct PhongSpans<'a, 'f, S: Simd, Sh: Shader> {
    band: &'a mut Band,
    fill: &'a Fill<'f, S, Sh>,
    rows: std::ops::Range<i32>,
    band_y0: u32,
}

impl<S: Simd, Sh: Shader> Apart<S> for PhongSpans<'_, '_, S, Sh> {
    type Output = ();
    #[inline(always)]
    fn run(self, s: S) {
        let (rows, y0) = (self.rows, self.band_y0);
        self.band.queue.older = self.band.queue.len > 0;
        self.band.walk_spans::<S, Sh, true>(s, self.fill, rows, y0);
    }
}

/// One row of a triangle: its distance from the triangle's first row, and
/// planes' values at the triangle's first column: the depth plane's always,
/// the others too unless the shader is deferred. A deferred shader (Phong,
/// eight planes) evaluates them per block that passes the depth test, with
/// the same operations (`origin + dy·rows`), so the values are the same.
#[derive(Clone, Copy)]
pub(super) struct Row {
    pub(super) dy: f32,
    pub(super) values: [f32; 2 + MAX_ATTRS],
    /// Whether `values` holds every plane.
    pub(super) all: bool,
}

/// What every block of one triangle needs.
pub(super) struct Fill<'a, S: Simd, Sh: Shader> {
    pub(super) t: &'a Triangle,
    /// The triangle's flat colour, packed.
    pub(super) color: u32,
    pub(super) planes: &'a [Plane],
    pub(super) shader: &'a Sh,
    pub(super) shader_lanes: &'a Sh::Lanes<S>,
    pub(super) interpolation: Interpolation,
    pub(super) pass: Pass,
    /// Each plane's step per pixel along x, in all lanes.
    pub(super) dx: [Vf<S>; 2 + MAX_ATTRS],
    /// Plane `j`'s value at the triangle's first pixel and step per row, in lane `j`.
    pub(super) origin: Vf<S>,
    pub(super) dy: Vf<S>,
    /// 0, 1, … 7.
    pub(super) lanes: Vf<S>,
    /// Whether a depth test met a tie ([`Band::ties`]). Set, never cleared,
    /// and only when there is one: no store per block. A reference, so that
    /// `Fill` holds no cell of its own: a `&Fill` then tells the compiler
    /// that no store changes it, and the walk's loops keep its planes in
    /// registers (with the cell inside, a Gouraud quad took 1.14× longer).
    pub(super) ties: &'a Cell<bool>,
    /// Whether to look for ties at all ([`Band::watch_ties`]).
    pub(super) watch_ties: bool,
}

impl<S: Simd, Sh: Shader> Fill<'_, S, Sh> {
    /// Row `y` (see [`Row`]).
    #[inline(always)]
    pub(super) fn row(&self, y: i32) -> Row {
        if !Sh::DEFERRED {
            return self.row_all(y);
        }
        let dy = (y - self.t.y0) as f32;
        let mut values = [0f32; 2 + MAX_ATTRS];
        values[0] = self.plane_at_row(0, dy);
        Row {
            dy,
            values,
            all: false,
        }
    }

    /// Row `y` with every plane's value (large triangles: many blocks per row).
    #[inline(always)]
    fn row_all(&self, y: i32) -> Row {
        let dy = (y - self.t.y0) as f32;
        let mut values = [0f32; 2 + MAX_ATTRS];
        // Every plane at once, with the operations of `plane_at_row` (a
        // product, then a sum: the same values).
        (self.origin + self.dy * dy).store(&mut values);
        Row {
            dy,
            values,
            all: true,
        }
    }

    /// The columns of the block at image column `x`, relative to the
    /// triangle's first, as the planes take them.
    #[inline(always)]
    pub(super) fn column(&self, x: i32) -> Vf<S> {
        self.lanes + Vf::splat(self.lanes.1, (x - self.t.x0) as f32)
    }

    /// Plane `j`'s value at the triangle's first column, `dy` rows down.
    #[inline(always)]
    fn plane_at_row(&self, j: usize, dy: f32) -> f32 {
        self.planes[j].at_origin + self.planes[j].dy * dy
    }
}

/// The lanes of a block inside the triangle (its three edge functions `e`
/// and the box's right end `right` all at least 0); then `e` and `right`
/// stepped to the next block of the row.
#[inline(always)]
pub(super) fn inside_then_step<S: Simd>(
    e: &mut [Vi<S>; 3],
    right: &mut Vi<S>,
    block_step: &[Vi<S>; 3],
    right_step: Vi<S>,
) -> Vi<S> {
    let inside = (e[0] | e[1] | e[2] | *right).gt(Vi::splat(right.1, -1));
    for i in 0..3 {
        e[i] = e[i] + block_step[i];
    }
    *right = *right - right_step;
    inside
}

/// The depth test of the lanes of `inside` in a block of `row` whose
/// columns relative to the triangle's first are `x` ([`Fill::column`]):
/// the lanes that passed, whose depth is now stored.
#[inline(always)]
pub(super) fn depth_test<S: Simd, Sh: Shader>(
    s: S,
    f: &Fill<'_, S, Sh>,
    inside: Vi<S>,
    x: Vf<S>,
    row: &Row,
    depth_slot: &mut [f32; 8],
) -> Vi<S> {
    let depth = x.mul_add(f.dx[0], Vf::splat(s, row.values[0]));
    let stored = Vf::load(s, depth_slot);
    let nearer = depth.lt(stored);
    let pass = inside & nearer;
    if pass.mask_bits() != 0 {
        Vf::select(pass, depth, stored).store(depth_slot);
    }
    // A tie: neither nearer nor farther than the depth stored. A fragment
    // at exactly 1, the cleared depth, counts too, though no order draws
    // it: a false alarm (the frame is drawn again in the scene's order),
    // and no constant 1 kept in a vector register, which cost the span
    // loops of frames that do not watch (BENCHMARKS.md, "Ties watched only
    // where they matter").
    if f.watch_ties && (inside.mask_bits() & !(nearer | stored.lt(depth)).mask_bits()) != 0 {
        f.ties.set(true);
    }
    pass
}

/// A block of a shader that is not deferred (flat, Gouraud): depth test,
/// colours of the lanes that passed written; returns how many passed.
/// `SPAN`: a block of a large triangle's span, where nearly every block is
/// whole. `row_w`: w for the whole row if the caller has it ([`row_w`]).
#[inline(always)]
pub(super) fn shade_block<S: Simd, Sh: Shader, const SPAN: bool>(
    s: S,
    f: &Fill<'_, S, Sh>,
    inside: Vi<S>,
    x: Vf<S>,
    (row, row_w): (&Row, Option<Vf<S>>),
    depth_slot: &mut [f32; 8],
    color_slot: &mut [i32; 8],
) -> u32 {
    let pass = depth_test(s, f, inside, x, row, depth_slot);
    let bits = pass.mask_bits();
    if bits == 0 {
        return 0;
    }
    let planes = (Sh::ATTRS, Sh::SCALE_FREE);
    let at_row = |j| Vf::splat(s, row.values[j]);
    let attrs = interpolate_planes(f.interpolation, planes, x, |k| f.dx[k], at_row, row_w);
    let colors = f.shader.shade(f.shader_lanes, s, f.color, f.t.flip, &attrs);
    // A whole block of a span is stored without reading the old colours
    // (a load that waits for the line, where a store would not). Blocks
    // of small triangles are always blended: a branch on it is
    // mispredicted on meshes whose blocks are partly covered at random
    // (12 % of the teapot's 1920×1080 flat frame).
    if SPAN && bits == 0xff {
        s.i_store(colors.0, color_slot);
        return 8;
    }
    let old = Vi(s.i_load(color_slot), s);
    s.i_store(Vi::select(pass, colors, old).0, color_slot);
    bits.count_ones()
}

/// `planes` (the first of the result) with a deferred shader's normal
/// (attributes 0..3, planes 2..5) turned by `flip`, −1 for a back face
/// drawn.
///
/// A plane whose three numbers are negated gives exactly the negated
/// values wherever it is evaluated (rounding is symmetric), so every
/// interpolated normal is the turned one, bit for bit, without a test and
/// three multiplications per block or pair: the compiler computed those
/// products for every block and discarded them on front faces.
#[inline(always)]
fn turn_normals(planes: &[Plane], flip: f32) -> [Plane; PLANES] {
    let mut turned = [Plane::default(); PLANES];
    turned[..planes.len()].copy_from_slice(planes);
    for plane in &mut turned[2..5] {
        *plane = Plane {
            at_origin: plane.at_origin * flip,
            dx: plane.dx * flip,
            dy: plane.dy * flip,
        };
    }
    turned
}

/// The attributes at columns `x` of the triangle, given each plane's value
/// at the first column of the fragments' rows (for a deferred shader, the
/// normal already turned for back faces: [`turn_normals`]).
#[inline(always)]
pub(super) fn interpolate<S: Simd, Sh: Shader>(
    f: &Fill<'_, S, Sh>,
    x: Vf<S>,
    at_row: impl Fn(usize) -> Vf<S>,
) -> [Vf<S>; MAX_ATTRS] {
    let (count, scale_free) = (Sh::ATTRS, Sh::SCALE_FREE);
    let planes = (count, scale_free);
    interpolate_planes(f.interpolation, planes, x, |k| f.dx[k], at_row, None)
}

/// Attributes `0..count` at columns `x`, from each plane's gradient
/// `dx(j)` and its value at the first column of the row `at_row(j)`:
/// plane 1 is 1/w, attribute `k` is plane `2 + k` (divided by w in
/// perspective mode, so multiplied back by the interpolated w, except the
/// first `scale_free`, see [`Shader::SCALE_FREE`]). `row_w`: w itself
/// when the caller has it for the whole row ([`row_w`]), else `None`.
#[inline(always)]
pub(super) fn interpolate_planes<L: Lanes>(
    interpolation: Interpolation,
    (count, scale_free): (usize, usize),
    x: L,
    dx: impl Fn(usize) -> L,
    at_row: impl Fn(usize) -> L,
    row_w: Option<L>,
) -> [L; MAX_ATTRS] {
    let mut attrs = [x.splat_like(0.0); MAX_ATTRS];
    for k in 0..count {
        attrs[k] = x.mul_add(dx(2 + k), at_row(2 + k));
    }
    if needs_w(interpolation, (count, scale_free)) {
        // No closure (`Option::unwrap_or_else`): see `Surface::radiance`
        // (left out of line, it cost Phong's meshes a third more time).
        let w = match row_w {
            Some(w) => w,
            None => x.mul_add(dx(1), at_row(1)).recip(),
        };
        for k in scale_free..count {
            attrs[k] = attrs[k] * w;
        }
    }
    attrs
}

/// Whether every attribute [`interpolate_planes`] gives at every column
/// from `first` to `last` (lanes of exact integers in `f32`, each lane its
/// own range) is below 2^31 or NaN, for the same planes and row w; `false`
/// when that is not known. Gouraud's conversion to bytes may then drop its
/// guard against larger values (`pairs.rs`).
///
/// When w is the row's (`row_w`, one value for the whole row) or not
/// needed, an attribute is `x·dx + at_row`, then perhaps times w, in
/// correctly rounded steps of the one variable x: monotonic in x, as each
/// exact step is and rounding is. So its values between two columns lie
/// between its values there, which are computed with the same operations.
/// Where w is taken per pixel it is an estimated reciprocal, which need
/// not be monotonic: `false`.
#[inline(always)]
pub(super) fn planes_below<L: Lanes>(
    interpolation: Interpolation,
    (count, scale_free): (usize, usize),
    (first, last): (L, L),
    dx: impl Fn(usize) -> L,
    at_row: impl Fn(usize) -> L,
    row_w: Option<L>,
) -> bool {
    if count == 0 || (row_w.is_none() && needs_w(interpolation, (count, scale_free))) {
        return false;
    }
    let planes = (count, scale_free);
    let first = interpolate_planes(interpolation, planes, first, &dx, &at_row, row_w);
    let last = interpolate_planes(interpolation, planes, last, &dx, &at_row, row_w);
    // `gt` is false for NaN, so a NaN at an end says no.
    let limit = first[0].splat_like(2_147_483_648.0);
    let mut below = limit.gt(first[0]) & limit.gt(last[0]);
    for k in 1..count {
        below = below & limit.gt(first[k]) & limit.gt(last[k]);
    }
    L::mask_bits(below) == u32::MAX >> (32 - L::LANES)
}

/// Whether every lane of attributes `0..count` of `values` lies in
/// `[0, 256)`; `false` for no attributes. Given the attributes at a span's
/// two ends, where they are monotonic in x between them (see
/// [`planes_below`]), so are all between: [`known::BYTES`].
///
/// [`known::BYTES`]: crate::shade::known::BYTES
#[inline(always)]
pub(super) fn all_in_bytes<L: Lanes>(count: usize, values: &[L; MAX_ATTRS]) -> bool {
    let all = u32::MAX >> (32 - L::LANES);
    let mut inside = if count == 0 { 0 } else { all };
    let (zero, top) = (values[0].splat_like(0.0), values[0].splat_like(256.0));
    for &v in &values[..count] {
        // `gt` is false for NaN: a NaN is not below the top.
        inside &= L::mask_bits(top.gt(v)) & !L::mask_bits(zero.gt(v));
    }
    inside == all
}

/// Whether [`interpolate_planes`] multiplies attributes by w: in
/// perspective mode, for `count` attributes of which the first
/// `scale_free` are not.
#[inline(always)]
pub(super) fn needs_w(interpolation: Interpolation, (count, scale_free): (usize, usize)) -> bool {
    interpolation == Interpolation::Perspective && count > scale_free
}

/// w along a row of a triangle whose 1/w plane does not change along x
/// (`dx1 == 0`: a triangle parallel to the rows, whose w changes from row
/// to row only; one parallel to the screen, its corners' w equal, is drawn
/// in screen mode, `Triangle::interpolated`), given the plane's value at
/// the row `inv_w`, in the lanes of `like`; `None` otherwise, or when w is
/// not needed (see [`interpolate_planes`]).
///
/// Each lane's w is then `recip(x·dx1 + inv_w)` with `x·dx1 = ±0` (the
/// columns are finite), which is `recip(inv_w)` exactly for a nonzero
/// `inv_w`: the same bytes as per pixel, one reciprocal per row instead
/// of one per pixel (a fifth of a Gouraud pair's instructions).
#[inline(always)]
pub(super) fn row_w<L: Lanes>(
    interpolation: Interpolation,
    planes: (usize, usize),
    dx1: f32,
    inv_w: f32,
    like: L,
) -> Option<L> {
    // No closure (`bool::then`): see `Surface::radiance`.
    if needs_w(interpolation, planes) && dx1 == 0.0 && inv_w != 0.0 {
        Some(like.splat_like(inv_w).recip())
    } else {
        None
    }
}

/// The columns `[left, right)` of row `y` whose centres are inside the
/// triangle, within its bounding box; `None` when there are none.
///
/// Per edge, the test `a·(256·X + 128) + r ≥ 0` (with `r = b·y_s + c`) is
/// monotonic in the column X: the boundary is estimated with one `f64`
/// multiplication by a reciprocal and then settled by evaluating the exact
/// integer test at the estimate and its neighbour. The estimate is first
/// clamped next to the box, where it is within one column of the truth.
#[inline(always)]
fn span(t: &Triangle, y: i32) -> Option<(i32, i32)> {
    let y_s = i64::from(y) * SUBPIXEL_ONE + SUBPIXEL_HALF;
    let (mut left, mut right) = (i64::from(t.x0), i64::from(t.x1));
    for i in 0..3 {
        let a = i64::from(t.a[i]);
        let r = i64::from(t.b[i]) * y_s + t.c[i];
        let inside = |x: i64| a * (x * SUBPIXEL_ONE + SUBPIXEL_HALF) + r >= 0;
        if a == 0 {
            if r < 0 {
                return None;
            }
            continue;
        }
        // Boundary column: a·(256·X + 128) + r = 0.
        let estimate = (-(r + a * SUBPIXEL_HALF) as f64) / ((a * SUBPIXEL_ONE) as f64);
        if a > 0 {
            // Inside from the first X with the test true.
            let mut x = (estimate.ceil() as i64).clamp(left - 1, right + 1);
            if !inside(x) {
                x += 1;
            } else if inside(x - 1) {
                x -= 1;
            }
            left = left.max(x);
        } else {
            // Inside up to the last X with the test true.
            let mut x = (estimate.floor() as i64).clamp(left - 1, right + 1);
            if !inside(x) {
                x -= 1;
            } else if inside(x + 1) {
                x += 1;
            }
            right = right.min(x + 1);
        }
        if left >= right {
            return None;
        }
    }
    Some((left as i32, right as i32))
}
