//! The semantic model a check leaves behind: every name the scene defines
//! (constants, functions and their parameters, loop variables, textures,
//! materials, groups) with where it is defined and every place it is used,
//! across the scene's files. The checker records a use when evaluation
//! resolves a name, so each use belongs to the definition evaluation picked
//! (shadowing included); editors read the result (hover, go to definition,
//! references, rename, outline) and the unused-name warnings are computed
//! from it. It sits below the rest of `check/`: it imports only spans.

use super::schema::ParamSpec;
use crate::source::FileId;
use crate::span::Span;
use std::collections::{HashMap, HashSet};

/// What a definition defines.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SymbolKind {
    /// `let name = …;` (or POV-Ray's `#declare name = …;`).
    Constant,
    /// `fn name(…) = …;`.
    Function,
    /// A parameter of a function, visible in its body.
    Parameter,
    /// The variable of a `for` loop, visible in its body.
    LoopVariable,
    /// `texture name KIND { … }`.
    Texture,
    /// `material name { … }`.
    Material,
    /// `group name { … }`.
    Group,
}

/// The number of a definition in its [`Symbols`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct DefId(pub u32);

/// One definition in the source: a statement run many times (in a loop,
/// an include read twice) is still one.
#[derive(Debug, Clone, PartialEq)]
pub struct Definition {
    /// What it defines.
    pub kind: SymbolKind,
    /// The name as written.
    pub name: String,
    /// The name at the definition (the identifier alone).
    pub name_span: Span,
    /// The whole statement that defines it (a parameter's or loop
    /// variable's is the function's or loop's), for outlines.
    pub span: Span,
    /// Every place a use of the name resolved to this definition, once
    /// each however often it ran; in source order once the check is over.
    /// Only what ran counts: the names in a function's body are resolved
    /// when it is called, those of an `if` arm not taken never.
    pub uses: Vec<Span>,
    /// Its lack of uses is explained otherwise, so that it is not reported
    /// unused: its value had an error, or a misspelt name was pointed to it.
    pub excused: bool,
    /// A constant's value as a scene writes it (short values only), from
    /// the first time its statement ran: what hover shows.
    pub value: Option<String>,
}

/// A parameter written in a block (`radius 1`), with the row of the
/// block's schema it is: what hover shows and completion leaves out.
#[derive(Debug, Clone, Copy)]
pub struct ParamUse {
    /// Where its name is written.
    pub name_span: Span,
    /// Its row: name, type, example, range and doc line.
    pub spec: &'static ParamSpec,
}

/// Every definition of a scene and the uses of each ([`crate::check::Checked::symbols`]).
#[derive(Debug, Default)]
pub struct Symbols {
    /// The definitions; in source order (files in the order they were read)
    /// once [`Symbols::settle`] ran.
    defs: Vec<Definition>,
    /// Each definition by the span of its name: running a statement again
    /// finds the definition it made before.
    by_name: HashMap<Span, DefId>,
    /// The uses recorded at places that may be met again (a loop's body
    /// resolves the same name at the same place at every iteration);
    /// emptied by [`Symbols::settle`].
    seen: HashSet<(Span, DefId)>,
    /// Every parameter written in a block (of a kind, a material or a
    /// texture), with its schema row; in source order once settled.
    params: Vec<ParamUse>,
    /// The parameters recorded at places that may be met again.
    params_seen: HashSet<Span>,
    /// Every block statement's kind: where its name is written and the
    /// name of its row in `check::kinds` (in source order once settled).
    blocks: Vec<(Span, &'static str)>,
}

impl Symbols {
    /// No definitions.
    pub fn new() -> Self {
        Symbols::default()
    }

    /// Records the definition of `name` written at `name_span` in the
    /// statement `span` (once however often it runs) and returns it.
    pub fn define(&mut self, kind: SymbolKind, name: &str, name_span: Span, span: Span) -> DefId {
        if let Some(&id) = self.by_name.get(&name_span) {
            return id;
        }
        let id = DefId(self.defs.len() as u32);
        self.defs.push(Definition {
            kind,
            name: name.to_string(),
            name_span,
            span,
            uses: Vec::new(),
            excused: false,
            value: None,
        });
        self.by_name.insert(name_span, id);
        id
    }

    /// Records a constant's value as written (kept from the first run).
    pub fn set_value(&mut self, def: DefId, value: impl FnOnce() -> String) {
        let slot = &mut self.defs[def.0 as usize].value;
        if slot.is_none() {
            *slot = Some(value());
        }
    }

    /// Records that the name at `at` resolved to `def` (once per place).
    /// `repeating`: the place may be met again (in a loop, a repeated
    /// include, a function's body), so that a use already recorded is
    /// looked for now, keeping the uses as many as the places. A place met
    /// once is only pushed: hashing each use of a scene written out (three
    /// names in each of 100,000 spheres) made its `ptsc check` 1.9 %
    /// slower; the rare second meeting (a file included again) is removed
    /// by `settle`.
    pub fn record_use(&mut self, def: DefId, at: Span, repeating: bool) {
        let uses = &mut self.defs[def.0 as usize].uses;
        // A loop over one use meets the same place again and again.
        if uses.last() == Some(&at) || (repeating && !self.seen.insert((at, def))) {
            return;
        }
        uses.push(at);
    }

