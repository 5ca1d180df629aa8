//! Every user-facing number, colour, vector, switch and name of a scene,
//! declared once: its scene-file key, kind, default, range, unit, help,
//! label and flag.
//!
//! The declaration (`table.rs`, through the `declare!` macro of
//! `declare.rs`) makes three things: the table of parameters ([`all`]),
//! the schema's lists of choices, and the scene file's sections
//! ([`ModelSection`] … [`RenderSection`], the serde structs `shadelab-io`
//! reads a file into, one field per declared key). From the table come the
//! scene file's checks (ranges, defaults and messages), the command line's
//! override flags and the page's controls, from [`schema_json`] (served as
//! `params.json`). Adding a parameter is one field in the declaration, then
//! its use where it acts. Defaults that belong to a type of the core
//! ([`crate::Material::default`], [`crate::RenderOptions::default`]) are
//! read from it, so they stay declared where they act.
//!
//! The enumerated choices' values are declared with their types
//! ([`crate::choice`]); the declaration says which key chooses which.

mod declare;
mod table;

use std::sync::OnceLock;

use serde_json::{json, Value as Json};

use crate::choice::Choice;
use crate::color::Rgb8;
use crate::text::format_number;

pub use table::{
    AmbientSection, CameraSection, LightSection, MaterialSection, ModelSection, RenderSection,
};

/// Smallest `render.zoom`.
pub const MIN_ZOOM: f32 = 0.1;
/// Largest `render.zoom`.
pub const MAX_ZOOM: f32 = 100.0;

/// What a parameter's value is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// A finite number within `min..=max`.
    Number,
    /// A whole number within `min..=max`.
    Integer,
    /// Three whole numbers (red, green, blue), each within `min..=max`.
    Rgb,
    /// Three finite numbers, each within `min..=max`.
    Vec3,
    /// True or false.
    Bool,
    /// A non-empty text.
    Text,
}

impl Kind {
    /// The kind's name in the schema.
    pub fn name(self) -> &'static str {
        match self {
            Kind::Number => "number",
            Kind::Integer => "integer",
            Kind::Rgb => "rgb",
            Kind::Vec3 => "vec3",
            Kind::Bool => "bool",
            Kind::Text => "text",
        }
    }
}

/// A parameter's value: a default or a typical value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Value {
    /// A number (of kind number or integer).
    Number(f64),
    /// Three numbers (of kind rgb or vec3).
    Three([f64; 3]),
    /// A switch.
    Bool(bool),
    /// A text.
    Text(&'static str),
}

/// One user-facing parameter of a scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Param {
    /// The scene-file key, `section.key`; a light's are `lights.key` (each
    /// `[[lights]]` table's `key`).
    pub key: &'static str,
    /// What its value is.
    pub kind: Kind,
    /// The value a scene without the key gets; `None` when leaving it out
    /// means something else ([`Param::absent`]).
    pub default: Option<Value>,
    /// What leaving the key out means when there is no default ("the
    /// model's own", "floating point"); empty otherwise.
    pub absent: &'static str,
    /// The value a control that turns the parameter on starts from, when
    /// it has no default.
    pub typical: Option<Value>,
    /// The smallest value (of each component); 0 for switches and texts.
    pub min: f64,
    /// The largest value (of each component); 0 for switches and texts.
    pub max: f64,
    /// The unit of the value ("degrees", "pixels"), or empty.
    pub unit: &'static str,
    /// One sentence saying what it does.
    pub help: &'static str,
    /// The key that must be set for this one to be (`render.palette_offset`
    /// needs `render.palette_shades`), or empty.
    pub needs: &'static str,
    /// A short name for a control or a column ("Fall-off"), in English;
    /// the page shows its translation when it has one.
    pub label: &'static str,
    /// The names of a colour's or a vector's three numbers ([`RGB`],
    /// [`XYZ`], [`ATTENUATION_TERMS`]), for the controls of each; empty
    /// for a single value.
    pub parts: &'static [&'static str],
    /// The command line's flag that sets it (without `--`), or empty when
    /// it has none of its own (`render.width` is `--size`'s).
    pub flag: &'static str,
    /// Which bounds are themselves refused (a field of view lies strictly
    /// between 0 and 180 degrees, a near plane is more than 0).
    pub open: Open,
}

/// Which of a parameter's bounds are refused.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Open {
    /// `min..=max`.
    #[default]
    Neither,
    /// More than `min`, at most `max`.
    Min,
    /// Strictly between `min` and `max`.
    Both,
}

