//! The safety net: the formatted text must parse to the same syntax tree
//! (spans aside) and hold the same comments, or it is not used.

use super::scan::{comments, verbatim_ranges};
use super::FormatError;
use crate::syntax::ast::File;

/// Checks `out`, the formatting of `text` (parsed as `before`).
pub(super) fn verify(text: &str, before: &File, out: &str) -> Result<(), FormatError> {
    let after = super::parse(out).map_err(|e| match e {
        FormatError::Syntax(d) => FormatError::Bug(format!(
            "the formatted text does not parse: {}",
            d.first().map_or("", |d| d.message.as_str())
        )),
        bug => bug,
    })?;
    if spanless(before) != spanless(&after) {
        return Err(FormatError::Bug(
            "the formatted text parses to another syntax tree".into(),
        ));
    }
    if comment_texts(text, before) != comment_texts(out, &after) {
        return Err(FormatError::Bug(
            "the formatted text does not hold the same comments".into(),
        ));
    }
    Ok(())
}

/// The comments of `text` (parsed as `file`), sorted: a multiset.
pub(super) fn comment_texts(text: &str, file: &File) -> Vec<String> {
    let mut out: Vec<String> = comments(text, &verbatim_ranges(file))
        .iter()
        .map(|c| c.text(text).to_string())
        .collect();
    out.sort();
    out
}

/// The syntax tree as text without its spans: two trees that differ only
/// in where their nodes are give the same text. It is the tree's `Debug`
/// form with every `Span { … }` taken out (a span's form holds no brace).
pub fn spanless(file: &File) -> String {
    let full = format!("{file:?}");
    let mut out = String::with_capacity(full.len() / 2);
    let mut rest = full.as_str();
    while let Some(at) = rest.find("Span {") {
        out.push_str(&rest[..at]);
        let after = &rest[at..];
        rest = &after[after.find('}').map_or(after.len(), |k| k + 1)..];
    }
    out.push_str(rest);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> File {
        super::super::parse(text).unwrap_or_else(|_| panic!("parses: {text}"))
    }

    #[test]
    fn spans_do_not_count_but_everything_else_does() {
        let a = parse("sphere { center <0, 1, 0> radius 1 }");
        let b = parse("\n\nsphere {\n    center <0,1,0>\n    radius 1\n}\n");
        let c = parse("sphere { center <0, 1, 0> radius 2 }");
        assert_eq!(spanless(&a), spanless(&b));
        assert_ne!(spanless(&a), spanless(&c));
        assert!(!spanless(&a).contains("start"));
    }

    #[test]
    fn a_lost_comment_is_a_bug() {
        let text = "let a = 1; // one\n";
        let file = parse(text);
        assert!(verify(text, &file, "let a = 1; // one\n").is_ok());
        assert!(matches!(
            verify(text, &file, "let a = 1;\n"),
            Err(FormatError::Bug(_))
        ));
        assert!(matches!(
            verify(text, &file, "let a = 2; // one\n"),
            Err(FormatError::Bug(_))
        ));
    }
}
