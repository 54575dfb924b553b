//! Compile-time evaluation of expressions: numbers, vectors, colours,
//! strings, booleans, lists, functions, names and conditionals.
//!
//! Evaluation is bounded: expressions nest at most
//! [`crate::syntax::MAX_NESTING`] deep as written; calls of user
//! functions at most [`MAX_CALL_DEPTH`] deep (a recursion without an end
//! is a diagnostic, not a stack overflow) and [`MAX_CALLS`] in all; lists
//! and strings hold at most [`MAX_ITEMS`] items and [`MAX_STRING`] bytes,
//! lists nest at most [`MAX_LIST_DEPTH`] deep; and the work of all
//! evaluation together is bounded by a budget of steps
//! ([`budget::MAX_WORK`]), so that no expression, however small its text,
//! costs more than its share of it.

mod budget;
mod builtins;
mod env;
mod limits;
mod operators;
mod povray;
mod value;

pub use budget::{MAX_SUGGESTIONS, MAX_WORK};
pub use builtins::{random, FUNCTIONS, FUNCTION_DOCS};
pub use env::{Binding, Env, Unrun};
pub use limits::*;
pub use povray::{component_names, written};
pub use value::{shown, Function, List, Value, MAX_LIST_DEPTH};

use crate::diag::codes;
use crate::diag::{Diagnostic, Diagnostics};
use crate::span::Span;
use crate::syntax::ast::{BinOp, Expr, ExprKind, Ident};
use operators::{binary, index, Operands};

/// Evaluates `e`; on failure the reason is in `diags` and `None` is returned.
pub fn eval(e: &Expr, env: &mut Env, diags: &mut Diagnostics) -> Option<Value> {
    if env.depth >= MAX_EVAL_DEPTH {
        if !env.exhausted {
            env.exhausted = true;
            diags.push(
                Diagnostic::error(
                    codes::RECURSION_LIMIT,
                    format!("evaluation nests deeper than {MAX_EVAL_DEPTH} levels"),
                    e.span,
                )
                .with_label("too deep here")
                .with_help("functions that call functions multiply the depth of their expressions; use `let` for parts of them"),
            );
        }
        return None;
    }
    // An expression that a loop or a function runs again costs a step
    // (once, at the top level, its text bounds it); what an operation
    // makes costs by its size besides (`Env::made`).
    if (env.repeating > 0 || env.call_depth > 0) && !env.charge(1, e.span, diags) {
        return None;
    }
    env.depth += 1;
    let v = eval_inner(e, env, diags);
    env.depth -= 1;
    match e.kind {
        // What an operation computes is checked where it is computed (a
        // chain's every step, a built-in's result, a literal); a name, an
        // item or a function's result is a value checked before, and a
        // long vector is not walked again each time it is passed on.
        ExprKind::Number(_) => finite(v?, e.span, true, diags),
        _ => v,
    }
}

/// Evaluates a condition: `Some(true or false)`, or `None` after a
/// diagnostic (not a boolean, or broken).
pub fn condition(e: &Expr, env: &mut Env, diags: &mut Diagnostics) -> Option<bool> {
    match eval(e, env, diags)? {
        Value::Bool(b) => Some(b),
        other => {
            diags.push(
                Diagnostic::error(
                    codes::TYPE_MISMATCH,
                    format!(
                        "a condition must be `true` or `false`, found {}",
                        other.type_name()
                    ),
                    e.span,
                )
                .with_label(format!("this is {}", other.type_name()))
                .with_help("compare values to make a condition: `x > 0`, `name == \"final\"`"),
            );
            None
        }
    }
}

