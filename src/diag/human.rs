//! Diagnostics for people: miette's graphical report of each, drawn from an
//! [`Excerpt`] of its file, at most [`MAX_SHOWN`] of them per run.

use super::excerpt::{Excerpt, ExcerptSource};
use super::{Diagnostic, Diagnostics, Severity};
use crate::source::SourceMap;
use crate::span::Span;
use miette::{GraphicalReportHandler, GraphicalTheme, LabeledSpan};
use std::fmt;

/// Most diagnostics drawn in one report; the rest are counted in a last line
/// (JSON output lists them all).
pub const MAX_SHOWN: usize = 100;

/// Renders the diagnostics for a terminal (`color` picks the theme): all of
/// them up to [`MAX_SHOWN`], else that many (errors first, then in source
/// order) and a line that counts the others.
pub fn render(diags: &Diagnostics, sources: &SourceMap, color: bool) -> String {
    let mut out = String::new();
    let items = &diags.items;
    if items.len() <= MAX_SHOWN {
        for d in items {
            out.push_str(&render_one(d, sources, color));
        }
        return out;
    }
    // Errors before warnings, so that no error hides behind the cap.
    let mut shown: Vec<usize> = (0..items.len()).filter(|&i| items[i].is_error()).collect();
    shown.extend((0..items.len()).filter(|&i| !items[i].is_error()));
    shown.truncate(MAX_SHOWN);
    shown.sort_unstable();
    for &i in &shown {
        out.push_str(&render_one(&items[i], sources, color));
    }
    let hidden = |severity: Severity| {
        let total = items.iter().filter(|d| d.severity == severity).count();
        let drawn = shown
            .iter()
            .filter(|&&i| items[i].severity == severity)
            .count();
        total - drawn
    };
    let (errors, warnings) = (hidden(Severity::Error), hidden(Severity::Warning));
    out.push_str(&format!(
        "… {} more not shown ({errors} error{}, {warnings} warning{}); the JSON format lists every one\n",
        errors + warnings,
        if errors == 1 { "" } else { "s" },
        if warnings == 1 { "" } else { "s" },
    ));
    out
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
    // A secondary label in another file (an include chain) is a note line
    // under the report: `note: included from scene.pts:3:9`.
    let mut notes = String::new();
    if let Some(span) = d.span {
        // The primary label and the secondary ones in its file share an
        // excerpt.
        let mut here: Vec<(Span, Option<String>, bool)> =
            vec![(span, (!d.label.is_empty()).then(|| d.label.clone()), true)];
        for (s, l) in &d.secondary {
            if s.file == span.file {
                here.push((*s, Some(l.clone()), false));
            } else {
                let (line, column) = sources.line_col(s.file, s.start);
                let path = sources.get(s.file).path.display();
                notes.push_str(&format!("  note: {l} {path}:{line}:{column}\n"));
            }
        }
        let (excerpt, spans) = excerpt(sources, &here);
        for ((_, label, primary), s) in here.into_iter().zip(spans) {
            labels.push(if primary {
                LabeledSpan::new_primary_with_span(label, s)
            } else {
                LabeledSpan::new_with_span(label, s)
            });
        }
        source = Some(excerpt);
    }
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
    };
    let mut out = String::new();
    handler
        .render_report(&mut out, &report)
        .expect("writing to a String cannot fail");
    out.push_str(&notes);
    out
}

/// The excerpt of the file of `spans` (all in one file) and the spans in it.
fn excerpt(
    sources: &SourceMap,
    spans: &[(Span, Option<String>, bool)],
) -> (ExcerptSource, Vec<miette::SourceSpan>) {
    let file = sources.get(spans[0].0.file);
    let ranges: Vec<_> = spans
        .iter()
        .map(|(s, _, _)| (s.start as usize, s.end as usize))
        .collect();
    let (excerpt, mapped) = Excerpt::new(file.path.display().to_string(), file, &ranges);
    (
        ExcerptSource {
            excerpt,
            file_text: file.text.clone(),
        },
        mapped,
    )
}

/// What miette needs to draw one report.
#[derive(Debug)]
struct MietteReport {
    message: String,
    code: Option<&'static str>,
    severity: miette::Severity,
    help: Option<String>,
    source: Option<ExcerptSource>,
    labels: Vec<LabeledSpan>,
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
}
