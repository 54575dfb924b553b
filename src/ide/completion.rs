//! Completion: what may be written at the cursor. Block kinds and
//! statement keywords where a statement starts; inside a block, its
//! parameters not given yet (with snippets for vectors and
//! colours); at a parameter's value, its words, the names of the right
//! kind (a `material` offers materials) or textures; in expressions, the
//! names in scope and the built-in functions; in a string after `include`
//! or `file`, the files of the right type beside the scene.

use super::context::{context, Opener, Place};
use super::docs::{param_markdown, param_snippet, KEYWORD_DOCS, PREDEFINED_DOCS};
use super::View;
use crate::check::eval::FUNCTION_DOCS;
use crate::check::kinds::KINDS;
use crate::check::schema::{ParamSpec, Ty, TEXTURE_KINDS};
use crate::check::SymbolKind;
use std::ops::Range;
use std::path::{Path, PathBuf};

/// What a completion item is (the editor picks its icon).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ItemKind {
    /// A keyword.
    Keyword,
    /// A block kind (`sphere`).
    Kind,
    /// A block's parameter.
    Parameter,
    /// A word a parameter takes, or a value.
    Value,
    /// A constant or a predefined name.
    Constant,
    /// A function.
    Function,
    /// A material.
    Material,
    /// A texture (named, or a kind of texture).
    Texture,
    /// A group.
    Group,
    /// A file.
    File,
    /// A folder.
    Folder,
}

/// One completion item.
#[derive(Debug, Clone, PartialEq)]
pub struct Item {
    /// What the list shows.
    pub label: String,
    /// What it is.
    pub kind: ItemKind,
    /// A short line beside it (a type, a signature).
    pub detail: Option<String>,
    /// Markdown shown when it is selected.
    pub documentation: Option<String>,
    /// What is inserted in place of `replace`.
    pub insert: String,
    /// Whether `insert` is an LSP snippet (`${1:…}` placeholders).
    pub snippet: bool,
    /// Sorting key: items sort by it, then by label.
    pub sort: String,
    /// The bytes replaced (the word being typed).
    pub replace: Range<usize>,
}

/// Lists a folder: each entry's name and whether it is a folder (the
/// server gives the disk; the library reads none itself).
pub type ListFolder<'a> = &'a dyn Fn(&Path) -> Vec<(String, bool)>;

/// The completions at byte `offset` of the view's document.
pub fn complete(view: View, offset: usize, list: ListFolder) -> Vec<Item> {
    let cx = context(view.text, offset);
    let replace = cx.typed.clone();
    let mut out = Out {
        items: Vec::new(),
        replace,
    };
    if let Some(base) = member_base(view.text, cx.typed.start) {
        member_items(&mut out, view, base);
        return out.items;
    }
    match cx.place {
        Place::Statement => statement_items(&mut out),
        Place::Entry { opener, given } => entry_items(&mut out, opener, &given),
        Place::Value { param, .. } => value_items(&mut out, view, offset, param),
        Place::MaterialName => names(&mut out, view, offset, &[SymbolKind::Material]),
        Place::GroupName => names(&mut out, view, offset, &[SymbolKind::Group]),
        Place::Expression => expression_items(&mut out, view, offset),
        Place::String {
            after,
            opener,
            typed,
            range,
        } => {
            return path_items(view.path, &after, opener, &typed, range, list);
        }
        Place::Comment => {}
    }
    // A word offered twice (`rgb` as a colour's form and as a keyword of
    // expressions) is listed once, as it was first offered.
    let mut seen = std::collections::HashSet::new();
    out.items.retain(|i| seen.insert(i.label.clone()));
    out.items
}

/// The name before `base.` when the word being typed (from `start`)
/// follows a dot after a name (`v.`; not a number's `1.`).
fn member_base(text: &str, start: usize) -> Option<&str> {
    let before = text.get(..start)?.strip_suffix('.')?;
    let from = before
        .rfind(|c: char| !super::tokens::is_word_char(c))
        .map_or(0, |i| {
            i + before[i..].chars().next().map_or(1, char::len_utf8)
        });
    let name = &before[from..];
    let first = name.chars().next()?;
    (first.is_alphabetic() || first == '_').then_some(name)
}

