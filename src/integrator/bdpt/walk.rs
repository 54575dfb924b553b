//! The two random walks of bidirectional path tracing: the camera's path
//! and the light's, each vertex with its throughput and the densities with
//! which either side would generate it (Veach 1997, §10.2; pbrt-v4
//! §13.4.1–13.4.2).

use crate::geometry::{offset_origin, Ray};
use crate::integrator::T_MIN;
use crate::ir::{Hit, Scene};
use crate::light::emission::EmissionSelection;
use crate::material::Material;
use crate::sampling::sampler::{Draws, Sampler};
use glam::Vec3;

/// What a vertex is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Role {
    /// The camera's position.
    Camera,
    /// Where a light path starts: light `light`.
    Light {
        /// Its index among the scene's lights.
        light: u32,
    },
    /// A surface point.
    Surface,
    /// Where a camera path leaves the scene towards the background light.
    Background,
}

/// One vertex of a subpath.
#[derive(Debug, Clone)]
pub struct Vertex {
    /// What it is.
    pub role: Role,
    /// Where it is (for the background: the direction the path left in).
    pub p: Vec3,
    /// The surface's geometric normal (a light's, zero at a point).
    pub n_geo: Vec3,
    /// The shading normal.
    pub n_shading: Vec3,
    /// The surface hit (surfaces only).
    pub hit: Option<Hit>,
    /// The material there (surfaces only).
    pub material: Option<MaterialAt>,
    /// Whether the material has a non-delta lobe (joins can be made here).
    pub smooth: bool,
    /// Unit direction towards the subpath's previous vertex.
    pub wo: Vec3,
    /// The subpath's throughput up to and including arriving here.
    pub beta: Vec3,
    /// Density of generating it from the camera's side.
    pub from_camera: f32,
    /// Density of generating it from the light's side.
    pub from_light: f32,
    /// Whether the subpath left it through a delta lobe.
    pub delta: bool,
}

/// A surface vertex's material: the scene's (found again from the hit),
/// or one its textures made for the hit (boxed: a vertex stays small).
#[derive(Debug, Clone)]
pub enum MaterialAt {
    /// The scene's material of the hit's primitive.
    Scene,
    /// Made for the hit by its textures.
    Made(Box<Material>),
}

impl Vertex {
    /// The material of a surface vertex.
    pub fn material<'a>(&'a self, scene: &'a Scene) -> Option<&'a Material> {
        match (&self.material, &self.hit) {
            (Some(MaterialAt::Made(m)), _) => Some(m),
            (Some(MaterialAt::Scene), Some(hit)) => Some(scene.material_of_hit(hit)),
            _ => None,
        }
    }

    /// Whether a connection can be made at it (a surface with a non-delta
    /// lobe).
    pub fn connectible(&self) -> bool {
        match self.role {
            Role::Surface => self.smooth,
            Role::Light { .. } | Role::Camera => true,
            Role::Background => false,
        }
    }

    /// f at this surface vertex for light arriving from `wi` and leaving
    /// towards `wo`, as the camera's side sees it (radiance) or the
    /// light's (importance, with the shading-normal correction of Veach
    /// 1997 §5.3), and the densities of sampling `wi` from `wo` and back.
    pub fn f(&self, scene: &Scene, wo: Vec3, wi: Vec3, importance: bool) -> (Vec3, f32, f32) {
        let (Some(m), Some(hit)) = (self.material(scene), &self.hit) else {
            return (Vec3::ZERO, 0.0, 0.0);
        };
        if crate::integrator::crosses_surface(hit, wo, wi) {
            return (Vec3::ZERO, 0.0, 0.0);
        }
        let (f, pdf) = m.eval(wo, wi, hit.n_shading);
        let (_, pdf_back) = m.eval(wi, wo, hit.n_shading);
        let f = if importance {
            f * shading_correction(hit, wo, wi)
        } else {
            f
        };
        (f, pdf, pdf_back)
    }
}

/// Veach's adjoint factor for shading normals, |wo·ns||wi·ng| / (|wo·ng||wi·ns|),
/// with `wo` the direction importance leaves towards (pbrt-v4's
/// `CorrectShadingNormal`); 1 where shading and geometric normals agree.
fn shading_correction(hit: &Hit, wo: Vec3, wi: Vec3) -> f32 {
    if hit.n_shading == hit.n_geo {
        return 1.0;
    }
    let num = wo.dot(hit.n_shading).abs() * wi.dot(hit.n_geo).abs();
    let den = wo.dot(hit.n_geo).abs() * wi.dot(hit.n_shading).abs();
    if den > 0.0 {
        num / den
    } else {
        0.0
    }
}

