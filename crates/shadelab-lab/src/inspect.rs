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
//! [`Lighting::explain`], whose total is bit for bit the renderer's.

use std::fmt::Write as _;

use glam::Vec3;
use shadelab_core::{
    face_normals, probe, to_window, ClipVertex, FragmentRecord, Interpolation, LightingTerms,
    PaletteShade, Polygons, ProbeRequest, RenderError, RenderOptions, Rgb, Rgb8, Scene, Shading,
    SpanRecord, Specular, Terms,
};

use crate::lighting_of;
use crate::texts::Texts;

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
        let normal = scene.normals.normals[scene.normals.corner[c] as usize] * sign;
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

fn n(v: f64) -> String {
    let s = format!("{v:.4}");
    if s == "-0.0000" {
        "0.0000".into()
    } else {
        s
    }
}

fn vec3(v: Vec3) -> String {
    format!("({}, {}, {})", n(v.x.into()), n(v.y.into()), n(v.z.into()))
}

fn rgb(c: Rgb) -> String {
    format!("({}, {}, {})", n(c.r.into()), n(c.g.into()), n(c.b.into()))
}

fn rgb8(c: Rgb8) -> String {
    format!("({}, {}, {})", c.0[0], c.0[1], c.0[2])
}

fn triple(v: &[f64]) -> String {
    let parts: Vec<String> = v.iter().map(|&x| n(x)).collect();
    format!("({})", parts.join(", "))
}

fn letter(k: usize) -> String {
    char::from(b'A' + (k % 26) as u8).to_string()
}

/// The inspection as text in `texts`' language: per method, the polygon,
/// the scanline, P, Q, the parameters, the values and the colour.
///
/// It is [`inspection_header`] followed, for each method, by an empty line
/// and [`method_inspection_text`].
pub fn inspection_text(inspection: &Inspection, texts: &Texts) -> String {
    let mut out = inspection_header(inspection, texts);
    for m in &inspection.methods {
        out.push('\n');
        method_text(&mut out, m, inspection, texts);
    }
    out
}

/// The lines that hold for every method: the pixel, the interpolation, and
/// whether the frame was drawn by the tiled rasterizer or in fixed point.
pub fn inspection_header(inspection: &Inspection, texts: &Texts) -> String {
    let mut out = String::new();
    let (x, y) = (inspection.x.to_string(), inspection.y.to_string());
    let _ = writeln!(
        out,
        "{}",
        texts.fill("inspect.title", &[("x", &x), ("y", &y)])
    );
    let o = &inspection.options;
    let interp_id = match o.interpolation {
        Interpolation::Perspective => "inspect.interpolation_perspective",
        Interpolation::Screen => "inspect.interpolation_screen",
    };
    let _ = writeln!(out, "{}", texts.get(interp_id));
    if o.rasterizer == shadelab_core::Rasterizer::Tiled {
        let _ = writeln!(out, "{}", texts.get("inspect.reference"));
    }
    if let Some(bits) = o.fixed_point_bits {
        let _ = writeln!(
            out,
            "{}",
            texts.fill("inspect.fixed_point", &[("bits", &bits.to_string())])
        );
    }
    out
}

/// One method's account as text, its first line `== ` and the method's name.
pub fn method_inspection_text(
    method: &MethodView,
    inspection: &Inspection,
    texts: &Texts,
) -> String {
    let mut out = String::new();
    method_text(&mut out, method, inspection, texts);
    out
}

