//! The pixel inspector: for one pixel and each method, what the scanline
//! rasterizer did to colour it, with the textbook's formulas filled in.
//!
//! Everything shown comes from a probe of the real frame
//! ([`shadelab_core::probe`]): the polygon that won the depth test, the
//! scanline through the pixel, the points P and Q where it crosses the
//! polygon's edges with the edge parameters, the values stepped along the
//! edges and the span, the attributes the method received at the pixel
//! centre O, its light and the colour written. What the inspector adds is
//! the closed-form formula next to each stepped value (`I_P = (1 − s)·I_1 +
//! s·I_2`, `I_O = (1 − u)·I_P + u·I_Q`, or their perspective-correct forms)
//! and the reflection model's terms where it was evaluated, computed by
//! [`Lighting::explain`](shadelab_core::Lighting::explain), whose total is
//! bit for bit the renderer's.

use glam::Vec3;
use shadelab_core::{
    face_normals, probe, to_window, ClipVertex, FragmentRecord, Interpolation, LightingTerms,
    PaletteShade, Polygons, ProbeRequest, RenderError, RenderOptions, Rgb8, Scene, Shading,
    SpanRecord, Terms,
};

use crate::lighting_of;

/// A vertex of the polygon the scanline walk went round.
#[derive(Debug, Clone, PartialEq)]
pub struct WalkedVertex {
    /// Window position, pixels.
    pub window: (f64, f64),
    /// 1/w there.
    pub inv_w: f32,
    /// The method's attributes there (Gouraud: the vertex colour; Phong:
    /// normal and world position).
    pub attrs: Vec<f32>,
    /// The mesh corner it is, unless clipping made it.
    pub corner: Option<CornerView>,
}

/// A mesh corner of the polygon, with what the method computed there.
#[derive(Debug, Clone, PartialEq)]
pub struct CornerView {
    /// Index into the mesh's corners.
    pub corner: usize,
    /// The mesh vertex.
    pub vertex: u32,
    /// Its world position.
    pub position: Vec3,
    /// Its vertex normal (reversed for a back face).
    pub normal: Vec3,
    /// Gouraud: the reflection model at the vertex.
    pub lighting: Option<LightingTerms>,
}

/// Where the scanline crosses one edge.
#[derive(Debug, Clone, PartialEq)]
pub struct EdgeView {
    /// Index into [`MethodView::walked`] of the edge's upper end.
    pub from: usize,
    /// Of its lower end.
    pub to: usize,
    /// The crossing's x, pixels.
    pub x: f64,
    /// The edge parameter, 0 at `from`, 1 at `to`.
    pub s: f64,
    /// The attributes there by the closed-form formula.
    pub formula: Vec<f64>,
    /// The attributes as the walk stepped them down the edge.
    pub stepped: Vec<f64>,
}

/// The scanline through the pixel.
#[derive(Debug, Clone, PartialEq)]
pub struct SpanView {
    /// The row.
    pub row: u32,
    /// P, on the left edge.
    pub p: EdgeView,
    /// Q, on the right edge.
    pub q: EdgeView,
    /// `u = |PO| / |PQ|`.
    pub u: f64,
    /// The attributes at O by the closed-form formula from P and Q.
    pub formula: Vec<f64>,
    /// How attributes were interpolated.
    pub interpolation: Interpolation,
    /// Fixed-point fraction bits, if stepping was in fixed point.
    pub fraction_bits: Option<u32>,
    /// Pixels filled on this span.
    pub pixels: std::ops::Range<u32>,
}

/// One method's account of the pixel.
#[derive(Debug, Clone, PartialEq)]
pub struct MethodView {
    /// The method.
    pub shading: Shading,
    /// The winning fragment, or `None` for background.
    pub fragment: Option<FragmentRecord>,
    /// The mesh polygon's vertex indices.
    pub polygon: Vec<u32>,
    /// The convex polygon walked (the polygon, or a triangle of its fan).
    pub walked: Vec<WalkedVertex>,
    /// Which fan triangle, counting from 1, when drawn as a fan.
    pub fan_triangle: Option<usize>,
    /// Whether clipping changed the polygon.
    pub clipped: bool,
    /// The scanline walk at this pixel.
    pub span: Option<SpanView>,
    /// The reflection model where it was evaluated for this pixel: flat at
    /// the centroid, Phong at O (Gouraud's are per vertex, in `walked`).
    pub lighting: Option<LightingTerms>,
    /// Flat: the centroid; Phong: the interpolated position at O.
    pub point: Option<Vec3>,
    /// Flat: the face normal; Phong: the interpolated normal, normalised.
    pub normal: Option<Vec3>,
    /// Phong: the interpolated normal before normalising.
    pub raw_normal: Option<Vec3>,
    /// The palette's shade, in palette mode.
    pub palette: Option<PaletteShade>,
    /// The colour written (the background where nothing was drawn).
    pub color: Rgb8,
}

