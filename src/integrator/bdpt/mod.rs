//! Bidirectional path tracing (Veach & Guibas 1995; Veach 1997, ch. 10;
//! pbrt-v4 §13.4): a camera path and a light path per sample, joined at
//! every pair of their vertices, each join weighted by the power heuristic
//! over all the ways the same path could have been sampled ([`mis`]).
//! Light paths find what camera paths miss: a caustic (light through
//! glass onto a diffuse floor) is a light path that lands on the floor and
//! is joined to the camera (t = 1: the sample adds light to the pixel it
//! lands in, a [`Splat`]) or to a camera path's diffuse vertex.
//!
//! `.pts`: `render { integrator bdpt }`. Lights at infinity start no light
//! paths (their light reaches the camera's side through next-event
//! estimation and rays that leave the scene); light paths reach only a
//! pinhole camera (with a lens, strategies t = 1 are off). Media are not
//! traced bidirectionally: a scene with them renders with the path
//! integrator (`integrator::make`).

pub mod mis;
pub mod walk;

use super::{shadow_ray, Integrator, Splat, T_MIN};
use crate::ir::Scene;
use crate::light::emission::EmissionSelection;
use crate::light::Light;
use crate::sampling::sampler::{Draws, Sampler};
use glam::Vec3;
use mis::PathDensities;
use walk::{to_area, Role, Vertex};

/// The bidirectional path tracer of a scene.
pub struct Bdpt {
    /// Where light paths start (`None`: no light starts one).
    emission: Option<EmissionSelection>,
    /// Whether camera and light paths are also joined between their inner
    /// vertices (`bdpt`), or only to the camera and to the lights (`ptlt`).
    inner: bool,
}

impl Bdpt {
    /// The integrator for `scene`: its lights' emission chosen by power;
    /// `inner`: whether inner vertices are joined too (see [`Bdpt`]).
    pub fn new(scene: &Scene, inner: bool) -> Bdpt {
        let emission = (scene.light_powers.len() == scene.lights.len())
            .then(|| EmissionSelection::new(&scene.lights, &scene.light_powers))
            .flatten();
        Bdpt { emission, inner }
    }
}

impl Integrator for Bdpt {
    /// The sample's own pixel's share only: the light paths' joins to the
    /// camera (weighted to make up the rest) are dropped, so alone this is
    /// not the radiance; the pixel loop calls [`Integrator::li_splatting`].
    fn li(&self, scene: &Scene, ray: crate::geometry::Ray, sampler: &mut Sampler) -> Vec3 {
        self.li_splatting(scene, ray, sampler, &mut Vec::new())
    }

    fn splats(&self) -> bool {
        true
    }

    fn li_splatting(
        &self,
        scene: &Scene,
        ray: crate::geometry::Ray,
        sampler: &mut Sampler,
        splats: &mut Vec<Splat>,
    ) -> Vec3 {
        // A thread's buffers serve all its samples: allocating them for
        // each sample cost 9 % of a ptlt render's instructions.
        SCRATCH.with(|cell| match cell.try_borrow_mut() {
            Ok(mut scratch) => self.sample(scene, ray, sampler, splats, &mut scratch),
            Err(_) => self.sample(scene, ray, sampler, splats, &mut Scratch::default()),
        })
    }
}

/// The buffers one sample fills: its two subpaths and a path's densities.
#[derive(Default)]
struct Scratch {
    camera: Vec<Vertex>,
    light: Vec<Vertex>,
    densities: PathDensities,
}

thread_local! {
    /// Each thread's [`Scratch`].
    static SCRATCH: std::cell::RefCell<Scratch> = std::cell::RefCell::new(Scratch::default());
}

