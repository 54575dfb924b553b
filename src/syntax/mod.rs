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
    let builder = build::Builder {
        file,
        reserved: Default::default(),
        base: Default::default(),
    };
    // One statement at a time: pest queues two tokens per pair, about 40 bytes
    // each, and a whole large file's queue was 25 times the size of its text
    // (the fresh pages alone cost a third of the parse time).
    let mut statements = Vec::new();
    let mut pos = 0;
    let ast = loop {
        let rest = &text[pos..];
        match PtsParser::parse(Rule::next_statement, rest) {
            Ok(mut pairs) => {
                let pair = pairs.next().expect("a statement pair");
                let end = pair.as_span().end();
                builder.base.set(pos);
                if let Some(statement) = pair.into_inner().next() {
                    statements.push(builder.build_statement(statement));
                }
                pos += end.max(1);
            }
            Err(_) if PtsParser::parse(Rule::only_blanks, rest).is_ok() => {
                break ast::File { statements };
            }
            Err(_) => {
                // A syntax error: parse the whole file so that the error is
                // reported exactly as a whole-file parse finds it.
                let mut pairs = PtsParser::parse(Rule::file, text)
                    .map_err(|e| parser::convert_error(e, file, text))?;
                builder.base.set(0);
                break builder.build_file(pairs.next().expect("a file pair"));
            }
        }
    };
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The whole text parsed by one pest call (the path a syntax error takes).
    fn parse_whole(text: &str) -> ast::File {
        let mut pairs = PtsParser::parse(Rule::file, text).expect("parses");
        let builder = build::Builder {
            file: FileId(0),
            reserved: Default::default(),
            base: Default::default(),
        };
        builder.build_file(pairs.next().expect("a file pair"))
    }

    fn scene_files(dir: &std::path::Path, out: &mut Vec<std::path::PathBuf>) {
        for entry in std::fs::read_dir(dir).expect("readable folder").flatten() {
            let path = entry.path();
            if path.is_dir() {
                scene_files(&path, out);
            } else if path.extension().is_some_and(|e| e == "pts" || e == "ptsi") {
                out.push(path);
            }
        }
    }

    #[test]
    fn one_statement_at_a_time_builds_the_whole_file_ast() {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
        let mut files = Vec::new();
        scene_files(&root.join("examples"), &mut files);
        scene_files(&root.join("tests/golden/scenes"), &mut files);
        assert!(files.len() >= 10, "{files:?}");
        let mut texts: Vec<String> = files
            .iter()
            .map(|f| std::fs::read_to_string(f).expect("readable scene"))
            .collect();
        // Blanks and comments in every place a statement can start or end.
        texts.push(
            "\u{FEFF}// lead\r\n/* a */ let r = 2 * -(1 + 1);/**/\r\nfor i in 0..3 { sphere { radius r } }\
             \n  background rgb 0.5 // tail\n/* end */\n"
                .to_string(),
        );
        for text in &texts {
            let per_statement = parse(FileId(0), text).expect("parses");
            assert_eq!(per_statement, parse_whole(text), "{text}");
        }
    }
}
