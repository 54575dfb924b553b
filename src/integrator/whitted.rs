//! Recursive ray tracing (Whitted 1980) with distribution effects (Cook
//! 1984): direct light with shadow rays from every light (several per area
//! light, for soft shadows; from lights chosen by the light selection when
//! there are many), the ambient term, mirror and glossy reflection,
//! refraction weighted by exact Fresnel with total internal reflection, and
//! Beer's law. Indirect diffuse light is not computed: that is the path
//! integrator's job. Participating media only attenuate (light scattered
//! into a ray is not computed; a medium that scatters darkens what lies
//! behind it by its whole extinction, exp(−σt d)), and null boundaries
//! (`type none`) are passed through, also by shadow rays.
//!
//! `.pts`: `render { integrator whitted  max_depth 8  light_samples 4  ambient rgb 0.05 }`.

use super::{Integrator, T_MIN};
use crate::geometry::{offset_origin, Ray};
use crate::ir::media::{MediumStack, MAX_CROSSINGS};
use crate::ir::{Hit, Scene};
use crate::light::Light;
use crate::material::Material;
use crate::sampling::sampler::{Draws, Sampler};
use glam::Vec3;

/// The Whitted integrator.
pub struct Whitted;

/// A reflected or refracted branch whose weight in the pixel (the product of
/// the reflectances and Fresnel factors along it) falls below this is not
/// traced: it could change the 8-bit pixel by less than one step. POV-Ray's
/// `adc_bailout` with its default 1/255. Without it the tree of rays inside a
/// glass ball doubles at every segment.
pub const BAILOUT: f32 = 1.0 / 255.0;

impl Integrator for Whitted {
    fn li(&self, scene: &Scene, ray: Ray, sampler: &mut Sampler) -> Vec3 {
        trace(scene, ray, sampler, 1, 1.0)
    }
}

/// The light a ray meets, passed through null boundaries: its hit (none:
/// it left the scene) and the fraction of light that crosses the media
/// on the way; `media` ends as the media at the hit.
fn first_surface(scene: &Scene, ray: &mut Ray, media: &mut MediumStack) -> (Option<Hit>, Vec3) {
    let mut tr = Vec3::ONE;
    for _ in 0..MAX_CROSSINGS {
        let mut hit = scene.intersect(ray, T_MIN, f32::INFINITY);
        let mut slot = None;
        let material = hit
            .as_mut()
            .map(|h| scene.material_at(h, -ray.d, ray.time, &mut slot));
        let end = hit.as_ref().zip(material);
        let t = hit.as_ref().map_or(f32::INFINITY, |h| h.t);
        if let Some((m, t0, t1)) = scene.medium_span(media.segment(scene, ray.d, end), ray, t) {
            tr *= m.transmittance(t1 - t0);
        }
        match end {
            Some((h, m)) if m.is_null() => {
                media.cross(scene, ray.d, h, m);
                *ray = Ray::new(offset_origin(h.p, h.n_geo, ray.d), ray.d, ray.time);
            }
            _ => return (hit, tr),
        }
    }
    (None, Vec3::ZERO)
}

/// Radiance along `ray`, which is path segment number `segment` and counts
/// with `weight` (largest channel of the product of factors so far) in the pixel.
pub fn trace(scene: &Scene, ray: Ray, sampler: &mut Sampler, segment: u32, weight: f32) -> Vec3 {
    trace_in(scene, ray, sampler, (segment, weight), scene.camera_media)
}

/// [`trace`] for a ray that starts among `media`.
fn trace_in(
    scene: &Scene,
    mut ray: Ray,
    sampler: &mut Sampler,
    (segment, weight): (u32, f32),
    mut media: MediumStack,
) -> Vec3 {
    if !scene.volumetric {
        return shade(scene, ray, sampler, (segment, weight), media);
    }
    let (hit, tr) = first_surface(scene, &mut ray, &mut media);
    if tr == Vec3::ZERO {
        return Vec3::ZERO;
    }
    match hit {
        Some(_) => tr * shade(scene, ray, sampler, (segment, weight), media),
        None => tr * scene.environment(ray.d),
    }
}

