//! Volumetric path tracing: the path integrator's form for scenes with
//! participating media or null boundaries (`ir::Scene::volumetric`), as
//! Mitsuba 3's `volpath` for homogeneous media. Along each segment a
//! distance is sampled in the medium it crosses, from the extinction of the
//! path's hero channel (drawn once per path); chromatic media are weighed
//! by spectral MIS over the whole path (`ratio` below; pbrt-v4's `r_u`), a
//! balance heuristic over the three channels' strategies that keeps the
//! weights bounded. A
//! scattering point samples a light through null boundaries and media
//! (transmittance, `ir::media`) and the Henyey–Greenstein phase function,
//! weighted against each other by the power heuristic (Veach 1997), as
//! surfaces do with their BSDF. A null boundary (`type none`) is crossed
//! without counting as a bounce and without changing the MIS state, so a
//! light seen through it is weighted as if the boundary were not there.
//!
//! Draws: surfaces and scattering points use their bounce's slots
//! (`Draws::Light`, `Bsdf`, `Roulette`); the distance sampling draws from
//! the sample's PCG stream, so scenes without media sample as before.

use super::path::add;
use super::{crosses_surface, light_pdf, T_MIN};
use crate::geometry::{offset_origin, Ray};
use crate::ir::media::{MediumStack, MAX_CROSSINGS};
use crate::ir::{Hit, Scene};
use crate::material::medium::Medium;
use crate::material::{phase, Material};
use crate::sampling::sampler::{Draws, Sampler};
use crate::sampling::warp::power_heuristic;
use glam::Vec3;

/// Where a path scatters: on a surface or inside a medium.
enum Vertex<'a> {
    /// A surface hit with its material, seen from `wo`.
    Surface(&'a Hit, &'a Material),
    /// A point in a medium of phase asymmetry `g`.
    Medium(Vec3, f32),
}

impl Vertex<'_> {
    /// Where it is, and the normal light selection weighs lights with
    /// (zero in a medium: light arrives from every side).
    fn point(&self) -> (Vec3, Vec3) {
        match self {
            Vertex::Surface(hit, _) => (hit.p, hit.n_shading),
            Vertex::Medium(p, _) => (*p, Vec3::ZERO),
        }
    }

    /// f·|cos| (the phase function in a medium) for `wo` → `wi`, and the
    /// pdf of sampling `wi`.
    fn eval(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        match self {
            Vertex::Surface(hit, m) => {
                if crosses_surface(hit, wo, wi) {
                    return (Vec3::ZERO, 0.0);
                }
                let (f, pdf) = m.eval(wo, wi, hit.n_shading);
                (f * wi.dot(hit.n_shading).abs(), pdf)
            }
            Vertex::Medium(_, g) => {
                let p = phase::eval(wo, wi, *g);
                (Vec3::splat(p), p)
            }
        }
    }

    /// The shadow ray towards a light point at `dist` along `wi`, and how
    /// far it must be free.
    fn shadow_ray(&self, wi: Vec3, dist: f32, time: f32) -> (Ray, f32) {
        match self {
            Vertex::Surface(hit, _) => super::shadow_ray(hit, wi, dist, time),
            Vertex::Medium(p, _) => (Ray::new(*p, wi, time), dist * (1.0 - 1e-4)),
        }
    }
}

/// Next-event estimation at `vertex` for outgoing direction `wo`: one light
/// chosen by the scene's light selection, its light attenuated by the media
/// and null boundaries in between, weighted against sampling the vertex's
/// BSDF or phase function with the power heuristic.
fn direct_light(
    scene: &Scene,
    vertex: &Vertex,
    wo: Vec3,
    media: MediumStack,
    time: f32,
    sampler: &mut Sampler,
) -> Vec3 {
    let (p, n) = vertex.point();
    let u = sampler.next_f64();
    let Some((li_idx, pick_pdf)) = scene.light_sampler.sample(p, n, u) else {
        return Vec3::ZERO;
    };
    let u = sampler.next_2d();
    let light = &scene.lights[li_idx as usize];
    let emitted = |prim, q, uv, n, w| scene.emitted_at(prim, q, uv, n, w, time);
    let Some(ls) = light.sample(emitted, p, time, u) else {
        return Vec3::ZERO;
    };
    let (f, pdf) = vertex.eval(wo, ls.wi);
    if f == Vec3::ZERO {
        return Vec3::ZERO;
    }
    let (shadow, t_max) = vertex.shadow_ray(ls.wi, ls.dist, time);
    let media = match vertex {
        Vertex::Surface(hit, m) => media.towards(scene, (hit, m), wo, ls.wi),
        Vertex::Medium(..) => media,
    };
    let tr = scene.transmittance(&shadow, t_max, media);
    if tr == Vec3::ZERO {
        return Vec3::ZERO;
    }
    if light.is_delta() {
        return f * tr * ls.li / pick_pdf;
    }
    let light_pdf = ls.pdf * pick_pdf;
    f * tr * ls.li * power_heuristic(light_pdf, pdf) / light_pdf
}

