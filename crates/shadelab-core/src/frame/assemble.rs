//! Polygon assembly, the one front end of both rasterizers: from a mesh's
//! polygons to clipped, window-space, counter-clockwise polygons with
//! their attributes, handed to a rasterizer's [`PolygonSink`].
//!
//! The frame owns the geometry of a frame ([`Geometry`]: face normals and
//! centroids, the vertex stage's output) and hands the rasterizer an
//! [`Unprojected`], which the rasterizer knows only as a [`VertexStage`]:
//! it runs the stage when it suits it (the tiled rasterizer beside its own
//! per-vertex lighting) and gets an [`Assembly`], a [`PolygonSource`]
//! whose polygons it walks, any run of consecutive ones at a time, into a
//! sink of its choosing: the scanline rasterizer all of them into one, the
//! tiled one a chunk per setup task. Every polygon of a frame takes this walk:
//!
//! 1. **Degenerate** polygons (no face normal) are counted and dropped.
//! 2. **Facing** comes first, from the snapped positions of the vertex
//!    stage ([`project_vertices`](super::window::project_vertices)) when
//!    no corner needs clipping, so that a culled polygon costs no
//!    attribute work; otherwise the polygon is clipped ([`clip_polygon`])
//!    with its front attributes and faced from the clipped window polygon.
//! 3. **Culling** drops back faces when asked; a back face drawn gets its
//!    back attributes (normals reversed) and is reversed to wind
//!    counter-clockwise, as a front face.
//! 4. The sink receives the polygon: [`PolygonSink::triangle`] for the
//!    common case, a front-facing triangle needing no clipping (its
//!    snapped corners, attributes read by the sink only if it draws
//!    something), [`PolygonSink::polygon`] for the rest.
//!
//! What must hold, and why it is built this way:
//!
//! * **Both rasterizers see the same polygons.** The same positions,
//!   snapping, clipping and facing decisions, so their coverage can be
//!   compared pixel for pixel. A polygon whose vertices are all inside the
//!   view volume and guard band skips clipping, because clipping would
//!   return it unchanged ([`crate::clip::is_inside`]).
//! * **Nothing here is paid per polygon that need not be.** The walk is
//!   generic over the sink and inlined into each rasterizer's loop; the
//!   corners' attribute sources are prefetched a few polygons ahead
//!   (meshes list their faces far from their vertices' order).

use std::ops::Range;

use glam::Vec3;
use rayon::prelude::*;

use super::window::{guard_band, to_window, ProjectKernel, View};
use crate::clip::{clip_polygon, ClipVertex};
use crate::mesh::Mesh;
use crate::normals::face_geometry;
use crate::raster::{signed_area_ccw, PolygonSink, PolygonSource, Projected, Scratch, VertexStage};
use crate::scene::{RenderOptions, RenderStats, Scene};
use crate::simd::{dispatch, prefetch, SimdLevel};

/// How many polygons ahead the walk starts loading a polygon's vertices.
const PREFETCH_AHEAD: usize = 8;

/// A frame's geometry, kept from frame to frame: each polygon's unit face
/// normal and centroid (recomputed only when the mesh's geometry changes) and each
/// position's window position (the vertex stage, every frame).
#[derive(Debug)]
pub(crate) struct Geometry {
    /// The geometry the face normals are of ([`Mesh::geometry_id`], 0: none).
    key_geometry: u64,
    faces: Vec<Option<Vec3>>,
    /// Each polygon's centroid, kept with its face normal.
    centroids: Vec<Vec3>,
    projected: Vec<Projected>,
    /// The vertex stage's SIMD level: the renderer's, but the AVX2 build
    /// where AVX-512 is there too, as the tiled setup's.
    level: SimdLevel,
}

impl Default for Geometry {
    /// The best SIMD level of this CPU.
    fn default() -> Geometry {
        Geometry::with_simd(SimdLevel::detect())
    }
}

impl Geometry {
    /// Geometry whose vertex stage runs at `level` (one this CPU has: see
    /// [`SimdLevel::is_supported`]).
    pub(crate) fn with_simd(level: SimdLevel) -> Geometry {
        Geometry {
            key_geometry: 0,
            faces: Vec::new(),
            centroids: Vec::new(),
            projected: Vec::new(),
            level: level.without_avx512(),
        }
    }

