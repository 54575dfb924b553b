//! Syntax: text → AST. The only module that sees pest; `Pair`s never leave it.

pub mod ast;
mod build;
pub mod parser;
pub mod povray;

use crate::diag::{codes, Diagnostic};
use crate::source::FileId;
use crate::span::Span;
use parser::{PtsParser, Rule};
use pest::Parser;

/// The deepest nesting of `(`, `[`, `<` and `{` the parser accepts. Deeper input is
/// reported instead of risking the stack of a recursive-descent parser.
pub const MAX_NESTING: usize = 128;

/// Parses one file into an AST, or returns the first syntax error.
pub fn parse(file: FileId, text: &str) -> Result<ast::File, Diagnostic> {
    parse_in_pieces(file, text, PIECE)
}

/// Parses `text` and hands its statements to `sink` in file order, a piece at
/// a time, while the pieces after it are still being parsed: a checker
/// consuming them runs beside the parser instead of after it. On an error the
/// statements before it have been handed over and the first error of the file
/// (a syntax error exactly as a whole-file parse reports it, or a misused
/// reserved word) is returned.
pub fn parse_each(
    file: FileId,
    text: &str,
    sink: &mut (dyn FnMut(Vec<ast::Statement>) + Send),
) -> Result<(), Diagnostic> {
    parse_each_in_pieces(file, text, PIECE, sink)
}

/// Least size of the pieces a file is cut into, each parsed in one pest call.
const PIECE: usize = 16 * 1024;

/// Pieces parsed in parallel between two hand-overs to the sink (512 KB):
/// enough to keep both cores busy, few enough that the sink starts early.
const BATCH: usize = 32;

/// [`parse`] with the text cut into pieces of at least `min_piece` bytes.
fn parse_in_pieces(file: FileId, text: &str, min_piece: usize) -> Result<ast::File, Diagnostic> {
    let mut statements = Vec::new();
    parse_each_in_pieces(file, text, min_piece, &mut |piece| statements.extend(piece))?;
    Ok(ast::File { statements })
}

/// [`parse_each`] with pieces of at least `min_piece` bytes.
fn parse_each_in_pieces(
    file: FileId,
    text: &str,
    min_piece: usize,
    sink: &mut (dyn FnMut(Vec<ast::Statement>) + Send),
) -> Result<(), Diagnostic> {
    use rayon::prelude::*;
    let pieces = pieces(text, min_piece).map_err(|at| too_deep(file, at))?;
    // Each round parses one batch while the sink takes the batch before it.
    let mut ready: Vec<Parsed> = Vec::new();
    for batch in pieces.chunks(BATCH) {
        let (parsed, stop) = rayon::join(
            || {
                batch
                    .par_iter()
                    .map(|&(start, end)| parse_statements(file, &text[start..end], start))
                    .collect::<Vec<Parsed>>()
            },
            || hand_over(std::mem::take(&mut ready), sink),
        );
        if let Some(error) = stop {
            return Err(error.into_diagnostic(file, text));
        }
        ready = parsed;
    }
    match hand_over(ready, sink) {
        Some(error) => Err(error.into_diagnostic(file, text)),
        None => Ok(()),
    }
}

/// Gives the statements of `pieces` to `sink` in order, up to the first
/// error, which it returns.
fn hand_over(
    pieces: Vec<Parsed>,
    sink: &mut (dyn FnMut(Vec<ast::Statement>) + Send),
) -> Option<PieceError> {
    for piece in pieces {
        if !piece.statements.is_empty() {
            sink(piece.statements);
        }
        if piece.error.is_some() {
            return piece.error;
        }
    }
    None
}

/// The statements of a piece up to its first error.
struct Parsed {
    statements: Vec<ast::Statement>,
    error: Option<PieceError>,
}

/// Why a piece stopped early.
enum PieceError {
    /// pest failed: the whole file is parsed again for the exact error.
    Syntax,
    /// A reserved word used as a name (the builder's diagnostic).
    Reserved(Diagnostic),
}

