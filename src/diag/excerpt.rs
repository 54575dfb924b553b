//! The part of a file a diagnostic shows: the lines of its labels with one
//! line of context, each line cut to a window around the labels when it is
//! long. miette draws from the excerpt instead of the whole file, so drawing
//! costs the size of the excerpt (not of the file before the label), and no
//! label sits past the column miette's padding can reach (65,535).

use crate::source::SourceFile;
use miette::{MietteError, MietteSpanContents, SourceCode, SourceSpan, SpanContents};
use std::ops::Range;

/// A line longer than this (in bytes) is cut to windows around its labels.
const MAX_LINE: usize = 200;
/// Bytes kept on each side of a label's start or end in a cut line.
const WINDOW: usize = 60;
/// A label over more lines than this is shown on its first line only.
const MAX_LABEL_LINES: usize = 8;
/// Stands for the text left out of a cut line.
const ELLIPSIS: &str = "…";

/// Lines of one file, cut to size, with their true line numbers.
#[derive(Debug)]
pub struct Excerpt {
    name: String,
    text: String,
    lines: Vec<ExcerptLine>,
}

/// One line of the file in the excerpt.
#[derive(Debug)]
struct ExcerptLine {
    /// Where the line starts in the excerpt's text.
    start: usize,
    /// Its 0-based number in the file.
    line: usize,
    /// Where it starts in the file.
    file_start: usize,
    /// The parts of the line kept: their range in the file and where each
    /// starts in the excerpt's text.
    pieces: Vec<(Range<usize>, usize)>,
}

impl Excerpt {
    /// The excerpt of `file` for labels over `spans` (start and end bytes in
    /// the file, in any state: out of range, reversed, inside a character)
    /// and the spans moved into the excerpt.
    pub fn new(
        name: String,
        file: &SourceFile,
        spans: &[(usize, usize)],
    ) -> (Excerpt, Vec<SourceSpan>) {
        let last_line = file.line_starts().len() - 1;
        // Clean spans and the lines each one covers.
        let spans: Vec<(Range<usize>, usize, usize)> = spans
            .iter()
            .map(|&(start, end)| {
                let start = file.floor_char_boundary(start);
                let mut end = file.floor_char_boundary(end.max(start));
                let first = file.line_of(start);
                let mut last = file.line_of(end.saturating_sub(1).max(start));
                if last - first > MAX_LABEL_LINES {
                    end = file.line_range(first).end.max(start);
                    last = first;
                }
                (start..end, first, last)
            })
            .collect();
        // The lines to show: each label's, one before and one after.
        let mut wanted: Vec<usize> = spans
            .iter()
            .flat_map(|(_, first, last)| first.saturating_sub(1)..=(last + 1).min(last_line))
            .collect();
        wanted.sort_unstable();
        wanted.dedup();
        let mut excerpt = Excerpt {
            name,
            text: String::new(),
            lines: Vec::with_capacity(wanted.len()),
        };
        for line in wanted {
            let range = file.line_range(line);
            let points: Vec<usize> = spans
                .iter()
                .flat_map(|(s, _, _)| [s.start, s.end])
                .filter(|p| range.contains(p) || *p == range.end)
                .collect();
            excerpt.push_line(file, line, range, &points, line < last_line);
        }
        let mapped = spans
            .iter()
            .map(|(s, _, _)| {
                let start = excerpt.map(file, s.start);
                let end = excerpt.map(file, s.end).max(start);
                SourceSpan::from((start, end - start))
            })
            .collect();
        (excerpt, mapped)
    }