    /// The frame's polygons of `scene` drawn with `options`, the face
    /// normals brought up to date; the vertex stage is the rasterizer's to
    /// run ([`VertexStage::project`]).
    pub(crate) fn frame<'a>(
        &'a mut self,
        scene: &'a Scene,
        options: &RenderOptions,
    ) -> Unprojected<'a> {
        let mesh = &scene.mesh;
        self.update_faces(mesh);
        let (width, height) = (options.width, options.height);
        let aspect = width as f32 / height as f32;
        Unprojected {
            mesh,
            faces: &self.faces,
            centroids: &self.centroids,
            projected: &mut self.projected,
            level: self.level,
            view: View {
                view_projection: scene.camera.projection(aspect) * scene.camera.view(),
                width,
                height,
                guard: guard_band(width, height),
            },
            cull_backfaces: options.cull_backfaces,
        }
    }

    /// The face normals and centroids of `mesh`, brought up to date.
    pub(crate) fn faces_of(&mut self, mesh: &Mesh) -> (&[Option<Vec3>], &[Vec3]) {
        self.update_faces(mesh);
        (&self.faces, &self.centroids)
    }

    /// Takes `faces` and `centroids` as `mesh`'s face normals and
    /// centroids, which they must be, bit for bit (what [`face_geometry`]
    /// gives of it): a mesh whose polygons are another's reordered, each
    /// with the same corners in the same order, has that mesh's numbers
    /// reordered, and needs not compute them again.
    pub(crate) fn adopt_faces(
        &mut self,
        mesh: &Mesh,
        faces: Vec<Option<Vec3>>,
        centroids: Vec<Vec3>,
    ) {
        debug_assert_eq!(faces.len(), mesh.polygon_count());
        debug_assert_eq!(centroids.len(), mesh.polygon_count());
        self.key_geometry = mesh.geometry_id();
        (self.faces, self.centroids) = (faces, centroids);
    }

    fn update_faces(&mut self, mesh: &Mesh) {
        if self.key_geometry == mesh.geometry_id() {
            return;
        }
        self.key_geometry = mesh.geometry_id();
        face_geometry(mesh, &mut self.faces, &mut self.centroids);
    }
}

/// A frame's polygons before the vertex stage.
pub(crate) struct Unprojected<'a> {
    mesh: &'a Mesh,
    faces: &'a [Option<Vec3>],
    centroids: &'a [Vec3],
    projected: &'a mut Vec<Projected>,
    level: SimdLevel,
    view: View,
    cull_backfaces: bool,
}

impl VertexStage for Unprojected<'_> {
    type Polygons<'p>
        = Assembly<'p>
    where
        Self: 'p;

    /// Every position transformed and snapped, in parallel.
    fn project(&mut self) -> Assembly<'_> {
        let (positions, view) = (self.mesh.positions(), &self.view);
        self.projected.resize(positions.len(), Projected::default());
        let level = self.level;
        self.projected
            .par_chunks_mut(4096)
            .zip(positions.par_chunks(4096))
            .for_each(|(out, points)| dispatch(level, ProjectKernel { view, points, out }));
        Assembly {
            mesh: self.mesh,
            faces: self.faces,
            centroids: self.centroids,
            projected: self.projected.as_slice(),
            view: self.view,
            cull_backfaces: self.cull_backfaces,
        }
    }
}

/// A frame's polygons, ready to walk: what the walk reads of a frame.
#[derive(Clone, Copy)]
pub(crate) struct Assembly<'a> {
    pub(crate) mesh: &'a Mesh,
    /// One unit normal per polygon, `None` where its area is zero.
    pub(crate) faces: &'a [Option<Vec3>],
    /// Each polygon's centroid.
    pub(crate) centroids: &'a [Vec3],
    /// The vertex stage's output, one per mesh position.
    pub(crate) projected: &'a [Projected],
    pub(crate) view: View,
    pub(crate) cull_backfaces: bool,
}

