//! What an editor asks of a scene, answered from the text it holds and
//! the last check of it (`compile` with `lower: false`): hover, completion,
//! definitions and references, rename, outline, folding, colours and
//! fixes. Positions are byte offsets and answers are our own types; the
//! language server (`lsp`) turns them into the protocol's. The check may
//! be older than the text (a large scene is re-checked while the user
//! types): answers that need the check's spans use it only when its text
//! is the text held ([`View::fresh_file`]), and fall back on reading the
//! text otherwise.

pub mod actions;
pub mod colors;
pub mod completion;
pub mod context;
pub mod docs;
pub mod hover;
pub mod navigation;
pub mod outline;
pub mod tokens;

use crate::compile::Compiled;
use crate::source::FileId;
use std::path::Path;

/// A document as the editor holds it, and the last check that read it.
#[derive(Clone, Copy)]
pub struct View<'a> {
    /// The document's path (for a document without one, a made-up path
    /// in the folder its includes are read from).
    pub path: &'a Path,
    /// The document's text now.
    pub text: &'a str,
    /// The last check of a scene that reads this document (the document
    /// itself, or a scene including it), if there has been one.
    pub compiled: Option<&'a Compiled>,
}

impl<'a> View<'a> {
    /// The document's id in the check, if the check read it.
    pub fn file(&self) -> Option<FileId> {
        let compiled = self.compiled?;
        let path = normal(self.path);
        (compiled.sources.files().iter())
            .position(|f| normal(&f.path) == path)
            .map(|i| FileId(i as u32))
    }

    /// The document's id in the check, if the check read the text held
    /// now (so that the check's spans are offsets in it).
    pub fn fresh_file(&self) -> Option<FileId> {
        let id = self.file()?;
        let compiled = self.compiled?;
        (compiled.sources.get(id).text.as_str() == self.text).then_some(id)
    }
}

/// `path` with its `.` and `..` parts resolved lexically (an include's
/// path is its scene's folder joined with what the scene wrote): the
/// source seam's own rule, so that a document and an include compare equal.
pub use crate::source::lexically_normal as normal;

#[cfg(test)]
mod tests;
