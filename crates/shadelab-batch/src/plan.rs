//! What a batch renders for each mesh: views, modes, shards and file names.
//!
//! **Views.** `ring(N)` puts N cameras on a ring about the model's up axis,
//! the k-th at `yaw + 360°·k/N` (the scene's yaw and pitch are the start);
//! `cube` looks from the six sides: front, right, back, left at the
//! scene's pitch, then top and bottom (pitch ±90°, which the camera's orbit
//! holds 1° short of the pole so that "up" stays defined).
//!
//! **Shards.** `I/N` takes the entries whose id hashes to `I` modulo `N`
//! (64-bit FNV-1a of the id's UTF-8 bytes, fixed here and pinned by a test),
//! so shard membership depends on an entry's id alone: appending to or
//! reordering the manifest never moves a mesh to another shard, a rerun of a
//! shard finds its own finished outputs, and duplicate ids always meet in
//! the same shard, where they are caught. A line that cannot be parsed has no
//! id; it belongs to shard `line mod N`, so exactly one shard reports it.
//!
//! **Names.** Outputs are `DIR/<id>/<view>_<mode>.png`; an id is one path
//! component of letters, digits, `.`, `_` and `-` (not starting with `.`), so
//! no manifest can write outside `DIR`.

use std::path::{Path, PathBuf};
use std::str::FromStr;

use shadelab_core::Shading;

/// The cameras each mesh is seen from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Views {
    /// This many cameras evenly on a ring about the up axis.
    Ring(u32),
    /// Front, right, back, left, top, bottom.
    Cube,
}

/// Most views on a ring.
pub const MAX_RING_VIEWS: u32 = 360;

/// One camera of [`Views`].
#[derive(Debug, Clone, PartialEq)]
pub struct View {
    /// Its name in file names and the index (`v00`…, or `front`…).
    pub name: String,
    /// Degrees added to the scene's yaw.
    pub yaw: f32,
    /// Degrees added to the scene's pitch.
    pub pitch: f32,
}

impl Views {
    /// `n` views on a ring, 1..=[`MAX_RING_VIEWS`].
    ///
    /// # Errors
    /// The range, when `n` is outside it.
    pub fn ring(n: u32) -> Result<Views, String> {
        if (1..=MAX_RING_VIEWS).contains(&n) {
            Ok(Views::Ring(n))
        } else {
            Err(format!("must be 1..={MAX_RING_VIEWS} or \"cube\", got {n}"))
        }
    }

    /// The cameras, in order.
    pub fn list(self) -> Vec<View> {
        match self {
            Views::Ring(n) => {
                let width = if n > 100 { 3 } else { 2 };
                (0..n)
                    .map(|k| View {
                        name: format!("v{k:0width$}"),
                        yaw: 360.0 * k as f32 / n as f32,
                        pitch: 0.0,
                    })
                    .collect()
            }
            Views::Cube => [
                ("front", 0.0, 0.0),
                ("right", 90.0, 0.0),
                ("back", 180.0, 0.0),
                ("left", 270.0, 0.0),
                ("top", 0.0, 90.0),
                ("bottom", 0.0, -90.0),
            ]
            .into_iter()
            .map(|(name, yaw, pitch)| View {
                name: name.into(),
                yaw,
                pitch,
            })
            .collect(),
        }
    }

    /// How many cameras.
    pub fn count(self) -> usize {
        match self {
            Views::Ring(n) => n as usize,
            Views::Cube => 6,
        }
    }
}

impl FromStr for Views {
    type Err = String;

    fn from_str(s: &str) -> Result<Views, String> {
        let s = s.trim();
        if s.eq_ignore_ascii_case("cube") {
            return Ok(Views::Cube);
        }
        let n: u32 = s
            .parse()
            .map_err(|_| format!("must be a number of views or \"cube\", got {s:?}"))?;
        Views::ring(n)
    }
}

/// Shading methods from `flat`, `gouraud`, `phong`, `all`, comma-separated,
/// in the order given, without repeats.
///
/// # Errors
/// Names the unknown word.
pub fn parse_modes(s: &str) -> Result<Vec<Shading>, String> {
    let mut modes = Vec::new();
    for word in s.split(',').map(str::trim) {
        let add = match word.parse::<Shading>() {
            Ok(m) => vec![m],
            Err(_) if word.eq_ignore_ascii_case("all") => Shading::ALL.to_vec(),
            Err(_) => return Err(format!("{word:?} is not flat, gouraud, phong or all")),
        };
        for m in add {
            if !modes.contains(&m) {
                modes.push(m);
            }
        }
    }
    Ok(modes)
}

/// `WIDTHxHEIGHT`, each side at least 1 (the scene checks the upper limits).
///
/// # Errors
/// Says what was expected.
pub fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let bad = || format!("expected WIDTHxHEIGHT, got {s:?}");
    let (w, h) = s.trim().split_once(['x', 'X']).ok_or_else(bad)?;
    let w: u32 = w.trim().parse().map_err(|_| bad())?;
    let h: u32 = h.trim().parse().map_err(|_| bad())?;
    if w == 0 || h == 0 {
        return Err(format!("each side must be at least 1, got {s:?}"));
    }
    Ok((w, h))
}

/// A stable share of a manifest: shard `index` of `count`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// 0-based.
    pub index: u32,
    /// At least 1.
    pub count: u32,
}

impl Default for Shard {
    fn default() -> Shard {
        Shard { index: 0, count: 1 }
    }
}

impl Shard {
    /// Shard `index` of `count`.
    ///
    /// # Errors
    /// When `count` is 0 or `index` is not below it.
    pub fn new(index: u32, count: u32) -> Result<Shard, String> {
        if count == 0 || index >= count {
            return Err(format!("needs 0 <= I < N in I/N, got {index}/{count}"));
        }
        Ok(Shard { index, count })
    }

