//! Setup: one chunk of consecutive polygons walked by polygon assembly
//! (`frame/assemble.rs`: faced, culled, clipped when needed), then set up
//! as triangles and binned into bands (step 2 of `mod.rs`); flat shading
//! lights its polygons here, 8 at a time.

use glam::Vec3;

use super::setup::{plane_count, Plane, Triangle, ALL_ATTRS, BAND_ROWS};

use crate::raster::{
    fan, signed_area_ccw, PolygonSink, PolygonSource, Projected, Scratch, ScreenVertex,
};
use crate::scene::{RenderOptions, RenderStats, Scene, Shading};
use crate::shade::{PhongShader, MAX_ATTRS};
use crate::simd::{dispatch, prefetch, Kernel, ReleaseLines, Simd, SimdLevel, Vf, WritePrefetch};

/// The triangles of one chunk that touch one band, in submission order,
/// copied here so that the band reads them as one contiguous stream.
#[derive(Debug, Default)]
pub(super) struct Bin {
    pub(super) triangles: Vec<Triangle>,
    /// `plane_count` planes per triangle, but for the triangles whose
    /// planes the band solves (see `corners`).
    pub(super) planes: Vec<Plane>,
    /// The three methods at once: per triangle, where its corners' inputs
    /// are, from which the band solves its planes as setup would
    /// (`Frame::planes_of`), or [`CornerRefs::NONE`] for a clipped or fan
    /// triangle, whose planes are in `planes`. Empty for one method.
    ///
    /// A mesh triangle's 11 planes are 132 bytes against these 36: the
    /// bins are less than half as large, and a frame writes and reads that
    /// much less (the viewer's dragon: the slower part's engine 12.1 → 11.2
    /// ms in Chromium; BENCHMARKS.md, "Planes solved in the band").
    pub(super) corners: Vec<CornerRefs>,
    /// The columns `[x0, x1)` of the triangles' boxes, together (empty:
    /// `x0 >= x1`): the band clears and reads back only those.
    pub(super) columns: (i32, i32),
}

impl Bin {
    pub(super) fn clear(&mut self) {
        self.triangles.clear();
        self.planes.clear();
        self.corners.clear();
        self.columns = (i32::MAX, i32::MIN);
    }

    /// Hands the lines of its triangles, planes and corners back to memory
    /// ([`ReleaseLines`]): called by a band on a core apart from the one
    /// whose setup wrote them and will write them again next frame
    /// (`placement.rs`).
    pub(super) fn release(&self, lines: ReleaseLines) {
        lines.slice(&self.triangles);
        lines.slice(&self.planes);
        lines.slice(&self.corners);
    }
}

/// The columns band `index`'s triangles span over all `chunks`' bins
/// (empty when no triangle touches it: an empty bin's columns are
/// `i32::MAX..i32::MIN`).
pub(super) fn band_columns(chunks: &[Chunk], index: usize) -> std::ops::Range<usize> {
    let (x0, x1) = chunks.iter().fold((i32::MAX, i32::MIN), |(x0, x1), chunk| {
        let columns = chunk.bins[index].columns;
        (x0.min(columns.0), x1.max(columns.1))
    });
    if x0 < x1 {
        x0 as usize..x1 as usize
    } else {
        0..0
    }
}

/// Where a mesh triangle's three corners find their inputs: their
/// positions' (and projected vertices') indices, their normals' and their
/// Gouraud colours' (vertex table) indices.
///
/// Setup reads them from the corner arrays in submission order, where
/// consecutive triangles share cache lines. A band meets its triangles
/// skipping those of other bands, so that reading the corner arrays there
/// was a miss per triangle before the reads it leads to (BENCHMARKS.md,
/// "The viewer's engine under a profiler").
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct CornerRefs {
    pub(super) position: [u32; 3],
    pub(super) normal: [u32; 3],
    pub(super) lit: [u32; 3],
}

impl CornerRefs {
    /// No mesh triangle: the planes are in the bin.
    pub(super) const NONE: CornerRefs = CornerRefs {
        position: [u32::MAX; 3],
        normal: [u32::MAX; 3],
        lit: [u32::MAX; 3],
    };

    pub(super) fn is_none(&self) -> bool {
        self.position[0] == u32::MAX
    }
}

