//! The semantic model a compile gives (`Compiled::symbols`): every
//! definition with the span of its name and of each use, across included
//! files, each use belonging to the definition evaluation resolved it to
//! (shadowing, loops, functions, groups), also on a scene with errors. The
//! expected spans are found in the scenes' text, never written as offsets.

use ptsc::check::{DefId, Definition, SymbolKind, Symbols};
use ptsc::compile::{compile_file, Compiled, Options};
use ptsc::source::{FileId, MemoryFiles};
use ptsc::span::Span;
use std::path::{Path, PathBuf};

/// The folder the scenes lie in (in memory only).
const ROOT: &str = "/symbols test, in memory";

/// Compiles `files` (name, text), the first being the scene, checking only.
fn compile(files: &[(&str, &str)]) -> Compiled {
    let mut memory = MemoryFiles::new();
    for (name, text) in files {
        memory.insert(Path::new(ROOT).join(name), *text);
    }
    let options = Options {
        lower: false,
        files: &memory,
        ..Options::default()
    };
    let c = compile_file(&Path::new(ROOT).join(files[0].0), options).expect("in memory");
    assert_well_formed(&c);
    c
}

/// The text `span` covers.
fn text_of(c: &Compiled, span: Span) -> &str {
    &c.sources.get(span.file).text[span.start as usize..span.end as usize]
}

/// The id of the file named `name` (relative to [`ROOT`]).
fn file(c: &Compiled, name: &str) -> FileId {
    let path = PathBuf::from(ROOT).join(name);
    let i = (c.sources.files().iter())
        .position(|f| f.path == path)
        .unwrap_or_else(|| panic!("{name} was not read"));
    FileId(i as u32)
}

/// The span of the first whole word `name` inside `context`, which occurs
/// exactly once in the file `name_of_file`.
fn at(c: &Compiled, name_of_file: &str, context: &str, name: &str) -> Span {
    let id = file(c, name_of_file);
    let text = &c.sources.get(id).text;
    assert_eq!(
        text.matches(context).count(),
        1,
        "`{context}` is not once in {name_of_file}"
    );
    let base = text.find(context).unwrap();
    let word = |b: u8| b.is_ascii_alphanumeric() || b == b'_';
    let bytes = context.as_bytes();
    let offset = (context.match_indices(name))
        .map(|(i, _)| i)
        .find(|&i| {
            let before = i.checked_sub(1).map(|j| bytes[j]);
            let after = bytes.get(i + name.len()).copied();
            !before.is_some_and(word) && !after.is_some_and(word)
        })
        .unwrap_or_else(|| panic!("no word `{name}` in `{context}`"));
    Span::new(id, base + offset, base + offset + name.len())
}

/// The definition whose name is at `name_span`, which must be of `kind`.
fn def(c: &Compiled, kind: SymbolKind, name_span: Span) -> (DefId, &Definition) {
    let id = (c.symbols.defined_at(name_span))
        .unwrap_or_else(|| panic!("no definition at `{}`", text_of(c, name_span)));
    let d = c.symbols.get(id);
    assert_eq!(d.kind, kind, "{}", d.name);
    (id, d)
}

/// Asserts that the definition at `name_span` is a `kind` whose uses are
/// exactly `uses` (in source order), and that the statement it is defined
/// by starts with `keyword`.
fn assert_symbol(c: &Compiled, kind: SymbolKind, name_span: Span, keyword: &str, uses: &[Span]) {
    let (id, d) = def(c, kind, name_span);
    assert_eq!(d.name, text_of(c, name_span));
    assert!(
        text_of(c, d.span).starts_with(keyword),
        "`{}` is defined by `{}`",
        d.name,
        text_of(c, d.span)
    );
    let shown = |spans: &[Span]| -> Vec<String> {
        (spans.iter())
            .map(|s| format!("{}:{}", s.file.0, s.start))
            .collect()
    };
    assert_eq!(
        shown(c.symbols.references(id)),
        shown(uses),
        "uses of {}",
        d.name
    );
    for u in uses {
        let middle = u.start as usize + u.len() / 2;
        let found = c.symbols.definition_at(u.file, middle);
        assert_eq!(found, Some(id), "what `{}` at {u:?} refers to", d.name);
    }
    let middle = name_span.start as usize + name_span.len() / 2;
    assert_eq!(c.symbols.definition_at(name_span.file, middle), Some(id));
}

