//! Diagnostics: what ptsc tells the user about a scene. Each is data (a code,
//! a message, a labelled span, a help line), collected for the whole run and
//! rendered at the end by miette (human) or as JSON (editors, CI).

pub mod codes;
mod excerpt;
mod human;

pub use human::{render_one, MAX_SHOWN};

use crate::source::{FileId, SourceMap};
use crate::span::Span;

/// How bad a diagnostic is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Severity {
    /// Worth knowing; the scene still renders.
    Warning,
    /// The scene cannot render.
    Error,
}

/// One problem found in a scene, pointing at its source.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct Diagnostic {
    /// Error or warning.
    pub severity: Severity,
    /// Stable machine-readable code, e.g. `pts::check::unknown_param`.
    pub code: &'static str,
    /// One sentence, lower case, no final period.
    pub message: String,
    /// Where the problem is (absent for problems without a place, e.g. an empty scene).
    pub span: Option<Span>,
    /// What the underline says.
    pub label: String,
    /// Further places that explain the problem ("first defined here").
    pub secondary: Vec<(Span, String)>,
    /// What the user can do about it.
    pub help: Option<String>,
    /// A replacement that fixes it (a did-you-mean, the ptsc word for a
    /// POV-Ray one): the span's text becomes the string. Editors offer it
    /// as a quick fix.
    pub fix: Option<(Span, String)>,
    /// What tells it apart from another diagnostic of its code and span
    /// when repeats fold (see [`Diagnostics::folding`]): the parameter a
    /// "missing" names, where a block misses two (empty: nothing).
    pub distinct: &'static str,
}

impl Diagnostic {
    /// An error at `span`.
    pub fn error(code: &'static str, message: impl Into<String>, span: Span) -> Self {
        Diagnostic {
            severity: Severity::Error,
            code,
            message: bounded(message.into()),
            span: Some(span),
            label: String::new(),
            secondary: Vec::new(),
            help: None,
            fix: None,
            distinct: "",
        }
    }

    /// A warning at `span`.
    pub fn warning(code: &'static str, message: impl Into<String>, span: Span) -> Self {
        Diagnostic {
            severity: Severity::Warning,
            ..Diagnostic::error(code, message, span)
        }
    }

    /// Sets the label under the span.
    pub fn with_label(mut self, label: impl Into<String>) -> Self {
        self.label = bounded(label.into());
        self
    }

    /// Sets the help line.
    pub fn with_help(mut self, help: impl Into<String>) -> Self {
        self.help = Some(bounded(help.into()));
        self
    }

    /// Sets the replacement that fixes it ([`Diagnostic::fix`]).
    pub fn with_fix(mut self, span: Span, replacement: impl Into<String>) -> Self {
        self.fix = Some((span, replacement.into()));
        self
    }

    /// Sets what tells it apart from diagnostics of its code and span
    /// ([`Diagnostic::distinct`]).
    pub fn distinct_by(mut self, what: &'static str) -> Self {
        self.distinct = what;
        self
    }

    /// Adds a secondary labelled span.
    pub fn with_secondary(mut self, span: Span, label: impl Into<String>) -> Self {
        self.secondary.push((span, label.into()));
        self
    }

    /// Whether this is an error.
    pub fn is_error(&self) -> bool {
        self.severity == Severity::Error
    }
}

/// Every diagnostic of a run, in source order once sorted.
///
/// Adding one costs constant time whatever the list holds: a checker meets
/// the same problem once per iteration of a loop, and a loop of a million
/// iterations must not scan a million diagnostics each time. A folding
/// collection ([`Diagnostics::folding`], the checker's) keeps the first of
/// the diagnostics with one code and span and counts the others.
#[derive(Debug, Clone, Default)]
pub struct Diagnostics {
    /// The diagnostics. Read them freely; add with [`Diagnostics::push`]
    /// (which folds repeats and counts errors).
    pub items: Vec<Diagnostic>,
    /// Errors pushed so far, folded repeats included (never decreases).
    errors_pushed: u64,
    /// While folding: repeats of the diagnostics in `items`.
    folds: Option<Folds>,
}