impl PolygonSource for Assembly<'_> {
    fn count(&self) -> usize {
        self.mesh.polygon_count()
    }

    fn faces(&self) -> &[Option<Vec3>] {
        self.faces
    }

    fn centroids(&self) -> &[Vec3] {
        self.centroids
    }

    fn projected(&self) -> &[Projected] {
        self.projected
    }

    /// The walk (see the module's notes), inlined into the rasterizer's
    /// loop.
    #[inline(always)]
    fn walk<const N: usize, S: PolygonSink<N>>(
        &self,
        faces: Range<usize>,
        scratch: &mut Scratch<N>,
        sink: &mut S,
        stats: &mut RenderStats,
    ) {
        let mesh = self.mesh;
        let end = faces.end;
        for face in faces {
            if face + PREFETCH_AHEAD < end {
                self.prefetch(face + PREFETCH_AHEAD, sink);
            }
            let Some(normal) = self.faces[face] else {
                stats.degenerate += 1;
                continue;
            };
            let range = mesh.corner_range(face);
            if let &[i0, i1, i2] = &mesh.corners()[range.clone()] {
                let p = [i0, i1, i2].map(|i| self.projected[i as usize]);
                if p.iter().all(Projected::inside) {
                    let (x, y) = (p.map(|p| i64::from(p.x)), p.map(|p| i64::from(p.y)));
                    // As `signed_area_ccw`; snapped coordinates within ±2^29
                    // keep it in i64.
                    let area = (x[2] - x[0]) * (y[1] - y[0]) - (x[1] - x[0]) * (y[2] - y[0]);
                    if area == 0 {
                        stats.invisible += 1;
                        continue;
                    }
                    if area > 0 {
                        stats.rasterized += 1;
                        sink.triangle(face, normal, range.start, [i0, i1, i2], &p);
                        continue;
                    }
                    if self.cull_backfaces {
                        stats.culled += 1;
                        continue;
                    }
                    // A back face drawn: the general path.
                }
            }
            self.polygon(face, normal, scratch, sink, stats);
        }
    }
}

impl Assembly<'_> {
    /// Any polygon: clipped if needed, faced, culled or reversed. Kept out
    /// of the walk's loop, which it would crowd: few polygons come here.
    #[inline(never)]
    fn polygon<const N: usize, S: PolygonSink<N>>(
        &self,
        face: usize,
        normal: Vec3,
        scratch: &mut Scratch<N>,
        sink: &mut S,
        stats: &mut RenderStats,
    ) {
        let corners = &self.mesh.corners()[self.mesh.corner_range(face)];
        let unclipped = corners.iter().all(|&p| self.projected[p as usize].inside());
        let area = if unclipped {
            window_area(self.projected, corners)
        } else {
            self.project(face, false, false, scratch, sink);
            if scratch.window.len() < 3 {
                0
            } else {
                signed_area_ccw(&scratch.window)
            }
        };
        if area == 0 {
            stats.invisible += 1;
            return;
        }
        let back = area < 0;
        if back && self.cull_backfaces {
            stats.culled += 1;
            return;
        }
        if back || unclipped {
            self.project(face, back, unclipped, scratch, sink);
        }
        if back {
            scratch.window.reverse();
        }
        stats.rasterized += 1;
        sink.polygon(face, normal, back, &scratch.window);
    }

    /// The polygon's window-space vertices in `scratch.window`, clipped
    /// unless `unclipped` (every corner inside, as `polygon` found), with
    /// the attributes of its front (or back) side.
    fn project<const N: usize, S: PolygonSink<N>>(
        &self,
        face: usize,
        back: bool,
        unclipped: bool,
        scratch: &mut Scratch<N>,
        sink: &mut S,
    ) {
        let mesh = self.mesh;
        let range = mesh.corner_range(face);
        let corners = &mesh.corners()[range.clone()];
        scratch.window.clear();
        if unclipped {
            for (c, &v) in range.zip(corners) {
                let attrs = sink.corner(c, v, back);
                scratch
                    .window
                    .push(self.projected[v as usize].vertex(attrs));
            }
            return;
        }
        scratch.input.clear();
        for (c, &v) in range.zip(corners) {
            scratch.input.push(ClipVertex {
                clip: self.view.clip(mesh.positions()[v as usize]),
                attrs: sink.corner(c, v, back),
            });
        }
        clip_polygon(
            &scratch.input,
            self.view.guard,
            &mut scratch.clipped,
            &mut scratch.spare,
        );
        let (width, height) = (self.view.width, self.view.height);
        scratch
            .window
            .extend(scratch.clipped.iter().map(|v| to_window(v, width, height)));
    }

    /// Starts loading what walking polygon `face` reads at random: its
    /// vertices' window positions and the sink's attribute sources. Where
    /// [`prefetch`] is no instruction (WebAssembly), this does nothing: the
    /// addresses' index loads and bounds checks would stay.
    #[inline(always)]
    fn prefetch<const N: usize, S: PolygonSink<N>>(&self, face: usize, sink: &S) {
        if !cfg!(target_arch = "x86_64") {
            return;
        }
        let range = self.mesh.corner_range(face);
        if range.len() == 3 {
            // Triangles, nearly all polygons: straight-line code, no loop to
            // leave (its exit would be mispredicted every few polygons).
            self.prefetch_corner(range.start, sink);
            self.prefetch_corner(range.start + 1, sink);
            self.prefetch_corner(range.start + 2, sink);
            return;
        }
        for c in range {
            self.prefetch_corner(c, sink);
        }
    }

    /// [`Assembly::prefetch`] of one corner (a method, not a closure: a
    /// closure here was not inlined, and its calls cost 8 % of a frame).
    #[inline(always)]
    fn prefetch_corner<const N: usize, S: PolygonSink<N>>(&self, corner: usize, sink: &S) {
        let vertex = self.mesh.corners()[corner];
        prefetch(&self.projected[vertex as usize]);
        sink.prefetch_corner(corner, vertex);
    }
}

