//! The kinds of block statement (`kind { … }`), one row each: the kind's
//! name, what it is, its parameters with their documentation, what it
//! becomes (a setting, a light or a shape, with the function that converts
//! its checked parameters), POV-Ray's order of its positional values and
//! the POV-Ray words for it. The grammar reads a block's kind as a name; the
//! checker, the did-you-mean of an unknown kind, the docs' tables, the
//! editors' word lists and hover all read this table. Adding a kind is
//! adding a row.

mod kind;
pub mod lights;
pub mod settings;
pub mod shapes;

use super::schema::SHAPE_COMMON;
use crate::diag::{codes, did_you_mean, Diagnostic};
use crate::span::Span;
use crate::syntax::ast::{Block, Entry, Ident};
pub use kind::{Kind, Role, Setting, ShapeInput};

/// Every kind of block statement, in the order the docs list them: the
/// settings, the shapes, the lights (each file lists its own rows).
pub const KINDS: [&Kind; settings::ALL.len() + shapes::ALL.len() + lights::ALL.len()] = {
    let mut all = [&settings::RENDER; settings::ALL.len() + shapes::ALL.len() + lights::ALL.len()];
    let mut i = 0;
    let parts = [settings::ALL, shapes::ALL, lights::ALL];
    let mut part = 0;
    while part < parts.len() {
        let mut j = 0;
        while j < parts[part].len() {
            all[i] = parts[part][j];
            i += 1;
            j += 1;
        }
        part += 1;
    }
    all
};

/// The names of every kind, in the order of [`KINDS`] (the parser is
/// given them: see `syntax::parse_each`).
pub const NAMES: [&str; KINDS.len()] = {
    let mut names = [""; KINDS.len()];
    let mut i = 0;
    while i < KINDS.len() {
        names[i] = KINDS[i].name;
        i += 1;
    }
    names
};

/// Every parameter name of every kind and of materials and textures,
/// sorted (editors highlight them; their grammars are tested against this
/// list).
pub fn all_parameter_names() -> Vec<&'static str> {
    use super::schema::{BANDS, CHECKER, COLOR_MAP, GRADIENT, IMAGE, MATERIAL, NOISE};
    let mut names: Vec<&'static str> = (KINDS.iter().flat_map(|k| k.params.iter()))
        .chain(SHAPE_COMMON)
        .chain(MATERIAL)
        .chain(CHECKER)
        .chain(IMAGE)
        .chain(NOISE)
        .chain(BANDS)
        .chain(GRADIENT)
        .chain(COLOR_MAP)
        .filter(|p| p.povray.is_none())
        .map(|p| p.name)
        .collect();
    names.sort_unstable();
    names.dedup();
    names
}

/// The kind named `name`.
pub fn find(name: &str) -> Option<&'static Kind> {
    KINDS.iter().copied().find(|k| k.name == name)
}

/// The names of every kind.
pub fn names() -> impl Iterator<Item = &'static str> {
    NAMES.iter().copied()
}

/// What ptsc writes for POV-Ray's statement `word`, if a kind stands for
/// it: the help line of its row.
pub fn povray_hint(word: &str) -> Option<&'static str> {
    let kind = povray_kind(word)?;
    (kind.povray.iter())
        .find(|(w, _)| *w == word)
        .map(|(_, help)| *help)
}

/// The kind whose row lists POV-Ray's statement `word` (`light_source` →
/// `point_light`).
fn povray_kind(word: &str) -> Option<&'static Kind> {
    KINDS
        .iter()
        .copied()
        .find(|k| k.povray.iter().any(|(w, _)| *w == word))
}

/// Whether the unknown statement `word { … }` stands for what lights a
/// scene: a light's or a sky's POV-Ray word (`light_source`, `sky_sphere`)
/// or misspelling (`point_ligth`), or POV-Ray's `background { … }`. Its
/// error then says why the scene has no light, and "no light" would only
/// repeat it.
pub fn may_be_a_light(word: &str) -> bool {
    if word == "background" {
        return true;
    }
    let meant = povray_kind(word).or_else(|| did_you_mean(word, names()).and_then(find));
    meant.is_some_and(|k| {
        k.is_light() || matches!(k.role, Role::Setting(Setting::Sky | Setting::Environment))
    })
}

/// Whether `block`, read as a block of `kind`, names only parameters the
/// kind has: then putting the kind's name in place of another word is the
/// whole rewrite (POV-Ray's `light_source { <0, 4, 0> color rgb 1 }` is
/// not: its values are unnamed and its colour has another name).
fn fits(kind: &Kind, block: &Block) -> bool {
    block.entries.iter().all(|entry| match entry {
        Entry::Param { name, .. } | Entry::Texture { name, .. } => kind.param(&name.name).is_some(),
        Entry::Material { .. } => kind.takes_material(),
        _ => false,
    })
}

