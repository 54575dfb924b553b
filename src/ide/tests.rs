//! Answers that must agree with `ptsc check` (findings of a user trial of
//! the language server): hover's parameter lists and use counts, the
//! uses found in a misspelt parameter's value, completion's lists, and
//! quick fixes that leave no error behind.

use super::*;
use crate::compile::{compile_str, Compiled, Options};
use crate::source::MemoryFiles;
use std::path::Path;

const SCENE: &str = "/scene/s.pts";

fn check(text: &str) -> Compiled {
    let files = MemoryFiles::new();
    let options = Options {
        lower: false,
        files: &files,
        ..Options::default()
    };
    compile_str(Path::new(SCENE), text, options)
}

fn view<'a>(text: &'a str, compiled: &'a Compiled) -> View<'a> {
    View {
        path: Path::new(SCENE),
        text,
        compiled: Some(compiled),
    }
}

/// The hover at the `n`th `needle` of `text`.
fn hover_at(text: &str, needle: &str, n: usize) -> String {
    let c = check(text);
    let at = text.match_indices(needle).nth(n).expect("the needle").0;
    hover::hover(view(text, &c), at).expect("a hover").markdown
}

/// The labels completion offers where `|` stands.
fn labels(with_cursor: &str) -> Vec<String> {
    let at = with_cursor.find('|').unwrap();
    let text = with_cursor.replace('|', "");
    let c = check(&text);
    let none = |_: &Path| Vec::new();
    let items = completion::complete(view(&text, &c), at, &none);
    items.into_iter().map(|i| i.label).collect()
}

#[test]
fn hover_on_a_kind_lists_what_checks_help_lists() {
    let text = "sphere { center <0, 0, 0> radius 1 }\nplane { normal <0, 1, 0> }\n";
    for kind in ["sphere", "plane"] {
        let m = hover_at(text, kind, 0);
        let row = crate::check::kinds::find(kind).unwrap();
        let listed: Vec<String> = row.accepted().iter().map(|n| format!("`{n}`")).collect();
        assert!(m.contains(&listed.join(", ")), "{m}");
        assert!(m.contains("`velocity`, `material`"), "{m}");
    }
}

#[test]
fn hover_counts_uses_in_words() {
    let text = "let a = 1;\nlet b = a;\nlet c = 2;\nlet d = c + c;\nlet e = b + d;\n";
    assert!(hover_at(text, "a", 0).contains("used once"));
    assert!(hover_at(text, "c", 0).contains("used 2 times"));
    assert!(hover_at(text, "e =", 0).contains("not used"));
}

#[test]
fn a_name_in_a_misspelt_parameters_value_is_a_use() {
    let text = "let r = 1;\nsphere { center <0, 0, 0> radus r }\n";
    let c = check(text);
    let def = (c.symbols.iter().map(|(_, d)| d))
        .find(|d| d.name == "r")
        .unwrap();
    let at = text.rfind('r').unwrap();
    assert_eq!(def.uses.len(), 1, "{:?}", def.uses);
    assert_eq!(def.uses[0].start as usize, at);
    let unused =
        (c.diagnostics.items.iter()).any(|d| d.code == crate::diag::codes::UNUSED_CONSTANT);
    assert!(!unused, "{:?}", c.diagnostics.items);
}

#[test]
fn completion_lists_rgb_once_after_a_colour_parameter() {
    let l = labels("sphere { center <0, 0, 0> radius 1 material { diffuse | } }");
    assert_eq!(l.iter().filter(|l| *l == "rgb").count(), 1, "{l:?}");
}

#[test]
fn completion_after_a_dot_offers_the_components() {
    let l = labels("let v = <1, 2, 3>;\nlet a = v.|");
    assert_eq!(l, ["x", "y", "z"]);
    let l = labels("let c = rgb <1, 0, 0>;\nlet a = c.|");
    assert_eq!(l, ["red", "green", "blue"]);
    // A number's decimal point is not a component's dot.
    assert!(labels("let a = 1.|").contains(&"pi".to_string()));
}

#[test]
fn completion_leaves_out_the_parameters_given() {
    let l = labels("sky { sun_elevation 30 | }");
    assert!(!l.contains(&"sun_elevation".to_string()), "{l:?}");
    assert!(l.contains(&"sun_azimuth".to_string()), "{l:?}");
    let l = labels("sphere { material m | }");
    assert!(!l.contains(&"material".to_string()), "{l:?}");
    // Nor one that does the job of one given another way.
    let l = labels("sky { sun_elevation 30 | }");
    assert!(!l.contains(&"sun_direction".to_string()), "{l:?}");
    let l = labels("sky { sun_direction <0, 1, -1> | }");
    assert!(!l.contains(&"sun_azimuth".to_string()), "{l:?}");
    let l = labels("material m { type conductor preset gold | }");
    assert!(
        !l.contains(&"eta".to_string()) && l.contains(&"gloss".to_string()),
        "{l:?}"
    );
    // Transforms repeat.
    let l = labels("sphere { rotate <0, 1, 0> | }");
    assert!(l.contains(&"rotate".to_string()), "{l:?}");
}

/// The fixes offered for the diagnostic of `code` in `text`, applied.
fn fixed(text: &str, code: &str) -> Vec<String> {
    let c = check(text);
    let fixes = actions::fixes(view(text, &c), 0..text.len());
    (fixes.into_iter())
        .filter(|f| f.diagnostic.code == code)
        .map(|f| {
            let mut out = text.to_string();
            out.replace_range(f.range, &f.replacement);
            out
        })
        .collect()
}

#[test]
fn a_povray_light_is_not_half_fixed() {
    let camera = "camera { position <0, 1, 5> look_at <0, 0, 0> }\n";
    let half = format!("{camera}light_source {{ <0, 4, 0> color rgb 1 }}\n");
    assert_eq!(
        fixed(&half, crate::diag::codes::FOREIGN_BLOCK),
        Vec::<String>::new()
    );
    let whole = format!("{camera}light_source {{ position <0, 4, 0> intensity rgb 1 }}\n");
    let after = fixed(&whole, crate::diag::codes::FOREIGN_BLOCK);
    assert_eq!(after.len(), 1);
    assert!(
        check(&after[0]).diagnostics.items.is_empty(),
        "{}",
        after[0]
    );
}

#[test]
fn an_unused_constant_is_fixed_by_its_underscore() {
    let text = "camera { position <0, 1, 5> look_at <0, 0, 0> }\npoint_light { position <0, 4, 2> intensity rgb 20 }\nlet unused = 2;\n";
    let after = fixed(text, crate::diag::codes::UNUSED_CONSTANT);
    assert_eq!(after.len(), 1);
    assert!(after[0].contains("let _unused = 2;"), "{}", after[0]);
    assert!(
        check(&after[0]).diagnostics.items.is_empty(),
        "{}",
        after[0]
    );
}