/// `v` if every number in it is finite; else reports it at `span` (the
/// smallest expression that produced it) and returns `None`.
fn finite(v: Value, span: Span, literal: bool, diags: &mut Diagnostics) -> Option<Value> {
    let ok = match &v {
        Value::Num(x) => x.is_finite(),
        Value::Vector(v) => v.iter().all(|x| x.is_finite()),
        Value::Color(c) => c.iter().all(|x| x.is_finite()),
        _ => true,
    };
    if ok {
        return Some(v);
    }
    let overflow = match &v {
        Value::Num(x) => x.is_infinite(),
        Value::Vector(v) => v.iter().any(|x| x.is_infinite()),
        Value::Color(c) => c.iter().any(|x| x.is_infinite()),
        _ => false,
    };
    let (msg, label, help) = match (literal, overflow) {
        (true, _) => (
            "number too large",
            "this is not finite",
            "numbers must fit a 64-bit float (about 1.8e308)",
        ),
        (false, true) => (
            "the result is too large: beyond the ±1.8e308 of a 64-bit float",
            "this overflows",
            "scale the values down, or divide by a larger number; `pow`, `exp` and products of large numbers grow fast",
        ),
        (false, false) => (
            "the result is not a number (NaN)",
            "this is NaN",
            "an intermediate value overflowed (∞ − ∞, 0 × ∞); scale the values down",
        ),
    };
    diags.push(
        Diagnostic::error(codes::NOT_FINITE, msg, span)
            .with_label(label)
            .with_help(help),
    );
    None
}

fn eval_inner(e: &Expr, env: &mut Env, diags: &mut Diagnostics) -> Option<Value> {
    match &e.kind {
        ExprKind::Number(x) => Some(Value::Num(*x)),
        ExprKind::Str(s) if s.len() > limits::MAX_STRING => {
            // The bound of a string built by `+` holds for one written out.
            diags.push(env::too_large(format!("{} bytes", s.len()), e.span));
            None
        }
        ExprKind::Str(s) => {
            // A literal run again is copied again: a long one costs by its size.
            let v = Value::Str(s.as_str().into());
            let repeated = env.repeating > 0 || env.call_depth > 0;
            (!repeated || env.charge(v.weight(), e.span, diags)).then_some(v)
        }
        ExprKind::Bool(b) => Some(Value::Bool(*b)),
        ExprKind::Vector(items) => vector(items, env, diags),
        ExprKind::Color(inner) => color(inner, env, diags),
        ExprKind::Name(name) => name_value(name, e.span, env, diags),
        ExprKind::Neg(inner) => negate(inner, e.span, env, diags),
        ExprKind::Not(inner) => match eval(inner, env, diags)? {
            Value::Bool(b) => Some(Value::Bool(!b)),
            other => {
                diags.push(
                    Diagnostic::error(
                        codes::TYPE_MISMATCH,
                        format!("`!` needs `true` or `false`, found {}", other.type_name()),
                        e.span,
                    )
                    .with_label(format!("this is {}", other.type_name()))
                    .with_help("`!` turns a condition around: `!(x > 0)`"),
                );
                None
            }
        },
        ExprKind::List(items) => {
            let mut out = Vec::with_capacity(items.len());
            let mut ok = true;
            for it in items {
                match eval(it, env, diags) {
                    Some(v) => out.push(v),
                    None => ok = false,
                }
            }
            if !ok {
                return None;
            }
            env.new_list(out, e.span, diags)
        }
        ExprKind::Index { base, indexes } => {
            let mut v = eval(base, env, diags)?;
            let mut at = base.span;
            for ix in indexes {
                let i = eval(ix, env, diags)?;
                // A string is indexed by its characters, counted from its start.
                if matches!(v, Value::Str(_)) && !env.charge(v.weight(), at, diags) {
                    return None;
                }
                v = index(v, i, at, ix.span, diags)?;
                at = at.join(ix.span);
            }
            Some(v)
        }
        ExprKind::Member { base, member } => {
            let v = eval(base, env, diags)?;
            povray::member(v, base.span, member, diags)
        }
        ExprKind::FilterColor { word, value } => {
            let v = eval(value, env, diags);
            diags.push(povray::filter_color(word, v, e));
            None
        }
        ExprKind::If { arms, otherwise } => {
            // Only the chosen arm is evaluated: a recursion ends in the arm
            // that does not call again.
            for (k, (cond, value)) in arms.iter().enumerate() {
                if condition(cond, env, diags)? {
                    // What is not evaluated: its names are not unused.
                    for (c, v) in &arms[k + 1..] {
                        env.untaken.insert(c.span);
                        not_evaluated(v, env);
                    }
                    not_evaluated(otherwise, env);
                    env.ran.insert(value.span);
                    return eval(value, env, diags);
                }
                not_evaluated(value, env);
            }
            env.ran.insert(otherwise.span);
            eval(otherwise, env, diags)
        }
        ExprKind::Chain { first, rest } if matches!(rest[0].0, BinOp::And | BinOp::Or) => {
            // `a && b && c` (or `||`): stops at the first operand that
            // decides, as in C and Rust, so `i < len(xs) && xs[i] > 0`
            // never indexes out of range.
            let and = rest[0].0 == BinOp::And;
            let operands = std::iter::once(&**first).chain(rest.iter().map(|r| &r.2));
            for operand in operands {
                if condition(operand, env, diags)? != and {
                    return Some(Value::Bool(!and));
                }
            }
            Some(Value::Bool(and))
        }
        ExprKind::Chain { first, rest } => fold_chain(first, rest, env, diags),
        ExprKind::Call { func, args } => call(func, args, e.span, env, diags),
    }
}