/// Consecutive polygons set up by one task, with their per-band bins.
/// Aligned to 128 bytes so that chunks set up by different threads share
/// no cache line (their counters are written per polygon).
#[derive(Debug, Default)]
#[repr(align(128))]
pub(super) struct Chunk {
    pub(super) bins: Vec<Bin>,
    pub(super) stats: RenderStats,
    scratch: Scratch<ALL_ATTRS>,
    /// Flat shading: each front polygon's unit normal and centroid, lit in
    /// SIMD batches once setup is done, into `flat_colors` (packed); its
    /// triangles hold the index.
    pub(super) flat_surfaces: Vec<[f32; 6]>,
    pub(super) flat_colors: Vec<i32>,
    /// The pool thread that set it up this frame (`None`: none of the
    /// pool's): a band drawn on a core apart from that thread's hands back
    /// the lines of its bin once read (`placement.rs`, [`Bin::release`]).
    pub(super) set_up_on: Option<usize>,
}

/// What setup needs to know about the frame.
pub(super) struct Frame<'a> {
    pub(super) scene: &'a Scene,
    pub(super) options: &'a RenderOptions,
    /// The method whose attributes are set up, or `None` for the three
    /// methods at once (`ALL_ATTRS`: Phong's, then Gouraud's colours; flat
    /// colours in the triangles).
    pub(super) method: Option<Shading>,
    pub(super) corner_vertex: &'a [u32],
    /// Each polygon's centroid (flat shading's lit point).
    pub(super) centroids: &'a [Vec3],
    pub(super) phong: &'a PhongShader,
    pub(super) simd: SimdLevel,
    /// How setup asks for the lines of the bins it is about to write.
    pub(super) write_prefetch: WritePrefetch,
    pub(super) lit: &'a [[f32; 3]],
    pub(super) lit_back: &'a [[f32; 3]],
    pub(super) bands: usize,
    /// The image rows drawn (whole bands): polygons outside them are
    /// counted, but their triangles get no edges, planes or bins.
    pub(super) rows: std::ops::Range<i32>,
}

impl Frame<'_> {
    /// The attributes the shading method interpolates, at a corner.
    pub(super) fn corner_attrs(&self, corner: usize, back: bool) -> [f32; ALL_ATTRS] {
        let colour = || {
            let v = self.corner_vertex[corner] as usize;
            if back {
                self.lit_back[v]
            } else {
                self.lit[v]
            }
        };
        let surface = || {
            let normals = &self.scene.normals;
            let n = normals.normals[normals.corner()[corner] as usize];
            let p = self.scene.mesh.positions()[self.scene.mesh.corners()[corner] as usize];
            [n.x, n.y, n.z, p.x, p.y, p.z]
        };
        let mut out = [0.0; ALL_ATTRS];
        match self.method {
            Some(Shading::Flat) => {}
            Some(Shading::Gouraud) => out[..3].copy_from_slice(&colour()),
            Some(Shading::Phong) => out[..6].copy_from_slice(&surface()),
            None => {
                out[..6].copy_from_slice(&surface());
                out[6..].copy_from_slice(&colour());
            }
        }
        out
    }

    /// The planes of the three methods at once of mesh triangle `t`, whose
    /// corners' inputs are at `refs`, from the window positions
    /// `projected`: as `Setup::triangle` would have solved them (the same
    /// inputs as [`Frame::front_attrs`] reads).
    #[inline(always)]
    pub(super) fn planes_of<S: Simd>(
        &self,
        s: S,
        t: &Triangle,
        refs: &CornerRefs,
        projected: &[Projected],
    ) -> [Plane; super::setup::PLANES] {
        let (normals, positions) = (&self.scene.normals.normals, self.scene.mesh.positions());
        let vertex = |k: usize| {
            let n = normals[refs.normal[k] as usize];
            let p = positions[refs.position[k] as usize];
            let c = self.lit[refs.lit[k] as usize];
            projected[refs.position[k] as usize]
                .vertex([n.x, n.y, n.z, p.x, p.y, p.z, c[0], c[1], c[2]])
        };
        let v: [ScreenVertex<ALL_ATTRS>; 3] = [vertex(0), vertex(1), vertex(2)];
        t.planes(s, &v, ALL_ATTRS)
    }

    /// Where the corners of the mesh triangle whose first corner is
    /// `corner` find their inputs ([`Frame::planes_of`]).
    #[inline(always)]
    fn corner_refs(&self, corner: usize) -> CornerRefs {
        let (positions, normals) = (self.scene.mesh.corners(), self.scene.normals.corner());
        let at = |of: &[u32]| -> [u32; 3] { of[corner..corner + 3].try_into().unwrap() };
        CornerRefs {
            position: at(positions),
            normal: at(normals),
            lit: at(self.corner_vertex),
        }
    }

    /// Whether flat shading's colours are set up (in `Triangle::color`).
    pub(super) fn lights_polygons(&self) -> bool {
        matches!(self.method, None | Some(Shading::Flat))
    }

    /// [`Frame::corner_attrs`] of a front face, for the method with `A`
    /// attributes.
    #[inline(always)]
    pub(super) fn front_attrs<const A: usize>(&self, corner: usize) -> [f32; A] {
        let mut out = [0.0; A];
        if A == 3 {
            let c = self.lit[self.corner_vertex[corner] as usize];
            out[..3].copy_from_slice(&c);
        } else if A >= 6 {
            let normals = &self.scene.normals;
            let n = normals.normals[normals.corner()[corner] as usize];
            let p = self.scene.mesh.positions()[self.scene.mesh.corners()[corner] as usize];
            out[..6].copy_from_slice(&[n.x, n.y, n.z, p.x, p.y, p.z]);
        }
        if A == ALL_ATTRS {
            let c = self.lit[self.corner_vertex[corner] as usize];
            out[6..].copy_from_slice(&c);
        }
        out
    }

    /// Starts loading what [`Frame::front_attrs`] reads of corner `corner`
    /// (of vertex `vertex`) for `A` attributes.
    #[inline(always)]
    fn prefetch_corner<const A: usize>(&self, corner: usize, vertex: u32) {
        if A == 3 || A == ALL_ATTRS {
            prefetch(&self.lit[self.corner_vertex[corner] as usize]);
        }
        if A >= 6 {
            let normals = &self.scene.normals;
            prefetch(&normals.normals[normals.corner()[corner] as usize]);
        }
        // Phong's attributes read the position.
        if A >= 6 {
            prefetch(&self.scene.mesh.positions()[vertex as usize]);
        }
    }

    /// Whether triangle `t` has rows among those drawn.
    #[inline(always)]
    pub(super) fn draws(&self, t: &Triangle) -> bool {
        t.y1 > self.rows.start && t.y0 < self.rows.end
    }

    /// Whether this part counts flat's lighting of a front polygon whose
    /// pixels' top row is `y0` (of the rows drawn, or of the image for a
    /// polygon `None`): a polygon is counted by the part that holds its top
    /// row (the first part, for those set up whole), so that the parts'
    /// counts add up to the frame's even where their triangles span parts.
    #[inline(always)]
    fn counts_flat(&self, y0: Option<i32>) -> bool {
        match y0 {
            Some(y0) => y0 >= self.rows.start,
            None => self.rows.start == 0,
        }
    }

    pub(super) fn attr_count(&self) -> usize {
        match self.method {
            Some(Shading::Flat) => 0,
            Some(Shading::Gouraud) => 3,
            Some(Shading::Phong) => 6,
            None => ALL_ATTRS,
        }
    }
}

