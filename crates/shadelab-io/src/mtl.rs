//! Wavefront material libraries (`.mtl`): the ambient and diffuse colours
//! (`Ka`, `Kd`) of each named material, nothing else.
//!
//! An OBJ file names its libraries with `mtllib` and picks a material with
//! `usemtl`; shadelab's one material per scene may take its `ka` and `kd`
//! from there (see [`crate::load_mesh_file`]). Materials only colour a model,
//! so nothing in a library can make loading fail: a missing or unreadable
//! library, a statement that does not parse, a colour given in a form other
//! than RGB (`Kd spectral …`, `Kd xyz …`) are passed over in silence, and the
//! scene's own colours apply. Channels are clamped to 0–1.
//!
//! Written by hand rather than with `tobj::load_mtl_buf`: that parser rejects
//! the legal one-value form `Kd 0.5` (grey) and, in `tobj` 4.0.5, panics on
//! it; the two statements read here take a few lines.

use std::collections::HashSet;

use shadelab_core::Rgb;

use crate::input::lines_any;

/// A material as a library defines it: the colours it gives.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct MtlColors {
    pub name: String,
    pub ka: Option<Rgb>,
    pub kd: Option<Rgb>,
}

/// The materials of a library, in file order; of two materials with the same
/// name the first is kept. Linear in the text's length: names already seen
/// are kept in a hash set, so 300,000 materials take no longer than their
/// bytes take to read.
pub(crate) fn parse_mtl(text: &str) -> Vec<MtlColors> {
    let mut materials: Vec<MtlColors> = Vec::new();
    let mut seen: HashSet<String> = HashSet::new();
    let mut current: Option<MtlColors> = None;
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut finish = |material: Option<MtlColors>, materials: &mut Vec<MtlColors>| {
        if let Some(m) = material {
            if seen.insert(m.name.clone()) {
                materials.push(m);
            }
        }
    };
    for line in lines_any(text) {
        let statement = line.split('#').next().unwrap_or("").trim();
        let Some((keyword, rest)) = split_keyword(statement) else {
            continue;
        };
        match keyword {
            "newmtl" => {
                finish(current.take(), &mut materials);
                if !rest.is_empty() {
                    current = Some(MtlColors {
                        name: rest.to_owned(),
                        ka: None,
                        kd: None,
                    });
                }
            }
            "Ka" | "Kd" => {
                let (Some(material), Some(color)) = (current.as_mut(), rgb(rest)) else {
                    continue;
                };
                let slot = if keyword == "Ka" {
                    &mut material.ka
                } else {
                    &mut material.kd
                };
                *slot = Some(color);
            }
            _ => {}
        }
    }
    finish(current, &mut materials);
    materials
}

/// The first word of a statement and the rest, trimmed.
pub(crate) fn split_keyword(statement: &str) -> Option<(&str, &str)> {
    let statement = statement.trim_start();
    if statement.is_empty() {
        return None;
    }
    Some(match statement.split_once(char::is_whitespace) {
        Some((keyword, rest)) => (keyword, rest.trim()),
        None => (statement, ""),
    })
}

/// `r`, or `r g b`, each a finite number, clamped to 0–1.
fn rgb(args: &str) -> Option<Rgb> {
    let values = args
        .split_whitespace()
        .map(|a| a.parse::<f32>().ok().filter(|v| v.is_finite()))
        .collect::<Option<Vec<f32>>>()?;
    let c = match values[..] {
        [v] => Rgb::splat(v),
        [r, g, b] => Rgb::new(r, g, b),
        _ => return None,
    };
    Some(c.clamped())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colours_forms_and_what_is_passed_over() {
        let text = "\
# a library
newmtl red
Ka 0.1 0 0
Kd 1 0.2 0   # trailing comment
Ks 1 1 1
newmtl grey
Kd 0.5
newmtl odd
Kd spectral file.rfl
Ka xyz 0.1 0.2 0.3
Kd 2 -1 0.5
newmtl  name with spaces \t
Kd 0 0 1 1
Ka nan 0 0
newmtl red
Kd 0 1 0
Ka 0.3
newmtl
Kd 1 1 1
";
        let m = parse_mtl(text);
        let names: Vec<&str> = m.iter().map(|m| m.name.as_str()).collect();
        assert_eq!(names, ["red", "grey", "odd", "name with spaces"]);
        assert_eq!(m[0].ka, Some(Rgb::new(0.1, 0.0, 0.0)));
        assert_eq!(m[0].kd, Some(Rgb::new(1.0, 0.2, 0.0)));
        assert_eq!(m[1].ka, None);
        assert_eq!(m[1].kd, Some(Rgb::splat(0.5)));
        // The spectral and CIE forms are not RGB; the last Kd is clamped.
        assert_eq!(m[2].ka, None);
        assert_eq!(m[2].kd, Some(Rgb::new(1.0, 0.0, 0.5)));
        // Four values and a NaN are passed over.
        assert_eq!(m[3].kd, None);
        assert_eq!(m[3].ka, None);
    }

    #[test]
    fn nothing_usable_gives_nothing() {
        assert!(parse_mtl("").is_empty());
        assert!(parse_mtl("Kd 1 0 0\nKa 1 1 1\n").is_empty());
        assert!(parse_mtl("garbage ☃\n\n\t\n").is_empty());
        // A byte-order mark is not part of the first keyword.
        assert_eq!(
            parse_mtl("\u{feff}newmtl a\nKd 1 1 1\n")[0].kd,
            Some(Rgb::WHITE)
        );
    }
}
