//! Probes: what the scanline rasterizer actually did at chosen pixels.
//!
//! A probe renders the frame through the same pipeline as [`crate::render`]
//! (scanline rasterizer, same clipping, snapping, stepping and shading code)
//! into a target that keeps the depth of the watched pixels only. For each
//! watched pixel it records the fragment that won the depth test: the
//! polygon, the interpolated attributes the shading method received, the
//! light it computed and the colour written, and, on request, the scanline
//! walk's state for that span (P, Q, the edges' parameters and the stepped
//! values). Nothing is computed a second time, so what it reports is what
//! was drawn; teaching instruments build their explanations on it.

use crate::color::{Rgb, Rgb8};
use crate::frame::{lighting, validate, Geometry};
use crate::raster::scanline::{draw, Target};
use crate::raster::scanline::{SpanTrace, Varyings};
use crate::raster::{Interpolation, VertexStage, SUBPIXEL_ONE};
use crate::scene::{Rasterizer, RenderError, RenderOptions, Scene, Shading};

/// Which pixels to watch.
#[derive(Debug, Clone, Copy)]
pub struct ProbeRequest<'a> {
    /// The pixels, (column, row); outside the image they record nothing.
    pub pixels: &'a [(u32, u32)],
    /// Also record the scanline walk's state for each winning fragment.
    pub trace: bool,
}

/// A polygon vertex as the rasterizer received it.
#[derive(Debug, Clone, PartialEq)]
pub struct VertexRecord {
    /// Window x in pixels (snapped to 1/256).
    pub x: f64,
    /// Window y in pixels (snapped to 1/256), row 0 at the top.
    pub y: f64,
    /// Window depth.
    pub depth: f32,
    /// 1/w.
    pub inv_w: f32,
    /// The method's attributes at the vertex.
    pub attrs: Vec<f32>,
}

/// Depth, 1/w and the attributes as the walk steps them (attribute/w in
/// perspective mode).
#[derive(Debug, Clone, PartialEq)]
pub struct SteppedRecord {
    /// Window depth.
    pub depth: f64,
    /// 1/w.
    pub inv_w: f64,
    /// As stepped.
    pub stepped: Vec<f64>,
}

impl SteppedRecord {
    fn new<const N: usize>(v: &Varyings<N>) -> SteppedRecord {
        SteppedRecord {
            depth: v.depth,
            inv_w: v.inv_w,
            stepped: v.attrs.to_vec(),
        }
    }

    /// The attributes themselves (divided by 1/w in perspective mode).
    pub fn attributes(&self, interpolation: Interpolation) -> Vec<f64> {
        match interpolation {
            Interpolation::Perspective => self.stepped.iter().map(|a| a / self.inv_w).collect(),
            Interpolation::Screen => self.stepped.clone(),
        }
    }
}

/// Where the scanline crossed one edge.
#[derive(Debug, Clone, PartialEq)]
pub struct EdgeRecord {
    /// Index in [`SpanRecord::polygon`] of the edge's upper end.
    pub top: usize,
    /// Index of its lower end.
    pub bottom: usize,
    /// The crossing's x, pixels.
    pub x: f64,
    /// The edge parameter at the crossing, 0 at `top` and 1 at `bottom`.
    pub t: f64,
    /// The values stepped down the edge to this row.
    pub value: SteppedRecord,
}

/// The scanline walk's state for the span that drew a watched pixel.
#[derive(Debug, Clone, PartialEq)]
pub struct SpanRecord {
    /// The convex polygon walked: the whole (clipped) polygon, or a triangle of its fan.
    pub polygon: Vec<VertexRecord>,
    /// The row.
    pub row: u32,
    /// The left edge, crossed at P.
    pub left: EdgeRecord,
    /// The right edge, crossed at Q.
    pub right: EdgeRecord,
    /// First pixel filled and one past the last.
    pub pixels: std::ops::Range<u32>,
    /// Values at the first pixel's centre.
    pub start: SteppedRecord,
    /// Step per pixel.
    pub step: SteppedRecord,
    /// How attributes were interpolated.
    pub interpolation: Interpolation,
    /// Fixed-point fraction bits, when stepping was in fixed point.
    pub fraction_bits: Option<u32>,
}

