//! The fast rasterizer: per-vertex work once, triangle setup in parallel
//! chunks with per-chunk binning into bands of 16 rows, then bands
//! rasterized in parallel with SIMD blocks of 8 pixels.
//!
//! The pipeline of a frame:
//!
//! 1. **Vertices** (parallel): the frame's vertex stage transforms and
//!    snaps each position once (`frame/window.rs`, run through
//!    [`crate::raster::VertexStage`]), beside Gouraud's lighting of each
//!    distinct (position, normal), 8 at a time.
//! 2. **Setup** (parallel, in chunks of consecutive polygons): each chunk
//!    is walked by the frame's polygon assembly (`frame/assemble.rs`,
//!    through [`crate::raster::PolygonSource`]: facing, culling
//!    before any attribute is read, clipping when needed), which hands its
//!    polygons to the chunk's sink (`chunk.rs`). A front-facing triangle
//!    needing no clipping (nearly all of them) goes straight from the
//!    projected positions: the bounding box's pixel centres (none: done),
//!    edge functions and attribute planes. Anything else (clipped, back
//!    faces drawn, polygons) is split into the fan both rasterizers use.
//!    Each triangle is copied, with its planes, into the bin of every band
//!    it touches (for the three methods at once, a mesh triangle with its
//!    corners' indices instead: the band solves its planes, see below). Flat
//!    shading lights the chunk's front polygons after its walk, 8 at a
//!    time; a flat triangle holds its polygon's index into the chunk's
//!    colours.
//! 3. **Bands** (parallel): a band reads its chunks' bins in order (see
//!    `band/`), looking up flat triangles' colours in their chunk's, then
//!    writes its rows of the image.
//!
//! The threads share setup's chunks and the bands by their estimated cost
//! (`order.rs`), so that they end each phase together. Where a band runs
//! on a core apart from the one that set up a chunk (measured every tenth
//! of a second, `placement.rs`), it hands that chunk's bin back to memory
//! once read, so that the next frame's setup need not take its lines back
//! from the band's core.
//!
//! What must hold, and why it is built this way:
//!
//! * **The same pixels as the scanline reference.** Every polygon goes
//!   through the same assembly (`frame/assemble.rs`: clipping, viewport
//!   transform and snapping, facing) and the same [`crate::raster::fan`] as
//!   the scanline rasterizer drawing fans, so both see identical snapped
//!   triangles; coverage is then
//!   exact integer arithmetic in both (see `setup.rs`). Colours differ only
//!   by f32 rounding: within 1/255, checked by the equivalence tests.
//! * **Per-vertex work once per vertex.** Positions are transformed and
//!   snapped once each; a polygon whose vertices are all inside the view
//!   volume and guard band (nearly all of them) skips clipping, because
//!   clipping would return it unchanged.
//! * **Order is kept.** Chunks are set up in parallel, each binning into its
//!   own per-band lists; a band walks the chunks in order, so triangles meet
//!   the depth test in submission order, as with one thread, and the image
//!   does not depend on the thread count. On request
//!   ([`TiledRasterizer::watch_ties`]) the depth tests watch for a tie, a
//!   fragment at the depth an earlier triangle stored
//!   ([`TiledRasterizer::met_ties`]): only then could another order give
//!   other pixels, which lets the frame draw a mesh in a spatial order of
//!   its own (`frame/spatial.rs`) and fall back to the mesh's on a tie.
//!   Frames in the scene's own order do not watch: the look costs the
//!   fill of large triangles.
//! * **Memory is read in streams.** Bins hold copies of their triangles, so
//!   a band reads one contiguous run instead of chasing indices; each thread
//!   draws its bands one after another in the same depth and colour
//!   buffers, which stay in its cache.
//! * **No allocation per frame in steady state.** All buffers live in
//!   [`TiledRasterizer`] and are cleared, not dropped, between frames.
//! * **The three methods at once share the geometry.** The viewer's three
//!   panels (and `render_methods`' callers) draw one scene with each method.
//!   Steps 1 and 2 do not depend on the method but for the attributes, so
//!   `render_methods` runs them once with the attributes of all three
//!   (Phong's normal and position, Gouraud's colours, flat's colour in the
//!   triangle: `setup::ALL_ATTRS`). The three images share coverage and
//!   depth too, so each band walks and depth-tests each triangle once:
//!   Phong's shader drives the walk, and every block that passes the depth
//!   test also writes flat's and Gouraud's colours into buffers of their
//!   own ([`AllMethods`]). Every plane is solved on its own, clipping
//!   interpolates each attribute on its own, and each method's colours are
//!   computed with its own frame's operations, so the bytes and counts are
//!   those of three frames (`tests/methods.rs`). Their planes are 11 per
//!   triangle, 132 bytes: a mesh triangle is binned with its corners'
//!   indices instead (`CornerRefs`, read by setup in submission order), and
//!   each band it touches solves them from the corners with setup's
//!   function and inputs (`Frame::planes_of`). On small triangles
//!   (one band, mostly) that costs less than writing and reading them,
//!   most of all in a frame whose bins' memory has gone cold. On meshes of
//!   70k–100k small triangles the three cost about half of three frames
//!   (WebAssembly, 480²), where setup is now the larger part.
//! * **A part of the rows, for threads of their own.** The viewer's
//!   WebAssembly has one thread per worker; two workers each draw half the
//!   rows of the three frames. Every polygon is still projected, faced and
//!   counted (the counts stay the frame's), but a triangle outside the
//!   part's rows gets no edges, attributes, planes or bins, and only the
//!   part's bands are walked: the bytes are those of the frame's rows. So
//!   that no part needs the edges of triangles it does not draw, flat's
//!   lighting of a polygon is counted by the part holding its top pixel
//!   row (`Frame::counts_flat`): those counts add up over the parts, like
//!   the pixels'.