/// The repeats a folding collection has met: where the first diagnostic of
/// each code and span is, and how many times each came.
#[derive(Debug, Clone, Default)]
struct Folds {
    /// The index in `items` of the first diagnostic of a code and span (and
    /// [`Diagnostic::distinct`]).
    first: std::collections::HashMap<(&'static str, Option<Span>, &'static str), usize>,
    /// How many times the diagnostic at each index of `items` came.
    times: Vec<u64>,
}

impl FromIterator<Diagnostic> for Diagnostics {
    fn from_iter<I: IntoIterator<Item = Diagnostic>>(iter: I) -> Self {
        let mut d = Diagnostics::new();
        iter.into_iter().for_each(|x| d.push(x));
        d
    }
}

impl Diagnostics {
    /// An empty collection.
    pub fn new() -> Self {
        Self::default()
    }

    /// An empty collection that folds repeats: a diagnostic with the code,
    /// span and [`Diagnostic::distinct`] of an earlier one (its message may differ, by a loop
    /// variable) is counted, not kept; [`Diagnostics::settle`] writes the
    /// counts into the messages.
    pub fn folding() -> Self {
        Diagnostics {
            folds: Some(Folds::default()),
            ..Self::default()
        }
    }

    /// Adds one (in constant time).
    pub fn push(&mut self, d: Diagnostic) {
        if d.is_error() {
            self.errors_pushed += 1;
        }
        if let Some(folds) = &mut self.folds {
            match folds.first.entry((d.code, d.span, d.distinct)) {
                std::collections::hash_map::Entry::Occupied(e) => {
                    folds.times[*e.get()] += 1;
                    return;
                }
                std::collections::hash_map::Entry::Vacant(e) => {
                    e.insert(self.items.len());
                    folds.times.push(1);
                }
            }
        }
        self.items.push(d);
    }

    /// Errors pushed so far, folded repeats included: it never decreases,
    /// so that comparing it before and after some work tells in constant
    /// time whether that work met an error.
    pub fn errors_pushed(&self) -> u64 {
        self.errors_pushed
    }

    /// Ends folding: each diagnostic that came more than once says how many
    /// times (`… (1,000 times)`). Later pushes are kept as they come.
    pub fn settle(&mut self) {
        let Some(folds) = self.folds.take() else {
            return;
        };
        for (d, &n) in self.items.iter_mut().zip(&folds.times) {
            if n > 1 {
                d.message = format!("{} ({} times)", d.message, group_digits(n));
            }
        }
    }

    /// Adds all of `other`.
    pub fn extend(&mut self, mut other: Diagnostics) {
        other.settle();
        other.items.into_iter().for_each(|d| self.push(d));
    }

    /// Drops each diagnostic equal to an earlier one (the same problem met
    /// again), keeping the first's place in the list.
    pub fn dedup(&mut self) {
        self.settle();
        let mut seen = std::collections::HashSet::new();
        let items = std::mem::take(&mut self.items);
        self.items = (items.into_iter())
            .filter(|d| seen.insert(d.clone()))
            .collect();
    }

    /// Whether any is an error.
    pub fn has_errors(&self) -> bool {
        self.items.iter().any(Diagnostic::is_error)
    }

    /// Number of errors.
    pub fn error_count(&self) -> usize {
        self.items.iter().filter(|d| d.is_error()).count()
    }

    /// Number of warnings.
    pub fn warning_count(&self) -> usize {
        self.items.len() - self.error_count()
    }

    /// Sorts by file and position, keeping the order of equal positions.
    pub fn sort(&mut self) {
        self.settle();
        self.items
            .sort_by_key(|d| d.span.map(|s| (s.file.0, s.start)).unwrap_or((u32::MAX, 0)));
    }

    /// Renders the diagnostics for a terminal (`color` picks the theme): at
    /// most [`MAX_SHOWN`] of them (errors first), then a line counting the rest.
    pub fn render_human(&self, sources: &SourceMap, color: bool) -> String {
        human::render(self, sources, color)
    }

    /// Renders every diagnostic as a JSON array (one object per diagnostic).
    pub fn render_json(&self, sources: &SourceMap) -> String {
        serde_json::to_string_pretty(&self.json_items(sources)).expect("JSON of plain values")
    }

