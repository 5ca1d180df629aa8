//! The fast rasterizer: per-vertex work once, triangle setup in parallel
//! chunks with per-chunk binning into bands of 16 rows, then bands
//! rasterized in parallel with SIMD blocks of 8 pixels.
//!
//! The pipeline of a frame:
//!
//! 1. **Vertices** (parallel): each position transformed and snapped once;
//!    Gouraud lights each distinct (position, normal) 8 at a time.
//! 2. **Setup** (parallel, in chunks of consecutive polygons): a triangle
//!    whose corners are all inside the view volume goes straight from the
//!    projected positions: facing from the snapped area, culling before any
//!    attribute is read, the bounding box's pixel centres (none: done), edge
//!    functions and attribute planes. Anything else (clipped, back faces drawn,
//!    polygons) takes the general path. Each triangle is copied, with its
//!    planes, into the bin of every band it touches.
//! 3. **Bands** (parallel): a band reads its chunks' bins in order (see
//!    `band.rs`), then writes its rows of the image.
//!
//! What must hold, and why it is built this way:
//!
//! * **The same pixels as the scanline reference.** Every polygon goes
//!   through the same clipping ([`crate::clip_polygon`]), the same viewport
//!   transform and snapping ([`crate::raster::to_window`]), the same facing
//!   decision and the same [`crate::raster::fan`] as the scanline rasterizer
//!   drawing fans, so both see identical snapped triangles; coverage is then
//!   exact integer arithmetic in both (see `setup.rs`). Colours differ only
//!   by f32 rounding: within 1/255, checked by the equivalence tests.
//! * **Per-vertex work once per vertex.** Positions are transformed and
//!   snapped once each; a polygon whose vertices are all inside the view
//!   volume and guard band (nearly all of them) skips clipping, because
//!   clipping would return it unchanged.
//! * **Order is kept.** Chunks are set up in parallel, each binning into its
//!   own per-band lists; a band walks the chunks in order, so triangles meet
//!   the depth test in submission order, as with one thread, and the image
//!   does not depend on the thread count.
//! * **Memory is read in streams.** Bins hold copies of their triangles, so
//!   a band reads one contiguous run instead of chasing indices; each thread
//!   draws its bands one after another in the same depth and colour
//!   buffers, which stay in its cache.
//! * **No allocation per frame in steady state.** All buffers live in
//!   [`TiledRasterizer`] and are cleared, not dropped, between frames.

mod band;
mod setup;

use std::collections::HashMap;
use std::sync::{Mutex, MutexGuard};

use glam::{Mat4, Vec3, Vec4};
use rayon::prelude::*;

use self::band::{band_rows, Band, Pass};
use self::setup::{plane_count, Plane, Triangle, BAND_ROWS};
use crate::clip::{clip_polygon, is_inside, ClipVertex};
use crate::color::Rgb8;
use crate::image::Image;
use crate::normals::face_normal;
use crate::raster::{fan, signed_area_ccw, ScreenVertex};
use crate::raster::{guard_band, to_window, Rasterize};
use crate::scene::{RenderOptions, RenderStats, Scene, Shading};
use crate::shade::{
    byte_units, FlatShader, GouraudShader, Lighting, PhongShader, Shader, Terms, MAX_ATTRS,
};
use crate::simd::{dispatch, prefetch, Kernel, Simd, SimdLevel, Vf};

/// How many polygons ahead setup starts loading a polygon's vertices.
const PREFETCH_AHEAD: usize = 8;

/// Setup chunks per thread. A polygon's cost varies tenfold (a back face
/// stops at facing, a front face is set up and binned) and meshes list
/// their visible faces unevenly: with 2 chunks per thread the bunny's four
/// chunks took 1.1, 0.9, 0.43 and 0.39 ms, and one thread waited for the
/// other. Smaller chunks, taken as threads come free, even that out; a
/// band walks one bin per chunk, which costs little more.
const SETUP_CHUNKS_PER_THREAD: usize = 8;

/// The tiled rasterizer's buffers, reused from frame to frame.
#[derive(Debug)]
pub(crate) struct TiledRasterizer {
    simd: SimdLevel,
    /// Per mesh position: its snapped window position (16 bytes, so that
    /// setup's random accesses stay in cache). Clip-space positions are not
    /// kept: the few polygons that need clipping compute theirs again.
    projected: Vec<Projected>,
    vertices: VertexTable,
    faces: FaceNormals,
    /// Gouraud colours per distinct vertex, front and (culling off) back,
    /// clamped to [0, 1] and kept in byte units ([`byte_units`]).
    lit: Vec<[f32; 3]>,
    lit_back: Vec<[f32; 3]>,
    chunks: Vec<Chunk>,
    /// The frame's lighting, prepared for lanes.
    phong: PhongShader,
    /// One band's working buffers per thread: each thread draws its bands
    /// one after the other in the same buffers, which stay in its cache.
    bands: Vec<Mutex<Band>>,
}

