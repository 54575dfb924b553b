//! The parser's guess that a block lacks its `}` never blames a closed
//! block: every example, with one token deleted, or one inserted, on each
//! line in turn, is parsed; "this block is never closed" may only come
//! where a `}` was deleted, and then it names the `{` that `}` closed.

use ptsc::diag::codes;
use ptsc::source::FileId;

/// A token of a scene: its byte range.
type Token = (usize, usize);

/// The tokens of `text` (words and numbers, strings, single punctuation
/// characters), skipping blanks and comments.
fn tokens(text: &str) -> Vec<Token> {
    let bytes = text.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        let c = bytes[i];
        let start = i;
        if c.is_ascii_whitespace() {
            i += 1;
            continue;
        }
        if text[i..].starts_with("//") {
            i += text[i..].find('\n').unwrap_or(text.len() - i);
            continue;
        }
        if text[i..].starts_with("/*") {
            i += text[i..].find("*/").map_or(text.len() - i, |e| e + 2);
            continue;
        }
        if c == b'"' {
            i += 1;
            while i < bytes.len() && bytes[i] != b'"' && bytes[i] != b'\n' {
                i += if bytes[i] == b'\\' { 2 } else { 1 };
            }
            i = (i + 1).min(bytes.len());
        } else if c.is_ascii_alphanumeric() || c == b'_' || c == b'.' {
            while i < bytes.len()
                && (bytes[i].is_ascii_alphanumeric() || bytes[i] == b'_' || bytes[i] == b'.')
            {
                i += 1;
            }
        } else {
            i += text[i..].chars().next().unwrap().len_utf8();
        }
        out.push((start, i));
    }
    out
}

/// For each `}` token, the byte offset of the `{` it closes.
fn partners(text: &str, toks: &[Token]) -> Vec<Option<usize>> {
    let mut stack = Vec::new();
    toks.iter()
        .map(|&(s, _)| match &text[s..s + 1] {
            "{" => {
                stack.push(s);
                None
            }
            "}" => stack.pop(),
            _ => None,
        })
        .collect()
}

/// The offset of the `{` an unclosed-block error blames in `text`, if the
/// parse reports one.
fn blamed(text: &str) -> Option<usize> {
    let d = ptsc::syntax::parse(FileId(0), text, &ptsc::check::kinds::NAMES).err()?;
    (d.code == codes::UNCLOSED_BLOCK).then(|| d.span.unwrap().start as usize)
}

/// Tokens worth inserting: a word, a number, a value's punctuation.
const INSERTED: &[&str] = &["oops", "1", "<", ",", "material", "rgb", ";", "sphere"];

#[test]
fn a_closed_block_is_never_blamed_for_a_missing_brace() {
    let root = crate::root();
    let mut files: Vec<_> = std::fs::read_dir(root.join("examples"))
        .unwrap()
        .chain(std::fs::read_dir(root.join("examples/parts")).unwrap())
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "pts" || x == "ptsi"))
        .collect();
    files.sort();
    assert!(files.len() >= 20, "only {} examples", files.len());
    let (mut cases, mut wrong) = (0, Vec::new());
    for path in &files {
        let text = std::fs::read_to_string(path).unwrap();
        let toks = tokens(&text);
        let closes = partners(&text, &toks);
        // Every token deleted in turn.
        for (k, &(s, e)) in toks.iter().enumerate() {
            let mutated = format!("{}{}", &text[..s], &text[e..]);
            cases += 1;
            let Some(at) = blamed(&mutated) else { continue };
            // Offsets before the deletion are unchanged. The `{` blamed
            // must be the one whose `}` was deleted or a block around it
            // (braces alone cannot tell which lacks its `}`, and closing
            // either mends the file).
            let around = |open: usize| {
                let closing = (toks.iter().zip(&closes)).find(|(_, p)| **p == Some(open));
                closing.is_some_and(|(&(c, _), _)| open < s && s < c)
            };
            if closes[k].is_none() || !(closes[k] == Some(at) || around(at)) {
                wrong.push(format!(
                    "{}: deleting `{}` at byte {s} blames the `{{` at {at}",
                    path.display(),
                    &text[s..e]
                ));
            }
        }
        // A token inserted at the start and at the end of every line.
        let mut line_start = 0;
        for line in text.split_inclusive('\n') {
            let line_end = line_start + line.trim_end().len();
            for at in [line_start, line_end] {
                for word in INSERTED {
                    let mutated = format!("{} {word} {}", &text[..at], &text[at..]);
                    cases += 1;
                    if let Some(blame) = blamed(&mutated) {
                        wrong.push(format!(
                            "{}: inserting `{word}` at byte {at} blames the `{{` at {blame}",
                            path.display()
                        ));
                    }
                }
            }
            line_start += line.len();
        }
    }
    assert!(cases > 10_000, "only {cases} cases");
    assert!(
        wrong.is_empty(),
        "{} of {cases} mutations blame a closed block:\n{}",
        wrong.len(),
        wrong[..wrong.len().min(30)].join("\n")
    );
}
