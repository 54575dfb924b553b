//! Per-block parameter schemas and the collector that checks a block's
//! entries against one: unknown, duplicate and ill-typed parameters.

use super::eval::Env;
use super::param_errors::*;
use super::schema::*;
use super::typed_value::typed_value;
use crate::diag::codes;
use crate::diag::{did_you_mean, Diagnostic, Diagnostics};
use crate::span::Span;
use crate::syntax::ast::{Block, Entry, ExprKind, Ident};
use std::borrow::Cow;

pub use super::typed_value::Val;

/// What an entry gives a parameter: a value, a texture (its kind, its
/// block, the whole entry's span) or a colour stop (read by the texture's
/// own check).
enum Source<'a> {
    Value(&'a crate::syntax::ast::Expr),
    Texture(&'a crate::syntax::ast::Ident, &'a Block, Span),
    Stop(Span),
    /// `materials { … }`, read by the mesh's statement.
    Materials(Span),
}

impl Source<'_> {
    /// Where the value is written.
    fn span(&self) -> Span {
        match self {
            Source::Value(e) => e.span,
            Source::Texture(_, _, span) | Source::Stop(span) | Source::Materials(span) => *span,
        }
    }
}

/// The texture `value` names, if it is a bare name that is not a constant
/// but a declared texture (`texture oak wood { … }`).
fn named_texture(value: &crate::syntax::ast::Expr, env: &mut Env) -> Option<super::scene::Texture> {
    let ExprKind::Name(name) = &value.kind else {
        return None;
    };
    if env.is_bound(name) {
        return None;
    }
    let (texture, def) = env.textures.get(name)?.clone();
    env.record_use(def, value.span);
    Some(texture)
}

