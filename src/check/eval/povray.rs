//! POV-Ray's forms of values: a vector's components by name (`v.x`, read as
//! POV-Ray reads them) and colours with filter and transmit channels
//! (`rgbf <r, g, b, f>`), which ptsc answers with what to write instead.

use super::budget::Work;
use super::value::{text, Value};
use crate::diag::{codes, did_you_mean, Diagnostic, Diagnostics};
use crate::span::Span;
use crate::syntax::ast::{Expr, Ident};

/// The components of a vector by name, as POV-Ray names them: `x y z t`,
/// and `u v` for a 2-vector's.
const VECTOR_COMPONENTS: &[(&str, usize)] =
    &[("x", 0), ("y", 1), ("z", 2), ("t", 3), ("u", 0), ("v", 1)];

/// The components of a colour by name (`red green blue`, and `x y z` as
/// POV-Ray allows).
const COLOR_COMPONENTS: &[(&str, usize)] = &[
    ("red", 0),
    ("green", 1),
    ("blue", 2),
    ("x", 0),
    ("y", 1),
    ("z", 2),
];

/// The names of the components of a vector of `len` items (`None`: of
/// any length), or of a colour: what `base.` may be followed by.
pub fn component_names(color: bool, len: Option<usize>) -> Vec<&'static str> {
    let table = if color {
        COLOR_COMPONENTS
    } else {
        VECTOR_COMPONENTS
    };
    let mut names: Vec<&str> = (table.iter())
        .filter(|(_, i)| len.is_none_or(|n| *i < n))
        .map(|(n, _)| *n)
        .collect();
    // `x y z` of a colour are POV-Ray's spellings; a 3-vector's `u v` too.
    match (color, len) {
        (true, _) => names.retain(|n| !matches!(*n, "x" | "y" | "z")),
        (false, Some(2)) => {}
        (false, _) => names.retain(|n| !matches!(*n, "u" | "v")),
    }
    names
}

/// `base.member`: a component of a vector or colour. `at` is the whole
/// expression, `base_span` where the vector is written.
pub(super) fn member(
    base: Value,
    base_span: Span,
    member: &Ident,
    diags: &mut Diagnostics,
) -> Option<Value> {
    let name = member.name.as_str();
    let (items, table): (&[f64], _) = match &base {
        Value::Vector(v) => (v, VECTOR_COMPONENTS),
        Value::Color(c) => (c, COLOR_COMPONENTS),
        other => {
            diags.push(
                Diagnostic::error(
                    codes::TYPE_MISMATCH,
                    format!("`.{name}` of {}", other.type_name()),
                    base_span,
                )
                .with_label(format!("this is {}, not a vector", other.type_name()))
                .with_help("`.x`, `.y` and `.z` read a vector's components (`.red`, `.green`, `.blue` a colour's); a list's items are `xs[0]`"),
            );
            return None;
        }
    };
    let found = table.iter().find(|(n, _)| *n == name);
    match found {
        Some(&(_, i)) if i < items.len() => Some(Value::Num(items[i])),
        Some(_) => {
            diags.push(
                Diagnostic::error(
                    codes::INDEX_OUT_OF_RANGE,
                    format!("`.{name}` of {}", base.type_name()),
                    member.span,
                )
                .with_label(format!("{} has no such component", base.type_name()))
                .with_help(
                    "`.x` is the first component, `.y` the second, `.z` the third, `.t` the fourth",
                ),
            );
            None
        }
        None => {
            let names = table.iter().map(|(n, _)| *n);
            let help = match (name, did_you_mean(name, names)) {
                ("filter" | "transmit" | "gray" | "grey" | "hf", _) => {
                    "ptsc colours have three channels: `.red`, `.green`, `.blue`".to_string()
                }
                (_, Some(s)) => format!("did you mean `.{s}`?"),
                _ => {
                    let all: Vec<String> = table.iter().map(|(n, _)| format!("`.{n}`")).collect();
                    format!("{} has the components {}", base.type_name(), all.join(", "))
                }
            };
            diags.push(
                Diagnostic::error(
                    codes::UNKNOWN_COMPONENT,
                    format!("unknown component `.{name}`"),
                    member.span,
                )
                .with_label(format!("not a component of {}", base.type_name()))
                .with_help(help),
            );
            None
        }
    }
}

/// POV-Ray's `rgbf`, `rgbt` or `rgbft` colour: an error that names the
/// ptsc colour and the material's `transmission` for its see-through part
/// (`value` is the evaluated value, `expr` the whole colour).
pub(super) fn filter_color(word: &Ident, value: Option<Value>, expr: &Expr) -> Diagnostic {
    let channels = match word.name.as_str() {
        "rgbft" => 5,
        _ => 4,
    };
    let help = match value {
        Some(Value::Vector(v)) if v.len() == channels => {
            let rgb = written(&Value::Vector(v[..3].into()));
            let through: f64 = v[3..].iter().sum();
            if through == 0.0 {
                format!("write `rgb {rgb}`")
            } else {
                let amount = written(&Value::Num(through.clamp(0.0, 1.0)));
                format!("write `rgb {rgb}`, and give the material `transmission {amount}` for the see-through part (`ior 1` lets light through unbent, as POV-Ray's filter and transmit do without an `interior`)")
            }
        }
        _ => "write `rgb <r, g, b>`; a see-through material has `transmission` (with `ior 1`, light passes unbent)".to_string(),
    };
    Diagnostic::error(
        codes::FILTER_COLOR,
        format!(
            "ptsc colours have no filter or transmit channel (`{}`)",
            word.name
        ),
        expr.span,
    )
    .with_label(format!("POV-Ray's `{}` colour", word.name))
    .with_help(help)
}

/// `v` as a scene writes it, for a suggestion (short values only).
pub fn written(v: &Value) -> String {
    text(v, 0, 200, &mut Work::new(1_000)).unwrap_or_else(|_| "…".to_string())
}
