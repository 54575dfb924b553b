//! The diagnostic catalogue (`src/diag/codes.rs`) and the source agree:
//! every code the source reports is in the catalogue, every code in the
//! catalogue is reported somewhere, no code is written as a bare string
//! literal, and `docs/diagnostics.md` is the catalogue's Markdown.

use ptsc::diag::codes::{markdown, CATALOGUE};
use std::collections::BTreeSet;

/// The `"pts::a::b"` string literals of a text.
fn code_literals(text: &str) -> Vec<String> {
    let mut found = Vec::new();
    let mut rest = text;
    while let Some(at) = rest.find("\"pts::") {
        let after = &rest[at + 1..];
        let code: String = after
            .chars()
            .take_while(|&c| c.is_ascii_lowercase() || c == '_' || c == ':')
            .collect();
        if after[code.len()..].starts_with('"') && code.matches("::").count() == 2 {
            found.push(code);
        }
        rest = after;
    }
    found
}

/// The `pub const NAME: &str = "code";` lines of the catalogue's source.
fn declared_constants(codes_rs: &str) -> Vec<(String, String)> {
    codes_rs
        .lines()
        .filter_map(|line| {
            let rest = line.strip_prefix("pub const ")?;
            let (name, rest) = rest.split_once(": &str = \"")?;
            let code = rest.strip_suffix("\";")?;
            Some((name.to_string(), code.to_string()))
        })
        .collect()
}

/// The broken rules, given the catalogue's codes, its source and the other
/// source files (path, text).
fn mismatches(catalogue: &[&str], codes_rs: &str, sources: &[(String, String)]) -> Vec<String> {
    let mut broken = Vec::new();
    let declared = declared_constants(codes_rs);
    let in_catalogue: BTreeSet<&str> = catalogue.iter().copied().collect();
    for (name, code) in &declared {
        if !in_catalogue.contains(code.as_str()) {
            broken.push(format!(
                "{code} ({name}) is used but missing from CATALOGUE"
            ));
        }
        let used = sources.iter().any(|(_, text)| {
            text.match_indices(name.as_str()).any(|(i, _)| {
                let before = text[..i].chars().next_back();
                let after = text[i + name.len()..].chars().next();
                let part = |c: Option<char>| c.is_some_and(|c| c.is_alphanumeric() || c == '_');
                !part(before) && !part(after)
            })
        });
        if !used {
            broken.push(format!(
                "{code} ({name}) is in the catalogue but nothing reports it"
            ));
        }
    }
    let constants: BTreeSet<&str> = declared.iter().map(|(_, c)| c.as_str()).collect();
    for code in catalogue {
        if !constants.contains(code) {
            broken.push(format!("{code} is in CATALOGUE without a constant"));
        }
    }
    for (path, text) in sources {
        for code in code_literals(text) {
            broken.push(format!(
                "{path}: the code {code} is written as a string; use its constant from diag::codes"
            ));
        }
    }
    broken
}

fn sources() -> (String, Vec<(String, String)>) {
    let src = crate::root().join("src");
    let files = crate::files_below(&src, "rs");
    let codes_rs = src.join("diag/codes.rs");
    let others = files
        .into_iter()
        .filter(|f| *f != codes_rs)
        .map(|f| {
            let text = std::fs::read_to_string(&f).unwrap();
            (crate::relative(&f).display().to_string(), text)
        })
        .collect();
    (std::fs::read_to_string(codes_rs).unwrap(), others)
}

#[test]
fn every_code_used_is_in_the_catalogue_and_every_entry_is_used() {
    let (codes_rs, others) = sources();
    let catalogue: Vec<&str> = CATALOGUE.iter().map(|e| e.code).collect();
    assert!(catalogue.len() >= 40, "{} codes", catalogue.len());
    let broken = mismatches(&catalogue, &codes_rs, &others);
    assert!(broken.is_empty(), "{}", broken.join("\n"));
}

#[test]
fn the_catalogue_check_fails_on_a_missing_or_unused_code_or_a_literal() {
    let (codes_rs, others) = sources();
    let mut catalogue: Vec<&str> = CATALOGUE.iter().map(|e| e.code).collect();
    // An entry removed from the table: a code in use is missing.
    let removed = catalogue.remove(0);
    let broken = mismatches(&catalogue, &codes_rs, &others);
    assert!(
        broken
            .iter()
            .any(|b| b.contains(removed) && b.contains("missing")),
        "{broken:?}"
    );
    // A constant nothing reports, and a code written as a literal.
    let extra = format!("{codes_rs}\npub const NEVER_USED: &str = \"pts::check::never_used\";\n");
    let mut with_literal = others.clone();
    with_literal.push(("x.rs".into(), "f(\"pts::check::bare\")".into()));
    let mut catalogue: Vec<&str> = CATALOGUE.iter().map(|e| e.code).collect();
    catalogue.push("pts::check::never_used");
    let broken = mismatches(&catalogue, &extra, &with_literal);
    assert!(broken.iter().any(|b| b.contains("nothing reports it")));
    assert!(broken.iter().any(|b| b.contains("written as a string")));
}

#[test]
fn docs_diagnostics_md_is_the_catalogue() {
    let path = crate::root().join("docs/diagnostics.md");
    let text = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        text == markdown(),
        "docs/diagnostics.md is out of date: run `cargo run -- explain --all > docs/diagnostics.md`"
    );
}

#[test]
fn explain_prints_every_code() {
    let bin = env!("CARGO_BIN_EXE_ptsc");
    for e in CATALOGUE {
        let short = e.code.rsplit("::").next().unwrap();
        for name in [e.code, short] {
            let out = std::process::Command::new(bin)
                .args(["explain", name])
                .output()
                .unwrap();
            assert!(out.status.success(), "explain {name}");
            let text = String::from_utf8(out.stdout).unwrap();
            assert!(text.starts_with(e.code) && text.contains(e.explanation));
        }
    }
    let out = std::process::Command::new(bin)
        .args(["explain", "unknwn_param"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("did you mean `unknown_param`?"));
}

/// Every `pts` block of the language reference parses (its examples are
/// fragments of scenes, so they are only parsed, not checked): as
/// statements, or as the entries of an object's block.
#[test]
fn language_reference_examples_parse() {
    let text = std::fs::read_to_string(crate::root().join("docs/language.md")).unwrap();
    let mut blocks = 0;
    for (k, block) in text.split("```pts\n").skip(1).enumerate() {
        let code = block.split("```").next().unwrap();
        let parse = |text: &str| {
            ptsc::syntax::parse(ptsc::source::FileId(0), text, &ptsc::check::kinds::NAMES)
        };
        if let (Err(d), Err(_)) = (parse(code), parse(&format!("sphere {{ {code} }}"))) {
            panic!("block {k} of docs/language.md does not parse: {d:?}\n{code}");
        }
        blocks += 1;
    }
    assert!(blocks >= 3, "{blocks} pts blocks");
}
