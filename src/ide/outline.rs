//! The outline of a document (its statements as a tree: camera, lights,
//! materials, objects, groups and what loops and branches hold) and its
//! folding ranges, read from the text held now with the error-tolerant
//! parser (a statement with a syntax error is left out; the rest stays).

use super::tokens::{tokens, TokenKind};
use crate::check::kinds::{self, Role};
use crate::source::FileId;
use crate::syntax::ast::Statement;
use std::ops::Range;

/// What an outline entry is (the editor picks its icon).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SymbolClass {
    /// A setting block (`render`, `camera`, `sky`, …).
    Setting,
    /// A light.
    Light,
    /// An object (a shape).
    Object,
    /// A material.
    Material,
    /// A texture.
    Texture,
    /// A group, or a placement of one.
    Group,
    /// A constant.
    Constant,
    /// A function.
    Function,
    /// A loop, a branch, an include, anything else.
    Other,
}

/// One entry of the outline.
#[derive(Debug, Clone, PartialEq)]
pub struct OutlineItem {
    /// Its name (`sphere`, `material glass`, `for i`).
    pub name: String,
    /// What it is.
    pub class: SymbolClass,
    /// The whole statement.
    pub range: Range<usize>,
    /// The part to select (its name).
    pub selection: Range<usize>,
    /// The statements inside (a group's, a loop's, a branch's).
    pub children: Vec<OutlineItem>,
}

/// The outline of `text`.
pub fn outline(text: &str) -> Vec<OutlineItem> {
    let mut statements = Vec::new();
    let _ = crate::syntax::parse_each(FileId(0), text, &kinds::NAMES, &mut |s| {
        statements.extend(s)
    });
    statements.iter().filter_map(item).collect()
}

fn range(span: crate::span::Span) -> Range<usize> {
    span.start as usize..span.end as usize
}

fn item(st: &Statement) -> Option<OutlineItem> {
    let whole = range(st.span());
    let leaf = |name: String, class, selection: Range<usize>| OutlineItem {
        name,
        class,
        range: whole.clone(),
        selection,
        children: Vec::new(),
    };
    let inner = |body: &[Statement]| body.iter().filter_map(item).collect::<Vec<_>>();
    Some(match st {
        Statement::Let { name, .. } => leaf(
            format!("let {}", name.name),
            SymbolClass::Constant,
            range(name.span),
        ),
        Statement::Function { name, .. } => leaf(
            format!("fn {}", name.name),
            SymbolClass::Function,
            range(name.span),
        ),
        Statement::Material { name, .. } => leaf(
            format!("material {}", name.name),
            SymbolClass::Material,
            range(name.span),
        ),
        Statement::Texture { name, kind, .. } => leaf(
            format!("texture {} {}", name.name, kind.name),
            SymbolClass::Texture,
            range(name.span),
        ),
        Statement::Instance { group, .. } => leaf(
            format!("instance {}", group.name),
            SymbolClass::Group,
            range(group.span),
        ),
        Statement::Include {
            path, path_span, ..
        } => leaf(
            format!("include \"{path}\""),
            SymbolClass::Other,
            range(*path_span),
        ),
        Statement::Background { .. } => leaf(
            "background".to_string(),
            SymbolClass::Setting,
            whole.start..whole.start + 10,
        ),
        Statement::Block { kind, .. } => {
            let class = match kinds::find(&kind.name).map(|k| k.role) {
                Some(Role::Setting(_)) => SymbolClass::Setting,
                Some(Role::Light(_)) => SymbolClass::Light,
                Some(Role::Shape(_)) if kind.name.contains("light") => SymbolClass::Light,
                Some(Role::Shape(_)) => SymbolClass::Object,
                None => SymbolClass::Other,
            };
            leaf(kind.name.clone(), class, range(kind.span))
        }
        Statement::Group { name, body, .. } => OutlineItem {
            children: inner(body),
            ..leaf(
                format!("group {}", name.name),
                SymbolClass::Group,
                range(name.span),
            )
        },
        Statement::For { var, body, .. } => OutlineItem {
            children: inner(body),
            ..leaf(
                format!("for {}", var.name),
                SymbolClass::Other,
                range(var.span),
            )
        },
        Statement::If {
            arms, otherwise, ..
        } => {
            let mut children: Vec<OutlineItem> = arms.iter().flat_map(|(_, b)| inner(b)).collect();
            children.extend(otherwise.iter().flat_map(|b| inner(b)));
            OutlineItem {
                children,
                ..leaf(
                    "if".to_string(),
                    SymbolClass::Other,
                    whole.start..whole.start + 2,
                )
            }
        }
        Statement::Directive { .. } | Statement::Foreign { .. } => return None,
    })
}

/// A folding range: lines `start` to `end` (0-based byte offsets of its
/// first and last characters; the server turns them into lines).
#[derive(Debug, Clone, PartialEq)]
pub struct Fold {
    /// Bytes of the folded region (from its `{` or `/*` to its end).
    pub range: Range<usize>,
    /// Whether it is a comment.
    pub comment: bool,
}

/// The braces and block comments of `text` that span lines, and runs of
/// two or more `//` comment lines.
pub fn folds(text: &str) -> Vec<Fold> {
    let mut out = Vec::new();
    let mut open = Vec::new();
    let mut line_comments: Option<Range<usize>> = None;
    for t in tokens(text) {
        let s = &text[t.range.clone()];
        if t.kind == TokenKind::Comment && s.starts_with("//") {
            line_comments = match line_comments.take() {
                Some(r)
                    if !text[r.end..t.range.start].contains("\n\n")
                        && text[r.end..t.range.start].trim().is_empty() =>
                {
                    Some(r.start..t.range.end)
                }
                Some(r) => {
                    push_fold(&mut out, text, r, true);
                    Some(t.range.clone())
                }
                None => Some(t.range.clone()),
            };
            continue;
        }
        if let Some(r) = line_comments.take() {
            push_fold(&mut out, text, r, true);
        }
        match (t.kind, s) {
            (TokenKind::Comment, _) => push_fold(&mut out, text, t.range.clone(), true),
            (TokenKind::Punct, "{") => open.push(t.range.start),
            (TokenKind::Punct, "}") => {
                if let Some(start) = open.pop() {
                    push_fold(&mut out, text, start..t.range.end, false);
                }
            }
            _ => {}
        }
    }
    if let Some(r) = line_comments {
        push_fold(&mut out, text, r, true);
    }
    out.sort_by_key(|f| f.range.start);
    out
}

fn push_fold(out: &mut Vec<Fold>, text: &str, range: Range<usize>, comment: bool) {
    if text[range.clone()].contains('\n') {
        out.push(Fold { range, comment });
    }
}