/// The state a path carries from one scattering vertex to the next.
struct PathState {
    radiance: Vec3,
    beta: Vec3,
    /// The last vertex's sampling pdf (0: delta) and position and normal,
    /// for MIS on emitters hit.
    prev_pdf: f32,
    prev_p: Vec3,
    prev_n: Vec3,
    media: MediumStack,
    /// The channel whose extinction samples distances (drawn at the
    /// path's first medium).
    hero: Option<usize>,
    /// Each channel's probability of the path's distance decisions had it
    /// been the hero, relative to their average (which is 1): `beta` is
    /// the path's contribution divided by that average, the balance
    /// heuristic's estimate.
    ratio: Vec3,
}

/// The volumetric path-traced radiance along `ray` (`nee`: sample lights).
pub fn volpath_li(scene: &Scene, mut ray: Ray, sampler: &mut Sampler, nee: bool) -> Vec3 {
    let s = &scene.settings;
    let mut st = PathState {
        radiance: Vec3::ZERO,
        beta: Vec3::ONE,
        prev_pdf: 0.0,
        prev_p: ray.o,
        prev_n: Vec3::ZERO,
        media: scene.camera_media,
        hero: None,
        ratio: Vec3::ONE,
    };
    let mut segments = 0u32;
    let mut crossings = 0u32;
    loop {
        segments += 1;
        let bounce = segments - 1;
        let mut hit = scene.intersect(&ray, T_MIN, f32::INFINITY);
        let mut slot = None;
        let material = (hit.as_mut()).map(|h| scene.material_at(h, -ray.d, ray.time, &mut slot));
        let end = hit.as_ref().zip(material);
        let t_end = hit.as_ref().map_or(f32::INFINITY, |h| h.t);
        // The medium of this segment: scatter in it, or pass through it.
        let segment = st.media.segment(scene, ray.d, end);
        if let Some(span) = scene.medium_span(segment, &ray, t_end) {
            match through_medium(scene, &ray, span, (&mut st, segments), sampler, nee) {
                InMedium::Passed => {}
                InMedium::Scattered(next) => {
                    crossings = 0;
                    ray = next;
                    continue;
                }
                InMedium::Ended => break,
            }
        }
        let (Some(hit), Some(material)) = (hit.as_ref(), material) else {
            escaped(scene, &ray, &mut st, segments, nee);
            break;
        };
        let wo = -ray.d;
        // A null boundary: cross it, as if it were not there.
        if material.is_null() {
            crossings += 1;
            if crossings > MAX_CROSSINGS {
                break;
            }
            st.media.cross(scene, ray.d, hit, material);
            ray = Ray::new(offset_origin(hit.p, hit.n_geo, ray.d), ray.d, ray.time);
            segments -= 1;
            continue;
        }
        crossings = 0;
        // Emission seen along the path.
        let le = material.emitted(wo, hit.n_geo);
        if le != Vec3::ZERO {
            let light = (nee && st.prev_pdf > 0.0).then(|| scene.area_light_at(hit));
            let w = match light.flatten() {
                Some(light) => {
                    let from = [st.prev_p, st.prev_n];
                    power_heuristic(st.prev_pdf, light_pdf(scene, light, from, hit, ray.d))
                }
                None => 1.0,
            };
            add(&mut st.radiance, st.beta * le * w, segments - 1, s.clamp);
        }
        if segments >= s.max_depth || !material.scatters() {
            break;
        }
        if nee && material.has_smooth_lobe() {
            sampler.start(bounce, Draws::Light);
            let vertex = Vertex::Surface(hit, material);
            let c = direct_light(scene, &vertex, wo, st.media, ray.time, sampler);
            add(&mut st.radiance, st.beta * c, segments, s.clamp);
        }
        if s.ambient != Vec3::ZERO {
            if let Some(albedo) = material.ambient_albedo() {
                add(
                    &mut st.radiance,
                    st.beta * albedo * s.ambient,
                    segments,
                    s.clamp,
                );
            }
        }
        let Some(bs) = super::continue_path(hit, material, wo, bounce, sampler) else {
            break;
        };
        st.beta *= bs.weight;
        st.prev_pdf = bs.pdf;
        st.prev_p = hit.p;
        st.prev_n = hit.n_shading;
        st.media = st.media.towards(scene, (hit, material), wo, bs.wi);
        if !roulette(&mut st.beta, segments, s.rr_depth, bounce, sampler) {
            break;
        }
        ray = Ray::new(offset_origin(hit.p, hit.n_geo, bs.wi), bs.wi, ray.time);
    }
    st.radiance
}

