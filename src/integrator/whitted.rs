//! Recursive ray tracing (Whitted 1980) with distribution effects (Cook
//! 1984): direct light with shadow rays from every light (several per area
//! light, for soft shadows; from lights chosen by the light selection when
//! there are many), the ambient term, mirror and glossy reflection,
//! refraction weighted by exact Fresnel with total internal reflection, and
//! Beer's law. Indirect diffuse light is not computed: that is the path
//! integrator's job.
//!
//! `.pts`: `render { integrator whitted  max_depth 8  light_samples 4  ambient rgb 0.05 }`.

use super::{Integrator, T_MIN};
use crate::geometry::{offset_origin, Ray};
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

/// Radiance along `ray`, which is path segment number `segment` and counts
/// with `weight` (largest channel of the product of factors so far) in the pixel.
pub fn trace(scene: &Scene, ray: Ray, sampler: &mut Sampler, segment: u32, weight: f32) -> Vec3 {
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
        l += direct(scene, &hit, m, wo, ray.time, sampler);
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
        let l = trace(scene, r, sampler, segment + 1, w);
        sampler.pad();
        l
    });
    // Beer's law over the segment just travelled inside this object.
    if let Some(medium) = m.interior() {
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
    hit: &Hit,
    m: &Material,
    wo: Vec3,
    time: f32,
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
            acc += light_sample(scene, hit, m, wo, time, light, u) / pmf;
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
            acc += light_sample(scene, hit, m, wo, time, light, sampler.next_2d());
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
    hit: &Hit,
    m: &Material,
    wo: Vec3,
    time: f32,
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
    if scene.occluded(&shadow, T_MIN, t_max) {
        return Vec3::ZERO;
    }
    let cos = ls.wi.dot(hit.n_shading).abs();
    if light.is_delta() {
        f * ls.li * cos
    } else {
        f * ls.li * cos / ls.pdf
    }
}
