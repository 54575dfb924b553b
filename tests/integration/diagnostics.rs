//! `tests/diagnostics/*.pts`: one mistake per file, snapshotted as the user
//! sees it (miette's graphical report without colour).

use ptsc::compile::{compile_file, Options};

#[test]
fn every_diagnostic_file_renders_as_snapshotted() {
    let root = crate::root();
    std::env::set_current_dir(&root).unwrap();
    insta::glob!("..", "diagnostics/*.pts", |path| {
        let rel = crate::relative(path);
        let checked = compile_file(&rel, Options::default()).expect("readable test file");
        let name = rel.file_stem().unwrap().to_string_lossy().to_string();
        let d = &checked.diagnostics;
        assert!(
            !d.items.is_empty(),
            "{name}: expected at least one diagnostic"
        );
        if name.starts_with("warn_") {
            assert!(
                !d.has_errors(),
                "{name}: a warning case must not have errors"
            );
        } else {
            assert!(d.has_errors(), "{name}: expected an error");
        }
        for item in &d.items {
            assert!(
                item.help.is_some(),
                "{name}: every diagnostic has a help line: {item:?}"
            );
            assert!(
                item.span.is_some(),
                "{name}: every diagnostic has a span: {item:?}"
            );
        }
        insta::assert_snapshot!(d.render_human(&checked.sources, false));
    });
}

#[test]
fn at_least_forty_diagnostic_files() {
    let n = std::fs::read_dir(crate::root().join("tests/diagnostics"))
        .unwrap()
        .filter(|e| {
            e.as_ref()
                .unwrap()
                .path()
                .extension()
                .is_some_and(|x| x == "pts")
        })
        .count();
    assert!(n >= 40, "only {n} diagnostic cases");
}

#[test]
fn json_output_has_positions() {
    let path = crate::root().join("tests/diagnostics/unknown_param.pts");
    let checked = compile_file(&path, Options::default()).unwrap();
    let json: serde_json::Value =
        serde_json::from_str(&checked.diagnostics.render_json(&checked.sources)).unwrap();
    let first = &json[0];
    assert_eq!(first["severity"], "error");
    assert_eq!(first["code"], "pts::check::unknown_param");
    assert_eq!(first["line"], 4);
    assert_eq!(first["column"], 27);
    let (s, e) = (
        first["span"]["start"].as_u64().unwrap(),
        first["span"]["end"].as_u64().unwrap(),
    );
    let text = std::fs::read_to_string(&path).unwrap();
    assert_eq!(&text[s as usize..e as usize], "radus");
}
