//! The camera: pinhole or thin lens (depth of field), vertical field of view,
//! a shutter interval (motion blur).

use crate::geometry::Ray;
use crate::render::sampling::concentric_disk;
use glam::{Vec2, Vec3};

/// A camera ready to generate rays.
#[derive(Debug, Clone)]
pub struct Camera {
    position: Vec3,
    right: Vec3,
    up: Vec3,
    forward: Vec3,
    tan_half: f32,
    aspect: f32,
    lens_radius: f32,
    focus: f32,
    shutter: (f32, f32),
    width: f32,
    height: f32,
}

impl Camera {
    /// Builds the camera for an image of `width` × `height`.
    pub fn new(c: &crate::check::Camera, width: u32, height: u32) -> Camera {
        // The frame in f64, rounded once: `up` may be any non-zero vector
        // (the checker's domain), which need not fit an f32.
        let unit = crate::check::domain::unit;
        let forward = unit(c.look_at - c.position).unwrap_or(glam::DVec3::NEG_Z);
        let right =
            unit(forward.cross(unit(c.up).unwrap_or(glam::DVec3::Y))).unwrap_or(glam::DVec3::X);
        let up = right.cross(forward);
        let (position, forward, right, up) = (
            c.position.as_vec3(),
            forward.as_vec3(),
            right.as_vec3(),
            up.as_vec3(),
        );
        Camera {
            position,
            right,
            up,
            forward,
            tan_half: (c.fov.to_radians() as f32 * 0.5).tan(),
            aspect: width as f32 / height as f32,
            lens_radius: c.aperture as f32,
            focus: c.focus_distance as f32,
            shutter: (c.shutter.0 as f32, c.shutter.1 as f32),
            width: width as f32,
            height: height as f32,
        }
    }

    /// The ray through image position `film` (pixels, y down), lens sample
    /// `lens` and time sample `u_time`.
    pub fn ray(&self, film: Vec2, lens: Vec2, u_time: f32) -> Ray {
        let sx = (2.0 * film.x / self.width - 1.0) * self.tan_half * self.aspect;
        let sy = (1.0 - 2.0 * film.y / self.height) * self.tan_half;
        let dir = self.forward + sx * self.right + sy * self.up;
        let time = self.shutter.0 + (self.shutter.1 - self.shutter.0) * u_time;
        if self.lens_radius <= 0.0 {
            return Ray::new(self.position, dir.normalize(), time);
        }
        // Thin lens: every ray through the lens meets the pinhole ray on the plane in focus.
        let focus_point = self.position + dir * self.focus;
        let d = self.lens_radius * concentric_disk(lens);
        let origin = self.position + d.x * self.right + d.y * self.up;
        Ray::new(origin, (focus_point - origin).normalize(), time)
    }
}
