//! Triangle intersection: Möller and Trumbore 1997, "Fast, Minimum Storage
//! Ray/Triangle Intersection".

use super::shape::ShapeHit;
use super::Ray;
use glam::{Vec2, Vec3};

/// The hit in `(t_min, t_max)` with the triangle `p0, p0 + e1, p0 + e2`; uv
/// are the barycentrics of the second and third vertex. Both sides hit.
#[inline(always)]
pub fn intersect(
    p0: Vec3,
    e1: Vec3,
    e2: Vec3,
    ray: &Ray,
    t_min: f32,
    t_max: f32,
) -> Option<ShapeHit> {
    moller_trumbore(ray, p0, e1, e2, t_min, t_max, |u, v| {
        v >= 0.0 && u + v <= 1.0
    })
}

/// Möller–Trumbore on the plane spanned by `e1`, `e2` from `p`: the hit with
/// coordinates (u, v) in that basis, u in [0, 1] and `v_ok(u, v)`, and t in
/// `(t_min, t_max)`. It exits early: most tests in a BVH leaf miss, and a miss
/// is usually known from u alone. Shared with quads.
#[inline(always)]
pub fn moller_trumbore(
    ray: &Ray,
    p: Vec3,
    e1: Vec3,
    e2: Vec3,
    t_min: f32,
    t_max: f32,
    v_ok: impl Fn(f32, f32) -> bool,
) -> Option<ShapeHit> {
    let pv = ray.d.cross(e2);
    let det = e1.dot(pv);
    if det.abs() < 1e-20 {
        return None;
    }
    let inv = 1.0 / det;
    let tv = ray.o - p;
    let u = tv.dot(pv) * inv;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let qv = tv.cross(e1);
    let v = ray.d.dot(qv) * inv;
    if !v_ok(u, v) {
        return None;
    }
    let t = e2.dot(qv) * inv;
    (t > t_min && t < t_max).then_some(ShapeHit {
        t,
        uv: Vec2::new(u, v),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hit_miss_edges_grazing() {
        let hit = |o: [f32; 3], d: [f32; 3]| {
            let r = Ray::new(Vec3::from(o), Vec3::from(d).normalize(), 0.0);
            intersect(Vec3::ZERO, Vec3::X, Vec3::Y, &r, 1e-4, f32::INFINITY)
        };
        let h = hit([0.2, 0.3, 1.], [0., 0., -1.]).unwrap();
        assert!((h.t - 1.0).abs() < 1e-6 && (h.uv - Vec2::new(0.2, 0.3)).length() < 1e-6);
        assert!(hit([0.8, 0.8, 1.], [0., 0., -1.]).is_none());
        assert!(hit([-0.1, 0.5, 1.], [0., 0., -1.]).is_none());
        // From behind, and a ray in the triangle's plane.
        assert!(hit([0.2, 0.2, -1.], [0., 0., 1.]).is_some());
        assert!(hit([-1., 0.2, 0.], [1., 0., 0.]).is_none());
    }
}