/// A vertex's window position, when it is inside the view volume and guard
/// band (`x == OUTSIDE` otherwise). Snapped coordinates stay within ±2^29,
/// so they fit in `i32`.
#[derive(Debug, Clone, Copy, Default)]
struct Projected {
    x: i32,
    y: i32,
    depth: f32,
    inv_w: f32,
}

impl Projected {
    const OUTSIDE: i32 = i32::MIN;

    fn inside(&self) -> bool {
        self.x != Projected::OUTSIDE
    }
}

/// The triangles of one chunk that touch one band, in submission order,
/// copied here so that the band reads them as one contiguous stream.
#[derive(Debug, Default)]
struct Bin {
    triangles: Vec<Triangle>,
    /// `plane_count` planes per triangle.
    planes: Vec<Plane>,
    /// The columns `[x0, x1)` of the triangles' boxes, together (empty:
    /// `x0 >= x1`): the band clears and reads back only those.
    columns: (i32, i32),
}

impl Bin {
    fn clear(&mut self) {
        self.triangles.clear();
        self.planes.clear();
        self.columns = (i32::MAX, i32::MIN);
    }
}

/// Consecutive polygons set up by one task, with their per-band bins.
/// Aligned to 128 bytes so that chunks set up by different threads share
/// no cache line (their counters are written per polygon).
#[derive(Debug, Default)]
#[repr(align(128))]
struct Chunk {
    bins: Vec<Bin>,
    stats: RenderStats,
    input: Vec<ClipVertex<MAX_ATTRS>>,
    clipped: Vec<ClipVertex<MAX_ATTRS>>,
    scratch: Vec<ClipVertex<MAX_ATTRS>>,
    window: Vec<ScreenVertex<MAX_ATTRS>>,
    /// Flat shading: each front polygon's unit normal and centroid, lit in
    /// SIMD batches once setup is done; triangles hold an index until then.
    flat_surfaces: Vec<[f32; 6]>,
    flat_colors: Vec<i32>,
}

/// Distinct (position, normal) pairs of a mesh, rebuilt only when the
/// mesh's geometry or its corner normal indices change.
#[derive(Debug, Default)]
struct VertexTable {
    /// The geometry it was built for ([`crate::mesh::Mesh::geometry_id`], 0: none).
    key_geometry: u64,
    key_normals: Vec<u32>,
    /// Per corner, its vertex.
    corner_vertex: Vec<u32>,
    /// Per vertex, its position and normal index (`u32::MAX` when unused).
    position: Vec<u32>,
    normal: Vec<u32>,
    used: u64,
}

impl VertexTable {
    fn update(&mut self, mesh: &crate::mesh::Mesh, corner_normals: &[u32], normal_count: usize) {
        if self.key_geometry == mesh.geometry_id() && same(&self.key_normals, corner_normals) {
            return;
        }
        let corners = mesh.corners();
        self.key_geometry = mesh.geometry_id();
        self.key_normals.clear();
        self.key_normals.extend_from_slice(corner_normals);
        // A vertex per normal index, owned by the first position using it;
        // a normal shared by several positions gets extra vertices.
        self.position.clear();
        self.position.resize(normal_count, u32::MAX);
        self.normal.clear();
        self.normal.extend(0..normal_count as u32);
        self.corner_vertex.clear();
        let mut extra: HashMap<(u32, u32), u32> = HashMap::new();
        for (&p, &n) in corners.iter().zip(corner_normals) {
            let owner = &mut self.position[n as usize];
            let id = if *owner == u32::MAX || *owner == p {
                *owner = p;
                n
            } else {
                *extra.entry((p, n)).or_insert_with(|| {
                    self.normal.push(n);
                    (self.normal.len() - 1) as u32
                })
            };
            self.corner_vertex.push(id);
        }
        self.position.resize(self.normal.len(), u32::MAX);
        for (&(p, _), &id) in &extra {
            self.position[id as usize] = p;
        }
        self.used = self.position.iter().filter(|&&p| p != u32::MAX).count() as u64;
    }
}

/// Each polygon's unit face normal (`None` when degenerate), recomputed
/// only when the mesh's geometry changes.
#[derive(Debug, Default)]
struct FaceNormals {
    /// The geometry they were computed for ([`crate::mesh::Mesh::geometry_id`], 0: none).
    key_geometry: u64,
    normals: Vec<Option<Vec3>>,
}

