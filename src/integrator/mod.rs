//! Integrators answer one question: the radiance arriving along a camera ray.
//! The pixel loop (`render`) is theirs to share. Shared pieces live here: the
//! direct-lighting estimate used by `path` (with MIS) and `whitted`.

pub mod bdpt;
pub mod debug;
pub mod hybrid;
pub mod path;
pub mod volpath;
pub mod whitted;

use crate::geometry::{offset_origin, Ray};
use crate::ir::settings::IntegratorKind;
use crate::ir::{Hit, Scene};
use crate::material::Material;
use crate::sampling::sampler::Sampler;
use crate::sampling::warp::power_heuristic;
use glam::Vec3;

/// Radiance along a ray.
pub trait Integrator: Sync {
    /// Estimates the radiance arriving at the ray's origin from its direction.
    fn li(&self, scene: &Scene, ray: Ray, sampler: &mut Sampler) -> Vec3;

    /// Whether [`Integrator::li_from`] uses a camera ray's first hit found
    /// outside it (the pixel loop then traces a pixel's camera rays as a
    /// packet).
    fn takes_first_hit(&self, _scene: &Scene) -> bool {
        false
    }

    /// [`Integrator::li`] for a ray whose first hit (`None`: it leaves the
    /// scene) [`Scene::intersect`] has given already.
    fn li_from(&self, scene: &Scene, ray: Ray, _first: Option<Hit>, sampler: &mut Sampler) -> Vec3 {
        self.li(scene, ray, sampler)
    }

    /// Whether a sample also adds light to other pixels than its own
    /// ([`Integrator::li_splatting`]'s splats: light paths joined to the
    /// camera).
    fn splats(&self) -> bool {
        false
    }

    /// [`Integrator::li`], with the light the sample adds to other pixels
    /// pushed onto `splats`.
    fn li_splatting(
        &self,
        scene: &Scene,
        ray: Ray,
        sampler: &mut Sampler,
        _splats: &mut Vec<Splat>,
    ) -> Vec3 {
        self.li(scene, ray, sampler)
    }
}

/// Light a sample adds to the pixel at image position `film` (pixels of
/// the scene's image, y down), in the units of a pixel's mean times its
/// samples per pixel: the image adds the splats' sum divided by the mean
/// number of samples per pixel.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Splat {
    /// Where on the image.
    pub film: glam::Vec2,
    /// How much.
    pub value: Vec3,
}

/// Whether the integrator `kind` makes for `scene` splats (its film then
/// keeps a light film: [`Integrator::splats`]).
pub fn splats(kind: IntegratorKind, scene: &Scene) -> bool {
    kind.renders_with(scene.volumetric).is_bidirectional()
}

/// The integrator a scene asks for (`bdpt` or `ptlt` in a scene with media: the
/// path integrator, which traces them).
pub fn make(kind: IntegratorKind, scene: &Scene) -> Box<dyn Integrator> {
    match kind.renders_with(scene.volumetric) {
        IntegratorKind::Bdpt => Box::new(bdpt::Bdpt::new(scene, true)),
        IntegratorKind::Ptlt => Box::new(bdpt::Bdpt::new(scene, false)),
        IntegratorKind::Path => Box::new(path::PathIntegrator),
        IntegratorKind::Whitted => Box::new(whitted::Whitted),
        IntegratorKind::Hybrid => Box::new(hybrid::Hybrid),
        IntegratorKind::Normals => Box::new(debug::Debug::Normals),
        IntegratorKind::Albedo => Box::new(debug::Debug::Albedo),
        IntegratorKind::Depth => Box::new(debug::Debug::Depth),
        IntegratorKind::Uv => Box::new(debug::Debug::Uv),
    }
}

pub use crate::geometry::T_MIN;

/// Next-event estimation at `hit` for outgoing direction `wo`: one light
/// chosen by the scene's light selection, weighted against BSDF sampling with the power heuristic
/// (delta lights get weight 1).
pub fn direct_light_mis(
    scene: &Scene,
    hit: &Hit,
    material: &Material,
    wo: Vec3,
    time: f32,
    sampler: &mut Sampler,
) -> Vec3 {
    let u = sampler.next_f64();
    let Some((li_idx, pick_pdf)) = scene.light_sampler.sample(hit.p, hit.n_shading, u) else {
        return Vec3::ZERO;
    };
    let u = sampler.next_2d();
    let light = &scene.lights[li_idx as usize];
    let emitted = |prim, q, uv, n, w| scene.emitted_at(prim, q, uv, n, w, time);
    let Some(ls) = light.sample(emitted, hit.p, time, u) else {
        return Vec3::ZERO;
    };
    if crosses_surface(hit, wo, ls.wi) {
        return Vec3::ZERO;
    }
    let (f, bsdf_pdf) = material.eval(wo, ls.wi, hit.n_shading);
    if f == Vec3::ZERO {
        return Vec3::ZERO;
    }
    let (shadow, t_max) = shadow_ray(hit, ls.wi, ls.dist, time);
    if scene.occluded(&shadow, T_MIN, t_max) {
        return Vec3::ZERO;
    }
    let cos = ls.wi.dot(hit.n_shading).abs();
    if light.is_delta() {
        return f * ls.li * cos / pick_pdf;
    }
    let light_pdf = ls.pdf * pick_pdf;
    let w = power_heuristic(light_pdf, bsdf_pdf);
    f * ls.li * cos * w / light_pdf
}

