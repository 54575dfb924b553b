//! Syntax: text → AST. The only module that sees pest; `Pair`s never leave it.

pub mod ast;
mod build;
mod build_expr;
mod build_statement;
mod error_context;
mod grammar;
mod hand_over;
mod hints;
mod nested_comment;
pub mod parser;
pub mod povray;
mod recover;
mod scan;
pub mod words;

use crate::diag::{codes, Diagnostic};
use crate::source::FileId;
use crate::span::Span;
use parser::{PtsParser, Rule};
use pest::Parser;
use recover::{Break, Parsed};
use scan::{bom_len, for_each_code_mark, statement_follows};

/// The deepest nesting of `(`, `[`, `<` and `{` the parser accepts. Deeper input is
/// reported instead of risking the stack of a recursive-descent parser.
pub const MAX_NESTING: usize = 128;

/// Parses one file into an AST, or returns its first error (a syntax error
/// exactly as a whole-file parse reports it, or a misused reserved word);
/// parsing stops there.
pub fn parse(file: FileId, text: &str, kinds: &[&str]) -> Result<ast::File, Diagnostic> {
    parse_in_pieces(file, text, kinds, PIECE)
}

/// Parses `text` and hands its statements to `sink` in file order, a piece at
/// a time, while the pieces after it are still being parsed: a checker
/// consuming them runs beside the parser instead of after it. Returns the
/// file's errors in file order, empty when it parsed. A broken statement is
/// skipped to where the next statement plausibly starts and parsing goes on
/// there, so the statements before and after it are handed over; its error
/// is reported as a parse of the text from the end of the previous error
/// finds it (the first exactly as a whole-file parse). A `{` or comment
/// never closed runs to the end of the file: nothing follows. After 100
/// errors, one more diagnostic says that the rest of the file is not read.
///
/// `kinds` are the names of the kinds of block statement (the checker's
/// kind table): the grammar reads any name before a block as a kind, and a
/// name whose braces hold no ptsc block as a statement ptsc does not have
/// (POV-Ray's `light_source { … }`), unless it is one of `kinds`: then the
/// block has a syntax error.
pub fn parse_each(
    file: FileId,
    text: &str,
    kinds: &[&str],
    sink: &mut (dyn FnMut(Vec<ast::Statement>) + Send),
) -> Vec<Diagnostic> {
    parse_each_in_pieces(file, text, kinds, PIECE, true, sink)
}

/// Least size of the pieces a file is cut into, each parsed in one pest call.
const PIECE: usize = 16 * 1024;

/// Pieces parsed in parallel between two hand-overs to the sink (512 KB):
/// enough to keep both cores busy, few enough that the sink starts early.
const BATCH: usize = 32;

/// [`parse`] with the text cut into pieces of at least `min_piece` bytes.
fn parse_in_pieces(
    file: FileId,
    text: &str,
    kinds: &[&str],
    min_piece: usize,
) -> Result<ast::File, Diagnostic> {
    let mut statements = Vec::new();
    let errors = parse_each_in_pieces(file, text, kinds, min_piece, false, &mut |piece| {
        statements.extend(piece)
    });
    match errors.into_iter().next() {
        Some(first) => Err(first),
        None => Ok(ast::File { statements }),
    }
}

/// [`parse_each`] with pieces of at least `min_piece` bytes; without
/// `recover`, parsing stops at the first error.
fn parse_each_in_pieces(
    file: FileId,
    text: &str,
    kinds: &[&str],
    min_piece: usize,
    recover: bool,
    sink: &mut (dyn FnMut(Vec<ast::Statement>) + Send),
) -> Vec<Diagnostic> {
    use rayon::prelude::*;
    let pieces = match pieces(text, min_piece) {
        Ok(pieces) => pieces,
        Err(at) => return vec![too_deep(file, at)],
    };
    let mut hand_over = hand_over::HandOver::new(file, text, kinds, recover);
    let limit = hand_over.limit();
    // Each round parses one batch while the sink takes the batch before it.
    let mut ready: Vec<Parsed> = Vec::new();
    for batch in pieces.chunks(BATCH) {
        let (parsed, ()) = rayon::join(
            || {
                batch
                    .par_iter()
                    .map(|&(start, end)| parse_piece(file, (text, kinds), start, end, limit))
                    .collect::<Vec<Parsed>>()
            },
            || hand_over.take(std::mem::take(&mut ready), sink),
        );
        if hand_over.stopped() {
            return hand_over.finish();
        }
        ready = parsed;
    }
    hand_over.take(ready, sink);
    hand_over.finish()
}

