//! The parse paths agree: pieces, statement by statement, the whole file;
//! and reading past errors.

use super::*;

/// Kinds of block for these tests (the checker gives the parser its
/// table's names, `check::kinds::NAMES`, which the syntax module cannot
/// import; any list of names serves a test of the parser).
const KINDS: &[&str] = &[
    "render",
    "camera",
    "environment",
    "sky",
    "sphere",
    "plane",
    "quad",
    "disk",
    "triangle",
    "box",
    "cylinder",
    "cone",
    "torus",
    "mesh",
    "point_light",
    "spot_light",
    "directional_light",
];

/// The first error of `text` as the parser reports it: a whole-file parse,
/// unless a statement before where pest failed is refused while it is
/// built (a kind's broken block read whole, a reserved word as a name),
/// which the statement-by-statement reading finds first. (In the parser
/// itself the first broken statement is known, so no second reading.)
fn parse_whole(file: FileId, text: &str, kinds: &[&str]) -> Result<ast::File, Diagnostic> {
    hand_over::parse_whole(file, text, kinds).map_err(|d| {
        let read = recover::parse_from(file, (text, kinds), bom_len(text), text.len(), 1);
        (read.breaks.into_iter().next().and_then(|b| b.reserved)).unwrap_or(d)
    })
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
        let whole = parse_whole(FileId(0), text, KINDS).expect("parses");
        // Pieces as small as possible (cut after every statement), and
        // the whole text as one piece.
        for min_piece in [1, usize::MAX] {
            let pieces = parse_in_pieces(FileId(0), text, KINDS, min_piece).expect("parses");
            assert_eq!(pieces, whole, "{text}");
        }
        // One statement at a time, each in its window, as after an error.
        let slow = recover::parse_from(
            FileId(0),
            (text, KINDS),
            bom_len(text),
            text.len(),
            usize::MAX,
        );
        assert!(slow.breaks.is_empty(), "{text}");
        assert_eq!(slow.statements, whole.statements, "{text}");
    }
    // An error in a later piece is the error a whole-file parse reports.
    let broken = "let a = 1;\nsphere { radius 1 }\nsphere { radius < 1, }\nlet b = 2;\n";
    let expected = format!("{:?}", parse_whole(FileId(0), broken, KINDS).unwrap_err());
    for min_piece in [1, usize::MAX] {
        let got = parse_in_pieces(FileId(0), broken, KINDS, min_piece).unwrap_err();
        assert_eq!(format!("{got:?}"), expected);
    }
}

#[test]
fn a_byte_order_mark_is_blank_only_at_the_start() {
    for min_piece in [1, usize::MAX] {
        let parse = |text: &str| parse_in_pieces(FileId(0), text, KINDS, min_piece);
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
        let whole = parse_whole(FileId(0), &text, KINDS).map_err(|d| format!("{d:?}"));
        for min_piece in [1, 7, usize::MAX] {
            let pieces = parse_in_pieces(FileId(0), &text, KINDS, min_piece).map_err(|d| format!("{d:?}"));
            proptest::prop_assert_eq!(&pieces, &whole, "{:?}", text);
        }
        // Read past errors, the statements and errors do not depend on the
        // pieces, nor on reading one statement at a time from the start.
        let reference = recovered(&text, usize::MAX);
        for min_piece in [1, 7] {
            proptest::prop_assert_eq!(&recovered(&text, min_piece), &reference, "{:?}", text);
        }
        let (statements, errors) = reference;
        let slow = recover::parse_from(FileId(0), (&text, KINDS), bom_len(&text), text.len(), usize::MAX);
        proptest::prop_assert_eq!(&slow.statements, &statements, "{:?}", text);
        proptest::prop_assert_eq!(slow.breaks.len(), errors.len(), "{:?}", text);
        // The first error is the one parsing stops at; without errors, the
        // statements are the whole file's.
        match (&whole, errors.first()) {
            (Ok(file), None) => proptest::prop_assert_eq!(&file.statements, &statements),
            (Err(first), Some(d)) => proptest::prop_assert_eq!(first, &format!("{d:?}")),
            _ => proptest::prop_assert!(false, "{:?}: {:?}", text, errors),
        }
        // Statements in file order, each within the text.
        let mut end = 0;
        for st in &statements {
            let span = st.span();
            proptest::prop_assert!(end <= span.start && span.end as usize <= text.len());
            end = span.end;
        }
    }
}

