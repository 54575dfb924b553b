//! A parameter's value checked against its row's type: the words of a
//! word list, numbers, vectors, colours, strings and flags.

use super::eval::{eval, Env, Value};
use super::param_errors::{foreign_type, word_as_string};
use super::schema::*;
use crate::diag::codes;
use crate::diag::{did_you_mean, Diagnostic, Diagnostics};
use crate::syntax::ast::{Expr, ExprKind};

/// A checked parameter value.
#[derive(Debug, Clone, PartialEq)]
pub enum Val {
    /// A number (or whole number).
    Num(f64),
    /// A vector.
    Vector(Vec<f64>),
    /// A colour.
    Color([f64; 3]),
    /// A string.
    Str(String),
    /// A boolean.
    Bool(bool),
    /// A word from a fixed set.
    Word(String),
    /// A texture (for the parameters that take one).
    Texture(Box<super::scene::Texture>),
}

/// Evaluates one parameter value and checks its type against the spec.
pub(super) fn typed_value(
    spec: &ParamSpec,
    value: &Expr,
    env: &mut Env,
    diags: &mut Diagnostics,
) -> Option<Val> {
    if let Ty::Word(words) = spec.ty {
        return word_value(spec, words, value, diags);
    }
    let v = eval(value, env, diags)?;
    let ok = match (&spec.ty, v) {
        (Ty::Num, Value::Num(x)) => Some(Val::Num(x)),
        (Ty::Int, Value::Num(x)) if x.fract() == 0.0 => Some(Val::Num(x)),
        (Ty::Int, Value::Num(x)) => {
            diags.push(
                Diagnostic::error(
                    codes::TYPE_MISMATCH,
                    format!("`{}` must be a whole number, found {x}", spec.name),
                    value.span,
                )
                .with_label("has a fractional part")
                .with_help(format!("write e.g. `{} {}`", spec.name, spec.example)),
            );
            return None;
        }
        (Ty::Vec2, Value::Vector(v)) if v.len() == 2 => Some(Val::Vector(v.to_vec())),
        (Ty::Vec3, Value::Vector(v)) if v.len() == 3 => Some(Val::Vector(v.to_vec())),
        (Ty::NumOrVec3, Value::Num(x)) => Some(Val::Vector(vec![x; 3])),
        (Ty::NumOrVec3, Value::Vector(v)) if v.len() == 3 => Some(Val::Vector(v.to_vec())),
        (Ty::NumOrVec2, Value::Num(x)) => Some(Val::Vector(vec![x; 2])),
        (Ty::NumOrVec2, Value::Vector(v)) if v.len() == 2 => Some(Val::Vector(v.to_vec())),
        (Ty::Matrix, Value::Vector(v)) if v.len() == 12 || v.len() == 16 => {
            Some(Val::Vector(v.to_vec()))
        }
        (Ty::Color, Value::Color(c)) => Some(Val::Color(c)),
        (Ty::Str, Value::Str(s)) => Some(Val::Str(s.to_string())),
        (Ty::Bool, Value::Bool(b)) => Some(Val::Bool(b)),
        (ty, other) => {
            let help = match (ty, &other) {
                (Ty::Color, Value::Vector(v)) if v.len() == 3 => format!(
                    "colours are written with `rgb`: `{} rgb <{}, {}, {}>`",
                    spec.name, v[0], v[1], v[2]
                ),
                (Ty::Color, Value::Num(x)) => {
                    format!("colours are written with `rgb`: `{} rgb {x}`", spec.name)
                }
                _ => format!("write e.g. `{} {}`", spec.name, spec.example),
            };
            diags.push(
                Diagnostic::error(
                    codes::TYPE_MISMATCH,
                    format!(
                        "`{}` expects {}, found {}",
                        spec.name,
                        ty.describe(),
                        other.type_name()
                    ),
                    value.span,
                )
                .with_label(format!("this is {}", other.type_name()))
                .with_help(help),
            );
            return None;
        }
    };
    ok
}

/// The word of a word list (`type conductor`, `preset gold`) that `value`
/// names, or the error with the word it was meant to be.
fn word_value(
    spec: &ParamSpec,
    words: &'static [&'static str],
    value: &Expr,
    diags: &mut Diagnostics,
) -> Option<Val> {
    if let ExprKind::Str(text) = &value.kind {
        diags.push(word_as_string(spec, text, value.span, words));
        return None;
    }
    let ExprKind::Name(w) = &value.kind else {
        diags.push(
            Diagnostic::error(
                codes::TYPE_MISMATCH,
                format!("`{}` expects {}", spec.name, spec.ty.describe()),
                value.span,
            )
            .with_label("not one of the accepted words")
            .with_help(format!("write e.g. `{} {}`", spec.name, spec.example)),
        );
        return None;
    };
    if words.contains(&w.as_str()) {
        return Some(Val::Word(w.clone()));
    }
    let metal = (words == METAL_PRESETS).then(|| other_metal(w));
    // Mitsuba's plugin names as a material's `type` (`roughconductor`).
    let foreign = || {
        let hint = (spec.name == "type").then(|| foreign_type(w));
        hint.flatten().map(str::to_string)
    };
    let help = match (
        metal.flatten().or_else(foreign),
        did_you_mean(w, words.iter().copied()),
    ) {
        (Some(help), _) => help,
        (None, Some(s)) => format!("did you mean `{s}`?"),
        (None, None) => format!("use one of {}", words.join(", ")),
    };
    diags.push(
        Diagnostic::error(
            codes::UNKNOWN_WORD,
            format!("unknown {} `{w}`", spec.name),
            value.span,
        )
        .with_label(format!("not a known {}", spec.name))
        .with_help(help),
    );
    None
}
