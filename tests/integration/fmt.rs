//! `ptsc fmt`: idempotent on every scene the project keeps (examples,
//! diagnostics, golden, hostile, the docs' `pts` snippets), keeping the
//! syntax tree (spans aside) and every comment; a property test over random
//! scenes with comments in random gaps; the command line (`--check`, in
//! place, syntax errors, stdin).

use crate::{files_below, ptsc, root, temp_dir_with};
use proptest::prelude::*;
use ptsc::format::{format_text, spanless, FormatError};

/// The syntax tree of `text`, spans aside (`None`: it does not parse).
fn tree(text: &str) -> Option<String> {
    ptsc::syntax::parse(ptsc::source::FileId(0), text, &ptsc::check::kinds::NAMES)
        .ok()
        .map(|f| spanless(&f))
}

/// The comments of `text`, sorted, by a scan of its own (strings skipped).
fn comments(text: &str) -> Vec<String> {
    let b = text.as_bytes();
    let (mut out, mut i) = (Vec::new(), 0);
    while i < b.len() {
        if b[i] == b'"' {
            i += 1;
            while i < b.len() && b[i] != b'"' && b[i] != b'\n' {
                i += if b[i] == b'\\' { 2 } else { 1 };
            }
        } else if text[i..].starts_with("//") {
            let end = text[i..].find('\n').map_or(text.len(), |k| i + k);
            out.push(text[i..end].trim_end().to_string());
            i = end;
        } else if text[i..].starts_with("/*") {
            let end = text[i + 2..].find("*/").map_or(text.len(), |k| i + k + 4);
            out.push(text[i..end].to_string());
            i = end;
        }
        i += 1;
    }
    out.sort();
    out
}

/// Formats `text` and checks the result: same tree, same comments,
/// idempotent. `false`: the text does not parse (nothing to check).
fn check_one(name: &str, text: &str) -> bool {
    let Some(before) = tree(text) else {
        assert!(matches!(format_text(text), Err(FormatError::Syntax(_))));
        return false;
    };
    let once = format_text(text).unwrap_or_else(|e| panic!("{name}: {e}"));
    assert_eq!(
        tree(&once).as_deref(),
        Some(before.as_str()),
        "{name}: tree"
    );
    assert_eq!(comments(&once), comments(text), "{name}: comments");
    let twice = format_text(&once).unwrap_or_else(|e| panic!("{name} (twice): {e}"));
    assert_eq!(once, twice, "{name}: not idempotent");
    true
}

/// The ```pts blocks of the docs and the README.
fn doc_snippets() -> Vec<(String, String)> {
    let mut docs = files_below(&root().join("docs"), "md");
    docs.push(root().join("README.md"));
    let mut out = Vec::new();
    for doc in docs {
        let text = std::fs::read_to_string(&doc).unwrap();
        for (k, part) in text.split("```pts\n").skip(1).enumerate() {
            let code = part.split("```").next().unwrap_or("");
            out.push((format!("{}#{k}", doc.display()), code.to_string()));
        }
    }
    out
}

#[test]
fn fmt_is_idempotent_and_faithful_on_every_kept_scene() {
    let mut files = Vec::new();
    for dir in [
        "examples",
        "tests/diagnostics",
        "tests/golden",
        "tests/hostile",
    ] {
        files.extend(files_below(&root().join(dir), "pts"));
        files.extend(files_below(&root().join(dir), "ptsi"));
    }
    let mut texts: Vec<(String, String)> = files
        .iter()
        .map(|f| (f.display().to_string(), std::fs::read_to_string(f).unwrap()))
        .collect();
    let snippets = doc_snippets();
    assert!(snippets.len() > 20, "{} snippets", snippets.len());
    texts.extend(snippets);
    let checked = texts.iter().filter(|(n, t)| check_one(n, t)).count();
    assert!(checked > 250, "only {checked} of {} parse", texts.len());
}

/// Expression tokens: `component` without bare comparisons (vector
/// components, parameter values), `expr` with them.
fn component() -> BoxedStrategy<Vec<String>> {
    let leaf = prop_oneof![
        prop::sample::select(vec!["1", "0.5", ".5", "2.", "1e3", "2.5E-2", "42"]),
        prop::sample::select(vec!["a", "b", "size", "xs"]),
        prop::sample::select(vec!["\"s\"", "\"a\\\"b\"", "\"// no\"", "true", "false"]),
    ]
    .prop_map(|t| vec![t.to_string()]);
    leaf.prop_recursive(3, 24, 3, |inner| {
        let op = prop::sample::select(vec!["+", "-", "*", "/", "%", "==", "!=", "&&", "||"]);
        prop_oneof![
            (inner.clone(), op, inner.clone()).prop_map(|(a, o, b)| cat([a, vec![o.into()], b])),
            prop::collection::vec(inner.clone(), 2..4).prop_map(|c| wrap("<", c, ">")),
            prop::collection::vec(inner.clone(), 0..3).prop_map(|c| wrap("[", c, "]")),
            prop::collection::vec(inner.clone(), 1..3)
                .prop_map(|c| cat([vec!["f".into()], wrap("(", c, ")")])),
            inner.clone().prop_map(|e| wrap("(", vec![e], ")")),
            inner.clone().prop_map(|e| cat([vec!["-".into()], e])),
            inner.clone().prop_map(|e| cat([vec!["!".into()], e])),
            inner
                .clone()
                .prop_map(|e| cat([vec!["xs".into(), "[".into()], e, vec!["]".into()]])),
            (inner.clone(), inner.clone(), inner).prop_map(|(c, a, b)| cat([
                vec!["if".into()],
                c,
                vec!["{".into()],
                a,
                vec!["}".into(), "else".into(), "{".into()],
                b,
                vec!["}".into()]
            ])),
            prop::sample::select(vec!["0.5", "<1, 2, 3>"])
                .prop_map(|v| cat([vec!["rgb".into()], v.split(' ').map(String::from).collect()])),
        ]
    })
    .boxed()
}

