//! Placements of groups (`instance name { … }`). Each placement, through
//! every level of groups placing groups, becomes either objects of the
//! scene (the group's objects with the placements' transforms composed
//! onto their own, their motion added and, for an object that names no
//! material, the nearest enclosing instance's) or, for a group placed
//! several times, a placement of its shared prototype (`ir::instance`).
//!
//! A placement is expanded into objects when sharing would gain nothing:
//! its group is placed once (a single placement renders as the flat scene
//! does). Objects that cannot be shared are expanded alone, the rest of
//! their group still shared: an infinite plane (no bounds to place) and an
//! object emissive under some placement (lights are sampled as the scene's
//! primitives; a lamp's bulb is small). A lamp of a million triangles
//! placed a thousand times is refused by the primitive limit
//! (`shapes::MAX_PRIMITIVES`), not built.

use super::shapes::{self, within_domain};
use super::{geometry, LowerCache};
use crate::accel::bvh::Bvh;
use crate::accel::bvh4::Bvh4;
use crate::check::non_uniform;
use crate::check::{self, Instance, Object};
use crate::diag::{codes, Diagnostic, Diagnostics};
use crate::geometry::round::similarity_scale;
use crate::geometry::Aabb;
use crate::ir::instance::{Instances, Placement, Prototype, INHERITED};
use crate::source::Files;
use crate::span::Span;
use glam::{Affine3A, DMat4, DVec3};
use std::collections::HashMap;

/// One placement of a group's own objects, in the world.
#[derive(Debug, Clone)]
pub struct Leaf {
    /// The group placed.
    pub group: usize,
    /// Group → world.
    pub transform: DMat4,
    /// World velocity of the group's frame.
    pub velocity: DVec3,
    /// The material of its objects that name none, from the nearest
    /// enclosing instance that gives one.
    pub material: Option<usize>,
    /// The outermost instance.
    pub span: Span,
}

/// The scene with its placements sorted out.
pub struct Split {
    /// The scene with the placements that are not shared expanded into
    /// objects (`None`: the scene has no instance, nothing changes).
    pub scene: Option<check::Scene>,
    /// The placements of shared groups.
    pub shared: Vec<Leaf>,
    /// What of each group its shared placements share: its objects less
    /// those expanded alone (planes, emitters), by group index.
    pub groups: Vec<check::Group>,
}

/// Every placement of the scene's groups, through every level (iterative:
/// a chain of groups each placing the one before goes as deep as the
/// scene has groups). Only placements of groups with objects of their own.
fn leaves(scene: &check::Scene) -> Vec<Leaf> {
    let mut out = Vec::new();
    let mut stack: Vec<(&Instance, DMat4, DVec3, Option<usize>, Span)> = (scene.instances.iter())
        .rev()
        .map(|i| (i, DMat4::IDENTITY, DVec3::ZERO, None, i.span))
        .collect();
    while let Some((instance, parent, parent_velocity, inherited, span)) = stack.pop() {
        let transform = parent * instance.transform;
        let velocity = parent_velocity + parent.transform_vector3(instance.velocity);
        let material = instance.material.or(inherited);
        let group = &scene.groups[instance.group];
        if !group.objects.is_empty() {
            out.push(Leaf {
                group: instance.group,
                transform,
                velocity,
                material,
                span,
            });
        }
        for inner in group.instances.iter().rev() {
            stack.push((inner, transform, velocity, material, span));
        }
    }
    out
}

/// The material an object of a group has under a placement.
fn material_under(object: &Object, unmaterialled: bool, leaf: &Leaf) -> usize {
    match leaf.material {
        Some(m) if unmaterialled => m,
        _ => object.material,
    }
}