impl FaceNormals {
    fn update(&mut self, mesh: &crate::mesh::Mesh) {
        if self.key_geometry == mesh.geometry_id() {
            return;
        }
        self.key_geometry = mesh.geometry_id();
        self.normals.resize(mesh.polygon_count(), None);
        self.normals
            .par_chunks_mut(1024)
            .enumerate()
            .for_each(|(k, normals)| {
                let mut points = Vec::new();
                for (i, normal) in normals.iter_mut().enumerate() {
                    points.clear();
                    let polygon = mesh.polygon(k * 1024 + i);
                    points.extend(polygon.iter().map(|&v| mesh.positions()[v as usize]));
                    *normal = face_normal(&points);
                }
            });
    }
}

/// `a == b`, compared in parallel: the vertex table is keyed by the scene's
/// corner normal indices (which a caller may change between frames without
/// changing the mesh), checked every frame.
fn same<T: PartialEq + Sync>(a: &[T], b: &[T]) -> bool {
    const CHUNK: usize = 1 << 14;
    a.len() == b.len()
        && a.par_chunks(CHUNK)
            .zip(b.par_chunks(CHUNK))
            .all(|(x, y)| x == y)
}

/// What setup needs to know about the frame.
struct Frame<'a> {
    scene: &'a Scene,
    options: &'a RenderOptions,
    projected: &'a [Projected],
    view_projection: Mat4,
    corner_vertex: &'a [u32],
    faces: &'a [Option<Vec3>],
    phong: &'a PhongShader,
    simd: SimdLevel,
    lit: &'a [[f32; 3]],
    lit_back: &'a [[f32; 3]],
    guard: f32,
    bands: usize,
}

impl Frame<'_> {
    /// The attributes the shading method interpolates, at a corner.
    fn corner_attrs(&self, corner: usize, back: bool) -> [f32; MAX_ATTRS] {
        match self.options.shading {
            Shading::Flat => [0.0; MAX_ATTRS],
            Shading::Gouraud => {
                let v = self.corner_vertex[corner] as usize;
                let [r, g, b] = if back { self.lit_back[v] } else { self.lit[v] };
                [r, g, b, 0.0, 0.0, 0.0]
            }
            Shading::Phong => {
                let normals = &self.scene.normals;
                let n = normals.normals[normals.corner[corner] as usize];
                let p = self.scene.mesh.positions()[self.scene.mesh.corners()[corner] as usize];
                [n.x, n.y, n.z, p.x, p.y, p.z]
            }
        }
    }

    /// [`Frame::corner_attrs`] of a front face, for the method with `A`
    /// attributes.
    #[inline(always)]
    fn front_attrs<const A: usize>(&self, corner: usize) -> [f32; A] {
        let mut out = [0.0; A];
        if A == 3 {
            let c = self.lit[self.corner_vertex[corner] as usize];
            out[..3].copy_from_slice(&c);
        } else if A == 6 {
            let normals = &self.scene.normals;
            let n = normals.normals[normals.corner[corner] as usize];
            let p = self.scene.mesh.positions()[self.scene.mesh.corners()[corner] as usize];
            out.copy_from_slice(&[n.x, n.y, n.z, p.x, p.y, p.z]);
        }
        out
    }

    /// Starts loading what setting up polygon `face` reads at random: its
    /// vertices' window positions and (for `A` attributes) the corners'
    /// attribute sources. Meshes list their faces in an order far from
    /// their vertices' (the bunny's faces jump by a median of 1,557 vertex
    /// indices), so without this nearly every polygon waits for memory.
    #[inline(always)]
    fn prefetch<const A: usize>(&self, face: usize) {
        let mesh = &self.scene.mesh;
        let range = mesh.corner_range(face);
        if range.len() == 3 {
            // Triangles, nearly all polygons: straight-line code, no loop to
            // leave (its exit would be mispredicted every few polygons).
            let first = range.start;
            self.prefetch_corner::<A>(first);
            self.prefetch_corner::<A>(first + 1);
            self.prefetch_corner::<A>(first + 2);
            return;
        }
        for corner in range {
            self.prefetch_corner::<A>(corner);
        }
    }

    /// [`Frame::prefetch`] of one corner.
    #[inline(always)]
    fn prefetch_corner<const A: usize>(&self, corner: usize) {
        let mesh = &self.scene.mesh;
        let vertex = mesh.corners()[corner] as usize;
        prefetch(&self.projected[vertex]);
        if A == 3 {
            prefetch(&self.lit[self.corner_vertex[corner] as usize]);
        } else if A == 6 {
            let normals = &self.scene.normals;
            prefetch(&normals.normals[normals.corner[corner] as usize]);
            prefetch(&mesh.positions()[vertex]);
        }
    }

    fn attr_count(&self) -> usize {
        match self.options.shading {
            Shading::Flat => 0,
            Shading::Gouraud => 3,
            Shading::Phong => 6,
        }
    }
}

