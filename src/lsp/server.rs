//! The main loop: documents the editor holds, the last check of each, the
//! answers to requests. Requests are answered on this thread from the
//! last check (never waiting for one); checks run on the checker's thread
//! ([`super::checker`]). A request that panics is answered with an error
//! and the server goes on; a malformed message is reported in the log.

use super::checker::{Checker, Done, Job, DEBOUNCE};
use super::convert::{diagnostic, Lines, UNSAVED_FOLDER};
use super::position::{Encoding, LineIndex};
use super::state::{Document, Server};
use super::transport::MALFORMED;
use crate::compile::Compiled;
use crate::source::MemoryFiles;
use crossbeam_channel::{select, unbounded, Receiver};
use lsp_server::{Connection, ErrorCode, Message, Notification, Request, Response};
use lsp_types as lsp;
use serde_json::Value;
use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

/// How the session ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ending {
    /// `shutdown` then `exit`.
    Clean,
    /// `exit` without `shutdown`, or the input ended.
    Abrupt,
}

/// Serves `connection` until `exit` or the end of its input.
pub fn serve(connection: &Connection) -> Ending {
    let Some((encoding, root)) = initialize(connection) else {
        return Ending::Abrupt;
    };
    let (done_tx, done_rx) = unbounded::<Done>();
    let mut server = Server {
        sender: connection.sender.clone(),
        encoding,
        root,
        documents: HashMap::new(),
        checks: HashMap::new(),
        published: HashMap::new(),
        checker: Checker::start(done_tx),
        shutdown: false,
    };
    server.run(&connection.receiver, &done_rx)
}

/// Waits for `initialize` (answering anything else before it with an
/// error) and answers it: the encoding chosen, and the workspace's folder.
fn initialize(connection: &Connection) -> Option<(Encoding, Option<PathBuf>)> {
    loop {
        let message = connection.receiver.recv().ok()?;
        match message {
            Message::Request(req) if req.method == "initialize" => {
                let params: lsp::InitializeParams =
                    serde_json::from_value(req.params).unwrap_or_default();
                let utf8 = (params.capabilities.general.as_ref())
                    .and_then(|g| g.position_encodings.as_ref())
                    .is_some_and(|e| e.contains(&lsp::PositionEncodingKind::UTF8));
                let encoding = if utf8 {
                    Encoding::Utf8
                } else {
                    Encoding::Utf16
                };
                let root = workspace_root(&params);
                let result = lsp::InitializeResult {
                    capabilities: super::handlers::capabilities(encoding),
                    server_info: Some(lsp::ServerInfo {
                        name: "ptsc".to_string(),
                        version: Some(env!("CARGO_PKG_VERSION").to_string()),
                    }),
                };
                let _ = connection
                    .sender
                    .send(Response::new_ok(req.id, result).into());
                return Some((encoding, root));
            }
            Message::Request(req) => {
                let e = Response::new_err(
                    req.id,
                    ErrorCode::ServerNotInitialized as i32,
                    "the server is not initialized".into(),
                );
                let _ = connection.sender.send(e.into());
            }
            Message::Notification(n) if n.method == "exit" => return None,
            _ => {}
        }
    }
}

/// The workspace's folder: the first workspace folder, else the root URI
/// (a `file:` URI; another names no folder).
#[allow(deprecated)] // `root_uri`: older editors send only it.
fn workspace_root(params: &lsp::InitializeParams) -> Option<PathBuf> {
    let first = (params.workspace_folders.iter().flatten()).map(|f| f.uri.as_str());
    let root = params.root_uri.as_ref().map(|u| u.as_str());
    first
        .chain(root)
        .find_map(|u| url::Url::parse(u).ok()?.to_file_path().ok())
        .map(|p| crate::ide::normal(&p))
}

impl Server {
    fn run(&mut self, input: &Receiver<Message>, done: &Receiver<Done>) -> Ending {
        loop {
            select! {
                recv(input) -> m => match m {
                    Ok(m) => if let Some(end) = self.message(m) { return end },
                    Err(_) => return Ending::Abrupt,
                },
                recv(done) -> d => if let Ok(d) = d { self.checked(d) },
            }
        }
    }

    /// Handles one message; `Some` when the session is over.
    fn message(&mut self, message: Message) -> Option<Ending> {
        match message {
            Message::Request(req) => self.request(req),
            Message::Notification(n) if n.method == "exit" => {
                return Some(if self.shutdown {
                    Ending::Clean
                } else {
                    Ending::Abrupt
                });
            }
            Message::Notification(n) => self.notification(n),
            Message::Response(_) => {}
        }
        None
    }

