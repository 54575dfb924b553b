//! Reading on after a syntax error: a statement that does not parse is
//! skipped to where the next one plausibly starts ([`resume_after`]) and
//! reading goes on there, so that a file with a mistake still yields the
//! statements before and after it.
//!
//! Here statements are read one at a time, each from a window of the text
//! rather than from the rest of the file: pest walks its whole input to
//! build an error (for the failing line and column), so a failure costs the
//! length of what pest was given, and a file of many broken statements would
//! cost quadratic time. A window ends where no token crosses, and is widened
//! until the outcome cannot depend on where it ended ([`Reader::next`]), so
//! what is read from a place never depends on where the file was cut into
//! parse pieces.

use super::build::Builder;
use super::parser::{PtsParser, Rule};
use super::scan::statement_follows;
use super::words::statement_word;
use crate::diag::Diagnostic;
use crate::source::FileId;
use pest::iterators::Pair;
use pest::Parser;

/// The statements read from a stretch of a file (a parse piece), and its
/// broken statements.
pub(super) struct Parsed {
    /// The first byte of the stretch.
    pub start: usize,
    /// One past its last byte.
    pub end: usize,
    /// The statements that parsed, in file order.
    pub statements: Vec<super::ast::Statement>,
    /// The statements that did not, in file order.
    pub breaks: Vec<Break>,
    /// Where the statement after the stretch starts (at or past `end`);
    /// `None` when a broken statement runs to the end of the file, or
    /// reading stopped at the first error.
    pub next: Option<usize>,
}

/// A statement that does not parse, or declares a reserved word.
pub(super) struct Break {
    /// How many statements of its stretch come before it (without the
    /// statement of a reserved word, or a `let` whose `;` is missing).
    pub kept: usize,
    /// Where it starts.
    pub at: usize,
    /// The end of a window in which pest fails on it as on the whole text:
    /// its diagnostic is made from a parse up to there.
    pub seen: usize,
    /// Where reading resumes after it; `None` when it runs to the end.
    pub resume: Option<usize>,
    /// The builder's diagnostic of a reserved word used as a name; `None`
    /// for a syntax error.
    pub reserved: Option<Diagnostic>,
}

/// Reads statements from byte `from` one at a time until `to` or past it:
/// a parse piece that failed as a whole (`to` is its end), or the rest of
/// one that a broken statement before it ran into. Stops at the `limit`th
/// broken statement.
pub(super) fn parse_from(
    file: FileId,
    (text, kinds): (&str, &[&str]),
    from: usize,
    to: usize,
    limit: usize,
) -> Parsed {
    let builder = Builder::new(file, text, kinds, 0);
    let mut parsed = Parsed {
        start: from,
        end: to,
        statements: Vec::new(),
        breaks: Vec::new(),
        next: None,
    };
    let mut reader = Reader {
        text,
        hard: 0,
        soft: 0,
    };
    let mut pos = from;
    while pos < to {
        let (kept, at, seen, resume, reserved) = match reader.next(pos) {
            Next::End => {
                pos = text.len();
                break;
            }
            Next::Statement(pair, end) => {
                let Some(pair) = pair else {
                    pos = end;
                    continue;
                };
                builder.base.set(pos);
                let at = pos + pair.as_span().start();
                // A directive's line may hold brackets that do not pair:
                // the boundary found past it no longer holds.
                if pair.as_rule() == Rule::directive_stmt {
                    reader.forget();
                }
                let statement = builder.build_statement(pair);
                pos = end;
                let reserved = builder.reserved.take();
                let kept = parsed.statements.len();
                // A reserved word as a name is reported, but the statement
                // is kept, so that its uses raise no second error.
                parsed.statements.push(statement);
                match reserved {
                    None => continue,
                    Some(d) => (kept, at, end, Some(end), Some(d)),
                }
            }
            Next::Broken { at, error, seen } => {
                let resume = resume_after(text, at, error);
                // A statement starts where pest failed: the `;` before it
                // may be all that is missing.
                if let Some(pair) = unended(text, at, error).filter(|_| resume == Some(error)) {
                    builder.base.set(at);
                    parsed.statements.push(builder.build_statement(pair));
                    builder.reserved.take();
                }
                (parsed.statements.len(), at, seen, resume, None)
            }
        };
        parsed.breaks.push(Break {
            kept,
            at,
            seen,
            resume,
            reserved,
        });
        match resume {
            Some(r) if parsed.breaks.len() < limit => pos = r,
            _ => return parsed,
        }
    }
    parsed.next = Some(pos);
    parsed
}