impl SpanRecord {
    fn new<const N: usize>(span: &SpanTrace<'_, N>) -> SpanRecord {
        let edge = |e: &crate::raster::scanline::EdgeTrace<N>| EdgeRecord {
            top: e.top,
            bottom: e.bottom,
            x: e.x,
            t: e.t,
            value: SteppedRecord::new(&e.value),
        };
        SpanRecord {
            polygon: span
                .polygon
                .iter()
                .map(|v| VertexRecord {
                    x: v.x as f64 / SUBPIXEL_ONE as f64,
                    y: v.y as f64 / SUBPIXEL_ONE as f64,
                    depth: v.depth,
                    inv_w: v.inv_w,
                    attrs: v.attrs.to_vec(),
                })
                .collect(),
            row: span.row,
            left: edge(&span.left),
            right: edge(&span.right),
            pixels: span.pixels.clone(),
            start: SteppedRecord::new(&span.start),
            step: SteppedRecord::new(&span.step),
            interpolation: span.options.interpolation,
            fraction_bits: span.options.fraction_bits,
        }
    }

    /// The span parameter of pixel column `x`: `u = |PO| / |PQ|`, with O the pixel's centre.
    pub fn u(&self, x: u32) -> f64 {
        (f64::from(x) + 0.5 - self.left.x) / (self.right.x - self.left.x)
    }
}

/// The fragment that won the depth test at a watched pixel.
#[derive(Debug, Clone, PartialEq)]
pub struct FragmentRecord {
    /// Column.
    pub x: u32,
    /// Row.
    pub y: u32,
    /// The mesh polygon drawn there.
    pub face: usize,
    /// Seen from behind (culling off): lit with reversed normals.
    pub back: bool,
    /// Window depth.
    pub depth: f32,
    /// The interpolated attributes the shading method received.
    pub attrs: Vec<f32>,
    /// The light the method computed, before clamping and rounding.
    pub lit: Rgb,
    /// The colour written.
    pub color: Rgb8,
    /// The walk's state, when traced.
    pub span: Option<SpanRecord>,
}

struct ProbeTarget {
    /// Per image row: the watched columns of that row, sorted, with their
    /// slots (memory in proportion to the rows and the pixels watched).
    rows: Vec<Vec<(u32, usize)>>,
    depth: Vec<f32>,
    records: Vec<Option<FragmentRecord>>,
    trace: bool,
    pending: Vec<Option<SpanRecord>>,
    face: usize,
    back: bool,
}

impl ProbeTarget {
    fn slot(&self, x: u32, y: u32) -> Option<usize> {
        let row = &self.rows[y as usize];
        if row.is_empty() {
            return None;
        }
        row.binary_search_by_key(&x, |&(c, _)| c)
            .ok()
            .map(|k| row[k].1)
    }
}

impl Target for ProbeTarget {
    fn test(&mut self, x: u32, y: u32, depth: f32) -> bool {
        match self.slot(x, y) {
            Some(s) if depth < self.depth[s] => {
                self.depth[s] = depth;
                true
            }
            _ => false,
        }
    }

    fn write(&mut self, _x: u32, _y: u32, _color: Rgb8) {}

    fn polygon(&mut self, face: usize, back: bool) {
        self.face = face;
        self.back = back;
    }

    fn wants_trace(&self, y: u32) -> bool {
        self.trace && !self.rows[y as usize].is_empty()
    }

    fn trace<const N: usize>(&mut self, span: &SpanTrace<'_, N>) {
        let mut record = None;
        for x in span.pixels.clone() {
            if let Some(s) = self.slot(x, span.row) {
                let r = record.get_or_insert_with(|| SpanRecord::new(span));
                self.pending[s] = Some(r.clone());
            }
        }
    }

