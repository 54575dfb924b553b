//! The render IR: flat arrays of primitives and materials, a BVH, lights with
//! a power-proportional selection table. Built from the checked scene by
//! [`lower`](lower::lower); every primitive remembers the span it came from.

pub mod cutout;
pub mod instance;
pub mod media;
mod memory;
pub mod packet;
pub mod settings;
mod surface;

use crate::accel::bvh4::{Bvh4, TreeHit};
use crate::accel::ray_count;
use crate::camera::Camera;
use crate::geometry::shape::{Shape, ShapeHit};
use crate::geometry::{Aabb, Ray};
use crate::light::selection::LightSampler;
use crate::light::Light;
use crate::material::Material;
use crate::span::Span;
use crate::texture::Texture;
use glam::{Affine3A, Vec2, Vec3};
use settings::Settings;
use std::sync::Arc;

/// One primitive: geometry only, so that `watch` shares it between compiles
/// (its material is its object's, see [`Scene::material_of`]). Exactly one
/// cache line: a leaf's primitives are read during traversal, and a 64-byte
/// record that straddled two lines would cost two memory fetches.
#[derive(Debug, Clone)]
#[repr(align(64))]
pub struct Prim {
    /// Geometry in world space at time 0.
    pub shape: Shape,
    /// Linear motion per unit time.
    pub velocity: Vec3,
}

/// A surface hit.
#[derive(Debug, Clone, Copy)]
pub struct Hit {
    /// Distance along the ray.
    pub t: f32,
    /// Point.
    pub p: Vec3,
    /// Outward geometric normal (unit).
    pub n_geo: Vec3,
    /// Shading normal (unit, same hemisphere as `n_geo`).
    pub n_shading: Vec3,
    /// Whether a texture bent the shading normal (a normal or bump map):
    /// then a reflection may not cross the surface
    /// (`integrator::crosses_surface`).
    pub bent: bool,
    /// Primitive index (in the scene, or in the prototype of `instance`).
    pub prim: u32,
    /// The placement hit ([`instance::NO_INSTANCE`]: the scene's own
    /// primitives).
    pub instance: u32,
    /// The shape's own surface parameters at the hit: (s, t) along a
    /// quad's edges, a triangle's barycentrics (b1, b2), as the scene gave
    /// them (see [`Shape::own_uv`]); zero for the others (see
    /// [`Scene::texcoords`]).
    pub uv: Vec2,
}