fn method_text(out: &mut String, m: &MethodView, insp: &Inspection, t: &Texts) {
    let _ = writeln!(out, "== {}", t.get(&format!("method.{}", m.shading.name())));
    let Some(f) = &m.fragment else {
        let _ = writeln!(
            out,
            "   {}",
            t.fill("inspect.background", &[("color", &rgb8(m.color))])
        );
        return;
    };
    let vertices: Vec<String> = m.polygon.iter().map(u32::to_string).collect();
    let _ = writeln!(
        out,
        "   {}",
        t.fill(
            "inspect.polygon",
            &[
                ("face", &f.face.to_string()),
                ("count", &m.polygon.len().to_string()),
                ("vertices", &vertices.join(", ")),
            ]
        )
    );
    if f.back {
        let _ = writeln!(out, "   {}", t.get("inspect.back"));
    }
    let walked_names: Vec<String> = (0..m.walked.len()).map(letter).collect();
    match m.fan_triangle {
        Some(k) => {
            let _ = writeln!(
                out,
                "   {}",
                t.fill(
                    "inspect.fan",
                    &[("k", &k.to_string()), ("vertices", &walked_names.join(""))]
                )
            );
        }
        None if insp.options.polygons == Polygons::Whole || m.polygon.len() == 3 => {
            let _ = writeln!(out, "   {}", t.get("inspect.whole"));
        }
        None => {}
    }
    if m.clipped {
        let _ = writeln!(out, "   {}", t.get("inspect.clipped"));
    }
    // The walked vertices.
    let _ = writeln!(out, "   {}", t.get("inspect.vertices"));
    for (k, v) in m.walked.iter().enumerate() {
        let mut line = format!(
            "     {} = ({}, {})",
            letter(k),
            n(v.window.0),
            n(v.window.1)
        );
        match &v.corner {
            Some(c) => {
                let _ = write!(
                    line,
                    "  {}",
                    t.fill(
                        "inspect.vertex",
                        &[
                            ("vertex", &c.vertex.to_string()),
                            ("normal", &vec3(c.normal))
                        ]
                    )
                );
            }
            None => line.push_str("  *"),
        }
        if m.shading == Shading::Gouraud {
            let i: Vec<f64> = v.attrs.iter().map(|&a| f64::from(a)).collect();
            let _ = write!(line, "  I = {}", triple(&i));
        }
        let _ = writeln!(out, "{line}");
        if let Some(terms) = v.corner.as_ref().and_then(|c| c.lighting.as_ref()) {
            lighting_lines(out, terms, insp.options.specular, "       ", t);
            if terms.total.clamped() != terms.total {
                let _ = writeln!(
                    out,
                    "       {}",
                    t.fill("inspect.clamped", &[("value", &rgb(terms.total.clamped()))])
                );
            }
        }
    }
    if let Some(span) = &m.span {
        span_text(out, m, span, f, t);
    }
    match m.shading {
        Shading::Flat => {
            let _ = writeln!(
                out,
                "   {}",
                t.fill(
                    "inspect.flat_eval",
                    &[
                        ("point", &vec3(m.point.unwrap_or_default())),
                        ("normal", &vec3(m.normal.unwrap_or_default()))
                    ]
                )
            );
            if let Some(terms) = &m.lighting {
                lighting_lines(out, terms, insp.options.specular, "     ", t);
            }
        }
        Shading::Gouraud => {
            let _ = writeln!(out, "   {}", t.get("inspect.gouraud_eval"));
        }
        Shading::Phong => {
            let _ = writeln!(
                out,
                "   {}",
                t.fill(
                    "inspect.phong_eval",
                    &[
                        ("raw", &vec3(m.raw_normal.unwrap_or_default())),
                        ("normal", &vec3(m.normal.unwrap_or_default())),
                        ("point", &vec3(m.point.unwrap_or_default()))
                    ]
                )
            );
            if let Some(terms) = &m.lighting {
                lighting_lines(out, terms, insp.options.specular, "     ", t);
            }
        }
    }
    if let Some(p) = &m.palette {
        let _ = writeln!(
            out,
            "   {}",
            t.fill(
                "inspect.palette",
                &[
                    ("intensity", &n(p.intensity.into())),
                    (
                        "shades",
                        &insp.options.palette.map_or(0, |p| p.shades).to_string()
                    ),
                    ("shade", &p.shade.to_string()),
                    (
                        "offset",
                        &insp.options.palette.map_or(0, |p| p.offset).to_string()
                    ),
                    ("index", &p.index.to_string()),
                ]
            )
        );
    }
    let _ = match (&m.palette, insp.options.palette) {
        (Some(shade), Some(palette)) => writeln!(
            out,
            "   {}",
            t.fill(
                "inspect.final_palette",
                &[
                    ("index", &shade.index.to_string()),
                    ("shade", &shade.shade.to_string()),
                    ("top", &(palette.shades - 1).to_string()),
                    ("color", &rgb8(f.color)),
                ]
            )
        ),
        _ => writeln!(
            out,
            "   {}",
            t.fill(
                "inspect.final",
                &[("lit", &rgb(f.lit)), ("color", &rgb8(f.color))]
            )
        ),
    };
}

