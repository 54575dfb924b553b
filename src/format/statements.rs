//! Statements, one per line, and the bodies of `for`, `if` and `group`
//! (always broken, one statement per line, indented one level). The empty
//! lines between statements are kept (a run of them as one).

use super::blocks::{block, verbatim};
use super::exprs::expr;
use super::printer::Printer;
use super::scan::find_code;
use crate::syntax::ast::{Expr, File, Ident, Statement};

/// Writes a whole file.
pub(super) fn file(p: &mut Printer, f: &File) {
    let end = p.text.len();
    statements(p, &f.statements, end);
}

/// Writes a list of statements that ends at `end` (the file's end or the
/// body's `}`), with their comments.
fn statements(p: &mut Printer, list: &[Statement], end: usize) {
    let mut first = true;
    for (k, s) in list.iter().enumerate() {
        let span = s.span();
        p.leading(span.start as usize, first);
        statement(p, s);
        let limit = list.get(k + 1).map_or(end, |n| n.span().start as usize);
        let item_end = p.code_end(span.start as usize, span.end as usize);
        p.trailing(item_end, limit);
        p.end_line();
        first = false;
    }
    p.dangling(end, first);
}

/// Writes a body `{ … }` whose `{` is the first after `from`; returns
/// where its `}` is.
fn body(p: &mut Printer, from: usize, list: &[Statement]) -> usize {
    let open = find_code(p.text, from, b'{');
    let after = list.last().map_or(open + 1, |s| s.span().end as usize);
    let close = find_code(p.text, after, b'}');
    p.space();
    p.token(open, "{");
    if list.is_empty() && !p.comment_before(close) {
        p.write("}");
        return close;
    }
    p.end_line();
    p.indent += 1;
    p.last_end = open + 1;
    statements(p, list, close);
    p.indent -= 1;
    p.end_line();
    p.token(close, "}");
    close
}

/// Writes a keyword and a name after it: `group chair`.
fn word_and_name(p: &mut Printer, at: usize, word: &str, name: &Ident) {
    p.token(at, word);
    p.space();
    p.token(name.span.start as usize, &name.name);
}

/// Writes one statement (without its line end).
fn statement(p: &mut Printer, s: &Statement) {
    let (start, end) = (s.span().start as usize, s.span().end as usize);
    match s {
        Statement::Let { name, value, .. } => {
            word_and_name(p, start, "let", name);
            p.space();
            p.write("=");
            p.space();
            expr(p, value);
            p.token(end - 1, ";");
        }
        Statement::Include { path_span, .. } => {
            p.token(start, "include");
            p.space();
            verbatim(p, *path_span);
        }
        Statement::For {
            var,
            start: from,
            end: to,
            body: list,
            ..
        } => {
            word_and_name(p, start, "for", var);
            p.space();
            p.write("in");
            p.space();
            expr(p, from);
            if let Some(to) = to {
                p.write("..");
                expr(p, to);
            }
            body(p, to.as_ref().unwrap_or(from).span.end as usize, list);
        }
        Statement::If {
            arms, otherwise, ..
        } => if_statement(p, start, arms, otherwise.as_deref()),
        Statement::Function {
            name,
            params,
            body: value,
            ..
        } => {
            word_and_name(p, start, "fn", name);
            p.write("(");
            for (k, param) in params.iter().enumerate() {
                if k > 0 {
                    p.write(",");
                    p.space();
                }
                p.token(param.span.start as usize, &param.name);
            }
            p.write(")");
            p.space();
            p.write("=");
            p.space();
            expr(p, value);
            p.token(end - 1, ";");
        }
        Statement::Group {
            name, body: list, ..
        } => {
            word_and_name(p, start, "group", name);
            body(p, name.span.end as usize, list);
        }
        Statement::Instance {
            group: name,
            block: b,
            ..
        } => {
            word_and_name(p, start, "instance", name);
            p.space();
            block(p, b);
        }
        Statement::Background { value, .. } => {
            p.token(start, "background");
            p.space();
            expr(p, value);
        }
        Statement::Material { name, block: b, .. } => {
            word_and_name(p, start, "material", name);
            p.space();
            block(p, b);
        }
        Statement::Texture {
            name,
            kind,
            block: b,
            ..
        } => {
            word_and_name(p, start, "texture", name);
            p.space();
            p.token(kind.span.start as usize, &kind.name);
            p.space();
            block(p, b);
        }
        Statement::Block { kind, block: b, .. } => {
            p.token(kind.span.start as usize, &kind.name);
            p.space();
            block(p, b);
        }
        Statement::Directive { .. } | Statement::Foreign { .. } => verbatim(p, s.span()),
    }
}

/// Writes `if c { … } else if d { … } else { … }`.
fn if_statement(
    p: &mut Printer,
    start: usize,
    arms: &[(Expr, Vec<Statement>)],
    otherwise: Option<&[Statement]>,
) {
    let mut close = start;
    for (k, (cond, list)) in arms.iter().enumerate() {
        if k == 0 {
            p.token(start, "if");
        } else {
            p.space();
            p.write("else if");
        }
        p.space();
        expr(p, cond);
        close = body(p, cond.span.end as usize, list);
    }
    if let Some(list) = otherwise {
        p.space();
        p.write("else");
        body(p, close + 1, list);
    }
}