/// The statements and errors of `text` read past its errors, with pieces
/// of at least `min_piece` bytes.
fn recovered(text: &str, min_piece: usize) -> (Vec<ast::Statement>, Vec<Diagnostic>) {
    let mut statements = Vec::new();
    let errors = parse_each_in_pieces(FileId(0), text, KINDS, min_piece, true, &mut |s| {
        statements.extend(s)
    });
    (statements, errors)
}

/// Each case: a text with mistakes, and the broken parts that are skipped.
/// Blanking those out (spaces for every byte but line ends) leaves a file
/// that parses into exactly the statements recovered outside them, spans
/// included, and each error points into its broken part (or, for a missing
/// `;`, at the token after it).
const BROKEN: &[(&str, &[&str])] = &[
    // A `;` missing after a `let`: the next line starts a statement.
    (
        "let a = 1\nsphere { radius a }\nlet b = 2;\n",
        &["let a = 1"],
    ),
    // The same within a line: a statement keyword where the `;` goes.
    (
        "let c = 1 sphere { radius c }\nlet d = 2;\n",
        &["let c = 1 "],
    ),
    // A stray token between statements.
    (
        "sphere { radius 1 }\n) oops\nsphere { radius 2 }\n",
        &[") oops"],
    ),
    // A stray token inside a block: skipped to the block's end.
    (
        "sphere { radius 1 ) }\nlet e = 1;\n",
        &["sphere { radius 1 ) }"],
    ),
    // A misspelt keyword in a loop's body: the loop is skipped whole.
    (
        "for i in 0..2 {\n  lett x = 1;\n  sphere { radius i }\n}\nsphere { radius 2 }\n",
        &["for i in 0..2 {\n  lett x = 1;\n  sphere { radius i }\n}"],
    ),
    // A string without its closing quote: the `}` after it on the line
    // still closes the block.
    (
        "mesh { file \"a.obj }\nsphere { radius 2 }\n",
        &["mesh { file \"a.obj }"],
    ),
    // A bracket left open: the `;` ends the statement.
    ("let f = (1 + 2;\nlet g = 3;\n", &["let f = (1 + 2;"]),
    // An `if` value's `else` missing: the statement ends at its `;`.
    (
        "let h = if true { 1 } oops;\nlet k = 2;\n",
        &["let h = if true { 1 } oops;"],
    ),
    // An `else` on the line after its block's `}`.
    (
        "if true { 1 }\nelse { sphere { radius 1 } }\nlet m = 1;\n",
        &["if true { 1 }\nelse { sphere { radius 1 } }"],
    ),
    // A reserved word as a name: that statement alone is dropped.
    ("let group = 1;\nlet n = 2;\n", &["let group = 1;"]),
    // Two mistakes.
    (
        "let p = 1\nsphere { radius p }\nsphere { center <1, 2 radius 1 }\nlet q = 2;\n",
        &["let p = 1", "sphere { center <1, 2 radius 1 }"],
    ),
    // A `{` never closed runs to the end of the file: nothing after it.
    (
        "let r = 1;\nsphere { radius 1\nsphere { radius 2 }\nlet s = 2;\n",
        &["sphere { radius 1\nsphere { radius 2 }\nlet s = 2;\n"],
    ),
    // A comment never closed, likewise.
    (
        "sphere { radius 1 }\n/* note\nsphere { radius 2 }\n",
        &["/* note\nsphere { radius 2 }\n"],
    ),
];

#[test]
fn statements_before_and_after_an_error_are_read() {
    for &(text, broken) in BROKEN {
        let mut blanked = text.to_string();
        let mut parts = Vec::new();
        let mut from = 0;
        for part in broken {
            let at = from + text[from..].find(part).expect("the part is in the text");
            let blank: String = part
                .chars()
                .map(|c| if c == '\n' { c } else { ' ' })
                .collect();
            blanked.replace_range(at..at + part.len(), &blank);
            parts.push(at..at + part.len());
            from = at + part.len();
        }
        let expected = parse_whole(FileId(0), &blanked, KINDS).expect("the rest parses");
        for min_piece in [1, 7, usize::MAX] {
            let (statements, errors) = recovered(text, min_piece);
            let outside: Vec<_> = (statements.into_iter())
                .filter(|s| !parts.iter().any(|p| p.contains(&(s.span().start as usize))))
                .collect();
            assert_eq!(outside, expected.statements, "{text:?}");
            assert_eq!(errors.len(), parts.len(), "{text:?}: {errors:#?}");
            for (d, part) in errors.iter().zip(&parts) {
                let at = d.span.expect("a span").start as usize;
                let next_token = text.len() - text[part.end..].trim_start().len();
                assert!(
                    part.start <= at && at <= next_token,
                    "{text:?}: {d:#?} outside {part:?}"
                );
            }
            // The first is exactly what parsing stops at.
            let first = parse_in_pieces(FileId(0), text, KINDS, min_piece).unwrap_err();
            assert_eq!(errors[0], first, "{text:?}");
        }
    }
}

