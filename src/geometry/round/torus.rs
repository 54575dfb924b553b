//! The torus: a circle of radius `minor` swept around the circle of radius
//! `major` about an axis. Its implicit equation
//! (|p|² + R² − r²)² = 4R² |p⊥|² (p⊥: p across the axis) is a quartic along
//! a ray; its roots are bracketed and refined by `polynomial::roots_in`,
//! with the ray's origin first moved to where it enters the torus's
//! bounding sphere, so that the coefficients are of the torus's size
//! whatever the distance the ray came from (pbrt-v3's and Graphics Gems'
//! advice: a far origin makes the quartic ill-conditioned).

use super::{Description, Round, Surface};
use crate::geometry::polynomial::{self, MAX_DEGREE};
use crate::geometry::shape::{Shape, ShapeHit};
use crate::geometry::{texcoord, unit_f32, Aabb, Ray};
use glam::{DMat4, DVec3, Vec2, Vec3};
use std::f32::consts::TAU;

/// A torus in its object's frame: a circle of radius `minor` swept around
/// a circle of radius `major` about `axis`.
#[derive(Debug, Clone, PartialEq)]
pub struct TorusDesc {
    /// Centre.
    pub center: DVec3,
    /// Unit axis of symmetry.
    pub axis: DVec3,
    /// Distance from the centre to the tube's centre line.
    pub major: f64,
    /// Radius of the tube.
    pub minor: f64,
}

impl Description for TorusDesc {
    fn name(&self) -> &'static str {
        "torus"
    }

    fn place(&self, m: &DMat4, scale: f64, out: &mut Vec<Shape>) {
        out.push(Shape::Round(Round::Torus(Torus {
            center: m.transform_point3(self.center).as_vec3(),
            axis: unit_f32(m.transform_vector3(self.axis)),
            major: (self.major * scale) as f32,
            minor: (self.minor * scale) as f32,
        })));
    }

    fn numbers(&self) -> Vec<f64> {
        let [c, a] = [self.center, self.axis].map(|p| p.to_array());
        [&c[..], &a[..], &[self.major, self.minor]].concat()
    }
}

/// A ring torus (`minor` < `major`).
#[derive(Debug, Clone, Copy)]
pub struct Torus {
    /// Centre.
    pub center: Vec3,
    /// Unit axis of symmetry.
    pub axis: Vec3,
    /// Distance from the centre to the tube's centre line (R).
    pub major: f32,
    /// Radius of the tube (r).
    pub minor: f32,
}

impl Torus {
    /// The point of the tube's centre circle nearest `p`.
    fn ring_point(&self, p: Vec3) -> Vec3 {
        let d = p - self.center;
        let across = d - d.dot(self.axis) * self.axis;
        let dir = across.normalize_or(crate::geometry::orthonormal_basis(self.axis).0);
        self.center + self.major * dir
    }
}

impl Surface for Torus {
    #[inline(never)]
    fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<ShapeHit> {
        let (big, small) = (self.major as f64, self.minor as f64);
        let a = self.axis.as_dvec3();
        let d = ray.d.as_dvec3();
        let o = ray.o.as_dvec3() - self.center.as_dvec3();
        // The stretch of the ray inside the bounding sphere.
        let bound = big + small;
        let (s0, s1) = super::cone::quadratic_roots(
            d.length_squared(),
            2.0 * o.dot(d),
            o.length_squared() - bound * bound,
        )?;
        let lo = s0.max(t_min as f64);
        let hi = s1.min(t_max as f64);
        if lo >= hi {
            return None;
        }
        // The quartic in s = t − lo, from the origin moved to `lo`.
        let o = o + lo * d;
        let (dd, od, oo) = (d.length_squared(), o.dot(d), o.length_squared());
        let (da, oa) = (d.dot(a), o.dot(a));
        // |p|² + R² − r² = g2 s² + g1 s + g0; |p⊥|² = h2 s² + h1 s + h0.
        let (g2, g1, g0) = (dd, 2.0 * od, oo + big * big - small * small);
        let (h2, h1, h0) = (dd - da * da, 2.0 * (od - oa * da), oo - oa * oa);
        let k = 4.0 * big * big;
        let c = [
            g0 * g0 - k * h0,
            2.0 * g1 * g0 - k * h1,
            g1 * g1 + 2.0 * g2 * g0 - k * h2,
            2.0 * g2 * g1,
            g2 * g2,
        ];
        let mut roots = [0.0; MAX_DEGREE];
        let n = polynomial::roots_in(&c, 0.0, hi - lo, &mut roots);
        roots[..n].iter().find_map(|&s| {
            let t = (lo + s) as f32;
            (t > t_min && t < t_max).then_some(ShapeHit { t, uv: Vec2::ZERO })
        })
    }

