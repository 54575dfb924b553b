//! The errors of a block's parameters, one constructor each: an unknown
//! or repeated parameter, a texture or a transform where none goes, a
//! POV-Ray word the row refuses, a value that is not a material.

use super::schema::{metal_preset, ParamSpec, METAL_PRESETS};
use crate::diag::{codes, did_you_mean, Diagnostic};
use crate::span::Span;
use crate::syntax::ast::Ident;

/// The error of a transform given to what lies at infinity (an
/// environment or a sky): only turning means anything there.
pub(super) fn at_infinity(what: &str, name: &str, span: Span) -> Option<Diagnostic> {
    if !matches!(what, "environment" | "sky") || !matches!(name, "translate" | "scale" | "matrix") {
        return None;
    }
    let why = match name {
        "translate" => "it is infinitely far: moving it changes nothing",
        "scale" => "it has no size: every direction keeps its light",
        _ => "a matrix could move, scale or shear it",
    };
    let help = match what {
        "environment" => "turn it with `rotate <x, y, z>` (degrees); to move the scene against it, move the camera and the objects",
        _ => "turn the sun with `sun_direction` or `sun_azimuth`; to move the scene against it, move the camera and the objects",
    };
    Some(
        Diagnostic::error(
            codes::UNKNOWN_PARAM,
            format!("`{name}` has no meaning for the {what}"),
            span,
        )
        .with_label(why)
        .with_help(help),
    )
}

/// The error for a texture (`what`, at `span`) given to a parameter that
/// takes a plain value.
pub(super) fn texture_not_allowed(spec: &ParamSpec, what: &str, span: Span) -> Diagnostic {
    Diagnostic::error(
        codes::TEXTURE_NOT_ALLOWED,
        format!("`{}` cannot be given a texture", spec.name),
        span,
    )
    .with_label(what.to_string())
    .with_help(format!(
        "`{}` takes {}; textures go on a material's colours and numbers (`diffuse`, `gloss`, `emission`, …) and its `normal_map` and `bump`",
        spec.name,
        spec.ty.describe()
    ))
}

/// The error for a POV-Ray (or Mitsuba) word that a block's row refuses (`falloff` in
/// a `spot_light`), with its row's help line and the names it accepts.
pub(super) fn refused_povray_word(
    name: &crate::syntax::ast::Ident,
    what: &str,
    help: &str,
    accepted: &[&str],
) -> Diagnostic {
    Diagnostic::error(
        codes::UNKNOWN_PARAM,
        format!("unknown parameter `{}` in `{what}`", name.name),
        name.span,
    )
    .with_label("another renderer's word for a parameter of this block")
    .with_help(format!("{help}; `{what}` accepts {}", accepted.join(", ")))
}

/// `material` given a value that is not a material.
pub(super) fn not_a_material(span: Span) -> Diagnostic {
    Diagnostic::error(
        codes::TYPE_MISMATCH,
        "`material` takes a material name or an inline material block",
        span,
    )
    .with_label("not a material")
    .with_help("write `material white` (a declared name) or `material { diffuse rgb 0.8 }`")
}

/// `material "Au"`: Mitsuba's conductor names its metal so; ptsc's
/// `preset` does (`entry` is the whole `material "Au"`).
pub(super) fn metal_as_material(entry: Span, preset: &str, what: &str) -> Diagnostic {
    let in_material = what == "material" || what.starts_with("material ");
    let d = Diagnostic::error(
        codes::TYPE_MISMATCH,
        "`material` takes a material name or an inline material block",
        entry,
    )
    .with_label("Mitsuba's name of a conductor's metal");
    if in_material {
        d.with_help(format!(
            "Mitsuba's `material` of a conductor is `preset {preset}` in ptsc (of a `type conductor` material)"
        ))
        .with_fix(entry, format!("preset {preset}"))
    } else {
        d.with_help(format!(
            "Mitsuba's `material` of a conductor is `preset {preset}` in ptsc: `material {{ type conductor preset {preset} }}`"
        ))
    }
}

/// A parameter that takes a word given a string (`type "conductor"`,
/// `preset "Au"`, as Mitsuba's files write them): the word it means, if
/// one fits, is the fix.
pub(super) fn word_as_string(
    spec: &ParamSpec,
    text: &str,
    span: Span,
    words: &[&str],
) -> Diagnostic {
    let fit = words
        .iter()
        .find(|w| **w == text)
        .copied()
        .or_else(|| {
            (words == METAL_PRESETS)
                .then(|| metal_preset(text))
                .flatten()
        })
        .or_else(|| did_you_mean(text, words.iter().copied()));
    let d = Diagnostic::error(
        codes::TYPE_MISMATCH,
        format!("`{}` takes a word, not a string", spec.name),
        span,
    )
    .with_label("a string");
    match fit {
        Some(word) => d
            .with_help(format!("write `{} {word}`, without quotes", spec.name))
            .with_fix(span, word),
        None => {
            let foreign = (spec.name == "type").then(|| foreign_type(text));
            d.with_help(foreign.flatten().map_or_else(
                || format!("write one of {} without quotes", words.join(", ")),
                str::to_string,
            ))
        }
    }
}

/// What ptsc writes for another renderer's material type (Mitsuba's
/// plugin names: `roughconductor`, `diffuse`), given as a `type`.
pub(super) fn foreign_type(word: &str) -> Option<&'static str> {
    match word {
        // A ptsc parameter's name, so not among the global hints.
        "diffuse" => Some("Mitsuba's `diffuse` BSDF is ptsc's default material, `type mix` (or no `type`), with `diffuse rgb …`"),
        _ => crate::syntax::povray::hint(word),
    }
}

/// A parameter the block `what` does not have, with `help`.
pub(super) fn unknown_parameter(name: &Ident, what: &str, help: String) -> Diagnostic {
    Diagnostic::error(
        codes::UNKNOWN_PARAM,
        format!("unknown parameter `{}` in `{what}`", name.name),
        name.span,
    )
    .with_label("not a parameter of this block")
    .with_help(help)
}

/// A parameter given a second time (at `span`; first at `first`).
pub(super) fn given_twice(name: &str, what: &str, span: Span, first: Span) -> Diagnostic {
    Diagnostic::error(
        codes::DUPLICATE_PARAM,
        format!("parameter `{name}` given twice in `{what}`"),
        span,
    )
    .with_label("given again here")
    .with_secondary(first, "first given here")
    .with_help("remove one of them")
}

/// "a" or "an" before `word`, by its first letter.
pub(super) fn article(word: &str) -> &'static str {
    match word.chars().next() {
        Some('a' | 'e' | 'i' | 'o' | 'u') => "an",
        _ => "a",
    }
}
