//! The end of a check: whole-scene warnings (no light, integrator settings
//! that make no sense), the unused names (read from the symbols), the
//! camera and render defaults, duplicate removal and source order, the
//! symbols settled.

use super::unbuilt::Unbuilt;
use super::undeclared::words;
use super::*;

impl Checker<'_> {
    /// Runs the whole-scene checks and assembles the result.
    pub(super) fn finish(mut self) -> Checked {
        self.check_unrun();
        let render = self.render.take().map(|r| r.0).unwrap_or_default();
        // Warnings about the whole scene; a file that did not parse makes them noise.
        if self.syntax_failed {
            // The symbols are still what an editor reads on a broken file.
            self.pending_material_uses();
            // A broken image or mesh is a mistake of its own, not an echo
            // of the syntax error: the driver reads the files all the same.
            let unbuilt = self.unbuilt();
            return self.checked(None, Some(unbuilt));
        }
        self.resolve_pending_materials();
        for meant in std::mem::take(&mut self.meant_materials) {
            if let Some(m) = self.material_names.get(&meant.name) {
                self.env.symbols.excuse(m.def);
            }
        }
        self.defined_elsewhere();
        self.report_unused();
        let background = self.background.map(|b| b.0).unwrap_or([0.0; 3]);
        self.light_warnings(&render, background);
        self.atmosphere_warnings();
        let camera = self.camera.take();
        if self.camera_span.is_none() {
            self.diags.push(
                Diagnostic::error(
                    codes::MISSING_CAMERA,
                    "the scene has no camera",
                    Span::new(FileId(0), 0, 0),
                )
                .with_label("the scene starts here")
                .with_help("add `camera { position <0, 1, 5> look_at <0, 0, 0> }`"),
            );
        }
        let scene = match camera {
            Some(camera) if !self.diags.has_errors() => Some(Scene {
                render,
                camera,
                background,
                environment: self.environment.take(),
                sky: self.sky.take(),
                atmosphere: self.atmosphere.take(),
                materials: std::mem::take(&mut self.materials),
                objects: std::mem::take(&mut self.objects),
                lights: std::mem::take(&mut self.lights),
                groups: std::mem::take(&mut self.groups),
                instances: std::mem::take(&mut self.instances),
                default_material: self.default_material,
            }),
            _ => None,
        };
        let unbuilt = scene.is_none().then(|| self.unbuilt());
        self.checked(scene, unbuilt)
    }

    /// What the scene names for lowering to read, taken (it is not built).
    fn unbuilt(&mut self) -> Unbuilt {
        let (materials, environment) = (&mut self.materials, &mut self.environment);
        Unbuilt::take(materials, environment, (&self.objects, &self.groups))
    }

    /// The result of the check with `scene` (or, without one, what the
    /// scene names for lowering to read): the diagnostics with their
    /// chains of includes, folded and in source order, the symbols settled.
    fn checked(mut self, scene: Option<Scene>, unbuilt: Option<Unbuilt>) -> Checked {
        self.show_include_chains();
        self.diags.settle();
        self.take_back_unknown_groups();
        self.diags.sort();
        let mut symbols = self.env.symbols;
        symbols.settle();
        Checked {
            sources: self.sources,
            scene,
            diagnostics: self.diags,
            symbols,
            unbuilt,
        }
    }

    /// Whether the scene has media, as lowering finds them (an atmosphere,
    /// a null boundary, a transmissive material that scatters inside): the
    /// scenes `bdpt` and `ptlt` leave to the path integrator.
    fn has_media(&self) -> bool {
        // In f32, as lowering holds them: a coefficient too small for an
        // f32 is no medium there, nor here.
        let positive = |c: &[f64; 3]| c.iter().any(|&c| c as f32 > 0.0);
        let atmosphere = self.atmosphere.as_ref().is_some_and(|a| {
            let m = &a.medium;
            (0..3).any(|i| m.absorption[i] as f32 + m.scattering[i] as f32 != 0.0)
        });
        atmosphere
            || self.materials.iter().any(|m| {
                m.kind == crate::check::scene::MaterialKind::None
                    || (m.transmission as f32 > 0.0 && positive(&m.scattering))
            })
    }

    /// `ambient` and `clamp` do nothing under `bdpt` and `ptlt` (their
    /// strategies weigh each other; a term or a cap on one of them would
    /// bias the sum).
    fn bidirectional_warnings(&mut self) {
        let settings = [
            (
                self.ambient_span,
                "ambient",
                "adds no light under bdpt and ptlt",
            ),
            (self.clamp_span, "clamp", "caps nothing under bdpt and ptlt"),
        ];
        for (span, word, label) in settings {
            if let Some(at) = span {
                self.diags.push(
                    Diagnostic::warning(
                        codes::INTEGRATOR_SETTING,
                        format!("`{word}` has no effect with this integrator"),
                        at,
                    )
                    .with_label(label)
                    .with_help(format!(
                        "remove `{word}`, or use `integrator path`, which applies it"
                    )),
                );
            }
        }
    }

    /// An atmosphere left to size itself around a scene with an infinite
    /// plane ends at a ball near the objects: the plane's far part, the
    /// horizon, shows no haze.
    fn atmosphere_warnings(&mut self) {
        let Some(a) = &self.atmosphere else {
            return;
        };
        if a.radius.is_some() {
            return;
        }
        let plane = (self.objects.iter()).find(|o| matches!(o.shape, Shape::Plane { .. }));
        if let Some(plane) = plane {
            self.diags.push(
                Diagnostic::warning(
                    codes::NO_EFFECT,
                    "the atmosphere ends near the objects, short of this plane's horizon",
                    plane.span,
                )
                .with_label("an infinite plane")
                .with_help("without `radius`, `atmosphere` fills a ball just around the objects, the camera and the lights; give it a `radius` (and `center`) as far as the haze should reach"),
            );
        }
    }

    /// A scene lit only by point and spot lights that give the point the
    /// camera looks at almost no light: a POV-Ray habit, whose
    /// `light_source` does not fall off with distance, where ptsc's lights
    /// fall off with its square (a light of intensity 1 at 500 units gives
    /// 4·10⁻⁶ of it). Said at the light that gives the most.
    fn dim_point_lights(&mut self) {
        /// Irradiance below which a diffuse surface renders all but black.
        const DIM: f64 = 0.01;
        // (A scene with errors does not render; a light out of range is
        // one of them, and its distance no advice.)
        let Some(camera) = self.camera.as_ref().filter(|_| !self.diags.has_errors()) else {
            return;
        };
        let target = camera.look_at;
        let given = |l: &Light| match l {
            Light::Point {
                position,
                intensity,
            }
            | Light::Spot {
                position,
                intensity,
                ..
            } => {
                let d2 = (*position - target).length_squared().max(1e-12);
                Some((intensity.iter().fold(0.0f64, |a, &c| a.max(c)) / d2, d2))
            }
            Light::Directional { .. } => None,
        };
        let lit: Vec<(f64, f64, Span)> = (self.lights.iter())
            .filter_map(|(l, span)| given(l).map(|(e, d2)| (e, d2, *span)))
            .collect();
        let total: f64 = lit.iter().map(|l| l.0).sum();
        let Some(&(most, d2, span)) = lit.iter().max_by(|a, b| a.0.total_cmp(&b.0)) else {
            return;
        };
        if total >= DIM || !total.is_finite() {
            return;
        }
        self.diags.push(
            Diagnostic::warning(
                codes::DIM_LIGHT,
                "the lights give almost no light where the camera looks: the image will be nearly black",
                span,
            )
            .with_label(format!(
                "{:.1} units from the camera's `look_at`, this light gives it an irradiance of {most:.1e} (a lit surface gets about 1)",
                d2.sqrt()
            ))
            .with_help(format!(
                "point and spot lights fall off with the square of the distance (POV-Ray's `light_source` does not): `intensity rgb {}` gives about 1 there; a far sun is a `directional_light`",
                suggested_intensity(d2)
            )),
        );
    }

    /// The warnings about the scene's light and the integrator that
    /// renders it: no light at all, media that `bdpt` and `ptlt` leave to
    /// the path integrator, an ambient term under the path integrator,
    /// whitted shading that ignores the only lights.
    fn light_warnings(&mut self, render: &RenderSettings, background: [f64; 3]) {
        let root = FileId(0);
        let integrator = render.settings.integrator;
        let renders_with =
            integrator.renders_with(integrator.is_bidirectional() && self.has_media());
        // Objects of groups placed count (an instance's material makes
        // objects without one emissive too).
        let placed = |g: &usize| self.placed_groups.contains(g);
        let has_emitter = (self.objects.iter())
            .chain(
                (0..self.groups.len())
                    .filter(placed)
                    .flat_map(|g| &self.groups[g].objects),
            )
            .any(|o| self.materials[o.material].is_emissive())
            || (self.instances.iter())
                .chain(self.groups.iter().flat_map(|g| &g.instances))
                .any(|i| i.material.is_some_and(|m| self.materials[m].is_emissive()));
        let has_point_light = self.lights.iter().any(|(l, _)| match l {
            Light::Point { intensity, .. } | Light::Spot { intensity, .. } => {
                intensity.iter().any(|c| *c > 0.0)
            }
            Light::Directional { .. } => false,
        });
        let has_other_light = has_emitter
            || self.lights.iter().any(|(l, _)| match l {
                Light::Directional { irradiance, .. } => irradiance.iter().any(|c| *c > 0.0),
                _ => false,
            })
            || background.iter().any(|c| *c > 0.0)
            || self
                .environment
                .as_ref()
                .is_some_and(|e| e.intensity.iter().any(|c| *c > 0.0))
            || self
                .sky
                .as_ref()
                .is_some_and(|s| (s.intensity.iter().chain(&s.sun_intensity)).any(|c| *c > 0.0))
            // `ambient` adds light only where it is applied: not by the
            // integrators that join light paths.
            || (render.settings.ambient.max_element() > 0.0 && !renders_with.is_bidirectional());
        let has_light = has_point_light || has_other_light;
        let debug_view = render.settings.integrator.is_debug_view();
        if has_point_light && !has_other_light && !self.light_with_errors && !debug_view {
            self.dim_point_lights();
        }
        // (A light block with errors may be the light: its errors say so.)
        if !has_light && !self.light_with_errors && !debug_view {
            let at = self.camera_span.unwrap_or(Span::new(root, 0, 0));
            self.diags.push(
                Diagnostic::warning(codes::NO_LIGHT, "the scene has no light: the image will be black", at)
                    .with_label("nothing in this scene emits light")
                    .with_help("add a `point_light { … }`, a `background rgb …`, or an object with `emission` in its material"),
            );
        }
        if renders_with != integrator {
            let at = (self.integrator_span.or(self.camera_span)).unwrap_or(Span::new(root, 0, 0));
            self.diags.push(
                Diagnostic::warning(codes::INTEGRATOR_SETTING, IntegratorKind::MEDIA_LEFT_TO_PATH, at)
                    .with_label("the scene has an atmosphere, a null boundary or a scattering inside")
                    .with_help("use `integrator path` (it traces media), or leave the media out to trace light paths"),
            );
        }
        if renders_with.is_bidirectional() {
            self.bidirectional_warnings();
        }
        if renders_with == IntegratorKind::Path {
            if let Some(s) = self.ambient_span {
                self.diags.push(
                    Diagnostic::warning(codes::INTEGRATOR_SETTING, "the ambient term biases the path integrator", s)
                        .with_label("adds light that no source emits")
                        .with_help("path tracing computes indirect light itself; remove `ambient` for an unbiased image"),
                );
            }
        }
        if matches!(
            render.settings.integrator,
            IntegratorKind::Whitted | IntegratorKind::Hybrid
        ) && render.settings.light_samples == 0
            && has_emitter
            && self.lights.is_empty()
        {
            let at = self
                .light_samples_span
                .or(self.camera_span)
                .unwrap_or(Span::new(root, 0, 0));
            let mut d = Diagnostic::warning(
                codes::INTEGRATOR_SETTING,
                "whitted shading with `light_samples 0` ignores the only lights of this scene",
                at,
            )
            .with_label("no shadow rays towards area lights")
            .with_help("set `light_samples` to 1 or more in `render { … }`, or add a point, spot or directional light");
            if let Some(o) = self
                .objects
                .iter()
                .find(|o| self.materials[o.material].is_emissive())
            {
                d = d.with_secondary(o.span, "this emissive shape is such a light");
            }
            self.diags.push(d);
        }
    }

    /// Warns of every definition no use resolved to, as the symbols have
    /// it ([`Symbols::unused`]).
    fn report_unused(&mut self) {
        let written = self.written_in_untaken_code();
        let mut warnings = Vec::new();
        for d in self.env.symbols.unused() {
            let (name, span) = (&d.name, d.name_span);
            // Written where the code did not run this time: used there.
            let elsewhere =
                |at: &&(Span, usize)| at.0.file != span.file || at.1 != span.start as usize;
            if written
                .get(name.as_str())
                .is_some_and(|at| at.iter().any(|a| elsewhere(&a)))
            {
                continue;
            }
            let warning = match d.kind {
                SymbolKind::Material => Diagnostic::warning(
                    codes::UNUSED_MATERIAL,
                    format!("material `{name}` is never used"),
                    span,
                )
                .with_label("declared here")
                .with_help("remove it, or give it to an object with `material NAME`"),
                kind => Diagnostic::warning(
                    codes::UNUSED_CONSTANT,
                    match kind {
                        SymbolKind::Function => format!("function `{name}` is never called"),
                        SymbolKind::Texture => format!("texture `{name}` is never used"),
                        _ => format!("constant `{name}` is never used"),
                    },
                    span,
                )
                .with_label("defined here")
                .with_help(format!(
                    "remove it, or start its name with `_` if that is intended: `_{name}`"
                ))
                // Nothing uses it, so its definition is the whole rename.
                .with_fix(span, format!("_{name}")),
            };
            warnings.push(warning);
        }
        for w in warnings {
            self.diags.push(w);
        }
    }
}

