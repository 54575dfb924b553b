//! The editors' keyword lists must match the grammar's keywords and the
//! kinds of block of the checker's kind table (`check::kinds`).

use std::collections::BTreeSet;

fn grammar_keywords() -> BTreeSet<String> {
    let g = std::fs::read_to_string(crate::root().join("grammar/pts.pest")).unwrap();
    g.lines()
        .filter_map(|l| l.strip_prefix("kw_"))
        .map(|l| l.split_whitespace().next().unwrap().to_string())
        .collect()
}

/// What the editors highlight as words of the language: the grammar's
/// keywords and the names of the kinds of block.
fn language_words() -> BTreeSet<String> {
    let mut words = grammar_keywords();
    words.extend(ptsc::check::kinds::names().map(str::to_string));
    words
}

fn words_in(text: &str) -> BTreeSet<String> {
    text.split(|c: char| !(c.is_alphanumeric() || c == '_'))
        .filter(|w| !w.is_empty())
        .map(str::to_string)
        .collect()
}

#[test]
fn grammar_keywords_match_the_parser_table() {
    let from_grammar = grammar_keywords();
    let from_table: BTreeSet<String> = ptsc::syntax::parser::KEYWORDS
        .iter()
        .map(|s| s.to_string())
        .collect();
    assert_eq!(from_grammar, from_table);
}

#[test]
fn vscode_grammar_knows_every_keyword() {
    let tm =
        std::fs::read_to_string(crate::root().join("editors/vscode/syntaxes/pts.tmLanguage.json"))
            .unwrap();
    let json: serde_json::Value = serde_json::from_str(&tm).unwrap();
    let mut words = BTreeSet::new();
    for p in json["repository"]["keywords"]["patterns"]
        .as_array()
        .unwrap()
    {
        let m = p["match"].as_str().unwrap();
        let inner = m.trim_start_matches("\\b(").trim_end_matches(")\\b");
        let names = inner.split('|').map(str::to_string);
        // The predefined names are names, not keywords.
        if p["name"] == "variable.language.pts" {
            let predefined: BTreeSet<String> = names.collect();
            assert_eq!(predefined, ptsc::check::PREDEFINED.map(String::from).into());
        } else {
            words.extend(names);
        }
    }
    assert_eq!(words, language_words());
}

#[test]
fn vim_syntax_knows_every_keyword() {
    let vim = std::fs::read_to_string(crate::root().join("editors/vim/syntax/pts.vim")).unwrap();
    let mut words = BTreeSet::new();
    for line in vim.lines() {
        if let Some(rest) = line.strip_prefix("syn keyword ") {
            let mut it = rest.split_whitespace();
            let group = it.next().unwrap();
            // Keywords only: not functions, parameters, integrator words
            // or the predefined names (those are checked apart).
            if group == "ptsPredefined" {
                let predefined: BTreeSet<String> = it.map(str::to_string).collect();
                assert_eq!(predefined, ptsc::check::PREDEFINED.map(String::from).into());
            } else if !matches!(group, "ptsFunction" | "ptsParam" | "ptsWord") {
                words.extend(it.map(str::to_string));
            }
        }
    }
    assert_eq!(words, language_words());
}

#[test]
fn editors_know_every_function() {
    let vim = std::fs::read_to_string(crate::root().join("editors/vim/syntax/pts.vim")).unwrap();
    let tm =
        std::fs::read_to_string(crate::root().join("editors/vscode/syntaxes/pts.tmLanguage.json"))
            .unwrap();
    let (vim_words, tm_words) = (words_in(&vim), words_in(&tm));
    for (f, _) in ptsc::check::eval::FUNCTIONS {
        assert!(vim_words.contains(*f), "vim lacks {f}");
        assert!(tm_words.contains(*f), "vscode lacks {f}");
    }
}