/// Continues a path at `hit` by sampling its material for `wo` (the
/// bounce's BSDF draws); `None` where the path ends: no sample, a weight
/// that is zero or not finite, or a reflection that would cross a bent
/// surface ([`crosses_surface`]).
#[inline(always)]
pub fn continue_path(
    hit: &Hit,
    material: &Material,
    wo: Vec3,
    bounce: u32,
    sampler: &mut Sampler,
) -> Option<crate::material::BsdfSample> {
    sampler.start(bounce, crate::sampling::sampler::Draws::Bsdf);
    continue_path_drawing(hit, material, wo, sampler)
}

/// [`continue_path`] drawing the sampler's next numbers, wherever they
/// point (a light path's: the PCG stream, so that it shares no slot with
/// its sample's camera path).
#[inline(always)]
pub fn continue_path_drawing(
    hit: &Hit,
    material: &Material,
    wo: Vec3,
    sampler: &mut Sampler,
) -> Option<crate::material::BsdfSample> {
    let bs = material.sample(wo, hit.n_shading, sampler.next_f32(), sampler.next_2d())?;
    let usable = bs.weight.is_finite()
        && bs.weight != Vec3::ZERO
        && (bs.transmitted || !crosses_surface(hit, wo, bs.wi));
    usable.then_some(bs)
}

/// `c` scaled so that its largest component is at most `x`, its hue kept
/// (a sample's bound and `render { clamp }`).
#[inline]
pub fn scaled_within(c: Vec3, x: f32) -> Vec3 {
    let m = c.max_element();
    if m > x {
        c * (x / m)
    } else {
        c
    }
}

/// The shadow ray from `hit` towards a light point at distance `dist` along
/// `wi` (infinite for lights at infinity), and how far it must be free. The
/// ray starts off the surface and is aimed at the light point itself (as
/// pbrt's `SpawnRayTo`), stopping a relative margin short of it so that the
/// light's own surface does not block it. (Sent along `wi` from the offset
/// origin, it passed beside the point and entered a curved lamp before it:
/// a sphere lamp within ~0.2 units of a surface lost up to all of its light
/// there.)
#[inline(always)]
pub fn shadow_ray(hit: &Hit, wi: Vec3, dist: f32, time: f32) -> (Ray, f32) {
    let origin = offset_origin(hit.p, hit.n_geo, wi);
    if !dist.is_finite() {
        return (Ray::new(origin, wi, time), f32::INFINITY);
    }
    let to = hit.p + wi * dist - origin;
    let length = to.length();
    if length > 0.0 {
        (Ray::new(origin, to / length, time), length * (1.0 - 1e-4))
    } else {
        (Ray::new(origin, wi, time), 0.0)
    }
}

/// Whether `wi` leaves a hit whose shading normal a texture bent on the
/// other side of the surface than `wo`: such a reflection would leak light
/// through it (Veach 1997, §5.3: the geometric normal decides). Smooth
/// meshes keep their shading normals' answer, as in pbrt and Mitsuba.
#[inline]
pub fn crosses_surface(hit: &Hit, wo: Vec3, wi: Vec3) -> bool {
    hit.bent && (wi.dot(hit.n_geo) > 0.0) != (wo.dot(hit.n_geo) > 0.0)
}

/// Pdf with which [`direct_light_mis`] would have produced a ray from the
/// point `from` with shading normal `from_n` that hits emitter `light` at
/// `hit` (solid angle, including the light choice).
#[inline]
pub fn light_pdf(
    scene: &Scene,
    light: u32,
    [from, from_n]: [Vec3; 2],
    hit: &Hit,
    dir: Vec3,
) -> f32 {
    let pick = scene.light_sampler.pmf(from, from_n, light);
    pick * scene.lights[light as usize].pdf_towards(from, dir, hit.p, hit.n_geo)
}