impl Chunk {
    /// The polygon's window-space vertices, clipped, with the attributes of
    /// its front (or back) side, as the scanline pipeline computes them.
    fn project(&mut self, frame: &Frame<'_>, face: usize, back: bool) {
        let mesh = &frame.scene.mesh;
        let (width, height) = (frame.options.width, frame.options.height);
        let range = mesh.corner_range(face);
        self.window.clear();
        let inside = mesh.corners()[range.clone()]
            .iter()
            .all(|&p| frame.projected[p as usize].inside());
        if inside {
            for c in range {
                let w = frame.projected[mesh.corners()[c] as usize];
                self.window.push(ScreenVertex {
                    x: i64::from(w.x),
                    y: i64::from(w.y),
                    depth: w.depth,
                    inv_w: w.inv_w,
                    attrs: frame.corner_attrs(c, back),
                });
            }
            return;
        }
        self.input.clear();
        for c in range {
            self.input.push(ClipVertex {
                clip: clip_position(
                    frame.view_projection,
                    mesh.positions()[mesh.corners()[c] as usize],
                ),
                attrs: frame.corner_attrs(c, back),
            });
        }
        clip_polygon(
            &self.input,
            frame.guard,
            &mut self.clipped,
            &mut self.scratch,
        );
        self.window
            .extend(self.clipped.iter().map(|v| to_window(v, width, height)));
    }

    /// Sets up polygons `faces` and bins their triangles, with the method's
    /// `A` attributes, compiled for the SIMD level (for the compiler's own
    /// vectorization: the arithmetic is the same, so are the results).
    #[inline(always)]
    fn setup<const A: usize>(&mut self, frame: &Frame<'_>, faces: std::ops::Range<usize>) {
        self.bins.resize_with(frame.bands, Bin::default);
        self.bins.truncate(frame.bands);
        for bin in &mut self.bins {
            bin.clear();
        }
        self.stats = RenderStats::default();
        self.flat_surfaces.clear();
        let mesh = &frame.scene.mesh;
        let end = faces.end;
        for face in faces {
            if face + PREFETCH_AHEAD < end {
                frame.prefetch::<A>(face + PREFETCH_AHEAD);
            }
            let Some(normal) = frame.faces[face] else {
                self.stats.degenerate += 1;
                continue;
            };
            let range = mesh.corner_range(face);
            let corners = &mesh.corners()[range.clone()];
            if let &[i0, i1, i2] = corners {
                let p = [i0, i1, i2].map(|i| frame.projected[i as usize]);
                if p.iter().all(Projected::inside) {
                    // `None`: a back face drawn with culling off, left to the general path.
                    if self
                        .setup_triangle::<A>(frame, range.start, &p, normal)
                        .is_some()
                    {
                        continue;
                    }
                }
            }
            self.setup_polygon(frame, face, normal);
        }
        if frame.options.shading == Shading::Flat {
            self.light_flat_polygons(frame);
        }
    }

    /// The common case: a triangle whose corners are all inside the view
    /// volume, set up straight from the projected positions. `None` when it
    /// is a back face to be drawn (culling off), left to `setup_polygon`.
    #[inline(always)]
    fn setup_triangle<const A: usize>(
        &mut self,
        frame: &Frame<'_>,
        first_corner: usize,
        p: &[Projected; 3],
        normal: Vec3,
    ) -> Option<()> {
        let options = frame.options;
        let x = p.map(|p| i64::from(p.x));
        let y = p.map(|p| i64::from(p.y));
        // As `signed_area_ccw`; snapped coordinates within ±2^29 keep it in i64.
        let area = (x[2] - x[0]) * (y[1] - y[0]) - (x[1] - x[0]) * (y[2] - y[0]);
        if area == 0 {
            self.stats.invisible += 1;
            return Some(());
        }
        if area < 0 {
            if options.cull_backfaces {
                self.stats.culled += 1;
                return Some(());
            }
            return None;
        }
        self.stats.rasterized += 1;
        let Some(mut t) = Triangle::edges(x, y, options.width, options.height) else {
            return Some(());
        };
        if t.covers_no_centre() {
            return Some(());
        }
        let vertex = |k: usize| ScreenVertex {
            x: x[k],
            y: y[k],
            depth: p[k].depth,
            inv_w: p[k].inv_w,
            attrs: frame.front_attrs::<A>(first_corner + k),
        };
        let v: [ScreenVertex<A>; 3] = [vertex(0), vertex(1), vertex(2)];
        let planes = t.planes(&v, A, options.interpolation);
        if A == 0 {
            // As `flat_surface`, with the triangle's corners at hand.
            let positions = frame.scene.mesh.positions();
            let corners = &frame.scene.mesh.corners()[first_corner..first_corner + 3];
            let c = (Vec3::ZERO
                + positions[corners[0] as usize]
                + positions[corners[1] as usize]
                + positions[corners[2] as usize])
                / 3.0;
            self.flat_surfaces
                .push([normal.x, normal.y, normal.z, c.x, c.y, c.z]);
            t.color = (self.flat_surfaces.len() - 1) as u32;
        }
        self.bin(&t, &planes[..plane_count(A)]);
        Some(())
    }