    fn shaded<const N: usize>(&mut self, x: u32, y: u32, attrs: &[f32; N], lit: Rgb, color: Rgb8) {
        if let Some(s) = self.slot(x, y) {
            self.records[s] = Some(FragmentRecord {
                x,
                y,
                face: self.face,
                back: self.back,
                depth: self.depth[s],
                attrs: attrs.to_vec(),
                lit,
                color,
                span: self.pending[s].clone(),
            });
        }
    }
}

/// Renders `scene` with the scanline rasterizer (whatever `options`
/// says) and records the winning fragment at each requested pixel, in the
/// order asked; `None` where nothing was drawn or the pixel is outside.
///
/// # Errors
/// As [`crate::render`].
pub fn probe(
    scene: &Scene,
    options: &RenderOptions,
    request: ProbeRequest<'_>,
) -> Result<Vec<Option<FragmentRecord>>, RenderError> {
    let options = RenderOptions {
        rasterizer: Rasterizer::Scanline,
        ..*options
    };
    validate(scene, &options)?;
    let (w, h) = (options.width, options.height);
    let mut target = ProbeTarget {
        rows: vec![Vec::new(); h as usize],
        depth: Vec::new(),
        records: Vec::new(),
        trace: request.trace,
        pending: Vec::new(),
        face: 0,
        back: false,
    };
    // A pixel asked for twice shares one slot.
    let mut inside: Vec<(u32, u32, usize)> = request
        .pixels
        .iter()
        .enumerate()
        .filter(|(_, &(x, y))| x < w && y < h)
        .map(|(k, &(x, y))| (y, x, k))
        .collect();
    inside.sort_unstable();
    let mut slot_of_request = vec![None; request.pixels.len()];
    for (i, &(y, x, k)) in inside.iter().enumerate() {
        if i == 0 || (inside[i - 1].0, inside[i - 1].1) != (y, x) {
            target.depth.push(1.0);
            target.records.push(None);
            target.pending.push(None);
            target.rows[y as usize].push((x, target.depth.len() - 1));
        }
        slot_of_request[k] = Some(target.depth.len() - 1);
    }
    let mut geometry = Geometry::default();
    let mut frame = geometry.frame(scene, &options);
    let lighting = lighting(scene, &options);
    draw(&frame.project(), scene, &options, &lighting, &mut target);
    Ok(slot_of_request
        .into_iter()
        .map(|s| s.and_then(|s| target.records[s].clone()))
        .collect())
}

struct DepthTarget {
    width: u32,
    depth: Vec<f32>,
}

impl Target for DepthTarget {
    fn test(&mut self, x: u32, y: u32, depth: f32) -> bool {
        let d = &mut self.depth[y as usize * self.width as usize + x as usize];
        if depth < *d {
            *d = depth;
        }
        false
    }

    fn write(&mut self, _x: u32, _y: u32, _color: Rgb8) {}
}

/// The depth buffer of a frame (window depth, 1.0 where nothing is drawn),
/// row by row, as the scanline rasterizer leaves it.
///
/// # Errors
/// As [`crate::render`].
pub fn depth_buffer(scene: &Scene, options: &RenderOptions) -> Result<Vec<f32>, RenderError> {
    let options = RenderOptions {
        rasterizer: Rasterizer::Scanline,
        shading: Shading::Flat,
        palette: None,
        ..*options
    };
    validate(scene, &options)?;
    let mut target = DepthTarget {
        width: options.width,
        depth: vec![1.0; options.width as usize * options.height as usize],
    };
    let mut geometry = Geometry::default();
    let mut frame = geometry.frame(scene, &options);
    let lighting = lighting(scene, &options);
    draw(&frame.project(), scene, &options, &lighting, &mut target);
    Ok(target.depth)
}