    /// Appends line `line` of `file`, cut to windows around `points` when long.
    fn push_line(
        &mut self,
        file: &SourceFile,
        line: usize,
        range: Range<usize>,
        points: &[usize],
        line_break: bool,
    ) {
        let windows = if range.len() <= MAX_LINE {
            vec![range.clone()]
        } else {
            let mut windows: Vec<Range<usize>> = points
                .iter()
                .map(|&p| {
                    let lo = file.floor_char_boundary(p.saturating_sub(WINDOW).max(range.start));
                    let hi = file.floor_char_boundary((p + WINDOW).min(range.end)).max(p);
                    lo..hi
                })
                .collect();
            if windows.is_empty() {
                let hi = file.floor_char_boundary(range.start + 2 * WINDOW);
                windows.push(range.start..hi);
            }
            windows.sort_unstable_by_key(|w| w.start);
            let mut merged: Vec<Range<usize>> = Vec::with_capacity(windows.len());
            for w in windows {
                match merged.last_mut() {
                    Some(m) if w.start <= m.end + ELLIPSIS.len() + 2 => m.end = m.end.max(w.end),
                    _ => merged.push(w),
                }
            }
            merged
        };
        let start = self.text.len();
        let mut pieces = Vec::with_capacity(windows.len());
        for (k, w) in windows.iter().enumerate() {
            if k == 0 && w.start > range.start {
                self.text.push_str(ELLIPSIS);
            }
            if k > 0 {
                self.text.push(' ');
                self.text.push_str(ELLIPSIS);
                self.text.push(' ');
            }
            pieces.push((w.clone(), self.text.len()));
            push_printable(&mut self.text, &file.text[w.clone()]);
        }
        if windows.last().is_some_and(|w| w.end < range.end) {
            self.text.push_str(ELLIPSIS);
        }
        if line_break {
            self.text.push('\n');
        }
        self.lines.push(ExcerptLine {
            start,
            line,
            file_start: range.start,
            pieces,
        });
    }

    /// Where byte `offset` of the file (a label's end) is in the excerpt.
    fn map(&self, file: &SourceFile, offset: usize) -> usize {
        let line = file.line_of(offset);
        let Ok(i) = self.lines.binary_search_by_key(&line, |l| l.line) else {
            return self.text.len();
        };
        let l = &self.lines[i];
        for (range, at) in &l.pieces {
            if range.start <= offset && offset <= range.end {
                return at + (offset - range.start);
            }
        }
        // Between two pieces (cannot happen for label ends): the next piece.
        l.pieces
            .iter()
            .find(|(range, _)| range.start > offset)
            .or(l.pieces.last())
            .map_or(l.start, |(_, at)| *at)
    }

    /// The 0-based column (in characters) in the file of excerpt offset `at`.
    fn file_column(&self, file_text: &str, at: usize) -> usize {
        let i = self
            .lines
            .partition_point(|l| l.start <= at)
            .saturating_sub(1);
        let l = &self.lines[i];
        let offset = l
            .pieces
            .iter()
            .rev()
            .find(|(_, start)| *start <= at)
            .map_or(l.file_start, |(range, start)| {
                (range.start + (at - start)).min(range.end)
            });
        file_text
            .get(l.file_start..offset)
            .map_or(0, |s| s.chars().count())
    }
}

/// An excerpt with the file text it came from, as miette reads it.
#[derive(Debug)]
pub struct ExcerptSource {
    /// The excerpt.
    pub excerpt: Excerpt,
    /// The whole file's text (for columns only).
    pub file_text: std::sync::Arc<String>,
}

impl SourceCode for ExcerptSource {
    fn read_span<'a>(
        &'a self,
        span: &SourceSpan,
        context_lines_before: usize,
        context_lines_after: usize,
    ) -> Result<Box<dyn SpanContents<'a> + 'a>, MietteError> {
        let e = &self.excerpt;
        let inner = e
            .text
            .as_str()
            .read_span(span, context_lines_before, context_lines_after)?;
        let data_start = inner.span().offset();
        let i = e
            .lines
            .partition_point(|l| l.start <= data_start)
            .saturating_sub(1);
        let line = e.lines.get(i).map_or(0, |l| l.line);
        // miette asks for a column only without context (the header's
        // `file:line:column`): the file's, not the excerpt's.
        let column = if context_lines_before == 0 && !e.lines.is_empty() {
            e.file_column(&self.file_text, span.offset())
        } else {
            0
        };
        let data = inner.data();
        let line_count = data.iter().filter(|&&b| b == b'\n').count();
        Ok(Box::new(MietteSpanContents::new_named(
            e.name.clone(),
            data,
            *inner.span(),
            line,
            column,
            line_count,
        )))
    }
}

