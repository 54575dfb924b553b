//! The checker's answers to POV-Ray's forms inside blocks: a block ptsc
//! does not have (`pigment { … }`) and values without parameter names
//! (`sphere { <0, 1, 0>, 1 }`). The words' hints are in
//! `syntax/povray.rs`; the positional order of each shape is in its row
//! of `params.rs` ([`super::schema::povray_positional`]).

use super::eval::{eval, written, Env, Value};
use super::schema::{ParamSpec, Positional, Ty};
use crate::diag::{codes, did_you_mean, Diagnostic, Diagnostics};
use crate::span::Span;
use crate::syntax::ast::{Expr, Ident};

/// The error for `name { … }` inside the block `what` (with the
/// parameters `schemas`; `all`: the words it accepts, a `material` among
/// them where it takes one), at `span`.
pub fn foreign_block(
    what: &str,
    name: &Ident,
    span: Span,
    (schemas, all): (&[&'static [ParamSpec]], &[&'static str]),
) -> Diagnostic {
    let word = name.name.as_str();
    let takes_materials = (schemas.iter().flat_map(|s| s.iter()))
        .any(|p| p.name == word && p.ty == super::schema::Ty::Materials);
    if takes_materials {
        return Diagnostic::error(
            codes::FOREIGN_BLOCK,
            format!("`{word}` holds names in quotes, each with a material"),
            span,
        )
        .with_label("not a name in quotes and a material")
        .with_help(format!(
            "write the file's material names in quotes: `{word} {{ \"Leaf\" green  \"Bark\" material {{ diffuse rgb 0.3 }} }}`"
        ));
    }
    if (schemas.iter().flat_map(|s| s.iter())).any(|p| p.name == word) {
        return Diagnostic::error(
            codes::FOREIGN_BLOCK,
            format!("`{word}` takes a value, not a block"),
            span,
        )
        .with_label("a parameter written as a block")
        .with_help(format!(
            "write `{word} VALUE`, or a texture as `{word} KIND {{ … }}` (e.g. `{word} checker {{ … }}`) where `{word}` takes one"
        ));
    }
    let help = match crate::syntax::povray::block(word) {
        Some(hint) => hint.to_string(),
        None => match did_you_mean(word, all.iter().copied()) {
            Some(s) => format!("did you mean the parameter `{s}`?"),
            None => format!("`{what}` accepts {}", all.join(", ")),
        },
    };
    let message = if crate::syntax::povray::block(word).is_some() {
        let renderer = crate::syntax::povray::renderer(word);
        format!("{renderer}'s `{word} {{ … }}` is not ptsc")
    } else {
        format!("unknown block `{word}` in `{what}`")
    };
    Diagnostic::error(codes::FOREIGN_BLOCK, message, span)
        .with_label("a block ptsc does not have here")
        .with_help(help)
}

/// The error for `values` written without parameter names in the block
/// `what`, at `span`: the block written with the names they stand for
/// where the kind has a POV-Ray order (`row`, from the kind table) and the
/// values evaluate; with the names of the parameters the values stand for.
pub fn positional(
    (what, row): (&str, Option<Positional>),
    (values, span): (&[Expr], Span),
    schemas: &[&'static [ParamSpec]],
    env: &mut Env,
) -> (Diagnostic, &'static [&'static str]) {
    let help = match row {
        Some((names, note)) => {
            let rewritten = rewrite(what, names, values, (schemas, env)).unwrap_or_else(|| {
                names
                    .iter()
                    .map(|n| format!("{n} …"))
                    .collect::<Vec<_>>()
                    .join(" ")
            });
            let note = if note.is_empty() {
                String::new()
            } else {
                format!(" ({note})")
            };
            format!("ptsc names each value: `{what} {{ {rewritten} }}`{note}")
        }
        None => format!("ptsc names each value: `{what} {{ name value … }}`"),
    };
    let d = Diagnostic::error(
        codes::POSITIONAL_VALUES,
        format!("values without parameter names in `{what}`"),
        span,
    )
    .with_label("POV-Ray's positional form")
    .with_help(help);
    (d, row.map_or(&[][..], |(names, _)| names))
}

