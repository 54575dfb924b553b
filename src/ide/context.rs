//! Where a cursor stands, read from the text alone (the last check may be
//! older than the text, and a file being typed rarely parses): at the
//! start of a statement, inside a block of some kind (with the parameters
//! it already has), at a parameter's value, in an expression, in a string
//! (after `include` or `file`) or in a comment.

use super::tokens::{tokens, Token, TokenKind};
use crate::check::kinds::{self, Kind, Role};
use crate::check::schema::{ParamSpec, MATERIAL, SHAPE_COMMON, TEXTURE_KINDS};
use std::ops::Range;

/// What a `{` opens.
#[derive(Debug, Clone, Copy)]
pub enum Opener {
    /// A block statement of a known kind (`sphere {`).
    Kind(&'static Kind),
    /// A material, named or inline (`material glass {`, `material {`).
    Material,
    /// A texture of the named kind (`diffuse checker {`, `texture oak wood {`).
    Texture(&'static str),
    /// A placement of a group (`instance chair {`).
    Instance,
    /// Statements: the body of a `for`, an `if`, a group.
    Body,
    /// Anything else (a misspelt kind, POV-Ray's `pigment {`).
    Opaque,
}

impl PartialEq for Opener {
    /// The same opener (kinds by name).
    fn eq(&self, other: &Opener) -> bool {
        match (self, other) {
            (Opener::Kind(a), Opener::Kind(b)) => a.name == b.name,
            (Opener::Texture(a), Opener::Texture(b)) => a == b,
            _ => std::mem::discriminant(self) == std::mem::discriminant(other),
        }
    }
}

impl Opener {
    /// The parameter rows a block of this opener reads, in order.
    pub fn schemas(self) -> Vec<&'static [ParamSpec]> {
        match self {
            Opener::Kind(k) if matches!(k.role, Role::Shape(_)) => vec![k.params, SHAPE_COMMON],
            Opener::Kind(k) => vec![k.params],
            Opener::Material => vec![MATERIAL],
            Opener::Texture(t) => crate::check::texture::texture_schemas(t)
                .unwrap_or(&[])
                .to_vec(),
            Opener::Instance => vec![SHAPE_COMMON],
            Opener::Body | Opener::Opaque => Vec::new(),
        }
    }

    /// The row of the parameter `name` of this opener, if it has one.
    pub fn param(self, name: &str) -> Option<&'static ParamSpec> {
        let rows = self.schemas();
        rows.into_iter()
            .flatten()
            .find(|p| p.name == name && p.povray.is_none())
    }
}

/// Where the cursor stands.
#[derive(Debug, Clone)]
pub enum Place {
    /// Where a statement may start (top level or a body).
    Statement,
    /// Among a block's entries; `given` the parameter names it has.
    Entry {
        /// What the block is.
        opener: Opener,
        /// The names of the parameters already written in it.
        given: Vec<String>,
    },
    /// After a parameter's name, where its value goes.
    Value {
        /// What the block is.
        opener: Opener,
        /// The parameter.
        param: &'static ParamSpec,
    },
    /// After `material` inside a block: a material's name (or `{`).
    MaterialName,
    /// After `instance`: a group's name.
    GroupName,
    /// In an expression (after `=`, an operator, `(` or `,`).
    Expression,
    /// Inside a string; `after` the word before it (`include`, `file`) and
    /// `opener` the block it is in.
    String {
        /// The word before the string.
        after: String,
        /// The block the string is in.
        opener: Opener,
        /// The string's text so far (without its opening quote).
        typed: String,
        /// The bytes of that text.
        range: Range<usize>,
    },
    /// In a comment: nothing to offer.
    Comment,
}

impl PartialEq for Place {
    /// The same place (parameters by name).
    fn eq(&self, other: &Place) -> bool {
        use Place::*;
        match (self, other) {
            (
                Entry {
                    opener: a,
                    given: x,
                },
                Entry {
                    opener: b,
                    given: y,
                },
            ) => a == b && x == y,
            (
                Value {
                    opener: a,
                    param: p,
                },
                Value {
                    opener: b,
                    param: q,
                },
            ) => a == b && p.name == q.name,
            (
                String {
                    after: a,
                    opener: o,
                    typed: t,
                    range: r,
                },
                String {
                    after: b,
                    opener: p,
                    typed: u,
                    range: q,
                },
            ) => a == b && o == p && t == u && r == q,
            _ => std::mem::discriminant(self) == std::mem::discriminant(other),
        }
    }
}

