//! The four languages have the same texts: every id in each, with the same
//! placeholders, none empty, none left in English by mistake.

use std::collections::BTreeSet;

use shadelab_lab::{placeholders, Lang, Texts};

#[test]
fn every_language_has_every_id_with_the_same_placeholders() {
    let english = Texts::new(Lang::En);
    let ids: BTreeSet<&str> = english.entries().map(|(id, _)| id).collect();
    assert!(ids.len() > 80, "{} ids", ids.len());
    for lang in Lang::ALL {
        let texts = Texts::new(lang);
        let these: BTreeSet<&str> = texts.entries().map(|(id, _)| id).collect();
        let missing: Vec<_> = ids.difference(&these).collect();
        let extra: Vec<_> = these.difference(&ids).collect();
        assert!(
            missing.is_empty() && extra.is_empty(),
            "{lang:?}: missing {missing:?}, extra {extra:?}"
        );
        for (id, text) in texts.entries() {
            assert!(!text.trim().is_empty(), "{lang:?} {id} is empty");
            assert_eq!(
                placeholders(text),
                placeholders(english.get(id)),
                "{lang:?} {id}: placeholders differ"
            );
            assert!(
                !text.contains('\\'),
                "{lang:?} {id}: a stray line continuation"
            );
        }
    }
}

#[test]
fn translations_are_translated() {
    let english = Texts::new(Lang::En);
    for lang in [Lang::Ru, Lang::Sk, Lang::Cs] {
        let texts = Texts::new(lang);
        // Prose (anything longer than a short label) must differ from the English.
        for (id, text) in texts.entries() {
            if text.chars().count() > 24 && id.starts_with("about.") {
                assert_ne!(text, english.get(id), "{lang:?} {id} is still English");
            }
        }
    }
    // The terms the textbooks use.
    assert_eq!(
        Texts::new(Lang::Ru).get("method.gouraud"),
        "Закраска по Гуро"
    );
    assert_eq!(
        Texts::new(Lang::Ru).get("method.phong"),
        "Закраска по Фонгу"
    );
    assert_eq!(
        Texts::new(Lang::Sk).get("method.gouraud"),
        "Gouraudovo tieňovanie"
    );
    assert_eq!(
        Texts::new(Lang::Cs).get("method.phong"),
        "Phongovo stínování"
    );
    for (lang, term) in [
        (Lang::Ru, "полосы маха"),
        (Lang::Sk, "machove pásy"),
        (Lang::Cs, "machovy proužky"),
    ] {
        let text = Texts::new(lang).get("about.mach_bands").to_lowercase();
        assert!(text.contains(term), "{lang:?}: {text}");
    }
}

#[test]
fn fill_replaces_placeholders_and_unknown_ids_show_themselves() {
    let ru = Texts::new(Lang::Ru);
    assert_eq!(
        ru.fill("inspect.title", &[("x", "3"), ("y", "4")]),
        "Пиксель (3, 4)"
    );
    assert_eq!(ru.get("no.such.id"), "no.such.id");
}