    /// Records that the parameter written at `name_span` is the schema row
    /// `spec` (once per place; `repeating` as for [`Symbols::record_use`]).
    pub fn record_param(&mut self, name_span: Span, spec: &'static ParamSpec, repeating: bool) {
        if repeating && !self.params_seen.insert(name_span) {
            return;
        }
        self.params.push(ParamUse { name_span, spec });
    }

    /// Records that the block statement whose kind is written at
    /// `kind_span` is of the kind named `kind` (a row of `check::kinds`).
    pub fn record_block(&mut self, kind_span: Span, kind: &'static str) {
        if self.blocks.last().map(|b| b.0) != Some(kind_span) {
            self.blocks.push((kind_span, kind));
        }
    }

    /// Every block statement: where its kind is written and the kind's
    /// name, in source order.
    pub fn blocks(&self) -> &[(Span, &'static str)] {
        &self.blocks
    }

    /// Every parameter written in the scene's blocks, with its schema row,
    /// in source order.
    pub fn params(&self) -> &[ParamUse] {
        &self.params
    }

    /// The parameter whose name covers `offset` of `file`, if any.
    pub fn param_at(&self, file: FileId, offset: usize) -> Option<&ParamUse> {
        let offset = offset as u32;
        (self.params.iter()).find(|p| {
            p.name_span.file == file && p.name_span.start <= offset && offset < p.name_span.end
        })
    }

    /// Marks `def` as one not to report unused ([`Definition::excused`]).
    pub fn excuse(&mut self, def: DefId) {
        self.defs[def.0 as usize].excused = true;
    }

    /// The definition whose name is written at `name_span`, if any.
    pub fn defined_at(&self, name_span: Span) -> Option<DefId> {
        self.by_name.get(&name_span).copied()
    }

    /// Puts the definitions, and the uses of each, in source order, and
    /// drops what only recording needed. The check calls it once, last:
    /// the numbers of definitions change.
    pub fn settle(&mut self) {
        let order = |s: &Span| (s.file.0, s.start, s.end);
        self.defs.sort_by_key(|d| order(&d.name_span));
        for d in &mut self.defs {
            d.uses.sort_by_key(order);
            d.uses.dedup();
        }
        self.by_name = (self.defs.iter().enumerate())
            .map(|(i, d)| (d.name_span, DefId(i as u32)))
            .collect();
        self.seen = HashSet::new();
        // A file included twice records its parameters at each reading.
        self.params.sort_by_key(|p| order(&p.name_span));
        self.params.dedup_by_key(|p| p.name_span);
        self.params_seen = HashSet::new();
        self.blocks.sort_by_key(|b| order(&b.0));
        self.blocks.dedup_by_key(|b| b.0);
    }

    /// The definition numbered `id`.
    pub fn get(&self, id: DefId) -> &Definition {
        &self.defs[id.0 as usize]
    }

    /// How many definitions there are.
    pub fn len(&self) -> usize {
        self.defs.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.defs.is_empty()
    }

    /// Every definition with its number, in source order (after the check).
    pub fn iter(&self) -> impl Iterator<Item = (DefId, &Definition)> {
        (self.defs.iter().enumerate()).map(|(i, d)| (DefId(i as u32), d))
    }

    /// The places `def` is used, in source order (after the check).
    pub fn references(&self, def: DefId) -> &[Span] {
        &self.get(def).uses
    }

    /// The definition of the name at byte `offset` of `file`: the one
    /// defined there, or the one a use there resolves to. (A use in a file
    /// included from two loops may resolve to each loop's variable: the
    /// first in source order is given.)
    pub fn definition_at(&self, file: FileId, offset: usize) -> Option<DefId> {
        let offset = offset as u32;
        let covers = |s: &Span| s.file == file && s.start <= offset && offset < s.end;
        self.iter()
            .find(|(_, d)| covers(&d.name_span) || d.uses.iter().any(covers))
            .map(|(id, _)| id)
    }

    /// The definitions no use resolved to that the scene should hear of:
    /// constants, functions, textures and materials, neither excused nor
    /// named with a leading `_` ("unused on purpose"). Parameters, loop
    /// variables and groups are not reported.
    pub fn unused(&self) -> impl Iterator<Item = &Definition> {
        self.defs.iter().filter(|d| {
            matches!(
                d.kind,
                SymbolKind::Constant
                    | SymbolKind::Function
                    | SymbolKind::Texture
                    | SymbolKind::Material
            ) && d.uses.is_empty()
                && !d.excused
                && !d.name.starts_with('_')
        })
    }
}