/// The `let` or `fn` at `at` that pest could not parse past `error`, if
/// it is whole but its `;` (`let r = 1` and a new line): built as the
/// statement it would be with it, its name is still defined.
fn unended(text: &str, at: usize, error: usize) -> Option<Pair<'_, Rule>> {
    // Without the blanks before the error, which pest's span would take in.
    let head = text[at..error].trim_end();
    if !(head.starts_with("let") || head.starts_with("fn")) {
        return None;
    }
    let mut pairs = PtsParser::parse(Rule::unended, head).ok()?;
    pairs.next()?.into_inner().next()
}

/// What [`Reader::next`] found.
enum Next<'t> {
    /// A statement (its pair, counted from where reading started) and the
    /// byte after it.
    Statement(Option<Pair<'t, Rule>>, usize),
    /// Nothing but blanks and comments up to the end of the file.
    End,
    /// No statement parses from `at` (where it starts, after blanks); pest
    /// failed at `error`, in the window that ends at `seen`.
    Broken {
        at: usize,
        error: usize,
        seen: usize,
    },
}

/// The least window a statement is first read in, when no hard boundary
/// comes sooner: most statements fit, and a failure costs no more.
const WINDOW: usize = 256;

/// Reads statements one at a time, each in a window of the text.
struct Reader<'t> {
    text: &'t str,
    /// The first hard boundary ([`hard_boundary`]) after the statements
    /// read so far, or 0 when it is to be found again. A statement that
    /// parsed and a skipped broken one leave no bracket open, so the
    /// boundary found from an earlier place holds for the later ones: each
    /// byte is scanned for it once, however many statements precede it.
    hard: usize,
    /// A soft point ([`soft_point`]) found from an earlier place, or 0; it
    /// holds for the later ones as `hard` does. Found two [`WINDOW`]s
    /// ahead, it serves the statements of the next window (finding one for
    /// every short statement would scan each byte many times).
    soft: usize,
}

impl<'t> Reader<'t> {
    /// Forgets the boundaries found: the statement just read may have left
    /// a bracket open.
    fn forget(&mut self) {
        self.hard = 0;
        self.soft = 0;
    }

    /// The statement at `pos`. Its window first ends at the hard boundary
    /// after `pos`, if that is near, else at a soft one ([`soft_point`]).
    /// pest's answer in a window is the answer in the whole text when it
    /// failed before the window's end (no rule looked past it), or parsed a
    /// statement that ended before a hard boundary (no statement goes on
    /// past one) or before a token that cannot go on with it
    /// ([`settled`]). Else the window grows fourfold and pest runs again:
    /// the failures cost at most a few times the last window.
    fn next(&mut self, pos: usize) -> Next<'t> {
        let text = self.text;
        if self.hard <= pos {
            self.hard = hard_boundary(text, pos);
            self.soft = 0;
        }
        let mut lim = if self.hard - pos <= WINDOW {
            self.hard
        } else {
            if !(pos + WINDOW..=pos + 3 * WINDOW).contains(&self.soft) {
                self.soft = soft_point(text, pos, pos + 2 * WINDOW);
            }
            self.soft.min(self.hard)
        };
        loop {
            let window = &text[pos..lim];
            let whole = lim == text.len();
            match PtsParser::parse(Rule::next_statement, window) {
                Ok(mut pairs) => {
                    let pair = pairs.next().expect("next_statement matched");
                    let end = pos + pair.as_span().end();
                    if whole || lim >= self.hard || settled(text, end, lim) {
                        return Next::Statement(pair.into_inner().next(), end);
                    }
                }
                Err(e) => {
                    let error = pos + error_position(&e);
                    if whole || error < lim {
                        // Where the statement starts: after the blanks
                        // before the error (only those are read).
                        let at = match PtsParser::parse(Rule::only_blanks, &text[pos..error]) {
                            Ok(_) => error,
                            Err(b) => pos + error_position(&b),
                        };
                        if at == text.len() {
                            return Next::End;
                        }
                        return Next::Broken {
                            at,
                            error,
                            seen: lim,
                        };
                    }
                }
            }
            lim = soft_point(text, pos, pos + 4 * (lim - pos).max(WINDOW));
        }
    }
}

/// Where pest failed, counted from the start of its input.
pub(super) fn error_position(e: &pest::error::Error<Rule>) -> usize {
    match e.location {
        pest::error::InputLocation::Pos(p) => p,
        pest::error::InputLocation::Span((s, _)) => s,
    }
}

