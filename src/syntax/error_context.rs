//! What the text around a syntax error says about it: blocks never
//! closed, the words before it, other languages' habits. The parser's
//! error translation ([`super::hints::convert_error`]) reads these.

use crate::diag::{codes, Diagnostic};
use crate::source::FileId;
use crate::span::Span;

use super::grammar::{PtsParser, Rule};
use super::words::{statement_word, KEYWORDS};
use pest::error::InputLocation;

/// Whether `before` ends with the word `rgb` (and minus signs): a colour
/// of a colour without brackets.
pub(super) fn after_rgb(before: &str) -> bool {
    let t = before.trim_end_matches(|c: char| c.is_whitespace() || c == '-');
    t.strip_suffix("rgb").is_some_and(|head| {
        !head
            .chars()
            .next_back()
            .is_some_and(|c| c.is_alphanumeric() || c == '_')
    })
}

/// The byte offsets of the `{` without a matching `}` in `text`,
/// outermost first, skipping comments and strings.
pub(super) fn open_braces(text: &str) -> Vec<usize> {
    let mut stack = Vec::new();
    super::scan::for_each_code_mark(text, |i, b| {
        match b {
            b'{' => stack.push(i),
            b'}' => {
                stack.pop();
            }
            _ => {}
        }
        true
    });
    stack
}

/// The first line directly inside the block opened at `open` (not inside a
/// block within it) that starts with the name of a kind of block: where
/// the statement after a block never closed starts (the grammar reads it as
/// a block inside, so pest fails only at the end of the file).
pub(super) fn kind_inside<'t>(
    text: &'t str,
    open: usize,
    kinds: &[&str],
) -> Option<(usize, &'t str)> {
    let mut braces = Vec::new();
    super::scan::for_each_code_mark(&text[open..], |i, b| {
        if b == b'{' || b == b'}' {
            braces.push((open + i, b == b'{'));
        }
        true
    });
    let (mut depth, mut k) = (0i64, 0);
    let mut line = open + text[open..].find('\n')? + 1;
    loop {
        while k < braces.len() && braces[k].0 < line {
            depth += if braces[k].1 { 1 } else { -1 };
            k += 1;
        }
        if depth <= 0 {
            return None;
        }
        let rest = &text[line..];
        let at = line + (rest.len() - rest.trim_start_matches([' ', '\t']).len());
        if depth == 1 {
            if let Some(word) = statement_word(text, at).filter(|w| kinds.contains(w)) {
                return Some((at, word));
            }
        }
        line += rest.find('\n')? + 1;
    }
}

/// The error for the `{` at `open`, never closed.
pub(super) fn unclosed_block(file: FileId, open: usize) -> Diagnostic {
    Diagnostic::error(
        codes::UNCLOSED_BLOCK,
        "this block is never closed",
        Span::new(file, open, open + 1),
    )
    .with_label("this `{` has no matching `}`")
    .with_help("add `}` at the end of the block")
}

/// Whether closing a block with `}` just before `at` (the start of the
/// line where the parser failed at `pos`) lets a parse of the file from
/// `base` get past `pos`: the evidence that the block lacks its `}`.
pub(super) fn closing_helps(text: &str, base: usize, at: usize, pos: usize) -> bool {
    use pest::Parser;
    let patched = format!("{}}}{}", &text[base..at], &text[at..]);
    match PtsParser::parse(Rule::file, &patched) {
        Ok(_) => true,
        Err(e) => {
            let failed = match e.location {
                InputLocation::Pos(p) => p,
                InputLocation::Span((s, _)) => s,
            };
            failed > pos + 1 - base
        }
    }
}

/// The statement word that opens the line holding byte `pos`
/// ([`statement_word`]), and where it stands: an error on such a line
/// inside a block opened on an earlier line means that block was never
/// closed.
pub(super) fn statement_on_line(text: &str, pos: usize) -> Option<(usize, &str)> {
    let line_start = text[..pos].rfind('\n').map_or(0, |i| i + 1);
    let line = &text[line_start..];
    let indent = line.len() - line.trim_start().len();
    let at = line_start + indent;
    statement_word(text, at).map(|w| (at, w))
}

/// Whether the `{` at `open` opens a block statement or a material (where
/// statements cannot stand), not the body of a `for`, an `if` or a group
/// (where they can): the name right before it stands where a statement
/// starts (`sphere {`), or follows `material`, `instance` or a texture's
/// `texture NAME`.
pub(super) fn block_brace(text: &str, open: usize) -> bool {
    let before = text[..open].trim_end();
    let mut words = before
        .rsplit(|c: char| !(c.is_alphanumeric() || c == '_'))
        .filter(|w| !w.is_empty());
    let last = words.next().unwrap_or("");
    if !before.ends_with(last) || last.is_empty() || KEYWORDS.contains(&last) {
        return false;
    }
    let previous = words.next();
    if matches!(previous, Some("material" | "instance")) || words.next() == Some("texture") {
        return true;
    }
    // What stands before the name: nothing, or the end of a statement.
    let head = before[..before.len() - last.len()].trim_end();
    head.is_empty() || head.ends_with([';', '{', '}'])
}

