//! Expressions, on one line: `a + b * c`, `<1, 2, 3>`, `f(x, y)`, `[a, b]`.
//! Numbers and strings are printed as written (`.5`, `1e3`, escapes), and
//! the parentheses the user wrote are kept (the AST keeps their span as
//! the expression's, which is how they are found).

use super::printer::Printer;
use super::scan::{next_code, number_end, string_end};
use crate::syntax::ast::{Expr, ExprKind};

/// Writes `e`, with its parentheses if the source has them.
pub(super) fn expr(p: &mut Printer, e: &Expr) {
    let (start, end) = (e.span.start as usize, e.span.end as usize);
    if parenthesised(p.text, e) {
        p.token(start, "(");
        bare(p, e, false);
        p.token(end - 1, ")");
    } else {
        bare(p, e, true);
    }
}

/// Whether the source writes `e` in parentheses: its span is then the
/// parentheses', starting before its first operand (an operator chain, an
/// index, a member) or at a `(` (anything else starts with its own token).
pub(super) fn parenthesised(text: &str, e: &Expr) -> bool {
    let start = e.span.start;
    match &e.kind {
        ExprKind::Chain { first, .. } => start < first.span.start,
        ExprKind::Index { base, .. } | ExprKind::Member { base, .. } => start < base.span.start,
        _ => text.as_bytes().get(start as usize) == Some(&b'('),
    }
}

/// Writes `e` without its parentheses; `own_span`: its span is its own (no
/// parentheses), so its first and last tokens are where the span says.
fn bare(p: &mut Printer, e: &Expr, own_span: bool) {
    let start = e.span.start as usize;
    // Where the first token is: inside the parentheses when there are
    // some (and, for a literal or a name, past the signs that cancelled
    // out: `(--1)` is the number 1).
    let leaf = matches!(
        e.kind,
        ExprKind::Number(_) | ExprKind::Str(_) | ExprKind::Bool(_) | ExprKind::Name(_)
    );
    let first = match (own_span, leaf) {
        (true, _) => start,
        (false, false) => next_code(p.text, start, b"("),
        (false, true) => next_code(p.text, start, b"(-!"),
    };
    let close = |p: &mut Printer, s: &str| {
        if own_span {
            p.token(e.span.end as usize - 1, s)
        } else {
            p.write(s)
        }
    };
    match &e.kind {
        ExprKind::Number(_) => {
            let text = p.text;
            p.token(first, &text[first..number_end(text, first)]);
        }
        ExprKind::Str(_) => {
            let text = p.text;
            p.token(first, &text[first..string_end(text, first)]);
        }
        ExprKind::Bool(b) => p.token(first, if *b { "true" } else { "false" }),
        ExprKind::Name(name) => p.token(first, name),
        ExprKind::Vector(items) => {
            p.token(first, "<");
            list(p, items);
            close(p, ">");
        }
        ExprKind::List(items) => {
            p.token(first, "[");
            list(p, items);
            close(p, "]");
        }
        ExprKind::Color(value) => {
            p.token(first, "rgb");
            p.space();
            expr(p, value);
        }
        ExprKind::FilterColor { word, value } => {
            p.token(word.span.start as usize, &word.name);
            p.space();
            expr(p, value);
        }
        ExprKind::Call { func, args } => {
            p.token(func.span.start as usize, &func.name);
            p.write("(");
            list(p, args);
            close(p, ")");
        }
        ExprKind::Neg(inner) | ExprKind::Not(inner) => {
            let sign = if matches!(e.kind, ExprKind::Neg(_)) {
                "-"
            } else {
                "!"
            };
            p.token(first, sign);
            expr(p, inner);
        }
        ExprKind::Index { base, indexes } => {
            expr(p, base);
            for i in indexes {
                p.write("[");
                expr(p, i);
                p.write("]");
            }
        }
        ExprKind::Member { base, member } => {
            expr(p, base);
            p.write(".");
            p.token(member.span.start as usize, &member.name);
        }
        ExprKind::If { arms, otherwise } => {
            if_value(p, first, arms, otherwise);
            close(p, "}");
        }
        ExprKind::Chain { first, rest } => {
            expr(p, first);
            for (op, at, operand) in rest {
                p.space();
                p.token(at.start as usize, op.symbol());
                p.space();
                expr(p, operand);
            }
        }
    }
}

/// Writes `a, b, c`.
pub(super) fn list(p: &mut Printer, items: &[Expr]) {
    for (k, item) in items.iter().enumerate() {
        if k > 0 {
            p.write(",");
            p.space();
        }
        expr(p, item);
    }
}

/// Writes `if c { a } else if d { b } else { e` (the caller closes it).
fn if_value(p: &mut Printer, at: usize, arms: &[(Expr, Expr)], otherwise: &Expr) {
    for (k, (cond, value)) in arms.iter().enumerate() {
        if k == 0 {
            p.token(at, "if");
        } else {
            p.space();
            p.write("else if");
        }
        p.space();
        expr(p, cond);
        p.space();
        p.write("{");
        p.space();
        expr(p, value);
        p.space();
        p.write("}");
    }
    p.space();
    p.write("else {");
    p.space();
    expr(p, otherwise);
    p.space();
}
