//! Infinite plane intersection.

use super::shape::ShapeHit;
use super::Ray;
use glam::{Vec2, Vec3};

/// The hit in `(t_min, t_max)` with the plane through `point` with unit `normal`.
#[inline(always)]
pub fn intersect(point: Vec3, normal: Vec3, ray: &Ray, t_min: f32, t_max: f32) -> Option<ShapeHit> {
    let denom = normal.dot(ray.d);
    if denom == 0.0 {
        return None;
    }
    let t = (point - ray.o).dot(normal) / denom;
    (t > t_min && t < t_max).then_some(ShapeHit { t, uv: Vec2::ZERO })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hit_miss_behind_parallel() {
        let hit = |o: [f32; 3], d: [f32; 3]| {
            let r = Ray::new(Vec3::from(o), Vec3::from(d).normalize(), 0.0);
            intersect(Vec3::ZERO, Vec3::Y, &r, 1e-4, f32::INFINITY)
        };
        assert!(hit([100., 1., 0.], [0., -1., 0.]).is_some());
        assert!(hit([0., 1., 0.], [0., 1., 0.]).is_none());
        assert!(hit([0., -1., 0.], [0., 1., 0.]).is_some());
        assert!(hit([0., 1., 0.], [1., 0., 0.]).is_none());
    }
}