mod band;
mod chunk;
mod order;
mod placement;
mod setup;
mod vertices;

use std::sync::{Mutex, MutexGuard};

use rayon::prelude::*;

use self::band::{band_rows, Band, Colors, Depths, Pass, RowWrite};

use self::chunk::{band_columns, Chunk, Frame, SetupKernel};
use self::order::{band_cost, by_cost, chunk_cost, Borrows, Job, Jobs, Tail};
use self::placement::{HandBack, Placement};
pub(crate) use self::setup::BAND_ROWS;
use self::setup::{plane_count, PLANES};
use self::vertices::{light_vertices, VertexTable};

use crate::color::Rgb8;
use crate::image::Image;
use crate::raster::{PolygonSource, Projected, Rasterize, VertexStage};
use crate::scene::{RenderOptions, RenderStats, Scene, Shading};
use crate::shade::{AllMethods, FlatShader, GouraudShader, Lighting, PhongShader, Shader};
use crate::simd::{dispatch, Kernel, Simd, SimdLevel, WritePrefetch};

/// Setup chunks per thread. A polygon's cost varies tenfold (a back face
/// stops at facing, a front face is set up and binned) and meshes list
/// their visible faces unevenly: with 2 chunks per thread the bunny's four
/// chunks took 1.1, 0.9, 0.43 and 0.39 ms, and one thread waited for the
/// other. Smaller chunks, taken as threads come free, even that out; a
/// band walks one bin per chunk, which costs little more.
const SETUP_CHUNKS_PER_THREAD: usize = 8;

/// The fewest polygons a setup chunk is given (but for a scene of fewer).
const SETUP_CHUNK_POLYGONS: usize = 64;

/// How many chunks setup splits `polygons` into on `threads` threads:
/// [`SETUP_CHUNKS_PER_THREAD`] per thread, but none of fewer than
/// [`SETUP_CHUNK_POLYGONS`] polygons. A scene of a few polygons (the
/// full-screen quad) is then set up in one chunk, on the calling thread,
/// instead of as jobs that cost more to hand out than their polygons do
/// to set up (the quad with two threads: 512×512 flat and Gouraud 5–6 %
/// faster; BENCHMARKS.md, "Scenes of few polygons set up in one chunk").
fn setup_chunks(threads: usize, polygons: usize) -> usize {
    (threads * SETUP_CHUNKS_PER_THREAD)
        .min(polygons.div_ceil(SETUP_CHUNK_POLYGONS))
        .max(1)
}

