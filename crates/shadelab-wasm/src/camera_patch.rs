//! A frame that only turns the camera, read without reading the scene again.
//!
//! The page asks for every frame with the whole scene text, and dragging or
//! an arrow key changes nothing in it but `yaw`, `pitch` and `zoom` of its
//! `[render]` section. Parsing the TOML again for that is a tenth of a
//! teapot frame's time in WebAssembly, so [`camera_change`] compares the new
//! text with the last one line by line: when every line is the same but
//! those three keys' (in the same order, in `[render]`, as `key = number`),
//! it gives their new values, and the engine sets them on the scene file it
//! kept and resolves the camera through the same `SceneFile` function as
//! always. Anything else — another line changed, a comment, a value that is
//! not a plain decimal number as TOML writes it — gives `None`, and the text
//! is read as a whole: the shortcut never accepts what TOML would refuse,
//! and never reads a value differently.

/// The camera keys a frame may change without the scene being read again.
const CAMERA_KEYS: [&str; 3] = ["yaw", "pitch", "zoom"];

/// `render.yaw`, `render.pitch` and `render.zoom` as `new` gives them, when
/// `new` differs from `old` only in the values of those keys; `None`
/// otherwise. Each entry is the key's new value, or `None` when unchanged.
pub fn camera_change(old: &str, new: &str) -> Option<[Option<f32>; 3]> {
    let mut changed = [None; 3];
    let mut any = false;
    let mut section = "";
    let (mut a, mut b) = (old.split('\n'), new.split('\n'));
    loop {
        match (a.next(), b.next()) {
            (None, None) => break,
            (Some(x), Some(y)) if x == y => {
                if x.starts_with('[') {
                    section = x;
                }
            }
            (Some(x), Some(y)) => {
                if section != "[render]" {
                    return None;
                }
                let (kx, _) = x.split_once(" = ")?;
                let (ky, value) = y.split_once(" = ")?;
                let k = CAMERA_KEYS.iter().position(|&c| c == kx && c == ky)?;
                if changed[k].is_some() {
                    return None;
                }
                changed[k] = Some(toml_decimal(value)?);
                any = true;
            }
            _ => return None,
        }
    }
    any.then_some(changed)
}

/// `text` as a number when it is written as TOML writes a plain decimal
/// float or integer: `-12`, `30.5`, `1e-7`, `2.5E+3` (no underscores, no
/// leading zeros, digits on both sides of the point; no `inf` or `nan`).
fn toml_decimal(text: &str) -> Option<f32> {
    let body = text.strip_prefix(['-', '+']).unwrap_or(text);
    let (mantissa, exponent) = match body.split_once(['e', 'E']) {
        Some((m, e)) => (m, Some(e)),
        None => (body, None),
    };
    let (int, frac) = match mantissa.split_once('.') {
        Some((i, f)) => (i, Some(f)),
        None => (mantissa, None),
    };
    let digits = |s: &str| !s.is_empty() && s.bytes().all(|c| c.is_ascii_digit());
    let plain = digits(int)
        && (int == "0" || !int.starts_with('0'))
        && frac.is_none_or(digits)
        && exponent.is_none_or(|e| digits(e.strip_prefix(['-', '+']).unwrap_or(e)));
    if plain {
        text.parse().ok()
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const OLD: &str = "[model]\nsource = \"teapot\"\n\n[render]\nwidth = 480\nyaw = 0.0\npitch = 10.0\nzoom = 1.0\n";

    #[test]
    fn only_the_cameras_keys_may_change() {
        let new = OLD
            .replace("yaw = 0.0", "yaw = -12.5")
            .replace("zoom = 1.0", "zoom = 2.5e0");
        assert_eq!(
            camera_change(OLD, &new),
            Some([Some(-12.5), None, Some(2.5)])
        );
        assert_eq!(
            camera_change(OLD, OLD),
            None,
            "nothing changed: read nothing"
        );
        for other in [
            OLD.replace("width = 480", "width = 481"),
            OLD.replace("yaw = 0.0", "yaw = 1.0\n"),
            OLD.replace("yaw = 0.0", "yaw = 1.0 # turned"),
            OLD.replace("yaw = 0.0", "yaw = 1_0.0"),
            OLD.replace("yaw = 0.0", "yaw = .5"),
            OLD.replace("yaw = 0.0", "yaw = 5."),
            OLD.replace("yaw = 0.0", "yaw = 05.0"),
            OLD.replace("yaw = 0.0", "yaw = inf"),
            OLD.replace("yaw = 0.0", "yaw = nan"),
            OLD.replace("yaw = 0.0", "yaw=1.0"),
            OLD.replace("yaw = 0.0", "pitch = 1.0"),
            OLD.replace("source = \"teapot\"", "source = \"cube\""),
            OLD.replace("[render]", "[camera]"),
            format!("{OLD}[material]\nshininess = 3.0\n"),
        ] {
            assert_eq!(camera_change(OLD, &other), None, "{other}");
        }
    }

    #[test]
    fn decimals_are_read_as_toml_reads_them() {
        for (text, value) in [
            ("0", 0.0),
            ("-0.0", -0.0),
            ("+7", 7.0),
            ("1e-7", 1e-7),
            ("3.25E+2", 325.0),
        ] {
            assert_eq!(toml_decimal(text), Some(value), "{text}");
            let parsed: toml::Value = toml::from_str(&format!("x = {text}")).unwrap();
            let from_toml = parsed["x"]
                .as_float()
                .or(parsed["x"].as_integer().map(|i| i as f64));
            assert_eq!(from_toml.map(|v| v as f32), Some(value), "{text}");
        }
        for text in [
            "", "-", "1.", ".1", "1e", "e5", "00", "1__0", "0x10", "infinity", "NaN", "1.0.0",
        ] {
            assert_eq!(toml_decimal(text), None, "{text}");
        }
    }
}
