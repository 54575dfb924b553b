//! Parallelogram ("quad") intersection: Möller–Trumbore (1997) in the basis of
//! the two edges, accepting (u, v) in the unit square.

use super::shape::ShapeHit;
use super::triangle::moller_trumbore;
use super::Ray;
use glam::Vec3;

/// The hit in `(t_min, t_max)` with `p + u·e1 + v·e2`, u, v in [0, 1]; both
/// sides hit.
#[inline(always)]
pub fn intersect(
    p: Vec3,
    e1: Vec3,
    e2: Vec3,
    ray: &Ray,
    t_min: f32,
    t_max: f32,
) -> Option<ShapeHit> {
    moller_trumbore(ray, p, e1, e2, t_min, t_max, |_, v| {
        (0.0..=1.0).contains(&v)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec2;

    #[test]
    fn hit_miss_behind_grazing() {
        let (p, e1, e2) = (
            Vec3::new(-1., 0., -1.),
            Vec3::new(0., 0., 2.),
            Vec3::new(2., 0., 0.),
        );
        let hit = |o: [f32; 3], d: [f32; 3]| {
            let r = Ray::new(Vec3::from(o), Vec3::from(d).normalize(), 0.0);
            intersect(p, e1, e2, &r, 1e-4, f32::INFINITY)
        };
        let h = hit([0.5, 1., 0.5], [0., -1., 0.]).unwrap();
        assert!((h.t - 1.0).abs() < 1e-6);
        // uv are the coordinates along e1 (z) and e2 (x).
        assert!((h.uv - Vec2::new(0.75, 0.75)).length() < 1e-6);
        assert!(hit([1.5, 1., 0.], [0., -1., 0.]).is_none());
        // From behind: quads are two-sided for intersection.
        assert!(hit([0., -1., 0.], [0., 1., 0.]).is_some());
        // Parallel (grazing) rays miss.
        assert!(hit([0., 0., -5.], [0., 0., 1.]).is_none());
    }
}
