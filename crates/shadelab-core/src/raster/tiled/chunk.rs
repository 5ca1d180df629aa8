//! Setup: one chunk of consecutive polygons projected, culled, clipped
//! when needed, set up as triangles and binned into bands (step 2 of
//! `mod.rs`); flat shading lights its polygons here, 8 at a time.

use glam::{Mat4, Vec3, Vec4};

use super::setup::{plane_count, Plane, Triangle, ALL_ATTRS, BAND_ROWS};

use crate::clip::{clip_polygon, ClipVertex};
use crate::raster::to_window;
use crate::raster::{fan, signed_area_ccw, ScreenVertex};
use crate::scene::{RenderOptions, RenderStats, Scene, Shading};
use crate::shade::{PhongShader, MAX_ATTRS};
use crate::simd::{dispatch, prefetch, Kernel, Simd, SimdLevel, Vf};

/// How many polygons ahead setup starts loading a polygon's vertices.
const PREFETCH_AHEAD: usize = 8;

/// A vertex's window position, when it is inside the view volume and guard
/// band (`x == OUTSIDE` otherwise). Snapped coordinates stay within ±2^29,
/// so they fit in `i32`.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Projected {
    pub(super) x: i32,
    pub(super) y: i32,
    pub(super) depth: f32,
    pub(super) inv_w: f32,
}

impl Projected {
    pub(super) const OUTSIDE: i32 = i32::MIN;

    pub(super) fn inside(&self) -> bool {
        self.x != Projected::OUTSIDE
    }
}

/// The triangles of one chunk that touch one band, in submission order,
/// copied here so that the band reads them as one contiguous stream.
#[derive(Debug, Default)]
pub(super) struct Bin {
    pub(super) triangles: Vec<Triangle>,
    /// `plane_count` planes per triangle.
    pub(super) planes: Vec<Plane>,
    /// The columns `[x0, x1)` of the triangles' boxes, together (empty:
    /// `x0 >= x1`): the band clears and reads back only those.
    pub(super) columns: (i32, i32),
}

