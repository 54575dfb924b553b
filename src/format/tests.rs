//! Layout snapshots and small cases of the formatter.

use super::{format_range, format_text, FormatError};

/// The formatting of `text`, which must be idempotent.
fn fmt(text: &str) -> String {
    let once = format_text(text).unwrap_or_else(|e| panic!("{e}\n{text}"));
    let twice = format_text(&once).unwrap_or_else(|e| panic!("{e}\n{once}"));
    assert_eq!(once, twice, "not idempotent");
    once
}

#[test]
fn a_windows_file_keeps_its_line_ends() {
    let text = "// a room\r\nsphere {center <0,1,0>\r\n radius 1}\r\n/* two\r\nlines */\r\nmaterial m {\r\n    diffuse rgb 1 // white\r\n}\r\n";
    let out = fmt(text);
    assert_eq!(
        out.matches('\n').count(),
        out.matches("\r\n").count(),
        "{out:?}"
    );
    assert!(!out.contains("\r\r"), "{out:?}");
    assert_eq!(fmt(&out.replace("\r\n", "\n")), out.replace("\r\n", "\n"));
    // An editor's selection of a statement gets its line ends too.
    let (_, part) = format_range(text, 15, 20).unwrap();
    assert_eq!(part, "sphere { center <0, 1, 0> radius 1 }");
}

#[test]
fn a_short_block_stays_on_its_line() {
    assert_eq!(
        fmt("sphere   {center <0,1,0>\n radius 1}"),
        "sphere { center <0, 1, 0> radius 1 }\n"
    );
}

