//! Code that did not run: an `if`'s arm not taken, a loop's body run no
//! time, a function never called. The checker runs a scene to check it,
//! so a mistake there would wait for the day that code runs (`if final {
//! … }` in a draft). What needs no values is checked here, with the errors
//! a run gives: the kinds of statements and textures, the names of
//! parameters, POV-Ray's blocks and directives, and the names, functions
//! and materials that nothing in the scene's text defines.

use super::schema::{ParamSpec, Positional, Ty, MATERIAL, SHAPE_COMMON};
use super::*;
use crate::syntax::ast::{Block, Expr, ExprKind};
use eval::Unrun;

/// What code that did not run uses by name (a name, a function, a
/// material): each is unknown if the scene's text writes it nowhere else.
#[derive(Default)]
struct Uses {
    names: Vec<Ident>,
    functions: Vec<Ident>,
    materials: Vec<Ident>,
    /// An `include` did not run: its file, never read, may define any of
    /// them.
    include: bool,
}

impl Checker<'_> {
    /// Checks the code that did not run (see the module's comment).
    pub(super) fn check_unrun(&mut self) {
        let pieces = std::mem::take(&mut self.env.unrun);
        if pieces.is_empty() {
            return;
        }
        // A `fn` in a loop defines a function per pass: called if any was.
        let functions: Vec<&Definition> = (self.env.symbols.iter())
            .map(|(_, d)| d)
            .filter(|d| d.kind == SymbolKind::Function)
            .collect();
        let called: HashSet<Span> = (functions.iter())
            .filter(|d| !d.uses.is_empty())
            .map(|d| d.span)
            .collect();
        let uncalled: HashSet<Span> = (functions.iter())
            .map(|d| d.span)
            .filter(|s| !called.contains(s))
            .collect();
        let mut uses = Uses::default();
        for piece in &pieces {
            match piece {
                // Called or not is the symbols' to say (a loop's body of
                // one `fn` statement has its span, and ran).
                Unrun::Function(span, body) if uncalled.contains(span) => names_in(body, &mut uses),
                Unrun::Function(..) => {}
                // Ran in another pass (a loop's iteration, another call):
                // checked there.
                _ if self.env.ran.contains(&piece.span()) => {}
                Unrun::Statements(_, body) => self.unrun_statements(body, &mut uses),
                Unrun::Value(value) => names_in(value, &mut uses),
            }
        }
        self.report_undefined(uses);
    }

    fn unrun_statements(&mut self, body: &[Statement], uses: &mut Uses) {
        for statement in body {
            match statement {
                Statement::Let { value, .. } | Statement::Background { value, .. } => {
                    names_in(value, uses)
                }
                Statement::For {
                    start, end, body, ..
                } => {
                    names_in(start, uses);
                    end.iter().for_each(|e| names_in(e, uses));
                    self.unrun_statements(body, uses);
                }
                Statement::If {
                    arms, otherwise, ..
                } => {
                    for (cond, body) in arms {
                        names_in(cond, uses);
                        self.unrun_statements(body, uses);
                    }
                    self.unrun_statements(otherwise.as_deref().unwrap_or_default(), uses);
                }
                Statement::Function { body, .. } => names_in(body, uses),
                Statement::Group { body, .. } => self.unrun_statements(body, uses),
                Statement::Instance { group, block, .. } => {
                    let head = ("instance", group.span);
                    self.unrun_block(head, block, (&[SHAPE_COMMON], None), true, uses);
                }
                Statement::Material { name, block, .. } => {
                    let what = format!("material {}", name.name);
                    self.unrun_material((&what, name.span), block, uses);
                }
                Statement::Texture { kind, block, .. } => self.unrun_texture(kind, block, uses),
                Statement::Block { kind, block, span } => match kinds::find(&kind.name) {
                    Some(row) => {
                        self.env.symbols.record_block(kind.span, row.name);
                        let schemas = (&row.schemas()[..], row.positional);
                        let head = (row.name, kind.span);
                        self.unrun_block(head, block, schemas, row.is_shape(), uses);
                    }
                    None => self
                        .diags
                        .push(kinds::unknown_statement(kind, *span, Some(block))),
                },
                // A kind's block that did not parse: a syntax error already.
                Statement::Foreign { name, .. } if kinds::find(&name.name).is_some() => {}
                Statement::Foreign { name, span } => {
                    self.diags.push(kinds::unknown_statement(name, *span, None))
                }
                Statement::Directive { name, .. } => self.diags.push(povray::directive(name)),
                Statement::Include { .. } => uses.include = true,
            }
        }
    }

    /// A block's entries: their names against the schemas, the textures
    /// and materials given, the names their values use.
    fn unrun_block(
        &mut self,
        head: (&str, Span),
        block: &Block,
        schemas: (&[&'static [ParamSpec]], Option<Positional>),
        takes_material: bool,
        uses: &mut Uses,
    ) {
        let checking = (&mut self.env, &mut self.diags);
        let named = Params::names_only(head, block, schemas, takes_material, checking);
        for (spec, entry) in named {
            match entry {
                // A word (`integrator path`) is not a name; a word that is
                // not one of the row's is left to the run's own message.
                Entry::Param { value, .. }
                    if matches!((&value.kind, spec.ty), (ExprKind::Name(_), Ty::Word(_))) => {}
                Entry::Param { value, .. } => names_in(value, uses),
                Entry::Texture { kind, block, .. } => self.unrun_texture(kind, block, uses),
                Entry::Stop {
                    position, color, ..
                } => {
                    names_in(position, uses);
                    names_in(color, uses);
                }
                Entry::Materials { swaps, .. } => {
                    for swap in swaps {
                        self.unrun_material_ref(&swap.material, swap.span, uses);
                    }
                }
                _ => {}
            }
        }
        if takes_material {
            for entry in &block.entries {
                if let Entry::Material { material, span } = entry {
                    self.unrun_material_ref(material, *span, uses);
                }
            }
        }
    }

    fn unrun_material_ref(&mut self, material: &MaterialRef, span: Span, uses: &mut Uses) {
        match material {
            MaterialRef::Named(name) => uses.materials.push(name.clone()),
            MaterialRef::Inline(block) => self.unrun_material(("material", span), block, uses),
        }
    }

    /// A material's block, read as `material::collect` reads it.
    fn unrun_material(&mut self, head: (&str, Span), block: &Block, uses: &mut Uses) {
        let order = (&[MATERIAL][..], material::POSITIONAL);
        self.unrun_block(head, block, order, false, uses);
    }

    /// A texture's block, read as `texture::check_texture` reads it.
    fn unrun_texture(&mut self, kind: &Ident, block: &Block, uses: &mut Uses) {
        match texture::texture_schemas(&kind.name) {
            Some(schemas) => {
                let order = (schemas, texture::povray_order(&kind.name));
                self.unrun_block((&kind.name, kind.span), block, order, false, uses);
            }
            None => self.diags.push(texture::unknown_texture(kind)),
        }
    }

    /// Reports what code that did not run uses and nothing defines: not
    /// bound when the scene ends, not built in, and written nowhere in the
    /// scene's text but there (a definition in any branch, or in a
    /// statement that did not parse, would be); nothing where an include
    /// did not run.
    fn report_undefined(&mut self, uses: Uses) {
        if uses.include {
            return;
        }
        let env = &self.env;
        let names: Vec<Ident> = (uses.names.into_iter())
            .filter(|n| !env.is_bound(&n.name) && !env.textures.contains_key(&n.name))
            .filter(|n| !env.predefined.iter().any(|(p, _)| *p == n.name))
            .collect();
        let functions: Vec<Ident> = (uses.functions.into_iter())
            .filter(|f| !env.is_bound(&f.name))
            .filter(|f| !eval::FUNCTIONS.iter().any(|(b, _)| *b == f.name))
            .collect();
        let materials: Vec<Ident> = (uses.materials.into_iter())
            .filter(|m| !self.material_names.contains_key(&m.name))
            .collect();
        let nowhere = self.written_only_at(&names);
        for n in names.iter().filter(|n| nowhere.contains(n.name.as_str())) {
            let d = eval::unknown_name(&n.name, n.span, &mut self.env);
            self.diags.push(d);
        }
        let nowhere = self.written_only_at(&functions);
        for f in functions
            .iter()
            .filter(|f| nowhere.contains(f.name.as_str()))
        {
            let d = eval::unknown_function(f, &mut self.env);
            self.diags.push(d);
        }
        let nowhere = self.written_only_at(&materials);
        for m in materials
            .iter()
            .filter(|m| nowhere.contains(m.name.as_str()))
        {
            self.unknown_material(m);
        }
    }
}

/// Every name and function an expression uses.
fn names_in(e: &Expr, uses: &mut Uses) {
    e.each_name(&mut |name, span, function| {
        let ident = Ident {
            name: name.to_string(),
            span,
        };
        match function {
            true => uses.functions.push(ident),
            false => uses.names.push(ident),
        }
    });
}

#[cfg(test)]
mod tests {
    use crate::check::check_str;
    use std::path::Path;

    const HEAD: &str = "camera { position <0, 1, 5> look_at <0, 0, 0> }\npoint_light { position <0, 5, 5> intensity rgb 30 }\nsphere { center <0, 0, 0> radius 1 }\n";

    /// The codes and messages of a scene's errors.
    fn errors(body: &str) -> Vec<String> {
        let text = format!("{HEAD}{body}");
        let checked = check_str(Path::new("scene.pts"), &text);
        (checked.diagnostics.items.iter())
            .filter(|d| d.is_error())
            .map(|d| format!("{}: {}", d.code, d.message))
            .collect()
    }

    #[test]
    fn an_arm_not_taken_is_checked_once_however_often_it_is_passed() {
        let e = errors("for i in 0..100 { if i > 1000 { sphere { center x radus 1 } } }");
        assert_eq!(
            e,
            ["pts::check::unknown_param: unknown parameter `radus` in `sphere`"]
        );
    }

    #[test]
    fn an_arm_taken_in_some_pass_is_reported_by_the_run_alone() {
        let e = errors("for i in 0..3 { if i == 1 { sphere { center x radus 1 } } }");
        assert_eq!(
            e,
            ["pts::check::unknown_param: unknown parameter `radus` in `sphere`"]
        );
        let e = errors("fn f(a) = if a > 0 { a } else { nowhere };\nlet b = f(1) + f(-1);");
        assert_eq!(e, ["pts::check::unknown_name: unknown name `nowhere`"]);
    }

    #[test]
    fn names_defined_in_any_branch_or_file_not_read_are_not_unknown() {
        // Defined in another branch, which did not run either.
        assert!(
            errors("if false { let r = 1; }\nif false { sphere { center x radius r } }").is_empty()
        );
        // An include that did not run may define anything.
        let e =
            errors("if false { include \"more.ptsi\"\n sphere { center x radius from_there } }");
        assert!(e.is_empty(), "{e:?}");
        // Words of a row (`integrator path`) and predefined names are not names.
        assert!(
            errors("if false { render { integrator path } sphere { center x * pi } }").is_empty()
        );
    }

    #[test]
    fn a_function_declared_in_a_loop_is_checked_once() {
        let e = errors("for i in 0..3 { fn _f(a) = a + nope; }");
        assert_eq!(e, ["pts::check::unknown_name: unknown name `nope`"]);
    }

    #[test]
    fn what_needs_values_is_left_to_the_run() {
        // A type error needs the value: not reported where it did not run.
        assert!(errors("if false { sphere { center x radius \"one\" } }").is_empty());
    }
}
