//! A block statement (`sphere { … }`, `camera { … }`, a light): checked
//! against its schema and converted into a piece of the scene.

use super::*;

impl Checker<'_> {
    /// A block statement `kind { … }`: its kind looked up in the kind
    /// table, its entries checked against the kind's schemas, and the
    /// result kept as a setting, a light or an object.
    pub(super) fn block(
        &mut self,
        kind: &Ident,
        block: &crate::syntax::ast::Block,
        span: Span,
        file: FileId,
    ) {
        let Some(row) = kinds::find(&kind.name) else {
            self.diags
                .push(kinds::unknown_statement(kind, span, Some(block)));
            self.light_with_errors |= kinds::may_be_a_light(&kind.name);
            return;
        };
        let kind_span = kind.span;
        self.env.symbols.record_block(kind_span, row.name);
        if let Some(g) = self
            .open_group
            .filter(|_| !row.is_shape() && !row.is_light())
        {
            self.diags.push(not_in_group(
                &format!("`{}`", row.name),
                kind_span,
                self.groups[g].span,
                "settings and the sky belong at the top level of the scene",
            ));
            return;
        }
        let errors_before = self.diags.errors_pushed();
        let p = Params::collect_block(
            (row.name, kind_span),
            block,
            (&row.schemas(), row.positional),
            row.takes_material(),
            (&mut self.env, &mut self.diags),
        );
        self.meant_materials.extend(p.meant_material.clone());
        let material_entries = material_entries(block);
        if !row.takes_material() {
            for (_, s) in &material_entries {
                self.diags.push(
                    Diagnostic::error(
                        codes::UNKNOWN_PARAM,
                        format!("`{}` does not take a material", row.name),
                        *s,
                    )
                    .with_label("not allowed here")
                    .with_help("materials belong to objects such as `sphere { … }`"),
                );
            }
        }
        match row.role {
            kinds::Role::Setting(setting) => self.setting(setting, &p, kind_span, span, file),
            kinds::Role::Light(convert) => {
                if let Some(l) = convert(&p, &mut self.diags) {
                    // A group's lights are the scene's once placed.
                    match self.open_group {
                        Some(g) => self.groups[g].lights.push((l, span)),
                        None => self.lights.push((l, span)),
                    }
                }
                self.light_with_errors |= self.diags.errors_pushed() > errors_before;
            }
            kinds::Role::Shape(convert) => {
                let material = self.object_material(&material_entries, span);
                // Only a file's shape has a path to resolve (Path::parent
                // is not free).
                let base = match row.params.iter().any(|p| p.ty == schema::Ty::Str) {
                    true => folder_of(&self.sources, file),
                    false => Path::new(""),
                };
                let mut input = kinds::ShapeInput {
                    r: reader::Reader {
                        p: &p,
                        diags: &mut self.diags,
                    },
                    kind: row,
                    base_dir: base,
                    files: self.files,
                };
                let mut shape = convert(&mut input);
                let mut pending = Vec::new();
                if row.param("materials").is_some() {
                    let swaps = self.swaps(block, material_entries.first().map(|m| m.1));
                    // The names not declared yet are looked up at the end
                    // even when the shape has an error (then unplaced).
                    if let Some((slots, names)) = swaps {
                        pending = names;
                        if let Some(Shape::Mesh { swaps: slot, .. }) = &mut shape {
                            *slot = slots;
                        }
                    }
                }
                let at = self.object(shape, material, &material_entries, (&p, kind_span, span));
                let Some(at) = at else {
                    // Not kept (its shape had an error): the names of its
                    // materials are still looked up, so that an unknown one
                    // is not news only once the shape is fixed.
                    let named = match material_entries.first() {
                        Some((MaterialRef::Named(name), _))
                            if material == Some(PENDING_MATERIAL) =>
                        {
                            Some((*name).clone())
                        }
                        _ => None,
                    };
                    let swapped = pending.into_iter().map(|(_, name)| name);
                    self.unplaced_materials
                        .extend(named.into_iter().chain(swapped));
                    return;
                };
                for (k, name) in pending {
                    let at = ObjectRef {
                        swap: Some(k),
                        ..at
                    };
                    self.pending_materials.push((at, name));
                }
            }
        }
    }

    /// A settings block (`render`, `camera`, `environment`, `sky`,
    /// `atmosphere`): kept,
    /// unless given before.
    fn setting(
        &mut self,
        setting: kinds::Setting,
        p: &Params,
        kind_span: Span,
        span: Span,
        file: FileId,
    ) {
        match setting {
            kinds::Setting::Render => {
                let base = folder_of(&self.sources, file);
                let settings = blocks::render_settings(p, base, &mut self.diags);
                if let Some((_, first)) = &self.render {
                    self.diags
                        .push(duplicate_block("render", kind_span, *first));
                    return;
                }
                self.ambient_span = p.get("ambient").map(|v| v.1);
                self.clamp_span = p.get("clamp").map(|v| v.1);
                self.light_samples_span = p.get("light_samples").map(|v| v.1);
                self.integrator_span = p.get("integrator").map(|v| v.1);
                self.render = Some((settings, kind_span));
            }
            kinds::Setting::Camera => {
                let cam = blocks::camera(p, span, &mut self.diags);
                if let Some(first) = self.camera_span {
                    self.diags.push(duplicate_block("camera", kind_span, first));
                    return;
                }
                self.camera_span = Some(kind_span);
                self.camera = cam;
            }
            kinds::Setting::Environment => {
                let base = folder_of(&self.sources, file);
                let environment = blocks::environment(p, base, span, &mut self.diags);
                if let Some(e) = &self.environment {
                    self.diags
                        .push(duplicate_block("environment", kind_span, e.span));
                    return;
                }
                if let Some(first) = self.infinite_light() {
                    self.diags.push(two_skies(kind_span, first));
                    return;
                }
                self.environment = environment;
            }
            kinds::Setting::Sky => {
                let sky = blocks::sky(p, span, &mut self.diags);
                if let Some(s) = &self.sky {
                    self.diags.push(duplicate_block("sky", kind_span, s.span));
                    return;
                }
                if let Some(first) = self.infinite_light() {
                    self.diags.push(two_skies(kind_span, first));
                    return;
                }
                self.sky = sky;
            }
            kinds::Setting::Atmosphere => {
                let atmosphere = blocks::atmosphere(p, span, &mut self.diags);
                if let Some(a) = &self.atmosphere {
                    self.diags
                        .push(duplicate_block("atmosphere", kind_span, a.span));
                    return;
                }
                self.atmosphere = Some(atmosphere);
            }
        }
    }

    /// An object of `shape` (when it checked) and `material`, with the
    /// block's transforms and motion: kept in the open group or the scene,
    /// at the place returned.
    fn object(
        &mut self,
        shape: Option<Shape>,
        material: Option<usize>,
        material_entries: &[(&MaterialRef, Span)],
        (p, kind_span, span): (&Params, Span, Span),
    ) -> Option<ObjectRef> {
        let transform: DMat4 = objects::transform(p, &mut self.diags);
        let velocity = objects::velocity(p);
        let (Some(shape), Some(material)) = (shape, material) else {
            return None;
        };
        if let Some(what) = shape.round_kind() {
            if let Some(d) = objects::uneven_round(p, &transform, what, span) {
                self.diags.push(d);
                return None;
            }
        }
        if matches!(shape, Shape::Plane { .. })
            && material != PENDING_MATERIAL
            && self.materials[material].is_emissive()
        {
            self.diags.push(emissive_plane(kind_span));
            return None;
        }
        let object = Object {
            shape,
            material,
            transform,
            velocity,
            span,
        };
        let at = match self.open_group {
            Some(g) => {
                let group = &mut self.groups[g];
                group.objects.push(object);
                group.unmaterialled.push(material_entries.is_empty());
                ObjectRef {
                    group: Some(g),
                    index: group.objects.len() - 1,
                    swap: None,
                }
            }
            None => {
                self.objects.push(object);
                ObjectRef {
                    group: None,
                    index: self.objects.len() - 1,
                    swap: None,
                }
            }
        };
        if material == PENDING_MATERIAL {
            if let Some((MaterialRef::Named(name), _)) = material_entries.first() {
                self.pending_materials.push((at, (*name).clone()));
            }
        }
        Some(at)
    }

    /// Resolves the material entries of an object to an index (a default one when absent).
    pub(super) fn object_material(
        &mut self,
        entries: &[(&MaterialRef, Span)],
        span: Span,
    ) -> Option<usize> {
        for (_, s) in entries.iter().skip(1) {
            self.diags.push(
                Diagnostic::error(codes::DUPLICATE_PARAM, "an object has one material", *s)
                    .with_label("second material")
                    .with_secondary(entries[0].1, "first material")
                    .with_help("remove one of them"),
            );
        }
        match entries.first() {
            // One grey material serves every object without one (a loop of
            // a million spheres made a million copies of it).
            None => Some(*self.default_material.get_or_insert_with(|| {
                self.materials.push(Material::default_at(span));
                self.materials.len() - 1
            })),
            Some((MaterialRef::Named(name), _)) => match self.material_names.get(&name.name) {
                Some(m) => {
                    self.env.record_use(m.def, name.span);
                    Some(m.index)
                }
                // Declared further on, perhaps: names of materials are
                // resolved when the whole scene has been read.
                None => Some(PENDING_MATERIAL),
            },
            Some((MaterialRef::Inline(block), s)) => {
                let p = material::collect("material", *s, block, (&mut self.env, &mut self.diags));
                self.light_with_errors |= p.refused("emission");
                let mut m = material::material(&p, None, *s, &mut self.diags);
                m.resolve_paths(folder_of(&self.sources, s.file));
                self.materials.push(m);
                Some(self.materials.len() - 1)
            }
        }
    }
}
