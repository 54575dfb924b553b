//! Blocks and their entries: `sphere { center <0, 1, 0> radius 1 }` on
//! one line when it fits in [`WIDTH`] columns and holds no comment, else
//! one entry per line, indented one level; values are not aligned.

use super::exprs::{expr, list};
use super::printer::{Printer, WIDTH};
use crate::span::Span;
use crate::syntax::ast::{Block, Entry, MaterialRef};

/// Writes a block, on the line or broken.
pub(super) fn block(p: &mut Printer, b: &Block) {
    p.comments_before(b.span.start as usize);
    match flat(p, b) {
        Some(line) if p.column() + line.chars().count() <= WIDTH => p.write(&line),
        _ => broken(p, b),
    }
}

/// The block on one line, if it holds no comment (nor a multi-line
/// entry written as it is).
fn flat(p: &Printer, b: &Block) -> Option<String> {
    if p.comment_before(b.span.end as usize) {
        return None;
    }
    let mut sub = Printer::new(p.text, Vec::new());
    if b.entries.is_empty() {
        sub.write("{}");
    } else {
        sub.write("{");
        for e in &b.entries {
            sub.space();
            entry(&mut sub, e);
        }
        sub.space();
        sub.write("}");
    }
    let line = sub.finish();
    let line = line.trim_end_matches('\n');
    (!line.contains('\n')).then(|| line.to_string())
}

/// Writes a block one entry per line.
fn broken(p: &mut Printer, b: &Block) {
    let (start, close) = (b.span.start as usize, b.span.end as usize - 1);
    p.token(start, "{");
    p.end_line();
    p.indent += 1;
    p.last_end = start + 1;
    let mut first = true;
    for (k, e) in b.entries.iter().enumerate() {
        let span = entry_span(e);
        p.leading(span.start as usize, first);
        entry(p, e);
        let limit = b
            .entries
            .get(k + 1)
            .map_or(close, |n| entry_span(n).start as usize);
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

/// Where an entry is.
fn entry_span(e: &Entry) -> Span {
    match e {
        Entry::Flag { name } => name.span,
        Entry::Param { span, .. }
        | Entry::Texture { span, .. }
        | Entry::Stop { span, .. }
        | Entry::Foreign { span, .. }
        | Entry::Positional { span, .. }
        | Entry::Material { span, .. } => *span,
    }
}

/// Writes one entry.
fn entry(p: &mut Printer, e: &Entry) {
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
            expr(p, color);
        }
        Entry::Foreign { span, .. } => verbatim(p, *span),
        Entry::Positional { values, .. } => list(p, values),
        Entry::Material { material, span } => {
            p.token(span.start as usize, "material");
            p.space();
            match material {
                MaterialRef::Named(name) => p.token(name.span.start as usize, &name.name),
                MaterialRef::Inline(b) => block(p, b),
            }
        }
    }
}

/// Writes the source of `span` as it is (without the blanks that end it):
/// what ptsc does not read, a POV-Ray directive or block.
pub(super) fn verbatim(p: &mut Printer, span: Span) {
    let (start, end) = (span.start as usize, span.end as usize);
    let text = p.text;
    p.token(start, text[start..end].trim_end());
}