    /// The diagnostics as [`Diagnostics::render_json`]'s objects (for a
    /// caller that joins several compiles' into one array).
    pub fn json_items(&self, sources: &SourceMap) -> Vec<serde_json::Value> {
        let mut columns = Columns::default();
        self.items
            .iter()
            .map(|d| {
                let mut obj = serde_json::json!({
                    "severity": match d.severity { Severity::Error => "error", Severity::Warning => "warning" },
                    "code": d.code,
                    "message": d.message,
                    "label": d.label,
                    "help": d.help,
                });
                if let Some(span) = d.span {
                    let (line, column) = columns.line_col(sources, span.file, span.start);
                    let (end_line, end_column) = columns.line_col(sources, span.file, span.end);
                    obj["file"] = sources.get(span.file).path.display().to_string().into();
                    obj["span"] = serde_json::json!({"start": span.start, "end": span.end});
                    obj["line"] = line.into();
                    obj["column"] = column.into();
                    obj["end_line"] = end_line.into();
                    obj["end_column"] = end_column.into();
                }
                // Secondary places: "first defined here", the include chain.
                let notes: Vec<serde_json::Value> = d
                    .secondary
                    .iter()
                    .map(|(s, label)| {
                        let (line, column) = columns.line_col(sources, s.file, s.start);
                        serde_json::json!({
                            "label": label,
                            "file": sources.get(s.file).path.display().to_string(),
                            "span": {"start": s.start, "end": s.end},
                            "line": line,
                            "column": column,
                        })
                    })
                    .collect();
                if !notes.is_empty() {
                    obj["notes"] = notes.into();
                }
                obj
            })
            .collect()
    }
}

/// `n` with thousands separated: `4,000,000`.
pub fn group_digits(n: u64) -> String {
    let digits = n.to_string();
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

/// Where a model file (an MTL library, a glTF) names another file, said in
/// the errors about that file: its path is relative to the model file,
/// not to the scene. Message text, kept here rather than in the checked
/// scene, whose values are typed.
#[derive(Debug, Clone, PartialEq)]
pub struct NamedIn {
    /// The file as the model names it and where, written for a message:
    /// `` `tex/a.png` of `images[0]` in `sub/a.gltf` ``.
    pub named: String,
    /// What its path is relative to, and how to mend it.
    pub help: String,
}

/// `n` and its noun, singular for one: `1 vertex`, `2 vertices` (a
/// message's count of anything a file holds may be one).
pub fn count(n: impl Into<u64>, one: &str, many: &str) -> String {
    let n = n.into();
    format!("{} {}", group_digits(n), if n == 1 { one } else { many })
}

/// Line and column lookups that remember the last one: diagnostics come in
/// source order, so many on one long line cost that line once, not once each.
#[derive(Default)]
struct Columns {
    /// File, 0-based line, byte offset and 1-based column of the last lookup.
    last: Option<(FileId, usize, usize, usize)>,
}

impl Columns {
    /// 1-based line and column (in characters) of byte `offset` of `file`.
    fn line_col(&mut self, sources: &SourceMap, file: FileId, offset: u32) -> (usize, usize) {
        let f = sources.get(file);
        let cut = f.floor_char_boundary(offset as usize);
        let line = f.line_of(cut);
        let (from, col) = match self.last {
            Some((lf, ll, lo, lc)) if lf == file && ll == line && lo <= cut => (lo, lc),
            _ => (f.line_starts()[line] as usize, 1),
        };
        let col = col + f.text[from..cut].chars().count();
        self.last = Some((file, line, cut, col));
        (line + 1, col)
    }
}

/// The closest candidate to `word` by edit distance, if it is close enough
/// to be a plausible typo ("did you mean").
pub fn did_you_mean<'a>(
    word: &str,
    candidates: impl IntoIterator<Item = &'a str>,
) -> Option<&'a str> {
    let limit = (word.chars().count() / 3).max(1);
    // Every one-letter name is one edit from every other (`I` from `x`).
    if word.chars().count() < 2 {
        return None;
    }
    candidates
        .into_iter()
        .map(|c| (edit_distance(word, c), c))
        .filter(|(d, _)| *d <= limit)
        .min_by_key(|(d, _)| *d)
        .map(|(_, c)| c)
}