/// The tiled rasterizer's buffers, reused from frame to frame.
#[derive(Debug)]
pub(crate) struct TiledRasterizer {
    simd: SimdLevel,
    vertices: VertexTable,
    /// Gouraud colours per distinct vertex, front and (culling off) back,
    /// clamped to [0, 1] and kept in byte units
    /// ([`byte_units`](crate::shade::byte_units)).
    lit: Vec<[f32; 3]>,
    lit_back: Vec<[f32; 3]>,
    /// Setup's chunks: the first `chunks_used` are this frame's
    /// ([`setup_chunks`]). The others keep their bins' room for a scene of
    /// more polygons, so that a batch alternating small and large meshes
    /// does not allocate them again.
    chunks: Vec<Chunk>,
    chunks_used: usize,
    /// The frame's lighting, prepared for lanes.
    phong: PhongShader,
    /// The last frame's lighting evaluations: flat's (per polygon) and
    /// Gouraud's (per vertex).
    evaluations: (u64, u64),
    /// One band's working buffers per thread: each thread draws its bands
    /// one after the other in the same buffers, which stay in its cache.
    bands: Vec<Mutex<Band>>,
    /// The frame's setup chunks and bands, as shared between threads
    /// (`order.rs`).
    setup_jobs: Jobs<SetupChunk>,
    band_jobs: Jobs<BandRows>,
    /// Which threads' cores are apart, measured every tenth of a second: a
    /// band hands back the bins set up on a core apart from its own
    /// (`placement.rs`).
    placement: Placement,
    /// Whether the last frame's depth test met a tie ([`Band::ties`]).
    ties: bool,
    /// Whether the depth tests look for ties ([`TiledRasterizer::watch_ties`]).
    watch_ties: bool,
}

/// A setup job's work: its chunk.
struct SetupChunk;

impl Borrows for SetupChunk {
    type At<'a> = &'a mut Chunk;
}

/// A band job's work: its rows of up to three images (flat's, Gouraud's
/// and Phong's; one image's are the first, the others empty).
struct BandRows;

impl Borrows for BandRows {
    type At<'a> = [&'a mut [Rgb8]; 3];
}

/// What a band tells of its walk: fragments shaded, pixels covered, and
/// whether a depth test met a tie ([`Band::ties`]).
type Drawn = (u64, u64, bool);

fn add_drawn(a: Drawn, b: Drawn) -> Drawn {
    (a.0 + b.0, a.1 + b.1, a.2 | b.2)
}

/// What a band drew: see [`Drawn`].
fn drawn(band: &Band) -> Drawn {
    (band.fragments, band.covered, band.ties())
}

/// Where a band's result goes.
enum Output<'a> {
    /// One method's image rows.
    Image {
        rows: &'a mut [Rgb8],
        write: RowWrite,
    },
    /// The rows of flat's, Gouraud's and Phong's images, drawn at once
    /// ([`AllMethods`]), and what solves the planes of the triangles
    /// binned with their corners (see `chunk.rs`, `Bin`): the frame's
    /// attribute sources and window positions.
    Methods {
        rows: [&'a mut [Rgb8]; 3],
        write: RowWrite,
        sources: (&'a Frame<'a>, &'a [Projected]),
    },
    /// Coverage counts.
    Counts(&'a mut [u32]),
}

/// One band's work, compiled per SIMD level. With [`AllMethods`] a bin holds
/// the planes of the three methods at once (`PLANES` per triangle) only for
/// clipped and fan triangles; a mesh triangle's are solved here.
struct BandKernel<'a, S> {
    band: &'a mut Band,
    index: usize,
    bins: Bins<'a>,
    shader: &'a S,
    options: &'a RenderOptions,
    output: Output<'a>,
}

impl<S: Shader> Kernel for BandKernel<'_, S> {
    type Output = ();

    #[inline(always)]
    fn run<Sd: Simd>(self, simd: Sd) {
        let o = self.options;
        let (y0, y1) = band_rows(self.index, o.height);
        let pass = match self.output {
            Output::Image { .. } | Output::Methods { .. } => Pass::Shade,
            Output::Counts(_) => Pass::Count,
        };
        let Bins { chunks, hand_back } = self.bins;
        let columns = band_columns(chunks, self.index);
        let all = S::ALL_METHODS;
        self.band.begin(o.width, y1 - y0, pass, columns, all);
        let stride = if all { PLANES } else { plane_count(S::ATTRS) };
        let lanes = self.shader.lanes(simd);
        // Flat colours are lit per chunk after its setup: a flat triangle
        // holds its polygon's index into the chunk's colours.
        let flat = S::ATTRS == 0 || all;
        for chunk in chunks {
            let bin = &chunk.bins[self.index];
            // The three methods at once: a mesh triangle's planes are
            // solved here, from its corners (see `chunk.rs`, `Bin`). One
            // loop, no closure: a closure left out of line would lose the
            // SIMD level's target features.
            let sources = match self.output {
                Output::Methods { sources, .. } if !bin.corners.is_empty() => Some(sources),
                _ => None,
            };
            let mut stored = bin.planes.chunks_exact(stride);
            for (k, t) in bin.triangles.iter().enumerate() {
                let solved;
                let planes = match sources {
                    Some((frame, projected)) if !bin.corners[k].is_none() => {
                        solved = frame.planes_of(simd, t, &bin.corners[k], projected);
                        &solved[..stride]
                    }
                    _ => stored.next().expect("a stored triangle's planes"),
                };
                let color = if flat {
                    chunk.flat_colors[t.color as usize] as u32
                } else {
                    t.color
                };
                self.band.draw(
                    simd,
                    t,
                    color,
                    planes,
                    self.shader,
                    &lanes,
                    t.interpolation,
                    y0,
                    y1,
                    pass,
                );
            }
            hand_back.bin(chunk, bin);
        }
        self.band.flush(simd, self.shader, &lanes);
        match self.output {
            Output::Image { rows, write } => {
                let (colors, depths) = (Colors::Shader, Depths::Clear);
                self.band.finish(simd, rows, o.width, write, colors, depths)
            }
            Output::Methods { rows, write, .. } => {
                let [flat, gouraud, phong] = rows;
                // Phong's read last: it clears the depths the others read.
                let band = &mut *self.band;
                for (out, colors, depths) in [
                    (flat, Colors::Flat, Depths::Keep),
                    (gouraud, Colors::Gouraud, Depths::Keep),
                    (phong, Colors::Shader, Depths::Clear),
                ] {
                    band.finish(simd, out, o.width, write, colors, depths);
                }
            }
            Output::Counts(counts) => self.band.finish_counts(counts, o.width),
        }
    }
}