/// `<a, b, …>`: a vector of numbers.
fn vector(items: &[Expr], env: &mut Env, diags: &mut Diagnostics) -> Option<Value> {
    let mut out = Vec::with_capacity(items.len());
    let mut ok = true;
    for it in items {
        match eval(it, env, diags) {
            Some(Value::Num(x)) => out.push(x),
            Some(other) => {
                diags.push(
                    Diagnostic::error(
                        codes::TYPE_MISMATCH,
                        format!(
                            "a vector component must be a number, found {}",
                            other.type_name()
                        ),
                        it.span,
                    )
                    .with_label("not a number")
                    .with_help("vectors hold numbers: `<1, 2, 3>`"),
                );
                ok = false;
            }
            None => ok = false,
        }
    }
    ok.then_some(Value::Vector(out.into()))
}

/// `rgb value`: a grey level, an `<r, g, b>` triple or a colour.
fn color(inner: &Expr, env: &mut Env, diags: &mut Diagnostics) -> Option<Value> {
    match eval(inner, env, diags)? {
        Value::Num(x) => Some(Value::Color([x; 3])),
        Value::Vector(v) if v.len() == 3 => Some(Value::Color([v[0], v[1], v[2]])),
        Value::Color(c) => Some(Value::Color(c)),
        other => {
            diags.push(
                Diagnostic::error(
                    codes::TYPE_MISMATCH,
                    format!(
                        "`rgb` needs a number or a vector of 3, found {}",
                        other.type_name()
                    ),
                    inner.span,
                )
                .with_label("not a grey level or an <r, g, b> triple")
                .with_help("write `rgb <0.8, 0.2, 0.1>` or `rgb 0.5`"),
            );
            None
        }
    }
}

/// The error for a call of `func`, which is neither built in nor declared:
/// POV-Ray's word for it, a did-you-mean, or the built-in functions.
pub fn unknown_function(func: &Ident, env: &mut Env) -> Diagnostic {
    let built_in: Vec<&str> = FUNCTIONS.iter().map(|(n, _)| *n).collect();
    let pov = crate::syntax::povray::function(&func.name);
    let help = match pov
        .map(str::to_string)
        .or_else(|| env.suggest_name(&func.name, &built_in))
    {
        Some(hint) if pov.is_some() => hint,
        Some(s) => format!("did you mean `{s}`?"),
        None => format!(
            "the built-in functions are {}; declare your own with `fn {}(x) = …;`",
            built_in.join(", "),
            func.name
        ),
    };
    Diagnostic::error(
        codes::UNKNOWN_FUNCTION,
        format!("unknown function `{}`", func.name),
        func.span,
    )
    .with_label("no such function")
    .with_help(help)
}

/// Records the arm `value` of an `if` expression as not evaluated (kept
/// the first time for the checks without values: `check::unrun`).
fn not_evaluated(value: &Expr, env: &mut Env) {
    if env.untaken.insert(value.span) {
        env.unrun.push(Unrun::Value(value.clone()));
    }
}

/// The value of `name`, used at `span`, or why there is none.
fn name_value(name: &str, span: Span, env: &mut Env, diags: &mut Diagnostics) -> Option<Value> {
    if let Some(v) = env.lookup(name, span) {
        return v;
    }
    diags.push(unknown_name(name, span, env));
    if env.unknown_names.len() < env::MAX_UNKNOWN_KEPT {
        env.unknown_names.push((name.to_string(), span));
    }
    None
}