/// The components `base.` may name: a vector's (as many as it has) or a
/// colour's, by the constant's value; a vector's when that is not known.
fn member_items(out: &mut Out, view: View, base: &str) {
    let value = (view.compiled)
        .and_then(|c| super::hover::by_name(c, base))
        .and_then(|d| d.value.as_deref());
    // A constant's value as a scene writes it: `rgb <…>` or `<a, b, c>`.
    let (color, len) = match value {
        Some(v) if v.starts_with("rgb") => (true, None),
        Some(v) if v.starts_with('<') => (false, Some(v.matches(',').count() + 1)),
        _ => (false, None),
    };
    let names = crate::check::eval::component_names(color, len);
    let what = if color { "colour" } else { "vector" };
    for name in names {
        out.push(name, ItemKind::Value, "0", None).detail = Some(format!("a {what}'s component"));
    }
}

struct Out {
    items: Vec<Item>,
    replace: Range<usize>,
}

impl Out {
    fn push(
        &mut self,
        label: &str,
        kind: ItemKind,
        sort: &str,
        insert: Option<(String, bool)>,
    ) -> &mut Item {
        let (insert, snippet) = insert.unwrap_or_else(|| (label.to_string(), false));
        self.items.push(Item {
            label: label.to_string(),
            kind,
            detail: None,
            documentation: None,
            insert,
            snippet,
            sort: sort.to_string(),
            replace: self.replace.clone(),
        });
        self.items.last_mut().expect("just pushed")
    }
}

fn statement_items(out: &mut Out) {
    for kind in KINDS {
        let snippet = format!("{} {{\n\t$0\n}}", kind.name);
        let item = out.push(kind.name, ItemKind::Kind, "1", Some((snippet, true)));
        item.detail = Some(kind.summary.to_string());
        item.documentation = Some(super::hover::kind_markdown(kind));
    }
    for (word, doc, example) in KEYWORD_DOCS {
        let snippet = match *word {
            "let" => "let ${1:name} = ${2:0};",
            "fn" => "fn ${1:name}(${2:x}) = ${3:x};",
            "for" => "for ${1:i} in ${2:0}..${3:10} {\n\t$0\n}",
            "if" => "if ${1:condition} {\n\t$0\n}",
            "include" => "include \"$1\"",
            "material" => "material ${1:name} {\n\t$0\n}",
            "texture" => "texture ${1:name} ${2:checker} {\n\t$0\n}",
            "group" => "group ${1:name} {\n\t$0\n}",
            "instance" => "instance ${1:name} {\n\t$0\n}",
            "background" => "background rgb ${1:0.1}",
            _ => continue,
        };
        let item = out.push(
            word,
            ItemKind::Keyword,
            "0",
            Some((snippet.to_string(), true)),
        );
        item.detail = Some(doc.to_string());
        item.documentation = Some(format!("```pts\n{example}\n```"));
    }
}

fn entry_items(out: &mut Out, opener: Opener, given: &[String]) {
    let block = match opener {
        Opener::Kind(k) => k.name,
        Opener::Material => "material",
        Opener::Texture(t) => t,
        Opener::Instance => "instance",
        Opener::Body | Opener::Opaque => return,
    };
    let schemas = opener.schemas();
    for spec in (schemas.iter().copied().flatten()).filter(|p| p.povray.is_none()) {
        // A parameter given once may not be given again, nor one that does
        // the job of one given another way (check refuses both).
        let done = given.iter().any(|g| g == spec.name) && !spec.repeat;
        let excluded = (given.iter()).any(|g| crate::check::schema::excludes(spec, g, &schemas));
        if done || excluded || out.items.iter().any(|i| i.label == spec.name) {
            continue;
        }
        let item = out.push(
            spec.name,
            ItemKind::Parameter,
            "0",
            Some((param_snippet(spec), true)),
        );
        item.detail = Some(spec.ty.describe());
        item.documentation = Some(param_markdown(spec, block));
    }
    let takes_material = matches!(opener, Opener::Kind(k) if k.takes_material());
    if takes_material && !given.iter().any(|g| g == "material") {
        let item = out.push(
            "material",
            ItemKind::Parameter,
            "0",
            Some(("material ${1:name}".to_string(), true)),
        );
        item.detail = Some("a material's name or `material { … }`".to_string());
    }
}

fn value_items(out: &mut Out, view: View, offset: usize, param: &'static ParamSpec) {
    match param.ty {
        Ty::Word(words) => {
            for w in words {
                out.push(w, ItemKind::Value, "0", None).detail =
                    Some(format!("{} value", param.name));
            }
        }
        Ty::Bool => {
            out.push("true", ItemKind::Value, "0", None);
            out.push("false", ItemKind::Value, "0", None);
        }
        Ty::Color => {
            out.push(
                "rgb",
                ItemKind::Value,
                "0",
                Some(("rgb <${1:0.8}, ${2:0.8}, ${3:0.8}>".to_string(), true)),
            );
        }
        _ => {}
    }
    if param.texture || param.ty == Ty::Texture {
        for t in TEXTURE_KINDS {
            let snippet = format!("{t} {{\n\t$0\n}}");
            out.push(t, ItemKind::Texture, "1", Some((snippet, true)))
                .detail = Some("a texture".to_string());
        }
        names(out, view, offset, &[SymbolKind::Texture]);
    }
    if !matches!(param.ty, Ty::Word(_) | Ty::Bool | Ty::Str | Ty::Texture) {
        expression_items(out, view, offset);
    }
}