/// Where parsing resumes after the statement at `at` that pest could not
/// parse past `error`: the end of the broken statement, as best the
/// brackets tell it. Counting `(`, `[` and `{` from `at`, the first of:
/// - `error` itself, when a statement keyword other than `if` stands there
///   outside brackets: the statement before it lacks its end
///   (`let a = 1 sphere { … }`, a `;` missing);
/// - the start of a line after `error`, outside brackets, that opens with a
///   statement keyword (or a `#` directive): what follows a `let` whose `;`
///   is missing, a stray word, a half-written statement;
/// - just after a `;`, or a `}` followed by a statement (not `else`), at or
///   after `error`, that leaves no bracket open: the end of the statement
///   with a mistake inside its blocks (a stray token, a misspelt word, a
///   bracket left open inside a block: a `}` closes every `(` and `[` of
///   its block, a `;` those of its statement).
///
/// A string without its closing quote counts as a stray quote, so that the
/// `}` after it on its line still closes its block. `None` when nothing
/// qualifies: a `{` never closed, or a comment never closed, runs to the end
/// of the file, and nothing follows it.
pub(super) fn resume_after(text: &str, at: usize, error: usize) -> Option<usize> {
    if let Some(rest) = text[error..].strip_prefix("/*") {
        if !rest.contains("*/") {
            return None;
        }
    }
    let mut nest = Nest::default();
    walk(text, at, |i, b| {
        if i >= error {
            return false;
        }
        nest.take(b);
        true
    });
    if error > at && nest.is_empty() && opens_statement(text, error, false) {
        return Some(error);
    }
    let mut found = None;
    walk(text, error, |i, b| {
        match b {
            b'\n' if nest.is_empty() => {
                let line = &text[i + 1..];
                let start = i + 1 + (line.len() - line.trim_start_matches([' ', '\t']).len());
                if opens_statement(text, start, true) {
                    found = Some(start);
                }
            }
            b' ' | b'\t' | b'\r' | b'\n' => {}
            _ => {
                nest.take(b);
                if nest.is_empty()
                    && (b == b';' || (b == b'}' && statement_follows(&text[i + 1..])))
                {
                    found = Some(i + 1);
                }
            }
        }
        found.is_none()
    });
    found
}

/// Whether a statement starts at `at`: a statement word
/// ([`statement_word`]), or at the start of a line `if` and a `#` directive too (in the middle of a line,
/// `if` may well be a value's).
fn opens_statement(text: &str, at: usize, line_start: bool) -> bool {
    let rest = &text[at..];
    if line_start
        && rest.starts_with('#')
        && rest[1..].starts_with(|c: char| c.is_ascii_alphabetic())
    {
        return true;
    }
    statement_word(text, at).is_some_and(|word| line_start || word != "if")
}

/// The first hard boundary after `pos`: just after a `;`, or a `}` followed
/// by a statement, that leaves no bracket opened after `pos` open (or the
/// end of the text). No statement goes on past one: a `let` or `fn` ends at
/// its `;`, and after a block's `}` only `else` or an operator could go on.
/// (A POV-Ray directive's line may, but it is not ptsc: its statement is
/// read up to there.)
fn hard_boundary(text: &str, pos: usize) -> usize {
    let mut nest = Nest::default();
    let mut found = text.len();
    walk(text, pos, |i, b| {
        nest.take(b);
        if nest.is_empty() && (b == b';' || (b == b'}' && statement_follows(&text[i + 1..]))) {
            found = i + 1;
            return false;
        }
        true
    });
    found
}

/// The first place at or after `min` just after a blank outside comments,
/// strings and brackets opened after `pos` (or the end of the text). No
/// token crosses it (a blank inside brackets could be inside a lookahead
/// such as a flag's, which pest does not count as an attempt).
fn soft_point(text: &str, pos: usize, min: usize) -> usize {
    let mut nest = Nest::default();
    let mut found = text.len();
    walk(text, pos, |i, b| {
        if matches!(b, b' ' | b'\t' | b'\r' | b'\n') {
            if i + 1 >= min && nest.is_empty() {
                found = i + 1;
                return false;
            }
        } else {
            nest.take(b);
        }
        true
    });
    found
}

/// Whether a statement that parsed up to `end` in a window ending at `lim`
/// ends there in the whole text too: the token after it lies in the window
/// and nothing goes on with it (a word other than `else`, a digit, a
/// quote, a `#`, a brace, `;`, `,`, `)` or `]`; not an operator, `.`, `[`
/// or `(`, nor anything unusual).
fn settled(text: &str, end: usize, lim: usize) -> bool {
    let t = skip_blanks(text, end);
    if t >= lim {
        return false;
    }
    let rest = &text[t..];
    let c = rest.as_bytes()[0];
    if c.is_ascii_alphabetic() || c == b'_' {
        let len = rest
            .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
            .unwrap_or(rest.len());
        return &rest[..len] != "else";
    }
    c.is_ascii_digit() || matches!(c, b'"' | b'#' | b'{' | b'}' | b';' | b',' | b')' | b']')
}