/// Appends `piece` with each control character but the tab as `?`s of its
/// length in bytes (so offsets into the excerpt stay right): an escape or a
/// bell in a scene's bytes must not reach the terminal.
fn push_printable(out: &mut String, piece: &str) {
    for c in piece.chars() {
        match c {
            '\t' => out.push(c),
            '\r' => out.push(' '),
            c if c.is_control() => out.extend(std::iter::repeat_n('?', c.len_utf8())),
            c => out.push(c),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn file(text: &str) -> SourceFile {
        SourceFile::new("t.pts", text.to_string())
    }

    #[test]
    fn short_lines_are_kept_whole_with_one_line_of_context() {
        let f = file("a\nbb\ncc x\ndd\nee\n");
        let (e, spans) = Excerpt::new("t".into(), &f, &[(8, 9)]);
        assert_eq!(e.text, "bb\ncc x\ndd\n");
        assert_eq!(
            e.lines.iter().map(|l| l.line).collect::<Vec<_>>(),
            vec![1, 2, 3]
        );
        assert_eq!(&e.text[spans[0].offset()..][..1], "x");
    }

    #[test]
    fn a_long_line_is_cut_around_each_label() {
        let text = format!(
            "{}AAA{}BBB{}",
            "x".repeat(100_000),
            "y".repeat(100_000),
            "z".repeat(50)
        );
        let f = file(&text);
        let a = (100_000, 100_003);
        let b = (200_003, 200_006);
        let (e, spans) = Excerpt::new("t".into(), &f, &[a, b]);
        assert!(e.text.len() < 400, "{}", e.text.len());
        assert!(e.text.starts_with(ELLIPSIS));
        let at = |s: &SourceSpan| &e.text[s.offset()..s.offset() + s.len()];
        assert_eq!(at(&spans[0]), "AAA");
        assert_eq!(at(&spans[1]), "BBB");
        // Columns are the file's.
        let src = ExcerptSource {
            excerpt: e,
            file_text: f.text.clone(),
        };
        let c = src.read_span(&spans[1], 0, 0).unwrap();
        assert_eq!(c.column(), 200_003);
        assert_eq!(c.line(), 0);
    }

    #[test]
    fn labels_in_any_state_are_clamped() {
        let f = file("é\nab");
        for span in [(0, 1), (5, 3), (100, 200), (1, 1), (0, 100)] {
            let (e, spans) = Excerpt::new("t".into(), &f, &[span]);
            for s in spans {
                assert!(s.offset() + s.len() <= e.text.len());
                assert!(e.text.is_char_boundary(s.offset()));
            }
        }
    }

    #[test]
    fn a_label_over_many_lines_keeps_its_first() {
        let text = "x\n".repeat(1000);
        let f = file(&text);
        let (e, spans) = Excerpt::new("t".into(), &f, &[(0, text.len())]);
        assert_eq!(e.lines.len(), 2);
        assert_eq!(spans[0].len(), 1);
    }

    #[test]
    fn far_apart_labels_keep_their_line_numbers() {
        let text = (0..10_000)
            .map(|i| format!("line {i}\n"))
            .collect::<String>();
        let f = file(&text);
        let far = f.line_starts()[9000] as usize;
        let (e, spans) = Excerpt::new("t".into(), &f, &[(0, 4), (far, far + 4)]);
        let src = ExcerptSource {
            excerpt: e,
            file_text: f.text.clone(),
        };
        let c = src.read_span(&spans[1], 1, 1).unwrap();
        assert_eq!(c.line(), 8999);
        assert_eq!(
            std::str::from_utf8(c.data()).unwrap(),
            "line 8999\nline 9000\nline 9001\n"
        );
    }
}