    /// Whether the entry with this id belongs to this shard.
    pub fn has_id(self, id: &str) -> bool {
        fnv1a(id.as_bytes()) % u64::from(self.count) == u64::from(self.index)
    }

    /// Whether a manifest line without a usable id belongs to this shard.
    pub fn has_line(self, line: u64) -> bool {
        line % u64::from(self.count) == u64::from(self.index)
    }

    /// The index file's name: `index.jsonl`, or `index-I-of-N.jsonl` when
    /// sharded, so that shards writing into one folder never share a file.
    pub fn index_name(self) -> String {
        if self.count == 1 {
            "index.jsonl".into()
        } else {
            format!("index-{}-of-{}.jsonl", self.index, self.count)
        }
    }
}

impl FromStr for Shard {
    type Err = String;

    fn from_str(s: &str) -> Result<Shard, String> {
        let bad = || format!("expected I/N (e.g. 0/4), got {s:?}");
        let (i, n) = s.trim().split_once('/').ok_or_else(bad)?;
        Shard::new(
            i.trim().parse().map_err(|_| bad())?,
            n.trim().parse().map_err(|_| bad())?,
        )
    }
}

/// 64-bit FNV-1a: tiny, fixed for ever, and good enough to spread ids.
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

/// Longest id, in bytes.
pub const MAX_ID_BYTES: usize = 200;

/// Checks that `id` is usable as a folder name.
///
/// # Errors
/// Says what an id may contain.
pub fn check_id(id: &str) -> Result<(), String> {
    let allowed = |c: char| c.is_ascii_alphanumeric() || matches!(c, '.' | '_' | '-');
    if id.is_empty() || id.len() > MAX_ID_BYTES || id.starts_with('.') || !id.chars().all(allowed) {
        return Err(format!(
            "id \"{}\" is not usable: 1 to {MAX_ID_BYTES} letters, digits, '.', '_' or '-', not starting with '.'",
            crate::escape(id)
        ));
    }
    Ok(())
}

/// The id of an entry that gives none: its path without the extension,
/// every character an id may not hold (the path's separators among them)
/// replaced by `_`, leading dots dropped.
pub fn default_id(path: &str) -> String {
    let p = Path::new(path);
    let stem = match (p.parent(), p.file_stem()) {
        (Some(parent), Some(stem)) => parent.join(stem),
        _ => PathBuf::from(path),
    };
    let text = stem.to_string_lossy();
    let mut id: String = text
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || matches!(c, '.' | '_' | '-') {
                c
            } else {
                '_'
            }
        })
        .collect();
    while id.starts_with(['.', '_']) && id.len() > 1 {
        id.remove(0);
    }
    id.truncate(MAX_ID_BYTES);
    id
}

/// The file of one output, relative to the output folder.
pub fn output_name(id: &str, view: &View, mode: Shading) -> String {
    format!("{id}/{}_{}.png", view.name, mode.name())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ring_views_are_evenly_spaced_and_named() {
        let v = Views::Ring(4).list();
        let got: Vec<(&str, f32)> = v.iter().map(|v| (v.name.as_str(), v.yaw)).collect();
        assert_eq!(
            got,
            [("v00", 0.0), ("v01", 90.0), ("v02", 180.0), ("v03", 270.0)]
        );
        assert_eq!(Views::Cube.list().len(), 6);
        assert_eq!("cube".parse(), Ok(Views::Cube));
        assert_eq!("6".parse(), Ok(Views::Ring(6)));
        assert!("0".parse::<Views>().is_err());
        assert!("361".parse::<Views>().is_err());
    }

    #[test]
    fn modes_parse_in_order_without_repeats() {
        assert_eq!(parse_modes("all"), Ok(Shading::ALL.to_vec()));
        assert_eq!(
            parse_modes("phong, flat,phong"),
            Ok(vec![Shading::Phong, Shading::Flat])
        );
        assert!(parse_modes("smooth").unwrap_err().contains("\"smooth\""));
    }

    #[test]
    fn shards_parse_and_the_hash_is_pinned() {
        assert_eq!("1/4".parse(), Ok(Shard { index: 1, count: 4 }));
        assert!("4/4".parse::<Shard>().is_err());
        assert!("0/0".parse::<Shard>().is_err());
        assert!("x".parse::<Shard>().is_err());
        // FNV-1a's published test vectors: membership must never change.
        assert_eq!(fnv1a(b""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(fnv1a(b"a"), 0xaf63_dc4c_8601_ec8c);
        assert_eq!(fnv1a(b"foobar"), 0x8594_4171_f739_67e8);
    }

    #[test]
    fn every_id_is_in_exactly_one_shard() {
        for n in 1..6 {
            for id in ["a", "bunny", "chairs_0001", "x.y-z"] {
                let owners = (0..n).filter(|&i| Shard::new(i, n).unwrap().has_id(id));
                assert_eq!(owners.count(), 1);
            }
        }
    }

    #[test]
    fn ids_are_single_safe_path_components() {
        for bad in ["", "..", ".hidden", "a/b", "a\\b", "é", "a b", "a\nb"] {
            assert!(check_id(bad).is_err(), "{bad:?}");
        }
        check_id("chair-01.v2_x").unwrap();
        assert!(check_id("a\nb").unwrap_err().contains("a\\nb"));
        assert_eq!(default_id("chairs/a 1.obj"), "chairs_a_1");
        assert_eq!(default_id("../up/x.stl"), "up_x");
        assert_eq!(default_id("bunny.obj"), "bunny");
        check_id(&default_id("../../é/.x.obj")).unwrap();
    }
}