/// The last `n` words before `pos` (letters, digits, `_`), nearest last,
/// with whether the nearest one ends right before `pos` (blanks aside).
pub(super) fn words_before(text: &str, pos: usize, n: usize) -> (Vec<&str>, bool) {
    let before = &text[..pos];
    let adjacent = before
        .trim_end()
        .chars()
        .next_back()
        .is_some_and(|c| c.is_alphanumeric() || c == '_');
    let mut words: Vec<&str> = before
        .rsplit(|c: char| !(c.is_alphanumeric() || c == '_'))
        .filter(|w| !w.is_empty())
        .take(n)
        .collect();
    words.reverse();
    (words, adjacent)
}

/// The help for another language's range (`before` the error, `found`
/// at it): Rust's inclusive `0..=3`, a `step` after a loop's range.
pub(super) fn range_habit(before: &str, found: &str) -> Option<String> {
    let before = before.trim_end();
    if found == "`=`" && before.ends_with("..") {
        return Some(
            "a range leaves out its end: `0..4` is 0, 1, 2, 3 (write `0..=3` as `0..4`)".into(),
        );
    }
    let in_for = before
        .rfind("for ")
        .is_some_and(|at| before[at..].contains(".."));
    (found == "`step`" && in_for).then(|| {
        "a range goes by 1: scale its number instead, `for i in 0..10 { let t = i * 0.1; … }`"
            .into()
    })
}

/// The help for `let x = ;`: a value was expected right after a `let`'s
/// `=` (not after `==`, `<=`, `>=` or `!=`, nor at a second `=`).
pub(super) fn missing_constant_value(
    before: &str,
    expected: &[&str],
    found: &str,
) -> Option<String> {
    if found == "`=`" {
        return None;
    }
    let before = before.trim_end();
    let after_let = before
        .strip_suffix('=')
        .filter(|b| !b.ends_with(['=', '<', '>', '!']))
        .and_then(|b| {
            b.trim_end()
                .rsplit_once(|c: char| !(c.is_alphanumeric() || c == '_'))
        })
        .is_some_and(|(b, _)| b.trim_end().ends_with("let"));
    (after_let && expected.iter().any(|e| e.starts_with("a value")))
        .then(|| "a constant takes its value after `=`: `let radius = 0.5;`".into())
}

/// A hint that fits the usual causes of a parse error.
pub(super) fn help_for(expected: &[&str], found: &str) -> String {
    if found == "end of file" && expected.contains(&"`}`") {
        return "a block is not closed: add `}`".into();
    }
    if expected.contains(&"a name") && found.starts_with('`') {
        let word = found.trim_matches('`');
        if KEYWORDS.contains(&word) {
            return format!("`{word}` is a reserved word; pick another name");
        }
    }
    if expected.iter().any(|e| e.starts_with("a value")) {
        return "a parameter is a name followed by a value, e.g. `radius 0.5` or `center <0, 1, 0>`"
            .into();
    }
    if found == "`{`" && expected.iter().any(|e| e.starts_with("an operator")) {
        return "a parameter's value opens no block: a texture is its kind and a block (`diffuse checker { … }`), a material `material { … }`; remove these braces or name the kind".into();
    }
    if found == "`}`" && expected == ["a statement"] {
        return "this `}` closes no block: remove it, or open the block it ends above it".into();
    }
    if found == "`=`" && expected.contains(&"a name") {
        return "a name goes before `=`: `let radius = 1;`".into();
    }
    if expected.contains(&"a statement") || expected.contains(&"`let`") {
        let word = found.trim_matches('`');
        if let Some(k) = crate::diag::did_you_mean(word, KEYWORDS.iter().copied()) {
            return format!("did you mean `{k}`?");
        }
        return "a scene is a list of statements: `let`, `fn`, `include`, `for`, `if`, `background`, `material`, `group`, `instance`, `camera { … }`, `render { … }`, a light or an object such as `sphere { … }`".into();
    }
    if expected.contains(&"`>`") && expected.contains(&"`,`") {
        return "separate vector components with `,` and close the vector with `>`: `<1, 2, 3>`"
            .into();
    }
    if expected.contains(&"`;`") {
        return "end a `let` with `;`".into();
    }
    // POV-Ray compares with `=` (`#if (A = 1)`).
    if found == "`=`" {
        return "`=` only defines (`let a = 1;`): compare with `==`, as in `if a == 1 { … }`"
            .into();
    }
    "check the syntax near this point (see docs/language.md)".into()
}
