//! Lights in groups: each top-level placement of a group adds the group's
//! lights (and those of the groups it places, through every level) to the
//! scene's lights, moved by the placements' transforms composed. Lights
//! are few and cheap, so they are placed here, once, rather than shared
//! like objects: lowering and the whole-scene checks ("no light") see
//! them as lights written at the top level.

use super::*;
use crate::check::domain::{number, MAX_MAGNITUDE};

impl Checker<'_> {
    /// Counts what one placement of the group just declared makes: its
    /// objects and lights and those of the groups it places.
    pub(super) fn count_placements(&mut self, index: usize) {
        let g = &self.groups[index];
        let (objects, lights) = (g.instances.iter()).fold((0u64, 0u64), |(o, l), i| {
            let inner = &self.groups[i.group];
            (
                o.saturating_add(inner.placed_objects),
                l.saturating_add(inner.placed_lights),
            )
        });
        let lights = lights.saturating_add(g.lights.len() as u64);
        let objects = objects.saturating_add(g.objects.len() as u64);
        // Lights count against the limit on placed objects too: a light
        // nested in groups placing groups multiplies like an object.
        self.groups[index].placed_objects = objects.saturating_add(g.lights.len() as u64);
        self.groups[index].placed_lights = lights;
    }

    /// Adds the lights a top-level `instance` places to the scene's lights,
    /// in the order written (a group's own lights, then those of the
    /// groups it places). A light moved beyond the renderer's range is an
    /// error at the instance (reported once for it).
    pub(super) fn place_lights(&mut self, instance: &Instance) {
        let mut stack = vec![(instance.group, instance.transform)];
        let mut beyond = false;
        while let Some((g, transform)) = stack.pop() {
            let group = &self.groups[g];
            if group.placed_lights == 0 {
                continue;
            }
            for (light, _) in &group.lights {
                let placed = light.placed(&transform);
                let far = placed
                    .position()
                    .is_some_and(|p| p.abs().max_element() > MAX_MAGNITUDE);
                // Kept all the same: the error stops the render, and the
                // scene is not also "without light".
                beyond |= far;
                self.lights.push((placed, instance.span));
            }
            // Popped in reverse: the first inner placement is placed first.
            for inner in group.instances.iter().rev() {
                stack.push((inner.group, transform * inner.transform));
            }
        }
        if beyond {
            self.diags.push(
                Diagnostic::error(
                    codes::OUT_OF_RANGE,
                    format!(
                        "this instance places a light beyond ±{}",
                        number(MAX_MAGNITUDE)
                    ),
                    instance.span,
                )
                .with_label("a light of the group lands out of the renderer's range")
                .with_help(
                    "the renderer computes in 32-bit floats; check the instance's transforms",
                ),
            );
        }
    }
}