impl Open {
    /// Whether `v` is within `lo` and `hi`, these bounds refused as said.
    pub fn contains<T: PartialOrd>(self, lo: T, hi: T, v: T) -> bool {
        match self {
            Open::Neither => lo <= v && v <= hi,
            Open::Min => lo < v && v <= hi,
            Open::Both => lo < v && v < hi,
        }
    }

    /// Its name in the schema.
    pub fn name(self) -> &'static str {
        match self {
            Open::Neither => "neither",
            Open::Min => "min",
            Open::Both => "both",
        }
    }
}

/// The parts of a colour.
pub const RGB: &[&str] = &["red", "green", "blue"];
/// The parts of a position or a direction.
pub const XYZ: &[&str] = &["x", "y", "z"];
/// The parts of a light's attenuation, as `constant + linear·d + quadratic·d²`.
pub const ATTENUATION_TERMS: &[&str] = &["constant", "linear", "quadratic"];

impl Param {
    /// A parameter with nothing set, which each declaration completes
    /// (`Param { key, kind, help, …, ..Param::BLANK }`).
    pub(crate) const BLANK: Param = Param {
        key: "",
        kind: Kind::Number,
        default: None,
        absent: "",
        typical: None,
        min: 0.0,
        max: 0.0,
        unit: "",
        help: "",
        needs: "",
        label: "",
        parts: &[],
        flag: "",
        open: Open::Neither,
    };

    /// `min..=max` with the unit, as messages and help show it
    /// ("0..=180 degrees", "each channel 0..=255", "within ±1e30").
    pub fn range_text(&self) -> String {
        let unit = if self.unit.is_empty() {
            String::new()
        } else {
            format!(" {}", self.unit)
        };
        let (lo, hi) = (num(self.min), num(self.max));
        match self.open {
            Open::Both => return format!("strictly between {lo} and {hi}{unit}"),
            Open::Min => return format!("more than {lo} and at most {hi}{unit}"),
            Open::Neither => {}
        }
        match self.kind {
            Kind::Vec3 if self.min == -self.max => format!("within ±{hi}{unit}"),
            Kind::Vec3 => format!("each {lo}..={hi}{unit}"),
            Kind::Rgb => format!("each channel {lo}..={hi}"),
            Kind::Bool | Kind::Text => String::new(),
            Kind::Number | Kind::Integer => format!("{lo}..={hi}{unit}"),
        }
    }

    /// The help with the range and the default, for a flag's or a control's text.
    pub fn long_help(&self) -> String {
        let range = self.range_text();
        let mut text = self.help.trim_end_matches('.').to_owned();
        if !range.is_empty() {
            text.push_str(&format!("; {range}"));
        }
        match (&self.default, self.absent) {
            (Some(v), _) => text.push_str(&format!("; default {}", self.show(v))),
            (None, absent) if !absent.is_empty() => {
                text.push_str(&format!("; unset: {absent}"));
            }
            _ => {}
        }
        text
    }

    /// `v` (a number of this parameter) if it is within range, or what is
    /// wrong, without the key ("must be 0..=180 degrees, got 200"). A
    /// number the scene file holds in single precision is compared with the
    /// bounds in single precision.
    ///
    /// # Errors
    /// The problem, for the caller to prefix with the key it read.
    pub fn check(&self, v: f32) -> Result<f32, String> {
        let (lo, hi) = (self.min as f32, self.max as f32);
        if v.is_finite() && self.open.contains(lo, hi, v) {
            Ok(v)
        } else {
            Err(format!(
                "must be {}, got {}",
                self.range_text(),
                format_number(v)
            ))
        }
    }

    /// A whole number of this parameter if it is within range, or what is wrong.
    ///
    /// # Errors
    /// As [`Param::check`].
    pub fn check_whole(&self, v: i64) -> Result<i64, String> {
        if self.open.contains(self.min, self.max, v as f64) {
            Ok(v)
        } else {
            Err(format!("must be {}, got {v}", self.range_text()))
        }
    }

    /// A colour of this parameter if every channel is within range, or what is wrong.
    ///
    /// # Errors
    /// As [`Param::check`].
    pub fn check_rgb(&self, c: [i64; 3]) -> Result<Rgb8, String> {
        match c
            .iter()
            .find(|&&v| !self.open.contains(self.min, self.max, v as f64))
        {
            Some(v) => Err(format!(
                "each channel must be {}..={}, got {v}",
                num(self.min),
                num(self.max)
            )),
            None => Ok(Rgb8::new(c[0] as u8, c[1] as u8, c[2] as u8)),
        }
    }