/// The first byte at or after `from` that is not an ASCII blank or inside a
/// closed comment. (pest skips a few more blanks; where it would skip one
/// of those, [`settled`] sees an unusual character and says no.)
fn skip_blanks(text: &str, from: usize) -> usize {
    let bytes = text.as_bytes();
    let mut i = from;
    loop {
        match bytes.get(i) {
            Some(b' ' | b'\t' | b'\n' | b'\r' | b'\x0B' | b'\x0C') => i += 1,
            Some(b'/') if bytes.get(i + 1) == Some(&b'/') => {
                i = text[i..].find('\n').map_or(text.len(), |k| i + k);
            }
            Some(b'/') if bytes.get(i + 1) == Some(&b'*') => match text[i + 2..].find("*/") {
                Some(k) => i += k + 4,
                None => return i,
            },
            _ => return i,
        }
    }
}

/// The brackets open in a scan, innermost last: `(`, `[` and `{` only (a
/// `<` may be a comparison). A closing bracket that does not match the
/// innermost is a stray one and ignored; a `}` closes its `{` and every
/// bracket left open inside it, a `;` every `(` and `[` since the last `{`.
#[derive(Default)]
struct Nest {
    open: Vec<u8>,
    /// How many of `open` are `{`: a `}` with none open costs nothing.
    braces: usize,
}

impl Nest {
    /// Takes a bracket or `;` (other bytes change nothing).
    fn take(&mut self, b: u8) {
        let open = &mut self.open;
        match b {
            b'(' | b'[' | b'{' => {
                open.push(b);
                self.braces += usize::from(b == b'{');
            }
            b')' | b']' if open.last() == Some(&if b == b')' { b'(' } else { b'[' }) => {
                open.pop();
            }
            b'}' if self.braces > 0 => {
                let k = open
                    .iter()
                    .rposition(|&o| o == b'{')
                    .expect("a `{` is open");
                open.truncate(k);
                self.braces -= 1;
            }
            b';' => {
                let k = open.iter().rposition(|&o| o == b'{').map_or(0, |k| k + 1);
                open.truncate(k);
            }
            _ => {}
        }
    }

    fn is_empty(&self) -> bool {
        self.open.is_empty()
    }
}

/// Calls `f(offset, byte)` from byte `from` on for every bracket (`(`, `)`,
/// `[`, `]`, `{`, `}`), `;` and ASCII blank outside comments and strings,
/// until `f` returns `false`. Unlike [`super::scan::for_each_code_mark`] (the
/// scan of whole files), it reads as pest does where a file is broken: a
/// `"` whose string does not close on its line, or a `/*` that never
/// closes, is one stray character, and what follows it is code.
fn walk(text: &str, from: usize, mut f: impl FnMut(usize, u8) -> bool) {
    let bytes = text.as_bytes();
    // Every quote before this offset opens no closed string: a string
    // found open at the end of a line makes the quotes after it on that
    // line stray too (scanning each to the line's end would be quadratic).
    let mut stray_until = 0;
    // A `/*` at or after this offset never closes (nor did an earlier one).
    let mut unclosed_from = usize::MAX;
    let mut i = from;
    while i < bytes.len() {
        let b = bytes[i];
        match b {
            b'/' if bytes.get(i + 1) == Some(&b'/') => {
                i = text[i..].find('\n').map_or(text.len(), |k| i + k);
                continue;
            }
            b'/' if bytes.get(i + 1) == Some(&b'*') && i < unclosed_from => {
                match text[i + 2..].find("*/") {
                    Some(k) => {
                        i += k + 4;
                        continue;
                    }
                    None => unclosed_from = i,
                }
            }
            b'"' if i >= stray_until => {
                let mut j = i + 1;
                while j < bytes.len() && bytes[j] != b'"' && bytes[j] != b'\n' {
                    j += if bytes[j] == b'\\' { 2 } else { 1 };
                }
                if bytes.get(j) == Some(&b'"') {
                    i = j + 1;
                    continue;
                }
                stray_until = j;
            }
            b'(' | b')' | b'[' | b']' | b'{' | b'}' | b';' | b' ' | b'\t' | b'\r' | b'\n'
                if !f(i, b) =>
            {
                return;
            }
            _ => {}
        }
        i += 1;
    }
}
