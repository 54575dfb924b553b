//! Instancing: a group placed several times is lowered once, in its own
//! frame, as a [`Prototype`] (its primitives and their BVH); each placement
//! is a [`Placement`] (a transform, a motion, the material of the parts
//! that name none). The placements have their own BVH over their world
//! bounds: a ray goes through the scene's tree, then through this one,
//! and into a prototype's tree in the placement's frame (the two-level
//! structure of pbrt-v4's instances and Mitsuba's `shapegroup`). Without
//! placements the scene's flat path is unchanged.
//!
//! Rays keep their parameter in the placement's frame: the direction is
//! transformed, not normalised, so a hit's `t` compares with the scene's.
//! Normals go back to the world by the inverse transpose of the linear
//! part, which keeps each surface's outward side (also under a mirroring
//! placement).

use super::cutout::first_kept;
use super::{Hit, Prim};
use crate::accel::bvh4::{Bvh4, TreeHit};
use crate::geometry::shape::{Shape, ShapeHit};
use crate::geometry::{Aabb, Ray};
use glam::{Affine3A, Mat3, Vec2, Vec3};
use std::sync::Arc;

/// A [`Hit::instance`] that is no placement: the hit is on the scene's own
/// primitives.
pub const NO_INSTANCE: u32 = u32::MAX;

/// A [`Prototype::object_material`] that is the placement's material.
pub const INHERITED: u32 = u32::MAX;

/// A group's geometry in the group's frame, shared by its placements.
#[derive(Debug, Clone)]
pub struct Prototype {
    /// The records of its primitives (plain triangles have none, as in the
    /// scene; see `accel::numbering`).
    pub prims: Arc<Vec<Prim>>,
    /// The object of the group each primitive came from.
    pub prim_object: Arc<Vec<u32>>,
    /// The BVH over its primitives.
    pub wide: Arc<Bvh4>,
    /// Vertex normals of its mesh triangles with attributes.
    pub normals: Arc<Vec<[Vec3; 3]>>,
    /// Vertex texture coordinates of its mesh triangles with attributes.
    pub uvs: Arc<Vec<[Vec2; 3]>>,
    /// Corner tangents of its mesh triangles with attributes (see
    /// [`crate::ir::Scene::tangents`]).
    pub tangents: Arc<Vec<[glam::Vec4; 3]>>,
    /// Vertex colours of its mesh triangles with attributes.
    pub colors: Arc<Vec<[Vec3; 3]>>,
    /// Bounds of its primitives over the shutter, in its frame.
    pub bounds: Aabb,
    /// Each object's material (index into the scene's), or [`INHERITED`].
    pub object_material: Vec<u32>,
    /// The object ← group transforms of the objects not at the identity,
    /// sorted by object (texture patterns live in an object's frame).
    pub object_from_group: Vec<(u32, Affine3A)>,
}

impl Prototype {
    /// The closest hit of `ray` (in the prototype's frame) with its
    /// primitives; `passes(prim, hit)` says where the ray goes through a
    /// surface (cutouts).
    #[inline]
    fn closest(
        &self,
        ray: &Ray,
        t_min: f32,
        t_max: f32,
        passes: impl Fn(u32, &ShapeHit) -> bool,
    ) -> Option<TreeHit> {
        self.wide.closest(ray, t_min, t_max, |i, tmax| {
            let p = &self.prims[i as usize];
            first_kept(p, ray, (t_min, tmax), |h| passes(i, h))
        })
    }

    /// Whether anything of the prototype blocks `ray` (in its frame).
    fn any(
        &self,
        ray: &Ray,
        t_min: f32,
        t_max: f32,
        passes: impl Fn(u32, &ShapeHit) -> bool,
    ) -> bool {
        self.wide.any(ray, t_min, t_max, |i, tmax| {
            let p = &self.prims[i as usize];
            first_kept(p, ray, (t_min, tmax), |h| passes(i, h)).is_some()
        })
    }

    /// The group → object transform of the object of primitive `prim`, if
    /// it is not the identity.
    pub fn object_from_group(&self, prim: u32) -> Option<&Affine3A> {
        let object = self.prim_object[prim as usize];
        let i = self
            .object_from_group
            .binary_search_by_key(&object, |&(o, _)| o)
            .ok()?;
        Some(&self.object_from_group[i].1)
    }
}

/// One placement of a prototype.
#[derive(Debug, Clone)]
pub struct Placement {
    /// Index into [`Instances::prototypes`].
    pub prototype: u32,
    /// Group → world at time 0.
    pub world_from_group: Affine3A,
    /// World → group at time 0.
    pub group_from_world: Affine3A,
    /// Normals from the group's frame to the world's (the inverse
    /// transpose of the linear part).
    pub normal_to_world: Mat3,
    /// Linear motion per unit of shutter time, in the world.
    pub velocity: Vec3,
    /// The material of the group's objects that name none.
    pub material: u32,
}

impl Placement {
    /// A placement of `prototype` by the group → world transform `m`.
    pub fn new(prototype: u32, m: Affine3A, velocity: Vec3, material: u32) -> Self {
        Placement {
            prototype,
            world_from_group: m,
            group_from_world: m.inverse(),
            normal_to_world: m.matrix3.inverse().transpose().into(),
            velocity,
            material,
        }
    }

    /// `ray` in the group's frame at the ray's time (direction not
    /// normalised: `t` is the world's).
    #[inline]
    pub fn local_ray(&self, ray: &Ray) -> Ray {
        let o = ray.o - self.velocity * ray.time;
        Ray::new(
            self.group_from_world.transform_point3(o),
            self.group_from_world.transform_vector3(ray.d),
            ray.time,
        )
    }