    fn request(&mut self, req: Request) {
        if req.method == "shutdown" {
            self.shutdown = true;
            self.respond(Response::new_ok(req.id, Value::Null));
            return;
        }
        if self.shutdown {
            let e = Response::new_err(
                req.id,
                ErrorCode::InvalidRequest as i32,
                "the server is shutting down".into(),
            );
            self.respond(e);
            return;
        }
        let id = req.id.clone();
        let answer = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            super::handlers::handle(self, req)
        }));
        let response = match answer {
            Ok(Ok(result)) => Response::new_ok(id, result),
            Ok(Err((code, message))) => Response::new_err(id, code, message),
            Err(panic) => {
                let what = panic
                    .downcast_ref::<&str>()
                    .map(|s| s.to_string())
                    .or_else(|| panic.downcast_ref::<String>().cloned())
                    .unwrap_or_default();
                self.log(
                    lsp::MessageType::ERROR,
                    format!("a request failed (a bug in ptsc): {what}"),
                );
                Response::new_err(
                    id,
                    ErrorCode::InternalError as i32,
                    format!("ptsc failed on this request (a bug): {what}"),
                )
            }
        };
        self.respond(response);
    }

    fn notification(&mut self, n: Notification) {
        let method = n.method.clone();
        let result =
            std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| self.document_event(n)));
        match result {
            Ok(Ok(())) => {}
            Ok(Err(e)) => self.log(lsp::MessageType::WARNING, format!("{method}: {e}")),
            Err(_) => self.log(
                lsp::MessageType::ERROR,
                format!("{method} failed (a bug in ptsc)"),
            ),
        }
    }

    fn document_event(&mut self, n: Notification) -> Result<(), String> {
        let bad = |e: serde_json::Error| format!("bad parameters: {e}");
        match n.method.as_str() {
            MALFORMED => {
                let error = n
                    .params
                    .get("error")
                    .and_then(Value::as_str)
                    .unwrap_or("")
                    .to_string();
                self.log(
                    lsp::MessageType::ERROR,
                    format!("ignored a malformed message: {error}"),
                );
            }
            "textDocument/didOpen" => {
                let p: lsp::DidOpenTextDocumentParams =
                    serde_json::from_value(n.params).map_err(bad)?;
                let d = p.text_document;
                let key = d.uri.as_str().to_string();
                let path = self.path_of(&key);
                let index = LineIndex::new(&d.text);
                let doc = Document {
                    uri: d.uri,
                    path,
                    text: Arc::new(d.text),
                    index,
                    version: d.version,
                };
                self.documents.insert(key.clone(), doc);
                self.changed(&key, false);
            }
            "textDocument/didChange" => {
                let p: lsp::DidChangeTextDocumentParams =
                    serde_json::from_value(n.params).map_err(bad)?;
                let key = p.text_document.uri.as_str().to_string();
                let encoding = self.encoding;
                let doc = self
                    .documents
                    .get_mut(&key)
                    .ok_or("a change to a document that is not open")?;
                let mut text = doc.text.as_str().to_string();
                for change in p.content_changes {
                    apply(&mut text, &change, encoding);
                }
                doc.index = LineIndex::new(&text);
                doc.text = Arc::new(text);
                doc.version = p.text_document.version;
                self.changed(&key, true);
            }
            "textDocument/didClose" => {
                let p: lsp::DidCloseTextDocumentParams =
                    serde_json::from_value(n.params).map_err(bad)?;
                let key = p.text_document.uri.as_str().to_string();
                self.documents.remove(&key);
                let closed = self.checks.remove(&key);
                self.checker.forget(&key);
                for uri in self.published.remove(&key).unwrap_or_default() {
                    self.publish(&uri, Vec::new(), None);
                }
                // The scenes that include it read it from the disk again.
                self.recheck_readers(&self.path_of(&key));
                // Open files it included are reported by their own checks again.
                let included: Vec<PathBuf> = (closed.iter())
                    .flat_map(|(_, c)| c.sources.files().iter().skip(1))
                    .map(|f| crate::ide::normal(&f.path))
                    .collect();
                let reopened: Vec<String> = (self.documents.iter())
                    .filter(|(_, d)| included.contains(&d.path))
                    .map(|(k, _)| k.clone())
                    .collect();
                for k in reopened {
                    self.schedule(&k, false);
                }
            }
            "workspace/didChangeWatchedFiles" => {
                let p: lsp::DidChangeWatchedFilesParams =
                    serde_json::from_value(n.params).map_err(bad)?;
                for change in p.changes {
                    self.recheck_readers(&self.path_of(change.uri.as_str()));
                }
            }
            _ => {}
        }
        Ok(())
    }

    /// Schedules the check of `key` and of every open scene that read it.
    fn changed(&mut self, key: &str, debounce: bool) {
        self.schedule(key, debounce);
        if let Some(path) = self.documents.get(key).map(|d| d.path.clone()) {
            let readers: Vec<String> = self
                .readers_of(&path)
                .into_iter()
                .filter(|k| k != key)
                .collect();
            for k in readers {
                self.schedule(&k, debounce);
            }
        }
    }

    fn recheck_readers(&mut self, path: &Path) {
        for k in self.readers_of(path) {
            self.schedule(&k, false);
        }
    }

    /// The open documents whose last check read `path`.
    fn readers_of(&self, path: &Path) -> Vec<String> {
        let path = crate::ide::normal(path);
        (self.checks.iter())
            .filter(|(_, (_, c))| c.dependencies.iter().any(|d| crate::ide::normal(d) == path))
            .map(|(k, _)| k.clone())
            .collect()
    }

    fn schedule(&mut self, key: &str, debounce: bool) {
        let Some(doc) = self.documents.get(key) else {
            return;
        };
        let mut files = MemoryFiles::over_disk();
        files.unsaved_folder(UNSAVED_FOLDER);
        for d in self.documents.values() {
            files.insert(d.path.clone(), d.text.as_bytes().to_vec());
        }
        self.checker.schedule(Job {
            uri: key.to_string(),
            path: doc.path.clone(),
            version: doc.version,
            text: doc.text.clone(),
            files,
            due: Instant::now()
                + if debounce {
                    DEBOUNCE
                } else {
                    std::time::Duration::ZERO
                },
        });
    }

    /// A check finished: keep it and publish its diagnostics, unless the
    /// document changed since.
    fn checked(&mut self, done: Done) {
        let current = self.documents.get(&done.uri).map(|d| d.version);
        if current != Some(done.version) {
            return;
        }
        self.checks
            .insert(done.uri.clone(), (done.version, done.compiled.clone()));
        self.publish_check(&done.uri, &done.compiled);
    }

    /// The diagnostics of a check, each file's under its own URI. A file
    /// another open scene includes is reported by that scene's check (its
    /// names are defined there), not by its own.
    fn publish_check(&mut self, key: &str, compiled: &Compiled) {
        let root = self
            .documents
            .get(key)
            .map(|d| d.path.clone())
            .unwrap_or_default();
        let included_elsewhere = (self.checks.iter()).any(|(k, (_, c))| {
            k != key
                && c.sources
                    .files()
                    .iter()
                    .skip(1)
                    .any(|f| crate::ide::normal(&f.path) == root)
        });
        let mut by_file: HashMap<u32, Vec<&crate::diag::Diagnostic>> = HashMap::new();
        for d in &compiled.diagnostics.items {
            let file = d.span.map_or(0, |s| s.file.0);
            by_file.entry(file).or_default().push(d);
        }
        let mut uris = Vec::new();
        let indexes: Vec<LineIndex> = (compiled.sources.files().iter())
            .map(|f| LineIndex::new(&f.text))
            .collect();
        for (i, source) in compiled.sources.files().iter().enumerate() {
            if i == 0 && included_elsewhere {
                continue;
            }
            let Some(uri) = self.uri_of(&source.path) else {
                continue;
            };
            let lines = Lines {
                text: &source.text,
                index: &indexes[i],
                encoding: self.encoding,
            };
            let mut related = |span: crate::span::Span| self.location(compiled, &indexes, span);
            let items: Vec<lsp::Diagnostic> = (by_file.get(&(i as u32)).into_iter().flatten())
                .map(|d| diagnostic(d, &lines, &mut related))
                .collect();
            let version = self.documents.get(uri.as_str()).map(|d| d.version);
            uris.push(uri.as_str().to_string());
            self.publish(uri.as_str(), items, version);
        }
        // Files it included before and does not now: cleared.
        let before = self
            .published
            .insert(key.to_string(), uris.clone())
            .unwrap_or_default();
        let still: HashSet<&String> = self.published.values().flatten().collect();
        let gone: Vec<String> = before
            .into_iter()
            .filter(|u| !uris.contains(u) && !still.contains(u))
            .collect();
        for uri in gone {
            self.publish(&uri, Vec::new(), None);
        }
    }

    fn publish(&self, uri: &str, diagnostics: Vec<lsp::Diagnostic>, version: Option<i32>) {
        let Ok(uri) = uri.parse::<lsp::Uri>() else {
            return;
        };
        self.notify(
            "textDocument/publishDiagnostics",
            lsp::PublishDiagnosticsParams {
                uri,
                diagnostics,
                version,
            },
        );
    }
}

/// Applies one change (a range replaced, or the whole text) to `text`.
fn apply(text: &mut String, change: &lsp::TextDocumentContentChangeEvent, encoding: Encoding) {
    match change.range {
        None => text.clone_from(&change.text),
        Some(range) => {
            let index = LineIndex::new(text);
            let start = index.offset(text, range.start.line, range.start.character, encoding);
            let end = index
                .offset(text, range.end.line, range.end.character, encoding)
                .max(start);
            text.replace_range(start..end, &change.text);
        }
    }
}
