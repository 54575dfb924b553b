//! The statements of parse pieces handed over in file order, and the
//! diagnostics of a file's syntax errors.
//!
//! Pieces are parsed in parallel, each from its own start. Where a broken
//! statement's skip ([`super::recover::resume_after`]) runs past the end of
//! its piece, the next piece's own parse started in the wrong place: reading
//! goes on from where the skip ended, one statement at a time, until it
//! meets the start of a later piece again. So the statements and errors of
//! a file are the same however it was cut.

use super::ast;
use super::build;
use super::parser::{PtsParser, Rule};
use super::recover::{parse_from, Break, Parsed};
use super::scan::bom_len;
use crate::diag::{codes, Diagnostic};
use crate::source::FileId;
use crate::span::Span;
use pest::Parser;

/// Most syntax errors reported for one file: at the next one, reading
/// stops. Past a hundred mistakes the file is rarely ptsc (or its next
/// errors news), and a file of broken statements is not read for minutes.
pub(super) const MAX_ERRORS: usize = 100;

/// Where handing statements over stands.
pub(super) struct HandOver<'t> {
    file: FileId,
    text: &'t str,
    /// The names of the kinds of block statement.
    kinds: &'t [&'t str],
    /// Whether reading goes on after a broken statement.
    recover: bool,
    /// Where the next statement starts; `None` once nothing more is read.
    cursor: Option<usize>,
    /// The diagnostics of the broken statements met so far.
    errors: Vec<Diagnostic>,
    /// How many broken statements were met.
    broken: usize,
    /// Where reading resumed after the last broken statement: the next
    /// syntax error is reported as a parse of the text from there finds it.
    resumed: usize,
}