#[test]
fn layout_of_blocks() {
    insta::assert_snapshot!(fmt(r#"
render {resolution <256,256> samples 64}
camera { position <0, 1, 5> look_at <0, 0.5, 0> fov 40 aperture 0.05 focus_distance 5 shutter <0, 1> }
plane{normal <0,1,0> material {diffuse rgb 0.6}}
sphere { center <0, 1, 0> radius 1 material { diffuse checker { even rgb 0.9 odd rgb 0.1 scale 0.5 } reflection rgb 0.2 } }
texture oak wood { stop 0 rgb <0.55, 0.35, 0.18> stop .7 rgb <0.4, 0.24, 0.1>
                   stop 1 rgb <0.25, 0.14, 0.06> scale 0.1 }
sphere { <0, 1, 0>, 1 no_shadow }
box {}
"#));
}

#[test]
fn layout_of_statements() {
    insta::assert_snapshot!(fmt(r#"
let r=0.5;let xs=[1,2,  3,];
fn spot(i)=<60*(rand(7,3*i)-0.5),0,20-60*rand(7,3*i+1)>;
include "parts.ptsi"
background rgb <0.7,0.8,1.0>
let v = -(-r) + !true * xs[1][0] - (1.50e3) + ((r));
let w = if r < 1 { "small" } else if r >= 2 { "big" } else { "mid" };
group chair { box { min <0,0,0> max <1,1,1> }
for leg in [<0, 0>, <0.45, 0>] { box { min <leg[0], 0, leg[1]> max <leg[0] + 0.05, 0.45, leg[1] + 0.05> } } }
instance chair{translate <-1,0,0>}
for i in 0..4 { if i % 2 == 0 { sphere { center <i, 0, 0> radius 0.2 } } else if i == 3 {} else { cube { size 1 } } }
light_source { <0, 0, 0> color rgb 1 }
#declare R = 1;
#if (R)
"#));
}

#[test]
fn layout_of_comments() {
    insta::assert_snapshot!(fmt(r#"// A header comment.

/* A block comment. */
let a = 1 + /* inside */ 2; // trailing
let b = a   // before the semicolon
;


// Leading, after two empty lines (kept as one).
sphere { // after the brace
    center <0, /* in a vector */ 1, 0>
    radius .5 // trailing an entry

    // dangling at the end of a block
}
group g {
    // the only thing in a group
}
box { /* dangling in a block */ }
fn f(x, /* a parameter */ y) = x * y; /* after a function */
sphere { radius 1 } /* t1 */ /* t2 */ // t3
// at the end of the file
"#));
}

#[test]
fn blank_lines_are_kept_one_at_most() {
    assert_eq!(
        fmt("\n\n\nlet a = 1;\n\n\n\nlet b = 2;\nlet c = 3;\n\n\n"),
        "let a = 1;\n\nlet b = 2;\nlet c = 3;\n"
    );
}

#[test]
fn a_block_that_does_not_fit_is_broken_and_nested_ones_decide_alone() {
    let long = "plane { point <0, 0, 0> normal <0, 1, 0> material { diffuse checker { even rgb 0.9 odd rgb 0.1 space world scale 0.5 } reflection rgb 0.25 gloss 0.3 } }";
    let out = fmt(long);
    assert!(out.lines().all(|l| l.chars().count() <= 100), "{out}");
    assert!(out.contains("\n    material {"), "{out}");
    assert!(out
        .contains("        diffuse checker { even rgb 0.9 odd rgb 0.1 space world scale 0.5 }\n"));
}

#[test]
fn a_parenthesis_after_a_name_keeps_the_signs_that_part_them() {
    // Written without `!!`, each `(…)` would call the name before it.
    for text in [
        "sphere { stop 1 - !\"s\" stop !!(2) xs }\n",
        "sphere { radius r !!(2) }\n",
        "sphere { radius 1 - r !!(2) + 1 }\n",
        "sphere { stop 1 x !!(2), 3 }\n",
        "sphere { stop a !!(2) + x }\n",
        "sphere { stop a !!(2)[0] }\n",
    ] {
        let out = fmt(text);
        assert!(out.contains("!!("), "{text} -> {out}");
    }
    // A first value needs none, nor does a colour after a number.
    assert_eq!(fmt("sphere { (2) }\n"), "sphere { (2) }\n");
    assert_eq!(fmt("sphere { stop 1 (c) }\n"), "sphere { stop 1 (c) }\n");
}

#[test]
fn literals_keep_their_spelling() {
    assert_eq!(
        fmt("let a = .5 + 1. + 1e3 + 2.50E-2;\nlet s = \"a\\\"b\\\\ // no\";\n"),
        "let a = .5 + 1. + 1e3 + 2.50E-2;\nlet s = \"a\\\"b\\\\ // no\";\n"
    );
}

#[test]
fn empty_text_and_a_byte_order_mark() {
    assert_eq!(fmt(""), "");
    assert_eq!(fmt("\n\n  \n"), "");
    assert_eq!(fmt("\u{FEFF}let a=1;"), "\u{FEFF}let a = 1;\n");
}

#[test]
fn a_syntax_error_is_refused_with_its_diagnostic() {
    match format_text("sphere { radius 1 ") {
        Err(FormatError::Syntax(d)) => assert_eq!(d.len(), 1),
        other => panic!("{other:?}"),
    }
    // Every syntax error of the file, as `ptsc check` reports them.
    match format_text("let a = ;\nsphere { radius 1 }\nlet b = 2 +;\n") {
        Err(FormatError::Syntax(d)) => assert_eq!(d.len(), 2, "{d:?}"),
        other => panic!("{other:?}"),
    }
}

#[test]
fn a_range_formats_the_statements_it_touches() {
    let text = "let a=1;\nsphere{radius 1}\nlet b=2;\n";
    let at = text.find("radius").unwrap();
    let (range, new) = format_range(text, at, at).unwrap();
    assert_eq!(&text[range.clone()], "sphere{radius 1}");
    assert_eq!(new, "sphere { radius 1 }");
    let (range, new) = format_range(text, 0, text.len()).unwrap();
    assert_eq!(range, 0..text.len() - 1);
    assert_eq!(new, "let a = 1;\nsphere { radius 1 }\nlet b = 2;");
    let (range, new) = format_range("// only\n", 0, 3).unwrap();
    assert_eq!((range, new.as_str()), (0..0, ""));
}