    /// Queues a polygon for flat lighting; returns its index.
    fn flat_surface(&mut self, frame: &Frame<'_>, face: usize, normal: Vec3, back: bool) -> u32 {
        let mesh = &frame.scene.mesh;
        let polygon = mesh.polygon(face);
        let centroid = polygon
            .iter()
            .map(|&i| mesh.positions()[i as usize])
            .sum::<Vec3>()
            / polygon.len() as f32;
        let n = if back { -normal } else { normal };
        let p = centroid;
        self.flat_surfaces.push([n.x, n.y, n.z, p.x, p.y, p.z]);
        (self.flat_surfaces.len() - 1) as u32
    }

    /// Adds a set-up triangle to the bins of the bands it touches.
    #[inline(always)]
    fn bin(&mut self, t: &Triangle, planes: &[Plane]) {
        for band in t.bands() {
            let bin = &mut self.bins[band];
            bin.triangles.push(*t);
            bin.planes.extend_from_slice(planes);
            bin.columns = (bin.columns.0.min(t.x0), bin.columns.1.max(t.x1));
        }
    }

    /// Any polygon: clipped if needed, faced, split into the fan both
    /// rasterizers use.
    fn setup_polygon(&mut self, frame: &Frame<'_>, face: usize, normal: Vec3) {
        let options = frame.options;
        let mesh = &frame.scene.mesh;
        let attrs = frame.attr_count();
        // Facing first, from the projected positions when no clipping is
        // needed, so that culled polygons cost no attribute work.
        let corners = &mesh.corners()[mesh.corner_range(face)];
        let unclipped = corners
            .iter()
            .all(|&p| frame.projected[p as usize].inside());
        let area = if unclipped {
            window_area(frame.projected, corners)
        } else {
            self.project(frame, face, false);
            if self.window.len() < 3 {
                0
            } else {
                signed_area_ccw(&self.window)
            }
        };
        if area == 0 {
            self.stats.invisible += 1;
            return;
        }
        let back = area < 0;
        if back && options.cull_backfaces {
            self.stats.culled += 1;
            return;
        }
        if back || unclipped {
            self.project(frame, face, back);
        }
        if back {
            self.window.reverse();
        }
        self.stats.rasterized += 1;
        let color = if options.shading == Shading::Flat {
            self.flat_surface(frame, face, normal, back)
        } else {
            0
        };
        let fan = fan(&self.window);
        let once = if fan.once_per_pixel {
            face as u32 + 1
        } else {
            0
        };
        let window = std::mem::take(&mut self.window);
        for triangle in fan.triangles(&window) {
            if signed_area_ccw(&triangle) <= 0 {
                continue;
            }
            let (x, y) = (triangle.map(|v| v.x), triangle.map(|v| v.y));
            let Some(mut t) = Triangle::edges(x, y, options.width, options.height) else {
                continue;
            };
            if t.covers_no_centre() {
                continue;
            }
            let planes = t.planes(&triangle, attrs, options.interpolation);
            t.color = color;
            t.flip = if back { -1.0 } else { 1.0 };
            t.once = once;
            self.bin(&t, &planes[..plane_count(attrs)]);
        }
        self.window = window;
    }

    /// Lights the front polygons of flat shading, 8 at a time, and gives
    /// their triangles the colour.
    fn light_flat_polygons(&mut self, frame: &Frame<'_>) {
        self.stats.lighting_evaluations += self.flat_surfaces.len() as u64;
        self.flat_colors.clear();
        self.flat_colors
            .resize(self.flat_surfaces.len().next_multiple_of(8), 0);
        let kernel = FlatKernel {
            surfaces: &self.flat_surfaces,
            colors: &mut self.flat_colors,
            shader: frame.phong,
        };
        dispatch(frame.simd, kernel);
        for bin in &mut self.bins {
            for t in &mut bin.triangles {
                t.color = self.flat_colors[t.color as usize] as u32;
            }
        }
    }
}

