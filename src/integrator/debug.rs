//! Debug integrators that show geometry before light transport: shading
//! normals, the albedo of the first hit, its distance and its texture
//! coordinates.

use super::{Integrator, T_MIN};
use crate::geometry::Ray;
use crate::ir::Scene;
use crate::sampling::sampler::Sampler;
use glam::Vec3;

/// Which debug view.
pub enum Debug {
    /// Normal mapped from [-1, 1] to [0, 1].
    Normals,
    /// Diffuse + reflection + transmission weights of the first hit.
    Albedo,
    /// Distance d mapped to d / (1 + d).
    Depth,
    /// Texture coordinates as red (u) and green (v), wrapped to [0, 1).
    Uv,
}

impl Integrator for Debug {
    fn li(&self, scene: &Scene, ray: Ray, _sampler: &mut Sampler) -> Vec3 {
        let Some(mut hit) = scene.intersect(&ray, T_MIN, f32::INFINITY) else {
            return Vec3::ZERO;
        };
        match self {
            Debug::Normals => {
                // The normal textures bend, too.
                scene.material_at(&mut hit, -ray.d, ray.time, &mut None);
                hit.n_shading * 0.5 + Vec3::splat(0.5)
            }
            Debug::Albedo => (scene.material_at(&mut hit, -ray.d, ray.time, &mut None)).albedo(),
            Debug::Depth => Vec3::splat(hit.t / (1.0 + hit.t)),
            Debug::Uv => {
                let uv = scene.texcoords(&hit, ray.time);
                let wrap = |x: f32| x - x.floor();
                Vec3::new(wrap(uv.x), wrap(uv.y), 0.0)
            }
        }
    }
}