impl Bin {
    pub(super) fn clear(&mut self) {
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
pub(super) struct Chunk {
    pub(super) bins: Vec<Bin>,
    pub(super) stats: RenderStats,
    pub(super) input: Vec<ClipVertex<ALL_ATTRS>>,
    pub(super) clipped: Vec<ClipVertex<ALL_ATTRS>>,
    pub(super) scratch: Vec<ClipVertex<ALL_ATTRS>>,
    pub(super) window: Vec<ScreenVertex<ALL_ATTRS>>,
    /// Flat shading: each front polygon's unit normal and centroid, lit in
    /// SIMD batches once setup is done; triangles hold an index until then.
    pub(super) flat_surfaces: Vec<[f32; 6]>,
    pub(super) flat_colors: Vec<i32>,
}

/// What setup needs to know about the frame.
pub(super) struct Frame<'a> {
    pub(super) scene: &'a Scene,
    pub(super) options: &'a RenderOptions,
    /// The method whose attributes are set up, or `None` for the three
    /// methods at once (`ALL_ATTRS`: Phong's, then Gouraud's colours; flat
    /// colours in the triangles).
    pub(super) method: Option<Shading>,
    pub(super) projected: &'a [Projected],
    pub(super) view_projection: Mat4,
    pub(super) corner_vertex: &'a [u32],
    pub(super) faces: &'a [Option<Vec3>],
    pub(super) phong: &'a PhongShader,
    pub(super) simd: SimdLevel,
    pub(super) lit: &'a [[f32; 3]],
    pub(super) lit_back: &'a [[f32; 3]],
    pub(super) guard: f32,
    pub(super) bands: usize,
    /// The image rows drawn (whole bands): triangles outside them are
    /// counted, and flat lights their polygons, but they get no planes and
    /// no bins.
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
            let n = normals.normals[normals.corner[corner] as usize];
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
            let n = normals.normals[normals.corner[corner] as usize];
            let p = self.scene.mesh.positions()[self.scene.mesh.corners()[corner] as usize];
            out[..6].copy_from_slice(&[n.x, n.y, n.z, p.x, p.y, p.z]);
        }
        if A == ALL_ATTRS {
            let c = self.lit[self.corner_vertex[corner] as usize];
            out[6..].copy_from_slice(&c);
        }
        out
    }

    /// Starts loading what setting up polygon `face` reads at random: its
    /// vertices' window positions and (for `A` attributes) the corners'
    /// attribute sources. Meshes list their faces in an order far from
    /// their vertices' (the bunny's faces jump by a median of 1,557 vertex
    /// indices), so without this nearly every polygon waits for memory.
    /// Where [`prefetch`] is no instruction (WebAssembly), this does
    /// nothing: the addresses' index loads and bounds checks would stay.
    #[inline(always)]
    pub(super) fn prefetch<const A: usize>(&self, face: usize) {
        if !cfg!(target_arch = "x86_64") {
            return;
        }
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
    pub(super) fn prefetch_corner<const A: usize>(&self, corner: usize) {
        let mesh = &self.scene.mesh;
        let vertex = mesh.corners()[corner] as usize;
        prefetch(&self.projected[vertex]);
        if A == 3 || A == ALL_ATTRS {
            prefetch(&self.lit[self.corner_vertex[corner] as usize]);
        }
        if A >= 6 {
            let normals = &self.scene.normals;
            prefetch(&normals.normals[normals.corner[corner] as usize]);
            prefetch(&mesh.positions()[vertex]);
        }
    }

    /// Whether triangle `t` has rows among those drawn.
    #[inline(always)]
    pub(super) fn draws(&self, t: &Triangle) -> bool {
        t.y1 > self.rows.start && t.y0 < self.rows.end
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

impl Chunk {
    /// The polygon's window-space vertices, clipped, with the attributes of
    /// its front (or back) side, as the scanline pipeline computes them.
    pub(super) fn project(&mut self, frame: &Frame<'_>, face: usize, back: bool) {
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
    pub(super) fn setup<const A: usize>(
        &mut self,
        frame: &Frame<'_>,
        faces: std::ops::Range<usize>,
    ) {
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
        if frame.lights_polygons() {
            self.light_flat_polygons(frame);
        }
    }

    /// The common case: a triangle whose corners are all inside the view
    /// volume, set up straight from the projected positions. `None` when it
    /// is a back face to be drawn (culling off), left to `setup_polygon`.
    #[inline(always)]
    pub(super) fn setup_triangle<const A: usize>(
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
        if A == 0 || A == ALL_ATTRS {
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
        if !frame.draws(&t) {
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
        self.bin(&t, &planes[..plane_count(A)], frame);
        Some(())
    }

    /// Queues a polygon for flat lighting; returns its index.
    pub(super) fn flat_surface(
        &mut self,
        frame: &Frame<'_>,
        face: usize,
        normal: Vec3,
        back: bool,
    ) -> u32 {
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

    /// Adds a set-up triangle to the bins of the drawn bands it touches.
    #[inline(always)]
    pub(super) fn bin(&mut self, t: &Triangle, planes: &[Plane], frame: &Frame<'_>) {
        let bands = t.bands();
        let drawn = frame.rows.start as usize / BAND_ROWS as usize
            ..(frame.rows.end as usize).div_ceil(BAND_ROWS as usize);
        for band in bands.start.max(drawn.start)..bands.end.min(drawn.end) {
            let bin = &mut self.bins[band];
            bin.triangles.push(*t);
            bin.planes.extend_from_slice(planes);
            bin.columns = (bin.columns.0.min(t.x0), bin.columns.1.max(t.x1));
        }
    }

    /// Any polygon: clipped if needed, faced, split into the fan both
    /// rasterizers use.
    pub(super) fn setup_polygon(&mut self, frame: &Frame<'_>, face: usize, normal: Vec3) {
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
        let color = if frame.lights_polygons() {
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
            if t.covers_no_centre() || !frame.draws(&t) {
                continue;
            }
            let planes = t.planes(&triangle, attrs, options.interpolation);
            t.color = color;
            t.flip = if back { -1.0 } else { 1.0 };
            t.once = once;
            self.bin(&t, &planes[..plane_count(attrs)], frame);
        }
        self.window = window;
    }

    /// Lights the front polygons of flat shading, 8 at a time, and gives
    /// their triangles the colour.
    pub(super) fn light_flat_polygons(&mut self, frame: &Frame<'_>) {
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

/// One chunk's setup, compiled per SIMD level.
pub(super) struct SetupKernel<'a, 'f> {
    pub(super) chunk: &'a mut Chunk,
    pub(super) frame: &'a Frame<'f>,
    pub(super) faces: std::ops::Range<usize>,
}

impl Kernel for SetupKernel<'_, '_> {
    type Output = ();

    #[inline(always)]
    fn run<S: Simd>(self, _: S) {
        let (chunk, frame, faces) = (self.chunk, self.frame, self.faces);
        match frame.method {
            Some(Shading::Flat) => chunk.setup::<0>(frame, faces),
            Some(Shading::Gouraud) => chunk.setup::<3>(frame, faces),
            Some(Shading::Phong) => chunk.setup::<6>(frame, faces),
            None => chunk.setup::<ALL_ATTRS>(frame, faces),
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
            let packed = self.shader.light(s, &attrs);
            s.i_store(packed.0, colors.try_into().unwrap());
        }
    }
}

/// A position in clip space: one expression for the vertex stage and for
/// the polygons that clipping recomputes, so both see the same values.
#[inline(always)]
pub(super) fn clip_position(view_projection: Mat4, p: Vec3) -> Vec4 {
    view_projection * p.extend(1.0)
}

/// Twice the signed area of a polygon's projected, snapped positions
/// (as [`signed_area_ccw`] of its window polygon).
pub(super) fn window_area(projected: &[Projected], corners: &[u32]) -> i128 {
    let n = corners.len();
    let mut sum: i128 = 0;
    for i in 0..n {
        let a = &projected[corners[i] as usize];
        let b = &projected[corners[(i + 1) % n] as usize];
        sum += a.x as i128 * b.y as i128 - b.x as i128 * a.y as i128;
    }
    -sum
}
