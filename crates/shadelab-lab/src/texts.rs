//! The instruments' texts in English, Russian, Slovak and Czech.
//!
//! Each language is a TOML file under `texts/`, embedded at build time: tables of
//! strings whose dotted paths are the ids (`method.gouraud`,
//! `inspect.span`). A string may hold placeholders, `{name}`, filled by
//! [`Texts::fill`]. Every language has the same ids and the same
//! placeholders per id (a test holds them to it), so the viewer can load
//! any file and switch language without gaps.

use std::collections::BTreeMap;

/// A language the texts exist in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Lang {
    /// English.
    #[default]
    En,
    /// Russian.
    Ru,
    /// Slovak.
    Sk,
    /// Czech.
    Cs,
}

impl Lang {
    /// All four.
    pub const ALL: [Lang; 4] = [Lang::En, Lang::Ru, Lang::Sk, Lang::Cs];

    /// The ISO 639-1 code.
    pub fn code(self) -> &'static str {
        match self {
            Lang::En => "en",
            Lang::Ru => "ru",
            Lang::Sk => "sk",
            Lang::Cs => "cs",
        }
    }

    /// The language of a BCP 47 tag such as a browser sends (`ru-RU`,
    /// `cs`, `sk-SK`), if it is one of ours.
    pub fn from_tag(tag: &str) -> Option<Lang> {
        let primary = tag.split(['-', '_']).next()?.to_ascii_lowercase();
        Lang::ALL.into_iter().find(|l| l.code() == primary)
    }

    /// The first of a browser's preferred languages that we have, else English.
    pub fn negotiate<'a>(preferred: impl IntoIterator<Item = &'a str>) -> Lang {
        preferred
            .into_iter()
            .find_map(Lang::from_tag)
            .unwrap_or_default()
    }

    /// The TOML source of this language's texts.
    pub fn source(self) -> &'static str {
        match self {
            Lang::En => include_str!("../texts/en.toml"),
            Lang::Ru => include_str!("../texts/ru.toml"),
            Lang::Sk => include_str!("../texts/sk.toml"),
            Lang::Cs => include_str!("../texts/cs.toml"),
        }
    }
}

/// One language's texts, by id.
#[derive(Debug, Clone, PartialEq)]
pub struct Texts {
    /// The language.
    pub lang: Lang,
    strings: BTreeMap<String, String>,
}

impl Texts {
    /// The texts of `lang`.
    ///
    /// # Panics
    /// If the embedded file is not valid TOML of strings (a test checks all four).
    pub fn new(lang: Lang) -> Texts {
        let table: toml::Table = toml::from_str(lang.source())
            .unwrap_or_else(|e| panic!("texts/{}.toml: {e}", lang.code()));
        let mut strings = BTreeMap::new();
        flatten("", &table, &mut strings);
        Texts { lang, strings }
    }

    /// The string with id `id`, or the id itself when there is none (so a
    /// gap shows, and does not crash a lesson).
    pub fn get<'a>(&'a self, id: &'a str) -> &'a str {
        self.strings.get(id).map_or(id, String::as_str)
    }

    /// The string `id` with each `{name}` replaced by its value.
    pub fn fill(&self, id: &str, values: &[(&str, &str)]) -> String {
        let mut out = self.get(id).to_owned();
        for (name, value) in values {
            out = out.replace(&format!("{{{name}}}"), value);
        }
        out
    }

    /// Every id and its string, sorted by id.
    pub fn entries(&self) -> impl Iterator<Item = (&str, &str)> {
        self.strings.iter().map(|(k, v)| (k.as_str(), v.as_str()))
    }
}

fn flatten(prefix: &str, table: &toml::Table, out: &mut BTreeMap<String, String>) {
    for (key, value) in table {
        let id = if prefix.is_empty() {
            key.clone()
        } else {
            format!("{prefix}.{key}")
        };
        match value {
            toml::Value::String(s) => {
                out.insert(id, s.trim_end().to_owned());
            }
            toml::Value::Table(t) => flatten(&id, t, out),
            other => panic!("texts: {id} is a {}, not a string", other.type_str()),
        }
    }
}

/// The placeholders `{name}` in a string, sorted.
pub fn placeholders(s: &str) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    let mut rest = s;
    while let Some(open) = rest.find('{') {
        let after = &rest[open + 1..];
        match after.find('}') {
            Some(close)
                if after[..close]
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || c == '_') =>
            {
                out.push(after[..close].to_owned());
                rest = &after[close + 1..];
            }
            _ => rest = after,
        }
    }
    out.sort();
    out.dedup();
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tags_map_to_languages() {
        assert_eq!(Lang::from_tag("ru-RU"), Some(Lang::Ru));
        assert_eq!(Lang::from_tag("CS"), Some(Lang::Cs));
        assert_eq!(Lang::from_tag("sk_SK"), Some(Lang::Sk));
        assert_eq!(Lang::from_tag("de-DE"), None);
        assert_eq!(Lang::negotiate(["de", "sk-SK", "en"]), Lang::Sk);
        assert_eq!(Lang::negotiate(["fr"]), Lang::En);
    }

    #[test]
    fn placeholders_are_found() {
        assert_eq!(
            placeholders("P = ({x}, {y}) {x} {not a name}"),
            vec!["x", "y"]
        );
    }
}
