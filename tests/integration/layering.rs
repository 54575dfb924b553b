//! The architecture invariants of ARCHITECTURE.md, checked on the source:
//! the crate's top-level modules import only modules on a lower floor (so
//! they form a DAG), no render-side module imports the front end, `check`
//! reads only the settings of the IR, and only `cli/` prints.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// Every top-level module with its floor: a module may import only modules
/// on a lower floor. Keep in step with ARCHITECTURE.md's table.
const FLOORS: &[(&str, u32)] = &[
    // Foundations.
    ("source", 0),
    ("span", 1),
    ("diag", 2),
    ("sampling", 0),
    ("geometry", 1),
    ("accel", 2),
    ("output", 0),
    ("bench_data", 0),
    // The renderer's concepts and the IR that holds them.
    ("material", 3),
    ("texture", 3),
    ("camera", 3),
    ("light", 4),
    ("ir", 5),
    ("integrator", 6),
    ("render", 7),
    // The front end.
    ("syntax", 3),
    ("check", 6),
    // Between them: lowering, then the driver, then the front doors.
    ("lower", 8),
    ("compile", 9),
    // The editor's side: the formatter (syntax and the kinds' names), the
    // answers over a check, the language server.
    ("format", 7),
    ("ide", 10),
    ("lsp", 11),
    ("fuzz", 10),
    ("cli", 12),
];

/// Modules that never import the front end (`syntax`, `check`), the
/// lowering stage or what sits above it.
const RENDER_SIDE: &[&str] = &[
    "sampling",
    "geometry",
    "accel",
    "output",
    "material",
    "texture",
    "camera",
    "light",
    "ir",
    "integrator",
    "render",
];

/// The front end and the stages above the renderer.
const FRONT: &[&str] = &[
    "syntax", "check", "lower", "compile", "format", "ide", "lsp", "fuzz", "cli",
];

/// The top-level module a file of `src/` belongs to (`None`: lib.rs, main.rs).
fn module_of(src: &Path, file: &Path) -> Option<String> {
    let rel = file.strip_prefix(src).unwrap();
    let first = rel.components().next()?.as_os_str().to_str()?.to_string();
    let name = first.strip_suffix(".rs").unwrap_or(&first).to_string();
    (name != "lib" && name != "main").then_some(name)
}

/// The crate paths a text names: `crate::a::b…` and each name of
/// `crate::{a::…, b}`, as full paths (`a::b…`).
fn crate_paths(text: &str) -> Vec<String> {
    let mut paths = Vec::new();
    let path_char = |c: char| c.is_alphanumeric() || c == '_' || c == ':';
    let mut rest = text;
    while let Some(at) = rest.find("crate::") {
        let after = &rest[at + "crate::".len()..];
        if let Some(group) = after.strip_prefix('{') {
            let end = group.find('}').unwrap_or(group.len());
            for item in group[..end].split(',') {
                let item: String = item.trim().chars().take_while(|&c| path_char(c)).collect();
                if !item.is_empty() {
                    paths.push(item);
                }
            }
        } else {
            paths.push(after.chars().take_while(|&c| path_char(c)).collect());
        }
        rest = after;
    }
    paths
}

/// Every (importing module, imported path, file) of `src/`.
fn imports() -> Vec<(String, String, PathBuf)> {
    let src = crate::root().join("src");
    let files = crate::files_below(&src, "rs");
    let mut found = Vec::new();
    for file in files {
        let Some(module) = module_of(&src, &file) else {
            continue;
        };
        let text = std::fs::read_to_string(&file).unwrap();
        for path in crate_paths(&text) {
            let top = path.split("::").next().unwrap().to_string();
            if top != module && !top.is_empty() {
                found.push((module.clone(), path, crate::relative(&file)));
            }
        }
    }
    found
}

/// The broken rules among `imports` (empty: the layering holds).
fn violations(imports: &[(String, String, PathBuf)]) -> Vec<String> {
    let floor: BTreeMap<&str, u32> = FLOORS.iter().copied().collect();
    let mut broken = BTreeSet::new();
    for (module, path, file) in imports {
        let top = path.split("::").next().unwrap();
        let (Some(&from), Some(&to)) = (floor.get(module.as_str()), floor.get(top)) else {
            broken.insert(format!(
                "{}: `{module}` or `{top}` has no floor in FLOORS",
                file.display()
            ));
            continue;
        };
        if to >= from {
            broken.insert(format!(
                "{}: `{module}` (floor {from}) imports `{path}` (floor {to}): imports only go down",
                file.display()
            ));
        }
        if RENDER_SIDE.contains(&module.as_str()) && FRONT.contains(&top) {
            broken.insert(format!(
                "{}: render-side `{module}` imports `{path}`: only `lower` reads the front end's types",
                file.display()
            ));
        }
        if module == "check" && top == "ir" && !path.starts_with("ir::settings") {
            broken.insert(format!(
                "{}: `check` imports `{path}`: it reads only `ir::settings` (names shared with the renderer)",
                file.display()
            ));
        }
    }
    broken.into_iter().collect()
}

