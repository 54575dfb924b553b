//! The end of a check: whole-scene warnings (no light, unused materials and
//! constants, integrator settings that make no sense), the camera and render
//! defaults, duplicate removal and source order.

use super::*;

impl Checker {
    /// Runs the whole-scene checks and assembles the result.
    pub(super) fn finish(mut self) -> Checked {
        let root = FileId(0);
        let render = self.render.take().map(|r| r.0).unwrap_or_default();
        // Warnings about the whole scene; a file that did not parse makes them noise.
        if self.syntax_failed {
            dedup(&mut self.diags);
            self.diags.sort();
            return Checked {
                sources: self.sources,
                scene: None,
                diagnostics: self.diags,
            };
        }
        for (name, span) in &self.lets {
            // A leading `_` says "unused on purpose".
            if !self.env.used.contains(span) && !name.starts_with('_') {
                self.diags.push(
                    Diagnostic::warning(
                        codes::UNUSED_CONSTANT,
                        format!("constant `{name}` is never used"),
                        *span,
                    )
                    .with_label("defined here")
                    .with_help(format!(
                        "remove it, or start its name with `_` if that is intended: `_{name}`"
                    )),
                );
            }
        }
        let mut unused: Vec<(&String, &MaterialEntry)> = self
            .material_names
            .iter()
            .filter(|(n, m)| !self.used_materials.contains(&m.index) && !n.starts_with('_'))
            .collect();
        unused.sort_by_key(|(_, m)| m.index);
        for (name, m) in unused {
            self.diags.push(
                Diagnostic::warning(
                    codes::UNUSED_MATERIAL,
                    format!("material `{name}` is never used"),
                    m.span,
                )
                .with_label("declared here")
                .with_help("remove it, or give it to an object with `material NAME`"),
            );
        }
        let background = self.background.map(|b| b.0).unwrap_or([0.0; 3]);
        let has_emitter = self
            .objects
            .iter()
            .any(|o| self.materials[o.material].is_emissive());
        let has_light = has_emitter
            || self.lights.iter().any(|(l, _)| match l {
                Light::Point { intensity, .. } | Light::Spot { intensity, .. } => {
                    intensity.iter().any(|c| *c > 0.0)
                }
                Light::Directional { irradiance, .. } => irradiance.iter().any(|c| *c > 0.0),
            })
            || background.iter().any(|c| *c > 0.0)
            || render.ambient.iter().any(|c| *c > 0.0);
        if !has_light
            && !matches!(
                render.integrator,
                IntegratorKind::Normals | IntegratorKind::Albedo | IntegratorKind::Depth
            )
        {
            let at = self.camera_span.unwrap_or(Span::new(root, 0, 0));
            self.diags.push(
                Diagnostic::warning(codes::NO_LIGHT, "the scene has no light: the image will be black", at)
                    .with_label("nothing in this scene emits light")
                    .with_help("add a `point_light { … }`, a `background rgb …`, or an object with `emission` in its material"),
            );
        }
        if render.integrator == IntegratorKind::Path {
            if let Some(s) = self.ambient_span {
                self.diags.push(
                    Diagnostic::warning(codes::INTEGRATOR_SETTING, "the ambient term biases the path integrator", s)
                        .with_label("adds light that no source emits")
                        .with_help("path tracing computes indirect light itself; remove `ambient` for an unbiased image"),
                );
            }
        }
        if matches!(
            render.integrator,
            IntegratorKind::Whitted | IntegratorKind::Hybrid
        ) && render.light_samples == 0
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
        let camera = self.camera.take();
        if self.camera_span.is_none() {
            self.diags.push(
                Diagnostic::error(
                    codes::MISSING_CAMERA,
                    "the scene has no camera",
                    Span::new(root, 0, 0),
                )
                .with_label("the scene starts here")
                .with_help("add `camera { position <0, 1, 5> look_at <0, 0, 0> }`"),
            );
        }
        dedup(&mut self.diags);
        self.diags.sort();
        let scene = if self.diags.has_errors() {
            None
        } else {
            camera.map(|camera| Scene {
                render,
                camera,
                background,
                materials: self.materials,
                objects: self.objects,
                lights: self.lights,
            })
        };
        Checked {
            sources: self.sources,
            scene,
            diagnostics: self.diags,
        }
    }
}

/// Removes repeated diagnostics (loops and includes can produce the same one many times).
pub(super) fn dedup(diags: &mut Diagnostics) {
    let mut seen = HashSet::new();
    diags
        .items
        .retain(|d| seen.insert((d.code, d.span, d.message.clone())));
}
