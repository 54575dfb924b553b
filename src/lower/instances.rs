//! Placements of groups (`instance name { … }`) expanded into the objects
//! they place: each object of a placed group (and of the groups it places
//! in turn) with the placements' transforms composed onto its own, its
//! material (or the nearest enclosing instance's, for an object that names
//! none) and the placements' motion added to its own.

use crate::check::{self, Instance, Object};
use glam::{DMat4, DVec3};

/// The scene with every instance replaced by the objects it places, or
/// `None` when it has no instance. Iterative (a chain of groups each
/// placing the one before goes as deep as the scene has groups).
pub fn flatten(scene: &check::Scene) -> Option<check::Scene> {
    if scene.instances.is_empty() {
        return None;
    }
    let mut objects = scene.objects.clone();
    // (instance, parent → world transform, the parent's world velocity,
    // the material inherited from enclosing instances).
    let mut stack: Vec<(&Instance, DMat4, DVec3, Option<usize>)> = (scene.instances.iter())
        .rev()
        .map(|i| (i, DMat4::IDENTITY, DVec3::ZERO, None))
        .collect();
    while let Some((instance, parent, parent_velocity, inherited)) = stack.pop() {
        let to_world = parent * instance.transform;
        let velocity = parent_velocity + parent.transform_vector3(instance.velocity);
        let material = instance.material.or(inherited);
        let group = &scene.groups[instance.group];
        for (object, &unmaterialled) in group.objects.iter().zip(&group.unmaterialled) {
            objects.push(Object {
                transform: to_world * object.transform,
                velocity: velocity + to_world.transform_vector3(object.velocity),
                material: match material {
                    Some(m) if unmaterialled => m,
                    _ => object.material,
                },
                ..object.clone()
            });
        }
        for inner in group.instances.iter().rev() {
            stack.push((inner, to_world, velocity, material));
        }
    }
    Some(check::Scene {
        objects,
        groups: Vec::new(),
        instances: Vec::new(),
        ..scene.clone()
    })
}
