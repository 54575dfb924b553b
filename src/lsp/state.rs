//! What the server holds: the editor's documents, the last check of
//! each, and the ways to answer (respond, notify, log) and to name places
//! (URIs and locations of a check's spans).

use super::checker::Checker;
use super::convert::{path_to_uri, Lines};
use super::position::{Encoding, LineIndex};
use crate::compile::Compiled;
use crate::ide::View;
use lsp_server::{Message, Notification, Response};
use lsp_types as lsp;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// A request's answer, or its error code and message.
pub type Answer = Result<serde_json::Value, (i32, String)>;

/// A document the editor holds.
pub struct Document {
    /// Its URI as the editor wrote it.
    pub uri: lsp::Uri,
    /// Its path.
    pub path: PathBuf,
    /// Its text now.
    pub text: Arc<String>,
    /// Its lines.
    pub index: LineIndex,
    /// Its version.
    pub version: i32,
}

/// The server's state.
pub struct Server {
    pub(super) sender: crossbeam_channel::Sender<Message>,
    pub(super) encoding: Encoding,
    /// The workspace's folder, if the editor named one: where a document
    /// without a path (`untitled:`) reads its includes from.
    pub(super) root: Option<PathBuf>,
    pub(super) documents: HashMap<String, Document>,
    /// The last check of each open document, with the version it read.
    pub(super) checks: HashMap<String, (i32, Arc<Compiled>)>,
    /// The URIs each open document's last publication covered (itself and
    /// the files it includes), to clear them when they are gone.
    pub(super) published: HashMap<String, Vec<String>>,
    pub(super) checker: Checker,
    pub(super) shutdown: bool,
}

impl Server {
    pub(super) fn respond(&self, response: Response) {
        let _ = self.sender.send(response.into());
    }

    pub(super) fn notify(&self, method: &str, params: impl serde::Serialize) {
        let _ = self
            .sender
            .send(Notification::new(method.to_string(), params).into());
    }

    /// The path of the document `uri` ([`super::convert::uri_to_path`]).
    pub(super) fn path_of(&self, uri: &str) -> PathBuf {
        super::convert::uri_to_path(uri, self.root.as_deref())
    }

    pub(super) fn log(&self, typ: lsp::MessageType, message: String) {
        self.notify("window/logMessage", lsp::LogMessageParams { typ, message });
    }

    /// The URI of `path`: an open document's own, else a `file:` URI.
    pub(super) fn uri_of(&self, path: &Path) -> Option<lsp::Uri> {
        let path = crate::ide::normal(path);
        match self.documents.values().find(|d| d.path == path) {
            Some(d) => Some(d.uri.clone()),
            None => path_to_uri(&path),
        }
    }

    /// The protocol location of a span of a check; `indexes` are the
    /// line indexes of the check's files, in their order (built once per
    /// publication, not once per span).
    pub(super) fn location(
        &self,
        compiled: &Compiled,
        indexes: &[LineIndex],
        span: crate::span::Span,
    ) -> Option<lsp::Location> {
        let source = compiled.sources.files().get(span.file.0 as usize)?;
        let uri = self.uri_of(&source.path)?;
        let lines = Lines {
            text: &source.text,
            index: indexes.get(span.file.0 as usize)?,
            encoding: self.encoding,
        };
        Some(lsp::Location {
            uri,
            range: lines.range(span.start as usize, span.end as usize),
        })
    }

    /// The view of an open document: its text and the check to answer
    /// from (its own, or that of an open scene that includes it).
    pub(super) fn view<'a>(&'a self, uri: &str) -> Option<(View<'a>, &'a Document)> {
        let doc = self.documents.get(uri)?;
        let own = self.checks.get(uri).map(|(_, c)| c.as_ref());
        let is_fragment = doc.path.extension().is_some_and(|e| e == "ptsi");
        let includer = || {
            (self.checks.iter())
                .filter(|(k, _)| k.as_str() != uri)
                .map(|(_, (_, c))| c.as_ref())
                .find(|c| {
                    c.sources
                        .files()
                        .iter()
                        .skip(1)
                        .any(|f| crate::ide::normal(&f.path) == doc.path)
                })
        };
        let compiled = if is_fragment {
            includer().or(own)
        } else {
            own.or_else(includer)
        };
        Some((
            View {
                path: &doc.path,
                text: &doc.text,
                compiled,
            },
            doc,
        ))
    }
}
