//! Indexing and the binary operators: arithmetic on numbers, vectors and
//! colours, joining strings and lists, comparisons. Each counts its work
//! before doing it ([`Env::charge`], [`Env::charge_items`]).

use super::env::{too_large, Env};
use super::limits::{MAX_ITEMS, MAX_STRING};
use super::value::{self, Value};
use crate::diag::{codes, Diagnostic, Diagnostics};
use crate::span::Span;
use crate::syntax::ast::BinOp;

/// `v[i]`: an item of a list, a component of a vector or colour, a
/// character of a string.
pub(super) fn index(
    v: Value,
    i: Value,
    at: Span,
    i_span: Span,
    diags: &mut Diagnostics,
) -> Option<Value> {
    let len = match &v {
        Value::List(l) => l.items.len(),
        Value::Vector(x) => x.len(),
        Value::Color(_) => 3,
        Value::Str(s) => s.chars().count(),
        other => {
            diags.push(
                Diagnostic::error(
                    codes::TYPE_MISMATCH,
                    format!("cannot index {}", other.type_name()),
                    at,
                )
                .with_label(format!("this is {}", other.type_name()))
                .with_help("lists, vectors, colours and strings are indexed: `xs[0]`"),
            );
            return None;
        }
    };
    let k = match i {
        Value::Num(x) if x.fract() == 0.0 => x,
        other => {
            diags.push(
                Diagnostic::error(
                    codes::TYPE_MISMATCH,
                    format!(
                        "an index must be a whole number, found {}",
                        match other {
                            Value::Num(x) => value::shown(x),
                            o => o.type_name(),
                        }
                    ),
                    i_span,
                )
                .with_label("not a whole number")
                .with_help("index from 0: `xs[0]` is the first item; `floor` rounds down"),
            );
            return None;
        }
    };
    if k < 0.0 || k >= len as f64 {
        diags.push(
            Diagnostic::error(
                codes::INDEX_OUT_OF_RANGE,
                format!(
                    "index {} is out of range for {}",
                    value::shown(k),
                    v.type_name()
                ),
                i_span,
            )
            .with_label(if len == 0 {
                "it is empty".to_string()
            } else {
                format!("valid indexes are 0 to {}", len - 1)
            })
            .with_secondary(at, v.type_name())
            .with_help("index from 0; `len(xs)` is one past the last index"),
        );
        return None;
    }
    let k = k as usize;
    Some(match v {
        Value::List(l) => l.items[k].clone(),
        Value::Vector(x) => Value::Num(x[k]),
        Value::Color(c) => Value::Num(c[k]),
        Value::Str(s) => {
            let c = s.chars().nth(k).map(String::from).unwrap_or_default();
            Value::Str(c.into())
        }
        _ => unreachable!("checked above"),
    })
}

/// Where the parts of one operation are written.
#[derive(Debug, Clone, Copy)]
pub(super) struct Operands {
    /// The left operand (everything folded so far).
    pub(super) lhs: Span,
    /// The operator.
    pub(super) op: Span,
    /// The right operand.
    pub(super) rhs: Span,
    /// Whether the left operand is a bare `rgb x`, which takes only `x`.
    pub(super) bare_rgb: bool,
}

/// A type mismatch labelled at the operator (so that the operands' labels
/// fall under the operands, not all at the end of the expression).
fn mismatch(at: Operands, msg: String, help: &str) -> Diagnostic {
    let help = if at.bare_rgb {
        "`rgb` takes only the value right after it (`rgb 0.5 + 0.1` is `(rgb 0.5) + 0.1`): to make a colour of the whole expression, put it in brackets, `rgb (0.5 + 0.1)`"
    } else {
        help
    };
    Diagnostic::error(codes::TYPE_MISMATCH, msg, at.op)
        .with_label("incompatible operands")
        .with_help(help.to_string())
}