fn expression_items(out: &mut Out, view: View, offset: usize) {
    names(
        out,
        view,
        offset,
        &[
            SymbolKind::Constant,
            SymbolKind::Function,
            SymbolKind::Parameter,
            SymbolKind::LoopVariable,
        ],
    );
    for (name, signature, doc) in FUNCTION_DOCS {
        let snippet = format!("{name}($1)");
        let item = out.push(name, ItemKind::Function, "3", Some((snippet, true)));
        item.detail = Some(signature.to_string());
        item.documentation = Some(doc.to_string());
    }
    for (name, doc) in PREDEFINED_DOCS {
        out.push(name, ItemKind::Constant, "2", None).detail = Some(doc.to_string());
    }
    for word in ["rgb", "true", "false", "if"] {
        out.push(word, ItemKind::Keyword, "4", None);
    }
}

/// The names of `kinds` the check knows, visible at `offset` (a
/// parameter or loop variable only inside its function or loop).
fn names(out: &mut Out, view: View, offset: usize, kinds: &[SymbolKind]) {
    let Some(compiled) = view.compiled else {
        return;
    };
    let file = view.file();
    for (_, def) in compiled.symbols.iter() {
        if !kinds.contains(&def.kind) || out.items.iter().any(|i| i.label == def.name) {
            continue;
        }
        let local = matches!(def.kind, SymbolKind::Parameter | SymbolKind::LoopVariable);
        let inside = Some(def.span.file) == file
            && (def.span.start as usize..=def.span.end as usize).contains(&offset);
        if local && !inside {
            continue;
        }
        let kind = match def.kind {
            SymbolKind::Function => ItemKind::Function,
            SymbolKind::Material => ItemKind::Material,
            SymbolKind::Texture => ItemKind::Texture,
            SymbolKind::Group => ItemKind::Group,
            _ => ItemKind::Constant,
        };
        let insert =
            (def.kind == SymbolKind::Function).then(|| (format!("{}($1)", def.name), true));
        let item = out.push(&def.name, kind, "1", insert);
        item.documentation = Some(super::hover::definition_markdown(compiled, def));
        item.detail = def.value.clone();
    }
}

/// The extensions a string after `after` in `opener` names.
fn extensions(after: &str, opener: Opener) -> Option<&'static [&'static str]> {
    const IMAGES: &[&str] = &[
        "png", "jpg", "jpeg", "exr", "hdr", "pfm", "tga", "bmp", "tif", "tiff", "webp",
    ];
    match (after, opener) {
        ("include", _) => Some(&["ptsi", "pts"]),
        ("file", Opener::Kind(k)) if k.name == "mesh" => Some(&["obj", "ply"]),
        ("file", Opener::Texture(_)) | ("file", Opener::Kind(_)) => Some(IMAGES),
        _ => None,
    }
}

fn path_items(
    scene: &Path,
    after: &str,
    opener: Opener,
    typed: &str,
    range: Range<usize>,
    list: ListFolder,
) -> Vec<Item> {
    let Some(exts) = extensions(after, opener) else {
        return Vec::new();
    };
    // Only the last part of the path typed is replaced.
    let (dir_part, name_part) = typed.rsplit_once('/').map_or(("", typed), |(d, n)| (d, n));
    let replace = range.end - name_part.len()..range.end;
    let base = scene.parent().unwrap_or(Path::new(".")).join(dir_part);
    let mut items = Vec::new();
    let mut entries = list(&PathBuf::from(&base));
    entries.sort();
    for (name, is_dir) in entries {
        if name.starts_with('.') && !name_part.starts_with('.') {
            continue;
        }
        let ext = Path::new(&name)
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        if !is_dir && !ext.is_some_and(|e| exts.contains(&e.as_str())) {
            continue;
        }
        let (kind, insert, sort) = if is_dir {
            (ItemKind::Folder, format!("{name}/"), "1")
        } else {
            (ItemKind::File, name.clone(), "0")
        };
        items.push(Item {
            label: insert.clone(),
            kind,
            detail: None,
            documentation: None,
            insert,
            snippet: false,
            sort: sort.to_string(),
            replace: replace.clone(),
        });
    }
    items
}