/// Every definition's name and every use is the name's text, in a file of
/// the compile, and the definitions come in source order.
fn assert_well_formed(c: &Compiled) {
    let files = c.sources.files().len() as u32;
    let mut previous = None;
    for (_, d) in c.symbols.iter() {
        let key = (d.name_span.file.0, d.name_span.start);
        assert!(previous < Some(key), "`{}` is out of order", d.name);
        previous = Some(key);
        for s in std::iter::once(&d.name_span).chain(&d.uses) {
            assert!(s.file.0 < files, "`{}`: {s:?} is in no file", d.name);
            assert_eq!(text_of(c, *s), d.name, "at {s:?}");
        }
        let start = d.span.start..=d.span.end;
        assert!(d.span.file == d.name_span.file && start.contains(&d.name_span.start));
        assert!(d
            .uses
            .windows(2)
            .all(|w| (w[0].file.0, w[0].start) < (w[1].file.0, w[1].start)));
    }
}

/// The messages of the warnings, sorted.
fn warnings(c: &Compiled) -> Vec<String> {
    let mut w: Vec<String> = (c.diagnostics.items.iter())
        .map(|d| d.message.clone())
        .collect();
    w.sort();
    w
}

const HEAD: &str = "render { resolution <8, 8> samples 1 }\n\
                    camera { position <0, 1, 5> look_at <0, 0, 0> }\n\
                    point_light { position <0, 4, 4> intensity rgb 30 }\n";

const INCLUDES: &str = r#"
include "parts/defs.ptsi"
let size = r * 2;
sphere { center <0, size, 0> radius r material shiny }
for i in 0..3 {
    let r = 0.1 * (i + 1);
    sphere { center <i, -1, 0> radius r }
}
sphere { center <0, 0, 2> radius r material { diffuse wood } }
include "parts/after.ptsi"
"#;

const DEFS: &str = "let r = 0.5;\n\
                    texture wood checker { even rgb 0.9 odd rgb 0.1 }\n\
                    material shiny { diffuse wood }\n";

const AFTER: &str = "sphere { center <size, 0, 0> radius r material shiny }\n";

/// The scene of includes: names defined in an include and used in the
/// scene, defined in the scene and used in a later include; a `let` in a
/// loop's body hides the include's constant of the same name there only.
fn includes() -> Compiled {
    let main = format!("{HEAD}{INCLUDES}");
    let c = compile(&[
        ("main.pts", &main),
        ("parts/defs.ptsi", DEFS),
        ("parts/after.ptsi", AFTER),
    ]);
    assert!(c.diagnostics.items.is_empty(), "{:?}", warnings(&c));
    c
}

#[test]
fn a_constant_of_an_include_is_used_in_the_scene_and_in_a_later_include() {
    let c = includes();
    let m = "main.pts";
    assert_symbol(
        &c,
        SymbolKind::Constant,
        at(&c, "parts/defs.ptsi", "let r = 0.5", "r"),
        "let",
        &[
            at(&c, m, "let size = r * 2", "r"),
            at(&c, m, "radius r material shiny", "r"),
            at(&c, m, "radius r material { diffuse", "r"),
            at(&c, "parts/after.ptsi", "radius r", "r"),
        ],
    );
    assert_symbol(
        &c,
        SymbolKind::Constant,
        at(&c, m, "let size", "size"),
        "let",
        &[
            at(&c, m, "<0, size, 0>", "size"),
            at(&c, "parts/after.ptsi", "<size, 0, 0>", "size"),
        ],
    );
}