/// `name value …` for `values` under `names`, from their evaluated values
/// (a plane's distance becomes a point on it, a number where a vector goes
/// the vector POV-Ray makes of it); `None` when a value does not evaluate
/// or the counts differ.
fn rewrite(
    kind: &str,
    names: &[&str],
    values: &[Expr],
    (schemas, env): (&[&'static [ParamSpec]], &mut Env),
) -> Option<String> {
    if names.len() != values.len() {
        return None;
    }
    let mut quiet = Diagnostics::default();
    let mut evaluated = Vec::with_capacity(values.len());
    for v in values {
        evaluated.push(eval(v, env, &mut quiet)?);
    }
    if kind == "plane" {
        // POV-Ray's plane { N, D }: the points p with p · N/|N| = D.
        let (Value::Vector(n), Value::Num(d)) = (&evaluated[0], &evaluated[1]) else {
            return None;
        };
        let length = n.iter().map(|x| x * x).sum::<f64>().sqrt();
        if n.len() != 3 || length == 0.0 {
            return None;
        }
        // (Rounded to a millionth: the help is read, `<1.414214, …>`.)
        let point: Vec<f64> = n
            .iter()
            .map(|x| (x / length * d * 1e6).round() / 1e6)
            .collect();
        evaluated[1] = Value::Vector(point.into());
    }
    if kind == "box" {
        // POV-Ray takes any two opposite corners; ptsc the smaller first.
        if let (Value::Vector(a), Value::Vector(b)) = (&evaluated[0], &evaluated[1]) {
            let lo: Vec<f64> = a.iter().zip(b.iter()).map(|(x, y)| x.min(*y)).collect();
            let hi: Vec<f64> = a.iter().zip(b.iter()).map(|(x, y)| x.max(*y)).collect();
            evaluated = vec![Value::Vector(lo.into()), Value::Vector(hi.into())];
        }
    }
    for (value, name) in evaluated.iter_mut().zip(names) {
        // POV-Ray's `sphere { 0, 1 }`: the centre <0, 0, 0>.
        if let Value::Num(n) = *value {
            if takes_vector(schemas, name) {
                *value = Value::Vector(vec![n; 3].into());
            }
        }
    }
    let pairs: Vec<String> = names
        .iter()
        .zip(&evaluated)
        .map(|(n, v)| format!("{n} {}", written(v)))
        .collect();
    Some(pairs.join(" "))
}

/// Whether the parameter `name` of `schemas` takes only a vector of 3.
fn takes_vector(schemas: &[&'static [ParamSpec]], name: &str) -> bool {
    (schemas.iter().flat_map(|s| s.iter())).any(|p| p.name == name && p.ty == Ty::Vec3)
}

/// The error for a name alone before the `}` of the block `what`:
/// POV-Ray's flag (`no_shadow`), or a parameter without its value (its
/// row `spec` where the block has it: the help writes its example; a word
/// the block does not have may be a material's name where it
/// `takes_material`).
pub fn flag(
    what: &str,
    name: &Ident,
    (spec, takes_material): (Option<&ParamSpec>, bool),
    schemas: &[&'static [ParamSpec]],
) -> Diagnostic {
    let word = name.name.as_str();
    if let Some(hint) = crate::syntax::povray::flag(word) {
        return Diagnostic::error(
            codes::UNKNOWN_PARAM,
            format!("`{word}` is a POV-Ray flag"),
            name.span,
        )
        .with_label(format!("not a parameter of `{what}`"))
        .with_help(hint);
    }
    // The block's own first parameter as the example of a name and a value.
    let first = (schemas.iter().flat_map(|s| s.iter())).find(|p| p.povray.is_none());
    let example = first.map_or("radius 1".to_string(), |p| {
        format!("{} {}", p.name, p.example)
    });
    let help = match (spec, takes_material) {
        (Some(spec), _) => format!("write `{word} {}`", spec.example),
        (None, true) => format!(
            "a parameter is a name and a value (e.g. `{example}`); a material is given as `material {word}`"
        ),
        (None, false) => format!("a parameter is a name and a value (e.g. `{example}`)"),
    };
    Diagnostic::error(
        codes::MISSING_VALUE,
        format!("`{word}` has no value"),
        name.span,
    )
    .with_label("a name without a value")
    .with_help(help)
}

/// The error for POV-Ray's directive `#name`, spanning the `#` and the
/// word.
pub fn directive(name: &Ident) -> Diagnostic {
    let word = name.name.as_str();
    let (start, end) = (name.span.start as usize, name.span.end as usize);
    let span = Span::new(name.span.file, start.saturating_sub(1), end);
    let help = crate::syntax::povray::directive(word).map_or_else(
        || "ptsc has no `#` directives: write its statements without `#`: `let`, `include`, `for`, `if`, …".to_string(),
        str::to_string,
    );
    Diagnostic::error(
        codes::DIRECTIVE,
        format!("`#{word}` is a POV-Ray directive"),
        span,
    )
    .with_label("not ptsc")
    .with_help(help)
}