    /// A vector of this parameter if it is finite and within range, or what is wrong.
    ///
    /// # Errors
    /// As [`Param::check`].
    pub fn check_vec3(&self, v: [f32; 3]) -> Result<[f32; 3], String> {
        let (lo, hi) = (self.min as f32, self.max as f32);
        if v.iter()
            .all(|&c| c.is_finite() && self.open.contains(lo, hi, c))
        {
            Ok(v)
        } else {
            Err(format!(
                "must be finite and {}, got [{}]",
                self.range_text(),
                v.map(format_number).join(", ")
            ))
        }
    }

    /// The default as a number; panics when it is not one (a mistake in the table).
    pub fn default_number(&self) -> f32 {
        match self.default {
            Some(Value::Number(v)) => v as f32,
            _ => panic!("{} has no default number", self.key),
        }
    }

    /// The default as three numbers; panics when it is not that.
    pub fn default_three(&self) -> [f64; 3] {
        match self.default {
            Some(Value::Three(v)) => v,
            _ => panic!("{} has no default of three numbers", self.key),
        }
    }

    /// The default as a colour; panics when it is not three numbers.
    pub fn default_rgb(&self) -> [i64; 3] {
        self.default_three().map(|c| c as i64)
    }

    /// The default as a switch; panics when it is not one.
    pub fn default_bool(&self) -> bool {
        match self.default {
            Some(Value::Bool(b)) => b,
            _ => panic!("{} has no default switch", self.key),
        }
    }

    /// `v` as help and messages show it.
    fn show(&self, v: &Value) -> String {
        match *v {
            Value::Number(x) => num(x),
            Value::Three(c) => c.map(num).join(","),
            Value::Bool(b) => b.to_string(),
            Value::Text(t) => t.to_owned(),
        }
    }

    /// `v` as JSON: whole numbers of integer and colour kinds without a fraction.
    fn json(&self, v: &Value) -> Json {
        let whole = matches!(self.kind, Kind::Integer | Kind::Rgb);
        let n = |x: f64| if whole { json!(x as i64) } else { json!(x) };
        match *v {
            Value::Number(x) => n(x),
            Value::Three(c) => Json::Array(c.iter().map(|&x| n(x)).collect()),
            Value::Bool(b) => json!(b),
            Value::Text(t) => json!(t),
        }
    }
}

/// A bound or value as messages show it ("0.1", "100", "1e30").
fn num(v: f64) -> String {
    format_number(v as f32)
}

/// A single-precision constant as the decimal it is written as (`0.1`,
/// not `0.10000000149011612`), for the table and the schema.
fn decimal(v: f32) -> f64 {
    format!("{v}").parse().unwrap_or(f64::from(v))
}

/// Every user-facing parameter, in the order the documentation lists them.
pub fn all() -> &'static [Param] {
    static TABLE: OnceLock<Vec<Param>> = OnceLock::new();
    TABLE.get_or_init(table::table)
}

/// The parameter of scene-file key `key`.
///
/// # Panics
/// When no parameter has that key: keys are written in code, and the
/// tests go through every one.
pub fn get(key: &str) -> &'static Param {
    all()
        .iter()
        .find(|p| p.key == key)
        .unwrap_or_else(|| panic!("no parameter {key}"))
}

/// A choice's list for the schema: its default and each value's name and help.
fn choice_list<T: Choice + Default>(key: &str) -> Json {
    json!({
        "key": key,
        "what": T::WHAT,
        "default": T::default().name(),
        "values": T::VALUES.iter().map(|v| json!({"name": v.name(), "help": v.help()})).collect::<Vec<_>>(),
    })
}

/// The schema of every parameter and choice, as the page reads it at start-up:
/// `{"params": [{key, kind, default, absent, typical, min, max, unit, help, needs, label, parts, flag}],
/// "choices": [{key, what, default, values: [{name, help}]}]}`.
pub fn schema() -> Json {
    let params = all()
        .iter()
        .map(|p| {
            json!({
                "key": p.key,
                "kind": p.kind.name(),
                "default": p.default.as_ref().map(|v| p.json(v)),
                "absent": p.absent,
                "typical": p.typical.as_ref().map(|v| p.json(v)),
                "min": p.min,
                "max": p.max,
                "unit": p.unit,
                "help": p.help,
                "needs": p.needs,
                "label": p.label,
                "parts": p.parts,
                "flag": p.flag,
                "open": p.open.name(),
            })
        })
        .collect::<Vec<_>>();
    let choices = table::choice_lists();
    json!({ "params": params, "choices": choices })
}

/// [`schema`] as JSON text (the viewer's `params.json`).
pub fn schema_json() -> String {
    schema().to_string()
}
