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
    parse_in_pieces(file, text, PIECE)
}

/// Least size of the pieces a file is cut into for parsing in parallel.
const PIECE: usize = 64 * 1024;

/// [`parse`] with the text cut into pieces of at least `min_piece` bytes,
/// parsed in parallel.
fn parse_in_pieces(file: FileId, text: &str, min_piece: usize) -> Result<ast::File, Diagnostic> {
    use rayon::prelude::*;
    let pieces = pieces(text, min_piece).map_err(|at| too_deep(file, at))?;
    let parsed: Vec<Option<Parsed>> = pieces
        .into_par_iter()
        .map(|(start, end)| parse_statements(file, &text[start..end], start))
        .collect();
    let mut statements = Vec::new();
    let mut reserved = None;
    for piece in parsed {
        let Some(piece) = piece else {
            // A syntax error: parse the whole file so that the error is
            // reported exactly as a whole-file parse finds it.
            return parse_whole(file, text);
        };
        statements.extend(piece.statements);
        reserved = reserved.or(piece.reserved);
    }
    match reserved {
        Some(d) => Err(d),
        None => Ok(ast::File { statements }),
    }
}

/// The statements of a piece and its first misuse of a reserved word.
struct Parsed {
    statements: Vec<ast::Statement>,
    reserved: Option<Diagnostic>,
}

/// The statements of `text` (which starts at byte `base` of the file), one
/// per pest call: pest queues two tokens of 40 bytes per pair, and a whole
/// file's queue was 32 times the size of its text (360 MB for the 11 MB
/// 100,000-sphere scene; zeroing its fresh pages took a third of the parse).
/// `None` on a syntax error.
fn parse_statements(file: FileId, text: &str, base: usize) -> Option<Parsed> {
    let builder = build::Builder {
        file,
        reserved: Default::default(),
        base: Default::default(),
    };
    let mut statements = Vec::new();
    let mut pos = 0;
    loop {
        let rest = &text[pos..];
        match PtsParser::parse(Rule::next_statement, rest) {
            Ok(mut pairs) => {
                let pair = pairs.next()?;
                let end = pair.as_span().end();
                builder.base.set(base + pos);
                if let Some(statement) = pair.into_inner().next() {
                    statements.push(builder.build_statement(statement));
                }
                pos += end.max(1);
            }
            Err(_) if PtsParser::parse(Rule::only_blanks, rest).is_ok() => break,
            Err(_) => return None,
        }
    }
    Some(Parsed {
        statements,
        reserved: builder.reserved.into_inner(),
    })
}

/// The whole file in one pest call: the path that reports syntax errors.
fn parse_whole(file: FileId, text: &str) -> Result<ast::File, Diagnostic> {
    let mut pairs =
        PtsParser::parse(Rule::file, text).map_err(|e| parser::convert_error(e, file, text))?;
    let builder = build::Builder {
        file,
        reserved: Default::default(),
        base: Default::default(),
    };
    let ast = builder.build_file(pairs.next().expect("a file pair"));
    match builder.reserved.into_inner() {
        Some(d) => Err(d),
        None => Ok(ast),
    }
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
    // A byte order mark may open the file (and only there): the first piece
    // starts after it, as `file` in the grammar skips it.
    let mut start = if text.starts_with('\u{FEFF}') { 3 } else { 0 };
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
        if depth == 0 && (b == b'}' || b == b';') && i + 1 - start >= min_piece {
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

/// The error for a bracket at `i` nested deeper than [`MAX_NESTING`].
fn too_deep(file: FileId, i: usize) -> Diagnostic {
    Diagnostic::error(
        "pts::syntax::too_deep",
        format!("nesting deeper than {MAX_NESTING} levels"),
        Span::new(file, i, i + 1),
    )
    .with_label("this bracket opens one level too many")
    .with_help("flatten the expression or block; use `let` for parts of it")
}

#[cfg(test)]
mod tests {
    use super::*;

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
    fn pieces_and_single_statements_build_the_whole_file_ast() {
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
        // `}` and `;` inside strings and comments must not cut a piece: three
        // statements, three cuts, and the blank rest.
        let tricky = "mesh { file \"a};b.obj\" // } ;\n material m } /* }; */ let s = \"x;}\";\n\
                      render { output \"o}.png\" }\n";
        assert_eq!(
            pieces(tricky, 1).map(|p| p.len()),
            Ok(4),
            "{:?}",
            pieces(tricky, 1)
        );
        texts.push(tricky.to_string());
        for text in &texts {
            let whole = parse_whole(FileId(0), text).expect("parses");
            // Pieces as small as possible (cut after every statement), and
            // one piece parsed statement by statement.
            for min_piece in [1, usize::MAX] {
                let pieces = parse_in_pieces(FileId(0), text, min_piece).expect("parses");
                assert_eq!(pieces, whole, "{text}");
            }
        }
        // An error in a later piece is the error a whole-file parse reports.
        let broken = "let a = 1;\nsphere { radius 1 }\nsphere { radius < 1, }\nlet b = 2;\n";
        let expected = format!("{:?}", parse_whole(FileId(0), broken).unwrap_err());
        for min_piece in [1, usize::MAX] {
            let got = parse_in_pieces(FileId(0), broken, min_piece).unwrap_err();
            assert_eq!(format!("{got:?}"), expected);
        }
    }

    #[test]
    fn a_byte_order_mark_is_blank_only_at_the_start() {
        for min_piece in [1, usize::MAX] {
            let parse = |text: &str| parse_in_pieces(FileId(0), text, min_piece);
            assert!(parse("\u{FEFF}").is_ok());
            assert_eq!(
                parse("\u{FEFF}let a = 1;")
                    .expect("parses")
                    .statements
                    .len(),
                1
            );
            assert!(parse("let a = 1;\u{FEFF}let b = 2;").is_err());
            // Rust's blanks: vertical tab, form feed, NEL and the line separator.
            let blanks = "let\u{B}a\u{C}=\u{85}1\u{2028};";
            assert_eq!(parse(blanks).expect("parses").statements.len(), 1);
        }
    }
}