/// Sorts the scene's placements into objects and shared placements.
pub fn split(scene: &check::Scene) -> Split {
    if scene.instances.is_empty() {
        return Split {
            scene: None,
            shared: Vec::new(),
            groups: Vec::new(),
        };
    }
    let leaves = leaves(scene);
    let mut count: HashMap<usize, usize> = HashMap::new();
    for leaf in &leaves {
        *count.entry(leaf.group).or_default() += 1;
    }
    let alone = expanded_alone(scene, &leaves);
    let groups: Vec<check::Group> = (scene.groups.iter().zip(&alone))
        .map(|(group, alone)| shareable_part(group, alone))
        .collect();
    let mut objects = scene.objects.clone();
    let mut shared = Vec::new();
    for leaf in leaves {
        let group = &scene.groups[leaf.group];
        let sharing = count[&leaf.group] >= 2 && !groups[leaf.group].objects.is_empty();
        let parts = (group.objects.iter().zip(&group.unmaterialled)).zip(&alone[leaf.group]);
        for ((object, &unmaterialled), &alone) in parts {
            if sharing && !alone {
                continue;
            }
            objects.push(Object {
                transform: leaf.transform * object.transform,
                velocity: leaf.velocity + leaf.transform.transform_vector3(object.velocity),
                material: material_under(object, unmaterialled, &leaf),
                ..object.clone()
            });
        }
        if sharing {
            shared.push(leaf);
        }
    }
    Split {
        scene: Some(check::Scene {
            objects,
            groups: Vec::new(),
            instances: Vec::new(),
            ..scene.clone()
        }),
        shared,
        groups,
    }
}

/// For each group, which of its objects are expanded at every placement:
/// planes (no bounds to place) and objects emissive under some placement.
fn expanded_alone(scene: &check::Scene, leaves: &[Leaf]) -> Vec<Vec<bool>> {
    let mut alone: Vec<Vec<bool>> = (scene.groups.iter())
        .map(|g| {
            (g.objects.iter())
                .map(|o| matches!(o.shape, check::Shape::Plane { .. }))
                .collect()
        })
        .collect();
    for leaf in leaves {
        let group = &scene.groups[leaf.group];
        let parts = group.objects.iter().zip(&group.unmaterialled);
        for (k, (o, &u)) in parts.enumerate() {
            if scene.materials[material_under(o, u, leaf)].is_emissive() {
                alone[leaf.group][k] = true;
            }
        }
    }
    alone
}

/// A group less its objects expanded alone: what its placements share.
fn shareable_part(group: &check::Group, alone: &[bool]) -> check::Group {
    let keep = |k: &usize| !alone[*k];
    let indices: Vec<usize> = (0..group.objects.len()).filter(keep).collect();
    check::Group {
        objects: indices.iter().map(|&k| group.objects[k].clone()).collect(),
        unmaterialled: indices.iter().map(|&k| group.unmaterialled[k]).collect(),
        instances: Vec::new(),
        ..group.clone()
    }
}

/// The material of each object of a prototype ([`INHERITED`]: the
/// placement's) and the frames of its objects not at the identity.
type Parts = (Vec<u32>, Vec<(u32, Affine3A)>);

/// The shared groups' primitives (one prototype each) and their
/// placements, gathered: every problem found, nothing built.
pub struct Gathered {
    /// Each prototype's primitives and what its objects are.
    prototypes: Vec<(shapes::Gathered, Parts)>,
    /// Each prototype's bounds over the shutter, in its frame.
    bounds: Vec<Aabb>,
    /// The placements, with the world bounds of each.
    placements: Vec<(Placement, Aabb)>,
}