#[test]
fn a_let_or_fn_without_its_semicolon_still_defines_its_name() {
    let text = "let a = 1\nfn f(x) = x * a\nsphere { radius f(a) }\nlet b = ;\n";
    let (statements, errors) = recovered(text, usize::MAX);
    assert_eq!(errors.len(), 3, "{errors:#?}");
    let shown: Vec<&str> = statements
        .iter()
        .map(|s| &text[s.span().start as usize..s.span().end as usize])
        .collect();
    assert_eq!(
        shown,
        ["let a = 1", "fn f(x) = x * a", "sphere { radius f(a) }"]
    );
}

#[test]
fn a_later_error_is_reported_as_a_parse_from_the_previous_one_finds_it() {
    let head = "let a = 1\n";
    let rest = "sphere { radius a }\nsphere { center <1, 2 radius 1 }\nlet q = 2;\n";
    let (_, errors) = recovered(&format!("{head}{rest}"), usize::MAX);
    let alone = parse_whole(FileId(0), rest, KINDS).unwrap_err();
    let span = alone.span.unwrap();
    let moved = Span::new(
        FileId(0),
        span.start as usize + head.len(),
        span.end as usize + head.len(),
    );
    assert_eq!(errors[1].span, Some(moved));
    assert_eq!(
        (&errors[1].message, &errors[1].label, &errors[1].help),
        (&alone.message, &alone.label, &alone.help)
    );
}

#[test]
fn reading_stops_after_a_hundred_errors() {
    let text = "oops 1;\nlet a = 1;\n".repeat(150);
    for min_piece in [1, usize::MAX] {
        let (statements, errors) = recovered(&text, min_piece);
        assert_eq!(statements.len(), 100);
        assert_eq!(errors.len(), 101);
        assert!(errors[100]
            .message
            .starts_with("more than 100 syntax errors"));
        let at = errors[100].span.unwrap().start as usize;
        assert_eq!(at, 100 * "oops 1;\nlet a = 1;\n".len());
    }
}

#[test]
fn an_error_in_a_block_that_starts_mid_line_is_read_without_a_panic() {
    // Found by the fuzzer after issue 37: the unclosed-block guess sliced
    // the file from the broken statement (`sphere`, after `for … {`) back
    // to the start of its line. The string left open on the first line
    // makes the first statement a piece of its own.
    let text = "era { p <0, 0,\"0> }\nfor i in 0..1 { sphere { center <0, 0, 0m1> } }\n";
    for min_piece in [1, 7, usize::MAX] {
        let (_, errors) = recovered(text, min_piece);
        assert!(
            errors
                .iter()
                .any(|d| d.message.contains("expected `>` or `,`")),
            "{errors:?}"
        );
    }
}

#[test]
fn many_broken_statements_cost_linear_time() {
    // Broken statements far from any `;` or `}` (each window is small),
    // on one line, on many lines, and valid statements between broken ones.
    let cases = [
        "sphere ".repeat(200_000),
        "let x = 1\n".repeat(100_000),
        format!("oops\n{}", "background rgb 1\n".repeat(100_000)),
        "mesh { file \"a }\n".repeat(50_000),
        "\"\\\"".repeat(100_000),
        format!("oops\n{}", "let a = 1 + 2 * 3\n".repeat(100_000)),
    ];
    for text in &cases {
        let start = std::time::Instant::now();
        let (_, errors) = recovered(text, PIECE);
        let took = start.elapsed();
        assert!(!errors.is_empty() && errors.len() <= 101);
        assert!(took.as_secs_f64() < 5.0, "{took:?} for {:?}…", &text[..40]);
    }
}