/// The error for the name `name`, used at `span`, that nothing defines:
/// the ptsc word for a POV-Ray one, or a did-you-mean.
pub fn unknown_name(name: &str, span: Span, env: &mut Env) -> Diagnostic {
    let d = Diagnostic::error(codes::UNKNOWN_NAME, format!("unknown name `{name}`"), span)
        .with_label("not defined");
    let texture = crate::check::schema::TEXTURE_KINDS.contains(&name).then(|| {
        format!("`{name}` is a texture, written with its block: `diffuse {name} {{ … }}` (POV-Ray's `pigment {{ {name} … }}`; docs/language.md, \"Textures\", lists its parameters)")
    });
    // `RGB`, `True`: a ptsc word in other letters (POV-Ray's are case-blind).
    let lower = name.to_ascii_lowercase();
    let case = (lower != name && crate::syntax::words::KEYWORDS.contains(&lower.as_str()))
        .then(|| format!("ptsc's words are lower case: `{lower}`"));
    match (
        (crate::syntax::povray::hint(name).map(str::to_string))
            .or(texture)
            .or(case),
        env.suggest_name(name, &[]),
    ) {
        (Some(hint), _) => d.with_help(hint),
        (None, Some(s)) => d.with_help(format!("did you mean `{s}`?")),
        (None, None) => d.with_help(format!("define it first with `let {name} = …;`")),
    }
}

/// `-value` at `span`: a number, vector or colour negated.
fn negate(inner: &Expr, span: Span, env: &mut Env, diags: &mut Diagnostics) -> Option<Value> {
    match eval(inner, env, diags)? {
        Value::Num(x) => Some(Value::Num(-x)),
        Value::Vector(v) => {
            // Counted before it is made: a budget spent stops the work.
            let weight = Value::Vector(v.clone()).weight();
            if !env.charge(weight, span, diags) {
                return None;
            }
            Some(Value::Vector(v.iter().map(|x| -x).collect()))
        }
        Value::Color(c) => Some(Value::Color(c.map(|x| -x))),
        other => {
            diags.push(
                Diagnostic::error(
                    codes::TYPE_MISMATCH,
                    format!("cannot negate {}", other.type_name()),
                    span,
                )
                .with_label("`-` needs a number, vector or colour")
                .with_help("remove the minus sign"),
            );
            None
        }
    }
}

/// `a op b op c …` (not `&&` or `||`): left to right, as `((a op b) op c)
/// …`; every operand is evaluated (all their mistakes reported), the fold
/// stops at the first failure.
fn fold_chain(
    first: &Expr,
    rest: &[(BinOp, Span, Expr)],
    env: &mut Env,
    diags: &mut Diagnostics,
) -> Option<Value> {
    // Left to right, as `((a op b) op c) …`: every operand is
    // evaluated (all their mistakes reported), the fold stops at the
    // first failure.
    let mut acc = eval(first, env, diags);
    let mut acc_span = first.span;
    // `rgb 0.5 + 0.1` is `(rgb 0.5) + 0.1`: worth a hint when it fails.
    let mut bare_rgb = matches!(first.kind, ExprKind::Color(_));
    for (op, op_span, operand) in rest {
        let b = eval(operand, env, diags);
        let span = acc_span.join(operand.span);
        let at = Operands {
            lhs: acc_span,
            op: *op_span,
            rhs: operand.span,
            bare_rgb,
        };
        acc = match (acc, b) {
            (Some(a), Some(b)) => {
                binary(*op, a, b, at, env, diags).and_then(|v| finite(v, span, false, diags))
            }
            _ => None,
        };
        acc_span = span;
        bare_rgb = false;
    }
    acc
}

