//! Unbiased path tracing (Kajiya 1986) with next-event estimation and
//! multiple importance sampling (Veach 1997), Russian roulette that divides
//! by the survival probability, and `max_depth` counted in path segments.
//!
//! `.pts`: `render { integrator path  max_depth 8  rr_depth 5  light_sampling true }`.
//! With `light_sampling false` it is the paper's naive estimator (BSDF
//! sampling only), kept for comparison. `render { clamp X }` clamps indirect
//! light (biased, off by default: see [`add`]).

use super::{direct_light_mis, light_pdf, scaled_within, Integrator, T_MIN};
use crate::geometry::{offset_origin, Ray};
use crate::ir::{Hit, Scene};
use crate::sampling::sampler::{Draws, Sampler};
use crate::sampling::warp::power_heuristic;
use glam::Vec3;

/// The path integrator.
pub struct PathIntegrator;

impl Integrator for PathIntegrator {
    fn li(&self, scene: &Scene, ray: Ray, sampler: &mut Sampler) -> Vec3 {
        path_li(scene, ray, sampler, scene.settings.light_sampling)
    }

    fn takes_first_hit(&self, scene: &Scene) -> bool {
        !scene.volumetric
    }

    fn li_from(&self, scene: &Scene, ray: Ray, first: Option<Hit>, sampler: &mut Sampler) -> Vec3 {
        let nee = scene.settings.light_sampling;
        if scene.volumetric {
            return super::volpath::volpath_li(scene, ray, sampler, nee);
        }
        surface_path_li(scene, ray, Some(first), sampler, nee)
    }
}

/// The path-traced radiance along `ray`.
pub fn path_li(scene: &Scene, ray: Ray, sampler: &mut Sampler, nee: bool) -> Vec3 {
    if scene.volumetric {
        return super::volpath::volpath_li(scene, ray, sampler, nee);
    }
    surface_path_li(scene, ray, None, sampler, nee)
}

/// [`path_li`] in a scene without media; `first`, when given, is the
/// ray's first hit, found already (a packet's).
#[inline(always)]
fn surface_path_li(
    scene: &Scene,
    mut ray: Ray,
    mut first: Option<Option<Hit>>,
    sampler: &mut Sampler,
    nee: bool,
) -> Vec3 {
    let s = &scene.settings;
    let mut radiance = Vec3::ZERO;
    let mut beta = Vec3::ONE;
    // The previous bounce: its pdf (0 = delta) and position, for MIS on emitters hit.
    let mut prev_pdf = 0.0f32;
    let mut prev_p = ray.o;
    let mut prev_n = Vec3::ZERO;
    let mut segments = 0u32;
    loop {
        segments += 1;
        let hit = match first.take() {
            Some(hit) => hit,
            None => scene.intersect(&ray, T_MIN, f32::INFINITY),
        };
        let Some(mut hit) = hit else {
            if let Some(env) = scene.env_light {
                let light = &scene.lights[env as usize];
                let w = if nee && prev_pdf > 0.0 {
                    let pick = scene.light_sampler.pmf(prev_p, prev_n, env);
                    let lp = pick * light.direction_pdf(ray.d);
                    power_heuristic(prev_pdf, lp)
                } else {
                    1.0
                };
                let c = beta * light.arriving_from(ray.d) * w;
                add(&mut radiance, c, segments - 1, s.clamp);
            }
            break;
        };
        let wo = -ray.d;
        let mut textured = None;
        let material = scene.material_at(&mut hit, wo, ray.time, &mut textured);
        // Leaving a surface with a medium inside means we travelled in it.
        if let Some(medium) = material.interior() {
            if ray.d.dot(hit.n_geo) > 0.0 {
                beta *= medium.transmittance(hit.t);
            }
        }
        // Emission seen along the path.
        let le = material.emitted(wo, hit.n_geo);
        if le != Vec3::ZERO {
            let light = (nee && prev_pdf > 0.0).then(|| scene.area_light_at(&hit));
            let w = match light.flatten() {
                Some(light) => {
                    let from = [prev_p, prev_n];
                    power_heuristic(prev_pdf, light_pdf(scene, light, from, &hit, ray.d))
                }
                None => 1.0,
            };
            add(&mut radiance, beta * le * w, segments - 1, s.clamp);
        }
        if segments >= s.max_depth || !material.scatters() {
            break;
        }
        // Direct light (the paper's ambient term is added here when asked for: biased).
        let bounce = segments - 1;
        if nee && material.has_smooth_lobe() {
            sampler.start(bounce, Draws::Light);
            let c = beta * direct_light_mis(scene, &hit, material, wo, ray.time, sampler);
            add(&mut radiance, c, segments, s.clamp);
        }
        if s.ambient != Vec3::ZERO {
            if let Some(albedo) = material.ambient_albedo() {
                add(&mut radiance, beta * albedo * s.ambient, segments, s.clamp);
            }
        }
        // Continue the path by sampling the BSDF.
        let Some(bs) = super::continue_path(&hit, material, wo, bounce, sampler) else {
            break;
        };
        beta *= bs.weight;
        prev_pdf = bs.pdf;
        prev_p = hit.p;
        prev_n = hit.n_shading;
        // Russian roulette once the path has rr_depth segments, deciding on the
        // next one: Mitsuba 3's convention (its `depth >= rr_depth` after the
        // depth-th interaction), so that both trace paths of the same length
        // when timed side by side. Survivors are divided by their probability, so the
        // estimate stays unbiased. The survival probability follows the
        // largest channel of the throughput (as pbrt-v4 and Mitsuba 3 do):
        // luminance would end saturated red or blue paths too early and make
        // those channels noisy.
        if segments >= s.rr_depth {
            let q = beta.max_element().clamp(0.05, 0.95);
            sampler.start(bounce, Draws::Roulette);
            if sampler.next_f32() >= q {
                break;
            }
            beta /= q;
        }
        ray = Ray::new(offset_origin(hit.p, hit.n_geo, bs.wi), bs.wi, ray.time);
    }
    radiance
}

/// Adds the contribution `c` of light arriving at the path's `vertex`-th
/// surface hit (0: the camera sees it, 1: the first hit's direct light).
/// With `render { clamp X }`, light arriving at the second hit or later —
/// indirect light, which reaches the camera after at least one bounce — is
/// scaled down so that its largest RGB component is at most X, keeping its
/// hue (Cycles' "indirect light clamp"). Off, `c` is added as it is.
#[inline]
pub(super) fn add(radiance: &mut Vec3, c: Vec3, vertex: u32, clamp: Option<f32>) {
    *radiance += match clamp {
        Some(x) if vertex >= 2 => scaled_within(c, x),
        _ => c,
    };
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clamping_keeps_the_hue_and_only_touches_indirect_light() {
        let c = Vec3::new(40.0, 20.0, 10.0);
        assert_eq!(scaled_within(c, 4.0), Vec3::new(4.0, 2.0, 1.0));
        assert_eq!(scaled_within(c, 100.0), c);
        for (vertex, clamp, want) in [
            (0, Some(4.0), c),
            (1, Some(4.0), c),
            (2, Some(4.0), Vec3::new(4.0, 2.0, 1.0)),
            (5, None, c),
        ] {
            let mut r = Vec3::ONE;
            add(&mut r, c, vertex, clamp);
            assert_eq!(r, Vec3::ONE + want, "vertex {vertex} clamp {clamp:?}");
        }
    }
}