/// Whether light `light` emits on both sides (an area light whose
/// material is two-sided): how its light paths choose a side, and the
/// densities the MIS weights give them.
pub fn two_sided(scene: &Scene, light: u32) -> bool {
    match &scene.lights[light as usize] {
        crate::light::Light::Area { prim, .. } => scene.material_of(*prim).two_sided,
        _ => false,
    }
}

/// A density by solid angle at `from` turned into one by area at `to`
/// (normal `n_to`; none for a point or a direction at infinity).
pub fn to_area(pdf: f32, from: Vec3, to: Vec3, n_to: Vec3) -> f32 {
    let d = to - from;
    let d2 = d.length_squared();
    if d2 == 0.0 {
        return 0.0;
    }
    let cos = if n_to == Vec3::ZERO {
        1.0
    } else {
        (n_to.dot(d) / d2.sqrt()).abs()
    };
    pdf * cos / d2
}

/// Which side is walking.
#[derive(Clone, Copy, PartialEq)]
enum Side {
    Camera,
    Light,
}

/// Continues a subpath from its last vertex along `ray` with throughput
/// `beta` and solid-angle density `pdf` of the ray's direction, adding
/// vertices until `max_vertices`, a miss, a surface that does not scatter
/// or Russian roulette. `bounce` numbers the first hit's draws.
#[allow(clippy::too_many_arguments)]
fn walk(
    scene: &Scene,
    mut ray: Ray,
    mut beta: Vec3,
    mut pdf: f32,
    side: Side,
    path: &mut Vec<Vertex>,
    max_vertices: usize,
    sampler: &mut Sampler,
) {
    let s = &scene.settings;
    let mut segments = path.len() as u32 - 1;
    while path.len() < max_vertices {
        segments += 1;
        let Some(mut hit) = scene.intersect(&ray, T_MIN, f32::INFINITY) else {
            if side == Side::Camera && scene.env_light.is_some() {
                path.push(Vertex {
                    role: Role::Background,
                    p: ray.d,
                    n_geo: Vec3::ZERO,
                    n_shading: Vec3::ZERO,
                    hit: None,
                    material: None,
                    smooth: false,
                    wo: -ray.d,
                    beta,
                    from_camera: pdf,
                    from_light: 0.0,
                    delta: false,
                });
            }
            return;
        };
        let wo = -ray.d;
        // A textured material is made for the hit in `slot` (which may
        // bend its shading normal); a plain one is the scene's.
        let mut slot = None;
        let _ = scene.material_at(&mut hit, wo, ray.time, &mut slot);
        let made = slot.map(Box::new);
        let material: &Material = match &made {
            Some(m) => m,
            None => scene.material_of_hit(&hit),
        };
        // Leaving a surface with a medium inside means the ray crossed it.
        if let Some(medium) = material.interior() {
            if ray.d.dot(hit.n_geo) > 0.0 {
                beta *= medium.transmittance(hit.t);
            }
        }
        let prev = path.last().expect("a walk starts from a vertex").p;
        let density = to_area(pdf, prev, hit.p, hit.n_geo);
        let (from_camera, from_light) = match side {
            Side::Camera => (density, 0.0),
            Side::Light => (0.0, density),
        };
        let (scatters, smooth) = (material.scatters(), material.has_smooth_lobe());
        let material = match made {
            Some(m) => MaterialAt::Made(m),
            None => MaterialAt::Scene,
        };
        path.push(Vertex {
            role: Role::Surface,
            p: hit.p,
            n_geo: hit.n_geo,
            n_shading: hit.n_shading,
            hit: Some(hit),
            material: Some(material),
            smooth,
            wo,
            beta,
            from_camera,
            from_light,
            delta: false,
        });
        if path.len() >= max_vertices || !scatters {
            return;
        }
        let bounce = segments - 1;
        let here = path.len() - 1;
        let v = &path[here];
        let (Some(m), Some(hit)) = (v.material(scene), v.hit.as_ref()) else {
            return;
        };
        // The light path draws from the PCG stream alone: had it drawn its
        // bounces' slots, its directions would repeat its camera path's,
        // and the joins of two dependent subpaths would be biased.
        let bs = match side {
            Side::Camera => crate::integrator::continue_path(hit, m, wo, bounce, sampler),
            Side::Light => crate::integrator::continue_path_drawing(hit, m, wo, sampler),
        };
        let Some(bs) = bs else {
            return;
        };
        let mut weight = bs.weight;
        if side == Side::Light {
            weight *= shading_correction(hit, wo, bs.wi);
        }
        let pdf_back = if bs.delta {
            0.0
        } else {
            m.eval(bs.wi, wo, hit.n_shading).1
        };
        let (p, next_origin) = (hit.p, offset_origin(hit.p, hit.n_geo, bs.wi));
        path[here].delta = bs.delta;
        // The previous vertex's density from the other side.
        let back = &mut path[here - 1];
        let density = to_area(pdf_back, p, back.p, back.n_geo);
        match side {
            Side::Camera => back.from_light = density,
            Side::Light => back.from_camera = density,
        }
        beta *= weight;
        pdf = if bs.delta { 0.0 } else { bs.pdf };
        if segments >= s.rr_depth {
            let q = beta.max_element().clamp(0.05, 0.95);
            match side {
                Side::Camera => sampler.start(bounce, Draws::Roulette),
                Side::Light => sampler.pad(),
            }
            if sampler.next_f32() >= q {
                return;
            }
            beta /= q;
        }
        ray = Ray::new(next_origin, bs.wi, ray.time);
    }
}