#[test]
fn a_let_in_a_loop_hides_the_outer_constant_in_the_body_only() {
    let c = includes();
    let m = "main.pts";
    let inner = at(&c, m, "let r = 0.1", "r");
    assert_symbol(
        &c,
        SymbolKind::Constant,
        inner,
        "let",
        &[at(&c, m, "radius r }", "r")],
    );
    // Three iterations, one definition and one use.
    let named_r = c.symbols.iter().filter(|(_, d)| d.name == "r").count();
    assert_eq!(named_r, 2);
    assert_symbol(
        &c,
        SymbolKind::LoopVariable,
        at(&c, m, "for i in", "i"),
        "for",
        &[at(&c, m, "(i + 1)", "i"), at(&c, m, "<i, -1, 0>", "i")],
    );
}

#[test]
fn materials_and_textures_are_used_by_name_across_files() {
    let c = includes();
    let (m, defs) = ("main.pts", "parts/defs.ptsi");
    assert_symbol(
        &c,
        SymbolKind::Material,
        at(&c, defs, "material shiny", "shiny"),
        "material",
        &[
            at(&c, m, "material shiny }", "shiny"),
            at(&c, "parts/after.ptsi", "material shiny", "shiny"),
        ],
    );
    assert_symbol(
        &c,
        SymbolKind::Texture,
        at(&c, defs, "texture wood", "wood"),
        "texture",
        &[
            at(&c, m, "diffuse wood", "wood"),
            at(&c, defs, "diffuse wood", "wood"),
        ],
    );
}

const GROUPS: &str = r#"
let big = true;
fn scaled(v, k) = v * k + offset;
let offset = 0;
group lamp {
    let h = scaled(2, 0.5);
    cylinder { base <0, 0, 0> top <0, h, 0> radius 0.02 material brass }
    sphere { center <0, h, 0> radius 0.1 }
}
if big {
    let n = 3;
} else {
    let n = 1;
}
material glow { emission rgb 1 }
for k in 0..n {
    instance lamp { translate <k, 0, 0> material glow }
}
sphere { center <0, -1, 0> radius 0.5 material brass }
material brass { diffuse rgb <0.8, 0.6, 0.2> }
material unused_one { diffuse rgb 0.1 }
let _quiet = 1;
fn never(x) = 2;
"#;

/// The scene of groups, functions and branches.
fn groups() -> Compiled {
    compile(&[("main.pts", &format!("{HEAD}{GROUPS}"))])
}

#[test]
fn a_group_placed_in_a_loop_has_one_use_and_its_material_two() {
    let c = groups();
    let m = "main.pts";
    assert_symbol(
        &c,
        SymbolKind::Group,
        at(&c, m, "group lamp", "lamp"),
        "group",
        &[at(&c, m, "instance lamp", "lamp")],
    );
    // Named before its declaration, in a group and at the top level.
    assert_symbol(
        &c,
        SymbolKind::Material,
        at(&c, m, "material brass {", "brass"),
        "material",
        &[
            at(&c, m, "radius 0.02 material brass", "brass"),
            at(&c, m, "radius 0.5 material brass", "brass"),
        ],
    );
    assert_symbol(
        &c,
        SymbolKind::Material,
        at(&c, m, "material glow {", "glow"),
        "material",
        &[at(&c, m, "material glow }", "glow")],
    );
    assert_symbol(
        &c,
        SymbolKind::Constant,
        at(&c, m, "let h", "h"),
        "let",
        &[
            at(&c, m, "top <0, h, 0>", "h"),
            at(&c, m, "<0, h, 0> radius 0.1", "h"),
        ],
    );
}