/// Whether a frame's image, `width × height`, of a scene of `polygons`, is
/// written out with streaming stores, which go around the caches to
/// memory ([`Simd::i_stream_rgb`]): when it is larger than a core's
/// second-level cache ([`STREAM_BYTES`]) and the scene has enough polygons
/// ([`STREAM_POLYGONS`]) for ordinary stores to push out the geometry that
/// the next frame reads again.
///
/// A scene of few polygons has little to keep: there, ordinary stores are
/// faster, as the image's lines are still in the last-level cache when the
/// next frame writes them. At 1920×1080 on the KVM Zen 5 EPYC, with two
/// threads, ordinary stores took 0.88–0.95 of the streaming stores' time
/// on the full-screen quad (2 triangles), 0.86–0.98 on the sphere (120)
/// and 0.97–0.99 on the teapot (4,032). On the bunny (69,451) and the
/// dragon (100,000) they took up to 1.03 with one thread (1.06 with two),
/// and up to 1.08 on a Zen 4 EPYC (BENCHMARKS.md, "The image streamed out
/// only for scenes of many polygons").
fn streams(width: u32, height: u32, polygons: usize) -> bool {
    let bytes = width as usize * height as usize * 3;
    bytes >= STREAM_BYTES && polygons >= STREAM_POLYGONS
}

/// Images of at least this many bytes may be written out with streaming
/// stores ([`streams`]): larger than a core's second-level cache.
const STREAM_BYTES: usize = 2 << 20;

/// Scenes of at least this many polygons have their large images written
/// out with streaming stores ([`streams`]). The teapot's 4,032 triangles
/// gain from ordinary stores, the bunny's 69,451 lose; at 64 bytes or
/// more a polygon for its corners, bins and planes, 16,384 of them fill a
/// 1 MB second-level cache.
const STREAM_POLYGONS: usize = 16_384;

/// A colour packed as the bands keep it: `r | g << 8 | b << 16`.
fn packed(Rgb8([r, g, b]): Rgb8) -> i32 {
    i32::from(r) | i32::from(g) << 8 | i32::from(b) << 16
}

/// The calling thread's band buffers (uncontended: one per pool thread;
/// a caller outside the pool uses the first).
fn scratch_band(scratch: &[Mutex<Band>]) -> MutexGuard<'_, Band> {
    let slot = rayon::current_thread_index().unwrap_or(0) % scratch.len();
    scratch[slot]
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// The frame's bins as a band reads them: setup's chunks, and what the
/// band hands back of them once read (`placement.rs`).
#[derive(Clone, Copy)]
struct Bins<'a> {
    chunks: &'a [Chunk],
    hand_back: HandBack<'a>,
}