    /// The world bounds of the placement of a prototype with `bounds`,
    /// over the shutter `(t0, t1)`.
    pub fn world_bounds(&self, bounds: Aabb, (t0, t1): (f32, f32)) -> Aabb {
        let mut b = Aabb::EMPTY;
        for k in 0..8 {
            let corner = Vec3::new(
                if k & 1 == 0 {
                    bounds.min.x
                } else {
                    bounds.max.x
                },
                if k & 2 == 0 {
                    bounds.min.y
                } else {
                    bounds.max.y
                },
                if k & 4 == 0 {
                    bounds.min.z
                } else {
                    bounds.max.z
                },
            );
            let p = self.world_from_group.transform_point3(corner);
            b = b.grow(p + self.velocity * t0).grow(p + self.velocity * t1);
        }
        b
    }
}

/// The placements of a scene and what they share.
#[derive(Debug, Clone, Default)]
pub struct Instances {
    /// The shared geometry.
    pub prototypes: Vec<Prototype>,
    /// The placements.
    pub placements: Vec<Placement>,
    /// The BVH over the placements' world bounds.
    pub tree: Bvh4,
}

/// A primitive's ray in its frame at the ray's time: `ray` itself for a
/// static primitive, else the ray moved back along the primitive's motion,
/// kept in `moved`. (Returning a copy put the ray through the stack on
/// every primitive test: see docs/performance.md, "Issue 39, step 0".)
#[inline(always)]
pub fn local_ray<'a>(prim: &Prim, ray: &'a Ray, moved: &'a mut Option<Ray>) -> &'a Ray {
    if prim.velocity == Vec3::ZERO {
        ray
    } else {
        moved.insert(Ray::new(ray.o - prim.velocity * ray.time, ray.d, ray.time))
    }
}

impl Instances {
    /// Whether the scene places nothing.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.placements.is_empty()
    }

    /// The closest hit of `ray` in `(t_min, t_max)` with any placement,
    /// finished in the world; `passes(placement, prim, hit)` says where
    /// the ray goes through a surface (cutouts).
    #[inline(never)]
    pub fn closest(
        &self,
        ray: &Ray,
        t_min: f32,
        t_max: f32,
        passes: impl Fn(u32, u32, &ShapeHit) -> bool,
    ) -> Option<Hit> {
        let mut found: Option<(u32, TreeHit, Ray)> = None;
        self.tree.closest(ray, t_min, t_max, |k, tmax| {
            let placement = &self.placements[k as usize];
            let prototype = &self.prototypes[placement.prototype as usize];
            let local = placement.local_ray(ray);
            let hit = prototype.closest(&local, t_min, tmax, |i, h| passes(k, i, h))?;
            let shape_hit = hit.hit;
            // The tree calls back with a smaller t_max each time: a hit
            // here is the closest so far.
            found = Some((k, hit, local));
            Some(shape_hit)
        });
        let (k, tree_hit, local) = found?;
        let placement = &self.placements[k as usize];
        let prototype = &self.prototypes[placement.prototype as usize];
        let record;
        let prim = match tree_hit.plain {
            Some(lane) => {
                record = Prim {
                    shape: lane.shape(),
                    velocity: Vec3::ZERO,
                };
                &record
            }
            None => &prototype.prims[tree_hit.prim as usize],
        };
        let mut slot = None;
        let moved = local_ray(prim, &local, &mut slot);
        let p_local = prim.shape.surface_point(moved, &tree_hit.hit);
        let n_local = prim.shape.normal_at(p_local);
        let uv = prim.shape.own_uv(tree_hit.hit.uv);
        let mut ns_local = n_local;
        if let Shape::Triangle { attributes, .. } = prim.shape {
            if let Some(ns) = prototype.normals.get(attributes as usize) {
                let n =
                    ((1.0 - uv.x - uv.y) * ns[0] + uv.x * ns[1] + uv.y * ns[2]).normalize_or_zero();
                if n != Vec3::ZERO {
                    ns_local = n;
                }
            }
        }
        let to_world = |n: Vec3| (placement.normal_to_world * n).normalize();
        let n_geo = to_world(n_local);
        let n_shading = to_world(ns_local);
        let n_shading = if n_shading.dot(n_geo) < 0.0 {
            -n_shading
        } else {
            n_shading
        };
        let p = placement
            .world_from_group
            .transform_point3(p_local + prim.velocity * ray.time)
            + placement.velocity * ray.time;
        Some(Hit {
            t: tree_hit.hit.t,
            p,
            n_geo,
            n_shading,
            bent: false,
            prim: tree_hit.prim,
            instance: k,
            uv,
        })
    }

    /// Whether any placement blocks the segment `(t_min, t_max)` of `ray`.
    /// `passes` as in [`Instances::closest`].
    #[inline(never)]
    pub fn any(
        &self,
        ray: &Ray,
        t_min: f32,
        t_max: f32,
        passes: impl Fn(u32, u32, &ShapeHit) -> bool,
    ) -> bool {
        self.tree.any(ray, t_min, t_max, |k, tmax| {
            let placement = &self.placements[k as usize];
            let prototype = &self.prototypes[placement.prototype as usize];
            prototype.any(&placement.local_ray(ray), t_min, tmax, |i, h| {
                passes(k, i, h)
            })
        })
    }
}
