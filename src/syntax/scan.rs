//! Scans of a file's text that see only what parsing needs to cut it and
//! to find its blocks: the marks outside comments and strings, where a
//! statement follows a `}`, and the byte order mark.

/// The length of the byte order mark that may open a file (and only there):
/// both parse paths start after it.
pub(super) fn bom_len(text: &str) -> usize {
    if text.starts_with('\u{FEFF}') {
        '\u{FEFF}'.len_utf8()
    } else {
        0
    }
}

/// Whether `rest` (what follows a `}` at nesting depth 0) goes on with a
/// new statement: a word other than `else`, or nothing. A `}` followed by
/// `else`, `;`, `{` or an operator closes a branch of an `if` (a statement
/// or a value, `let y = if a { 1 } else { 2 };`), not a statement.
pub(super) fn statement_follows(rest: &str) -> bool {
    let mut rest = rest;
    loop {
        rest = rest.trim_start();
        if let Some(r) = rest.strip_prefix("//") {
            rest = r.find('\n').map_or("", |k| &r[k..]);
        } else if let Some(r) = rest.strip_prefix("/*") {
            rest = r.find("*/").map_or("", |k| &r[k + 2..]);
        } else {
            break;
        }
    }
    let word_len = rest
        .find(|c: char| !(c.is_alphanumeric() || c == '_'))
        .unwrap_or(rest.len());
    rest.is_empty() || (word_len > 0 && &rest[..word_len] != "else")
}

/// Calls `f(offset, byte)` for every bracket (`(`, `)`, `[`, `]`, `<`, `>`, `{`, `}`)
/// and `;` of `text` outside comments and strings: the scans for parse pieces
/// and unclosed blocks need to see those only. `f` returns `false` to stop.
pub(crate) fn for_each_code_mark(text: &str, mut f: impl FnMut(usize, u8) -> bool) {
    /// Bytes the loop stops at: the marks, and what opens a comment or string.
    const STOP: [bool; 256] = {
        let mut t = [false; 256];
        let mut k = 0;
        let marks = b"()[]<>{};/\"";
        while k < marks.len() {
            t[marks[k] as usize] = true;
            k += 1;
        }
        t
    };
    let bytes = text.as_bytes();
    let mut i = 0;
    while i < bytes.len() {
        // Most bytes are none of these: one table load each (this scan runs
        // before the parallel parse starts, over the whole file).
        if !STOP[bytes[i] as usize] {
            i += 1;
            continue;
        }
        match bytes[i] {
            b'/' if bytes.get(i + 1) == Some(&b'/') => {
                while i < bytes.len() && bytes[i] != b'\n' {
                    i += 1;
                }
            }
            b'/' if bytes.get(i + 1) == Some(&b'*') => {
                i += 2;
                while i < bytes.len() && !(bytes[i] == b'*' && bytes.get(i + 1) == Some(&b'/')) {
                    i += 1;
                }
                i += 1;
            }
            b'"' => {
                i += 1;
                while i < bytes.len() && bytes[i] != b'"' && bytes[i] != b'\n' {
                    if bytes[i] == b'\\' {
                        i += 1;
                    }
                    i += 1;
                }
            }
            b'/' => {}
            b => {
                if !f(i, b) {
                    return;
                }
            }
        }
        i += 1;
    }
}

/// Where the code before `pos` ends: past blanks and the comments at the
/// ends of lines (`let r = 1 // radius`).
pub(super) fn code_end_before(text: &str, pos: usize) -> usize {
    let mut end = pos;
    loop {
        end = text[..end].trim_end().len();
        let code = &text[..end];
        if let Some(head) = code.strip_suffix("*/") {
            match head.rfind("/*") {
                Some(open) => end = open,
                None => return end,
            }
            continue;
        }
        let line_start = code.rfind('\n').map_or(0, |i| i + 1);
        match line_comment(&code[line_start..]) {
            Some(c) => end = line_start + c,
            None => return end,
        }
    }
}

/// Where a `//` comment starts in `line`, outside strings.
fn line_comment(line: &str) -> Option<usize> {
    let bytes = line.as_bytes();
    let mut in_string = false;
    let mut i = 0;
    while i < bytes.len() {
        match bytes[i] {
            b'\\' if in_string => i += 1,
            b'"' => in_string = !in_string,
            b'/' if !in_string && bytes.get(i + 1) == Some(&b'/') => return Some(i),
            _ => {}
        }
        i += 1;
    }
    None
}

#[cfg(test)]
mod tests {
    use super::code_end_before;

    #[test]
    fn code_ends_before_blanks_and_comments() {
        let at = |text: &str| code_end_before(text, text.len());
        assert_eq!(at("let r = 1\n\n"), 9);
        assert_eq!(at("let r = 1 // radius\n// a ball\n"), 9);
        assert_eq!(at("let r = 1 /* radius */\n"), 9);
        assert_eq!(at("let s = \"a // b\"\n"), 16, "not a comment in a string");
        assert_eq!(at("// only\n"), 0);
        assert_eq!(at(""), 0);
    }
}
