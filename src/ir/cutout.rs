//! Cutouts: surfaces that are there only where their material's opacity
//! says (leaves, fences, decals; glTF's `MASK` and `BLEND`, an MTL's `d`
//! and `map_d`). A ray passes a cut-out surface where the opacity is below
//! the material's cutoff, or, without a cutoff, with probability one minus
//! the opacity (stochastic transparency, as pbrt-v4's alpha textures and
//! Mitsuba's `mask`): unbiased, since the expected transmittance of a
//! surface of opacity α is 1 − α.
//!
//! The test runs inside traversal, for camera, bounce and shadow rays
//! alike, so every ray sees the same surface. Cut-out primitives are kept
//! out of the BVH's four-wide blocks (lowering), and a scene without
//! cutouts takes the traversal it had before (see [`Scene::intersect`]).
//! The random choice hashes the ray and the primitive: a pure function of
//! the sample, so renders stay deterministic on any thread count.

use super::instance::{local_ray, INHERITED, NO_INSTANCE};
use super::{Hit, Prim, Scene};
use crate::geometry::shape::ShapeHit;
use crate::geometry::Ray;
use glam::Vec3;

/// Where a material's surface is there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Opacity {
    /// The opacity, 0..1 (times the texture's, if any).
    pub value: f32,
    /// The texture giving the opacity (index into the scene's textures;
    /// its scalar value is read).
    pub texture: Option<u32>,
    /// Opaque at and above this opacity, absent below (`None`: fractions
    /// pass at random).
    pub cutoff: Option<f32>,
}

/// The cut-out materials of a scene.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Cutouts {
    /// Each material's opacity, `None` where it is wholly there.
    pub by_material: Vec<Option<Opacity>>,
}

impl Cutouts {
    /// The cutouts of materials with these opacities; `None` when no
    /// material is cut out.
    pub fn of(by_material: Vec<Option<Opacity>>) -> Option<Cutouts> {
        by_material
            .iter()
            .any(Option::is_some)
            .then_some(Cutouts { by_material })
    }
}

/// A uniform number in [0, 1) from a ray and the primitive it meets: the
/// same for the same ray (a pure function of the sample that made it) and
/// independent between primitives and rays. (A 64-bit mix of the bits,
/// finished by the splitmix64 finaliser: Steele et al. 2014.)
fn ray_hash(ray: &Ray, prim: u32, instance: u32) -> f32 {
    let bits = |v: Vec3| {
        (v.x.to_bits() as u64) ^ ((v.y.to_bits() as u64) << 21) ^ ((v.z.to_bits() as u64) << 42)
    };
    let mut h = bits(ray.o).wrapping_mul(0x9E37_79B9_7F4A_7C15)
        ^ bits(ray.d).rotate_left(29)
        ^ ((prim as u64) << 32 | instance as u64).wrapping_mul(0xD6E8_FEB8_6659_FD93);
    h ^= h >> 30;
    h = h.wrapping_mul(0xBF58_476D_1CE4_E5B9);
    h ^= h >> 27;
    h = h.wrapping_mul(0x94D0_49BB_1331_11EB);
    h ^= h >> 31;
    (h >> 40) as f32 * (1.0 / (1u64 << 24) as f32)
}

/// The most crossings of one primitive a ray looks through: a torus, the
/// shape with the most, has four.
const MAX_CROSSINGS: usize = 4;

/// The first hit of `prim` along `ray` in `(t_min, t_max)` that does not
/// `pass` (a surface passed, the search goes on beyond it: a sphere's far
/// side). Without cutouts (`pass` always false) this is the shape's test.
#[inline(always)]
pub(super) fn first_kept(
    prim: &Prim,
    ray: &Ray,
    (t_min, t_max): (f32, f32),
    pass: impl Fn(&ShapeHit) -> bool,
) -> Option<ShapeHit> {
    let mut moved = None;
    let local = local_ray(prim, ray, &mut moved);
    let mut lo = t_min;
    for _ in 0..MAX_CROSSINGS {
        let hit = prim.shape.intersect(local, lo, t_max)?;
        if !pass(&hit) {
            return Some(hit);
        }
        if hit.t <= lo {
            return None;
        }
        lo = hit.t;
    }
    None
}

impl Scene {
    /// The opacity of the material of primitive `prim` of placement
    /// `instance` (or of the scene: [`NO_INSTANCE`]), if it is cut out.
    #[inline]
    pub(super) fn opacity_of(&self, prim: u32, instance: u32) -> Option<&Opacity> {
        let cutouts = self.cutouts.as_deref()?;
        let material = if instance == NO_INSTANCE {
            let object = self.prim_object[prim as usize];
            self.object_material[object as usize]
        } else {
            let placement = &self.instances.placements[instance as usize];
            let prototype = &self.instances.prototypes[placement.prototype as usize];
            match prototype.object_material[prototype.prim_object[prim as usize] as usize] {
                INHERITED => placement.material,
                m => m,
            }
        };
        cutouts.by_material[material as usize].as_ref()
    }

    /// Whether `ray` (in the world) passes primitive `prim` of placement
    /// `instance` where it meets it, at `hit` (`hit.uv` the shape's
    /// parameters there as its test gives them).
    #[inline]
    pub(super) fn passes(&self, ray: &Ray, prim: u32, instance: u32, hit: &ShapeHit) -> bool {
        match self.opacity_of(prim, instance) {
            None => false,
            Some(opacity) => self.passes_at(opacity, ray, prim, instance, hit),
        }
    }

    /// [`Scene::passes`] for a primitive whose material has `opacity`.
    #[inline(never)]
    fn passes_at(
        &self,
        opacity: &Opacity,
        ray: &Ray,
        prim: u32,
        instance: u32,
        hit: &ShapeHit,
    ) -> bool {
        let own_uv = self.own_uv(prim, instance, hit);
        let alpha = match opacity.texture {
            None => opacity.value,
            Some(t) => {
                // The world point: the placement's and the primitive's
                // rays keep the world's parameter.
                let at = Hit {
                    t: hit.t,
                    p: ray.o + hit.t * ray.d,
                    n_geo: Vec3::Z,
                    n_shading: Vec3::Z,
                    bent: false,
                    prim,
                    instance,
                    uv: own_uv,
                };
                let point = self.shading_point(&at, ray.time);
                opacity.value * self.textures[t as usize].eval_scalar(&point)
            }
        };
        match opacity.cutoff {
            Some(cutoff) => alpha < cutoff,
            None => alpha < 1.0 && ray_hash(ray, prim, instance) >= alpha,
        }
    }

    /// The shape's own surface parameters at a hit on a record (cut-out
    /// primitives always have one).
    fn own_uv(&self, prim: u32, instance: u32, hit: &ShapeHit) -> glam::Vec2 {
        let prims = if instance == NO_INSTANCE {
            &self.prims
        } else {
            let placement = &self.instances.placements[instance as usize];
            &self.instances.prototypes[placement.prototype as usize].prims
        };
        prims[prim as usize].shape.own_uv(hit.uv)
    }
}