impl<'t> HandOver<'t> {
    /// Nothing handed over yet of `text`; with `recover`, reading goes on
    /// after each broken statement, else it stops at the first.
    pub fn new(file: FileId, text: &'t str, kinds: &'t [&'t str], recover: bool) -> Self {
        let start = bom_len(text);
        HandOver {
            file,
            text,
            kinds,
            recover,
            cursor: Some(start),
            errors: Vec::new(),
            broken: 0,
            resumed: start,
        }
    }

    /// The broken statement a piece's parse may stop at (the one that
    /// stops reading, counted in the piece): later ones are never needed.
    pub fn limit(&self) -> usize {
        if self.recover {
            MAX_ERRORS + 1
        } else {
            1
        }
    }

    /// Whether nothing more will be read: the pieces still to be parsed
    /// need not be.
    pub fn stopped(&self) -> bool {
        self.cursor.is_none()
    }

    /// Gives the statements of `pieces` (consecutive, in file order) to
    /// `sink` and reports their broken statements.
    pub fn take(
        &mut self,
        pieces: Vec<Parsed>,
        sink: &mut (dyn FnMut(Vec<ast::Statement>) + Send),
    ) {
        for piece in pieces {
            let Some(cursor) = self.cursor else { return };
            let piece = if piece.start == cursor {
                piece
            } else if piece.end <= cursor {
                // A broken statement before it ran past it.
                continue;
            } else {
                parse_from(
                    self.file,
                    (self.text, self.kinds),
                    cursor,
                    piece.end,
                    self.limit(),
                )
            };
            self.take_one(piece, sink);
        }
    }

    /// Hands over one piece read from the cursor, up to the broken
    /// statement that stops reading: the first without recovery, the one
    /// past [`MAX_ERRORS`] with it.
    fn take_one(&mut self, piece: Parsed, sink: &mut (dyn FnMut(Vec<ast::Statement>) + Send)) {
        let Parsed {
            mut statements,
            breaks,
            next,
            ..
        } = piece;
        let stop = if self.recover {
            MAX_ERRORS - self.broken
        } else {
            0
        };
        if let Some(b) = breaks.get(stop) {
            statements.truncate(b.kept);
        }
        if !statements.is_empty() {
            sink(statements);
        }
        for (k, b) in breaks.into_iter().enumerate() {
            if k == stop {
                if self.recover {
                    self.errors.push(too_many(self.file, self.text, b.at));
                } else {
                    self.note(b);
                }
                self.cursor = None;
                return;
            }
            self.note(b);
        }
        self.cursor = next;
    }

    /// Reports a broken statement.
    fn note(&mut self, b: Break) {
        self.broken += 1;
        let d = match b.reserved {
            Some(d) => d,
            // The first exactly as a parse of the whole file reports it.
            None if self.broken == 1 => first_error(self.file, self.text, self.kinds),
            None => later_error(self.file, (self.text, self.kinds), self.resumed, b.seen),
        };
        self.errors.push(d);
        if let Some(r) = b.resume {
            self.resumed = r;
        }
    }

    /// The file's syntax errors, in file order: empty when it parsed.
    pub fn finish(self) -> Vec<Diagnostic> {
        self.errors
    }
}

/// The diagnostic for the broken statement at `at`, past [`MAX_ERRORS`]:
/// reading stops there.
fn too_many(file: FileId, text: &str, at: usize) -> Diagnostic {
    let len = text[at..].chars().next().map_or(0, char::len_utf8);
    Diagnostic::error(
        codes::UNEXPECTED_TOKEN,
        format!("more than {MAX_ERRORS} syntax errors: the rest of this file is not read"),
        Span::new(file, at, at + len),
    )
    .with_label("another syntax error starts here")
    .with_help("mend the errors above and check again")
}

/// The first syntax error of a file: the whole file in one pest call, so
/// that it is exactly what a parse of the whole file reports.
fn first_error(file: FileId, text: &str, kinds: &[&str]) -> Diagnostic {
    match parse_whole(file, text, kinds) {
        Err(d) => d,
        Ok(_) => disagreed(file),
    }
}

/// A later syntax error: what a parse of the text from `from` (where
/// reading resumed after the error before) reports, with its spans counted
/// from the start of the file. pest reads up to `seen`, where its failure
/// is the one in the whole rest of the file ([`Break::seen`]), so that the
/// cost is that of the stretch, not of the rest of the file; the messages
/// look at the rest of the file as for a first error.
fn later_error(
    file: FileId,
    (text, kinds): (&str, &[&str]),
    from: usize,
    seen: usize,
) -> Diagnostic {
    match PtsParser::parse(Rule::file, &text[from..seen]) {
        Err(e) => shifted(
            super::hints::convert_error(e, file, (&text[from..], kinds), 0),
            from,
        ),
        Ok(_) => disagreed(file),
    }
}

/// `d` with its spans moved `by` bytes on.
fn shifted(mut d: Diagnostic, by: usize) -> Diagnostic {
    let by = by as u32;
    let shift = |s: &mut Span| {
        s.start += by;
        s.end += by;
    };
    if let Some(s) = &mut d.span {
        shift(s);
    }
    for (s, _) in &mut d.secondary {
        shift(s);
    }
    if let Some((s, _)) = &mut d.fix {
        shift(s);
    }
    d
}

/// The error for a file that the pieces found broken and a parse of the
/// text did not: the two paths accept the same files (tested); were they
/// ever to disagree, say so rather than panic.
fn disagreed(file: FileId) -> Diagnostic {
    Diagnostic::error(
        codes::INTERNAL,
        "the parser disagreed with itself on this file",
        Span::new(file, 0, 0),
    )
    .with_label("parsed whole but not in pieces")
    .with_help("please report this file as a ptsc bug")
}

/// The whole file in one pest call: the path that reports syntax errors.
pub(super) fn parse_whole(
    file: FileId,
    text: &str,
    kinds: &[&str],
) -> Result<ast::File, Diagnostic> {
    let bom = bom_len(text);
    let mut pairs = PtsParser::parse(Rule::file, &text[bom..])
        .map_err(|e| super::hints::convert_error(e, file, (text, kinds), bom))?;
    let builder = build::Builder::new(file, text, kinds, bom);
    let ast = builder.build_file(pairs.next().expect("a file pair"));
    match builder.reserved.into_inner() {
        Some(d) => Err(d),
        None => Ok(ast),
    }
}
