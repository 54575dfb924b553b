//! One function per statement kind: what each statement adds to the
//! environment or the scene.

use super::*;
use crate::syntax::ast::{Block, Expr, Ident};
use std::sync::Arc;

impl Checker<'_> {
    pub(super) fn statement(&mut self, st: &Statement, file: FileId) {
        if (self.cancel.as_ref()).is_some_and(|c| c.load(std::sync::atomic::Ordering::Relaxed)) {
            return;
        }
        // Checking a statement takes time in proportion to its text.
        if !self.charge_loop(1 + st.span().len() as u64 / STATEMENT_BYTES) {
            return;
        }
        match st {
            Statement::Let { name, value, span } => self.let_statement(name, value, *span),
            Statement::Texture {
                name,
                kind,
                block,
                span,
            } => self.texture_statement(name, kind, block, span),
            Statement::Include {
                path, path_span, ..
            } => self.include(path, *path_span, file),
            Statement::For {
                var,
                start,
                end: None,
                body,
                span,
            } => self.for_list((var, *span), start, body, file),
            Statement::For {
                var,
                start,
                end: Some(end),
                body,
                span,
            } => self.for_range((var, *span), (start, end), body, file),
            Statement::If {
                arms, otherwise, ..
            } => self.if_statement(arms, otherwise, file),
            Statement::Function {
                name,
                params,
                body,
                span,
            } => self.function_statement(name, params, body, *span),
            Statement::Group { name, body, span } => self.group(name, body, *span, file),
            Statement::Instance { group, block, span } => self.instance(group, block, *span),
            Statement::Background { value, span } => self.background_statement(value, span),
            Statement::Material { name, block, span } => self.material_statement(name, block, span),
            Statement::Block { kind, block, span } => self.block(kind, block, *span, file),
            // A kind's block that did not parse was reported as a syntax
            // error (see `syntax::parse_each`).
            Statement::Foreign { name, .. } if kinds::find(&name.name).is_some() => {}
            Statement::Foreign { name, span } => {
                self.diags.push(kinds::unknown_statement(name, *span, None));
                self.light_with_errors |= kinds::may_be_a_light(&name.name);
            }
            Statement::Directive {
                name,
                binding,
                parameters,
                span,
            } => {
                self.diags.push(povray::directive(name));
                // A `#macro`'s parameters: its body's uses of them are the
                // macro's, not unknown names.
                for p in parameters {
                    if self.name_taken(&p.name).is_none() {
                        let named = (p.name.as_str(), p.span);
                        let def = self.env.define(SymbolKind::Parameter, named, *span, None);
                        self.env.symbols.excuse(def);
                    }
                }
                // `#declare R = 1;` binds `R` as `let` would: its uses are
                // fine. A name bound before is POV-Ray's redefinition (not
                // an error there), a name without a value one whose uses
                // stay silent (`#for (I, …)`).
                match binding {
                    Some((bound, _)) if self.name_taken(&bound.name).is_some() => {}
                    Some((bound, Some(value))) => {
                        let name = bound.clone();
                        let value = value.clone();
                        let span = *span;
                        self.statement(&Statement::Let { name, value, span }, file);
                    }
                    Some((bound, None)) => {
                        let named = (bound.name.as_str(), bound.span);
                        let def = self.env.define(SymbolKind::Constant, named, *span, None);
                        self.env.symbols.excuse(def);
                    }
                    None => {}
                }
            }
        }
    }

    /// `let name = value;`: binds a constant.
    fn let_statement(&mut self, name: &Ident, value: &Expr, span: Span) {
        // A texture's name is taken too (both are read as names).
        if let Some(first) = self.name_taken(&name.name) {
            self.diags.push(defined_again(
                name,
                first,
                "constants cannot be redefined; pick another name",
            ));
            return;
        }
        if !self.loops.is_empty() {
            self.shadowed_in_loop(name, value);
        }
        let v = eval(value, &mut self.env, &mut self.diags);
        let broken = v.is_none();
        let shown = v.clone();
        let named = (name.name.as_str(), name.span);
        let def = self.env.define(SymbolKind::Constant, named, span, v);
        if let Some(v) = shown {
            self.env.symbols.set_value(def, || eval::written(&v));
        }
        if broken {
            // Uses of a broken constant stay silent; don't call it unused either.
            self.env.symbols.excuse(def);
        }
    }

    /// Warns of `let n = n + 1;` in a loop's body: a new constant that
    /// reads the outer one of its name, as a counter would, where the
    /// outer one never changes (once per statement, not per pass).
    fn shadowed_in_loop(&mut self, name: &Ident, value: &Expr) {
        let Some(outer) = self.env.visible_binding(&name.name) else {
            return;
        };
        // Each statement is looked at in its first pass only.
        if !self.shadow_examined.insert(name.span) {
            return;
        }
        let text = &self.sources.get(value.span.file).text;
        let written = text.get(value.span.start as usize..value.span.end as usize);
        if written.is_none_or(|w| !undeclared::words(w).any(|w| w == name.name)) {
            return;
        }
        let outer_at = self.env.symbols.get(outer.def).name_span;
        let was = match &outer.value {
            Some(v) => format!(
                "the outer `{}` ({} here): the loop does not change it",
                name.name,
                eval::written(v)
            ),
            None => format!("the outer `{}`: the loop does not change it", name.name),
        };
        self.diags.push(
            Diagnostic::warning(
                codes::SHADOWED_IN_LOOP,
                format!("`{}` is a new constant in each pass of the loop", name.name),
                name.span,
            )
            .with_label("declared again for this pass, from the outer one")
            .with_secondary(outer_at, was)
            .with_help(format!(
                "constants do not change: each pass computes its `{0}` from the outer `{0}`, not from the pass before, and the loop leaves the outer `{0}` as it was; compute it from the loop variable (`let {0} = start + i;`) or give it another name",
                name.name
            )),
        );
    }

    /// `texture name kind { … }`: declares a texture.
    fn texture_statement(&mut self, name: &Ident, kind: &Ident, block: &Block, span: &Span) {
        let clash = (self.env.textures.get(&name.name).map(|t| t.1))
            .or_else(|| self.env.in_current_frame(&name.name).map(|b| b.def))
            .map(|def| self.env.symbols.get(def).name_span);
        if let Some(first) = clash.filter(|&first| first != name.span) {
            self.diags.push(defined_again(
                name,
                first,
                "give each texture and constant its own name",
            ));
            return;
        }
        let texture = texture::check_texture(kind, block, *span, &mut self.env, &mut self.diags);
        if let Some(mut texture) = texture {
            texture.resolve_path(folder_of(&self.sources, span.file));
            let symbols = &mut self.env.symbols;
            let def = symbols.define(SymbolKind::Texture, &name.name, name.span, *span);
            self.env.textures.insert(name.name.clone(), (texture, def));
        }
    }

    /// `if c { … } else …`: runs the first arm whose condition holds.
    fn if_statement(
        &mut self,
        arms: &[(Expr, Vec<Statement>)],
        otherwise: &Option<Vec<Statement>>,
        file: FileId,
    ) {
        // A branch's statements run in the enclosing scope, as
        // POV-Ray's `#if`: `if final { let spp = 1024; } else { let
        // spp = 16; }` defines `spp` for what follows.
        for (k, (cond, body)) in arms.iter().enumerate() {
            match eval::condition(cond, &mut self.env, &mut self.diags) {
                Some(true) => {
                    let later = arms[k + 1..].iter().map(|(c, b)| (c.span, b.as_slice()));
                    for (cond, body) in later {
                        self.env.untaken.insert(cond);
                        self.not_run(body);
                    }
                    self.not_run(otherwise.as_deref().unwrap_or_default());
                    self.env.ran.extend(body_span(body));
                    return self.statements(body, file);
                }
                Some(false) => self.not_run(body),
                None => return,
            }
        }
        if let Some(body) = otherwise {
            self.env.ran.extend(body_span(body));
            self.statements(body, file);
        }
    }

    /// Records `body` as not run this time (kept the first time for the
    /// checks without values: `check::unrun`).
    pub(super) fn not_run(&mut self, body: &[Statement]) {
        if let Some(span) = body_span(body) {
            if self.env.untaken.insert(span) {
                (self.env.unrun).push(eval::Unrun::Statements(span, body.to_vec()));
            }
        }
    }

    /// `fn name(params) = body;`: binds a user function.
    fn function_statement(&mut self, name: &Ident, params: &[Ident], body: &Arc<Expr>, span: Span) {
        if let Some(first) = self.name_taken(&name.name) {
            if first != name.span {
                self.diags.push(defined_again(
                    name,
                    first,
                    "give each function, constant and texture its own name",
                ));
                return;
            }
        }
        if eval::FUNCTIONS.iter().any(|(f, _)| *f == name.name) {
            self.diags.push(
                Diagnostic::error(
                    codes::DUPLICATE_NAME,
                    format!("`{}` is a built-in function", name.name),
                    name.span,
                )
                .with_label("defined again here")
                .with_help(format!("pick another name, e.g. `my_{}`", name.name)),
            );
            return;
        }
        let mut seen: HashMap<&str, Span> = HashMap::new();
        for p in params {
            if let Some(first) = seen.insert(&p.name, p.span) {
                self.diags
                    .push(defined_again(p, first, "give each parameter its own name"));
                return;
            }
        }
        let symbols = &mut self.env.symbols;
        let params = (params.iter())
            .map(|p| {
                let def = symbols.define(SymbolKind::Parameter, &p.name, p.span, span);
                (p.name.clone(), def)
            })
            .collect();
        let f = eval::Function {
            name: name.name.clone(),
            params,
            body: body.clone(),
        };
        let value = Some(Value::Function(std::sync::Arc::new(f)));
        // Checked without values if it is never called (kept once).
        if self.env.functions_kept.insert(span) {
            (self.env.unrun).push(eval::Unrun::Function(span, body.clone()));
        }
        let named = (name.name.as_str(), name.span);
        self.env.define(SymbolKind::Function, named, span, value);
    }

    /// `background value`: the radiance from every direction.
    fn background_statement(&mut self, value: &Expr, span: &Span) {
        if let Some(g) = self.open_group {
            self.diags.push(not_in_group(
                "`background`",
                *span,
                self.groups[g].span,
                "settings and the sky belong at the top level of the scene",
            ));
            return;
        }
        let v = eval(value, &mut self.env, &mut self.diags);
        if let Some(first) = self.background.map(|b| b.1) {
            self.diags.push(duplicate_block("background", *span, first));
            return;
        }
        if let Some(first) = self.infinite_light() {
            self.diags.push(two_skies(*span, first));
            return;
        }
        match v {
            Some(Value::Color(c)) if c.iter().all(|x| *x >= 0.0) => {
                match domain::Quantity::Radiance.check_all(&c, "background", "", value.span) {
                    Ok(()) => self.background = Some((c, *span)),
                    Err(d) => self.diags.push(d),
                }
            }
            Some(Value::Color(_)) => self.diags.push(
                Diagnostic::error(
                    codes::OUT_OF_RANGE,
                    "the background must be non-negative",
                    value.span,
                )
                .with_label("negative radiance")
                .with_help("colour components are ≥ 0"),
            ),
            Some(other) => self.diags.push(
                Diagnostic::error(
                    codes::TYPE_MISMATCH,
                    format!("`background` expects a colour, found {}", other.type_name()),
                    value.span,
                )
                .with_label(format!("this is {}", other.type_name()))
                .with_help("write e.g. `background rgb <0.7, 0.8, 1.0>`"),
            ),
            None => {}
        }
    }

    /// `material name { … }`: declares a material.
    fn material_statement(&mut self, name: &Ident, block: &Block, span: &Span) {
        let what = format!("material {}", name.name);
        let checking = (&mut self.env, &mut self.diags);
        let p = material::collect(what, name.span, block, checking);
        // An emitter whose `emission` was refused may be the scene's light.
        self.light_with_errors |= p.refused("emission");
        for e in &block.entries {
            if let Entry::Material { span, .. } = e {
                self.diags.push(
                    Diagnostic::error(
                        codes::UNKNOWN_PARAM,
                        "a material cannot contain a material",
                        *span,
                    )
                    .with_label("not allowed inside `material`")
                    .with_help("put the material's parameters directly in its block"),
                );
            }
        }
        let mut m = material::material(&p, Some(name.name.clone()), *span, &mut self.diags);
        m.resolve_paths(folder_of(&self.sources, span.file));
        if let Some(prev) = self.material_names.get(&name.name) {
            // Loops may redeclare the same declaration; only distinct declarations clash.
            if prev.span != name.span {
                self.diags.push(
                    Diagnostic::error(
                        codes::DUPLICATE_NAME,
                        format!("material `{}` is already defined", name.name),
                        name.span,
                    )
                    .with_label("defined again here")
                    .with_secondary(prev.span, "first defined here")
                    .with_help("give each material its own name"),
                );
                return;
            }
        }
        self.materials.push(m);
        let symbols = &mut self.env.symbols;
        let def = symbols.define(SymbolKind::Material, &name.name, name.span, *span);
        self.material_names.insert(
            name.name.clone(),
            MaterialEntry {
                index: self.materials.len() - 1,
                span: name.span,
                def,
            },
        );
    }
}

/// The text a list of statements covers, from the first to the last
/// (`None`: empty).
pub(super) fn body_span(body: &[Statement]) -> Option<Span> {
    Some(body.first()?.span().join(body.last()?.span()))
}