impl PieceError {
    fn into_diagnostic(self, file: FileId, text: &str) -> Diagnostic {
        match self {
            // A syntax error: parse the whole file so that the error is
            // reported exactly as a whole-file parse finds it.
            PieceError::Syntax => match parse_whole(file, text) {
                Err(d) => d,
                // The two paths accept the same files (tested); were they
                // ever to disagree, say so rather than panic.
                Ok(_) => Diagnostic::error(
                    codes::INTERNAL,
                    "the parser disagreed with itself on this file",
                    Span::new(file, 0, 0),
                )
                .with_label("parsed whole but not in pieces")
                .with_help("please report this file as a ptsc bug"),
            },
            PieceError::Reserved(d) => d,
        }
    }
}

/// The statements of `text` (which starts at byte `base` of the file): the
/// whole piece in one pest call, or, if that fails, one statement per call up
/// to the error. Pieces are small: pest queues two tokens of 40 bytes per
/// pair, and a whole file's queue was 32 times the size of its text (360 MB
/// for the 11 MB 100,000-sphere scene; zeroing its fresh pages took a third
/// of the parse), while a call per statement paid pest's set-up and the
/// growth of its queue every time (5 % of the parse).
/// Stops at the first syntax error or misused reserved word.
fn parse_statements(file: FileId, text: &str, base: usize) -> Parsed {
    let builder = build::Builder {
        file,
        reserved: Default::default(),
        base: std::cell::Cell::new(base),
    };
    let mut parsed = Parsed {
        statements: Vec::new(),
        error: None,
    };
    // Builds a statement pair into `parsed`; false at a misused reserved word.
    let keep = |pair, parsed: &mut Parsed| {
        let statement = builder.build_statement(pair);
        match builder.reserved.take() {
            Some(d) => {
                parsed.error = Some(PieceError::Reserved(d));
                false
            }
            None => {
                parsed.statements.push(statement);
                true
            }
        }
    };
    if let Ok(mut pairs) = PtsParser::parse(Rule::file, text) {
        let pairs = pairs.next().expect("file matched").into_inner();
        for pair in pairs.filter(|p| p.as_rule() != Rule::EOI) {
            if !keep(pair, &mut parsed) {
                break;
            }
        }
        return parsed;
    }
    let mut pos = 0;
    loop {
        let rest = &text[pos..];
        match PtsParser::parse(Rule::next_statement, rest) {
            Ok(mut pairs) => {
                let pair = pairs.next().expect("next_statement matched");
                let end = pair.as_span().end();
                builder.base.set(base + pos);
                if let Some(statement) = pair.into_inner().next() {
                    if !keep(statement, &mut parsed) {
                        return parsed;
                    }
                }
                pos += end.max(1);
            }
            Err(_) if PtsParser::parse(Rule::only_blanks, rest).is_ok() => return parsed,
            Err(_) => {
                parsed.error = Some(PieceError::Syntax);
                return parsed;
            }
        }
    }
}

/// The whole file in one pest call: the path that reports syntax errors.
fn parse_whole(file: FileId, text: &str) -> Result<ast::File, Diagnostic> {
    let bom = bom_len(text);
    let mut pairs = PtsParser::parse(Rule::file, &text[bom..])
        .map_err(|e| parser::convert_error(e, file, text, bom))?;
    let builder = build::Builder {
        file,
        reserved: Default::default(),
        base: std::cell::Cell::new(bom),
    };
    let ast = builder.build_file(pairs.next().expect("a file pair"));
    match builder.reserved.into_inner() {
        Some(d) => Err(d),
        None => Ok(ast),
    }
}