    #[inline(never)]
    fn project(&self, p: Vec3) -> Vec3 {
        let q = self.ring_point(p);
        match (p - q).try_normalize() {
            Some(n) => q + self.minor * n,
            None => p,
        }
    }

    #[inline(never)]
    fn normal_at(&self, p: Vec3) -> Vec3 {
        (p - self.ring_point(p)).normalize_or(self.axis)
    }

    /// The area, 4π² R r.
    #[inline(never)]
    fn area(&self) -> f32 {
        TAU * TAU * self.major * self.minor
    }

    /// A point uniform by area from `u` in [0,1)², with its normal: the
    /// angle around the axis uniform, the angle around the tube θ with
    /// density ∝ R + r cos θ (the outer side has more area), by inverting
    /// its CDF (Rθ + r sin θ) / 2πR with Newton's method in a bracket.
    fn sample_area(&self, u: Vec2) -> (Vec3, Vec3) {
        let (big, small) = (self.major as f64, self.minor as f64);
        let target = std::f64::consts::TAU * big * u.y as f64;
        let (mut lo, mut hi) = (0.0, std::f64::consts::TAU);
        let mut theta = std::f64::consts::TAU * u.y as f64;
        for _ in 0..64 {
            let f = big * theta + small * theta.sin() - target;
            if f.abs() <= 1e-14 * big || hi - lo < 1e-12 {
                break;
            }
            if f < 0.0 {
                lo = theta;
            } else {
                hi = theta;
            }
            let step = theta - f / (big + small * theta.cos());
            theta = if step > lo && step < hi {
                step
            } else {
                0.5 * (lo + hi)
            };
        }
        let phi = TAU * u.x;
        let (x, z) = crate::geometry::orthonormal_basis(self.axis);
        let radial = phi.cos() * x + phi.sin() * z;
        let (s, c) = (theta as f32).sin_cos();
        let n = c * radial + s * self.axis;
        (self.center + self.major * radial + self.minor * n, n)
    }

    /// Bounds: along each axis i the torus extends R·sqrt(1 − aᵢ²) + r.
    fn bounds(&self) -> Aabb {
        let e = crate::geometry::disk::extent(self.axis, self.major) + Vec3::splat(self.minor);
        Aabb {
            min: self.center - e,
            max: self.center + e,
        }
    }

    fn uv_frame(&self) -> (Vec3, Vec3) {
        (self.center, self.axis)
    }

    fn texcoord(&self, local: Vec3, scale: f32) -> Vec2 {
        texcoord::torus(local, self.major * scale)
    }