impl Bdpt {
    /// One sample: its camera path and light path, joined.
    fn sample(
        &self,
        scene: &Scene,
        ray: crate::geometry::Ray,
        sampler: &mut Sampler,
        splats: &mut Vec<Splat>,
        scratch: &mut Scratch,
    ) -> Vec3 {
        let max_depth = scene.settings.max_depth as usize;
        let Scratch {
            camera,
            light,
            densities,
        } = scratch;
        walk::camera_path(scene, ray, max_depth + 1, camera, sampler);
        // The light path draws from the PCG stream, after every slot.
        sampler.pad();
        light.clear();
        if let Some(emission) = &self.emission {
            walk::light_path(scene, emission, ray.time, max_depth, light, sampler);
        }
        let (camera, light) = (&camera[..], &light[..]);
        let mut joins = Joins {
            scene,
            emission: self.emission.as_ref(),
            camera,
            light,
            time: ray.time,
            light_end: None,
            inner: self.inner,
        };
        if let (Some(Role::Light { light: index }), Some(second)) =
            (light.first().map(|v| v.role), light.get(1))
        {
            let end = joins.light_end(index, second, (light[0].p, light[0].n_geo));
            joins.light_end = Some(LightEnd {
                emission: light[0].from_light,
                ..end
            });
        }
        let mut radiance = Vec3::ZERO;
        for t in 1..=camera.len() {
            for s in 0..=light.len().max(1) {
                let k = s + t - 1;
                if k == 0 || (s == 1 && t == 1) || k > max_depth {
                    continue;
                }
                let d = &mut *densities;
                let l = match (s, t) {
                    (0, _) => joins.emitter_hit(t, d),
                    (_, 1) => {
                        joins.to_camera(s, d, splats);
                        Vec3::ZERO
                    }
                    (1, _) => joins.next_event(t, d, sampler),
                    _ if self.inner => joins.connect(s, t, d),
                    _ => Vec3::ZERO,
                };
                if l.is_finite() {
                    radiance += l;
                }
            }
        }
        radiance
    }
}

/// One sample's two subpaths and what joining them needs.
struct Joins<'a> {
    scene: &'a Scene,
    emission: Option<&'a EmissionSelection>,
    camera: &'a [Vertex],
    light: &'a [Vertex],
    time: f32,
    /// The light path's end seen from its second vertex (`None` for a
    /// light path of fewer than two vertices).
    light_end: Option<LightEnd>,
    /// Whether inner vertices are joined.
    inner: bool,
}

/// What a path's light end is to the MIS weights.
#[derive(Debug, Clone, Copy)]
struct LightEnd {
    hittable: bool,
    nee: f32,
    emission: f32,
}

impl LightEnd {
    /// Sets `d`'s light-end densities.
    fn apply(self, d: &mut PathDensities) {
        d.hittable = self.hittable;
        d.nee = self.nee;
        d.emission = self.emission;
    }
}