/// Edit distance in characters, a swap of two neighbours counting one
/// edit (the optimal string alignment distance: Levenshtein's with
/// Damerau's transpositions), so that `chiar` is one edit from `chair`.
pub fn edit_distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.chars().collect();
    let b: Vec<char> = b.chars().collect();
    // Three rows: the one before the previous serves transpositions.
    let mut before: Vec<usize> = vec![0; b.len() + 1];
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    let mut row: Vec<usize> = vec![0; b.len() + 1];
    for i in 1..=a.len() {
        row[0] = i;
        for j in 1..=b.len() {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            row[j] = (prev[j] + 1).min(row[j - 1] + 1).min(prev[j - 1] + cost);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                row[j] = row[j].min(before[j - 2] + 1);
            }
        }
        std::mem::swap(&mut before, &mut prev);
        std::mem::swap(&mut prev, &mut row);
    }
    prev[b.len()]
}

/// The most characters of a message, label or help line: a longer one
/// (a name of five million letters written twice) keeps its start and end.
const MAX_TEXT: usize = 600;

/// `text`, or its start and end around an ellipsis when longer than
/// [`MAX_TEXT`] characters, saying how long it was.
fn bounded(text: String) -> String {
    if text.len() <= MAX_TEXT {
        return text;
    }
    let count = text.chars().count();
    if count <= MAX_TEXT {
        return text;
    }
    let keep = MAX_TEXT / 2 - 20;
    let head: String = text.chars().take(keep).collect();
    let tail: String = text.chars().skip(count - keep).collect();
    format!("{head}…{tail} ({} characters)", group_digits(count as u64))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edit_distance_counts_single_edits() {
        assert_eq!(edit_distance("radius", "radius"), 0);
        assert_eq!(edit_distance("radus", "radius"), 1);
        // A swap of two neighbours is one edit.
        assert_eq!(edit_distance("raidus", "radius"), 1);
        assert_eq!(edit_distance("chiar", "chair"), 1);
        assert_eq!(edit_distance("ab", "ba"), 1);
        assert_eq!(edit_distance("abc", "ca"), 3);
        assert_eq!(edit_distance("", "abc"), 3);
    }

    #[test]
    fn a_folding_collection_counts_repeats_and_keeps_the_first() {
        let at = |start| Span::new(FileId(0), start, start + 1);
        let mut d = Diagnostics::folding();
        for i in 0..100_000 {
            d.push(Diagnostic::warning("w", format!("warning {i}"), at(1)));
        }
        d.push(Diagnostic::error("e", "error", at(2)));
        d.push(Diagnostic::error("e", "error again", at(2)));
        d.push(Diagnostic::error("e", "elsewhere", at(3)));
        // Told apart: two parameters missing from one block.
        d.push(Diagnostic::error("m", "needs a `min`", at(4)).distinct_by("min"));
        d.push(Diagnostic::error("m", "needs a `max`", at(4)).distinct_by("max"));
        assert_eq!(d.items.len(), 5);
        assert_eq!(d.errors_pushed(), 5);
        d.sort();
        let messages: Vec<&str> = d.items.iter().map(|d| d.message.as_str()).collect();
        assert_eq!(
            messages,
            [
                "warning 0 (100,000 times)",
                "error (2 times)",
                "elsewhere",
                "needs a `min`",
                "needs a `max`"
            ]
        );
        // Settled: what comes later is kept as it comes.
        d.push(Diagnostic::error("e", "late", at(3)));
        assert_eq!(d.items.len(), 6);
    }

    #[test]
    fn a_count_of_one_is_singular() {
        assert_eq!(count(1u32, "vertex", "vertices"), "1 vertex");
        assert_eq!(count(0u32, "vertex", "vertices"), "0 vertices");
        assert_eq!(count(12_000u64, "face", "faces"), "12,000 faces");
    }

    #[test]
    fn did_you_mean_picks_the_closest_plausible_name() {
        let names = ["radius", "center", "material"];
        assert_eq!(did_you_mean("radus", names), Some("radius"));
        assert_eq!(did_you_mean("centre", names), Some("center"));
        assert_eq!(did_you_mean("xyz", names), None);
    }
}