/// Gouraud's vertex colours, 8 vertices per SIMD evaluation, clamped to
/// [0, 1] as `Lighting::eval(..).clamped()`.
struct VertexKernel<'a> {
    first: usize,
    colors: &'a mut [[f32; 3]],
    table: &'a VertexTable,
    positions: &'a [Vec3],
    normals: &'a [Vec3],
    sign: f32,
    shader: &'a PhongShader,
    specular: bool,
}

impl Kernel for VertexKernel<'_> {
    type Output = ();

    #[inline(always)]
    fn run<S: Simd>(self, s: S) {
        let t = self.table;
        for (j, colors) in self.colors.chunks_mut(8).enumerate() {
            let base = self.first + 8 * j;
            let mut lanes = [[0f32; 8]; 6];
            for (i, v) in (base..base + colors.len()).enumerate() {
                let p = t.position[v];
                if p == u32::MAX {
                    continue;
                }
                let n = self.normals[t.normal[v] as usize] * self.sign;
                let q = self.positions[p as usize];
                for (k, value) in [n.x, n.y, n.z, q.x, q.y, q.z].into_iter().enumerate() {
                    lanes[k][i] = value;
                }
            }
            let attrs: [Vf<S>; MAX_ATTRS] = std::array::from_fn(|k| Vf::load(s, &lanes[k]));
            let rgb = self.shader.radiance(s, &attrs, self.specular);
            let mut out = [[0f32; 8]; 3];
            for k in 0..3 {
                let c = rgb[k].max(Vf::splat(s, 0.0)).min(Vf::splat(s, 1.0));
                byte_units(c).store(&mut out[k]);
            }
            for (i, color) in colors.iter_mut().enumerate() {
                *color = [out[0][i], out[1][i], out[2][i]];
            }
        }
    }
}

/// One chunk's setup, compiled per SIMD level.
struct SetupKernel<'a, 'f> {
    chunk: &'a mut Chunk,
    frame: &'a Frame<'f>,
    faces: std::ops::Range<usize>,
}

impl Kernel for SetupKernel<'_, '_> {
    type Output = ();

    #[inline(always)]
    fn run<S: Simd>(self, _: S) {
        let (chunk, frame, faces) = (self.chunk, self.frame, self.faces);
        match frame.options.shading {
            Shading::Flat => chunk.setup::<0>(frame, faces),
            Shading::Gouraud => chunk.setup::<3>(frame, faces),
            Shading::Phong => chunk.setup::<6>(frame, faces),
        }
    }
}

/// Flat shading's lighting, 8 polygons per SIMD evaluation.
struct FlatKernel<'a> {
    surfaces: &'a [[f32; 6]],
    colors: &'a mut [i32],
    shader: &'a PhongShader,
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
            let packed = self.shader.light(s, &attrs);
            s.i_store(packed.0, colors.try_into().unwrap());
        }
    }
}

/// A position in clip space: one expression for the vertex stage and for
/// the polygons that clipping recomputes, so both see the same values.
#[inline(always)]
fn clip_position(view_projection: Mat4, p: Vec3) -> Vec4 {
    view_projection * p.extend(1.0)
}

/// Twice the signed area of a polygon's projected, snapped positions
/// (as [`signed_area_ccw`] of its window polygon).
fn window_area(projected: &[Projected], corners: &[u32]) -> i128 {
    let n = corners.len();
    let mut sum: i128 = 0;
    for i in 0..n {
        let a = &projected[corners[i] as usize];
        let b = &projected[corners[(i + 1) % n] as usize];
        sum += a.x as i128 * b.y as i128 - b.x as i128 * a.y as i128;
    }
    -sum
}

/// Where a band's result goes.
enum Output<'a> {
    /// Image rows, and the background colour packed as in the band.
    Image(&'a mut [Rgb8], i32),
    /// Coverage counts.
    Counts(&'a mut [u32]),
}

/// One band's work, compiled per SIMD level.
struct BandKernel<'a, S> {
    band: &'a mut Band,
    index: usize,
    chunks: &'a [Chunk],
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
            Output::Image(..) => Pass::Shade,
            Output::Counts(_) => Pass::Count,
        };
        let (x0, x1) = self
            .chunks
            .iter()
            .fold((i32::MAX, i32::MIN), |(x0, x1), chunk| {
                let columns = chunk.bins[self.index].columns;
                (x0.min(columns.0), x1.max(columns.1))
            });
        let columns = if x0 < x1 {
            x0 as usize..x1 as usize
        } else {
            0..0
        };
        self.band.begin(o.width, y1 - y0, pass, columns);
        let stride = plane_count(S::ATTRS);
        let lanes = self.shader.lanes(simd);
        for chunk in self.chunks {
            let bin = &chunk.bins[self.index];
            for (t, planes) in bin.triangles.iter().zip(bin.planes.chunks_exact(stride)) {
                self.band.draw(
                    simd,
                    t,
                    planes,
                    self.shader,
                    &lanes,
                    o.interpolation,
                    y0,
                    y1,
                    pass,
                );
            }
        }
        self.band.flush(simd, self.shader, &lanes);
        match self.output {
            Output::Image(pixels, background) => {
                self.band.finish(simd, pixels, o.width, background)
            }
            Output::Counts(counts) => self.band.finish_counts(counts, o.width),
        }
    }
}