/// The statements of the piece `text[start..end]`: the whole piece in one
/// pest call, or, if that fails, one statement at a time
/// ([`recover::parse_from`]), past its errors up to the `limit`th. Pieces are
/// small: pest queues two tokens of 40 bytes per pair, and a whole file's
/// queue was 32 times the size of its text (360 MB for the 11 MB
/// 100,000-sphere scene; zeroing its fresh pages took a third of the
/// parse), while a call per statement paid pest's set-up and the growth of
/// its queue every time (5 % of the parse).
fn parse_piece(
    file: FileId,
    (text, kinds): (&str, &[&str]),
    start: usize,
    end: usize,
    limit: usize,
) -> Parsed {
    let Ok(mut pairs) = PtsParser::parse(Rule::file, &text[start..end]) else {
        return recover::parse_from(file, (text, kinds), start, end, limit);
    };
    let builder = build::Builder::new(file, text, kinds, start);
    let mut parsed = Parsed {
        start,
        end,
        statements: Vec::new(),
        breaks: Vec::new(),
        next: Some(end),
    };
    let pairs = pairs.next().expect("file matched").into_inner();
    for pair in pairs.filter(|p| p.as_rule() != Rule::EOI) {
        let span = pair.as_span();
        parsed.statements.push(builder.build_statement(pair));
        // A reserved word used as a name: reported, and the statement kept
        // (when parsing goes on) so that its uses raise no second error. A
        // kind's broken block is kept as the statement ptsc does not have
        // that it was read as (the checker knows it was reported).
        if let Some(d) = builder.reserved.take() {
            parsed.breaks.push(Break {
                kept: parsed.statements.len() - 1,
                at: start + span.start(),
                seen: start + span.end(),
                resume: Some(start + span.end()),
                reserved: Some(d),
            });
            if parsed.breaks.len() == limit {
                parsed.next = None;
                break;
            }
        }
    }
    parsed
}

/// Cuts `text` into pieces of at least `min_piece` bytes, each ending just
/// after a `}` or `;` at nesting depth 0 outside comments and strings. In a
/// valid file such a character ends a statement (blocks close statements, `;`
/// closes `let`), so the pieces parse alone into the file's statements; in an
/// invalid one some piece fails and the whole file is parsed for the error.
/// The same scan refuses nesting deeper than [`MAX_NESTING`], before pest
/// runs: `Err` holds the offset of the bracket one level too deep.
fn pieces(text: &str, min_piece: usize) -> Result<Vec<(usize, usize)>, usize> {
    let mut out = Vec::new();
    let mut start = bom_len(text);
    // The open brackets, innermost last. A `<` is a vector's or a
    // comparison's: a `>` closes it only right above it, and a `)`, `]`,
    // `}`, `{` or `;` first drops the `<`s above its own level (they were
    // comparisons: no vector holds a brace, a statement end or a closing
    // bracket of an outer level).
    let mut open: Vec<u8> = Vec::new();
    let mut too_deep = None;
    let bytes = text.as_bytes();
    for_each_code_mark(text, |i, b| {
        if matches!(b, b')' | b']' | b'}' | b'{' | b';') {
            while open.last() == Some(&b'<') {
                open.pop();
            }
        }
        match b {
            b'<' if bytes.get(i + 1) == Some(&b'=') => {}
            b'(' | b'[' | b'<' | b'{' => {
                open.push(b);
                if open.len() > MAX_NESTING {
                    too_deep = Some(i);
                    return false;
                }
            }
            b'>' if open.last() == Some(&b'<') => {
                open.pop();
            }
            b')' | b']' | b'}' => {
                open.pop();
            }
            _ => {}
        }
        if open.is_empty()
            && (b == b';' || (b == b'}' && statement_follows(&text[i + 1..])))
            && i + 1 - start >= min_piece
        {
            out.push((start, i + 1));
            start = i + 1;
        }
        true
    });
    if let Some(i) = too_deep {
        return Err(i);
    }
    out.push((start, text.len()));
    Ok(out)
}

/// The error for a bracket at `i` nested deeper than [`MAX_NESTING`].
fn too_deep(file: FileId, i: usize) -> Diagnostic {
    Diagnostic::error(
        codes::TOO_DEEP,
        format!("nesting deeper than {MAX_NESTING} levels"),
        Span::new(file, i, i + 1),
    )
    .with_label("this bracket opens one level too many")
    .with_help("flatten the expression or block; use `let` for parts of it")
}

#[cfg(test)]
pub(crate) mod tests;