/// The camera's subpath for `ray` (its first vertex the camera), at most
/// `max_vertices` vertices.
pub fn camera_path(
    scene: &Scene,
    ray: Ray,
    max_vertices: usize,
    path: &mut Vec<Vertex>,
    sampler: &mut Sampler,
) {
    path.clear();
    let lens = scene.camera.uses_lens();
    let pdf = match scene.camera.project(ray.o + ray.d) {
        Some((_, _, pdf)) => pdf,
        None => 0.0,
    };
    path.push(Vertex {
        role: Role::Camera,
        p: ray.o,
        n_geo: Vec3::ZERO,
        n_shading: Vec3::ZERO,
        hit: None,
        material: None,
        smooth: false,
        wo: Vec3::ZERO,
        beta: Vec3::ONE,
        from_camera: 1.0,
        from_light: 0.0,
        // A lens is not connected to: no strategy may end there.
        delta: lens,
    });
    walk(
        scene,
        ray,
        Vec3::ONE,
        pdf,
        Side::Camera,
        path,
        max_vertices,
        sampler,
    );
}

/// A light's subpath (its first vertex on the light), at most
/// `max_vertices` vertices; empty when no light starts one.
pub fn light_path(
    scene: &Scene,
    emission: &EmissionSelection,
    time: f32,
    max_vertices: usize,
    path: &mut Vec<Vertex>,
    sampler: &mut Sampler,
) {
    path.clear();
    let (light, pick) = emission.sample(sampler.next_f32());
    let (u_pos, u_dir) = (sampler.next_2d(), sampler.next_2d());
    let emitted = |prim, q, uv, n, w| scene.emitted_at(prim, q, uv, n, w, time);
    let l = &scene.lights[light as usize];
    let two_sided = two_sided(scene, light);
    let Some(e) = l.sample_emission(emitted, (time, two_sided), u_pos, u_dir) else {
        return;
    };
    let cos = if e.n == Vec3::ZERO {
        1.0
    } else {
        e.n.dot(e.dir).abs()
    };
    path.push(Vertex {
        role: Role::Light { light },
        p: e.p,
        n_geo: e.n,
        n_shading: e.n,
        hit: None,
        material: None,
        smooth: false,
        wo: Vec3::ZERO,
        beta: e.le / (pick * e.pdf_pos),
        from_camera: 0.0,
        from_light: pick * e.pdf_pos,
        delta: false,
    });
    if max_vertices <= 1 {
        return;
    }
    let beta = e.le * cos / (pick * e.pdf_pos * e.pdf_dir);
    let origin = if e.n == Vec3::ZERO {
        e.p
    } else {
        offset_origin(e.p, e.n, e.dir)
    };
    let ray = Ray::new(origin, e.dir, time);
    walk(
        scene,
        ray,
        beta,
        e.pdf_dir,
        Side::Light,
        path,
        max_vertices,
        sampler,
    );
}