/// The checked parameters of one block.
pub struct Params {
    /// What the block is called in messages (`sphere`, `material glass`).
    pub what: Cow<'static, str>,
    /// Where the block's keyword or name is (missing-parameter errors point there).
    pub head: Span,
    /// Well-typed single parameters. A block has a handful: a vector searched
    /// in order beats hashing (SipHash was 5 % of checking 100,000 spheres).
    values: Vec<(&'static str, (Val, Span))>,
    /// Repeatable parameters (transforms) in source order.
    pub ordered: Vec<(&'static str, Val, Span)>,
    /// Names that were given (well-typed or not), so a later "missing" is not reported twice.
    given: Vec<&'static str>,
    /// Names an unknown parameter was probably meant to be: not reported missing again.
    suggested: Vec<&'static str>,
    /// The name given to a word taken for a misspelt `material` (`materal
    /// red`): the caller counts that material as meant, not unused.
    pub meant_material: Option<crate::syntax::ast::Ident>,
}

impl Params {
    /// Checks `block` against `schema` (plus `extra`), evaluating values.
    /// Entries that are `material` references are left to the caller.
    pub fn collect(
        what: impl Into<Cow<'static, str>>,
        head: Span,
        block: &Block,
        schemas: &[&'static [ParamSpec]],
        env: &mut Env,
        diags: &mut Diagnostics,
    ) -> Params {
        Collecting::new(what.into(), head, schemas, None).run(block, env, diags)
    }

    /// [`Params::collect`] for a block statement whose kind has POV-Ray's
    /// `positional` order (its row in `check/kinds`), which the help for
    /// values without names writes out.
    /// `takes_material`: the block is an object's or an instance's, whose
    /// `material` the caller reads (named in the help for a misspelt word).
    pub fn collect_block(
        (what, head): (&'static str, Span),
        block: &Block,
        (schemas, positional): (&[&'static [ParamSpec]], Option<Positional>),
        takes_material: bool,
        (env, diags): (&mut Env, &mut Diagnostics),
    ) -> Params {
        let mut collecting = Collecting::new(what.into(), head, schemas, None);
        collecting.positional = positional;
        collecting.takes_material = takes_material;
        collecting.run(block, env, diags)
    }

    /// [`Params::collect`] for a block with POV-Ray's `positional` order
    /// (a checker's two colours, a material's colour alone) whose
    /// parameters may be given textures where `texture` checks them (a
    /// material's; `None` for a texture's own block).
    pub fn collect_ordered(
        what: impl Into<Cow<'static, str>>,
        head: Span,
        block: &Block,
        (schemas, positional): (&[&'static [ParamSpec]], Option<Positional>),
        (env, diags): (&mut Env, &mut Diagnostics),
        texture: Option<CheckTexture>,
    ) -> Params {
        let mut collecting = Collecting::new(what.into(), head, schemas, texture);
        collecting.positional = positional;
        collecting.run(block, env, diags)
    }

    /// For code that did not run: checks only the names of `block`'s
    /// entries against the schemas (as [`Params::collect_block`] does, with
    /// the same errors: unknown, refused or repeated parameters, POV-Ray's
    /// blocks), evaluating nothing; the entries that name a parameter,
    /// with its row.
    pub fn names_only<'b>(
        (what, head): (&str, Span),
        block: &'b Block,
        (schemas, positional): (&[&'static [ParamSpec]], Option<Positional>),
        takes_material: bool,
        (env, diags): (&mut Env, &mut Diagnostics),
    ) -> Vec<(&'static ParamSpec, &'b Entry)> {
        let mut collecting = Collecting::new(what.to_string().into(), head, schemas, None);
        collecting.positional = positional;
        collecting.takes_material = takes_material;
        let mut named = Vec::new();
        for entry in &block.entries {
            let (name, value) = match entry {
                Entry::Foreign { name, span } => {
                    diags.push(collecting.foreign(name, *span));
                    continue;
                }
                Entry::Param { name, value, .. } => (name, Source::Value(value)),
                Entry::Texture {
                    name,
                    kind,
                    block,
                    span,
                } => (name, Source::Texture(kind, block, *span)),
                Entry::Stop { word, span, .. } => (word, Source::Stop(*span)),
                Entry::Materials { word, span, .. } => (word, Source::Materials(*span)),
                // Read with their values (what a word takes, POV-Ray's
                // order): left to the run.
                Entry::Flag { .. } | Entry::Positional { .. } | Entry::Material { .. } => continue,
            };
            if let Some(spec) = collecting.spec(name, &value, diags) {
                env.record_param(name.span, spec);
                named.push((spec, entry));
            }
        }
        named
    }

    /// The value of an optional parameter.
    pub fn get(&self, name: &str) -> Option<&(Val, Span)> {
        self.values.iter().find(|(n, _)| *n == name).map(|(_, v)| v)
    }

    /// Whether the parameter was written (even if its value had an error).
    pub fn given(&self, name: &str) -> bool {
        self.given.contains(&name)
    }

    /// Whether the parameter `name` was written, or a word the block was
    /// told stands for it (Mitsuba's `material "Au"` for `preset`).
    pub fn meant(&self, name: &str) -> bool {
        self.given(name) || self.suggested.contains(&name)
    }

    /// Whether the parameter `name` was written but its value refused (and
    /// reported): it is there for the warnings that ask for it, so that
    /// "`gloss` has no effect without `reflection`" does not follow
    /// `reflection 1`'s type error.
    pub fn refused(&self, name: &str) -> bool {
        self.given(name) && self.get(name).is_none()
    }

    /// Whether the parameter `name` was written with anything but zero:
    /// also a value out of its range (`transmission 2`), which the reader
    /// refuses after collection and replaces by its default.
    pub fn given_nonzero(&self, name: &str) -> bool {
        match self.get(name) {
            Some((Val::Num(x), _)) => *x != 0.0,
            Some((Val::Color(c), _)) => c.iter().any(|x| *x != 0.0),
            Some(_) => true,
            None => self.given(name),
        }
    }

    /// A required parameter; reports it missing (once) if absent.
    pub fn require(
        &self,
        spec_name: &'static str,
        schema: &[ParamSpec],
        diags: &mut Diagnostics,
    ) -> Option<&(Val, Span)> {
        if let Some(v) = self.get(spec_name) {
            return Some(v);
        }
        if !self.given(spec_name) && !self.suggested.contains(&spec_name) {
            let example = schema
                .iter()
                .find(|s| s.name == spec_name)
                .map(|s| s.example)
                .unwrap_or("…");
            diags.push(
                Diagnostic::error(
                    codes::MISSING_PARAM,
                    format!("`{}` needs {} `{spec_name}`", self.what, article(spec_name)),
                    self.head,
                )
                .with_label(format!("`{spec_name}` is missing"))
                .with_help(format!("add `{spec_name} {example}` inside the braces"))
                .distinct_by(spec_name),
            );
        }
        None
    }
}

/// Checks a texture block given to a parameter (`diffuse checker { … }`):
/// the kind's name, its block and the whole entry's span.
pub type CheckTexture =
    fn(&Ident, &Block, Span, &mut Env, &mut Diagnostics) -> Option<super::scene::Texture>;

/// One block's entries being checked against its schemas.
struct Collecting<'s> {
    params: Params,
    schemas: &'s [&'static [ParamSpec]],
    /// How a texture given to a parameter is checked (`None`: the block
    /// takes no textures).
    texture: Option<CheckTexture>,
    /// Each parameter given once, where it was first given.
    first_seen: Vec<(&'static str, Span)>,
    /// POV-Ray's order of the block's positional values, if it has one.
    positional: Option<Positional>,
    /// Whether the block also takes a `material` (an object, an instance).
    takes_material: bool,
}

impl<'s> Collecting<'s> {
    fn new(
        what: Cow<'static, str>,
        head: Span,
        schemas: &'s [&'static [ParamSpec]],
        texture: Option<CheckTexture>,
    ) -> Self {
        Collecting {
            params: Params {
                what,
                head,
                values: Vec::new(),
                ordered: Vec::new(),
                given: Vec::new(),
                suggested: Vec::new(),
                meant_material: None,
            },
            schemas,
            texture,
            first_seen: Vec::new(),
            positional: None,
            takes_material: false,
        }
    }

    /// Every parameter of the schemas that is not only a refused POV-Ray
    /// word, and `material` where the block takes one.
    fn accepted(&self) -> Vec<&'static str> {
        accepted_names(self.schemas, self.takes_material)
    }

    /// The error for POV-Ray's block `name { … }` among the entries.
    fn foreign(&self, name: &Ident, span: Span) -> Diagnostic {
        let accepted = self.accepted();
        super::povray::foreign_block(&self.params.what, name, span, (self.schemas, &accepted))
    }

    /// Marks the parameter `name` (if the schemas have it) as meant: it is
    /// not reported missing after an error about it.
    fn suggest(&mut self, name: &str) {
        let all = self.schemas.iter().flat_map(|s| s.iter());
        let found = all.map(|p| p.name).find(|n| *n == name);
        self.params.suggested.extend(found);
    }

    fn run(mut self, block: &Block, env: &mut Env, diags: &mut Diagnostics) -> Params {
        for (i, entry) in block.entries.iter().enumerate() {
            let Some((name, value)) = self.source(block, i, entry, env, diags) else {
                continue;
            };
            let Some(spec) = self.spec(name, &value, diags) else {
                // An unknown, refused or repeated parameter's value is not
                // evaluated, but the names it reads are the ones in scope:
                // uses (hover, references and rename find them; a constant
                // used only there is not "unused").
                if let Source::Value(v) = &value {
                    v.each_name(&mut |name, at, _| {
                        env.lookup(name, at);
                    });
                }
                continue;
            };
            env.record_param(name.span, spec);
            let Some(val) = self.value(spec, &value, env, diags) else {
                continue;
            };
            self.store(spec, val, value.span(), diags);
        }
        self.params
    }

    /// The parameter an entry gives and its source; `None` for entries
    /// that are not parameters (a material, a POV-Ray block, flag or
    /// positional values: those reported here).
    fn source<'e>(
        &mut self,
        block: &'e Block,
        i: usize,
        entry: &'e Entry,
        env: &mut Env,
        diags: &mut Diagnostics,
    ) -> Option<(&'e Ident, Source<'e>)> {
        let what = self.params.what.clone();
        match entry {
            Entry::Foreign { name, span } => {
                diags.push(self.foreign(name, *span));
                None
            }
            // `diffuse gradient y`: `y` after a word taken as a value is
            // the rest of a POV-Ray form the word's error tells about.
            Entry::Flag { .. } if took_next_word(&block.entries, i, env).is_some() => None,
            Entry::Flag { name } => {
                let spec = (self.schemas.iter().flat_map(|s| s.iter()))
                    .find(|p| p.name == name.name && p.povray.is_none());
                diags.push(super::povray::flag(
                    &what,
                    name,
                    (spec, self.takes_material),
                    self.schemas,
                ));
                // A parameter written without its value is not missing too.
                self.suggest(&name.name);
                None
            }
            Entry::Positional { values, span } => {
                match took_next_word(&block.entries, i, env) {
                    // `no_shadow radius 1`, `diffuse color rgb 1`: the word
                    // before took the next one as its value; its error says
                    // why, and the parameter taken (POV-Ray's `location` is
                    // `position`) is given.
                    Some(taken) => {
                        self.suggest(crate::syntax::povray::parameter(taken).unwrap_or(taken))
                    }
                    None => {
                        let order = (what.as_ref(), self.positional);
                        let (d, names) =
                            super::povray::positional(order, (values, *span), self.schemas, env);
                        diags.push(d);
                        // Not reported missing too: the help names them.
                        self.params.suggested.extend_from_slice(names);
                    }
                }
                None
            }
            Entry::Param { name, value, .. } => Some((name, Source::Value(value))),
            Entry::Texture {
                name,
                kind,
                block,
                span,
            } => Some((name, Source::Texture(kind, block, *span))),
            Entry::Stop { word, span, .. } => Some((word, Source::Stop(*span))),
            Entry::Materials { word, span, .. } => Some((word, Source::Materials(*span))),
            Entry::Material { .. } => None,
        }
    }

    /// The schema row of the parameter `name`, once per block but for
    /// repeatable ones; `None` after reporting an unknown, refused or
    /// repeated parameter.
    fn spec(
        &mut self,
        name: &Ident,
        value: &Source,
        diags: &mut Diagnostics,
    ) -> Option<&'static ParamSpec> {
        let what = self.params.what.clone();
        if name.name == "material" {
            let metal = match value {
                Source::Value(e) => match &e.kind {
                    ExprKind::Str(s) => metal_preset(s),
                    _ => None,
                },
                _ => None,
            };
            diags.push(match metal {
                Some(preset) => {
                    // So the conductor is not also told it lacks one.
                    self.params.suggested.push("preset");
                    metal_as_material(name.span.join(value.span()), preset, &what)
                }
                None => not_a_material(value.span()),
            });
            return None;
        }
        let found = (self.schemas.iter().flat_map(|s| s.iter())).find(|s| s.name == name.name);
        if let Some(&ParamSpec {
            povray: Some((instead, help)),
            ..
        }) = found
        {
            self.params.suggested.push(instead);
            diags.push(
                refused_povray_word(name, &what, help, &self.accepted())
                    .with_fix(name.span, instead),
            );
            return None;
        }
        let Some(spec) = found else {
            let d = match at_infinity(&what, &name.name, name.span) {
                Some(d) => d,
                None => {
                    let (d, fix) = self.unknown_parameter(name);
                    if let (Some("material"), Source::Value(v)) = (fix, value) {
                        if let ExprKind::Name(meant) = &v.kind {
                            self.params.meant_material = Some(Ident {
                                name: meant.clone(),
                                span: v.span,
                            });
                        }
                    }
                    d
                }
            };
            diags.push(d);
            return None;
        };
        if !spec.repeat {
            if let Some((_, first)) = self.first_seen.iter().find(|(n, _)| *n == spec.name) {
                diags.push(given_twice(spec.name, &what, name.span, *first));
                return None;
            }
            self.first_seen.push((spec.name, name.span));
        }
        self.params.given.push(spec.name);
        Some(spec)
    }

    /// The error for the unknown parameter `name`: did-you-mean, or the
    /// ptsc word for a POV-Ray one, and the parameters the block accepts;
    /// with the word it was probably meant to be.
    fn unknown_parameter(&mut self, name: &Ident) -> (Diagnostic, Option<&'static str>) {
        let what = self.params.what.clone();
        if let Some(instead) = self.povray_colour(&name.name) {
            self.params.suggested.push(instead);
            let note = match self.positional {
                Some((_, note)) if !note.is_empty() => format!(" ({note})"),
                _ => String::new(),
            };
            let help = format!(
                "POV-Ray's colours of `{what}` come in order; ptsc names each: write `{instead} rgb …` here{note}"
            );
            let d = unknown_parameter(name, &what, help).with_fix(name.span, instead);
            return (d, Some(instead));
        }
        let all = self.accepted();
        let mut fix = None;
        let help = match did_you_mean(&name.name, all.iter().copied()) {
            Some(s) => {
                self.params.suggested.push(s);
                fix = Some(s);
                format!("did you mean `{s}`?")
            }
            None => {
                let hint = crate::syntax::povray::hint(&name.name);
                match crate::syntax::povray::parameter(&name.name) {
                    Some(instead) => {
                        if let Some(&known) = all.iter().find(|&&n| n == instead) {
                            self.params.suggested.push(known);
                            fix = Some(known);
                        }
                        let hint = hint.map(String::from).unwrap_or_else(|| {
                            format!("POV-Ray's `{}` is `{instead}` in ptsc", name.name)
                        });
                        format!("{hint}; `{what}` accepts {}", all.join(", "))
                    }
                    None => match hint {
                        Some(hint) => format!("{hint}; `{what}` accepts {}", all.join(", ")),
                        None => format!("`{what}` accepts {}", all.join(", ")),
                    },
                }
            }
        };
        let d = unknown_parameter(name, &what, help);
        match fix {
            Some(word) => (d.with_fix(name.span, word), fix),
            None => (d, None),
        }
    }

    /// The parameter POV-Ray's `color` (or `colour`) stands for in a block
    /// whose positional values are colours (a checker's `even`, then its
    /// `odd`; a material's `diffuse`): the first of them not given or
    /// named yet.
    fn povray_colour(&self, word: &str) -> Option<&'static str> {
        if !matches!(word, "color" | "colour") {
            return None;
        }
        let (names, _) = self.positional?;
        let colours = names.iter().filter(|&&n| {
            (self.schemas.iter().flat_map(|s| s.iter())).any(|p| p.name == n && p.ty == Ty::Color)
        });
        let p = &self.params;
        colours
            .copied()
            .find(|n| !p.given.contains(n) && !p.suggested.contains(n))
    }

    /// The value `source` gives the parameter `spec`: a value of its type
    /// or a texture where it takes one.
    fn value(
        &mut self,
        spec: &'static ParamSpec,
        source: &Source,
        env: &mut Env,
        diags: &mut Diagnostics,
    ) -> Option<Val> {
        match *source {
            // Stops are read with their texture (`check::texture`).
            Source::Stop(_) => None,
            // Resolved with the block's material (`check::block_statement`).
            Source::Materials(_) => None,
            Source::Value(value) if spec.texture => match named_texture(value, env) {
                Some(t) => Some(Val::Texture(Box::new(t))),
                None => typed_value(spec, value, env, diags),
            },
            Source::Texture(kind, block, span) if spec.texture => {
                let check = self.texture?;
                check(kind, block, span, env, diags).map(|t| Val::Texture(Box::new(t)))
            }
            Source::Value(value) => match named_texture(value, env) {
                Some(_) => {
                    diags.push(texture_not_allowed(spec, "a texture's name", value.span));
                    None
                }
                None => typed_value(spec, value, env, diags),
            },
            Source::Texture(kind, _, span) => {
                let what = format!("a `{}` texture", kind.name);
                diags.push(texture_not_allowed(spec, &what, span));
                None
            }
        }
    }

    /// Keeps `val` for `spec` once its numbers are in the parameter's range.
    fn store(&mut self, spec: &'static ParamSpec, val: Val, span: Span, diags: &mut Diagnostics) {
        let numbers: &[f64] = match &val {
            Val::Num(x) => std::slice::from_ref(x),
            Val::Vector(v) => v,
            Val::Color(c) => c,
            _ => &[],
        };
        let what = &self.params.what;
        if let Err(d) = spec.quantity.check_all(numbers, spec.name, what, span) {
            diags.push(d);
            return;
        }
        if spec.repeat {
            self.params.ordered.push((spec.name, val, span));
        } else {
            self.params.values.push((spec.name, (val, span)));
        }
    }
}

/// The word the entry before `entries[i]` took as its value, when it is
/// a bare name that means nothing (`no_shadow radius`, `diffuse color`):
/// then `entries[i]` is the rest of a POV-Ray form already reported.
fn took_next_word<'a>(entries: &'a [Entry], i: usize, env: &mut Env) -> Option<&'a str> {
    let previous = entries.get(i.checked_sub(1)?)?;
    let Entry::Param { value, .. } = previous else {
        return None;
    };
    match &value.kind {
        ExprKind::Name(n) if env.lookup(n, value.span).is_none() => Some(n),
        _ => None,
    }
}
