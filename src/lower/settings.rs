//! The `render { }` block → the renderer's settings.

use crate::check;
use crate::ir::settings::Settings;
use glam::DVec3;

/// The settings as the renderer reads them (f32 where it computes with them).
pub fn lower_settings(r: &check::RenderSettings) -> Settings {
    Settings {
        width: r.width,
        height: r.height,
        samples: r.samples,
        max_depth: r.max_depth,
        integrator: r.integrator,
        seed: r.seed,
        ambient: DVec3::from_array(r.ambient).as_vec3(),
        rr_depth: r.rr_depth,
        hybrid_weight: r.hybrid_weight as f32,
        clamp: r.clamp.map(|c| c as f32),
        light_sampling: r.light_sampling,
        light_samples: r.light_samples,
        exposure: r.exposure as f32,
    }
}