/// The parameter names the VS Code grammar highlights.
fn vscode_parameters(json: &serde_json::Value) -> BTreeSet<String> {
    let m = json["repository"]["parameters"]["match"].as_str().unwrap();
    let inner = &m[m.find("\\b(").unwrap() + 3..m.find(")\\b").unwrap()];
    inner.split('|').map(str::to_string).collect()
}

fn vscode_grammar() -> serde_json::Value {
    let tm =
        std::fs::read_to_string(crate::root().join("editors/vscode/syntaxes/pts.tmLanguage.json"))
            .unwrap();
    serde_json::from_str(&tm).unwrap()
}

#[test]
fn editors_know_every_parameter_and_only_parameters() {
    let names: BTreeSet<String> = ptsc::check::kinds::all_parameter_names()
        .into_iter()
        .map(str::to_string)
        .collect();
    assert_eq!(vscode_parameters(&vscode_grammar()), names);
    let vim = std::fs::read_to_string(crate::root().join("editors/vim/syntax/pts.vim")).unwrap();
    let vim_params: BTreeSet<String> = vim
        .lines()
        .filter_map(|l| l.strip_prefix("syn keyword ptsParam "))
        .flat_map(|l| l.split_whitespace().map(str::to_string))
        .collect();
    // `min` and `max` (box corners) are highlighted as the functions they also are.
    let functions: BTreeSet<String> = ptsc::check::eval::FUNCTIONS
        .iter()
        .map(|(f, _)| f.to_string())
        .collect();
    assert_eq!(vim_params, &names - &functions);
}

#[test]
fn vscode_numbers_and_parameters_match_what_they_should() {
    let json = vscode_grammar();
    let matches = |pattern: &str, text: &str| -> Vec<String> {
        let re = fancy_regex::Regex::new(pattern).unwrap();
        re.find_iter(text)
            .map(|m| m.unwrap().as_str().to_string())
            .collect()
    };
    let number = json["repository"]["numbers"]["match"].as_str().unwrap();
    assert_eq!(matches(number, "radius .5"), [".5"]);
    assert_eq!(matches(number, "for i in 0..10 {"), ["0", "10"]);
    assert_eq!(matches(number, "gloss 2.5e-3 * 1."), ["2.5e-3", "1."]);
    assert!(matches(number, "edge1 v0 a2").is_empty());
    let parameter = json["repository"]["parameters"]["match"].as_str().unwrap();
    assert_eq!(
        matches(parameter, "sphere { center c radius my_radius material m }"),
        ["center", "radius"]
    );
    // A box's `min` is a parameter, `min(a, b)` a function.
    assert_eq!(
        matches(parameter, "box { min <0,0,0> max min(1, 2) }"),
        ["min", "max"]
    );
}

#[test]
fn both_editors_highlight_every_integrator_and_sampler_name() {
    let root = crate::root();
    let vim = std::fs::read_to_string(root.join("editors/vim/syntax/pts.vim")).unwrap();
    let vim_words: BTreeSet<&str> = (vim.lines())
        .filter_map(|l| l.strip_prefix("syn keyword ptsWord "))
        .flat_map(str::split_whitespace)
        .collect();
    let json: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(root.join("editors/vscode/syntaxes/pts.tmLanguage.json")).unwrap(),
    )
    .unwrap();
    let pattern = json["repository"]["words"]["match"].as_str().unwrap();
    let inner = pattern
        .trim_start_matches("\\b(")
        .split(")\\b")
        .next()
        .unwrap();
    let vscode_words: BTreeSet<&str> = inner.split('|').collect();
    let names = (ptsc::ir::settings::IntegratorKind::WORDS.iter())
        .chain(ptsc::sampling::sampler::SamplerKind::WORDS.iter());
    for name in names {
        assert!(vim_words.contains(name), "vim does not highlight `{name}`");
        assert!(
            vscode_words.contains(name),
            "vscode does not highlight `{name}`"
        );
    }
}