/// The scene, ready to render.
#[derive(Debug, Clone)]
pub struct Scene {
    /// Render settings (after command-line overrides).
    pub settings: Settings,
    /// The camera.
    pub camera: Camera,
    /// The records of the primitives that need one (shared with `watch`'s
    /// cache while the geometry is unchanged): all but the plain triangles
    /// of the BVH's blocks, which their blocks describe completely and
    /// whose numbers come after these (see `accel::numbering`).
    pub prims: Arc<Vec<Prim>>,
    /// The object each primitive came from (index into `object_spans`), for
    /// every primitive, records or not.
    pub prim_object: Arc<Vec<u32>>,
    /// Where each object is written in the source.
    pub object_spans: Vec<Span>,
    /// Each object's material (index into `materials`).
    pub object_material: Vec<u32>,
    /// The BVH over the bounded primitives (4 wide, collapsed from a binary SAH tree).
    pub wide: Arc<Bvh4>,
    /// Unbounded primitives (planes), tested separately.
    pub unbounded: Arc<Vec<u32>>,
    /// Materials.
    pub materials: Vec<Material>,
    /// The textures materials name.
    pub textures: Vec<Texture>,
    /// Vertex normals of mesh triangles with vertex attributes (zero:
    /// flat), indexed by the triangle's `attributes`.
    pub normals: Arc<Vec<[Vec3; 3]>>,
    /// Vertex texture coordinates of mesh triangles with attributes, by the
    /// same index; shorter than `normals` when the last ones have none.
    pub uvs: Arc<Vec<[Vec2; 3]>>,
    /// Corner tangents of mesh triangles with attributes for normal maps,
    /// by the same index (xyz along ∂p/∂u, smoothed; w = ±1 the side of
    /// the bitangent n × t, 0 for a triangle without: its ∂p/∂u serves);
    /// shorter than `normals` when the last ones have none.
    pub tangents: Arc<Vec<[glam::Vec4; 3]>>,
    /// Vertex colours of mesh triangles with attributes, by the same index
    /// (white for a triangle without); shorter than `normals` when the
    /// last ones have none.
    pub colors: Arc<Vec<[Vec3; 3]>>,
    /// The emissive primitives, ascending; the i-th is light i (area lights
    /// come first in `lights`).
    pub area_lights: Vec<u32>,
    /// Lights.
    pub lights: Vec<Light>,
    /// How shadow rays choose among `lights`.
    pub light_sampler: LightSampler,
    /// Each light's power, as light selection's `power` rule weighs it
    /// (by index into `lights`): where light paths start.
    pub light_powers: Vec<f64>,
    /// Background radiance.
    pub background: Vec3,
    /// Index of the environment light, if the background is not black.
    pub env_light: Option<u32>,
    /// Bounds of the bounded geometry.
    pub bounds: Aabb,
    /// The world → object transforms of the objects that have one, sorted
    /// by object (the others are at the identity): texture coordinates and
    /// patterns live in an object's own frame.
    pub object_from_world: Vec<(u32, Affine3A)>,
    /// Groups placed several times: shared geometry and its placements.
    pub instances: Arc<instance::Instances>,
    /// The cut-out materials, if any material is (see [`cutout`]).
    pub cutouts: Option<Arc<cutout::Cutouts>>,
    /// The medium around the objects, if any.
    pub atmosphere: Option<media::Atmosphere>,
    /// The insides that hold the camera (see [`media::media_around`]).
    pub camera_media: media::MediumStack,
    /// Whether light meets scattering media or null boundaries (the path
    /// integrator then runs its volumetric form).
    pub volumetric: bool,
}

const _: () = assert!(std::mem::size_of::<Prim>() == 64);

impl Scene {
    /// Where primitive `prim` was written in the source.
    pub fn origin(&self, prim: u32) -> Span {
        self.object_spans[self.prim_object[prim as usize] as usize]
    }

    /// The material of primitive `prim`.
    #[inline]
    pub fn material_of(&self, prim: u32) -> &Material {
        let object = self.prim_object[prim as usize] as usize;
        &self.materials[self.object_material[object] as usize]
    }

    /// The material of the surface hit (an instanced object's own, or its
    /// placement's when it names none).
    #[inline(always)]
    pub fn material_of_hit(&self, hit: &Hit) -> &Material {
        if hit.instance == instance::NO_INSTANCE {
            self.material_of(hit.prim)
        } else {
            self.instanced_material(hit)
        }
    }

    /// [`Scene::material_of_hit`] for a hit on a placement.
    #[inline(never)]
    fn instanced_material(&self, hit: &Hit) -> &Material {
        let placement = &self.instances.placements[hit.instance as usize];
        let prototype = &self.instances.prototypes[placement.prototype as usize];
        let object = prototype.prim_object[hit.prim as usize];
        let m = match prototype.object_material[object as usize] {
            instance::INHERITED => placement.material,
            m => m,
        };
        &self.materials[m as usize]
    }

    /// The light the surface hit is, if it is emissive (placed geometry
    /// never is: lowering flattens placements with emissive parts).
    #[inline]
    pub fn area_light_at(&self, hit: &Hit) -> Option<u32> {
        if hit.instance == instance::NO_INSTANCE {
            self.area_light(hit.prim)
        } else {
            None
        }
    }

