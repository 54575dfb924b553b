//! Syntax: text → AST. The only module that sees pest; `Pair`s never leave it.

pub mod ast;
mod build;
pub mod parser;

use crate::diag::Diagnostic;
use crate::source::FileId;
use crate::span::Span;
use parser::{PtsParser, Rule};
use pest::Parser;

/// The deepest nesting of `(`, `<` and `{` the parser accepts. Deeper input is
/// reported instead of risking the stack of a recursive-descent parser.
pub const MAX_NESTING: usize = 128;

/// Parses one file into an AST, or returns the first syntax error.
pub fn parse(file: FileId, text: &str) -> Result<ast::File, Diagnostic> {
    if let Some(d) = check_nesting(file, text) {
        return Err(d);
    }
    let mut pairs =
        PtsParser::parse(Rule::file, text).map_err(|e| parser::convert_error(e, file, text))?;
    let builder = build::Builder {
        file,
        reserved: Default::default(),
    };
    let ast = builder.build_file(pairs.next().expect("a file pair"));
    match builder.reserved.into_inner() {
        Some(d) => Err(d),
        None => Ok(ast),
    }
}

/// Calls `f(offset, byte)` for every byte of `text` outside comments and
/// strings: the bracket scans below need to see code only.
pub(crate) fn for_each_code_byte(text: &str, mut f: impl FnMut(usize, u8) -> bool) {
    let bytes = text.as_bytes();
    let mut i = 0;
    while i < bytes.len() {
        match bytes[i] {
            b'/' if bytes.get(i + 1) == Some(&b'/') => {
                while i < bytes.len() && bytes[i] != b'\n' {
                    i += 1;
                }
            }
            b'/' if bytes.get(i + 1) == Some(&b'*') => {
                i += 2;
                while i < bytes.len() && !(bytes[i] == b'*' && bytes.get(i + 1) == Some(&b'/')) {
                    i += 1;
                }
                i += 1;
            }
            b'"' => {
                i += 1;
                while i < bytes.len() && bytes[i] != b'"' && bytes[i] != b'\n' {
                    if bytes[i] == b'\\' {
                        i += 1;
                    }
                    i += 1;
                }
            }
            b => {
                if !f(i, b) {
                    return;
                }
            }
        }
        i += 1;
    }
}

/// Finds nesting deeper than [`MAX_NESTING`], skipping comments and strings.
fn check_nesting(file: FileId, text: &str) -> Option<Diagnostic> {
    let mut depth = 0usize;
    let mut too_deep = None;
    for_each_code_byte(text, |i, b| {
        match b {
            b'(' | b'<' | b'{' => {
                depth += 1;
                if depth > MAX_NESTING {
                    too_deep = Some(i);
                    return false;
                }
            }
            b')' | b'>' | b'}' => depth = depth.saturating_sub(1),
            _ => {}
        }
        true
    });
    let i = too_deep?;
    Some(
        Diagnostic::error(
            "pts::syntax::too_deep",
            format!("nesting deeper than {MAX_NESTING} levels"),
            Span::new(file, i, i + 1),
        )
        .with_label("this bracket opens one level too many")
        .with_help("flatten the expression or block; use `let` for parts of it"),
    )
}
