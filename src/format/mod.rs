//! The formatter: `.pts` text → the same scene in the one canonical layout
//! (`ptsc fmt`, and an editor's "format document" and "format selection").
//!
//! The layout, in short (docs/language.md has it whole): 4 spaces per
//! level; one statement per line; a block on one line when it fits in 100
//! columns and holds no comment, else one entry per line (values not
//! aligned); `for`, `if` and `group` bodies always one statement per line;
//! single spaces around binary operators and after commas; numbers and
//! strings as written; the user's parentheses kept; every comment kept
//! (leading, trailing on its line, or dangling at a list's end); a run of
//! empty lines between statements becomes one.
//!
//! The AST has no comments (the grammar skips them): they are read from
//! the text ([`scan`]) and written where the tokens around them fall
//! ([`printer`]). The result is checked before it is returned ([`verify`]):
//! it must parse to the same tree, spans aside, with the same comments.

mod blocks;
mod exprs;
mod printer;
mod scan;
mod statements;
mod verify;

#[cfg(test)]
mod tests;

use crate::diag::Diagnostic;
use crate::source::FileId;
use crate::syntax::ast::File;
pub use verify::spanless;

/// Why a text was not formatted.
#[derive(Debug, Clone, PartialEq)]
pub enum FormatError {
    /// The text has a syntax error (its diagnostic, in file 0).
    Syntax(Vec<Diagnostic>),
    /// The formatter's result failed its own check (a bug in the formatter).
    Bug(String),
}

impl std::fmt::Display for FormatError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            FormatError::Syntax(d) => {
                let first = d.first().map_or("", |d| d.message.as_str());
                write!(f, "syntax error: {first}")
            }
            FormatError::Bug(why) => write!(f, "internal formatter bug: {why}"),
        }
    }
}

/// Formats a whole `.pts` text.
pub fn format_text(text: &str) -> Result<String, FormatError> {
    let file = parse(text)?;
    let out = print(text, &file);
    verify::verify(text, &file, &out)?;
    Ok(with_line_ends_of(text, out))
}

/// `out` with the line ends `text` uses: a file whose first line ends in
/// `\r\n` keeps them on every line (as rustfmt's `newline_style = "Auto"`),
/// so that formatting a Windows file does not rewrite each of its lines.
fn with_line_ends_of(text: &str, out: String) -> String {
    let crlf = text.find('\n').is_some_and(|at| text[..at].ends_with('\r'));
    if !crlf {
        return out;
    }
    // A comment or a verbatim block may have kept its own `\r\n`s.
    out.replace("\r\n", "\n").replace('\n', "\r\n")
}

/// Formats the top-level statements that overlap the bytes `start..end`
/// of `text`; returns the bytes they cover (from the first one's start to
/// the last one's end) and their new text. An empty range when no
/// statement overlaps.
pub fn format_range(
    text: &str,
    start: usize,
    end: usize,
) -> Result<(std::ops::Range<usize>, String), FormatError> {
    let file = parse(text)?;
    let overlaps = |s: &crate::syntax::ast::Statement| {
        let (a, b) = (s.span().start as usize, s.span().end as usize);
        a < end.max(start + 1) && start < b
    };
    let mut hit = file.statements.iter().filter(|s| overlaps(s));
    let Some(first) = hit.next() else {
        return Ok((start..start, String::new()));
    };
    let last = hit.next_back().unwrap_or(first);
    let range = first.span().start as usize..last.span().end as usize;
    let out = format_text(&text[range.clone()]).map_err(|e| match e {
        FormatError::Syntax(_) => FormatError::Bug("a statement does not parse alone".into()),
        bug => bug,
    })?;
    Ok((range, out.trim_end_matches(['\n', '\r']).to_string()))
}

/// Parses `text` as the formatter reads it: file 0, the kinds of the
/// checker's table.
fn parse(text: &str) -> Result<File, FormatError> {
    let kinds = &crate::check::kinds::NAMES;
    crate::syntax::parse(FileId(0), text, kinds).map_err(|first| {
        // Every syntax error, as `ptsc check` reports them (read again
        // only when there is one).
        let all = crate::syntax::parse_each(FileId(0), text, kinds, &mut |_| {});
        FormatError::Syntax(if all.is_empty() { vec![first] } else { all })
    })
}

/// The text of `file` (parsed from `text`) in the canonical layout.
fn print(text: &str, file: &File) -> String {
    let comments = scan::comments(text, &scan::verbatim_ranges(file));
    let mut p = printer::Printer::new(text, comments);
    statements::file(&mut p, file);
    let out = p.finish();
    if text.starts_with('\u{FEFF}') {
        format!("\u{FEFF}{out}")
    } else {
        out
    }
}
