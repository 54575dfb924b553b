//! pest pairs → AST. One `build_*` function per rule; rules that the grammar
//! makes impossible at a place are `unreachable!`. Here the builder and
//! its names; statements, blocks and entries in `build_statement.rs`, which
//! builds on expressions in `build_expr.rs`, which builds on this.

use super::ast::*;
use super::parser::Rule;
use crate::source::FileId;
use crate::span::Span;
use pest::iterators::Pair;

/// Builds AST nodes from the pairs of one file.
pub struct Builder<'t> {
    /// The file the pairs come from.
    pub file: FileId,
    /// The whole text of the file.
    pub text: &'t str,
    /// The names of the kinds of block statement (see [`super::parse_each`]).
    pub kinds: &'t [&'t str],
    /// The first statement refused while building: a declaration that uses
    /// a reserved word as its name, or a kind's block that does not parse.
    pub reserved: std::cell::RefCell<Option<crate::diag::Diagnostic>>,
    /// Where in the file the parsed text starts (pairs count from there).
    pub base: std::cell::Cell<usize>,
}

impl<'t> Builder<'t> {
    /// A builder of `file`'s pairs, parsed from byte `base` of its `text`.
    pub fn new(file: FileId, text: &'t str, kinds: &'t [&'t str], base: usize) -> Self {
        Builder {
            file,
            text,
            kinds,
            reserved: Default::default(),
            base: std::cell::Cell::new(base),
        }
    }

    /// Where `pair` is in the file.
    pub(super) fn span(&self, pair: &Pair<Rule>) -> Span {
        let s = pair.as_span();
        let base = self.base.get();
        Span::new(self.file, base + s.start(), base + s.end())
    }

    /// A name.
    pub(super) fn build_ident(&self, pair: Pair<Rule>) -> Ident {
        Ident {
            name: pair.as_str().to_string(),
            span: self.span(&pair),
        }
    }

    /// A name being declared: reserved words are refused.
    pub(super) fn build_decl_name(&self, pair: Pair<Rule>) -> Ident {
        let id = self.build_ident(pair);
        if super::words::KEYWORDS.contains(&id.name.as_str()) {
            let mut slot = self.reserved.borrow_mut();
            if slot.is_none() {
                *slot = Some(
                    crate::diag::Diagnostic::error(
                        crate::diag::codes::RESERVED_WORD,
                        format!("`{}` is a reserved word", id.name),
                        id.span,
                    )
                    .with_label("cannot be used as a name")
                    .with_help(format!("pick another name, e.g. `my_{}`", id.name)),
                );
            }
        }
        id
    }
}
