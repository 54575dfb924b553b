//! Disk intersection: the plane of the disk, then a radius test.

use super::shape::ShapeHit;
use super::Ray;
use glam::{Vec2, Vec3};

/// The hit in `(t_min, t_max)` with the disk (`center`, unit `normal`, `radius`).
#[inline(always)]
pub fn intersect(
    center: Vec3,
    normal: Vec3,
    radius: f32,
    ray: &Ray,
    t_min: f32,
    t_max: f32,
) -> Option<ShapeHit> {
    let denom = normal.dot(ray.d);
    if denom == 0.0 {
        return None;
    }
    let t = (center - ray.o).dot(normal) / denom;
    if !(t > t_min && t < t_max) {
        return None;
    }
    ((ray.at(t) - center).length_squared() <= radius * radius)
        .then_some(ShapeHit { t, uv: Vec2::ZERO })
}

/// Bounds of a disk: along each axis i it extends r·sqrt(1 − n_i²).
pub fn extent(normal: Vec3, radius: f32) -> Vec3 {
    let k = (Vec3::ONE - normal * normal).max(Vec3::ZERO);
    radius * Vec3::new(k.x.sqrt(), k.y.sqrt(), k.z.sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hit_miss_behind_grazing() {
        let hit = |o: [f32; 3], d: [f32; 3]| {
            let r = Ray::new(Vec3::from(o), Vec3::from(d).normalize(), 0.0);
            intersect(Vec3::ZERO, Vec3::Y, 1.0, &r, 1e-4, f32::INFINITY)
        };
        assert!(hit([0.5, 1., 0.5], [0., -1., 0.]).is_some());
        assert!(hit([0.9, 1., 0.9], [0., -1., 0.]).is_none());
        assert!(hit([0.5, -1., 0.5], [0., 1., 0.]).is_some());
        assert!(hit([-5., 0., 0.], [1., 0., 0.]).is_none());
        let e = extent(Vec3::Y, 1.0);
        assert!((e - Vec3::new(1.0, 0.0, 1.0)).length() < 1e-6);
    }
}