/// An expression that may compare.
fn expr() -> BoxedStrategy<Vec<String>> {
    prop_oneof![
        3 => component(),
        1 => (component(), prop::sample::select(vec!["<", ">", "<=", ">="]), component())
            .prop_map(|(a, o, b)| cat([a, vec![o.into()], b])),
    ]
    .boxed()
}

/// Joins token lists.
fn cat<const N: usize>(parts: [Vec<String>; N]) -> Vec<String> {
    parts.into_iter().flatten().collect()
}

/// `open a , b , c close`.
fn wrap(open: &str, items: Vec<Vec<String>>, close: &str) -> Vec<String> {
    let mut out = vec![open.to_string()];
    for (k, item) in items.into_iter().enumerate() {
        if k > 0 {
            out.push(",".into());
        }
        out.extend(item);
    }
    out.push(close.into());
    out
}

/// A block `{ entries }`.
fn block() -> BoxedStrategy<Vec<String>> {
    let entry = prop_oneof![
        3 => (prop::sample::select(vec!["radius", "center", "scale"]), component())
            .prop_map(|(n, v)| cat([vec![n.into()], v])),
        1 => Just(vec!["material".into(), "m".into()]),
        1 => Just(vec!["diffuse".into(), "checker".into(), "{".into(), "even".into(), "rgb".into(), "1".into(), "}".into()]),
        1 => (component(), component()).prop_map(|(a, b)| cat([vec!["stop".into()], a, b])),
    ];
    (prop::collection::vec(entry, 0..5), any::<bool>())
        .prop_map(|(entries, flag)| {
            let mut out = vec!["{".to_string()];
            out.extend(entries.into_iter().flatten());
            if flag {
                out.push("no_shadow".into());
            }
            out.push("}".into());
            out
        })
        .boxed()
}

/// A statement's tokens.
fn statement() -> BoxedStrategy<Vec<String>> {
    let simple = prop_oneof![
        expr().prop_map(|e| cat([
            vec!["let".into(), "a".into(), "=".into()],
            e,
            vec![";".into()]
        ])),
        expr().prop_map(|e| cat([
            vec![
                "fn".into(),
                "g".into(),
                "(".into(),
                "x".into(),
                ",".into(),
                "y".into(),
                ")".into(),
                "=".into()
            ],
            e,
            vec![";".into()]
        ])),
        block().prop_map(|b| cat([vec!["sphere".into()], b])),
        block().prop_map(|b| cat([vec!["material".into(), "m".into()], b])),
        block().prop_map(|b| cat([vec!["texture".into(), "t".into(), "wood".into()], b])),
        component().prop_map(|e| cat([vec!["background".into()], e])),
        Just(vec!["include".into(), "\"x.ptsi\"".into()]),
    ];
    simple
        .prop_recursive(2, 12, 3, |inner| {
            let body = prop::collection::vec(inner, 0..3).prop_map(|s| {
                cat([
                    vec!["{".into()],
                    s.into_iter().flatten().collect(),
                    vec!["}".into()],
                ])
            });
            prop_oneof![
                body.clone()
                    .prop_map(|b| cat([vec!["group".into(), "g".into()], b])),
                (component(), body.clone()).prop_map(|(n, b)| cat([
                    vec![
                        "for".into(),
                        "i".into(),
                        "in".into(),
                        "0".into(),
                        "..".into()
                    ],
                    n,
                    b
                ])),
                (expr(), body.clone(), prop::option::of(body)).prop_map(|(c, b, e)| {
                    let mut out = cat([vec!["if".into()], c, b]);
                    if let Some(e) = e {
                        out.push("else".into());
                        out.extend(e);
                    }
                    out
                }),
            ]
        })
        .boxed()
}

/// Joins tokens with the gaps: blanks, line ends, comments.
fn join(tokens: &[String], gaps: &[u8]) -> String {
    let mut out = String::new();
    for (k, t) in tokens.iter().enumerate() {
        out.push_str(t);
        out.push_str(&match gaps.get(k).copied().unwrap_or(0) % 12 {
            0..=4 => " ".to_string(),
            5 | 6 => "\n".to_string(),
            7 => "\n\n\n  ".to_string(),
            8 => "\t".to_string(),
            9 => format!(" /* k{k} */ "),
            10 => format!(" // k{k}\n"),
            _ => format!("\n/* k{k}\n   more */\n"),
        });
    }
    out
}