/// A chunk's end of polygon assembly, for the method with `A` attributes
/// (the general path carries `ALL_ATTRS`, of which the method's are set),
/// compiled for the SIMD level `S`.
struct Setup<'a, 'f, S, const A: usize> {
    simd: S,
    frame: &'a Frame<'f>,
    bins: &'a mut [Bin],
    flat_surfaces: &'a mut Vec<[f32; 6]>,
    /// Flat's lighting evaluations this part counts (see `Frame::counts_flat`).
    flat_evaluations: u64,
}

impl<S: Simd, const A: usize> PolygonSink<ALL_ATTRS> for Setup<'_, '_, S, A> {
    #[inline(always)]
    fn corner(&mut self, corner: usize, _: u32, back: bool) -> [f32; ALL_ATTRS] {
        self.frame.corner_attrs(corner, back)
    }

    #[inline(always)]
    fn prefetch_corner(&self, corner: usize, vertex: u32) {
        self.frame.prefetch_corner::<A>(corner, vertex);
    }

    /// The common case, set up straight from the projected positions: the
    /// attributes are read only for a triangle that covers a pixel centre
    /// in the rows drawn.
    #[inline(always)]
    fn triangle(
        &mut self,
        face: usize,
        normal: Vec3,
        first_corner: usize,
        _: [u32; 3],
        p: &[Projected; 3],
    ) {
        let frame = self.frame;
        let options = frame.options;
        let x = p.map(|p| i64::from(p.x));
        let y = p.map(|p| i64::from(p.y));
        // The rows first: about half of a frame's triangles are outside
        // each of two parts, and their edges cost more than the walk up to
        // here (a part of 16 empty rows of the dragon's frame: 4.1 ms with
        // them, 2.8 without, WebAssembly).
        let rows = frame.rows.clone();
        let Some(t) = Triangle::edges_in_rows(x, y, options.width, options.height, rows) else {
            return;
        };
        if t.covers_no_centre() {
            return;
        }
        // Flat's triangles interpolate nothing: their mode is never read
        // (`walk::needs_w`), and the test is left out of their loop.
        let mut t = if A == 0 {
            t
        } else {
            t.interpolated(options.interpolation, p.map(|p| p.inv_w))
        };
        if A == 0 || A == ALL_ATTRS {
            self.flat_evaluations += u64::from(frame.counts_flat(Some(t.y0)));
            // As `flat_surface`, for a front face.
            let c = frame.centroids[face];
            self.flat_surfaces
                .push([normal.x, normal.y, normal.z, c.x, c.y, c.z]);
            t.color = (self.flat_surfaces.len() - 1) as u32;
        }
        if A == ALL_ATTRS {
            // The band solves the planes (see `Bin::corners`).
            self.bin(&t, &[], &frame.corner_refs(first_corner));
            return;
        }
        let vertex = |k: usize| p[k].vertex(frame.front_attrs::<A>(first_corner + k));
        let v: [ScreenVertex<A>; 3] = [vertex(0), vertex(1), vertex(2)];
        let planes = t.planes(self.simd, &v, A);
        self.bin(&t, &planes[..plane_count(A)], &CornerRefs::NONE);
    }

