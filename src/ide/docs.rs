//! What hover and completion say about the words of the language that
//! have no row elsewhere: the keywords and the predefined names. (Block
//! kinds and parameters are documented in `check::kinds` and
//! `check::schema`, built-in functions in `check::eval::FUNCTION_DOCS`.)

use crate::check::schema::{ParamSpec, Ty};

/// Each keyword with a line on what it does and a short example.
pub const KEYWORD_DOCS: &[(&str, &str, &str)] = &[
    (
        "let",
        "a named constant; cannot be redefined",
        "let radius = 0.5;",
    ),
    (
        "include",
        "reads another scene file here, relative to this one (`.ptsi` fragments)",
        "include \"materials.ptsi\"",
    ),
    (
        "for",
        "a compile-time loop over a range (end exclusive) or a list's items",
        "for i in 0..10 { sphere { center <i, 0, 0> radius 0.4 } }",
    ),
    (
        "in",
        "the range or list of a `for` loop",
        "for x in [1, 2, 3] { … }",
    ),
    (
        "if",
        "a compile-time branch (a statement) or a choice of values (an expression)",
        "if frame > 10 { … } else { … }",
    ),
    (
        "else",
        "the other branch of an `if`",
        "let r = if big { 2 } else { 1 };",
    ),
    (
        "fn",
        "a function of numbers, vectors or colours",
        "fn lerp(a, b, t) = a + (b - a) * t;",
    ),
    (
        "group",
        "named objects placed by `instance`, built once however often placed",
        "group chair { box { min <0, 0, 0> max <1, 1, 1> } }",
    ),
    (
        "instance",
        "places a group, with its own transforms",
        "instance chair { translate <2, 0, 0> }",
    ),
    (
        "background",
        "the radiance seen where rays leave the scene",
        "background rgb <0.1, 0.1, 0.2>",
    ),
    (
        "material",
        "a named material (statement) or an object's material (in a block)",
        "material glass { type dielectric ior 1.5 }",
    ),
    (
        "texture",
        "a named texture: its name, its kind and its parameters",
        "texture oak wood { low rgb 0.3 high rgb 0.6 }",
    ),
    (
        "rgb",
        "a colour: one number (grey) or `<r, g, b>`, linear values",
        "rgb <0.8, 0.2, 0.1>",
    ),
    ("true", "the boolean true", "two_sided true"),
    ("false", "the boolean false", "smooth false"),
];

/// Each predefined name with what it holds.
pub const PREDEFINED_DOCS: &[(&str, &str)] = &[
    (
        "frame",
        "the frame number of an animation (`--frame`), 0 otherwise",
    ),
    (
        "clock",
        "the animation's time, from 0 at its first frame to 1 at its last",
    ),
    ("clock_delta", "the clock's step from one frame to the next"),
    ("pi", "π, 3.14159…"),
    ("x", "the vector `<1, 0, 0>`"),
    ("y", "the vector `<0, 1, 0>`"),
    ("z", "the vector `<0, 0, 1>`"),
];

/// A parameter's row as Markdown: its name and type, then its doc line
/// (meaning, default, range) and an example.
pub fn param_markdown(spec: &ParamSpec, block: &str) -> String {
    let mut out = format!("**{}** — {} (in `{block}`)", spec.name, spec.ty.describe());
    if spec.texture && spec.ty != Ty::Texture {
        out.push_str(", or a texture");
    }
    if !spec.doc.is_empty() {
        out.push_str("\n\n");
        out.push_str(spec.doc);
    }
    out.push_str(&format!("\n\n```pts\n{} {}\n```", spec.name, spec.example));
    out
}

/// The snippet a completion of parameter `spec` inserts (LSP snippet
/// syntax: `${1:…}` placeholders).
pub fn param_snippet(spec: &ParamSpec) -> String {
    let value = match spec.ty {
        Ty::Vec3 => "<${1:0}, ${2:0}, ${3:0}>".to_string(),
        Ty::Vec2 => "<${1:0}, ${2:0}>".to_string(),
        Ty::Color => "rgb <${1:0.8}, ${2:0.8}, ${3:0.8}>".to_string(),
        Ty::Str => "\"$1\"".to_string(),
        Ty::Bool => "${1|true,false|}".to_string(),
        Ty::Word(words) if !words.is_empty() => format!("${{1|{}|}}", words.join(",")),
        _ => format!("${{1:{}}}", snippet_escape(spec.example)),
    };
    format!("{} {value}", spec.name)
}

fn snippet_escape(s: &str) -> String {
    s.replace('\\', "\\\\")
        .replace('$', "\\$")
        .replace('}', "\\}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_keyword_and_predefined_name_is_documented() {
        let documented: Vec<_> = KEYWORD_DOCS.iter().map(|k| k.0).collect();
        assert_eq!(documented, crate::syntax::words::KEYWORDS);
        let predefined: Vec<_> = PREDEFINED_DOCS.iter().map(|k| k.0).collect();
        assert_eq!(predefined, crate::check::PREDEFINED);
    }
}