impl<'a> Bins<'a> {
    /// The bins of `chunks`, for a band drawn on the calling thread.
    fn here(chunks: &'a [Chunk], placement: &'a Placement) -> Bins<'a> {
        Bins {
            chunks,
            hand_back: placement.hand_back(),
        }
    }
}

/// Runs band `index` of a pass with the shader `S`, compiled for the SIMD
/// level.
fn band_pass<S: Shader>(
    simd: SimdLevel,
    band: &mut Band,
    index: usize,
    bins: Bins<'_>,
    shader: &S,
    options: &RenderOptions,
    output: Output<'_>,
) {
    let kernel = BandKernel::<S> {
        band,
        index,
        bins,
        shader,
        options,
        output,
    };
    // Every band runs the chosen level, AVX-512 included. Flat's and
    // Gouraud's bands once ran the AVX2 build, which was 7–13 % faster on a
    // full-screen quad when every block blended; since large triangles'
    // whole blocks store without blending, AVX-512's 32 registers keep the
    // span loop's planes out of the stack and its build is 3–4 % faster
    // (BENCHMARKS.md, "Flat's and Gouraud's bands on AVX-512"). Both give
    // the same bytes.
    dispatch(simd, kernel);
}

impl TiledRasterizer {
    pub fn new(simd: SimdLevel) -> TiledRasterizer {
        TiledRasterizer {
            simd: if simd.is_supported() {
                simd
            } else {
                SimdLevel::Portable
            },
            vertices: VertexTable::default(),
            lit: Vec::new(),
            lit_back: Vec::new(),
            chunks: Vec::new(),
            chunks_used: 0,
            phong: PhongShader::default(),
            evaluations: (0, 0),
            bands: Vec::new(),
            setup_jobs: Jobs::default(),
            band_jobs: Jobs::default(),
            placement: Placement::default(),
            ties: false,
            watch_ties: false,
        }
    }

    pub fn simd(&self) -> SimdLevel {
        self.simd
    }

    /// Whether the last frame drawn ([`Rasterize::render`],
    /// [`TiledRasterizer::render_methods`]) had a pixel where a fragment met
    /// the depth another triangle had stored: which of the two the test
    /// "less" kept depends on the order they were drawn in. A frame
    /// without one has the same pixels in any order (see `Band::ties`).
    pub fn met_ties(&self) -> bool {
        self.ties
    }

    /// Whether the frames drawn from now on look for ties
    /// ([`TiledRasterizer::met_ties`], false when they do not): only a
    /// frame drawn in another order than its scene's needs to, and the look
    /// has a cost in the fill ([`Band::watch_ties`]).
    pub fn watch_ties(&mut self, on: bool) {
        self.watch_ties = on;
    }

    /// As if the threads' cores had been measured: thread `k`'s apart from
    /// thread 0's where `apart[k]` (`placement.rs`).
    #[cfg(test)]
    pub(crate) fn assume_apart(&mut self, apart: Vec<bool>) {
        self.placement.assume(apart);
    }
}

