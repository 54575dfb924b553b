//! Blocks and their entries: `sphere { center <0, 1, 0> radius 1 }` on
//! one line when it fits in [`WIDTH`] columns and holds no comment, else
//! one entry per line, indented one level; values are not aligned.

use super::exprs::{expr, parenthesised};
use super::printer::{Printer, WIDTH};
use crate::span::Span;
use crate::syntax::ast::{Block, Entry, Expr, ExprKind, MaterialRef, MaterialSwap};

/// Writes a block, on the line or broken.
pub(super) fn block(p: &mut Printer, b: &Block) {
    braced(p, b.span, &b.entries, (entry_span, entry_lead, entry));
}

/// How a braced list's items are written: where each is, where the
/// comments before it end, and its writer (`after`: another item comes
/// before it).
type ItemWriter<T> = (fn(&T) -> Span, fn(&T) -> Span, fn(&mut Printer, &T, bool));

/// Writes `items` between the braces at `span`, on the line when they fit
/// in [`WIDTH`] columns and hold no comment, else one per line.
fn braced<T>(p: &mut Printer, span: Span, items: &[T], how: ItemWriter<T>) {
    p.comments_before(span.start as usize);
    match flat(p, span, items, how.2) {
        Some(line) if p.column() + line.chars().count() <= WIDTH => p.write(&line),
        _ => broken(p, span, items, how),
    }
}

/// The items on one line, if they hold no comment (nor a multi-line
/// entry written as it is).
fn flat<T>(
    p: &Printer,
    span: Span,
    items: &[T],
    write: fn(&mut Printer, &T, bool),
) -> Option<String> {
    if p.comment_before(span.end as usize) {
        return None;
    }
    let mut sub = Printer::new(p.text, Vec::new());
    if items.is_empty() {
        sub.write("{}");
    } else {
        sub.write("{");
        for (k, e) in items.iter().enumerate() {
            sub.space();
            write(&mut sub, e, k > 0);
        }
        sub.space();
        sub.write("}");
    }
    let line = sub.finish();
    let line = line.trim_end_matches('\n');
    (!line.contains('\n')).then(|| line.to_string())
}

/// Writes the items one per line.
fn broken<T>(p: &mut Printer, span: Span, items: &[T], (span_of, lead, write): ItemWriter<T>) {
    let (start, close) = (span.start as usize, span.end as usize - 1);
    p.token(start, "{");
    p.end_line();
    p.indent += 1;
    p.last_end = start + 1;
    let mut first = true;
    for (k, e) in items.iter().enumerate() {
        let span = span_of(e);
        p.leading(lead(e).start as usize, first);
        write(p, e, k > 0);
        let limit = items
            .get(k + 1)
            .map_or(close, |n| span_of(n).start as usize);
        let item_end = p.code_end(span.start as usize, span.end as usize);
        p.trailing(item_end, limit);
        p.end_line();
        first = false;
    }
    p.dangling(close, first);
    p.indent -= 1;
    p.end_line();
    p.token(close, "}");
}

/// Where the comments before an entry end: a positional list's first
/// value may start after signs that cancelled out (`!!1`), and a comment
/// between them leads the entry.
fn entry_lead(e: &Entry) -> Span {
    match e {
        Entry::Positional { values, .. } => values.first().map_or(entry_span(e), |v| v.span),
        _ => entry_span(e),
    }
}

/// Where an entry is.
fn entry_span(e: &Entry) -> Span {
    match e {
        Entry::Flag { name } => name.span,
        Entry::Param { span, .. }
        | Entry::Texture { span, .. }
        | Entry::Stop { span, .. }
        | Entry::Foreign { span, .. }
        | Entry::Positional { span, .. }
        | Entry::Materials { span, .. }
        | Entry::Material { span, .. } => *span,
    }
}

/// Writes one entry (`after`: another entry comes before it).
fn entry(p: &mut Printer, e: &Entry, after: bool) {
    match e {
        Entry::Flag { name } => p.token(name.span.start as usize, &name.name),
        Entry::Param { name, value, .. } => {
            p.token(name.span.start as usize, &name.name);
            p.space();
            expr(p, value);
        }
        Entry::Texture {
            name, kind, block, ..
        } => {
            p.token(name.span.start as usize, &name.name);
            p.space();
            p.token(kind.span.start as usize, &kind.name);
            p.space();
            self::block(p, block);
        }
        Entry::Stop {
            word,
            position,
            color,
            ..
        } => {
            p.token(word.span.start as usize, &word.name);
            p.space();
            expr(p, position);
            p.space();
            // `stop a (c)` would call `a`: the colour came from signs that
            // cancelled (`!!(c)` is `(c)`), keep two.
            if ends_with_name(p.text, position) && starts_with_paren(p.text, color) {
                p.write("!!");
            }
            apart(p, color, true);
        }
        Entry::Foreign { span, .. } => verbatim(p, *span),
        Entry::Positional { values, .. } => positional(p, values, after),
        Entry::Material { material, span } => material_ref(p, material, span.start as usize),
        Entry::Materials {
            word,
            swaps,
            braces,
            ..
        } => {
            p.token(word.span.start as usize, &word.name);
            p.space();
            braced(p, *braces, swaps, (|s| s.span, |s| s.span, swap));
        }
    }
}