/// The cursor's place and the name being typed at it (empty range if none).
#[derive(Debug, Clone, PartialEq)]
pub struct Context {
    /// Where the cursor stands.
    pub place: Place,
    /// The bytes of the word being typed, which a completion replaces.
    pub typed: Range<usize>,
}

struct Frame {
    opener: Opener,
    /// Index in `toks` of the first token inside.
    first: usize,
}

/// The context at byte `offset` of `text`.
pub fn context(text: &str, offset: usize) -> Context {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let all = tokens(&text[..offset]);
    let mut typed = offset..offset;
    let mut toks: &[Token] = &all;
    if let Some(last) = all.last() {
        match last.kind {
            TokenKind::Comment
                if !text[last.range.clone()].starts_with("/*")
                    || !text[last.range.clone()].ends_with("*/")
                    || last.range.end > offset =>
            {
                return Context {
                    place: Place::Comment,
                    typed,
                };
            }
            TokenKind::String if string_open(&text[last.range.clone()]) => {
                return string_context(text, &all, typed);
            }
            TokenKind::Word if last.range.end == offset => {
                typed = last.range.clone();
                toks = &all[..all.len() - 1];
            }
            _ => {}
        }
    }
    let code: Vec<Token> = toks
        .iter()
        .filter(|t| t.kind != TokenKind::Comment)
        .cloned()
        .collect();
    let frames = frames(text, &code);
    let place = place_in(text, &code, frames.last());
    Context { place, typed }
}

/// Whether a string token is still open (no closing quote yet).
fn string_open(s: &str) -> bool {
    s.len() < 2 || !s.ends_with('"') || s.ends_with("\\\"")
}

fn string_context(text: &str, all: &[Token], typed: Range<usize>) -> Context {
    let string = all.last().map_or(0..0, |t| t.range.clone());
    let code: Vec<Token> = all[..all.len() - 1]
        .iter()
        .filter(|t| t.kind != TokenKind::Comment)
        .cloned()
        .collect();
    let after = code
        .last()
        .filter(|t| t.kind == TokenKind::Word)
        .map_or(String::new(), |t| text[t.range.clone()].to_string());
    let opener = frames(text, &code)
        .last()
        .map_or(Opener::Body, |f| f.opener);
    let range = string.start + 1..typed.end;
    Context {
        place: Place::String {
            after,
            opener,
            typed: text[range.clone()].to_string(),
            range,
        },
        typed,
    }
}

/// The open braces before the end of `code`, outermost first.
fn frames(text: &str, code: &[Token]) -> Vec<Frame> {
    let mut stack: Vec<Frame> = Vec::new();
    for (i, t) in code.iter().enumerate() {
        match &text[t.range.clone()] {
            "{" => {
                let inside = stack.last().map_or(Opener::Body, |f| f.opener);
                stack.push(Frame {
                    opener: opener(text, &code[..i], inside),
                    first: i + 1,
                });
            }
            "}" => {
                stack.pop();
            }
            _ => {}
        }
    }
    stack
}

/// What the `{` after `before` opens, inside a block of `inside`.
fn opener(text: &str, before: &[Token], inside: Opener) -> Opener {
    let word = |k: usize| {
        (before.len() >= k)
            .then(|| &before[before.len() - k])
            .filter(|t| t.kind == TokenKind::Word)
            .map(|t| &text[t.range.clone()])
    };
    let Some(w) = word(1) else {
        return Opener::Body;
    };
    if let Some(&t) = TEXTURE_KINDS.iter().find(|&&t| t == w) {
        return Opener::Texture(t);
    }
    if w == "material" {
        return Opener::Material;
    }
    match word(2) {
        Some("material") => return Opener::Material,
        Some("instance") => return Opener::Instance,
        Some("group") | Some("in") => return Opener::Body,
        _ => {}
    }
    let in_block = !matches!(inside, Opener::Body);
    match kinds::find(w) {
        Some(k) if !in_block => Opener::Kind(k),
        _ if w == "else" => Opener::Body,
        _ if in_block => Opener::Opaque,
        _ => {
            // A name at the start of a statement is a block statement of a
            // kind ptsc does not know; after `if`/`for … in` it is a body.
            let before_word = before
                .len()
                .checked_sub(2)
                .map(|k| &text[before[k].range.clone()]);
            match before_word {
                None | Some("}") | Some(";") | Some("{") => Opener::Opaque,
                _ => Opener::Body,
            }
        }
    }
}