#[test]
fn imports_only_go_down_and_the_renderer_never_reads_the_front_end() {
    let found = imports();
    assert!(found.len() > 100, "only {} imports found", found.len());
    let broken = violations(&found);
    assert!(broken.is_empty(), "{}", broken.join("\n"));
    // Every module of src/ has a floor.
    let src = crate::root().join("src");
    let files = crate::files_below(&src, "rs");
    let floor: BTreeMap<&str, u32> = FLOORS.iter().copied().collect();
    for file in files {
        if let Some(m) = module_of(&src, &file) {
            assert!(floor.contains_key(m.as_str()), "{m} has no floor in FLOORS");
        }
    }
}

#[test]
fn the_rules_catch_an_upward_import_and_a_front_end_import() {
    let case = |module: &str, path: &str| {
        violations(&[(module.to_string(), path.to_string(), PathBuf::from("x.rs"))])
    };
    assert!(case("geometry", "render::film::Film")[0].contains("imports only go down"));
    assert!(case("material", "check::Material")
        .iter()
        .any(|v| v.contains("only `lower` reads")));
    assert!(case("check", "ir::Scene")[0].contains("reads only `ir::settings`"));
    assert!(case("lower", "check::Scene").is_empty());
    assert_eq!(
        crate_paths("use crate::{a::b, c};\nlet x = crate::d::e(1);"),
        ["a::b", "c", "d::e"]
    );
}

#[test]
fn only_cli_prints() {
    let src = crate::root().join("src");
    let files = crate::files_below(&src, "rs");
    for file in files {
        if module_of(&src, &file).as_deref() == Some("cli") {
            continue;
        }
        let text = std::fs::read_to_string(&file).unwrap();
        for macro_name in ["println!", "eprintln!", "print!(", "eprint!(", "dbg!("] {
            assert!(
                !text.contains(macro_name),
                "{} uses {macro_name}: only cli/ prints; return data instead",
                crate::relative(&file).display()
            );
        }
    }
}

/// Every word list of the checker's schemas (the kinds' rows, materials and
/// textures): the enumerated words a scene may write.
fn vocabulary() -> BTreeSet<&'static str> {
    use ptsc::check::schema::{self, Ty};
    let rows = (ptsc::check::kinds::KINDS.iter().map(|k| k.params)).chain([
        schema::SHAPE_COMMON,
        schema::MATERIAL,
        schema::CHECKER,
        schema::IMAGE,
        schema::NOISE,
        schema::BANDS,
        schema::UNBANDED,
        schema::GRADIENT,
        schema::COLOR_MAP,
    ]);
    let mut words = BTreeSet::new();
    for spec in rows.flatten() {
        if let Ty::Word(list) = spec.ty {
            words.extend(list.iter().copied());
        }
    }
    words
}

/// No string vocabulary crosses from check to lowering: the checked scene
/// holds typed values (enums defined once with their words), so lowering
/// never matches an enumerated word, and the checked scene's strings are
/// names only (for messages), never a word to be resolved later.
#[test]
fn no_word_of_the_language_crosses_from_check_to_lower() {
    let words = vocabulary();
    assert!(words.contains("conductor") && words.contains("world") && words.contains("clamp"));
    let lower = crate::root().join("src/lower");
    for entry in std::fs::read_dir(&lower).unwrap() {
        let path = entry.unwrap().path();
        let text = std::fs::read_to_string(&path).unwrap();
        for word in &words {
            for pattern in [
                format!("\"{word}\" =>"),
                format!("== \"{word}\""),
                format!("(\"{word}\")"),
            ] {
                assert!(
                    !text.contains(&pattern),
                    "{} matches the word `{word}`: check should hand over a typed value",
                    path.display()
                );
            }
        }
    }
    let scene = std::fs::read_to_string(crate::root().join("src/check/scene.rs")).unwrap();
    for line in scene.lines().map(str::trim) {
        if line.starts_with("pub ") && line.contains("String") {
            let field = line.trim_start_matches("pub ").split(':').next().unwrap();
            assert_eq!(
                field, "name",
                "check::scene's `{line}` is a string: make it a typed value"
            );
        }
    }
}