impl Checker<'_> {
    /// The names of the unused definitions that are written in code that
    /// did not run (`Env::untaken`, and the bodies of functions never
    /// called), with where: the file's span and the word's byte offset.
    fn written_in_untaken_code(&self) -> HashMap<&str, Vec<(Span, usize)>> {
        let unused: Vec<&crate::check::symbols::Definition> = self.env.symbols.unused().collect();
        let mut written: HashMap<&str, Vec<(Span, usize)>> = HashMap::new();
        if unused.is_empty() {
            return written;
        }
        let names: HashSet<&str> = unused.iter().map(|d| d.name.as_str()).collect();
        let uncalled = (unused.iter())
            .filter(|d| d.kind == SymbolKind::Function)
            .map(|d| d.span);
        let mut spans: Vec<Span> = self.env.untaken.iter().copied().chain(uncalled).collect();
        spans.sort_by_key(|s| (s.file.0, s.start, s.end));
        let mut covered: Option<Span> = None;
        for span in spans {
            // A span inside the last one read adds no word.
            if covered.is_some_and(|c| c.file == span.file && span.end <= c.end) {
                continue;
            }
            covered = Some(span);
            let text = &self.sources.get(span.file).text;
            let Some(part) = text.get(span.start as usize..span.end as usize) else {
                continue;
            };
            for word in words(part) {
                if let Some(&name) = names.get(word) {
                    // (The word's offset in `part`, from where it starts.)
                    let at =
                        span.start as usize + (word.as_ptr() as usize - part.as_ptr() as usize);
                    written.entry(name).or_default().push((span, at));
                }
            }
        }
        written
    }

    /// On a file with a syntax error: records the uses of materials
    /// declared after them, and reports the names that cannot be declared
    /// anywhere, not even in the statements that did not parse, since the
    /// scene's text holds them only where they are used (a typo would
    /// otherwise hide behind a missing `}` elsewhere).
    fn pending_material_uses(&mut self) {
        let mut unknown = Vec::new();
        let pending = std::mem::take(&mut self.pending_materials).into_iter();
        let unplaced = std::mem::take(&mut self.unplaced_materials);
        for name in pending.map(|(_, name)| name).chain(unplaced) {
            match self.material_names.get(&name.name) {
                Some(m) => self.env.symbols.record_use(m.def, name.span, true),
                None => unknown.push(name),
            }
        }
        let nowhere = self.written_only_at(&unknown);
        for name in unknown.iter().filter(|n| nowhere.contains(n.name.as_str())) {
            self.unknown_material(name);
        }
    }

    /// On a file with a syntax error, takes back the errors of instances
    /// of undeclared groups that a statement which did not parse may
    /// declare (`let ball = sphere { … }` already has its error, which
    /// says to write `group ball { … }`). After the diagnostics settled:
    /// their folding indexes them.
    fn take_back_unknown_groups(&mut self) {
        let names = std::mem::take(&mut self.unknown_groups);
        if !self.syntax_failed || names.is_empty() {
            return;
        }
        let nowhere = self.written_only_at(&names);
        let maybe_declared: HashSet<Span> = (names.iter())
            .filter(|n| !nowhere.contains(n.name.as_str()))
            .map(|n| n.span)
            .collect();
        (self.diags.items).retain(|d| {
            d.code != codes::UNKNOWN_GROUP || !d.span.is_some_and(|s| maybe_declared.contains(&s))
        });
    }

    /// Gives the objects that named a material before its declaration
    /// their material, and reports the names never declared.
    fn resolve_pending_materials(&mut self) {
        for name in std::mem::take(&mut self.unplaced_materials) {
            match self.material_names.get(&name.name) {
                Some(m) => self.env.symbols.record_use(m.def, name.span, true),
                None => self.unknown_material(&name),
            }
        }
        for (at, name) in std::mem::take(&mut self.pending_materials) {
            let objects = match at.group {
                Some(g) => &mut self.groups[g].objects,
                None => &mut self.objects,
            };
            let object = &mut objects[at.index];
            if let Some(m) = self.material_names.get(&name.name) {
                let index = m.index;
                // The objects of a loop name it at one place, once per iteration.
                self.env.symbols.record_use(m.def, name.span, true);
                if let Some(k) = at.swap {
                    swaps::set(object, k, index);
                    continue;
                }
                object.material = index;
                if matches!(object.shape, Shape::Plane { .. })
                    && self.materials[index].is_emissive()
                {
                    self.diags.push(emissive_plane(object.span));
                }
                continue;
            }
            // The scene has an error now; the object still needs a valid index.
            let span = object.span;
            let material = *self.default_material.get_or_insert_with(|| {
                self.materials.push(Material::default_at(span));
                self.materials.len() - 1
            });
            let object = match at.group {
                Some(g) => &mut self.groups[g].objects[at.index],
                None => &mut self.objects[at.index],
            };
            match at.swap {
                Some(k) => swaps::set(object, k, material),
                None => object.material = material,
            }
            self.unknown_material(&name);
        }
    }
}

/// The intensity that gives an irradiance of about 1 at distance² `d2`,
/// as a scene would write it: whole below a million, else in e-notation.
fn suggested_intensity(d2: f64) -> String {
    match d2.max(1.0) {
        i if i < 1e6 => format!("{:.0}", i.round()),
        i => format!("{i:.1e}"),
    }
}
