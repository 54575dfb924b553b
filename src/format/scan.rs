//! What the formatter reads of the text beside the AST: the comments (the
//! grammar skips them), where a brace or a literal is, and the statements
//! and entries that are printed as written (their content is not parsed).

use crate::syntax::ast::{Block, Entry, File, MaterialRef, Statement};

/// A comment of the text: `// …` up to its line's end, or `/* … */`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Comment {
    /// First byte (the `/`).
    pub start: usize,
    /// One past the last byte (a line comment stops before its `\n`).
    pub end: usize,
}

impl Comment {
    /// Whether it is a `//` comment (which ends its line).
    pub fn is_line(&self, text: &str) -> bool {
        text[self.start..].starts_with("//")
    }

    /// Its text as the formatter prints it (a line comment without the
    /// blanks, such as a `\r`, that end it).
    pub fn text<'t>(&self, text: &'t str) -> &'t str {
        let s = &text[self.start..self.end];
        if self.is_line(text) {
            s.trim_end()
        } else {
            s
        }
    }
}

/// The comments of `text` in order, outside strings and outside the
/// `verbatim` ranges (sorted, disjoint), whose text is printed as written.
pub(super) fn comments(text: &str, verbatim: &[(usize, usize)]) -> Vec<Comment> {
    let bytes = text.as_bytes();
    let mut out = Vec::new();
    let mut skip = verbatim.iter().peekable();
    let mut i = 0;
    while i < bytes.len() {
        while skip.peek().is_some_and(|&&(_, end)| end <= i) {
            skip.next();
        }
        if let Some(&&(start, end)) = skip.peek() {
            if start <= i {
                i = end;
                continue;
            }
        }
        match bytes[i] {
            b'"' => i = string_end(text, i),
            b'/' if bytes.get(i + 1) == Some(&b'/') => {
                let end = text[i..].find('\n').map_or(text.len(), |k| i + k);
                out.push(Comment { start: i, end });
                i = end;
            }
            b'/' if bytes.get(i + 1) == Some(&b'*') => {
                let end = text[i + 2..]
                    .find("*/")
                    .map_or(text.len(), |k| i + 2 + k + 2);
                out.push(Comment { start: i, end });
                i = end;
            }
            _ => i += 1,
        }
    }
    out
}

/// One past the end of the string literal that opens at `start` (a `"`):
/// its closing quote, or the end of its line when it has none.
pub(super) fn string_end(text: &str, start: usize) -> usize {
    let bytes = text.as_bytes();
    let mut i = start + 1;
    while i < bytes.len() && bytes[i] != b'"' && bytes[i] != b'\n' {
        i += if bytes[i] == b'\\' { 2 } else { 1 };
    }
    (i + 1).min(bytes.len())
}

/// One past the end of the number literal that starts at `start`, as the
/// grammar reads one (`12`, `0.5`, `.5`, `1.`, `1e-3`).
pub(super) fn number_end(text: &str, start: usize) -> usize {
    let b = text.as_bytes();
    let digits = |mut i: usize| {
        while i < b.len() && b[i].is_ascii_digit() {
            i += 1;
        }
        i
    };
    let mut i = digits(start);
    if b.get(i) == Some(&b'.') && b.get(i + 1) != Some(&b'.') {
        i = digits(i + 1);
    }
    if matches!(b.get(i), Some(b'e' | b'E')) {
        let mut j = i + 1;
        if matches!(b.get(j), Some(b'+' | b'-')) {
            j += 1;
        }
        if b.get(j).is_some_and(u8::is_ascii_digit) {
            i = digits(j);
        }
    }
    i
}

/// The first byte at or after `from` that is neither a blank, nor in a
/// comment, nor one of `also` (brackets to step over).
pub(super) fn next_code(text: &str, from: usize, also: &[u8]) -> usize {
    let bytes = text.as_bytes();
    let mut i = from;
    while i < bytes.len() {
        let b = bytes[i];
        if b == b'/' && bytes.get(i + 1) == Some(&b'/') {
            i = text[i..].find('\n').map_or(text.len(), |k| i + k);
        } else if b == b'/' && bytes.get(i + 1) == Some(&b'*') {
            i = text[i + 2..]
                .find("*/")
                .map_or(text.len(), |k| i + 2 + k + 2);
        } else if b.is_ascii_whitespace() || also.contains(&b) {
            i += 1;
        } else if b >= 0x80 && text[i..].starts_with(char::is_whitespace) {
            i += text[i..].chars().next().map_or(1, char::len_utf8);
        } else {
            return i;
        }
    }
    text.len()
}