    /// The material at a hit at `time` seen from `wo`: the material of the
    /// primitive, or, when it has textured parameters, the material they
    /// make there, kept in `slot` (a texture that bends normals sets the
    /// hit's shading normal). (A plain reference, not a `Cow`: the integrators then read
    /// a constant material as before; a `Cow` cost 2 % of a render.)
    #[inline(always)]
    pub fn material_at<'a>(
        &'a self,
        hit: &mut Hit,
        wo: Vec3,
        time: f32,
        slot: &'a mut Option<Material>,
    ) -> &'a Material {
        let m = self.material_of_hit(hit);
        match &m.textured {
            None => m,
            Some(t) => slot.insert(self.textured_material(t, hit, wo, time)),
        }
    }

    /// The radiance arriving from the direction `d` from outside the scene:
    /// the background or the environment map.
    pub fn environment(&self, d: Vec3) -> Vec3 {
        self.env_light
            .map_or(Vec3::ZERO, |i| self.lights[i as usize].arriving_from(d))
    }

    /// The light that primitive `prim` is, if it is emissive.
    pub fn area_light(&self, prim: u32) -> Option<u32> {
        self.area_lights.binary_search(&prim).ok().map(|i| i as u32)
    }

    /// The closest hit along `ray` beyond `t_min`: the scene's own
    /// primitives, then the placements of groups (if any). Counted as a
    /// closest-hit query.
    #[inline(always)]
    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<Hit> {
        ray_count::closest();
        self.closest_hit(ray, t_min, t_max)
    }

    /// [`Scene::intersect`] uncounted: a shadow ray's walk through media
    /// (`media.rs`) finds its surfaces with it and counts as a shadow query.
    #[inline(always)]
    fn closest_hit(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<Hit> {
        // The flat path as before placements and cutouts existed, its hit
        // built in place; a scene with either goes out of line (choosing
        // between two hits here cost scenes without placements 1.4 % of
        // their instructions).
        if self.instances.is_empty() && self.cutouts.is_none() {
            return self.intersect_own(ray, t_min, t_max, |_, _| false);
        }
        self.intersect_general(ray, t_min, t_max)
    }

    /// [`Scene::intersect`] in a scene with placements or cutouts.
    #[inline(never)]
    fn intersect_general(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<Hit> {
        match self.cutouts {
            None => self.intersect_placed(ray, t_min, t_max, |_, _, _| false),
            Some(_) => self.intersect_placed(ray, t_min, t_max, |instance, prim, hit| {
                self.passes(ray, prim, instance, hit)
            }),
        }
    }

    /// The closest hit with the scene's own primitives, then with the
    /// placements (if any); `passes(instance, prim, hit)` says where a
    /// ray goes through a surface.
    #[inline(always)]
    fn intersect_placed(
        &self,
        ray: &Ray,
        t_min: f32,
        t_max: f32,
        passes: impl Fn(u32, u32, &ShapeHit) -> bool,
    ) -> Option<Hit> {
        let own = self.intersect_own(ray, t_min, t_max, |prim, hit| {
            passes(instance::NO_INSTANCE, prim, hit)
        });
        if self.instances.is_empty() {
            return own;
        }
        let t_max = own.map_or(t_max, |h| h.t);
        self.instances.closest(ray, t_min, t_max, passes).or(own)
    }

    /// The closest hit along `ray` beyond `t_min` with the scene's own
    /// primitives.
    // Inlined into the integrators, as are the BSDF's and the lights' `sample`
    // and `eval`: called out of line, the `Hit` and `BsdfSample` they return
    // go through memory and their first loads stall the integrator.
    // `always` (here, in `Bvh4::closest`, `Light::sample` and
    // `Material::sample`): a plain `#[inline]` is dropped by LLVM's
    // heuristics after unrelated changes. Measurements: docs/performance.md,
    // "Why the BVH and traversal are as they are".
    #[inline(always)]
    fn intersect_own(
        &self,
        ray: &Ray,
        t_min: f32,
        t_max: f32,
        passes: impl Fn(u32, &ShapeHit) -> bool,
    ) -> Option<Hit> {
        let mut best = self.wide.closest(ray, t_min, t_max, |i, tmax| {
            let p = &self.prims[i as usize];
            cutout::first_kept(p, ray, (t_min, tmax), |h| passes(i, h))
        });
        for &i in self.unbounded.iter() {
            let p = &self.prims[i as usize];
            let tmax = best.map_or(t_max, |b| b.hit.t);
            if let Some(hit) = cutout::first_kept(p, ray, (t_min, tmax), |h| passes(i, h)) {
                best = Some(TreeHit {
                    prim: i,
                    hit,
                    plain: None,
                });
            }
        }
        Some(self.finish_own(ray, best?))
    }

    /// The hit of the scene's own primitive the tree walk found for `ray`.
    #[inline(always)]
    fn finish_own(&self, ray: &Ray, best: TreeHit) -> Hit {
        let TreeHit {
            prim: i,
            hit,
            plain,
        } = best;
        let t = hit.t;
        // A plain triangle's or quad's hit is finished from the block the
        // traversal just read: it has no record (and reading one cost a
        // cache miss). Its point and normal have a triangle's formulas.
        let record;
        let (prim, uv) = match plain {
            Some(lane) => {
                record = Prim {
                    shape: Shape::flat_triangle(lane.vertices),
                    velocity: Vec3::ZERO,
                };
                (&record, lane.own_uv(hit.uv))
            }
            None => {
                let prim = &self.prims[i as usize];
                (prim, prim.shape.own_uv(hit.uv))
            }
        };
        let mut slot = None;
        let local = instance::local_ray(prim, ray, &mut slot);
        let p_local = prim.shape.surface_point(local, &hit);
        let n_geo = prim.shape.normal_at(p_local);
        let mut n_shading = n_geo;
        if let Shape::Triangle { attributes, .. } = prim.shape {
            if attributes != u32::MAX {
                let ns = self.normals[attributes as usize];
                let n =
                    ((1.0 - uv.x - uv.y) * ns[0] + uv.x * ns[1] + uv.y * ns[2]).normalize_or_zero();
                if n != Vec3::ZERO {
                    n_shading = if n.dot(n_geo) < 0.0 { -n } else { n };
                }
            }
        }
        Hit {
            t,
            p: p_local + prim.velocity * ray.time,
            n_geo,
            n_shading,
            bent: false,
            prim: i,
            instance: instance::NO_INSTANCE,
            uv,
        }
    }

    /// Whether anything blocks the segment from `ray.o` to `ray.at(t_max)`.
    pub fn occluded(&self, ray: &Ray, t_min: f32, t_max: f32) -> bool {
        ray_count::shadow();
        if self.cutouts.is_none() {
            return self.occluded_by(ray, t_min, t_max, |_, _, _| false);
        }
        self.occluded_cut(ray, t_min, t_max)
    }

    /// [`Scene::occluded`] in a scene with cutouts.
    #[inline(never)]
    fn occluded_cut(&self, ray: &Ray, t_min: f32, t_max: f32) -> bool {
        self.occluded_by(ray, t_min, t_max, |instance, prim, hit| {
            self.passes(ray, prim, instance, hit)
        })
    }

    /// Whether anything blocks the segment, `passes(instance, prim, hit)`
    /// saying where a ray goes through a surface.
    #[inline(always)]
    fn occluded_by(
        &self,
        ray: &Ray,
        t_min: f32,
        t_max: f32,
        passes: impl Fn(u32, u32, &ShapeHit) -> bool,
    ) -> bool {
        let blocks = |i: u32, tmax: f32| {
            let p = &self.prims[i as usize];
            cutout::first_kept(p, ray, (t_min, tmax), |h| {
                passes(instance::NO_INSTANCE, i, h)
            })
            .is_some()
        };
        self.wide.any(ray, t_min, t_max, blocks)
            || self.unbounded.iter().any(|&i| blocks(i, t_max))
            || (!self.instances.is_empty() && self.instances.any(ray, t_min, t_max, passes))
    }
}
