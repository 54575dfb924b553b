//! `group name { … }` and `instance name { … }`: groups declared once and
//! placed by transforms.

use super::*;

impl Checker<'_> {
    /// `group name { body }`: runs the body with objects and instances
    /// going to the new group, which is named once it is whole (so that
    /// placing itself is a cycle, not a placement).
    pub(super) fn group(
        &mut self,
        name: &crate::syntax::ast::Ident,
        body: &[Statement],
        span: Span,
        file: FileId,
    ) {
        if let Some(outer) = self.open_group {
            self.diags.push(not_in_group(
                "a group declaration",
                span,
                self.groups[outer].span,
                "declare groups at the top level and place one in another with `instance`",
            ));
            return;
        }
        if let Some(&(_, first, _)) = self.group_names.get(&name.name) {
            // A loop or a second include runs one declaration again: it
            // declares the same group again, once.
            if first != name.span {
                self.diags
                    .push(defined_again(name, first, "give each group its own name"));
            }
            return;
        }
        self.groups.push(Group {
            name: name.name.clone(),
            objects: Vec::new(),
            unmaterialled: Vec::new(),
            instances: Vec::new(),
            lights: Vec::new(),
            placed_objects: 0,
            placed_lights: 0,
            span: name.span,
        });
        let index = self.groups.len() - 1;
        self.open_group = Some(index);
        // The body's constants and functions are its own.
        self.env.push();
        self.statements(body, file);
        self.env.pop();
        self.open_group = None;
        self.count_placements(index);
        let symbols = &mut self.env.symbols;
        let def = symbols.define(SymbolKind::Group, &name.name, name.span, span);
        self.group_names
            .insert(name.name.clone(), (index, name.span, def));
    }

    /// `instance name { … }`: a placement of a declared group.
    pub(super) fn instance(
        &mut self,
        name: &crate::syntax::ast::Ident,
        block: &crate::syntax::ast::Block,
        span: Span,
    ) {
        let p = Params::collect_block(
            ("instance", name.span),
            block,
            (&[schema::SHAPE_COMMON], None),
            true,
            (&mut self.env, &mut self.diags),
        );
        self.meant_materials.extend(p.meant_material.clone());
        let material_entries = material_entries(block);
        let transform = objects::transform(&p, &mut self.diags);
        let velocity = objects::velocity(&p);
        let material = if material_entries.is_empty() {
            None
        } else {
            self.object_material(&material_entries, span)
        };
        let group = match self.group_names.get(&name.name) {
            Some(&(g, _, def)) => {
                self.env.record_use(def, name.span);
                g
            }
            None => {
                let open = self.open_group.map(|g| &self.groups[g]);
                if let Some(open) = open.filter(|g| g.name == name.name) {
                    self.diags.push(
                        Diagnostic::error(
                            codes::GROUP_CYCLE,
                            format!("group `{}` contains itself", name.name),
                            name.span,
                        )
                        .with_label("placed inside its own declaration")
                        .with_secondary(open.span, "declared here")
                        .with_help("a group cannot hold copies of itself; repeat parts with a `for` loop, or place another group"),
                    );
                    return;
                }
                let mut d = Diagnostic::error(
                    codes::UNKNOWN_GROUP,
                    format!("unknown group `{}`", name.name),
                    name.span,
                )
                .with_label("no group of this name");
                let names = self.group_names.keys().map(String::as_str);
                d = match (self.env).suggest(&name.name, self.group_names.len(), names) {
                    Some(s) => d.with_help(format!("did you mean `{s}`?")),
                    None => d.with_help(format!(
                        "declare it before placing it: `group {} {{ sphere {{ … }} }}`",
                        name.name
                    )),
                };
                self.diags.push(d);
                self.unknown_groups.push(name.clone());
                return;
            }
        };
        self.placed_groups.insert(group);
        if self.groups[group].is_empty() {
            self.diags.push(
                Diagnostic::warning(
                    codes::EMPTY_GROUP,
                    format!("group `{}` holds nothing", name.name),
                    name.span,
                )
                .with_label("this instance adds nothing to the image")
                .with_secondary(self.groups[group].span, "declared here")
                .with_help("put objects in the group, or remove the instance"),
            );
        }
        if let Some((MaterialRef::Named(m), _)) = material_entries.first() {
            if material == Some(PENDING_MATERIAL) {
                // Resolved at the end like an object's; instances name
                // materials declared before them (reported otherwise).
                self.diags.push(unknown_material_here(
                    m,
                    &self.material_names,
                    &mut self.env,
                ));
                return;
            }
        }
        let instance = Instance {
            group,
            transform,
            material,
            velocity,
            span,
        };
        match self.open_group {
            Some(g) => self.groups[g].instances.push(instance),
            None => {
                // Groups placing groups multiply: the objects all placements
                // make are bounded like the statements loops run.
                let more = self.groups[group].placed_objects;
                self.placed_objects = self.placed_objects.saturating_add(more);
                if self.placed_objects > MAX_PLACED_OBJECTS {
                    if !self.placements_exhausted {
                        self.placements_exhausted = true;
                        self.diags.push(
                            Diagnostic::error(
                                codes::LOOP_TOO_LONG,
                                format!(
                                    "the instances of this scene place more than {} objects in all",
                                    group_digits(MAX_PLACED_OBJECTS)
                                ),
                                span,
                            )
                            .with_label(format!(
                                "this one places {}",
                                group_digits(more)
                            ))
                            .with_help("groups that place groups multiply; place fewer, or make a large part a mesh"),
                        );
                    }
                    return;
                }
                self.place_lights(&instance);
                self.instances.push(instance)
            }
        }
    }
}
