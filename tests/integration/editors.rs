//! The editors' keyword lists must match the grammar's keywords.

use std::collections::BTreeSet;

fn grammar_keywords() -> BTreeSet<String> {
    let g = std::fs::read_to_string(crate::root().join("grammar/pts.pest")).unwrap();
    g.lines()
        .filter_map(|l| l.strip_prefix("kw_"))
        .map(|l| l.split_whitespace().next().unwrap().to_string())
        .collect()
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
        words.extend(inner.split('|').map(str::to_string));
    }
    assert_eq!(words, grammar_keywords());
}

#[test]
fn vim_syntax_knows_every_keyword() {
    let vim = std::fs::read_to_string(crate::root().join("editors/vim/syntax/pts.vim")).unwrap();
    let mut words = BTreeSet::new();
    for line in vim.lines() {
        if let Some(rest) = line.strip_prefix("syn keyword ") {
            let mut it = rest.split_whitespace();
            let group = it.next().unwrap();
            if group != "ptsFunction" {
                words.extend(it.map(str::to_string));
            }
        }
    }
    assert_eq!(words, grammar_keywords());
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