/// What a segment's medium did to a path.
enum InMedium {
    /// It passed through to the segment's end (attenuated).
    Passed,
    /// It scattered, and goes on along this ray.
    Scattered(Ray),
    /// It ended there.
    Ended,
}

/// Samples where the path along `ray` scatters in `medium` over `[t0, t1]`;
/// at a scattering point (the path's vertex `segments`), samples a light
/// and the phase function.
fn through_medium(
    scene: &Scene,
    ray: &Ray,
    (medium, t0, t1): (Medium, f32, f32),
    (st, segments): (&mut PathState, u32),
    sampler: &mut Sampler,
    nee: bool,
) -> InMedium {
    if !medium.scatters() {
        st.beta *= medium.transmittance(t1 - t0);
        return InMedium::Passed;
    }
    let s = &scene.settings;
    sampler.pad();
    let hero = *(st.hero).get_or_insert_with(|| ((sampler.next_f32() * 3.0) as usize).min(2));
    let d = medium.sample_distance(t1 - t0, hero, sampler.next_f32());
    let mean = (st.ratio * d.pdf).element_sum() / 3.0;
    if mean.is_nan() || mean <= 0.0 || st.beta == Vec3::ZERO {
        return InMedium::Ended;
    }
    st.beta *= d.value / mean;
    st.ratio = st.ratio * d.pdf / mean;
    if !d.scattered {
        return InMedium::Passed;
    }
    if segments >= s.max_depth {
        return InMedium::Ended;
    }
    let (p, wo, bounce) = (ray.o + ray.d * (t0 + d.t), -ray.d, segments - 1);
    if nee {
        sampler.start(bounce, Draws::Light);
        let vertex = Vertex::Medium(p, medium.anisotropy);
        let c = direct_light(scene, &vertex, wo, st.media, ray.time, sampler);
        add(&mut st.radiance, st.beta * c, segments, s.clamp);
    }
    sampler.start(bounce, Draws::Bsdf);
    let (wi, pdf) = phase::sample(wo, medium.anisotropy, sampler.next_2d());
    st.prev_pdf = pdf;
    st.prev_p = p;
    st.prev_n = Vec3::ZERO;
    if !roulette(&mut st.beta, segments, s.rr_depth, bounce, sampler) {
        return InMedium::Ended;
    }
    InMedium::Scattered(Ray::new(p, wi, ray.time))
}

/// Light from the environment along a ray that left the scene (already
/// attenuated by the media it crossed).
fn escaped(scene: &Scene, ray: &Ray, st: &mut PathState, segments: u32, nee: bool) {
    let Some(env) = scene.env_light else {
        return;
    };
    let light = &scene.lights[env as usize];
    let w = if nee && st.prev_pdf > 0.0 {
        let pick = scene.light_sampler.pmf(st.prev_p, st.prev_n, env);
        power_heuristic(st.prev_pdf, pick * light.direction_pdf(ray.d))
    } else {
        1.0
    };
    let c = st.beta * light.arriving_from(ray.d) * w;
    add(&mut st.radiance, c, segments - 1, scene.settings.clamp);
}

/// Russian roulette after `segments` segments, from `rr_depth` on: a path
/// whose throughput's largest channel is below 1 survives with that
/// probability and is divided by it (pbrt-v4's rule); one at 1 or above
/// goes on (`max_depth` ends it). Unlike `path`'s cap of 0.95, this never
/// raises a throughput above 1, which keeps the long random walks of
/// media of albedo near 1 from heavy tails (a white furnace's pixels
/// strayed by 0.75 at 96 spp with the cap).
fn roulette(beta: &mut Vec3, segments: u32, rr_depth: u32, bounce: u32, s: &mut Sampler) -> bool {
    let q = beta.max_element();
    if segments < rr_depth || q >= 1.0 {
        return true;
    }
    s.start(bounce, Draws::Roulette);
    if s.next_f32() >= q {
        return false;
    }
    *beta /= q;
    true
}
