//! Never a panic: hand-written nasty inputs and a property test over random
//! and mutated text. Each input must give a scene or diagnostics, nothing else.

use proptest::prelude::*;
use ptsc::check::{check_bytes, check_file};
use std::path::Path;

fn run(bytes: &[u8]) -> ptsc::check::Checked {
    let c = check_bytes(Path::new("nasty.pts"), bytes.to_vec());
    // Rendering every diagnostic must not panic either (spans inside the text).
    let _ = c.diagnostics.render_human(&c.sources, false);
    let _ = c.diagnostics.render_json(&c.sources);
    c
}

fn errors(bytes: &[u8]) -> Vec<&'static str> {
    run(bytes)
        .diagnostics
        .items
        .iter()
        .filter(|d| d.is_error())
        .map(|d| d.code)
        .collect()
}

#[test]
fn empty_file_needs_a_camera() {
    assert_eq!(errors(b""), vec!["pts::check::missing_camera"]);
}

#[test]
fn binary_bytes_and_invalid_utf8_are_diagnostics() {
    let e = errors(&[0xff, 0xfe, 0x80, b'{', 0x1b]);
    assert!(e.contains(&"pts::check::invalid_utf8"), "{e:?}");
    // A NUL or an image's signature: not a scene, one error, no parse.
    let e = errors(&[0, 1, 2, 3, 4, 5, 6, 7]);
    assert_eq!(e, vec!["pts::check::not_a_scene"]);
    let png = b"\x89PNG\r\n\x1a\n\0\0\0\rIHDR\x1b[2J\x07";
    assert_eq!(errors(png), vec!["pts::check::not_a_scene"]);
}

#[test]
fn control_bytes_never_reach_the_terminal() {
    // An escape in a scene (a slip, or a file that is not one) is shown as
    // `?` in the excerpt: the terminal is not told to clear or recolour.
    let text = "camera { position <0, 0, 5> look_at <0, 0, 0> }\nx\x1b[2J = 1;\x07\n";
    let checked = ptsc::check::check_str(std::path::Path::new("esc.pts"), text);
    let shown = checked.diagnostics.render_human(&checked.sources, false);
    assert!(!shown.is_empty());
    assert!(!shown.contains(['\x1b', '\x07']), "{shown:?}");
    assert!(shown.contains("x?[2J = 1;?"), "{shown}");
}

#[test]
fn unterminated_string_and_comment() {
    assert_eq!(
        errors(b"mesh { file \"abc }"),
        vec!["pts::syntax::unterminated_string"]
    );
    assert_eq!(
        errors(b"/* open"),
        vec!["pts::syntax::unterminated_comment"]
    );
}

#[test]
fn ten_thousand_nested_braces() {
    let s = "{".repeat(10_000) + &"}".repeat(10_000);
    assert!(!errors(s.as_bytes()).is_empty());
    let s = format!("let x = {}1{};", "(".repeat(10_000), ")".repeat(10_000));
    assert_eq!(errors(s.as_bytes()), vec!["pts::syntax::too_deep"]);
    let s = format!("let x = {}1;", "-".repeat(100_000));
    let _ = run(s.as_bytes());
}

#[test]
fn huge_and_non_finite_numbers() {
    let cam = "camera { position <0,0,5> look_at <0,0,0> }\n";
    let e = errors(format!("{cam}sphere {{ center <0,0,0> radius 1e400 }}").as_bytes());
    assert_eq!(e, vec!["pts::check::not_finite"]);
    // Finite in f64, but beyond what the f32 renderer takes (the numeric domain).
    let e = errors(
        format!("{cam}sphere {{ center <0,0,0> radius 99999999999999999999999999999999 }}")
            .as_bytes(),
    );
    assert_eq!(e, vec!["pts::check::out_of_range"]);
    let e = errors(format!("{cam}sphere {{ center <0,0,0> radius 1e9 }}").as_bytes());
    assert!(e.is_empty(), "{e:?}");
    let e = errors(format!("{cam}sphere {{ center <0,0,0> radius NaN }}").as_bytes());
    assert_eq!(e, vec!["pts::check::unknown_name"]);
    let e = errors(format!("{cam}sphere {{ center <0,0,0> radius 1e300 * 1e300 }}").as_bytes());
    assert_eq!(e, vec!["pts::check::not_finite"]);
}