/// Gathers the prototypes of the shared groups placed by `shared` and
/// their placements. A problem of a group's own is reported once however
/// often it is placed; an object that only a placement's transform makes
/// unrenderable (a round shape scaled unevenly) once, at its first such
/// placement, with a note at the second.
pub fn gather(
    scene: &check::Scene,
    Split { shared, groups, .. }: &Split,
    (cache, files): (&mut LowerCache, &dyn Files),
) -> Result<Gathered, Diagnostics> {
    let mut diags = Diagnostics::new();
    let shutter = (scene.camera.shutter.0 as f32, scene.camera.shutter.1 as f32);
    // Each group's prototype, or `None` when its objects have errors.
    let mut prototype_of: HashMap<usize, Option<u32>> = HashMap::new();
    let mut out = Gathered {
        prototypes: Vec::new(),
        bounds: Vec::new(),
        placements: Vec::new(),
    };
    // The placements under which each (group, object) is scaled unevenly,
    // in the order first met.
    let mut uneven: Vec<((usize, usize), Vec<Span>)> = Vec::new();
    let mut uneven_at: HashMap<(usize, usize), usize> = HashMap::new();
    let mut uneven_count: HashMap<(usize, usize), usize> = HashMap::new();
    let cut = group_objects_where(scene, (shared, groups), check::Material::is_cut_out);
    let colored = group_objects_where(scene, (shared, groups), |m| m.vertex_color);
    for leaf in shared {
        let group = &groups[leaf.group];
        for (k, object) in group.objects.iter().enumerate() {
            // Round shapes take similarity transforms only, placed or not
            // (the flat scene could not hold an ellipsoid either); an
            // object uneven by itself is the group's own problem.
            let round = object.shape.round_kind().is_some();
            if round
                && similarity_scale(&object.transform).is_some()
                && similarity_scale(&(leaf.transform * object.transform)).is_none()
            {
                let at = *uneven_at.entry((leaf.group, k)).or_insert_with(|| {
                    uneven.push(((leaf.group, k), Vec::new()));
                    uneven.len() - 1
                });
                // Two spans are all the diagnostic shows; the count says the rest.
                let spans = &mut uneven[at].1;
                if spans.len() < 2 {
                    spans.push(leaf.span);
                }
                *uneven_count.entry((leaf.group, k)).or_default() += 1;
            }
        }
        let prototype = *prototype_of.entry(leaf.group).or_insert_with(|| {
            match shapes::gather(
                &group.objects,
                scene.camera.shutter,
                (cache, files),
                Default::default(),
                (cut[leaf.group].clone(), colored[leaf.group].clone()),
            ) {
                Ok(g) => {
                    out.bounds.push(g.bounds());
                    let parts = (object_materials(group), object_frames(group));
                    out.prototypes.push((g, parts));
                    Some(out.prototypes.len() as u32 - 1)
                }
                Err(d) => {
                    diags.extend(d);
                    None
                }
            }
        });
        let Some(prototype) = prototype else { continue };
        // Objects that name no material take the default one (each such
        // object's index is it) unless the placement gives one.
        let default = (group.objects.iter())
            .zip(&group.unmaterialled)
            .find(|(_, &u)| u)
            .map_or(0, |(o, _)| o.material);
        let placement = Placement::new(
            prototype,
            Affine3A::from_mat4(leaf.transform.as_mat4()),
            leaf.velocity.as_vec3(),
            leaf.material.unwrap_or(default) as u32,
        );
        let bounds = placement.world_bounds(out.bounds[prototype as usize], shutter);
        if !within_domain(bounds, glam::Vec3::ZERO, (0.0, 0.0)) {
            diags.push(
                Diagnostic::error(
                    codes::OUT_OF_RANGE,
                    format!(
                        "this instance reaches beyond ±{} after its transforms and motion",
                        crate::check::domain::number(crate::check::domain::MAX_MAGNITUDE)
                    ),
                    leaf.span,
                )
                .with_label("coordinates beyond the renderer's range")
                .with_help("the renderer computes in 32-bit floats; check the instance's transforms and velocity"),
            );
            continue;
        }
        out.placements.push((placement, bounds));
    }
    for ((group, k), spans) in uneven {
        let object = &groups[group].objects[k];
        let what = object.shape.round_kind().unwrap_or("shape");
        let mut d = non_uniform(object.span, what).with_secondary(spans[0], "placed here");
        if let Some(&second) = spans.get(1) {
            let label = match uneven_count[&(group, k)] {
                2 => "and here".to_string(),
                n => format!("and here ({n} placements scale it unevenly)"),
            };
            d = d.with_secondary(second, label);
        }
        diags.push(d);
    }
    if diags.has_errors() {
        return Err(diags);
    }
    Ok(out)
}

