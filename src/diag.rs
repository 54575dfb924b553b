//! Diagnostics: what ptsc tells the user about a scene. Each is data (a code,
//! a message, a labelled span, a help line), collected for the whole run and
//! rendered at the end by miette (human) or as JSON (editors, CI).

use crate::source::SourceMap;
use crate::span::Span;
use miette::{GraphicalReportHandler, GraphicalTheme, LabeledSpan, NamedSource};
use std::fmt;
use std::sync::Arc;

/// How bad a diagnostic is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Severity {
    /// Worth knowing; the scene still renders.
    Warning,
    /// The scene cannot render.
    Error,
}

/// One problem found in a scene, pointing at its source.
#[derive(Debug, Clone, PartialEq)]
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
}

impl Diagnostic {
    /// An error at `span`.
    pub fn error(code: &'static str, message: impl Into<String>, span: Span) -> Self {
        Diagnostic {
            severity: Severity::Error,
            code,
            message: message.into(),
            span: Some(span),
            label: String::new(),
            secondary: Vec::new(),
            help: None,
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
        self.label = label.into();
        self
    }

    /// Sets the help line.
    pub fn with_help(mut self, help: impl Into<String>) -> Self {
        self.help = Some(help.into());
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
#[derive(Debug, Clone, Default)]
pub struct Diagnostics {
    /// The diagnostics.
    pub items: Vec<Diagnostic>,
}

impl Diagnostics {
    /// An empty collection.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds one.
    pub fn push(&mut self, d: Diagnostic) {
        self.items.push(d);
    }

    /// Adds all of `other`.
    pub fn extend(&mut self, other: Diagnostics) {
        self.items.extend(other.items);
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
        self.items
            .sort_by_key(|d| d.span.map(|s| (s.file.0, s.start)).unwrap_or((u32::MAX, 0)));
    }

    /// Renders every diagnostic for a terminal (`color` picks the theme),
    /// followed by a summary line.
    pub fn render_human(&self, sources: &SourceMap, color: bool) -> String {
        let mut out = String::new();
        for d in &self.items {
            out.push_str(&render_one(d, sources, color));
        }
        out
    }

    /// Renders every diagnostic as a JSON array (one object per diagnostic).
    pub fn render_json(&self, sources: &SourceMap) -> String {
        let arr: Vec<serde_json::Value> = self
            .items
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
                    let (line, column) = sources.line_col(span.file, span.start);
                    let (end_line, end_column) = sources.line_col(span.file, span.end);
                    obj["file"] = sources.get(span.file).path.display().to_string().into();
                    obj["span"] = serde_json::json!({"start": span.start, "end": span.end});
                    obj["line"] = line.into();
                    obj["column"] = column.into();
                    obj["end_line"] = end_line.into();
                    obj["end_column"] = end_column.into();
                }
                obj
            })
            .collect();
        serde_json::to_string_pretty(&arr).expect("JSON of plain values")
    }
}

/// Renders one diagnostic with miette's graphical handler.
pub fn render_one(d: &Diagnostic, sources: &SourceMap, color: bool) -> String {
    let theme = if color {
        GraphicalTheme::unicode()
    } else {
        GraphicalTheme::unicode_nocolor()
    };
    let handler = GraphicalReportHandler::new_themed(theme)
        .with_width(100)
        .with_links(false);
    let mut labels = Vec::new();
    let mut source = None;
    if let Some(span) = d.span {
        let file = sources.get(span.file);
        source = Some(NamedSource::new(
            file.path.display().to_string(),
            file.text.clone(),
        ));
        let label = (!d.label.is_empty()).then(|| d.label.clone());
        labels.push(LabeledSpan::new_primary_with_span(label, span));
        for (s, l) in &d.secondary {
            if s.file == span.file {
                labels.push(LabeledSpan::new_with_span(Some(l.clone()), *s));
            }
        }
    }
    // Secondary spans in other files (e.g. an include chain) become related reports.
    let related: Vec<MietteReport> = d
        .span
        .map(|span| {
            d.secondary
                .iter()
                .filter(|(s, _)| s.file != span.file)
                .map(|(s, l)| {
                    let file = sources.get(s.file);
                    MietteReport {
                        message: l.clone(),
                        code: None,
                        severity: miette::Severity::Advice,
                        help: None,
                        source: Some(NamedSource::new(
                            file.path.display().to_string(),
                            file.text.clone(),
                        )),
                        labels: vec![LabeledSpan::new_primary_with_span(None, *s)],
                        related: Vec::new(),
                    }
                })
                .collect()
        })
        .unwrap_or_default();
    let report = MietteReport {
        message: d.message.clone(),
        code: Some(d.code),
        severity: match d.severity {
            Severity::Error => miette::Severity::Error,
            Severity::Warning => miette::Severity::Warning,
        },
        help: d.help.clone(),
        source,
        labels,
        related,
    };
    let mut out = String::new();
    handler
        .render_report(&mut out, &report)
        .expect("writing to a String cannot fail");
    out
}