#[test]
fn a_function_body_sees_its_parameters_not_the_callers_loop_variable() {
    let c = groups();
    let m = "main.pts";
    assert_symbol(
        &c,
        SymbolKind::Function,
        at(&c, m, "fn scaled", "scaled"),
        "fn",
        &[at(&c, m, "scaled(2, 0.5)", "scaled")],
    );
    assert_symbol(
        &c,
        SymbolKind::Parameter,
        at(&c, m, "scaled(v, k)", "k"),
        "fn",
        &[at(&c, m, "v * k", "k")],
    );
    assert_symbol(
        &c,
        SymbolKind::Parameter,
        at(&c, m, "scaled(v, k)", "v"),
        "fn",
        &[at(&c, m, "v * k", "v")],
    );
    assert_symbol(
        &c,
        SymbolKind::LoopVariable,
        at(&c, m, "for k in", "k"),
        "for",
        &[at(&c, m, "<k, 0, 0>", "k")],
    );
    // Defined after the function, before its call: the call sees it.
    assert_symbol(
        &c,
        SymbolKind::Constant,
        at(&c, m, "let offset", "offset"),
        "let",
        &[at(&c, m, "k + offset", "offset")],
    );
}

#[test]
fn only_the_branch_that_ran_defines_its_names() {
    let c = groups();
    let m = "main.pts";
    assert_symbol(
        &c,
        SymbolKind::Constant,
        at(&c, m, "let n = 3", "n"),
        "let",
        &[at(&c, m, "0..n", "n")],
    );
    assert_eq!(c.symbols.defined_at(at(&c, m, "let n = 1", "n")), None);
    assert_symbol(
        &c,
        SymbolKind::Constant,
        at(&c, m, "let big", "big"),
        "let",
        &[at(&c, m, "if big", "big")],
    );
}

#[test]
fn the_unused_warnings_are_the_unused_symbols() {
    let c = groups();
    assert_eq!(
        warnings(&c),
        [
            "function `never` is never called",
            "material `unused_one` is never used",
        ]
    );
    let unused: Vec<&str> = c.symbols.unused().map(|d| d.name.as_str()).collect();
    assert_eq!(unused, ["unused_one", "never"]);
    // Not reported, yet known: a parameter never read, a `_` name.
    let m = "main.pts";
    assert_symbol(
        &c,
        SymbolKind::Parameter,
        at(&c, m, "never(x)", "x"),
        "fn",
        &[],
    );
    assert_symbol(
        &c,
        SymbolKind::Constant,
        at(&c, m, "_quiet", "_quiet"),
        "let",
        &[],
    );
}

#[test]
fn an_include_run_in_two_loops_defines_once_and_uses_both_loop_variables() {
    let main = format!(
        "{HEAD}for i in 0..2 {{ include \"body.ptsi\" }}\nfor i in 5..7 {{ include \"body.ptsi\" }}\n"
    );
    let body = "let d = i * 2;\nsphere { center <d, 0, 0> radius 0.1 }\n";
    let c = compile(&[("main.pts", &main), ("body.ptsi", body)]);
    assert!(c.diagnostics.items.is_empty(), "{:?}", warnings(&c));
    let (m, b) = ("main.pts", "body.ptsi");
    let use_of_i = at(&c, b, "i * 2", "i");
    let first = at(&c, m, "for i in 0..2", "i");
    let second = at(&c, m, "for i in 5..7", "i");
    assert_eq!(
        c.symbols
            .references(def(&c, SymbolKind::LoopVariable, first).0),
        [use_of_i]
    );
    assert_eq!(
        c.symbols
            .references(def(&c, SymbolKind::LoopVariable, second).0),
        [use_of_i]
    );
    assert_symbol(
        &c,
        SymbolKind::Constant,
        at(&c, b, "let d", "d"),
        "let",
        &[at(&c, b, "<d, 0, 0>", "d")],
    );
    assert_eq!(c.symbols.len(), 3);
}

