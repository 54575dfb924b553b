//! Sphere intersection (pbrt-v4 §6.2), with the numerically careful
//! discriminant of Haines et al., Ray Tracing Gems ch. 7.

use super::shape::ShapeHit;
use super::Ray;
use glam::{Vec2, Vec3};

/// The closest hit in `(t_min, t_max)` with the sphere (`center`, `radius`),
/// from outside or from inside.
#[inline(always)]
pub fn intersect(center: Vec3, radius: f32, ray: &Ray, t_min: f32, t_max: f32) -> Option<ShapeHit> {
    let oc = ray.o - center;
    let a = ray.d.length_squared();
    let b = oc.dot(ray.d);
    // Compute the discriminant from the perpendicular distance, which stays
    // accurate for far rays (RTG ch. 7).
    let perp = oc - (b / a) * ray.d;
    let disc = radius * radius - perp.length_squared();
    if disc < 0.0 {
        return None;
    }
    // Roots of a·t² + 2b·t + c = 0 with b² − ac = a·disc, in the
    // cancellation-free form t0 = q/a, t1 = c/q.
    let sq = (a * disc).sqrt();
    let q = -(b + sq.copysign(b));
    let c = oc.length_squared() - radius * radius;
    let (mut t0, mut t1) = (q / a, if q != 0.0 { c / q } else { 0.0 });
    if t0 > t1 {
        std::mem::swap(&mut t0, &mut t1);
    }
    let t = if t0 > t_min && t0 < t_max {
        t0
    } else if t1 > t_min && t1 < t_max {
        t1
    } else {
        return None;
    };
    Some(ShapeHit { t, uv: Vec2::ZERO })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ray(o: [f32; 3], d: [f32; 3]) -> Ray {
        Ray::new(Vec3::from(o), Vec3::from(d).normalize(), 0.0)
    }

    #[test]
    fn hit_miss_inside_grazing_far() {
        let hit = |o, d| intersect(Vec3::ZERO, 1.0, &ray(o, d), 1e-4, f32::INFINITY);
        assert!((hit([0., 0., 5.], [0., 0., -1.]).unwrap().t - 4.0).abs() < 1e-5);
        assert!(hit([0., 2., 5.], [0., 0., -1.]).is_none());
        // Pointing away: both roots behind the origin.
        assert!(hit([0., 0., 5.], [0., 0., 1.]).is_none());
        let inside = hit([0., 0., 0.], [1., 0., 0.]).unwrap();
        assert!((inside.t - 1.0).abs() < 1e-5);
        assert!(hit([0., 0.9999, 5.], [0., 0., -1.]).is_some());
        // Far away and small: the careful discriminant still hits.
        let far = ray([0., 0.4, 0.], [0., 0., -1.]);
        assert!(intersect(Vec3::new(0., 0., -1e5), 0.5, &far, 1e-4, f32::INFINITY).is_some());
    }
}