/// Each object's material in a group's prototype: its own, or
/// [`INHERITED`] when it names none.
/// Whether each object of each group has a material with `property`
/// (cut out, vertex colours) under any of its shared placements (an object
/// that names no material takes each placement's); empty for a group with
/// no such object.
fn group_objects_where(
    scene: &check::Scene,
    (shared, groups): (&[Leaf], &[check::Group]),
    property: impl Fn(&check::Material) -> bool,
) -> Vec<Vec<bool>> {
    let mut cut: Vec<Vec<bool>> = vec![Vec::new(); groups.len()];
    for leaf in shared {
        let group = &groups[leaf.group];
        let objects = group.objects.iter().zip(&group.unmaterialled);
        let here: Vec<bool> = objects
            .map(|(o, &u)| property(&scene.materials[material_under(o, u, leaf)]))
            .collect();
        if here.contains(&true) {
            let all = &mut cut[leaf.group];
            all.resize(here.len(), false);
            all.iter_mut().zip(here).for_each(|(a, h)| *a |= h);
        }
    }
    cut
}

fn object_materials(group: &check::Group) -> Vec<u32> {
    (group.objects.iter())
        .zip(&group.unmaterialled)
        .map(|(o, &u)| if u { INHERITED } else { o.material as u32 })
        .collect()
}

/// The object ← group transforms of a group's objects that have one.
fn object_frames(group: &check::Group) -> Vec<(u32, Affine3A)> {
    (group.objects.iter().enumerate())
        .filter(|(_, o)| o.transform != DMat4::IDENTITY)
        .map(|(i, o)| {
            (
                i as u32,
                Affine3A::from_mat4(o.transform.inverse().as_mat4()),
            )
        })
        .collect()
}

/// Builds the prototypes' BVHs and the BVH over the placements.
pub fn build(gathered: Gathered, cache: &mut LowerCache) -> Instances {
    let prototypes: Vec<Prototype> = (gathered.prototypes.into_iter())
        .map(|(shapes, (object_material, object_from_group))| {
            let geometry = geometry::build(shapes);
            cache.bvh_builds += 1;
            Prototype {
                prims: geometry.prims,
                prim_object: geometry.prim_object,
                wide: geometry.wide,
                normals: geometry.normals,
                uvs: geometry.uvs,
                tangents: geometry.tangents,
                colors: geometry.colors,
                bounds: geometry.bounds,
                object_material,
                object_from_group,
            }
        })
        .collect();
    let (mut placements, boxes): (Vec<Placement>, Vec<Aabb>) =
        gathered.placements.into_iter().unzip();
    if placements.is_empty() {
        return Instances::default();
    }
    // The tree numbers placements in its leaves' order.
    let mut bvh = Bvh::build(&boxes, &|_| false);
    placements = (bvh.order.iter())
        .map(|&i| placements[i as usize].clone())
        .collect();
    bvh.order = (0..placements.len() as u32).collect();
    let mut tree = Bvh4::from_binary(&bvh);
    tree.pack_triangles(|_| None);
    Instances {
        prototypes,
        placements,
        tree,
    }
}

/// The bounds of every placement over the shutter.
pub fn bounds(instances: &Instances, shutter: (f32, f32)) -> Aabb {
    (instances.placements.iter())
        .map(|p| p.world_bounds(instances.prototypes[p.prototype as usize].bounds, shutter))
        .fold(Aabb::EMPTY, Aabb::union)
}
