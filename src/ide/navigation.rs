//! Go to definition, find references and rename, from the check's
//! symbols (each use belongs to the definition evaluation picked, across
//! includes); definition on an `include` or `file` path opens that file.
//! A name is renamed where the check saw it used: a use in a branch never
//! taken, or a function's body never called, was not resolved and is not
//! renamed (the rename says how many places it changes).

use super::context::{context, Place};
use super::tokens::word_at;
use super::View;
use crate::check::{DefId, SymbolKind};
use crate::span::Span;
use std::ops::Range;
use std::path::PathBuf;
use std::sync::Arc;

/// A place in a file the check read (or a file to open at its start).
#[derive(Debug, Clone, PartialEq)]
pub struct Location {
    /// The file.
    pub path: PathBuf,
    /// Bytes in its text.
    pub range: Range<usize>,
    /// The file's text as the check read it (empty for a file to open).
    pub text: Arc<String>,
}

/// The definition the name at `offset` resolves to.
fn def_at(view: View, offset: usize) -> Option<DefId> {
    let file = view.fresh_file()?;
    let symbols = &view.compiled?.symbols;
    symbols.definition_at(file, offset).or_else(|| {
        // The cursor just after the name.
        offset
            .checked_sub(1)
            .and_then(|o| symbols.definition_at(file, o))
    })
}

fn location(view: View, span: Span) -> Option<Location> {
    let source = view.compiled?.sources.get(span.file);
    Some(Location {
        path: source.path.clone(),
        range: span.start as usize..span.end as usize,
        text: source.text.clone(),
    })
}

/// Where the name (or the `include` / `file` path) at `offset` is defined.
pub fn definition(view: View, offset: usize) -> Option<Location> {
    if let Place::String { after, typed, .. } = context(view.text, offset).place {
        let rest = &view.text[offset.min(view.text.len())..];
        let whole = format!("{typed}{}", rest.split(['"', '\n']).next().unwrap_or(""));
        if after == "include" || after == "file" {
            let path = view
                .path
                .parent()
                .map_or(PathBuf::from(&whole), |d| d.join(&whole));
            return Some(Location {
                path: super::normal(&path),
                range: 0..0,
                text: Arc::default(),
            });
        }
        return None;
    }
    let def = def_at(view, offset)?;
    location(view, view.compiled?.symbols.get(def).name_span)
}

/// Every use of the name at `offset` (and its definition if asked).
pub fn references(view: View, offset: usize, with_definition: bool) -> Vec<Location> {
    let Some(def) = def_at(view, offset) else {
        return Vec::new();
    };
    let Some(compiled) = view.compiled else {
        return Vec::new();
    };
    let d = compiled.symbols.get(def);
    let spans = with_definition
        .then_some(d.name_span)
        .into_iter()
        .chain(d.uses.iter().copied());
    spans.filter_map(|s| location(view, s)).collect()
}

/// The range of the name at `offset` if it can be renamed.
pub fn prepare_rename(view: View, offset: usize) -> Result<Range<usize>, String> {
    let def = def_at(view, offset).ok_or_else(|| not_a_name(view))?;
    let word = word_at(view.text, offset).ok_or_else(|| not_a_name(view))?;
    let kind = view.compiled.map(|c| c.symbols.get(def).kind);
    match kind {
        Some(_) => Ok(word),
        None => Err(not_a_name(view)),
    }
}

fn not_a_name(view: View) -> String {
    if view.fresh_file().is_none() {
        "the scene is being checked; try again in a moment".to_string()
    } else {
        "only names the scene defines can be renamed (constants, functions, materials, textures, groups, parameters, loop variables)".to_string()
    }
}

/// The edits that rename the name at `offset` to `new_name`: its
/// definition and every use, or why not.
pub fn rename(
    view: View,
    offset: usize,
    new_name: &str,
) -> Result<Vec<(Location, String)>, String> {
    prepare_rename(view, offset)?;
    let def = def_at(view, offset).ok_or_else(|| not_a_name(view))?;
    let compiled = view.compiled.ok_or_else(|| not_a_name(view))?;
    valid_name(new_name)?;
    let d = compiled.symbols.get(def);
    // A name in the same namespace already taken: renaming would merge them.
    let namespace = |k: SymbolKind| match k {
        SymbolKind::Material => 1,
        SymbolKind::Group => 2,
        _ => 0,
    };
    if let Some((_, other)) = (compiled.symbols.iter())
        .find(|(id, o)| *id != def && o.name == new_name && namespace(o.kind) == namespace(d.kind))
    {
        let source = compiled.sources.get(other.name_span.file);
        let line = source.text[..other.name_span.start as usize]
            .matches('\n')
            .count()
            + 1;
        return Err(format!(
            "`{new_name}` is already defined ({}, line {line})",
            source.path.display()
        ));
    }
    // A predefined name (`x`, `pi`, `frame`) would be hidden wherever the
    // renamed one is seen, and a built-in function cannot be declared.
    if namespace(d.kind) == 0 && crate::check::PREDEFINED.contains(&new_name) {
        return Err(format!(
            "`{new_name}` is a predefined name: renaming to it would hide it where the scene uses it"
        ));
    }
    if d.kind == SymbolKind::Function
        && (crate::check::eval::FUNCTIONS.iter()).any(|(f, _)| *f == new_name)
    {
        return Err(format!("`{new_name}` is a built-in function"));
    }
    let spans = std::iter::once(d.name_span).chain(d.uses.iter().copied());
    Ok(spans
        .filter_map(|s| location(view, s))
        .map(|l| (l, new_name.to_string()))
        .collect())
}

/// Whether `name` can name something: a name, not a keyword.
fn valid_name(name: &str) -> Result<(), String> {
    let ok = name
        .chars()
        .next()
        .is_some_and(|c| c.is_alphabetic() || c == '_')
        && name.chars().all(super::tokens::is_word_char);
    if !ok {
        return Err(format!(
            "`{name}` is not a name (letters, digits and `_`, not starting with a digit)"
        ));
    }
    if crate::syntax::words::KEYWORDS.contains(&name) {
        return Err(format!("`{name}` is a keyword"));
    }
    Ok(())
}