/// The error for `name { … }` where a statement goes, at `span`: the ptsc
/// statement for POV-Ray's word, or the closest ptsc word. `block` is its
/// block where it parsed as one: the fix that renames a POV-Ray word is
/// offered only where the block then fits the kind (a fix that leaves
/// errors behind is not one; the help gives the whole form).
pub fn unknown_statement(name: &Ident, span: Span, block: Option<&Block>) -> Diagnostic {
    let word = name.name.as_str();
    if word == "background" {
        return Diagnostic::error(
            codes::FOREIGN_BLOCK,
            "`background` takes a colour, not a block",
            span,
        )
        .with_label("POV-Ray's `background { color … }`")
        .with_help("write `background rgb <0.5, 0.7, 1>` (no braces); a daylight sky is `sky { … }`, an HDR image `environment { … }`");
    }
    if let Some(hint) = povray_hint(word).or_else(|| crate::syntax::povray::hint(word)) {
        // A kind's row lists other renderers' words too (Mitsuba's `envmap`).
        let renderer = match hint.starts_with("Mitsuba's") {
            true => "Mitsuba",
            false => crate::syntax::povray::renderer(word),
        };
        let d = Diagnostic::error(
            codes::FOREIGN_BLOCK,
            format!("{renderer}'s `{word} {{ … }}` is not ptsc"),
            span,
        )
        .with_label("a statement ptsc does not have")
        .with_help(hint);
        // The kind that stands for the POV-Ray word: its name replaces it.
        return match povray_kind(word) {
            Some(k) if block.is_some_and(|b| fits(k, b)) => d.with_fix(name.span, k.name),
            _ => d,
        };
    }
    let words = (crate::syntax::parser::KEYWORDS.iter().copied()).chain(names());
    let suggestion = did_you_mean(word, words);
    let help = match suggestion {
        Some(s) => format!("did you mean `{s}`?"),
        None => "a scene is a list of statements: `let`, `fn`, `include`, `for`, `if`, `material`, `group`, `instance`, `camera { … }`, `render { … }`, a light or an object such as `sphere { … }`".to_string(),
    };
    let d = Diagnostic::error(
        codes::FOREIGN_BLOCK,
        format!("unknown statement `{word}`"),
        span,
    )
    .with_label("not a ptsc statement")
    .with_help(help);
    match suggestion {
        Some(s) => d.with_fix(name.span, s),
        None => d,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_distinct_and_not_keywords() {
        let mut seen = std::collections::HashSet::new();
        for k in KINDS {
            assert!(seen.insert(k.name), "{} twice", k.name);
            assert!(
                !crate::syntax::parser::KEYWORDS.contains(&k.name),
                "{} is a keyword: the grammar would not read it as a kind",
                k.name
            );
            assert!(!k.summary.is_empty(), "{} has no summary", k.name);
        }
    }

    #[test]
    fn every_parameter_is_documented() {
        for p in crate::check::schema::MATERIAL {
            assert!(!p.doc.is_empty(), "the material's `{}` has no doc", p.name);
        }
        for k in KINDS {
            for p in k.schemas().into_iter().flatten() {
                if p.povray.is_none() {
                    assert!(!p.doc.is_empty(), "`{}` of `{}` has no doc", p.name, k.name);
                }
            }
        }
    }

    #[test]
    fn positional_orders_name_parameters_of_the_kind() {
        for k in KINDS {
            for name in k.positional.iter().flat_map(|(names, _)| names.iter()) {
                assert!(
                    k.param(name).is_some(),
                    "`{name}` is no parameter of `{}`",
                    k.name
                );
            }
        }
    }

    #[test]
    fn povray_words_name_their_kind() {
        assert!(povray_hint("light_source").unwrap().contains("point_light"));
        assert!(povray_hint("cube").unwrap().contains("box"));
        assert!(povray_hint("sphere").is_none());
        for k in KINDS {
            for (w, help) in k.povray {
                assert!(find(w).is_none(), "{w} is a ptsc kind");
                assert!(
                    help.contains(k.name),
                    "the help for {w} does not name `{}`",
                    k.name
                );
            }
        }
    }

    #[test]
    fn a_refused_povray_word_names_a_parameter_its_block_has() {
        use crate::check::schema::*;
        let rows = (KINDS.iter().map(|k| k.params))
            .chain([NOISE, BANDS, UNBANDED, GRADIENT, CHECKER, IMAGE, MATERIAL]);
        let mut refused = 0;
        for row in rows {
            for spec in row.iter().filter(|s| s.povray.is_some()) {
                let (instead, help) = spec.povray.unwrap();
                refused += 1;
                assert!(help.contains(&format!("`{}`", spec.name)), "{help}");
                // `scale` is every texture's (TEXTURE_TRANSFORMS).
                let has = row.iter().any(|s| s.name == instead && s.povray.is_none());
                assert!(has || instead == "scale", "{}: {instead}", spec.name);
            }
        }
        assert_eq!(refused, 14);
        // Editors highlight parameters only: no word that is only refused.
        let names = all_parameter_names();
        for word in [
            "falloff",
            "tightness",
            "point_at",
            "color0",
            "spp",
            "origin",
        ] {
            assert!(!names.contains(&word), "{word}");
        }
    }
}