#[test]
fn bom_and_crlf_are_fine() {
    let text = "\u{feff}camera { position <0,0,5> look_at <0,0,0> }\r\npoint_light { position <0,5,0> intensity rgb 1 }\r\nsphere { center <0,0,0> radius 1 }\r\n";
    let c = run(text.as_bytes());
    assert!(!c.diagnostics.has_errors(), "{:?}", c.diagnostics);
    // A CRLF file still reports the right line.
    let text = "camera { position <0,0,5> look_at <0,0,0> }\r\n\r\nsphere { center <0,0,0> radius -1 }\r\n";
    let c = run(text.as_bytes());
    let d = c.diagnostics.items.iter().find(|d| d.is_error()).unwrap();
    assert_eq!(
        c.sources
            .line_col(d.span.unwrap().file, d.span.unwrap().start)
            .0,
        3
    );
}

#[test]
fn include_of_a_directory() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("sub")).unwrap();
    let scene = dir.path().join("s.pts");
    std::fs::write(
        &scene,
        "include \"sub\"\ncamera { position <0,0,5> look_at <0,0,0> }\n",
    )
    .unwrap();
    let c = check_file(&scene).unwrap();
    let e: Vec<_> = c
        .diagnostics
        .items
        .iter()
        .filter(|d| d.is_error())
        .map(|d| d.code)
        .collect();
    assert_eq!(e, vec!["pts::check::include_not_found"]);
}

#[test]
fn include_cycle_is_reported() {
    let root = crate::root().join("tests/diagnostics/include_cycle.pts");
    let c = check_file(&root).unwrap();
    assert!(c
        .diagnostics
        .items
        .iter()
        .any(|d| d.code == "pts::check::include_cycle"));
}

#[test]
fn loops_are_bounded() {
    let e = errors(b"for i in 0..1000 { for j in 0..1000 { for k in 0..1000 { let x = i; } } }");
    assert!(e.contains(&"pts::check::loop_too_long"), "{e:?}");
}

const TOKENS: &[&str] = &[
    "sphere",
    "{",
    "}",
    "<",
    ">",
    ",",
    "(",
    ")",
    "center",
    "radius",
    "1",
    "-2.5",
    "1e400",
    "material",
    "rgb",
    "let",
    "x",
    "=",
    ";",
    "for",
    "in",
    "..",
    "include",
    "\"",
    "/*",
    "*/",
    "//",
    "\n",
    " ",
    "camera",
    "render",
    "+",
    "*",
    "/",
    "-",
    "sqrt",
    "true",
    "quad",
    "mesh",
    "\"a.obj\"",
    "\u{feff}",
    "é",
];

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

    #[test]
    fn random_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..200)) {
        let _ = run(&bytes);
    }

    #[test]
    fn random_token_soup_never_panics(tokens in proptest::collection::vec(proptest::sample::select(TOKENS), 0..60)) {
        let text = tokens.join(" ");
        let _ = run(text.as_bytes());
    }

    #[test]
    fn mutated_examples_never_panic(cut in 0usize..4000, insert in proptest::sample::select(TOKENS)) {
        let base = std::fs::read_to_string(crate::root().join("examples/bench/cornell.pts")).unwrap();
        let mut cut = cut.min(base.len());
        while !base.is_char_boundary(cut) { cut -= 1; }
        let text = format!("{}{}{}", &base[..cut], insert, &base[cut..]);
        let _ = run(text.as_bytes());
        let _ = run(&base.as_bytes()[..cut]);
    }
}

/// Issue 35, item 12: vectors at the edges of 64-bit floats. Their squared
/// lengths overflowed (`normalize(<1e200, 0, 0>)` was `<0, 0, 0>`, a
/// length "not a finite number") or underflowed ("cannot normalize a zero
/// vector"), and a whole loop bound too large was "not a whole number".
#[test]
fn numbers_at_the_edges_of_f64() {
    let text = "camera { position <0,0,5> look_at <0,0,0> }\n\
        background rgb 1\n\
        let big = normalize(<1e200, 0, 0>);\n\
        let tiny = normalize(<0, 1e-200, 0>);\n\
        sphere { center big + tiny radius length(<1e200, 0, 0>) / 1e200 }\n";
    let c = run(text.as_bytes());
    let scene = c.scene.unwrap_or_else(|| {
        panic!("{}", c.diagnostics.render_human(&c.sources, false));
    });
    match scene.objects[0].shape {
        ptsc::check::Shape::Sphere { center, radius, .. } => {
            assert_eq!((center.to_array(), radius), ([1.0, 1.0, 0.0], 1.0));
        }
        ref other => panic!("not a sphere: {other:?}"),
    }
    let c =
        run(b"camera { position <0,0,5> look_at <0,0,0> }\nfor i in 0..1e300 { let _x = i; }\n");
    let d = c.diagnostics.items.iter().find(|d| d.is_error()).unwrap();
    assert_eq!(d.code, "pts::check::loop_too_long");
    assert!(d.message.contains("1e300 times"), "{}", d.message);
}
