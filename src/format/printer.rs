//! The output being written: indentation, spaces between tokens, and the
//! comments of the source, each written once, in order, where the tokens
//! around it put it.
//!
//! Every token written with a source position first writes the comments
//! that start before that position (inside a line: a `//` comment ends the
//! line, and the next line is a continuation, one level deeper). Lists
//! (statements, a broken block's entries) place them on lines of their
//! own: before an item (leading), after it on its line (trailing), or at
//! the end of the list (dangling).

use super::scan::{blank_between, Comment};

/// Columns a line should not go past: a block that would is broken.
pub(super) const WIDTH: usize = 100;

/// Spaces per level of indentation.
pub(super) const INDENT: usize = 4;

/// The formatter's output and where it stands in the source.
pub(super) struct Printer<'t> {
    /// The source text.
    pub text: &'t str,
    /// Its comments, in order.
    comments: Vec<Comment>,
    /// The first comment not written yet.
    next: usize,
    /// What is written so far.
    out: String,
    /// The current level of indentation.
    pub indent: usize,
    /// A space is due before the next token.
    space: bool,
    /// Nothing is written on the current line yet.
    line_start: bool,
    /// The current line continues a statement after a `//` comment.
    continued: bool,
    /// Where in the source the last item or comment of a list ended.
    pub last_end: usize,
}

impl<'t> Printer<'t> {
    /// A printer of `text`, whose comments are `comments`.
    pub fn new(text: &'t str, comments: Vec<Comment>) -> Printer<'t> {
        Printer {
            text,
            comments,
            next: 0,
            out: String::new(),
            indent: 0,
            space: false,
            line_start: true,
            continued: false,
            last_end: 0,
        }
    }

    /// The text written, ending in one line end (none when empty).
    pub fn finish(mut self) -> String {
        self.end_line();
        while self.out.ends_with("\n\n") {
            self.out.pop();
        }
        if self.out.trim().is_empty() {
            self.out.clear();
        }
        self.out
    }

    /// Writes `s` after the indentation or the space due.
    pub fn write(&mut self, s: &str) {
        if self.line_start {
            let levels = self.indent + usize::from(self.continued);
            self.out.push_str(&" ".repeat(levels * INDENT));
        } else if self.space {
            self.out.push(' ');
        }
        self.out.push_str(s);
        self.line_start = false;
        self.space = false;
    }

    /// A space before the next token.
    pub fn space(&mut self) {
        self.space = true;
    }

    /// Writes the comments before `pos`, then `s`.
    pub fn token(&mut self, pos: usize, s: &str) {
        self.comments_before(pos);
        self.write(s);
    }

    /// Ends the current line (if anything is on it).
    pub fn end_line(&mut self) {
        if !self.line_start {
            let kept = self.out.trim_end_matches(' ').len();
            self.out.truncate(kept);
            self.out.push('\n');
        }
        self.line_start = true;
        self.space = false;
        self.continued = false;
    }

    /// An empty line before the next one (one at most).
    pub fn blank_line(&mut self) {
        self.end_line();
        if !self.out.is_empty() && !self.out.ends_with("\n\n") {
            self.out.push('\n');
        }
    }

    /// The column the next token would start at.
    pub fn column(&self) -> usize {
        if self.line_start {
            (self.indent + usize::from(self.continued)) * INDENT
        } else {
            let line = self.out.rsplit('\n').next().unwrap_or("");
            line.chars().count() + usize::from(self.space)
        }
    }

    /// Where the item spanning `start..end` really ends: a parse's span
    /// may take in the blanks and comments that follow it (pest's search
    /// for one more repetition skips them), which are not the item's.
    pub fn code_end(&self, start: usize, end: usize) -> usize {
        let mut end = end;
        loop {
            end = start + self.text[start..end].trim_end().len();
            let inside = self
                .comments
                .iter()
                .rev()
                .find(|c| c.start < end && end <= c.end);
            match inside {
                Some(c) if c.start >= start => end = c.start,
                _ => return end,
            }
        }
    }

    /// Whether a comment not written yet starts before `end`.
    pub fn comment_before(&self, end: usize) -> bool {
        self.comments.get(self.next).is_some_and(|c| c.start < end)
    }

    /// The next comment not written yet if it starts before `end`.
    fn take_before(&mut self, end: usize) -> Option<Comment> {
        let c = *self.comments.get(self.next)?;
        (c.start < end).then(|| {
            self.next += 1;
            c
        })
    }

    /// Writes the comments before `pos` inside the current line.
    pub fn comments_before(&mut self, pos: usize) {
        while let Some(c) = self.take_before(pos) {
            if !self.line_start {
                self.space = true;
            }
            let continued = self.continued;
            self.write(c.text(self.text));
            if c.is_line(self.text) {
                self.end_line();
                self.continued = true;
            } else {
                self.continued = continued;
                self.space = true;
            }
            self.last_end = self.last_end.max(c.end);
        }
    }

    /// Writes the comments before `pos` on lines of their own, the first
    /// item of a list when `first`, with an empty line where the source has
    /// one between them (not at the list's start), and one before `pos` too.
    pub fn leading(&mut self, pos: usize, first: bool) {
        let first = self.dangling(pos, first);
        if !first && blank_between(self.text, self.last_end, pos) {
            self.blank_line();
        }
    }

    /// Writes the comments before `end` (a list's end) on lines of their
    /// own, as [`Printer::leading`] does; returns whether the list is still
    /// empty.
    pub fn dangling(&mut self, end: usize, first: bool) -> bool {
        let mut first = first;
        while let Some(c) = self.take_before(end) {
            self.end_line();
            if !first && blank_between(self.text, self.last_end, c.start) {
                self.blank_line();
            }
            self.write(c.text(self.text));
            self.end_line();
            self.last_end = c.end;
            first = false;
        }
        first
    }

    /// Writes the comments before `limit` that are on the line of the
    /// item that ended at `end` (or inside it), at the end of that line.
    pub fn trailing(&mut self, end: usize, limit: usize) {
        self.last_end = self.last_end.max(end);
        while let Some(c) = self.comments.get(self.next).copied() {
            let same_line =
                c.start < self.last_end || !self.text[self.last_end..c.start].contains('\n');
            if c.start >= limit || !same_line {
                break;
            }
            self.next += 1;
            self.space = true;
            self.write(c.text(self.text));
            self.last_end = self.last_end.max(c.end);
            if c.is_line(self.text) {
                // Nothing more on this line: it is the comment's.
                break;
            }
        }
    }
}