fn span_text(out: &mut String, m: &MethodView, span: &SpanView, f: &FragmentRecord, t: &Texts) {
    let yc = n(f64::from(span.row) + 0.5);
    let _ = writeln!(
        out,
        "   {}",
        t.fill(
            "inspect.scanline",
            &[("row", &span.row.to_string()), ("yc", &yc)]
        )
    );
    let name = |k: usize| letter(k);
    for (id, e) in [("inspect.edge_p", &span.p), ("inspect.edge_q", &span.q)] {
        let _ = writeln!(
            out,
            "   {}",
            t.fill(
                id,
                &[
                    ("x", &n(e.x)),
                    ("yc", &yc),
                    ("a", &name(e.from)),
                    ("b", &name(e.to)),
                    ("s", &n(e.s)),
                ]
            )
        );
    }
    let ox = n(f64::from(f.x) + 0.5);
    let _ = writeln!(
        out,
        "   {}",
        t.fill(
            "inspect.span",
            &[
                ("ox", &ox),
                ("yc", &yc),
                ("px", &n(span.p.x)),
                ("qx", &n(span.q.x)),
                ("u", &n(span.u)),
            ]
        )
    );
    let (label, range): (&str, std::ops::Range<usize>) = match m.shading {
        Shading::Flat => return,
        Shading::Gouraud => ("I", 0..3),
        Shading::Phong => ("N", 0..3),
    };
    let perspective = span.interpolation == Interpolation::Perspective;
    let mut show = |label: &str, range: std::ops::Range<usize>| {
        for (point, e) in [("P", &span.p), ("Q", &span.q)] {
            let (a, b) = (name(e.from), name(e.to));
            let formula = if perspective {
                format!("{label}_{point} = ((1 − s)·{label}_{a}/w_{a} + s·{label}_{b}/w_{b}) / ((1 − s)/w_{a} + s/w_{b})")
            } else {
                format!("{label}_{point} = (1 − s)·{label}_{a} + s·{label}_{b}")
            };
            let _ = writeln!(
                out,
                "   {formula} = {}   [{} {}]",
                triple(&e.formula[range.clone()]),
                t.get("inspect.stepped"),
                triple(&e.stepped[range.clone()])
            );
        }
        let formula = if perspective {
            format!("{label}_O = ((1 − u)·{label}_P/w_P + u·{label}_Q/w_Q) / ((1 − u)/w_P + u/w_Q)")
        } else {
            format!("{label}_O = (1 − u)·{label}_P + u·{label}_Q")
        };
        let actual: Vec<f64> = f.attrs[range.clone()]
            .iter()
            .map(|&a| f64::from(a))
            .collect();
        let _ = writeln!(
            out,
            "   {formula} = {}   [{} {}]",
            triple(&span.formula[range.clone()]),
            t.get("inspect.stepped"),
            triple(&actual)
        );
    };
    show(label, range);
    if m.shading == Shading::Phong {
        show("X", 3..6);
    }
}

fn lighting_lines(
    out: &mut String,
    terms: &LightingTerms,
    specular: Specular,
    indent: &str,
    t: &Texts,
) {
    let _ = writeln!(
        out,
        "{indent}{}",
        t.fill("inspect.ambient", &[("value", &rgb(terms.ambient))])
    );
    for (k, l) in terms.lights.iter().enumerate() {
        let _ = writeln!(
            out,
            "{indent}{}",
            t.fill(
                "inspect.light",
                &[
                    ("k", &(k + 1).to_string()),
                    ("l", &vec3(l.l)),
                    ("ndotl", &n(l.n_dot_l.into())),
                    ("diffuse", &rgb(l.diffuse)),
                ]
            )
        );
        if let (Some(c), Some(r)) = (l.cosine, l.reflected) {
            let _ = writeln!(
                out,
                "{indent}  {}",
                t.fill(
                    match specular {
                        Specular::Phong => "inspect.specular_phong",
                        Specular::BlinnPhong => "inspect.specular_blinn",
                    },
                    &[
                        ("r", &vec3(r)),
                        ("cos", &n(c.into())),
                        ("specular", &rgb(l.specular)),
                    ]
                )
            );
        }
    }
    let _ = writeln!(
        out,
        "{indent}{}",
        t.fill("inspect.total", &[("value", &rgb(terms.total))])
    );
}