/// The inspector's account of one pixel.
#[derive(Debug, Clone, PartialEq)]
pub struct Inspection {
    /// Column.
    pub x: u32,
    /// Row.
    pub y: u32,
    /// The options (their shading is replaced per method).
    pub options: RenderOptions,
    /// Flat, Gouraud, Phong, or the methods asked for.
    pub methods: Vec<MethodView>,
}

/// Inspects pixel (`x`, `y`) of `scene` for each method in `methods`.
///
/// # Errors
/// As [`shadelab_core::render`].
pub fn inspect(
    scene: &Scene,
    options: &RenderOptions,
    x: u32,
    y: u32,
    methods: &[Shading],
) -> Result<Inspection, RenderError> {
    let views = methods
        .iter()
        .map(|&shading| {
            inspect_method(
                scene,
                &RenderOptions {
                    shading,
                    ..*options
                },
                x,
                y,
            )
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Inspection {
        x,
        y,
        options: *options,
        methods: views,
    })
}

fn inspect_method(
    scene: &Scene,
    options: &RenderOptions,
    x: u32,
    y: u32,
) -> Result<MethodView, RenderError> {
    let record = probe(
        scene,
        options,
        ProbeRequest {
            pixels: &[(x, y)],
            trace: true,
        },
    )?
    .pop()
    .flatten();
    let mut view = MethodView {
        shading: options.shading,
        fragment: None,
        polygon: Vec::new(),
        walked: Vec::new(),
        fan_triangle: None,
        clipped: false,
        span: None,
        lighting: None,
        point: None,
        normal: None,
        raw_normal: None,
        palette: None,
        color: options.background,
    };
    let Some(record) = record else {
        return Ok(view);
    };
    let lighting = lighting_of(scene, options);
    let mesh = &scene.mesh;
    let face = record.face;
    view.polygon = mesh.polygon(face).to_vec();
    view.color = record.color;
    let sign = if record.back { -1.0 } else { 1.0 };
    let gouraud_terms = if options.gouraud_specular {
        Terms::Full
    } else {
        Terms::AmbientDiffuse
    };

    // Where each mesh corner lands in the window, to name the walked vertices.
    let aspect = options.width as f32 / options.height as f32;
    let view_projection = scene.camera.projection(aspect) * scene.camera.view();
    let corners: Vec<(usize, (i64, i64))> = mesh
        .corner_range(face)
        .map(|c| {
            let p = mesh.positions()[mesh.corners()[c] as usize];
            let w = to_window(
                &ClipVertex::<0> {
                    clip: view_projection * p.extend(1.0),
                    attrs: [],
                },
                options.width,
                options.height,
            );
            (c, (w.x, w.y))
        })
        .collect();
    let corner_view = |c: usize| {
        let vertex = mesh.corners()[c];
        let position = mesh.positions()[vertex as usize];
        let normal = scene.normals.normals[scene.normals.corner()[c] as usize] * sign;
        CornerView {
            corner: c,
            vertex,
            position,
            normal,
            lighting: (options.shading == Shading::Gouraud)
                .then(|| lighting.explain(position, normal, gouraud_terms)),
        }
    };

    if let Some(span) = &record.span {
        let snapped = |v: f64| (v * 256.0).round() as i64;
        view.walked = span
            .polygon
            .iter()
            .map(|v| WalkedVertex {
                window: (v.x, v.y),
                inv_w: v.inv_w,
                attrs: v.attrs.clone(),
                corner: corners
                    .iter()
                    .find(|(_, w)| *w == (snapped(v.x), snapped(v.y)))
                    .map(|&(c, _)| corner_view(c)),
            })
            .collect();
        view.clipped = view.walked.iter().any(|v| v.corner.is_none());
        if options.polygons == Polygons::Fans && view.polygon.len() > 3 && span.polygon.len() == 3 {
            view.fan_triangle = fan_index(&view.walked, &corners);
        }
        view.span = Some(span_view(span, record.x));
    }

    match options.shading {
        Shading::Flat => {
            let centroid = mesh
                .corner_range(face)
                .map(|c| mesh.positions()[mesh.corners()[c] as usize])
                .sum::<Vec3>()
                / mesh.corner_range(face).len() as f32;
            let normal = face_normals(mesh)[face].unwrap_or(Vec3::Z) * sign;
            view.point = Some(centroid);
            view.normal = Some(normal);
            view.lighting = Some(lighting.explain(centroid, normal, Terms::Full));
        }
        Shading::Gouraud => {}
        Shading::Phong => {
            let a = &record.attrs;
            let raw = Vec3::new(a[0], a[1], a[2]);
            let n = (raw * sign).normalize_or_zero();
            let p = Vec3::new(a[3], a[4], a[5]);
            view.raw_normal = Some(raw);
            view.normal = Some(n);
            view.point = Some(p);
            view.lighting = Some(lighting.explain(p, n, Terms::Full));
        }
    }
    if let Some(palette) = options.palette {
        view.palette = Some(palette.shade(record.lit, scene.material.kd));
    }
    view.fragment = Some(record);
    Ok(view)
}

/// Which triangle of the fan (from 1) the walked triangle is.
fn fan_index(walked: &[WalkedVertex], corners: &[(usize, (i64, i64))]) -> Option<usize> {
    let first = walked.first()?.corner.as_ref()?.corner;
    let second = walked.get(1)?.corner.as_ref()?.corner;
    let apex = corners.iter().position(|&(c, _)| c == first)?;
    let next = corners.iter().position(|&(c, _)| c == second)?;
    Some((next + corners.len() - apex) % corners.len())
}

fn span_view(span: &SpanRecord, x: u32) -> SpanView {
    let interpolation = span.interpolation;
    let edge = |e: &shadelab_core::EdgeRecord| {
        let (a, b) = (&span.polygon[e.top], &span.polygon[e.bottom]);
        let s = e.t;
        let formula = lerp_attributes(
            &a.attrs,
            f64::from(a.inv_w),
            &b.attrs,
            f64::from(b.inv_w),
            s,
            interpolation,
        );
        EdgeView {
            from: e.top,
            to: e.bottom,
            x: e.x,
            s,
            formula,
            stepped: e.value.attributes(interpolation),
        }
    };
    let (p, q) = (edge(&span.left), edge(&span.right));
    let u = span.u(x);
    // The closed form at O from the values at P and Q as the walk had them.
    let pv: Vec<f32> = span
        .left
        .value
        .attributes(interpolation)
        .iter()
        .map(|&v| v as f32)
        .collect();
    let qv: Vec<f32> = span
        .right
        .value
        .attributes(interpolation)
        .iter()
        .map(|&v| v as f32)
        .collect();
    let formula = lerp_attributes(
        &pv,
        span.left.value.inv_w,
        &qv,
        span.right.value.inv_w,
        u,
        interpolation,
    );
    SpanView {
        row: span.row,
        p,
        q,
        u,
        formula,
        interpolation,
        fraction_bits: span.fraction_bits,
        pixels: span.pixels.clone(),
    }
}

/// `(1 − s)·a + s·b`, or in perspective mode
/// `((1 − s)·a·wa + s·b·wb) / ((1 − s)·wa + s·wb)` with `wa`, `wb` the ends' 1/w.
pub fn lerp_attributes(
    a: &[f32],
    a_inv_w: f64,
    b: &[f32],
    b_inv_w: f64,
    s: f64,
    interpolation: Interpolation,
) -> Vec<f64> {
    a.iter()
        .zip(b)
        .map(|(&a, &b)| {
            let (a, b) = (f64::from(a), f64::from(b));
            match interpolation {
                Interpolation::Screen => (1.0 - s) * a + s * b,
                Interpolation::Perspective => {
                    ((1.0 - s) * a * a_inv_w + s * b * b_inv_w)
                        / ((1.0 - s) * a_inv_w + s * b_inv_w)
                }
            }
        })
        .collect()
}

// ------------------------------------------------------------------ text