/// Radiance along `ray`, whose first surface is not a null boundary, among
/// `media` (Beer's law of a non-volumetric scene applied here, at the exit).
fn shade(
    scene: &Scene,
    ray: Ray,
    sampler: &mut Sampler,
    (segment, weight): (u32, f32),
    media: MediumStack,
) -> Vec3 {
    let s = &scene.settings;
    let Some(mut hit) = scene.intersect(&ray, T_MIN, f32::INFINITY) else {
        return scene.environment(ray.d);
    };
    let wo = -ray.d;
    let mut textured = None;
    let m = scene.material_at(&mut hit, wo, ray.time, &mut textured);
    let mut l = m.emitted(wo, hit.n_geo);
    if segment >= s.max_depth {
        return l;
    }
    if m.has_smooth_lobe() {
        sampler.start(segment - 1, Draws::Light);
        l += direct(scene, (&hit, m, wo), ray.time, media, sampler);
    }
    if let Some(albedo) = m.ambient_albedo() {
        l += albedo * s.ambient;
    }
    // The reflected and refracted branches, unless their weight in the
    // pixel is below the bailout.
    // The branches after the first draw from the PCG stream: the first
    // one's subtree has used the later bounces' slots.
    let outside = wo.dot(hit.n_geo) >= 0.0;
    sampler.start(segment - 1, Draws::Bsdf);
    l += m.specular_light(wo, hit.n_shading, outside, sampler, |sampler, k, dir| {
        let w = weight * k;
        if w < BAILOUT {
            return Vec3::ZERO;
        }
        let r = Ray::new(offset_origin(hit.p, hit.n_geo, dir), dir, ray.time);
        let inside = media.towards(scene, (&hit, m), wo, dir);
        let l = trace_in(scene, r, sampler, (segment + 1, w), inside);
        sampler.pad();
        l
    });
    // Beer's law over the segment just travelled inside this object (a
    // volumetric scene's media are crossed by `trace_in`).
    if let (Some(medium), false) = (m.interior(), scene.volumetric) {
        if !outside {
            l *= medium.transmittance(hit.t);
        }
    }
    l
}

/// Direct light: from every light when there are few (one shadow ray per
/// delta light, `light_samples` per area light and for the light at
/// infinity), else from `light_samples` lights chosen by the scene's light
/// selection, each divided by the probability of its choice. With
/// `light_samples 0`, delta lights only.
fn direct(
    scene: &Scene,
    (hit, m, wo): (&Hit, &Material, Vec3),
    time: f32,
    media: MediumStack,
    sampler: &mut Sampler,
) -> Vec3 {
    let n = scene.settings.light_samples.max(1);
    let only_delta = scene.settings.light_samples == 0;
    if scene.lights.len() > EVERY_LIGHT_UP_TO {
        let mut acc = Vec3::ZERO;
        for _ in 0..n {
            let u = sampler.next_f64();
            let Some((i, pmf)) = scene.light_sampler.sample(hit.p, hit.n_shading, u) else {
                continue;
            };
            let light = &scene.lights[i as usize];
            let u = sampler.next_2d();
            if only_delta && !light.is_delta() {
                continue;
            }
            acc += light_sample(scene, (hit, m, wo), (time, media), light, u) / pmf;
        }
        return acc / n as f32;
    }
    let mut l = Vec3::ZERO;
    for light in &scene.lights {
        if only_delta && !light.is_delta() {
            continue;
        }
        let count = if light.is_delta() { 1 } else { n };
        let mut acc = Vec3::ZERO;
        for _ in 0..count {
            acc += light_sample(scene, (hit, m, wo), (time, media), light, sampler.next_2d());
        }
        l += acc / count as f32;
    }
    l
}

/// Lights up to which Whitted sends shadow rays to every light (each
/// `light_samples` times: beyond a few dozen lights, that many shadow rays
/// per hit cost more than a chosen few).
const EVERY_LIGHT_UP_TO: usize = 16;

/// One shadow ray to `light` from `hit` with the sample `u`: the light it
/// brings, reflected towards `wo` (divided by the pdf of the point on the
/// light; zero when it is blocked).
fn light_sample(
    scene: &Scene,
    (hit, m, wo): (&Hit, &Material, Vec3),
    (time, media): (f32, MediumStack),
    light: &Light,
    u: glam::Vec2,
) -> Vec3 {
    let Some(ls) = light.sample(
        |prim, q, uv, n, w| scene.emitted_at(prim, q, uv, n, w, time),
        hit.p,
        time,
        u,
    ) else {
        return Vec3::ZERO;
    };
    if super::crosses_surface(hit, wo, ls.wi) {
        return Vec3::ZERO;
    }
    let (f, _) = m.eval(wo, ls.wi, hit.n_shading);
    if f == Vec3::ZERO {
        return Vec3::ZERO;
    }
    let (shadow, t_max) = super::shadow_ray(hit, ls.wi, ls.dist, time);
    let tr = if scene.volumetric {
        let media = media.towards(scene, (hit, m), wo, ls.wi);
        scene.transmittance(&shadow, t_max, media)
    } else if scene.occluded(&shadow, T_MIN, t_max) {
        Vec3::ZERO
    } else {
        Vec3::ONE
    };
    if tr == Vec3::ZERO {
        return Vec3::ZERO;
    }
    let cos = ls.wi.dot(hit.n_shading).abs();
    if light.is_delta() {
        tr * f * ls.li * cos
    } else {
        tr * f * ls.li * cos / ls.pdf
    }
}
