//! The hint for a block comment that holds another. Comments do not nest
//! (as in C, POV-Ray and most languages with `/* */`), so the first `*/`
//! ends both, and what the writer meant to keep in the outer comment reads
//! as code up to a `*/` that no comment opened. The syntax error that
//! follows is found somewhere in that stretch, and names a token there,
//! not the cause.

use crate::diag::Diagnostic;
use crate::source::FileId;
use crate::span::Span;

/// How far before an error the scan for comments starts, and after it how
/// far it looks for the stray `*/`: a file has up to
/// [`super::hand_over::MAX_ERRORS`] syntax errors, each scanned for, so the
/// cost stays that of a window, not of the file. A comment longer than the
/// window that starts before it is not seen whole, and gets no hint.
const WINDOW: usize = 64 * 1024;

/// A block comment holding a `/*`, and the `*/` past its end that no
/// comment opened: byte offsets in the file's text.
#[derive(Debug, PartialEq, Eq)]
struct Nested {
    /// The `/*` inside the comment.
    inner: usize,
    /// The `*/` that ended the comment (the inner one's, as written).
    end: usize,
    /// The `*/` after it that no comment opened.
    stray: usize,
}

/// Adds to `d`, the syntax error at byte `pos`, what a nested comment
/// before it explains: the error lies between the first `*/` of a comment
/// holding a `/*` and a `*/` that no comment opened.
pub(super) fn explain(d: Diagnostic, text: &str, pos: usize, file: FileId) -> Diagnostic {
    let Some(n) = nested_before(text, pos) else {
        return d;
    };
    let d = if pos == n.stray {
        Diagnostic {
            message: "`*/` outside a comment".into(),
            label: "no comment is open here".into(),
            span: Some(Span::new(file, pos, pos + 2)),
            ..d
        }
    } else {
        d
    };
    d.with_secondary(
        Span::new(file, n.inner, n.inner + 2),
        "this `/*` is inside a comment: it opens no second one",
    )
    .with_secondary(
        Span::new(file, n.end, n.end + 2),
        "so the comment ends at this first `*/`",
    )
    .with_help(
        "block comments do not nest: end the inner comment's text without `*/`, or comment the lines out with `//`",
    )
}

/// The comment holding a `/*` whose stray closing `*/` lies at or after
/// `pos`, with nothing but code (no other comment's start, no other stray
/// `*/`) between that comment's end and the stray one.
fn nested_before(text: &str, pos: usize) -> Option<Nested> {
    let bytes = text.as_bytes();
    let mut i = pos.saturating_sub(WINDOW);
    // Start on a line's start: strings do not cross lines, comments may
    // (one that crosses the window's start is misread; see WINDOW).
    if i > 0 {
        while !text.is_char_boundary(i) {
            i += 1;
        }
        i = text[i..].find('\n').map_or(text.len(), |k| i + k + 1);
    }
    let last = bytes.len().min(pos.saturating_add(WINDOW));
    let mut holder: Option<(usize, usize)> = None;
    while i < last {
        match (bytes[i], bytes.get(i + 1)) {
            (b'/', Some(b'/')) => i = text[i..].find('\n').map_or(bytes.len(), |k| i + k),
            (b'/', Some(b'*')) => {
                if i >= pos {
                    return None;
                }
                let close = i + 2 + text[i + 2..].find("*/")?;
                holder = text[i + 2..close].find("/*").map(|k| (i + 2 + k, close));
                i = close + 2;
                continue;
            }
            (b'*', Some(b'/')) => {
                return match holder {
                    Some((inner, end)) if i >= pos => Some(Nested {
                        inner,
                        end,
                        stray: i,
                    }),
                    _ if i >= pos => None,
                    _ => {
                        // A stray `*/` before the error closes its own
                        // story: the error is not in its stretch.
                        holder = None;
                        i += 2;
                        continue;
                    }
                };
            }
            (b'"', _) => {
                let line_end = text[i + 1..].find('\n').map_or(bytes.len(), |k| i + 1 + k);
                let mut j = i + 1;
                while j < line_end && bytes[j] != b'"' {
                    j += if bytes[j] == b'\\' { 2 } else { 1 };
                }
                i = if j < line_end { j } else { i };
            }
            _ => {}
        }
        i += 1;
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    fn found(text: &str, at: &str) -> Option<Nested> {
        nested_before(text, text.find(at).unwrap())
    }

    #[test]
    fn a_comment_holding_a_comment_is_found_from_the_stray_close() {
        let text = "/* off\nsphere {} /* note */\nsphere {}\n*/\nsphere {}\n";
        let n = found(text, "*/\nsphere").unwrap();
        assert_eq!(&text[n.inner..n.inner + 9], "/* note *");
        assert_eq!(n.end, text.find("*/").unwrap());
        assert_eq!(n.stray, text.rfind("*/").unwrap());
        // And from an error between the two.
        let text = "/* off /* note */ prose here */ sphere {}";
        assert!(found(text, "prose").is_some());
    }

    #[test]
    fn plain_comments_strings_and_later_errors_get_no_hint() {
        // No comment holds a `/*`.
        assert_eq!(found("/* a */ sphere { */", "*/"), None);
        assert_eq!(found("/* a */ x */", "x"), None);
        // The `/*` is in a string or a line comment, not in the comment.
        assert_eq!(found("/* a \"\" */ \"/*\" x */", "x"), None);
        assert_eq!(found("// /* a\n x */", "x"), None);
        // A comment opened after the error, or a stray `*/` between.
        assert_eq!(found("/* a /* b */ x /* c */ */", "x"), None);
        assert_eq!(found("/* a /* b */ */ x */", "x */"), None);
        // No stray `*/` after the error.
        assert_eq!(found("/* a /* b */ x", "x"), None);
        // A quote that does not close on its line is one character.
        assert!(found("\" /* a /* b */ x */", "x").is_some());
    }

    #[test]
    fn the_scan_is_bounded_by_its_window() {
        let pad = " ".repeat(3 * WINDOW);
        let text = format!("/* a /* b */{pad}x */");
        assert_eq!(found(&text, "x"), None);
        let text = format!("{pad}\n/* a /* b */ x */");
        assert!(found(&text, "x").is_some());
    }
}
