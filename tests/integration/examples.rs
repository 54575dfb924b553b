//! Every scene in `examples/` checks without errors.

use ptsc::compile::{compile_file, Options};

#[test]
fn every_example_checks_clean() {
    // The bench mesh is generated, not kept in the repository.
    ptsc::bench_data::ensure_mesh_blob(&crate::root()).unwrap();
    let files = crate::files_below(&crate::root().join("examples"), "pts");
    assert!(files.len() >= 10, "found only {} examples", files.len());
    for f in files {
        let c = compile_file(&f, Options::default()).unwrap();
        assert!(
            !c.diagnostics.has_errors(),
            "{}:\n{}",
            f.display(),
            c.diagnostics.render_human(&c.sources, false)
        );
        assert!(c.ir.is_some());
    }
}

/// The generated bench mesh is the shared bench data byte for byte (the
/// Mitsuba references were made from that file). Without `../shared` (a
/// user's clone) there is nothing to compare with.
#[test]
fn the_generated_mesh_is_the_shared_one() {
    let shared = crate::root().join("../shared/bench/data/mesh_blob.ply");
    let Ok(expected) = std::fs::read(&shared) else {
        eprintln!("{} not found: nothing to compare with", shared.display());
        return;
    };
    let made = std::fs::read(ptsc::bench_data::ensure_mesh_blob(&crate::root()).unwrap()).unwrap();
    assert!(
        made == expected,
        "the generated blob differs from {}",
        shared.display()
    );
}

/// `.ci/run` runs the whole suite on a clone with nothing beside it, then,
/// with `../shared` beside the clone, only the tests named for it
/// (`cargo test --release shared`). So a test that reads `../shared` has
/// `shared` in its function's name, and no scene or script under test
/// reaches it. Comments do not count.
#[test]
fn the_readers_of_shared_are_named_for_it() {
    let root = crate::root();
    let mut sources = crate::files_below(&root.join("src"), "rs");
    sources.extend(crate::files_below(&root.join("tests"), "rs"));
    let mut wrong = Vec::new();
    for f in &sources {
        let text = std::fs::read_to_string(f).unwrap();
        let mut function = "";
        for (i, line) in text.lines().enumerate() {
            let code = line.split("//").next().unwrap_or_default();
            let mut words = code
                .split_whitespace()
                .skip_while(|w| matches!(*w, "pub" | "pub(crate)" | "pub(super)" | "const"));
            if words.next() == Some("fn") {
                let name = words.next().unwrap_or_default();
                function = name.split(['(', '<']).next().unwrap_or_default();
            }
            let reads = code.contains("shared/") || code.contains("\"shared\"");
            if reads && !function.contains("shared") {
                wrong.push(format!(
                    "{}:{} (in `{function}`)",
                    crate::relative(f).display(),
                    i + 1
                ));
            }
        }
    }
    let mut scenes = crate::files_below(&root.join("examples"), "pts");
    scenes.extend(crate::files_below(&root.join("tests"), "pts"));
    for f in &scenes {
        let text = std::fs::read_to_string(f).unwrap();
        for (i, line) in text.lines().enumerate() {
            if line
                .split("//")
                .next()
                .unwrap_or_default()
                .contains("shared/")
            {
                wrong.push(format!("{}:{}", crate::relative(f).display(), i + 1));
            }
        }
    }
    assert!(
        wrong.is_empty(),
        "these read ../shared outside a test named for it:\n{}",
        wrong.join("\n")
    );
}

/// The budgets bound runaway scenes, not real ones: every example and
/// golden scene checks within a fortieth of them (the most demanding,
/// `many_lights.pts`, takes about 590,000 steps of work and 61,000 loop
/// statements), so that a scene has to be 40 times larger than any of
/// them to meet a budget.
#[test]
fn every_example_is_far_below_the_budgets() {
    ptsc::bench_data::ensure_mesh_blob(&crate::root()).unwrap();
    let mut files = crate::files_below(&crate::root().join("examples"), "pts");
    files.extend(crate::files_below(
        &crate::root().join("tests/golden/scenes"),
        "pts",
    ));
    for f in files {
        let options = Options {
            lower: false,
            loop_statements: ptsc::check::MAX_LOOP_STATEMENTS / 40,
            work: ptsc::check::eval::MAX_WORK / 40,
            ..Options::default()
        };
        let c = compile_file(&f, options).unwrap();
        assert!(
            !c.diagnostics.has_errors(),
            "{}:\n{}",
            f.display(),
            c.diagnostics.render_human(&c.sources, false)
        );
    }
}