impl Joins<'_> {
    /// Fills `d` with the densities of the path made of the camera's first
    /// `t` vertices and the light's first `s` (reversed); the joins then
    /// set the densities their join changes.
    fn fill(&self, s: usize, t: usize, d: &mut PathDensities) {
        d.reset(s + t);
        let path = self.camera[..t].iter().chain(self.light[..s].iter().rev());
        for (i, v) in path.enumerate() {
            d.from_camera[i] = v.from_camera;
            d.from_light[i] = v.from_light;
            d.delta[i] = v.delta;
        }
        d.camera_connects = !self.scene.camera.uses_lens();
        d.inner = self.inner;
    }

    /// What the light at the path's end is to the other strategies: its
    /// next-event density seen from `from`, its emission density, and
    /// whether rays can hit it.
    fn light_end(&self, light: u32, from: &Vertex, (p, n): (Vec3, Vec3)) -> LightEnd {
        let scene = self.scene;
        let l = &scene.lights[light as usize];
        let pick = scene.light_sampler.pmf(from.p, from.n_shading, light);
        let nee = match l {
            Light::Environment { .. } | Light::Sky { .. } => pick * l.direction_pdf(p),
            _ if l.is_delta() => pick,
            _ => {
                let dir = (p - from.p).normalize_or_zero();
                to_area(pick * l.pdf_towards(from.p, dir, p, n), from.p, p, n)
            }
        };
        let emission = match (self.emission, l.starts_paths()) {
            (Some(e), true) => e.pmf(light) * l.emission_pdfs(n, Vec3::Z, false).0,
            _ => 0.0,
        };
        LightEnd {
            hittable: !l.is_delta(),
            nee,
            emission,
        }
    }

    /// [`Joins::light_end`] into `d`.
    fn endpoint(&self, light: u32, from: &Vertex, at: (Vec3, Vec3), d: &mut PathDensities) {
        self.light_end(light, from, at).apply(d);
    }

    /// The light path's end as the joins with it see it (the same for
    /// every join of a sample: found once).
    fn light_path_end(&self, d: &mut PathDensities) -> bool {
        match self.light_end {
            Some(end) => {
                end.apply(d);
                true
            }
            None => false,
        }
    }

    /// The density with which light `light` (at `p`, normal `n`) emits
    /// towards `to`, by area at `to`.
    fn emitted_towards(&self, light: u32, (p, n): (Vec3, Vec3), to: &Vertex) -> f32 {
        let l = &self.scene.lights[light as usize];
        let two_sided = walk::two_sided(self.scene, light);
        let dir = (to.p - p).normalize_or_zero();
        to_area(l.emission_pdfs(n, dir, two_sided).1, p, to.p, to.n_geo)
    }

    /// s = 0: the camera's path itself hit an emitter (or left the scene)
    /// at its vertex t − 1.
    fn emitter_hit(&self, t: usize, d: &mut PathDensities) -> Vec3 {
        let v = &self.camera[t - 1];
        let prev = &self.camera[t - 2];
        let scene = self.scene;
        let (le, light) = match v.role {
            Role::Background => {
                let Some(env) = scene.env_light else {
                    return Vec3::ZERO;
                };
                (scene.lights[env as usize].arriving_from(v.p), Some(env))
            }
            Role::Surface => {
                let (Some(m), Some(hit)) = (v.material(scene), &v.hit) else {
                    return Vec3::ZERO;
                };
                (m.emitted(v.wo, hit.n_geo), scene.area_light_at(hit))
            }
            _ => return Vec3::ZERO,
        };
        if le == Vec3::ZERO {
            return Vec3::ZERO;
        }
        self.fill(0, t, d);
        let k = t - 1;
        match light {
            Some(light) => {
                self.endpoint(light, prev, (v.p, v.n_geo), d);
                if v.role == Role::Surface {
                    d.from_light[k - 1] = self.emitted_towards(light, (v.p, v.n_geo), prev);
                }
            }
            // An emitter no light stands for (inside a shared group):
            // only this strategy finds it.
            None => {
                d.hittable = true;
                d.nee = 0.0;
                d.emission = 0.0;
            }
        }
        v.beta * le * d.weight(0)
    }

    /// t = 1: the light path's vertex s − 1 joined to the camera, added to
    /// the pixel it lands in.
    fn to_camera(&self, s: usize, d: &mut PathDensities, splats: &mut Vec<Splat>) {
        let y = &self.light[s - 1];
        if !y.connectible() || y.role != Role::Surface {
            return;
        }
        let camera = &self.scene.camera;
        let Some((film, _, pdf_camera)) = camera.project(y.p) else {
            return;
        };
        let to_camera = camera.position() - y.p;
        let dist = to_camera.length();
        let wc = to_camera / dist;
        let (f, _, pdf_back) = y.f(self.scene, y.wo, wc, true);
        if f == Vec3::ZERO {
            return;
        }
        let value = y.beta * f * wc.dot(y.n_shading).abs() / (dist * dist) * pdf_camera;
        if value == Vec3::ZERO || !value.is_finite() {
            return;
        }
        let (ray, t_max) = shadow_ray(y.hit.as_ref().unwrap(), wc, dist, self.time);
        if self.scene.occluded(&ray, T_MIN, t_max) {
            return;
        }
        self.fill(s, 1, d);
        d.from_camera[1] = to_area(pdf_camera, camera.position(), y.p, y.n_geo);
        if s >= 2 {
            let next = &self.light[s - 2];
            d.from_camera[2] = to_area(pdf_back, y.p, next.p, next.n_geo);
        }
        d.delta[1] = false;
        if !self.light_path_end(d) {
            return;
        }
        let w = d.weight(s);
        if w > 0.0 {
            splats.push(Splat {
                film,
                value: value * w,
            });
        }
    }

    /// s = 1: next-event estimation from the camera path's vertex t − 1.
    fn next_event(&self, t: usize, d: &mut PathDensities, sampler: &mut Sampler) -> Vec3 {
        let x = &self.camera[t - 1];
        if !x.connectible() || x.role != Role::Surface {
            return Vec3::ZERO;
        }
        let scene = self.scene;
        sampler.start(t as u32 - 2, Draws::Light);
        let u = sampler.next_f64();
        let Some((light, pick)) = scene.light_sampler.sample(x.p, x.n_shading, u) else {
            return Vec3::ZERO;
        };
        let u = sampler.next_2d();
        let l = &scene.lights[light as usize];
        let time = self.time;
        let emitted = |prim, q, uv, n, w| scene.emitted_at(prim, q, uv, n, w, time);
        let Some(ls) = l.sample(emitted, x.p, time, u) else {
            return Vec3::ZERO;
        };
        let (f, pdf_fwd, pdf_back) = x.f(self.scene, x.wo, ls.wi, false);
        if f == Vec3::ZERO {
            return Vec3::ZERO;
        }
        let hit = x.hit.as_ref().unwrap();
        let (ray, t_max) = shadow_ray(hit, ls.wi, ls.dist, time);
        if scene.occluded(&ray, T_MIN, t_max) {
            return Vec3::ZERO;
        }
        let cos = ls.wi.dot(x.n_shading).abs();
        let value = if l.is_delta() {
            x.beta * f * cos * ls.li / pick
        } else {
            x.beta * f * cos * ls.li / (pick * ls.pdf)
        };
        self.fill(0, t, d);
        d.from_camera.push(0.0);
        d.from_light.push(0.0);
        d.delta.push(false);
        d.delta[t - 1] = false;
        let at_infinity = !ls.dist.is_finite();
        let (p, n) = if at_infinity {
            (ls.wi, Vec3::ZERO)
        } else {
            (x.p + ls.wi * ls.dist, ls.n)
        };
        self.endpoint(light, x, (p, n), d);
        if at_infinity {
            d.from_camera[t] = pdf_fwd;
        } else {
            d.from_camera[t] = to_area(pdf_fwd, x.p, p, n);
            d.from_light[t - 1] = self.emitted_towards(light, (p, n), x);
        }
        let prev = &self.camera[t - 2];
        d.from_light[t - 2] = to_area(pdf_back, x.p, prev.p, prev.n_geo);
        value * d.weight(1)
    }

    /// s ≥ 2, t ≥ 2: the camera path's vertex t − 1 joined to the light
    /// path's vertex s − 1.
    fn connect(&self, s: usize, t: usize, d: &mut PathDensities) -> Vec3 {
        let (x, y) = (&self.camera[t - 1], &self.light[s - 1]);
        if !x.connectible()
            || !y.connectible()
            || x.role != Role::Surface
            || y.role != Role::Surface
        {
            return Vec3::ZERO;
        }
        let to = y.p - x.p;
        let dist2 = to.length_squared();
        if dist2 == 0.0 {
            return Vec3::ZERO;
        }
        let dist = dist2.sqrt();
        let w = to / dist;
        let (fx, px_fwd, px_back) = x.f(self.scene, x.wo, w, false);
        let (fy, py_fwd, py_back) = y.f(self.scene, y.wo, -w, true);
        let g = w.dot(x.n_shading).abs() * w.dot(y.n_shading).abs() / dist2;
        let value = x.beta * fx * g * fy * y.beta;
        if value == Vec3::ZERO || !value.is_finite() {
            return Vec3::ZERO;
        }
        let (ray, t_max) = shadow_ray(x.hit.as_ref().unwrap(), w, dist, self.time);
        if self.scene.occluded(&ray, T_MIN, t_max) {
            return Vec3::ZERO;
        }
        self.fill(s, t, d);
        let k = s + t - 1;
        d.from_camera[t] = to_area(px_fwd, x.p, y.p, y.n_geo);
        d.from_light[t - 1] = to_area(py_fwd, y.p, x.p, x.n_geo);
        let before = &self.camera[t - 2];
        d.from_light[t - 2] = to_area(px_back, x.p, before.p, before.n_geo);
        if t < k {
            let after = &self.light[s - 2];
            d.from_camera[t + 1] = to_area(py_back, y.p, after.p, after.n_geo);
        }
        d.delta[t - 1] = false;
        d.delta[t] = false;
        if !self.light_path_end(d) {
            return Vec3::ZERO;
        }
        value * d.weight(s)
    }
}