    /// Any other polygon: split into the fan both rasterizers use.
    fn polygon(
        &mut self,
        face: usize,
        normal: Vec3,
        back: bool,
        window: &[ScreenVertex<ALL_ATTRS>],
    ) {
        let frame = self.frame;
        let options = frame.options;
        let attrs = frame.attr_count();
        let color = if frame.lights_polygons() {
            self.flat_surface(face, normal, back)
        } else {
            0
        };
        let fan = fan(window);
        let once = if fan.once_per_pixel {
            face as u32 + 1
        } else {
            0
        };
        for triangle in fan.triangles(window) {
            if signed_area_ccw(&triangle) <= 0 {
                continue;
            }
            let (x, y) = (triangle.map(|v| v.x), triangle.map(|v| v.y));
            let Some(t) = Triangle::edges(x, y, options.width, options.height) else {
                continue;
            };
            if t.covers_no_centre() || !frame.draws(&t) {
                continue;
            }
            let mut t = t.interpolated(options.interpolation, triangle.map(|v| v.inv_w));
            let planes = t.planes(self.simd, &triangle, attrs);
            t.color = color;
            t.flip = if back { -1.0 } else { 1.0 };
            t.once = once;
            self.bin(&t, &planes[..plane_count(attrs)], &CornerRefs::NONE);
        }
    }
}

impl<S: Simd, const A: usize> Setup<'_, '_, S, A> {
    /// Queues a polygon for flat lighting; returns its index.
    fn flat_surface(&mut self, face: usize, normal: Vec3, back: bool) -> u32 {
        self.flat_evaluations += u64::from(self.frame.counts_flat(None));
        let n = if back { -normal } else { normal };
        let p = self.frame.centroids[face];
        self.flat_surfaces.push([n.x, n.y, n.z, p.x, p.y, p.z]);
        (self.flat_surfaces.len() - 1) as u32
    }

    /// Adds a set-up triangle to the bins of the drawn bands it touches:
    /// with its `planes`, or, for the three methods at once, with where its
    /// corners' inputs are (`corners`) and no planes, which the band then
    /// solves ([`CornerRefs::NONE`]: the planes are given).
    #[inline(always)]
    fn bin(&mut self, t: &Triangle, planes: &[Plane], corners: &CornerRefs) {
        let bands = t.bands();
        let rows = &self.frame.rows;
        let drawn = rows.start as usize / BAND_ROWS as usize
            ..(rows.end as usize).div_ceil(BAND_ROWS as usize);
        for band in bands.start.max(drawn.start)..bands.end.min(drawn.end) {
            let bin = &mut self.bins[band];
            bin.triangles.push(*t);
            bin.planes.extend_from_slice(planes);
            // The next pushes' lines, a few ahead: a dense mesh writes
            // megabytes of bins per frame (a Phong triangle is 80 + 96
            // bytes, in one stream per band), and a store to a line not in
            // the cache waits for it, filling the store queue (binning was
            // a tenth of the bunny's 1920×1080 Phong frame). Consecutive
            // triangles mostly share bands, so the lines are there by then.
            // The meshes' 1920×1080 rows: medians 2–10 % lower
            // (BENCHMARKS.md, "The same AMD EPYC: d380fe5, the bins
            // prefetched"). Taken for writing: the last frame's bands, on
            // both threads, read these lines (`WritePrefetch`).
            let ahead = self.frame.write_prefetch;
            if let Some(next) = bin.triangles.spare_capacity_mut().get(PREFETCH_TRIANGLES) {
                ahead.line(next);
            }
            if let Some(next) = bin.planes.spare_capacity_mut().get(PREFETCH_PLANES) {
                ahead.line(next);
            }
            if A == ALL_ATTRS {
                bin.corners.push(*corners);
            }
            bin.columns = (bin.columns.0.min(t.x0), bin.columns.1.max(t.x1));
        }
    }
}

