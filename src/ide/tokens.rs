//! A forgiving lexer for editor features: words, numbers, strings,
//! comments and punctuation with their byte ranges, on any text (a file
//! being typed is rarely valid). The parser's grammar decides what is a
//! scene; this only says what a cursor is on.

use std::ops::Range;

/// What a token is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TokenKind {
    /// A name or keyword.
    Word,
    /// A number literal.
    Number,
    /// A string literal (its quotes included; may be unterminated).
    String,
    /// A `//` or `/* */` comment.
    Comment,
    /// Any other character.
    Punct,
}

/// One token.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Token {
    /// What it is.
    pub kind: TokenKind,
    /// Its bytes in the text.
    pub range: Range<usize>,
}

/// The tokens of `text`, in order (white space left out).
pub fn tokens(text: &str) -> Vec<Token> {
    let bytes = text.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        let b = bytes[i];
        let start = i;
        let kind = if b.is_ascii_whitespace() {
            i += 1;
            continue;
        } else if text[i..].starts_with("//") {
            i = text[i..].find('\n').map_or(bytes.len(), |k| i + k);
            TokenKind::Comment
        } else if text[i..].starts_with("/*") {
            i = text[i + 2..]
                .find("*/")
                .map_or(bytes.len(), |k| i + 2 + k + 2);
            TokenKind::Comment
        } else if b == b'"' {
            i += 1;
            while i < bytes.len() && bytes[i] != b'"' && bytes[i] != b'\n' {
                i += if bytes[i] == b'\\' && i + 1 < bytes.len() {
                    2
                } else {
                    1
                };
            }
            i = (i + usize::from(i < bytes.len() && bytes[i] == b'"')).min(bytes.len());
            TokenKind::String
        } else if b.is_ascii_digit()
            || (b == b'.'
                && bytes.get(i + 1).is_some_and(u8::is_ascii_digit)
                && (i == 0 || bytes[i - 1] != b'.'))
        {
            i = number_end(bytes, i);
            TokenKind::Number
        } else if is_word_char(text[i..].chars().next().unwrap_or(' ')) {
            i += word_len(&text[i..]);
            TokenKind::Word
        } else {
            i += text[i..].chars().next().map_or(1, char::len_utf8);
            TokenKind::Punct
        };
        // Never stop inside a character.
        while !text.is_char_boundary(i) {
            i += 1;
        }
        out.push(Token {
            kind,
            range: start..i,
        });
    }
    out
}

/// Whether `c` may be part of a name.
pub fn is_word_char(c: char) -> bool {
    c.is_alphanumeric() || c == '_'
}

/// The length in bytes of the name at the start of `s`.
pub fn word_len(s: &str) -> usize {
    s.find(|c: char| !is_word_char(c)).unwrap_or(s.len())
}

fn number_end(bytes: &[u8], mut i: usize) -> usize {
    while i < bytes.len() && bytes[i].is_ascii_digit() {
        i += 1;
    }
    // `0..10` is a range: its `..` is not a decimal point.
    if i < bytes.len() && bytes[i] == b'.' && bytes.get(i + 1) != Some(&b'.') {
        i += 1;
        while i < bytes.len() && bytes[i].is_ascii_digit() {
            i += 1;
        }
    }
    if i < bytes.len() && (bytes[i] == b'e' || bytes[i] == b'E') {
        let mut j = i + 1;
        if j < bytes.len() && (bytes[j] == b'+' || bytes[j] == b'-') {
            j += 1;
        }
        if j < bytes.len() && bytes[j].is_ascii_digit() {
            i = j;
            while i < bytes.len() && bytes[i].is_ascii_digit() {
                i += 1;
            }
        }
    }
    i
}

/// The range of the name around `offset` (touching it on either side).
pub fn word_at(text: &str, offset: usize) -> Option<Range<usize>> {
    let offset = offset.min(text.len());
    if !text.is_char_boundary(offset) {
        return None;
    }
    let start = text[..offset]
        .char_indices()
        .rev()
        .take_while(|(_, c)| is_word_char(*c))
        .last()
        .map_or(offset, |(i, _)| i);
    let end = offset + word_len(&text[offset..]);
    (start < end && !text[start..].starts_with(|c: char| c.is_ascii_digit())).then_some(start..end)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tokens_of_a_scene_line() {
        let text = "sphere { center <0, .5, 1e3> } // é\n\"a.obj";
        let kinds: Vec<_> = tokens(text)
            .iter()
            .map(|t| (t.kind, &text[t.range.clone()]))
            .collect();
        use TokenKind::*;
        assert_eq!(
            kinds,
            [
                (Word, "sphere"),
                (Punct, "{"),
                (Word, "center"),
                (Punct, "<"),
                (Number, "0"),
                (Punct, ","),
                (Number, ".5"),
                (Punct, ","),
                (Number, "1e3"),
                (Punct, ">"),
                (Punct, "}"),
                (Comment, "// é"),
                (String, "\"a.obj"),
            ]
        );
        assert_eq!(&text[word_at(text, 3).unwrap()], "sphere");
        assert_eq!(&text[word_at(text, 6).unwrap()], "sphere");
        assert_eq!(word_at(text, 7), None);
        let r: Vec<_> = tokens("0..10").iter().map(|t| t.kind).collect();
        assert_eq!(r, [Number, Punct, Punct, Number]);
    }

    proptest::proptest! {
        #[test]
        fn tokens_cover_any_text_in_order(text in "\\PC{0,60}") {
            let mut end = 0;
            for t in tokens(&text) {
                proptest::prop_assert!(t.range.start >= end && t.range.end > t.range.start);
                proptest::prop_assert!(text.is_char_boundary(t.range.end));
                end = t.range.end;
            }
        }
    }
}
