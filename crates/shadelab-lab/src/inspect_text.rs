//! The pixel inspector's account as text, in the reader's language: for
//! each method the polygon, the scanline, P and Q with their parameters, the
//! stepped values beside their closed-form formulas, the reflection model's
//! terms and the colour written. The numbers come from [`inspect()`](crate::inspect()).

use std::fmt::Write as _;

use glam::Vec3;
use shadelab_core::{
    FragmentRecord, Interpolation, LightingTerms, Polygons, Rgb, Rgb8, Shading, Specular,
};

use crate::inspect::{Inspection, MethodView, SpanView};
use crate::texts::Texts;

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