proptest! {
    #[test]
    fn fmt_keeps_random_scenes_and_their_comments(
        statements in prop::collection::vec(statement(), 1..5),
        gaps in prop::collection::vec(any::<u8>(), 0..400),
    ) {
        let tokens: Vec<String> = statements.into_iter().flatten().collect();
        let text = join(&tokens, &gaps);
        prop_assume!(tree(&text).is_some());
        check_one("random scene", &text);
    }
}

#[test]
fn fmt_check_lists_files_that_would_change_and_changes_nothing() {
    let formatted = "sphere { radius 1 }\n";
    let messy = "sphere {radius   1}";
    let dir = temp_dir_with(&[("a.pts", formatted), ("b.pts", messy)]);
    let (a, b) = (dir.path().join("a.pts"), dir.path().join("b.pts"));
    let (code, out, _) = ptsc(&["fmt", "--check", a.to_str().unwrap()]);
    assert_eq!((code, out.as_str()), (0, ""));
    let (code, out, _) = ptsc(&["fmt", "--check", a.to_str().unwrap(), b.to_str().unwrap()]);
    assert_eq!(code, 1);
    assert_eq!(out.trim(), b.display().to_string());
    assert_eq!(std::fs::read_to_string(&b).unwrap(), messy);
}

#[test]
fn fmt_rewrites_in_place_and_leaves_formatted_files_alone() {
    let dir = temp_dir_with(&[("a.pts", "sphere { radius 1 }\n"), ("b.pts", "let a=1;\n")]);
    let (a, b) = (dir.path().join("a.pts"), dir.path().join("b.pts"));
    let stamp = std::fs::metadata(&a).unwrap().modified().unwrap();
    std::thread::sleep(std::time::Duration::from_millis(20));
    let (code, _, err) = ptsc(&["fmt", dir.path().to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(std::fs::read_to_string(&b).unwrap(), "let a = 1;\n");
    assert_eq!(std::fs::metadata(&a).unwrap().modified().unwrap(), stamp);
    let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert_eq!(left.len(), 2, "no temporary file left");
}

#[test]
fn fmt_refuses_a_syntax_error_and_leaves_the_file() {
    let broken = "sphere { radius 1\nlet a = ;\n";
    let dir = temp_dir_with(&[("bad.pts", broken)]);
    let bad = dir.path().join("bad.pts");
    let (code, _, err) = ptsc(&["fmt", bad.to_str().unwrap()]);
    assert_eq!(code, 1);
    assert!(err.contains("pts::syntax"), "{err}");
    assert!(err.contains("bad.pts"), "{err}");
    assert_eq!(std::fs::read_to_string(&bad).unwrap(), broken);
}

#[test]
fn fmt_refuses_a_model_as_check_does_and_says_where_a_text_is_not_utf8() {
    let obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    let dir = crate::temp_dir_with(&[("tri.obj", obj)]);
    let model = dir.path().join("tri.obj");
    let (code, err) = crate::ptsc_stderr(&["fmt", model.to_str().unwrap()]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("pts::check::not_a_scene"), "{err}");
    assert!(err.contains("an OBJ model, not a scene"), "{err}");
    assert_eq!(std::fs::read_to_string(&model).unwrap(), obj);

    let latin1 = dir.path().join("latin1.pts");
    std::fs::write(&latin1, b"// ok\n// caf\xe9\nlet a = 1;\n").unwrap();
    let (code, err) = crate::ptsc_stderr(&["fmt", latin1.to_str().unwrap()]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("not UTF-8 text (byte 12, line 2)"), "{err}");
}

#[test]
fn fmt_reads_stdin_and_writes_stdout() {
    let run = |args: &[&str], input: &str| {
        let input = std::io::Cursor::new(input.to_string());
        let (code, out, _) = crate::ptsc_fed(std::path::Path::new("."), args, input);
        (Some(code), out)
    };
    assert_eq!(
        run(&["fmt", "-"], "let a=1; // one"),
        (Some(0), "let a = 1; // one\n".to_string())
    );
    assert_eq!(run(&["fmt"], "box{}"), (Some(0), "box {}\n".to_string()));
    assert_eq!(
        run(&["fmt", "--check", "-"], "box{}"),
        (Some(1), "<stdin>\n".to_string())
    );
    assert_eq!(run(&["fmt", "-"], "box{"), (Some(1), "box{".to_string()));
}

#[test]
fn the_examples_are_in_the_canonical_layout() {
    // A newcomer learns the layout from the examples (the bench scenes
    // are generated copies of shared/bench's, one object a line).
    let (examples, parts) = (root().join("examples"), root().join("examples/parts"));
    let (code, out, err) = ptsc(&[
        "fmt",
        "--check",
        examples.to_str().unwrap(),
        parts.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "`ptsc fmt` would change:\n{out}{err}");
}
