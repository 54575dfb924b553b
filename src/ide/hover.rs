//! Hover: what the word under the cursor is. A parameter shows its row
//! of the kind table (type, meaning, default, range, an example), a block
//! kind its summary and parameters, a name its definition (a constant its
//! value), a built-in function its signature, a keyword its use; where a
//! diagnostic covers the cursor, its code's explanation (`ptsc explain`).

use super::context::{context, Opener, Place};
use super::docs::{param_markdown, KEYWORD_DOCS, PREDEFINED_DOCS};
use super::tokens::word_at;
use super::View;
use crate::check::eval::FUNCTION_DOCS;
use crate::check::kinds::{self, Kind};
use crate::check::schema::ParamSpec;
use crate::check::{Definition, SymbolKind};
use crate::compile::Compiled;
use std::ops::Range;

/// A hover's text and the range it is about.
#[derive(Debug, Clone, PartialEq)]
pub struct Hover {
    /// The bytes hovered (the word, or the diagnostic's span).
    pub range: Range<usize>,
    /// Markdown.
    pub markdown: String,
}

/// The hover at byte `offset` of the view's document.
pub fn hover(view: View, offset: usize) -> Option<Hover> {
    let word = word_at(view.text, offset);
    let mut sections = Vec::new();
    if let Some(range) = &word {
        if let Some(s) = about_word(view, range.clone()) {
            sections.push(s);
        }
    }
    let (explained, diag_range) = diagnostics_at(view, offset);
    sections.extend(explained);
    if sections.is_empty() {
        return None;
    }
    let range = word.or(diag_range)?;
    Some(Hover {
        range,
        markdown: sections.join("\n\n---\n\n"),
    })
}

/// What the word at `range` is.
fn about_word(view: View, range: Range<usize>) -> Option<String> {
    let word = &view.text[range.clone()];
    if let Some(file) = view.fresh_file() {
        let compiled = view.compiled?;
        let symbols = &compiled.symbols;
        if let Some(p) = symbols.param_at(file, range.start) {
            return Some(param_markdown(p.spec, &block_name(view.text, range.start)));
        }
        if let Some(def) = symbols.definition_at(file, range.start) {
            return Some(definition_markdown(compiled, symbols.get(def)));
        }
        if let Some((_, kind)) = (symbols.blocks().iter())
            .find(|(s, _)| s.file == file && s.start as usize == range.start)
        {
            return kinds::find(kind).map(kind_markdown);
        }
    }
    let place = context(view.text, range.start).place;
    let opener = match place {
        Place::Entry { opener, .. } | Place::Value { opener, .. } => Some(opener),
        _ => None,
    };
    if let Some(spec) = opener.and_then(|o| o.param(word)) {
        return Some(param_markdown(spec, &block_name(view.text, range.start)));
    }
    if place == Place::Statement {
        if let Some(kind) = kinds::find(word) {
            return Some(kind_markdown(kind));
        }
    }
    if let Some(rows) = crate::check::texture::texture_schemas(word) {
        return Some(texture_markdown(word, rows));
    }
    let after = view.text[range.end..].trim_start();
    if let Some((_, signature, doc)) = FUNCTION_DOCS.iter().find(|f| f.0 == word) {
        if after.starts_with('(') {
            return Some(format!(
                "```pts\n{signature}\n```\n\nbuilt-in function: {doc}"
            ));
        }
    }
    if let Some((_, doc, example)) = KEYWORD_DOCS.iter().find(|k| k.0 == word) {
        return Some(format!(
            "**{word}** (keyword) — {doc}\n\n```pts\n{example}\n```"
        ));
    }
    if let Some(def) = view.compiled.and_then(|c| by_name(c, word)) {
        return Some(definition_markdown(view.compiled?, def));
    }
    if let Some((_, doc)) = PREDEFINED_DOCS.iter().find(|p| p.0 == word) {
        return Some(format!("**{word}** (predefined) — {doc}"));
    }
    None
}

/// The definition of `name` in a check, preferring constants and
/// functions over loop variables and parameters.
pub fn by_name<'c>(compiled: &'c Compiled, name: &str) -> Option<&'c Definition> {
    let defs = compiled
        .symbols
        .iter()
        .map(|(_, d)| d)
        .filter(|d| d.name == name);
    defs.min_by_key(|d| matches!(d.kind, SymbolKind::Parameter | SymbolKind::LoopVariable))
}

