//! The camera block → the renderer's camera.

use crate::camera::Camera;
use crate::check;

/// The camera of the checked scene: its frame computed in f64 and rounded
/// once (`up` may be any non-zero vector of the checker's domain, which need
/// not fit an f32).
pub fn lower_camera(c: &check::Camera, width: u32, height: u32) -> Camera {
    let unit = crate::check::domain::unit;
    let forward = unit(c.look_at - c.position).unwrap_or(glam::DVec3::NEG_Z);
    let right = unit(forward.cross(unit(c.up).unwrap_or(glam::DVec3::Y))).unwrap_or(glam::DVec3::X);
    let up = right.cross(forward);
    Camera::new(
        [c.position, forward, right, up].map(|v| v.as_vec3()),
        c.fov.to_radians() as f32,
        (c.aperture as f32, c.focus_distance as f32),
        (c.shutter.0 as f32, c.shutter.1 as f32),
        (width, height),
    )
}