    fn texcoord_derivatives(&self, local: Vec3, scale: f32) -> (Vec3, Vec3) {
        texcoord::torus_derivatives(local, self.major * scale)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ray(o: [f32; 3], d: [f32; 3]) -> Ray {
        Ray::new(Vec3::from(o), Vec3::from(d).normalize(), 0.0)
    }

    fn ring() -> Torus {
        Torus {
            center: Vec3::ZERO,
            axis: Vec3::Y,
            major: 1.0,
            minor: 0.25,
        }
    }

    #[test]
    fn hit_miss_hole_inside_grazing() {
        let t = ring();
        let hit = |o, d| t.intersect(&ray(o, d), 1e-4, f32::INFINITY).map(|h| h.t);
        // Through the tube on the x axis: enters at x = 1.25.
        assert!((hit([5., 0., 0.], [-1., 0., 0.]).unwrap() - 3.75).abs() < 1e-5);
        // Down through the hole: nothing.
        assert!(hit([0., 5., 0.], [0., -1., 0.]).is_none());
        // Down onto the tube's top at x = 1.
        assert!((hit([1., 5., 0.], [0., -1., 0.]).unwrap() - 4.75).abs() < 1e-5);
        // From inside the tube: its wall, 0.25 away.
        assert!((hit([1., 0., 0.], [0., 1., 0.]).unwrap() - 0.25).abs() < 1e-5);
        // Above and beside: misses.
        assert!(hit([5., 0.3, 0.], [-1., 0., 0.]).is_none());
        assert!(hit([0., 0., 5.], [1., 0., 0.]).is_none());
        // Grazing the top of the tube: just above misses, just below hits.
        assert!(hit([1., 0.2501, 5.], [0., 0., -1.]).is_none());
        assert!(hit([1., 0.2499, 5.], [0., 0., -1.]).is_some());
        // Edge-on from far away: still the near side of the tube.
        let far = hit([1e4, 0., 0.], [-1., 0., 0.]).unwrap();
        assert!((far - (1e4 - 1.25)).abs() < 1e-2, "{far}");
        // Through the middle of the hole along the plane: the inner side at x = 0.75.
        let t_in = hit([0., 0., 0.], [1., 0., 0.]).unwrap();
        assert!((t_in - 0.75).abs() < 1e-5);
    }

    #[test]
    fn transformed_torus_normals_and_bounds() {
        let t = Torus {
            center: Vec3::new(2.0, 1.0, -1.0),
            axis: Vec3::Z,
            major: 2.0,
            minor: 0.5,
        };
        let r = ray([2., 1., 10.], [0., 0., -1.]);
        assert!(t.intersect(&r, 1e-4, f32::INFINITY).is_none(), "the hole");
        let r = ray([4., 1., 10.], [0., 0., -1.]);
        let h = t.intersect(&r, 1e-4, f32::INFINITY).unwrap();
        let p = t.project(r.at(h.t));
        assert!((p - Vec3::new(4.0, 1.0, -0.5)).length() < 1e-4, "{p}");
        assert!((t.normal_at(p) - Vec3::Z).length() < 1e-4);
        let b = t.bounds();
        assert!((b.min - Vec3::new(-0.5, -1.5, -1.5)).length() < 1e-6);
        assert!((b.max - Vec3::new(4.5, 3.5, -0.5)).length() < 1e-6);
    }

    #[test]
    fn area_samples_lie_on_the_surface_and_favour_the_outside() {
        let t = Torus {
            center: Vec3::new(0.5, 0.0, 0.0),
            axis: Vec3::new(0.0, 1.0, 1.0).normalize(),
            major: 1.0,
            minor: 0.5,
        };
        let n = 64;
        let mut outer = 0.0;
        for i in 0..n {
            for j in 0..n {
                let u = Vec2::new((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32);
                let (p, normal) = t.sample_area(u);
                assert!((t.project(p) - p).length() < 1e-5);
                assert!((t.normal_at(p) - normal).length() < 1e-4);
                let across = (p - t.center) - (p - t.center).dot(t.axis) * t.axis;
                if across.length() > t.major {
                    outer += 1.0 / (n * n) as f32;
                }
            }
        }
        // The outer half (|θ| < π/2) holds (πR + 2r) / 2πR of the area.
        let want = (std::f32::consts::PI + 1.0) / TAU;
        assert!((outer - want).abs() < 1e-2, "{outer} vs {want}");
        let area = TAU * TAU * 0.5;
        assert!((t.area() - area).abs() < 1e-5);
    }
}