/// Writes `material name` or `material { … }`, its word at `at`.
fn material_ref(p: &mut Printer, material: &MaterialRef, at: usize) {
    p.token(at, "material");
    p.space();
    match material {
        MaterialRef::Named(name) => p.token(name.span.start as usize, &name.name),
        MaterialRef::Inline(b) => block(p, b),
    }
}

/// Writes `"Name" material` of a `materials` block: the name as written.
fn swap(p: &mut Printer, s: &MaterialSwap, _after: bool) {
    let (start, end) = (s.name_span.start as usize, s.name_span.end as usize);
    p.token(start, &p.text[start..end]);
    p.space();
    match &s.material {
        MaterialRef::Named(name) => p.token(name.span.start as usize, &name.name),
        MaterialRef::Inline(_) => {
            let at = s.name_span.end as usize;
            let word = at + p.text[at..].find("material").unwrap_or(0);
            material_ref(p, &s.material, word);
        }
    }
}

/// Writes a positional list (`after`: another entry comes before it).
fn positional(p: &mut Printer, values: &[Expr], after: bool) {
    let Some((head, tail)) = values.split_first() else {
        return;
    };
    // A bare word first would read as a parameter's name or a
    // flag: only `name, …` is a positional list that starts so.
    // It came from signs that cancelled (`!!a` is `a`): keep two.
    let bare_name =
        matches!(head.kind, ExprKind::Name(_)) && !parenthesised(p.text, head) && !tail.is_empty();
    if starts_with_word(p.text, head) && !bare_name {
        p.write("!!");
        expr(p, head);
    } else if after && starts_with_paren(p.text, head) {
        // After an entry that ends with a name (`radius r`, a stop's
        // colour `c`) a parenthesis would call it: it came from signs
        // that cancelled (`!!(2)`), keep two. Positional values are an
        // error the checker reports, so the rare extra pair costs nothing.
        p.write("!!");
        expr(p, head);
    } else {
        apart(p, head, after);
    }
    for v in tail {
        p.write(",");
        p.space();
        expr(p, v);
    }
}

/// Writes `e`, which follows a value with nothing between them: after
/// `!!` if it would start with a `-` (the parser reads `!-!x` as `-!x`,
/// and `1 -!x` would be a subtraction; `!!` cancels out, and parentheses
/// after a name would make a call).
fn apart(p: &mut Printer, e: &Expr, after_value: bool) {
    // (And a list right after a value would index it: `1 [2]`.)
    if after_value && (starts_with_minus(p.text, e) || starts_with_list(p.text, e)) {
        p.write("!!");
    }
    expr(p, e);
}

/// The operand `e` is written starting with (itself, or the first operand
/// of its chain, index or member), if no parenthesis comes before it.
fn leftmost<'e>(text: &str, e: &'e Expr) -> Option<&'e Expr> {
    if parenthesised(text, e) {
        return None;
    }
    match &e.kind {
        ExprKind::Chain { first, .. } => leftmost(text, first),
        ExprKind::Index { base, .. } | ExprKind::Member { base, .. } => leftmost(text, base),
        _ => Some(e),
    }
}

/// Whether `e` is written starting with a list's `[`.
fn starts_with_list(text: &str, e: &Expr) -> bool {
    leftmost(text, e).is_some_and(|l| matches!(l.kind, ExprKind::List(_)))
}

/// Whether `e` is written starting with a parenthesis (itself, or the
/// first operand of its chain, index or member).
fn starts_with_paren(text: &str, e: &Expr) -> bool {
    parenthesised(text, e)
        || match &e.kind {
            ExprKind::Chain { first, .. } => starts_with_paren(text, first),
            ExprKind::Index { base, .. } | ExprKind::Member { base, .. } => {
                starts_with_paren(text, base)
            }
            _ => false,
        }
}

/// Whether `e` is written starting with a `-`.
fn starts_with_minus(text: &str, e: &Expr) -> bool {
    leftmost(text, e).is_some_and(|l| matches!(l.kind, ExprKind::Neg(_)))
}

/// Whether `e` is written ending with a name (a parenthesis after it would
/// make a call).
fn ends_with_name(text: &str, e: &Expr) -> bool {
    if parenthesised(text, e) {
        return false;
    }
    match &e.kind {
        ExprKind::Name(_) | ExprKind::Member { .. } => true,
        ExprKind::Chain { rest, .. } => {
            rest.last().is_some_and(|(_, _, x)| ends_with_name(text, x))
        }
        ExprKind::Neg(inner) | ExprKind::Not(inner) => ends_with_name(text, inner),
        _ => false,
    }
}

/// Whether `e` is written starting with a word (a name, `true`, `rgb`,
/// `if`, a call).
fn starts_with_word(text: &str, e: &Expr) -> bool {
    leftmost(text, e).is_some_and(|l| {
        matches!(
            l.kind,
            ExprKind::Name(_)
                | ExprKind::Bool(_)
                | ExprKind::Call { .. }
                | ExprKind::Color(_)
                | ExprKind::FilterColor { .. }
                | ExprKind::If { .. }
        )
    })
}

/// Writes the source of `span` as it is (without the blanks that end it):
/// what ptsc does not read, a POV-Ray directive or block.
pub(super) fn verbatim(p: &mut Printer, span: Span) {
    let (start, end) = (span.start as usize, span.end as usize);
    let text = p.text;
    p.token(start, text[start..end].trim_end());
}
