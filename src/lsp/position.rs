//! Positions as the client counts them: a line and a column in UTF-8
//! bytes (when the client accepts `positionEncoding: "utf-8"`, LSP 3.17) or
//! in UTF-16 code units (every client, VS Code's only one), converted to
//! and from byte offsets through a line index.

/// How columns are counted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Encoding {
    /// Bytes of UTF-8.
    Utf8,
    /// Code units of UTF-16 (a character outside the Basic Multilingual
    /// Plane counts 2).
    Utf16,
}

/// The byte offset where each line of a text starts.
#[derive(Debug, Clone)]
pub struct LineIndex {
    starts: Vec<usize>,
    len: usize,
}

impl LineIndex {
    /// The index of `text` (a line ends after `\n`; `\r\n` is one end).
    pub fn new(text: &str) -> LineIndex {
        let mut starts = vec![0];
        starts.extend(
            text.bytes()
                .enumerate()
                .filter(|(_, b)| *b == b'\n')
                .map(|(i, _)| i + 1),
        );
        LineIndex {
            starts,
            len: text.len(),
        }
    }

    /// The line and column of byte `offset` (clamped to the text, and back
    /// to a character boundary).
    pub fn position(&self, text: &str, offset: usize, encoding: Encoding) -> (u32, u32) {
        let mut offset = offset.min(self.len);
        while !text.is_char_boundary(offset) {
            offset -= 1;
        }
        let line = self.starts.partition_point(|&s| s <= offset) - 1;
        let column = &text[self.starts[line]..offset];
        let column = match encoding {
            Encoding::Utf8 => column.len(),
            Encoding::Utf16 => column.chars().map(char::len_utf16).sum(),
        };
        (line as u32, column as u32)
    }

    /// The byte offset of `line` and `column`: a line past the end is the
    /// end of the text, a column past the line's end is its end (before
    /// `\r\n`), a column inside a character is that character's start.
    pub fn offset(&self, text: &str, line: u32, column: u32, encoding: Encoding) -> usize {
        let Some(&start) = self.starts.get(line as usize) else {
            return self.len;
        };
        let end = self.starts.get(line as usize + 1).map_or(self.len, |&e| e);
        let line_text = text[start..end].trim_end_matches(['\n', '\r']);
        let mut counted = 0usize;
        for (i, c) in line_text.char_indices() {
            let width = match encoding {
                Encoding::Utf8 => c.len_utf8(),
                Encoding::Utf16 => c.len_utf16(),
            };
            if counted + width > column as usize {
                return start + i;
            }
            counted += width;
        }
        start + line_text.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn columns_count_bytes_or_utf16_units() {
        // é: 2 bytes, 1 unit; 𝄞 (U+1D11E): 4 bytes, 2 units.
        let text = "let é = 1;\r\nx𝄞y\n";
        let index = LineIndex::new(text);
        let y = text.find('y').unwrap();
        assert_eq!(index.position(text, y, Encoding::Utf8), (1, 5));
        assert_eq!(index.position(text, y, Encoding::Utf16), (1, 3));
        assert_eq!(index.offset(text, 1, 5, Encoding::Utf8), y);
        assert_eq!(index.offset(text, 1, 3, Encoding::Utf16), y);
        // Inside 𝄞: back to its start.
        assert_eq!(index.offset(text, 1, 2, Encoding::Utf16), y - 4);
        assert_eq!(index.position(text, y - 2, Encoding::Utf8), (1, 1));
        // Past the line's end, past the last line.
        assert_eq!(
            index.offset(text, 0, 99, Encoding::Utf16),
            text.find('\r').unwrap()
        );
        assert_eq!(index.offset(text, 9, 0, Encoding::Utf8), text.len());
        assert_eq!(index.position(text, 999, Encoding::Utf16), (2, 0));
    }

    proptest::proptest! {
        #[test]
        fn every_boundary_round_trips(text in "(a|é|𝄞|\n|\r\n| ){0,40}") {
            let index = LineIndex::new(&text);
            for (offset, _) in text.char_indices().chain([(text.len(), ' ')]) {
                if offset > 0 && text.as_bytes()[offset - 1] == b'\r' {
                    continue; // between \r and \n: not a position a client names
                }
                for encoding in [Encoding::Utf8, Encoding::Utf16] {
                    let (line, column) = index.position(&text, offset, encoding);
                    proptest::prop_assert_eq!(index.offset(&text, line, column, encoding), offset);
                }
            }
        }
    }
}
