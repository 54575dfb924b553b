//! The words of the language the parser knows beyond its grammar: the
//! reserved words, the keywords that open a statement, and how a statement
//! is recognised in the text (for recovery and for the messages of
//! syntax errors).

/// Every reserved word of the language (kept in sync with the grammar by a test).
pub const KEYWORDS: &[&str] = &[
    "let",
    "include",
    "for",
    "in",
    "if",
    "else",
    "fn",
    "group",
    "instance",
    "background",
    "material",
    "texture",
    "rgb",
    "true",
    "false",
];

/// Keywords that open a statement. A block statement opens with its kind's
/// name ([`statement_word`]).
pub(super) const STATEMENT_KEYWORDS: &[&str] = &[
    "let",
    "include",
    "for",
    "background",
    "if",
    "fn",
    "group",
    "material",
    "instance",
];

/// The word at `at`, if it opens a statement: a statement keyword (or
/// `texture`), or a name followed by `{` where a statement may start
/// (after blanks only): a block statement `kind { … }`. The grammar does not
/// know the kinds (the checker's table does), so a name and a brace is
/// taken for one.
pub(super) fn statement_word(text: &str, at: usize) -> Option<&str> {
    let rest = &text[at..];
    let len = rest
        .find(|c: char| !(c.is_alphanumeric() || c == '_'))
        .unwrap_or(rest.len());
    let word = &rest[..len];
    if word.is_empty() || word.starts_with(|c: char| c.is_ascii_digit()) {
        return None;
    }
    if STATEMENT_KEYWORDS.contains(&word) || word == "texture" {
        return Some(word);
    }
    let opens_block = rest[len..].trim_start().starts_with('{');
    (opens_block && !KEYWORDS.contains(&word)).then_some(word)
}