/// Twice the signed area of a polygon's projected, snapped positions
/// (as [`signed_area_ccw`] of its window polygon).
pub(crate) fn window_area(projected: &[Projected], corners: &[u32]) -> i128 {
    let n = corners.len();
    let mut sum: i128 = 0;
    for i in 0..n {
        let a = &projected[corners[i] as usize];
        let b = &projected[corners[(i + 1) % n] as usize];
        sum += a.x as i128 * b.y as i128 - b.x as i128 * a.y as i128;
    }
    -sum
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::super::window::project_vertices;
    use super::*;
    use crate::camera::Camera;
    use crate::models::{builtin_model, BUILTIN_MODELS};
    use crate::normals::face_normals;
    use crate::raster::ScreenVertex;

    /// Records what it is given; a corner's attributes name it. The
    /// default [`PolygonSink::triangle`].
    #[derive(Default)]
    struct Record(Vec<(usize, bool, Vec<ScreenVertex<3>>)>);

    fn attrs(corner: usize, vertex: u32, back: bool) -> [f32; 3] {
        [corner as f32, vertex as f32, f32::from(u8::from(back))]
    }

    impl PolygonSink<3> for Record {
        fn corner(&mut self, corner: usize, vertex: u32, back: bool) -> [f32; 3] {
            attrs(corner, vertex, back)
        }

        fn polygon(&mut self, face: usize, _: Vec3, back: bool, window: &[ScreenVertex<3>]) {
            self.0.push((face, back, window.to_vec()));
        }
    }

    /// [`Record`] with a triangle of its own, as the tiled setup has.
    #[derive(Default)]
    struct Triangles(Record);

    impl PolygonSink<3> for Triangles {
        fn corner(&mut self, corner: usize, vertex: u32, back: bool) -> [f32; 3] {
            attrs(corner, vertex, back)
        }

        fn polygon(&mut self, face: usize, n: Vec3, back: bool, window: &[ScreenVertex<3>]) {
            self.0.polygon(face, n, back, window);
        }

        fn triangle(
            &mut self,
            face: usize,
            _: Vec3,
            first_corner: usize,
            vertices: [u32; 3],
            p: &[Projected; 3],
        ) {
            let window = (0..3)
                .map(|k| p[k].vertex(attrs(first_corner + k, vertices[k], false)))
                .collect();
            self.0 .0.push((face, false, window));
        }
    }

    /// The walk, written the plain way: every polygon clipped, projected
    /// and faced from its clipped window polygon.
    fn reference(
        mesh: &Mesh,
        faces: &[Option<Vec3>],
        view: &View,
        cull: bool,
    ) -> (Vec<(usize, bool, Vec<ScreenVertex<3>>)>, RenderStats) {
        let mut stats = RenderStats::default();
        let mut out = Vec::new();
        let window = |face: usize, back: bool| {
            let input: Vec<ClipVertex<3>> = mesh
                .corner_range(face)
                .map(|c| {
                    let v = mesh.corners()[c];
                    ClipVertex {
                        clip: view.view_projection * mesh.positions()[v as usize].extend(1.0),
                        attrs: attrs(c, v, back),
                    }
                })
                .collect();
            let (mut clipped, mut spare) = (Vec::new(), Vec::new());
            clip_polygon(&input, view.guard, &mut clipped, &mut spare);
            clipped
                .iter()
                .map(|v| to_window(v, view.width, view.height))
                .collect::<Vec<_>>()
        };
        for (face, normal) in faces.iter().enumerate() {
            if normal.is_none() {
                stats.degenerate += 1;
                continue;
            }
            let front = window(face, false);
            let area = if front.len() < 3 {
                0
            } else {
                signed_area_ccw(&front)
            };
            if area == 0 {
                stats.invisible += 1;
            } else if area > 0 {
                stats.rasterized += 1;
                out.push((face, false, front));
            } else if cull {
                stats.culled += 1;
            } else {
                stats.rasterized += 1;
                let mut back = window(face, true);
                back.reverse();
                out.push((face, true, back));
            }
        }
        (out, stats)
    }

    /// Every built-in model, framed and from inside its bounds (near-plane
    /// and guard-band clipping), culling on and off: the walk hands over
    /// exactly the polygons, facings and window vertices of the plain way,
    /// and counts each polygon once.
    #[test]
    fn the_walk_gives_what_clipping_every_polygon_gives() {
        let (width, height) = (96, 64);
        let (mut clipped, mut backs) = (0, 0);
        for info in BUILTIN_MODELS {
            let mesh = builtin_model(info.name, None).unwrap();
            let faces = face_normals(&mesh);
            let (lo, hi) = mesh.bounds();
            let centre = (lo + hi) * 0.5;
            let radius = (hi - lo).length() * 0.5;
            let framed = Camera::framing_sphere(centre, radius, 45.0, 1.5);
            let inside = Camera {
                eye: centre + Vec3::new(0.1, 0.2, 0.3) * radius,
                near: 0.01 * radius,
                ..framed
            };
            for camera in [framed, framed.orbit(70.0, 30.0), inside] {
                let view = View {
                    view_projection: camera.projection(1.5) * camera.view(),
                    width,
                    height,
                    guard: guard_band(width, height),
                };
                let mut projected = vec![Projected::default(); mesh.positions().len()];
                project_vertices(&view, mesh.positions(), &mut projected);
                for cull in [true, false] {
                    let assembly = Assembly {
                        mesh: &mesh,
                        faces: &faces,
                        centroids: &[],
                        projected: &projected,
                        view,
                        cull_backfaces: cull,
                    };
                    let (want, want_stats) = reference(&mesh, &faces, &view, cull);
                    let case = format!("{} {camera:?} cull {cull}", info.name);
                    let all = 0..mesh.polygon_count();
                    let mut stats = RenderStats::default();
                    let mut record = Record::default();
                    assembly.walk(
                        all.clone(),
                        &mut Scratch::default(),
                        &mut record,
                        &mut stats,
                    );
                    assert_eq!(stats, want_stats, "{case}");
                    let mut triangles = Triangles::default();
                    let mut again = RenderStats::default();
                    assembly.walk(all, &mut Scratch::default(), &mut triangles, &mut again);
                    assert_eq!(again, want_stats, "{case}");
                    clipped += want
                        .iter()
                        .filter(|(face, _, w)| {
                            w.len() != mesh.corner_range(*face).len()
                                || w.iter().any(|v| v.attrs[0].fract() != 0.0)
                        })
                        .count();
                    backs += want.iter().filter(|(_, back, _)| *back).count();
                    for got in [record.0, triangles.0 .0] {
                        assert_eq!(got.len(), want.len(), "{case}");
                        for (got, want) in got.iter().zip(&want) {
                            assert_eq!(got, want, "{case}");
                        }
                    }
                    let counted = stats.degenerate + stats.invisible + stats.culled;
                    assert_eq!(counted + stats.rasterized, mesh.polygon_count() as u64);
                }
            }
        }
        // The cases reach clipping and back faces drawn.
        assert!(
            clipped > 100 && backs > 100,
            "{clipped} clipped, {backs} back faces"
        );
    }

    /// The vertex stage runs at the renderer's SIMD level (so `shadelab
    /// bench --simd portable` times a portable frame), at AVX2 where that
    /// is AVX-512 (as setup), and at the best this CPU has by default.
    #[test]
    fn the_vertex_stage_runs_at_the_renderers_level() {
        for level in SimdLevel::supported() {
            let renderer = crate::frame::Renderer::with_simd(level);
            assert_eq!(renderer.geometry.level, level.without_avx512());
        }
        assert_eq!(
            Geometry::default().level,
            SimdLevel::detect().without_avx512()
        );
    }
}
