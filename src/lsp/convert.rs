//! Between the protocol's names and ours: URIs and paths, positions and
//! byte offsets (in the negotiated encoding), our diagnostics and theirs.

use super::position::{Encoding, LineIndex};
use crate::diag::{Diagnostic, Severity};
use lsp_types as lsp;
use std::path::{Path, PathBuf};
use std::str::FromStr;

/// The made-up folder of a document that has no path (`untitled:`) when
/// there is no workspace: nothing is read from it
/// ([`crate::source::MemoryFiles::unsaved_folder`]), so its includes are
/// "unsaved", not "not found" in a folder that does not exist.
pub const UNSAVED_FOLDER: &str = "/untitled";

/// The path a document's URI names: a `file:` URI's path, else a made-up
/// name in the workspace's folder `root` (its includes are read from
/// there, as `ptsc check -` reads them from the working folder), or in
/// [`UNSAVED_FOLDER`] without one.
pub fn uri_to_path(uri: &str, root: Option<&Path>) -> PathBuf {
    if let Ok(url) = url::Url::parse(uri) {
        if url.scheme() == "file" {
            if let Ok(path) = url.to_file_path() {
                return crate::ide::normal(&path);
            }
        }
    }
    let name: String = uri
        .chars()
        .map(|c| {
            if c.is_alphanumeric() || c == '.' {
                c
            } else {
                '_'
            }
        })
        .collect();
    crate::ide::normal(&root.unwrap_or(Path::new(UNSAVED_FOLDER)).join(name))
}

/// The `file:` URI of a path.
pub fn path_to_uri(path: &Path) -> Option<lsp::Uri> {
    let url = url::Url::from_file_path(crate::ide::normal(path)).ok()?;
    lsp::Uri::from_str(url.as_str()).ok()
}

/// A text with its line index, to convert positions.
pub struct Lines<'a> {
    /// The text.
    pub text: &'a str,
    /// Its lines.
    pub index: &'a LineIndex,
    /// How columns count.
    pub encoding: Encoding,
}

impl Lines<'_> {
    /// The protocol position of byte `offset`.
    pub fn position(&self, offset: usize) -> lsp::Position {
        let (line, character) = self.index.position(self.text, offset, self.encoding);
        lsp::Position { line, character }
    }

    /// The protocol range of bytes `start..end`.
    pub fn range(&self, start: usize, end: usize) -> lsp::Range {
        lsp::Range {
            start: self.position(start),
            end: self.position(end.max(start)),
        }
    }

    /// The byte offset of a protocol position (clamped to the text).
    pub fn offset(&self, p: lsp::Position) -> usize {
        self.index
            .offset(self.text, p.line, p.character, self.encoding)
    }
}

/// One of our diagnostics in the protocol's terms, its span in `lines`;
/// `related` places its other spans ("defined here", "included from").
pub fn diagnostic(
    d: &Diagnostic,
    lines: &Lines,
    related: &mut dyn FnMut(crate::span::Span) -> Option<lsp::Location>,
) -> lsp::Diagnostic {
    let range = d.span.map_or_else(lsp::Range::default, |s| {
        lines.range(s.start as usize, s.end as usize)
    });
    let mut message = d.message.clone();
    if !d.label.is_empty() {
        message.push_str(&format!(" ({})", d.label));
    }
    if let Some(help) = &d.help {
        message.push_str(&format!("\nhelp: {help}"));
    }
    let related_information: Vec<lsp::DiagnosticRelatedInformation> = (d.secondary.iter())
        .filter_map(|(span, label)| {
            Some(lsp::DiagnosticRelatedInformation {
                location: related(*span)?,
                message: label.clone(),
            })
        })
        .collect();
    let unused = d.code.ends_with("unused") || d.code.contains("::unused_");
    lsp::Diagnostic {
        range,
        severity: Some(match d.severity {
            Severity::Error => lsp::DiagnosticSeverity::ERROR,
            Severity::Warning => lsp::DiagnosticSeverity::WARNING,
        }),
        code: Some(lsp::NumberOrString::String(d.code.to_string())),
        code_description: None,
        source: Some("ptsc".to_string()),
        message,
        related_information: (!related_information.is_empty()).then_some(related_information),
        tags: unused.then(|| vec![lsp::DiagnosticTag::UNNECESSARY]),
        data: None,
    }
}