impl Rasterize for TiledRasterizer {
    /// Draws a validated scene into `image` (already of the right size).
    fn render<V: VertexStage>(
        &mut self,
        vertices: &mut V,
        scene: &Scene,
        options: &RenderOptions,
        lighting: &Lighting,
        image: &mut Image,
    ) -> RenderStats {
        let all_rows = 0..options.height;
        let method = Some(options.shading);
        let (mut stats, _) = self.geometry(vertices, scene, options, lighting, method, &all_rows);
        let width = options.width as usize;
        let size = (options.width, options.height);
        let mut jobs = self.band_jobs.take();
        let (chunks, simd) = (self.frame_chunks(), self.simd);
        let background = packed(options.background);
        let stream = streams(options.width, options.height, scene.mesh.polygon_count());
        let phong = &self.phong;
        let (scratch, placement) = (&self.bands, &self.placement);
        let watch_ties = self.watch_ties;
        let draw = |index: usize, [rows, ..]: [&mut [Rgb8]; 3]| {
            let mut guard = scratch_band(scratch);
            let band = &mut *guard;
            band.watch_ties(watch_ties);
            let bins = Bins::here(chunks, placement);
            let output = Output::Image {
                rows,
                write: RowWrite { background, stream },
            };
            match options.shading {
                Shading::Flat => band_pass(simd, band, index, bins, &FlatShader, options, output),
                Shading::Gouraud => {
                    band_pass(simd, band, index, bins, &GouraudShader, options, output)
                }
                Shading::Phong => match &phong.one_point_light {
                    Some(one) => band_pass(simd, band, index, bins, one, options, output),
                    None => band_pass(simd, band, index, bins, phong, options, output),
                },
            }
            drawn(band)
        };
        // Each band its own job, the bands shared by cost (`order.rs`).
        let bands = image.pixels_mut().chunks_mut(width * BAND_ROWS as usize);
        jobs.extend(bands.enumerate().map(|(index, rows)| {
            let cost = band_cost(chunks, index, size, method);
            Job::new(index, cost, [rows, Default::default(), Default::default()])
        }));
        let (fragments, covered, ties) = by_cost(&mut jobs, Tail::PerEnd, &draw, &add_drawn);
        self.band_jobs.keep(jobs);
        self.ties = ties;
        stats.fragments_shaded += fragments;
        stats.covered_pixels += covered;
        if options.shading == Shading::Phong {
            stats.lighting_evaluations = stats.fragments_shaded;
        }
        stats
    }

    /// How many triangles cover each pixel, with no depth test.
    fn coverage<V: VertexStage>(
        &mut self,
        vertices: &mut V,
        scene: &Scene,
        options: &RenderOptions,
        lighting: &Lighting,
    ) -> Vec<u32> {
        let all_rows = 0..options.height;
        let method = Some(options.shading);
        self.geometry(vertices, scene, options, lighting, method, &all_rows);
        let width = options.width as usize;
        let mut counts = vec![0u32; width * options.height as usize];
        let (chunks, simd) = (self.frame_chunks(), self.simd);
        let (scratch, placement) = (&self.bands, &self.placement);
        counts
            .par_chunks_mut(width * BAND_ROWS as usize)
            .enumerate()
            .for_each(|(index, out)| {
                let mut band = scratch_band(scratch);
                band.watch_ties(false);
                let output = Output::Counts(out);
                let bins = Bins::here(chunks, placement);
                band_pass(simd, &mut band, index, bins, &FlatShader, options, output);
            });
        counts
    }
}

impl TiledRasterizer {
    /// Draws a validated scene with the three methods at once, flat,
    /// Gouraud and Phong, into `images` (already of the right size), in
    /// that order; `options.shading` is not read. The same bytes and
    /// statistics as three frames of [`Rasterize::render`], for about the
    /// cost of one frame's geometry and one walk of its triangles: the
    /// vertex stage, setup and binning run once, for the attributes of all
    /// three, and each triangle is walked and depth-tested once.
    ///
    /// Only rows `rows` are drawn (whole bands: `rows.start` a multiple of
    /// [`BAND_ROWS`], `rows.end` too or the image's height), into images
    /// of those rows; triangles wholly outside them get no planes and no
    /// bins. Every polygon's counts are the frame's, and so are Gouraud's
    /// evaluations; the pixels' counts (fragments, covered pixels, Phong's
    /// evaluations) are the rows', and flat's evaluations those of the
    /// polygons whose top pixel row is among them (the first part's too for
    /// polygons set up whole): they add up over the parts.
    pub fn render_methods<V: VertexStage>(
        &mut self,
        vertices: &mut V,
        scene: &Scene,
        options: &RenderOptions,
        lighting: &Lighting,
        rows: &std::ops::Range<u32>,
        images: [&mut Image; 3],
    ) -> [RenderStats; 3] {
        let (stats, polygons) = self.geometry(vertices, scene, options, lighting, None, rows);
        let first_band = (rows.start / BAND_ROWS) as usize;
        let size = (options.width, options.height);
        let mut jobs = self.band_jobs.take();
        let frame = self.frame(scene, options, None, polygons.centroids(), rows);
        let sources = (&frame, polygons.projected());
        let width = options.width as usize;
        let (chunks, simd) = (self.frame_chunks(), self.simd);
        let background = packed(options.background);
        let stream = streams(options.width, options.height, scene.mesh.polygon_count());
        let phong = &self.phong;
        let (scratch, placement) = (&self.bands, &self.placement);
        let watch_ties = self.watch_ties;
        let [flat, gouraud, phong_image] = images;
        // One walk of each triangle: the three methods share coverage and
        // depth, so the fragments and pixels drawn are the same for each.
        let draw = |index: usize, rows: [&mut [Rgb8]; 3]| {
            let mut guard = scratch_band(scratch);
            let band = &mut *guard;
            band.watch_ties(watch_ties);
            let bins = Bins::here(chunks, placement);
            let output = Output::Methods {
                rows,
                write: RowWrite { background, stream },
                sources,
            };
            match &phong.one_point_light {
                Some(one) => band_pass(simd, band, index, bins, &AllMethods(one), options, output),
                None => band_pass(simd, band, index, bins, &AllMethods(phong), options, output),
            }
            drawn(band)
        };
        // Each band its own job, shared by cost, as in `render`.
        let band_len = width * BAND_ROWS as usize;
        let bands = flat
            .pixels_mut()
            .chunks_mut(band_len)
            .zip(gouraud.pixels_mut().chunks_mut(band_len))
            .zip(phong_image.pixels_mut().chunks_mut(band_len));
        jobs.extend(bands.enumerate().map(|(k, ((f, g), p))| {
            let index = first_band + k;
            Job::new(index, band_cost(chunks, index, size, None), [f, g, p])
        }));
        let (fragments, covered, ties) = by_cost(&mut jobs, Tail::PerEnd, &draw, &add_drawn);
        self.band_jobs.keep(jobs);
        self.ties = ties;
        let (flat_evaluations, vertex_evaluations) = self.evaluations;
        std::array::from_fn(|k| {
            let lighting_evaluations = match k {
                0 => flat_evaluations,
                1 => vertex_evaluations,
                _ => fragments,
            };
            RenderStats {
                fragments_shaded: stats.fragments_shaded + fragments,
                covered_pixels: stats.covered_pixels + covered,
                lighting_evaluations,
                ..stats
            }
        })
    }