/// What miette needs to draw one report.
#[derive(Debug)]
struct MietteReport {
    message: String,
    code: Option<&'static str>,
    severity: miette::Severity,
    help: Option<String>,
    source: Option<NamedSource<Arc<String>>>,
    labels: Vec<LabeledSpan>,
    related: Vec<MietteReport>,
}

impl fmt::Display for MietteReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for MietteReport {}

impl miette::Diagnostic for MietteReport {
    fn code<'a>(&'a self) -> Option<Box<dyn fmt::Display + 'a>> {
        self.code.map(|c| Box::new(c) as Box<dyn fmt::Display>)
    }

    fn severity(&self) -> Option<miette::Severity> {
        Some(self.severity)
    }

    fn help<'a>(&'a self) -> Option<Box<dyn fmt::Display + 'a>> {
        self.help
            .as_ref()
            .map(|h| Box::new(h) as Box<dyn fmt::Display>)
    }

    fn source_code(&self) -> Option<&dyn miette::SourceCode> {
        self.source.as_ref().map(|s| s as &dyn miette::SourceCode)
    }

    fn labels(&self) -> Option<Box<dyn Iterator<Item = LabeledSpan> + '_>> {
        if self.labels.is_empty() {
            None
        } else {
            Some(Box::new(self.labels.iter().cloned()))
        }
    }

    fn related<'a>(&'a self) -> Option<Box<dyn Iterator<Item = &'a dyn miette::Diagnostic> + 'a>> {
        if self.related.is_empty() {
            None
        } else {
            Some(Box::new(
                self.related.iter().map(|r| r as &dyn miette::Diagnostic),
            ))
        }
    }
}

/// The closest candidate to `word` by edit distance, if it is close enough
/// to be a plausible typo ("did you mean").
pub fn did_you_mean<'a>(
    word: &str,
    candidates: impl IntoIterator<Item = &'a str>,
) -> Option<&'a str> {
    let limit = (word.chars().count() / 3).max(1);
    candidates
        .into_iter()
        .map(|c| (edit_distance(word, c), c))
        .filter(|(d, _)| *d <= limit)
        .min_by_key(|(d, _)| *d)
        .map(|(_, c)| c)
}

/// Levenshtein distance in characters.
pub fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut prev = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let cur = row[j + 1];
            row[j + 1] = if ca == *cb {
                prev
            } else {
                1 + prev.min(row[j]).min(row[j + 1])
            };
            prev = cur;
        }
    }
    row[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edit_distance_counts_single_edits() {
        assert_eq!(edit_distance("radius", "radius"), 0);
        assert_eq!(edit_distance("radus", "radius"), 1);
        assert_eq!(edit_distance("raidus", "radius"), 2);
        assert_eq!(edit_distance("", "abc"), 3);
    }

    #[test]
    fn did_you_mean_picks_the_closest_plausible_name() {
        let names = ["radius", "center", "material"];
        assert_eq!(did_you_mean("radus", names), Some("radius"));
        assert_eq!(did_you_mean("centre", names), Some("center"));
        assert_eq!(did_you_mean("xyz", names), None);
    }
}