/// The length of the byte order mark that may open a file (and only there):
/// both parse paths start after it.
fn bom_len(text: &str) -> usize {
    if text.starts_with('\u{FEFF}') {
        '\u{FEFF}'.len_utf8()
    } else {
        0
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

/// Whether `rest` (what follows a `}` at nesting depth 0) goes on with a
/// new statement: a word other than `else`, or nothing. A `}` followed by
/// `else`, `;`, `{` or an operator closes a branch of an `if` (a statement
/// or a value, `let y = if a { 1 } else { 2 };`), not a statement.
fn statement_follows(rest: &str) -> bool {
    let mut rest = rest;
    loop {
        rest = rest.trim_start();
        if let Some(r) = rest.strip_prefix("//") {
            rest = r.find('\n').map_or("", |k| &r[k..]);
        } else if let Some(r) = rest.strip_prefix("/*") {
            rest = r.find("*/").map_or("", |k| &r[k + 2..]);
        } else {
            break;
        }
    }
    let word_len = rest
        .find(|c: char| !(c.is_alphanumeric() || c == '_'))
        .unwrap_or(rest.len());
    rest.is_empty() || (word_len > 0 && &rest[..word_len] != "else")
}

/// Calls `f(offset, byte)` for every bracket (`(`, `)`, `[`, `]`, `<`, `>`, `{`, `}`)
/// and `;` of `text` outside comments and strings: the scans for parse pieces
/// and unclosed blocks need to see those only. `f` returns `false` to stop.
pub(crate) fn for_each_code_mark(text: &str, mut f: impl FnMut(usize, u8) -> bool) {
    /// Bytes the loop stops at: the marks, and what opens a comment or string.
    const STOP: [bool; 256] = {
        let mut t = [false; 256];
        let mut k = 0;
        let marks = b"()[]<>{};/\"";
        while k < marks.len() {
            t[marks[k] as usize] = true;
            k += 1;
        }
        t
    };
    let bytes = text.as_bytes();
    let mut i = 0;
    while i < bytes.len() {
        // Most bytes are none of these: one table load each (this scan runs
        // before the parallel parse starts, over the whole file).
        if !STOP[bytes[i] as usize] {
            i += 1;
            continue;
        }
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
            b'/' => {}
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
        codes::TOO_DEEP,
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
            // the whole text as one piece.
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

    /// Whole statements, blanks and comments (holding `}` and `;`), so that
    /// most texts parse and are cut in many places.
    const STATEMENTS: &[&str] = &[
        "sphere { radius 1 }",
        "let a = 1;",
        "material m { diffuse rgb 0.5 }",
        "sphere { center <1, 2, 3> material m radius -(2) * 3 }",
        "background rgb 1",
        "for i in 0..2 { sphere { radius i } }",
        "mesh { file \"a};b.obj\" }",
        "if a < b { let c = 1; } else if a > 2 { sphere { radius 1 } } else { }",
        "if a <= 1 {}",
        " else { let d = 2; }",
        "let y = if a < 1 { [1, 2][0] } else { 3 } + 1;",
        "fn f(x, y) = if x >= y && !(x == 2) { x } else { y };",
        "group g { cylinder { base <0, 0, 0> top <0, a < 1, 0> radius 1 } }",
        "instance g { translate <1, 0, 0> }",
        "for x in [1, 2] { torus { minor_radius x } }",
        "\n",
        " ",
        "// };\n",
        "/* ; } */",
        "\r\n",
        "\t",
    ];

    /// Fragments that break a text, or nearly do.
    const JUNK: &[&str] = &[
        "{", "}", ";", "<", ">", "(", "\"", "/*", "\u{FEFF}", "let", "1", "else", "[", "]", "if",
    ];

    proptest::proptest! {
        #[test]
        fn pieces_and_the_whole_file_agree(
            tokens in proptest::collection::vec(
                proptest::prop_oneof![
                    9 => proptest::sample::select(STATEMENTS),
                    1 => proptest::sample::select(JUNK),
                ],
                0..16,
            ),
            bom in proptest::bool::ANY,
        ) {
            let text = format!("{}{}", if bom { "\u{FEFF}" } else { "" }, tokens.concat());
            let whole = parse_whole(FileId(0), &text).map_err(|d| format!("{d:?}"));
            for min_piece in [1, 7, usize::MAX] {
                let pieces = parse_in_pieces(FileId(0), &text, min_piece).map_err(|d| format!("{d:?}"));
                proptest::prop_assert_eq!(&pieces, &whole, "{:?}", text);
            }
        }
    }
}
