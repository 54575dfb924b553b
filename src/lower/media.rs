//! The scene's media: the atmosphere's ball, the media around the camera,
//! and whether the renderer needs its volumetric path at all (a scene
//! without media pays nothing for them).

use crate::check;
use crate::geometry::Aabb;
use crate::ir::media::{media_around, Atmosphere};
use crate::ir::Scene;
use crate::light::Light;
use crate::material::medium::Medium;
use glam::{DVec3, Vec3};

/// A checked medium in the renderer's f32.
pub fn lower_medium(m: &check::scene::MediumParams) -> Medium {
    Medium {
        absorption: DVec3::from_array(m.absorption).as_vec3(),
        scattering: DVec3::from_array(m.scattering).as_vec3(),
        anisotropy: m.anisotropy as f32,
    }
}

/// The atmosphere in the ball given, or in the one just around `around`
/// (the objects), the camera and the lights placed in space.
fn lower_atmosphere(
    a: &check::Atmosphere,
    (around, camera): (Aabb, Vec3),
    lights: &[Light],
) -> Atmosphere {
    let mut ball = around.grow(camera);
    for l in lights {
        if let Light::Point { position, .. } | Light::Spot { position, .. } = l {
            ball = ball.grow(*position);
        }
    }
    let center = a.center.map_or(ball.center(), |c| c.as_vec3());
    let radius = match a.radius {
        Some(r) => r as f32,
        None => {
            let far = (ball.max - center).abs().max((ball.min - center).abs());
            // A little beyond the farthest corner, so that no surface lies on the edge.
            far.length() * 1.01 + 1e-3
        }
    };
    Atmosphere {
        medium: lower_medium(&a.medium),
        center,
        radius,
    }
}

/// Sets the scene's atmosphere, whether it is volumetric, and the media
/// around the camera (after the scene's BVH is built: found by tracing).
pub fn place_media(ir: &mut Scene, scene: &check::Scene, around: Aabb) {
    ir.atmosphere = (scene.atmosphere.as_ref())
        .map(|a| lower_atmosphere(a, (around, ir.camera.position()), &ir.lights))
        .filter(|a| a.medium.extinction() != Vec3::ZERO);
    let scattering =
        (ir.materials.iter()).any(|m| m.is_null() || m.interior().is_some_and(|i| i.scatters()));
    ir.volumetric = ir.atmosphere.is_some() || scattering;
    if ir.volumetric {
        ir.camera_media = media_around(ir, ir.camera.position());
    }
}