/// The name of the block around `offset` (for "in `sphere`").
fn block_name(text: &str, offset: usize) -> String {
    match context(text, offset).place {
        Place::Entry { opener, .. } | Place::Value { opener, .. } => match opener {
            Opener::Kind(k) => k.name.to_string(),
            Opener::Material => "material".to_string(),
            Opener::Texture(t) => t.to_string(),
            Opener::Instance => "instance".to_string(),
            _ => "block".to_string(),
        },
        _ => "block".to_string(),
    }
}

/// A block kind: its summary and its parameters (those check's help
/// lists, `material` included where the block takes one).
pub fn kind_markdown(kind: &'static Kind) -> String {
    let mut out = format!("**{}** — {}", kind.name, kind.summary);
    out.push_str(&param_list(kind.accepted()));
    out
}

fn texture_markdown(name: &str, rows: &[&'static [ParamSpec]]) -> String {
    let names = (rows.iter().copied().flatten())
        .filter(|p| p.povray.is_none())
        .map(|p| p.name);
    format!("**{name}** (texture){}", param_list(names.collect()))
}

fn param_list(names: Vec<&str>) -> String {
    let names: Vec<String> = names.iter().map(|n| format!("`{n}`")).collect();
    if names.is_empty() {
        String::new()
    } else {
        format!("\n\nparameters: {}", names.join(", "))
    }
}

/// A name's definition: what it is, its value or statement, where.
pub fn definition_markdown(compiled: &Compiled, def: &Definition) -> String {
    let what = match def.kind {
        SymbolKind::Constant => "constant",
        SymbolKind::Function => "function",
        SymbolKind::Parameter => "function parameter",
        SymbolKind::LoopVariable => "loop variable",
        SymbolKind::Texture => "texture",
        SymbolKind::Material => "material",
        SymbolKind::Group => "group",
    };
    let source = compiled.sources.get(def.span.file);
    let statement = source
        .text
        .get(def.span.start as usize..def.span.end as usize)
        .unwrap_or("");
    let mut out = format!("**{}** ({what})", def.name);
    if let Some(v) = &def.value {
        out.push_str(&format!(" = `{v}`"));
    }
    if matches!(def.kind, SymbolKind::Parameter | SymbolKind::LoopVariable) {
        // The statement is the whole function or loop: its first line says enough.
        let line = statement.lines().next().unwrap_or("");
        out.push_str(&format!("\n\n```pts\n{}\n```", shorten(line, 1)));
    } else {
        out.push_str(&format!("\n\n```pts\n{}\n```", shorten(statement, 12)));
    }
    let name = source
        .path
        .file_name()
        .map_or(String::new(), |n| n.to_string_lossy().into_owned());
    let line = source.text[..def.name_span.start as usize]
        .matches('\n')
        .count()
        + 1;
    out.push_str(&format!(
        "\n\ndefined in `{name}`, line {line}; {}",
        used(def.uses.len())
    ));
    out
}

/// How often a name is used, in words.
fn used(n: usize) -> String {
    match n {
        0 => "not used".to_string(),
        1 => "used once".to_string(),
        n => format!("used {n} times"),
    }
}

/// At most `lines` lines of `text`, each at most 120 characters.
fn shorten(text: &str, lines: usize) -> String {
    let mut out: Vec<String> = (text.lines().take(lines))
        .map(|l| {
            if l.chars().count() > 120 {
                format!("{}…", l.chars().take(120).collect::<String>())
            } else {
                l.to_string()
            }
        })
        .collect();
    if text.lines().count() > lines {
        out.push("…".to_string());
    }
    out.join("\n")
}

/// The explanations of the diagnostics whose span covers `offset` in the
/// view's document (of a check of the text held), and the first's range.
fn diagnostics_at(view: View, offset: usize) -> (Vec<String>, Option<Range<usize>>) {
    let (Some(file), Some(compiled)) = (view.fresh_file(), view.compiled) else {
        return (Vec::new(), None);
    };
    let mut out = Vec::new();
    let mut range = None;
    for d in &compiled.diagnostics.items {
        let Some(span) = d.span.filter(|s| s.file == file) else {
            continue;
        };
        let (start, end) = (span.start as usize, span.end as usize);
        if start <= offset && offset <= end.max(start + 1) {
            if let Some(entry) = crate::diag::codes::lookup(d.code) {
                let text = format!(
                    "`{}` — {}\n\n{}",
                    entry.code, entry.title, entry.explanation
                );
                if !out.contains(&text) {
                    out.push(text);
                }
                range.get_or_insert(start..end);
            }
        }
    }
    (out, range)
}