    /// The vertex stage, Gouraud's vertex lighting, then setup and binning
    /// of the frame's polygons, for `method`'s attributes (`None`: the
    /// three methods') and the image rows `rows` (whole bands; triangles
    /// outside them are counted, not set up); leaves the bins in the
    /// first `chunks_used` of `self.chunks`.
    /// The statistics' lighting evaluations are flat's (those the rows
    /// count: see `render_methods`) and Gouraud's (the frame's), also kept
    /// in `self.evaluations`.
    fn geometry<'v, V: VertexStage>(
        &mut self,
        vertices: &'v mut V,
        scene: &Scene,
        options: &RenderOptions,
        lighting: &Lighting,
        method: Option<Shading>,
        rows: &std::ops::Range<u32>,
    ) -> (RenderStats, V::Polygons<'v>) {
        self.phong.update(lighting);
        self.placement.update();
        let (vertex_table, lit, lit_back) = (&mut self.vertices, &mut self.lit, &mut self.lit_back);
        // Vertex lighting, like setup, runs the AVX2 build where AVX-512 is chosen.
        let (phong, simd) = (&self.phong, self.simd.without_avx512());
        // The frame's vertex stage, then Gouraud's vertex lighting: each
        // split in halves by rayon, the calling thread taking the first,
        // as it takes the first run of setup's chunks (`order.rs`). A mesh
        // drawn in a spatial order numbers its positions and normals as its
        // polygons first use them (`frame/spatial.rs`), so a thread's setup
        // reads mostly the positions it projected and the colours it lit,
        // not lines from the other core. Run together (`rayon::join`), the
        // two stages put the lighting on the other thread: the dragon's
        // Gouraud frames 2–5 % slower on two threads with the cores apart,
        // the bunny's within 1 % (BENCHMARKS.md, "Normals numbered in the
        // copy's order").
        let polygons = vertices.project();
        let evaluations = match method {
            Some(Shading::Gouraud) | None => {
                light_vertices(vertex_table, lit, lit_back, phong, simd, scene, options)
            }
            _ => 0,
        };

        let threads = rayon::current_num_threads().max(1);
        self.bands.resize_with(threads, Mutex::default);
        self.bands.truncate(threads);
        for band in &mut self.bands {
            let band = band
                .get_mut()
                .unwrap_or_else(|poisoned| poisoned.into_inner());
            band.reserve(options.width, method.is_none());
        }
        let chunk_count = setup_chunks(rayon::current_num_threads(), polygons.count());
        if self.chunks.len() < chunk_count {
            self.chunks.resize_with(chunk_count, Chunk::default);
        }
        self.chunks_used = chunk_count;
        // Setup fills the chunks while reading the rest of `self` (the
        // frame's attribute sources): taken out meanwhile, no copy.
        let mut chunks = std::mem::take(&mut self.chunks);
        let count = polygons.count();
        let faces = |i: usize| count * i / chunk_count..count * (i + 1) / chunk_count;
        let mut jobs = self.setup_jobs.take();
        let frame = self.frame(scene, options, method, polygons.centroids(), rows);
        // Shared by cost, from the chunks' last frame (`order.rs`).
        jobs.extend(
            chunks[..chunk_count]
                .iter_mut()
                .enumerate()
                .map(|(i, chunk)| Job::new(i, chunk_cost(chunk, faces(i).len()), chunk)),
        );
        let set_up = |i: usize, chunk: &mut Chunk| {
            let (frame, polygons, faces) = (&frame, &polygons, faces(i));
            dispatch(
                frame.simd,
                SetupKernel {
                    chunk,
                    frame,
                    polygons,
                    faces,
                },
            );
        };
        by_cost(&mut jobs, Tail::One, &set_up, &|(), ()| ());
        self.setup_jobs.keep(jobs);
        self.chunks = chunks;

        let mut stats = RenderStats {
            polygons: count as u64,
            lighting_evaluations: evaluations,
            ..RenderStats::default()
        };
        let mut flat_evaluations = 0;
        for chunk in self.frame_chunks() {
            let s = &chunk.stats;
            stats.degenerate += s.degenerate;
            stats.invisible += s.invisible;
            stats.culled += s.culled;
            stats.rasterized += s.rasterized;
            flat_evaluations += s.lighting_evaluations;
        }
        stats.lighting_evaluations += flat_evaluations;
        self.evaluations = (flat_evaluations, evaluations);
        (stats, polygons)
    }

    /// This frame's setup chunks (see `chunks`).
    fn frame_chunks(&self) -> &[Chunk] {
        &self.chunks[..self.chunks_used]
    }

    /// What setup, and a band solving the three methods' planes, read of
    /// the frame, for `method`'s attributes (`None`: the three methods').
    fn frame<'a>(
        &'a self,
        scene: &'a Scene,
        options: &'a RenderOptions,
        method: Option<Shading>,
        centroids: &'a [glam::Vec3],
        rows: &std::ops::Range<u32>,
    ) -> Frame<'a> {
        Frame {
            scene,
            options,
            method,
            corner_vertex: self.vertices.corner_vertex(scene.normals.corner()),
            centroids,
            phong: &self.phong,
            simd: self.simd.without_avx512(),
            write_prefetch: WritePrefetch::detect(),
            lit: &self.lit,
            lit_back: &self.lit_back,
            bands: options.height.div_ceil(BAND_ROWS) as usize,
            rows: rows.start as i32..rows.end as i32,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{setup_chunks, streams};

    /// Meshes get 8 chunks per thread; scenes of few polygons fewer, of at
    /// least 64 polygons each, and at least one.
    #[test]
    fn setup_chunks_of_at_least_64_polygons() {
        assert_eq!(setup_chunks(2, 100_000), 16);
        assert_eq!(setup_chunks(2, 4_032), 16);
        assert_eq!(setup_chunks(2, 1_024), 16);
        assert_eq!(setup_chunks(2, 1_023), 16);
        assert_eq!(setup_chunks(2, 960), 15);
        assert_eq!(setup_chunks(2, 120), 2);
        assert_eq!(setup_chunks(2, 2), 1);
        assert_eq!(setup_chunks(2, 0), 1);
        assert_eq!(setup_chunks(1, 100_000), 8);
        assert_eq!(setup_chunks(0, 100_000), 1);
    }

    /// Large images of many polygons stream; small images, and scenes of
    /// few polygons, do not.
    #[test]
    fn streaming_stores_for_large_images_of_many_polygons() {
        assert!(streams(1920, 1080, 69_451));
        assert!(streams(1920, 1080, 16_384));
        assert!(!streams(1920, 1080, 16_383));
        assert!(!streams(1920, 1080, 2));
        assert!(!streams(512, 512, 100_000));
        // 2 MiB of RGB: 699,051 pixels or more.
        assert!(streams(699_051, 1, 100_000));
        assert!(!streams(699_050, 1, 100_000));
    }
}