/// Where the first `want` outside comments and strings is, at or after
/// `from` (the text's end when there is none).
pub(super) fn find_code(text: &str, from: usize, want: u8) -> usize {
    let bytes = text.as_bytes();
    let mut i = next_code(text, from, &[]);
    while i < bytes.len() && bytes[i] != want {
        i = if bytes[i] == b'"' {
            string_end(text, i)
        } else {
            i + 1
        };
        i = next_code(text, i, &[]);
    }
    i
}

/// Whether `text[a..b]` holds a blank line (two line ends or more).
pub(super) fn blank_between(text: &str, a: usize, b: usize) -> bool {
    a < b && text[a..b].bytes().filter(|&c| c == b'\n').count() >= 2
}

/// The byte ranges printed as written, in order: POV-Ray directives, and
/// the statements and block entries ptsc does not have (their content is
/// not parsed, so a comment there is their text).
pub(super) fn verbatim_ranges(file: &File) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    statements(&file.statements, &mut out);
    out
}

/// The verbatim ranges of `list`, appended to `out`.
fn statements(list: &[Statement], out: &mut Vec<(usize, usize)>) {
    for s in list {
        match s {
            Statement::Directive { span, .. } | Statement::Foreign { span, .. } => {
                out.push((span.start as usize, span.end as usize))
            }
            Statement::For { body, .. } | Statement::Group { body, .. } => statements(body, out),
            Statement::If {
                arms, otherwise, ..
            } => {
                for (_, body) in arms {
                    statements(body, out);
                }
                if let Some(body) = otherwise {
                    statements(body, out);
                }
            }
            Statement::Instance { block, .. }
            | Statement::Material { block, .. }
            | Statement::Texture { block, .. }
            | Statement::Block { block, .. } => entries(block, out),
            Statement::Let { .. }
            | Statement::Include { .. }
            | Statement::Function { .. }
            | Statement::Background { .. } => {}
        }
    }
}

/// The verbatim ranges of a block's entries, appended to `out`.
fn entries(block: &Block, out: &mut Vec<(usize, usize)>) {
    for e in &block.entries {
        match e {
            Entry::Foreign { span, .. } => out.push((span.start as usize, span.end as usize)),
            Entry::Texture { block, .. }
            | Entry::Material {
                material: MaterialRef::Inline(block),
                ..
            } => entries(block, out),
            Entry::Materials { swaps, .. } => {
                for swap in swaps {
                    if let MaterialRef::Inline(block) = &swap.material {
                        entries(block, out);
                    }
                }
            }
            _ => {}
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn comments_skip_strings_and_verbatim_ranges() {
        let text = "a \"// no\" // yes\n/* b */ #if x // no\nc";
        let at = text.find('#').unwrap();
        let end = text[at..].find('\n').unwrap() + at;
        let found: Vec<&str> = comments(text, &[(at, end)])
            .iter()
            .map(|c| c.text(text))
            .collect();
        assert_eq!(found, ["// yes", "/* b */"]);
    }

    #[test]
    fn literals_end_where_the_grammar_ends_them() {
        assert_eq!(number_end("1.5e-3)", 0), 6);
        assert_eq!(number_end("1..3", 0), 1);
        assert_eq!(number_end(".5 ", 0), 2);
        assert_eq!(number_end("2e", 0), 1);
        assert_eq!(string_end(r#""a\"b" x"#, 0), 6);
    }

    #[test]
    fn code_is_found_past_comments_and_strings() {
        let text = "x] /* { */ \"{\" // {\n {";
        assert_eq!(find_code(text, 1, b'{'), text.len() - 1);
        assert_eq!(next_code(text, 1, b"]"), text.find('"').unwrap());
    }
}