fn place_in(text: &str, code: &[Token], frame: Option<&Frame>) -> Place {
    let opener = frame.map_or(Opener::Body, |f| f.opener);
    let inside = frame.map_or(code, |f| &code[f.first.min(code.len())..]);
    match opener {
        Opener::Body => statement_place(text, inside),
        Opener::Opaque => Place::Comment,
        _ => entry_place(text, inside, opener),
    }
}

fn statement_place(text: &str, inside: &[Token]) -> Place {
    // Only what follows the last statement boundary matters.
    match inside.last().map(|t| &text[t.range.clone()]) {
        None | Some("}") | Some(";") | Some("{") => Place::Statement,
        Some("instance") => Place::GroupName,
        Some(_) => Place::Expression,
    }
}

fn entry_place(text: &str, inside: &[Token], opener: Opener) -> Place {
    // The entries directly inside (not in nested blocks).
    let mut depth = 0i32;
    let mut direct = Vec::new();
    for t in inside {
        match &text[t.range.clone()] {
            "{" => depth += 1,
            "}" => depth -= 1,
            s if depth == 0 && t.kind == TokenKind::Word => direct.push((s, t)),
            _ => {}
        }
    }
    let given: Vec<String> = (direct.iter())
        .filter(|(s, _)| opener.param(s).is_some() || *s == "material")
        .map(|(s, _)| s.to_string())
        .collect();
    let last = inside.last();
    if let (Some(t), true) = (last, depth == 0) {
        if &text[t.range.clone()] == "material" {
            return Place::MaterialName;
        }
        if let Some(param) = (t.kind == TokenKind::Word)
            .then(|| opener.param(&text[t.range.clone()]))
            .flatten()
        {
            return Place::Value { opener, param };
        }
    }
    Place::Entry { opener, given }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(text_with_cursor: &str) -> Context {
        let offset = text_with_cursor.find('|').unwrap();
        let text = text_with_cursor.replace('|', "");
        context(&text, offset)
    }

    #[test]
    fn places() {
        assert_eq!(at("sph|").place, Place::Statement);
        assert_eq!(at("sph|").typed, 0..3);
        assert_eq!(at("for i in 0..3 { | }").place, Place::Statement);
        let Place::Entry { opener, given } = at("sphere { radius 1 ra| }").place else {
            panic!()
        };
        assert_eq!(opener, Opener::Kind(kinds::find("sphere").unwrap()));
        assert_eq!(given, ["radius"]);
        assert_eq!(at("sphere { material |").place, Place::MaterialName);
        assert_eq!(at("instance ch|").place, Place::GroupName);
        let Place::Value { param, opener } = at("material m { type |").place else {
            panic!()
        };
        assert_eq!((param.name, opener), ("type", Opener::Material));
        let Place::Entry { opener, .. } = at("sphere { material { diffuse checker { | } } }").place
        else {
            panic!()
        };
        assert_eq!(opener, Opener::Texture("checker"));
        let Place::String { after, typed, .. } = at("include \"lib/a|").place else {
            panic!()
        };
        assert_eq!((after.as_str(), typed.as_str()), ("include", "lib/a"));
        assert_eq!(at("let a = 1 + |").place, Place::Expression);
        assert_eq!(at("// sphere |").place, Place::Comment);
        assert_eq!(at("sphere { } |").place, Place::Statement);
        assert_eq!(at("if a > 1 { sp| }").place, Place::Statement);
        assert_eq!(at("pigment { co| }").place, Place::Comment);
    }
}