pub(super) fn binary(
    op: BinOp,
    a: Value,
    b: Value,
    at: Operands,
    env: &mut Env,
    diags: &mut Diagnostics,
) -> Option<Value> {
    let (a_span, b_span) = (at.lhs, at.rhs);
    use Value::*;
    match (op, &a, &b) {
        (BinOp::Eq | BinOp::Ne, _, _) => {
            // Two lists of a million items are compared item by item, each
            // a step of the budget: a loop of such comparisons stops.
            let Some(same) = value::equal(&a, &b, &mut env.work) else {
                env.out_of_work(a_span.join(b_span), diags);
                return None;
            };
            return Some(Bool(same == (op == BinOp::Eq)));
        }
        (BinOp::Lt | BinOp::Le | BinOp::Gt | BinOp::Ge, Num(x), Num(y)) => {
            return Some(Bool(match op {
                BinOp::Lt => x < y,
                BinOp::Le => x <= y,
                BinOp::Gt => x > y,
                _ => x >= y,
            }))
        }
        (BinOp::Lt | BinOp::Le | BinOp::Gt | BinOp::Ge, _, _) => {
            diags.push(
                mismatch(
                    at,
                    format!(
                        "cannot order {} and {} with `{}`",
                        a.type_name(),
                        b.type_name(),
                        op.symbol()
                    ),
                    "`<`, `<=`, `>` and `>=` compare numbers; `==` and `!=` compare any two values",
                )
                .with_secondary(a_span, a.type_name())
                .with_secondary(b_span, b.type_name()),
            );
            return None;
        }
        (BinOp::Add, Str(x), Str(y)) => {
            let (n, span) = (x.len() + y.len(), a_span.join(b_span));
            if n > MAX_STRING {
                diags.push(too_large(format!("{n} bytes"), span));
                return None;
            }
            let label = || "this is a string".to_string();
            if !(env.charge(n as u64 / 16, span, diags)
                && env.charge_items_as(n / 16, label, span, diags))
            {
                return None;
            }
            return Some(Str(format!("{x}{y}").into()));
        }
        (BinOp::Add, Str(_), _) | (BinOp::Add, _, Str(_)) => {
            diags.push(
                mismatch(
                    at,
                    format!("cannot add {} and {}", a.type_name(), b.type_name()),
                    "strings join with strings: turn a number into one with `str(x)`, as in `\"tree\" + str(i) + \".obj\"`",
                )
                .with_secondary(a_span, a.type_name())
                .with_secondary(b_span, b.type_name()),
            );
            return None;
        }
        (BinOp::Add, List(x), List(y)) => {
            let (n, span) = (x.items.len() + y.items.len(), a_span.join(b_span));
            if n > MAX_ITEMS {
                diags.push(too_large(format!("a list of {n}"), span));
                return None;
            }
            // Counted before the copy: a refused one costs nothing.
            if !env.charge_items(n, span, diags) {
                return None;
            }
            return Some(Value::list(
                x.items.iter().chain(&y.items).cloned().collect(),
            ));
        }
        (BinOp::And | BinOp::Or, _, _) => unreachable!("`&&` and `||` are evaluated lazily"),
        _ => {}
    }
    arithmetic(op, a, b, at, env, diags)
}

/// `a op b` for `+`, `-`, `*`, `/` and `%` on numbers, vectors and
/// colours, component by component (a vector or colour scaled by a
/// number), or why it cannot be.
fn arithmetic(
    op: BinOp,
    a: Value,
    b: Value,
    at: Operands,
    env: &mut Env,
    diags: &mut Diagnostics,
) -> Option<Value> {
    let (a_span, b_span) = (at.lhs, at.rhs);
    use Value::*;
    let f = |x: f64, y: f64| match op {
        BinOp::Add => x + y,
        BinOp::Sub => x - y,
        BinOp::Mul => x * y,
        BinOp::Div => x / y,
        BinOp::Rem => x % y,
        _ => unreachable!("comparisons are handled above"),
    };
    // Each component of a vector is computed: counted before, so that a
    // budget spent stops the work.
    if !env.charge(a.weight().max(b.weight()), a_span.join(b_span), diags) {
        return None;
    }
    if matches!(op, BinOp::Div | BinOp::Rem) {
        let zero = match &b {
            Num(y) => *y == 0.0,
            Vector(v) => v.contains(&0.0),
            Color(c) => c.contains(&0.0),
            _ => false,
        };
        if zero {
            diags.push(
                Diagnostic::error(codes::DIVISION_BY_ZERO, "division by zero", b_span)
                    .with_label("this is zero")
                    .with_help("divide by a non-zero value"),
            );
            return None;
        }
    }
    let additive = matches!(op, BinOp::Add | BinOp::Sub);
    let r = match (a, b) {
        (Num(x), Num(y)) => Num(f(x, y)),
        (Vector(u), Vector(v)) if u.len() == v.len() => {
            Vector(u.iter().zip(v.iter()).map(|(x, y)| f(*x, *y)).collect())
        }
        (Color(u), Color(v)) => Color([f(u[0], v[0]), f(u[1], v[1]), f(u[2], v[2])]),
        (Vector(u), Num(y)) if !additive => Vector(u.iter().map(|x| f(*x, y)).collect()),
        (Num(x), Vector(v)) if op == BinOp::Mul => Vector(v.iter().map(|y| f(x, *y)).collect()),
        (Color(u), Num(y)) if !additive => Color(u.map(|x| f(x, y))),
        (Num(x), Color(v)) if op == BinOp::Mul => Color(v.map(|y| f(x, y))),
        (Vector(u), Vector(v)) => {
            diags.push(
                mismatch(
                    at,
                    format!(
                        "cannot apply `{}` to vectors of {} and {} components",
                        op.symbol(),
                        u.len(),
                        v.len()
                    ),
                    "both vectors must have the same number of components",
                )
                .with_secondary(a_span, format!("{} components", u.len()))
                .with_secondary(b_span, format!("{} components", v.len())),
            );
            return None;
        }
        (x, y) => {
            diags.push(
                mismatch(
                    at,
                    format!(
                        "cannot apply `{}` to {} and {}",
                        op.symbol(),
                        x.type_name(),
                        y.type_name()
                    ),
                    "numbers, vectors and colours combine with themselves; vectors and colours can be scaled by a number",
                )
                .with_secondary(a_span, x.type_name())
                .with_secondary(b_span, y.type_name()),
            );
            return None;
        }
    };
    Some(r)
}