/// How many triangles past a bin's end `Setup::bin` prefetches (240
/// bytes): the distance measured in BENCHMARKS.md.
const PREFETCH_TRIANGLES: usize = 3;

/// How many planes past a bin's end `Setup::bin` prefetches: three Phong
/// triangles' eight planes (288 bytes), as measured.
const PREFETCH_PLANES: usize = 24;

impl Chunk {
    /// Walks polygons `faces` and bins their triangles, with the method's
    /// `A` attributes, compiled for the SIMD level `simd`: the planes'
    /// arithmetic is its `solve_planes`, the rest the compiler's own
    /// vectorization (the same arithmetic on every level, so the same results).
    #[inline(always)]
    fn setup<S: Simd, const A: usize, P: PolygonSource>(
        &mut self,
        simd: S,
        frame: &Frame<'_>,
        polygons: &P,
        faces: std::ops::Range<usize>,
    ) {
        self.bins.resize_with(frame.bands, Bin::default);
        self.bins.truncate(frame.bands);
        for bin in &mut self.bins {
            bin.clear();
        }
        self.stats = RenderStats::default();
        self.set_up_on = rayon::current_thread_index();
        self.flat_surfaces.clear();
        let mut sink = Setup::<S, A> {
            simd,
            frame,
            bins: &mut self.bins,
            flat_surfaces: &mut self.flat_surfaces,
            flat_evaluations: 0,
        };
        polygons.walk(faces, &mut self.scratch, &mut sink, &mut self.stats);
        self.stats.lighting_evaluations += sink.flat_evaluations;
        if frame.lights_polygons() {
            self.light_flat_polygons(frame);
        }
    }

    /// Lights the front polygons of flat shading, 8 at a time, into
    /// `flat_colors` (a flat triangle's `color` is its index there: the
    /// band looks it up, see `BandKernel`).
    pub(super) fn light_flat_polygons(&mut self, frame: &Frame<'_>) {
        self.flat_colors.clear();
        self.flat_colors
            .resize(self.flat_surfaces.len().next_multiple_of(8), 0);
        let kernel = FlatKernel {
            surfaces: &self.flat_surfaces,
            colors: &mut self.flat_colors,
            shader: frame.phong,
        };
        dispatch(frame.simd, kernel);
    }
}

/// One chunk's setup, compiled per SIMD level.
pub(super) struct SetupKernel<'a, 'f, P> {
    pub(super) chunk: &'a mut Chunk,
    pub(super) frame: &'a Frame<'f>,
    pub(super) polygons: &'a P,
    pub(super) faces: std::ops::Range<usize>,
}

impl<P: PolygonSource> Kernel for SetupKernel<'_, '_, P> {
    type Output = ();

    #[inline(always)]
    fn run<S: Simd>(self, s: S) {
        let (chunk, frame, faces) = (self.chunk, self.frame, self.faces);
        let polygons = self.polygons;
        match frame.method {
            Some(Shading::Flat) => chunk.setup::<S, 0, P>(s, frame, polygons, faces),
            Some(Shading::Gouraud) => chunk.setup::<S, 3, P>(s, frame, polygons, faces),
            Some(Shading::Phong) => chunk.setup::<S, 6, P>(s, frame, polygons, faces),
            None => chunk.setup::<S, ALL_ATTRS, P>(s, frame, polygons, faces),
        }
    }
}

/// Flat shading's lighting, 8 polygons per SIMD evaluation.
pub(super) struct FlatKernel<'a> {
    pub(super) surfaces: &'a [[f32; 6]],
    pub(super) colors: &'a mut [i32],
    pub(super) shader: &'a PhongShader,
}

impl Kernel for FlatKernel<'_> {
    type Output = ();

    #[inline(always)]
    fn run<S: Simd>(self, s: S) {
        for (surfaces, colors) in self.surfaces.chunks(8).zip(self.colors.chunks_exact_mut(8)) {
            let mut lanes = [[0f32; 8]; 6];
            for (i, surface) in surfaces.iter().enumerate() {
                for k in 0..6 {
                    lanes[k][i] = surface[k];
                }
            }
            let attrs: [Vf<S>; MAX_ATTRS] = std::array::from_fn(|k| Vf::load(s, &lanes[k]));
            self.shader.light(&attrs, colors);
        }
    }
}
