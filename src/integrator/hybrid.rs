//! The paper's hybrid: a weighted average of the Whitted and the path-traced
//! estimates of the same pixel, in one pass. Biased (Whitted omits indirect
//! diffuse light); it converges fast to a plausible image.
//!
//! `.pts`: `render { integrator hybrid  hybrid_weight 0.5 }` (weight of Whitted).

use super::{path::path_li, whitted, Integrator};
use crate::geometry::Ray;
use crate::ir::Scene;
use crate::sampling::sampler::Sampler;
use glam::Vec3;

/// The hybrid integrator.
pub struct Hybrid;

impl Integrator for Hybrid {
    fn li(&self, scene: &Scene, ray: Ray, sampler: &mut Sampler) -> Vec3 {
        let w = scene.settings.hybrid_weight;
        let a = whitted::trace(scene, ray, sampler, 1, 1.0);
        let b = path_li(scene, ray, sampler, scene.settings.light_sampling);
        w * a + (1.0 - w) * b
    }
}