#[test]
fn a_scene_with_errors_has_its_symbols_as_far_as_it_was_checked() {
    let main = format!(
        "{HEAD}let a = 1;\n\
         sphere {{ center <0, a, 0> radius a material m }}\n\
         let b = = 2;\n\
         sphere {{ center <1, 0, 0> radius a }}\n\
         material m {{ diffuse rgb 1 }}\n"
    );
    let c = compile(&[("main.pts", &main)]);
    assert!(c.has_errors());
    let m = "main.pts";
    assert_symbol(
        &c,
        SymbolKind::Constant,
        at(&c, m, "let a", "a"),
        "let",
        &[
            at(&c, m, "<0, a, 0>", "a"),
            at(&c, m, "radius a material", "a"),
            at(&c, m, "radius a }", "a"),
        ],
    );
    // Named before the syntax error, declared after it.
    assert_symbol(
        &c,
        SymbolKind::Material,
        at(&c, m, "material m {", "m"),
        "material",
        &[at(&c, m, "material m }", "m")],
    );
}

/// Every scene the project keeps, compiled from the disk: the examples,
/// the golden scenes and the diagnostics' scenes (most with errors).
fn kept_scenes() -> Vec<PathBuf> {
    let root = crate::root();
    let mut scenes = crate::files_below(&root.join("examples"), "pts");
    scenes.extend(crate::files_below(&root.join("tests/golden/scenes"), "pts"));
    scenes.extend(crate::files_below(&root.join("tests/diagnostics"), "pts"));
    scenes
}

#[test]
fn every_use_in_every_kept_scene_is_its_definitions_name() {
    let (mut scenes, mut uses, mut included) = (0, 0, 0);
    for path in kept_scenes() {
        let options = Options {
            lower: false,
            ..Options::default()
        };
        let c = compile_file(&path, options).unwrap();
        assert_well_formed(&c);
        let symbols: &Symbols = &c.symbols;
        uses += symbols.iter().map(|(_, d)| d.uses.len()).sum::<usize>();
        included += (symbols.iter())
            .flat_map(|(_, d)| &d.uses)
            .filter(|u| u.file != FileId(0))
            .count();
        scenes += 1;
    }
    // The property held of something: scenes, uses, uses in includes.
    assert!(
        scenes >= 200 && uses >= 500 && included > 0,
        "{scenes} {uses} {included}"
    );
}

/// Which schema row each parameter and which kind each block statement is:
/// a sphere's parameters written once in a loop run four times are one
/// occurrence each, with the row hover will show; a material's too.
#[test]
fn every_parameter_and_block_is_its_schema_row() {
    let scene = "camera { position <0, 1, 5> look_at <0, 0, 0> }\n\
                 material red { diffuse rgb <0.8, 0.1, 0.1> }\n\
                 for i in 0..4 {\n    sphere { center <i, 0, 0> radius 0.4 material red }\n}\n";
    let c = compile(&[("params.pts", scene)]);
    let s = &c.symbols;
    let radius = at(&c, "params.pts", "radius 0.4", "radius");
    let found: Vec<_> = (s.params().iter())
        .filter(|p| p.name_span == radius)
        .collect();
    assert_eq!(found.len(), 1, "one occurrence per place: {:?}", s.params());
    assert_eq!(found[0].spec.name, "radius");
    assert!(
        found[0].spec.doc.contains("radius"),
        "{}",
        found[0].spec.doc
    );
    let diffuse = at(&c, "params.pts", "diffuse rgb", "diffuse");
    let at_diffuse = s
        .param_at(diffuse.file, diffuse.start as usize + 2)
        .unwrap();
    assert_eq!(at_diffuse.spec.name, "diffuse");
    for p in s.params() {
        assert_eq!(text_of(&c, p.name_span), p.spec.name);
    }
    let kinds: Vec<(&str, &str)> = (s.blocks().iter())
        .map(|&(span, kind)| (text_of(&c, span), kind))
        .collect();
    assert_eq!(kinds, [("camera", "camera"), ("sphere", "sphere")]);
}
