//! The camera: pinhole or thin lens (depth of field), vertical field of view,
//! a shutter interval (motion blur).

use crate::geometry::Ray;
use crate::sampling::warp::concentric_disk;
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
    /// Where the camera is (the lens's centre).
    pub fn position(&self) -> Vec3 {
        self.position
    }

    /// Builds the camera for an image of `width` × `height`: its position
    /// and orthonormal frame (`forward`, `right`, `up`), the vertical field
    /// of view in radians, the lens (aperture radius, focus distance; a
    /// radius of 0 is a pinhole) and the shutter interval.
    pub fn new(
        [position, forward, right, up]: [Vec3; 4],
        fov_radians: f32,
        (lens_radius, focus): (f32, f32),
        shutter: (f32, f32),
        (width, height): (u32, u32),
    ) -> Camera {
        Camera {
            position,
            right,
            up,
            forward,
            tan_half: (fov_radians * 0.5).tan(),
            aspect: width as f32 / height as f32,
            lens_radius,
            focus,
            shutter,
            width: width as f32,
            height: height as f32,
        }
    }

    /// The shutter interval: the times rays are given.
    pub fn shutter(&self) -> (f32, f32) {
        self.shutter
    }

    /// Whether rays depend on the lens draw (a lens, not a pinhole).
    pub fn uses_lens(&self) -> bool {
        self.lens_radius > 0.0
    }

    /// Whether rays depend on the time draw (an open shutter).
    pub fn uses_time(&self) -> bool {
        self.shutter.0 != self.shutter.1
    }

    /// Where a pinhole camera sees the point `p`: its image position
    /// (pixels, y down, as [`Camera::ray`] takes it), the cosine between
    /// the view axis and the direction towards `p`, and the density by
    /// solid angle with which rays spread evenly over the image take that
    /// direction, 1 / (A cos³θ) with A the image's area on the plane at
    /// distance 1 (pbrt-v4 §5.4.1, `PDF_We`). `None` behind the camera,
    /// outside the image, and for a lens (light paths do not reach a thin
    /// lens here).
    pub fn project(&self, p: Vec3) -> Option<(Vec2, f32, f32)> {
        if self.lens_radius > 0.0 {
            return None;
        }
        let d = (p - self.position).normalize_or_zero();
        let cos = d.dot(self.forward);
        if cos <= 1e-6 {
            return None;
        }
        let on_plane = d / cos;
        let (sx, sy) = (on_plane.dot(self.right), on_plane.dot(self.up));
        let fx = (sx / (self.tan_half * self.aspect) + 1.0) * 0.5 * self.width;
        let fy = (1.0 - sy / self.tan_half) * 0.5 * self.height;
        if !(0.0..self.width).contains(&fx) || !(0.0..self.height).contains(&fy) {
            return None;
        }
        let area = 4.0 * self.tan_half * self.tan_half * self.aspect;
        Some((Vec2::new(fx, fy), cos, 1.0 / (area * cos * cos * cos)))
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_point_projects_to_where_its_ray_leaves_and_the_density_covers_the_image() {
        let frame = [Vec3::new(0.0, 0.0, 4.0), -Vec3::Z, Vec3::X, Vec3::Y];
        let camera = Camera::new(frame, 0.8, (0.0, 1.0), (0.0, 0.0), (64, 48));
        let mut state = 3u64;
        let mut rng = move || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 40) as f32 / (1u64 << 24) as f32
        };
        let mut integral = 0.0f64;
        let k = 200_000;
        for _ in 0..k {
            let film = Vec2::new(rng() * 64.0, rng() * 48.0);
            let ray = camera.ray(film, Vec2::ZERO, 0.0);
            let (back, _, _) = camera.project(ray.o + ray.d * 3.0).unwrap();
            assert!((back - film).length() < 1e-3, "{back} vs {film}");
            // Directions drawn uniformly on the sphere: the density
            // integrates to 1 over the directions the image covers.
            let d = crate::sampling::warp::uniform_sphere(Vec2::new(rng(), rng()));
            if let Some((_, _, pdf)) = camera.project(camera.position() + d) {
                integral += (pdf / crate::sampling::warp::UNIFORM_SPHERE_PDF) as f64;
            }
        }
        let integral = integral / k as f64;
        assert!((integral - 1.0).abs() < 0.02, "{integral}");
        let lens = Camera::new(frame, 0.8, (0.1, 4.0), (0.0, 0.0), (64, 48));
        assert!(
            lens.project(Vec3::ZERO).is_none(),
            "light paths skip a lens"
        );
    }
}