/// The calling thread's band buffers (uncontended: one per pool thread;
/// a caller outside the pool uses the first).
fn scratch_band(scratch: &[Mutex<Band>]) -> MutexGuard<'_, Band> {
    let slot = rayon::current_thread_index().unwrap_or(0) % scratch.len();
    scratch[slot]
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// Runs one band of a pass with the shader `S`, compiled for the SIMD level.
fn band_pass<S: Shader>(
    simd: SimdLevel,
    band: &mut Band,
    index: usize,
    chunks: &[Chunk],
    shader: &S,
    options: &RenderOptions,
    output: Output<'_>,
) {
    let kernel = BandKernel {
        band,
        index,
        chunks,
        shader,
        options,
        output,
    };
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
            projected: Vec::new(),
            vertices: VertexTable::default(),
            faces: FaceNormals::default(),
            lit: Vec::new(),
            lit_back: Vec::new(),
            chunks: Vec::new(),
            phong: PhongShader::default(),
            bands: Vec::new(),
        }
    }

    pub fn simd(&self) -> SimdLevel {
        self.simd
    }
}

impl Rasterize for TiledRasterizer {
    /// Draws a validated scene into `image` (already of the right size).
    fn render(
        &mut self,
        scene: &Scene,
        options: &RenderOptions,
        lighting: &Lighting,
        image: &mut Image,
    ) -> RenderStats {
        let mut stats = self.geometry(scene, options, lighting);
        let width = options.width as usize;
        let (chunks, simd) = (&self.chunks, self.simd);
        let Rgb8([r, g, b]) = options.background;
        let background = i32::from(r) | i32::from(g) << 8 | i32::from(b) << 16;
        let phong = &self.phong;
        let scratch = &self.bands;
        let bands = image
            .pixels_mut()
            .par_chunks_mut(width * BAND_ROWS as usize)
            .enumerate();
        let totals = bands.map(|(index, pixels)| {
            let mut guard = scratch_band(scratch);
            let band = &mut *guard;
            let output = Output::Image(pixels, background);
            match options.shading {
                Shading::Flat => band_pass(simd, band, index, chunks, &FlatShader, options, output),
                Shading::Gouraud => {
                    band_pass(simd, band, index, chunks, &GouraudShader, options, output)
                }
                Shading::Phong => match &phong.one_point_light {
                    Some(one) => band_pass(simd, band, index, chunks, one, options, output),
                    None => band_pass(simd, band, index, chunks, phong, options, output),
                },
            }
            (band.fragments, band.covered)
        });
        let (fragments, covered) = totals.reduce(|| (0, 0), |a, b| (a.0 + b.0, a.1 + b.1));
        stats.fragments_shaded += fragments;
        stats.covered_pixels += covered;
        if options.shading == Shading::Phong {
            stats.lighting_evaluations = stats.fragments_shaded;
        }
        stats
    }

    /// How many triangles cover each pixel, with no depth test.
    fn coverage(
        &mut self,
        scene: &Scene,
        options: &RenderOptions,
        lighting: &Lighting,
    ) -> Vec<u32> {
        let options = RenderOptions {
            shading: Shading::Flat,
            ..*options
        };
        self.geometry(scene, &options, lighting);
        let width = options.width as usize;
        let mut counts = vec![0u32; width * options.height as usize];
        let (chunks, simd) = (&self.chunks, self.simd);
        let scratch = &self.bands;
        counts
            .par_chunks_mut(width * BAND_ROWS as usize)
            .enumerate()
            .for_each(|(index, out)| {
                let mut band = scratch_band(scratch);
                let output = Output::Counts(out);
                band_pass(
                    simd,
                    &mut band,
                    index,
                    chunks,
                    &FlatShader,
                    &options,
                    output,
                );
            });
        counts
    }
}