/// A call of `func` with `args` at `span`: a user function, or a built-in
/// one with the right number of arguments.
fn call(
    func: &Ident,
    args: &[Expr],
    span: Span,
    env: &mut Env,
    diags: &mut Diagnostics,
) -> Option<Value> {
    let builtin = FUNCTIONS.iter().find(|(n, _)| *n == func.name);
    match env.lookup(&func.name, func.span) {
        Some(Some(Value::Function(f))) => return call_user(&f, args, span, env, diags),
        // Its declaration failed and said why.
        Some(None) if builtin.is_none() => return None,
        Some(Some(v)) if builtin.is_none() => {
            diags.push(
                Diagnostic::error(
                    codes::TYPE_MISMATCH,
                    format!("`{}` is not a function", func.name),
                    func.span,
                )
                .with_label(format!("this is {}", v.type_name()))
                .with_help("declare a function with `fn name(x) = …;`"),
            );
            return None;
        }
        _ => {}
    }
    let Some(&(_, (least, most))) = builtin else {
        diags.push(unknown_function(func, env));
        return None;
    };
    if !(least..=most).contains(&args.len()) {
        let takes = if least == most {
            format!("{least} argument{}", if least == 1 { "" } else { "s" })
        } else {
            format!("{least} or {most} arguments")
        };
        diags.push(
            Diagnostic::error(
                codes::WRONG_ARGUMENT_COUNT,
                format!("`{}` takes {takes}, found {}", func.name, args.len()),
                span,
            )
            .with_label("wrong number of arguments")
            .with_help(format!(
                "call it as `{}({})`",
                func.name,
                vec!["x"; least].join(", ")
            )),
        );
        return None;
    }
    let mut vals = Vec::new();
    for a in args {
        vals.push(eval(a, env, diags));
    }
    let vals: Option<Vec<Value>> = vals.into_iter().collect();
    builtins::call(&func.name, &vals?, args, span, env, diags)
        .and_then(|v| finite(v, span, false, diags))
}

/// Calls the user function `f` with `args` (evaluated here, in the
/// caller's scope); its body sees its parameters and the file's names.
fn call_user(
    f: &Function,
    args: &[Expr],
    span: Span,
    env: &mut Env,
    diags: &mut Diagnostics,
) -> Option<Value> {
    if args.len() != f.params.len() {
        diags.push(
            Diagnostic::error(
                codes::WRONG_ARGUMENT_COUNT,
                format!(
                    "`{}` takes {} argument{}, found {}",
                    f.name,
                    f.params.len(),
                    if f.params.len() == 1 { "" } else { "s" },
                    args.len()
                ),
                span,
            )
            .with_label("wrong number of arguments")
            .with_help(format!(
                "call it as `{}({})`",
                f.name,
                (f.params.iter().map(|(p, _)| p.as_str()))
                    .collect::<Vec<_>>()
                    .join(", ")
            )),
        );
        return None;
    }
    let mut vals = Vec::with_capacity(args.len());
    for a in args {
        vals.push(eval(a, env, diags));
    }
    let vals: Vec<Value> = vals.into_iter().collect::<Option<_>>()?;
    if env.exhausted {
        return None;
    }
    env.calls += 1;
    if env.call_depth >= MAX_CALL_DEPTH || env.calls > MAX_CALLS {
        env.exhausted = true;
        let (message, help) = if env.call_depth >= MAX_CALL_DEPTH {
            (
                format!("calls of functions nest deeper than {MAX_CALL_DEPTH}"),
                "a function that calls itself needs an `if` whose other arm stops calling: `fn f(n) = if n <= 0 { 1 } else { n * f(n - 1) };`",
            )
        } else {
            (
                format!("functions are called more than {MAX_CALLS} times"),
                "a function that calls itself twice doubles its calls at every level; compute such values with a loop",
            )
        };
        diags.push(
            Diagnostic::error(codes::RECURSION_LIMIT, message, span)
                .with_label(format!("in this call of `{}`", f.name))
                .with_help(help),
        );
        return None;
    }
    let outer_base = env.base;
    env.push();
    env.base = env.frames.len() - 1;
    env.call_depth += 1;
    for ((name, def), v) in f.params.iter().zip(vals) {
        let def = *def;
        env.bind(
            name,
            Binding {
                value: Some(v),
                def,
            },
        );
    }
    let v = eval(&f.body, env, diags);
    env.call_depth -= 1;
    env.base = outer_base;
    env.pop();
    v
}

#[cfg(test)]
mod tests;
