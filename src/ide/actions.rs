//! Quick fixes: a diagnostic's replacement (a did-you-mean, the ptsc word
//! for a POV-Ray one) as an edit the editor applies.

use super::tokens::word_len;
use super::View;
use crate::diag::Diagnostic;
use std::ops::Range;

/// A fix for one diagnostic.
#[derive(Debug, Clone, PartialEq)]
pub struct Fix {
    /// What the editor's menu says.
    pub title: String,
    /// The bytes replaced, in the document.
    pub range: Range<usize>,
    /// The new text.
    pub replacement: String,
    /// The diagnostic it fixes.
    pub diagnostic: Diagnostic,
}

/// The fixes of the diagnostics of the view's document (checked from the
/// text held now) that touch `range`.
pub fn fixes(view: View, range: Range<usize>) -> Vec<Fix> {
    let (Some(file), Some(compiled)) = (view.fresh_file(), view.compiled) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for d in &compiled.diagnostics.items {
        let Some(span) = d.span.filter(|s| s.file == file) else {
            continue;
        };
        let (start, end) = (span.start as usize, span.end as usize);
        if end < range.start || start > range.end {
            continue;
        }
        if let Some((at, replacement)) = fix_of(d, view.text) {
            let old = &view.text[at.clone()];
            out.push(Fix {
                title: format!("replace `{old}` with `{replacement}`"),
                range: at,
                replacement,
                diagnostic: d.clone(),
            });
        }
    }
    out
}

/// A diagnostic's replacement in `text`: its own ([`Diagnostic::fix`]),
/// or one read from a help line `did you mean `X`?` for the name its
/// span starts with.
pub fn fix_of(d: &Diagnostic, text: &str) -> Option<(Range<usize>, String)> {
    if let Some((span, replacement)) = &d.fix {
        let range = span.start as usize..span.end as usize;
        return text
            .get(range.clone())
            .map(|_| (range, replacement.clone()));
    }
    let help = d.help.as_deref()?;
    let rest = help.split("did you mean `").nth(1)?;
    let suggestion = rest.split('`').next()?;
    let span = d.span?;
    let start = span.start as usize;
    let len = word_len(text.get(start..)?);
    let simple = !suggestion.is_empty() && suggestion.chars().all(super::tokens::is_word_char);
    (len > 0 && simple).then(|| (start..start + len, suggestion.to_string()))
}