impl TiledRasterizer {
    /// Vertex stage, then setup and binning; leaves the bins in `self.chunks`.
    fn geometry(
        &mut self,
        scene: &Scene,
        options: &RenderOptions,
        lighting: &Lighting,
    ) -> RenderStats {
        let (width, height) = (options.width, options.height);
        let aspect = width as f32 / height as f32;
        let view_projection = scene.camera.projection(aspect) * scene.camera.view();
        let guard = guard_band(width, height);
        let mesh = &scene.mesh;
        self.phong.update(lighting);

        let positions = mesh.positions();
        let projected = &mut self.projected;
        // The positions' projection and Gouraud's vertex lighting are
        // independent: run together, neither waits for the other's last task.
        let project = || {
            projected.resize(positions.len(), Projected::default());
            projected
                .par_chunks_mut(4096)
                .zip(positions.par_chunks(4096))
                .for_each(|(out, points)| {
                    for (o, p) in out.iter_mut().zip(points) {
                        let clip = clip_position(view_projection, *p);
                        *o = if clip.is_finite() && is_inside(clip, guard) {
                            let w = to_window(&ClipVertex { clip, attrs: [] }, width, height);
                            Projected {
                                x: w.x as i32,
                                y: w.y as i32,
                                depth: w.depth,
                                inv_w: w.inv_w,
                            }
                        } else {
                            Projected {
                                x: Projected::OUTSIDE,
                                ..Projected::default()
                            }
                        };
                    }
                });
        };
        let (vertices, lit, lit_back) = (&mut self.vertices, &mut self.lit, &mut self.lit_back);
        let (phong, simd) = (&self.phong, self.simd);
        let light = || match options.shading {
            Shading::Gouraud => {
                light_vertices(vertices, lit, lit_back, phong, simd, scene, options)
            }
            _ => 0,
        };
        let ((), evaluations) = rayon::join(project, light);

        self.faces.update(mesh);
        let bands = height.div_ceil(BAND_ROWS) as usize;
        let threads = rayon::current_num_threads().max(1);
        self.bands.resize_with(threads, Mutex::default);
        self.bands.truncate(threads);
        for band in &mut self.bands {
            let band = band
                .get_mut()
                .unwrap_or_else(|poisoned| poisoned.into_inner());
            band.reserve(options.width);
        }
        let chunk_count = (rayon::current_num_threads() * SETUP_CHUNKS_PER_THREAD).max(1);
        self.chunks.resize_with(chunk_count, Chunk::default);
        self.chunks.truncate(chunk_count);
        let frame = Frame {
            scene,
            options,
            projected: &self.projected,
            view_projection,
            corner_vertex: &self.vertices.corner_vertex,
            faces: &self.faces.normals,
            phong: &self.phong,
            simd: self.simd,
            lit: &self.lit,
            lit_back: &self.lit_back,
            guard,
            bands,
        };
        let polygons = mesh.polygon_count();
        self.chunks
            .par_iter_mut()
            .enumerate()
            .for_each(|(i, chunk)| {
                let start = polygons * i / chunk_count;
                let end = polygons * (i + 1) / chunk_count;
                dispatch(
                    frame.simd,
                    SetupKernel {
                        chunk,
                        frame: &frame,
                        faces: start..end,
                    },
                );
            });

        let mut stats = RenderStats {
            polygons: polygons as u64,
            lighting_evaluations: evaluations,
            ..RenderStats::default()
        };
        for chunk in &self.chunks {
            let s = &chunk.stats;
            stats.degenerate += s.degenerate;
            stats.invisible += s.invisible;
            stats.culled += s.culled;
            stats.rasterized += s.rasterized;
            stats.lighting_evaluations += s.lighting_evaluations;
        }
        stats
    }
}

/// Gouraud's per-vertex lighting into `lit` (and `lit_back` for back faces
/// drawn), with the frame's lighting already in `shader`; returns the
/// number of evaluations.
fn light_vertices(
    vertices: &mut VertexTable,
    lit: &mut Vec<[f32; 3]>,
    lit_back: &mut Vec<[f32; 3]>,
    shader: &PhongShader,
    simd: SimdLevel,
    scene: &Scene,
    options: &RenderOptions,
) -> u64 {
    let normals = &scene.normals;
    vertices.update(&scene.mesh, &normals.corner, normals.normals.len());
    let terms = if options.gouraud_specular {
        Terms::Full
    } else {
        Terms::AmbientDiffuse
    };
    let table = &*vertices;
    let positions = scene.mesh.positions();
    let light = |out: &mut Vec<[f32; 3]>, sign: f32| {
        out.resize(table.position.len(), [0.0; 3]);
        out.par_chunks_mut(1024)
            .enumerate()
            .for_each(|(k, colors)| {
                let kernel = VertexKernel {
                    first: k * 1024,
                    colors,
                    table,
                    positions,
                    normals: &normals.normals,
                    sign,
                    shader,
                    specular: terms == Terms::Full,
                };
                dispatch(simd, kernel);
            });
    };
    light(lit, 1.0);
    if options.cull_backfaces {
        table.used
    } else {
        light(lit_back, -1.0);
        2 * table.used
    }
}
