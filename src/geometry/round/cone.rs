//! Cones, truncated cones and cylinders (a cylinder is a cone whose two
//! radii are equal): the lateral surface between two planes across the
//! axis, without its end disks (placing a closed one adds those as
//! `disk`s). The quadric's roots are taken in f64 with the
//! cancellation-free form of the quadratic (pbrt-v4 §6.3; Haines et al.,
//! Ray Tracing Gems ch. 7).

use super::{Description, Round, Surface};
use crate::geometry::shape::{Shape, ShapeHit};
use crate::geometry::{texcoord, Aabb, Ray};
use glam::{DMat4, DVec3, Vec2, Vec3};

/// A cone, a truncated cone or (equal radii) a cylinder in its object's
/// frame, from the centre of its base to the centre of its top.
#[derive(Debug, Clone, PartialEq)]
pub struct ConeDesc {
    /// Centre of the base.
    pub base: DVec3,
    /// Centre of the top.
    pub top: DVec3,
    /// Radius at the base.
    pub base_radius: f64,
    /// Radius at the top (0: a point).
    pub top_radius: f64,
    /// Without the end disks.
    pub open: bool,
}

impl Description for ConeDesc {
    fn name(&self) -> &'static str {
        if self.base_radius == self.top_radius {
            "cylinder"
        } else {
            "cone"
        }
    }

    /// Its lateral surface and, unless `open`, the disks that close it (a
    /// radius of 0 closes itself).
    fn place(&self, m: &DMat4, scale: f64, out: &mut Vec<Shape>) {
        let base = m.transform_point3(self.base).as_vec3();
        let top = m.transform_point3(self.top).as_vec3();
        let along = top - base;
        let height = along.length();
        let axis = along / height;
        let [r0, r1] = [self.base_radius * scale, self.top_radius * scale].map(|r| r as f32);
        out.push(Shape::Round(Round::Cone(Cone {
            base,
            axis,
            height,
            r0,
            r1,
        })));
        if self.open {
            return;
        }
        for (center, normal, radius) in [(base, -axis, r0), (top, axis, r1)] {
            if radius > 0.0 {
                out.push(Shape::Disk {
                    center,
                    normal,
                    radius,
                });
            }
        }
    }

    fn numbers(&self) -> Vec<f64> {
        let open = if self.open { 1.0 } else { 0.0 };
        let [b, t] = [self.base, self.top].map(|p| p.to_array());
        [&b[..], &t[..], &[self.base_radius, self.top_radius, open]].concat()
    }
}

/// A cone's lateral surface: from `base` along the unit `axis` for
/// `height`, its radius going linearly from `r0` at the base to `r1`.
#[derive(Debug, Clone, Copy)]
pub struct Cone {
    /// Centre of the base.
    pub base: Vec3,
    /// Unit axis from the base to the top.
    pub axis: Vec3,
    /// Distance from the base to the top.
    pub height: f32,
    /// Radius at the base.
    pub r0: f32,
    /// Radius at the top.
    pub r1: f32,
}

impl Cone {
    /// How the radius grows per unit of height.
    fn slope(&self) -> f64 {
        (self.r1 as f64 - self.r0 as f64) / self.height as f64
    }

    /// The radius at height `h` above the base.
    fn radius_at(&self, h: f32) -> f32 {
        self.r0 + (self.r1 - self.r0) * (h / self.height)
    }
}

impl Surface for Cone {
    // Out of line: inlined into every primitive test's dispatch it cost
    // scenes without cones registers (docs/performance.md, "Instancing").
    #[inline(never)]
    fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<ShapeHit> {
        let a = self.axis.as_dvec3();
        let o = ray.o.as_dvec3() - self.base.as_dvec3();
        let d = ray.d.as_dvec3();
        let (oa, da) = (o.dot(a), d.dot(a));
        let (op, dp) = (o - oa * a, d - da * a);
        let k = self.slope();
        // The radius at the origin's height, and the quadric
        // |op + t·dp|² = (r0 + k·(oa + t·da))².
        let ro = self.r0 as f64 + k * oa;
        let qa = dp.length_squared() - k * k * da * da;
        let qb = 2.0 * (op.dot(dp) - k * da * ro);
        let qc = op.length_squared() - ro * ro;
        let (t0, t1) = quadratic_roots(qa, qb, qc)?;
        let h_max = self.height as f64;
        [t0, t1].into_iter().find_map(|t| {
            let h = oa + t * da;
            let tf = t as f32;
            (tf > t_min && tf < t_max && (0.0..=h_max).contains(&h)).then_some(ShapeHit {
                t: tf,
                uv: Vec2::ZERO,
            })
        })
    }

    /// Its height kept, its distance from the axis made exact.
    #[inline(never)]
    fn project(&self, p: Vec3) -> Vec3 {
        let d = (p - self.base).as_dvec3();
        let a = self.axis.as_dvec3();
        let h = d.dot(a).clamp(0.0, self.height as f64);
        let radial = d - h * a;
        let len = radial.length();
        if len == 0.0 {
            return p;
        }
        let r = self.radius_at(h as f32) as f64;
        (self.base.as_dvec3() + h * a + radial * (r / len)).as_vec3()
    }

    #[inline(never)]
    fn normal_at(&self, p: Vec3) -> Vec3 {
        let d: DVec3 = (p - self.base).as_dvec3();
        let a = self.axis.as_dvec3();
        let radial = d - d.dot(a) * a;
        let len = radial.length();
        // At a cone's apex every direction across is as good; the axis
        // away from the wide end.
        if len == 0.0 {
            return if self.r1 < self.r0 {
                self.axis
            } else {
                -self.axis
            };
        }
        // The gradient of |radial| − r(h): radial/|radial| − slope · axis.
        (radial / len - self.slope() * a).normalize().as_vec3()
    }

    /// The lateral area: π (r0 + r1) × the slant height.
    #[inline(never)]
    fn area(&self) -> f32 {
        let dr = self.r1 - self.r0;
        std::f32::consts::PI * (self.r0 + self.r1) * (self.height * self.height + dr * dr).sqrt()
    }

    fn sample_area(&self, u: Vec2) -> (Vec3, Vec3) {
        // The area at height h is proportional to the radius there: the
        // inverse of the CDF of a linear density (r² interpolates).
        let h = if self.r0 == self.r1 {
            u.x * self.height
        } else {
            let (r0, r1) = (self.r0 as f64, self.r1 as f64);
            let r = (r0 * r0 + u.x as f64 * (r1 * r1 - r0 * r0)).sqrt();
            ((r - r0) / (r1 - r0) * self.height as f64) as f32
        };
        let phi = std::f32::consts::TAU * u.y;
        let (x, z) = crate::geometry::orthonormal_basis(self.axis);
        let radial = phi.cos() * x + phi.sin() * z;
        let p = self.base + h * self.axis + self.radius_at(h) * radial;
        let dr = self.r1 - self.r0;
        let n = (self.height * radial - dr * self.axis).normalize();
        (p, n)
    }

    /// The boxes of the two end circles.
    fn bounds(&self) -> Aabb {
        let top = self.base + self.height * self.axis;
        let (e0, e1) = (
            crate::geometry::disk::extent(self.axis, self.r0),
            crate::geometry::disk::extent(self.axis, self.r1),
        );
        Aabb {
            min: (self.base - e0).min(top - e1),
            max: (self.base + e0).max(top + e1),
        }
    }

    fn uv_frame(&self) -> (Vec3, Vec3) {
        (self.base, self.axis)
    }

    fn texcoord(&self, local: Vec3, scale: f32) -> Vec2 {
        texcoord::cone(local, self.height * scale)
    }

    fn texcoord_derivatives(&self, local: Vec3, scale: f32) -> (Vec3, Vec3) {
        texcoord::cone_derivatives(local, self.height * scale, (self.r1 - self.r0) * scale)
    }
}

/// The real roots of a·t² + b·t + c, ascending, in the cancellation-free
/// form t = q/a, c/q (one root twice when `a` is zero: a line).
pub fn quadratic_roots(a: f64, b: f64, c: f64) -> Option<(f64, f64)> {
    if a == 0.0 {
        if b == 0.0 {
            return None;
        }
        let t = -c / b;
        return Some((t, t));
    }
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return None;
    }
    let q = -0.5 * (b + disc.sqrt().copysign(b));
    let (t0, t1) = if q == 0.0 { (0.0, 0.0) } else { (q / a, c / q) };
    Some((t0.min(t1), t0.max(t1)))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ray(o: [f32; 3], d: [f32; 3]) -> Ray {
        Ray::new(Vec3::from(o), Vec3::from(d).normalize(), 0.0)
    }

    fn cylinder() -> Cone {
        Cone {
            base: Vec3::ZERO,
            axis: Vec3::Y,
            height: 2.0,
            r0: 1.0,
            r1: 1.0,
        }
    }

    #[test]
    fn cylinder_hit_miss_inside_beyond_the_ends() {
        let c = cylinder();
        let hit = |o, d| c.intersect(&ray(o, d), 1e-4, f32::INFINITY).map(|h| h.t);
        assert!((hit([0., 1., 5.], [0., 0., -1.]).unwrap() - 4.0).abs() < 1e-5);
        // Inside: the far wall.
        assert!((hit([0., 1., 0.], [1., 0., 0.]).unwrap() - 1.0).abs() < 1e-5);
        // Above the top, beside it, along the axis (open ends).
        assert!(hit([0., 3., 5.], [0., 0., -1.]).is_none());
        assert!(hit([1.5, 1., 5.], [0., 0., -1.]).is_none());
        assert!(hit([0., 5., 0.], [0., -1., 0.]).is_none());
        // Grazing the side: tangent at x = 1 (hits, once, or misses just outside).
        assert!(hit([1.001, 1., 5.], [0., 0., -1.]).is_none());
        assert!(hit([0.999, 1., 5.], [0., 0., -1.]).is_some());
        // Slanted, entering through the open top: hits the inside wall.
        let t = hit([0., 3., 0.], [1., -1., 0.]).unwrap();
        let p = ray([0., 3., 0.], [1., -1., 0.]).at(t);
        assert!((p - Vec3::new(1.0, 2.0, 0.0)).length() < 1e-4, "{p}");
    }

    #[test]
    fn transformed_cylinder_and_its_normals() {
        // Along x from (1, 2, 3), radius 0.5.
        let c = Cone {
            base: Vec3::new(1.0, 2.0, 3.0),
            axis: Vec3::X,
            height: 4.0,
            r0: 0.5,
            r1: 0.5,
        };
        let r = ray([3., 2., 10.], [0., 0., -1.]);
        let t = c.intersect(&r, 1e-4, f32::INFINITY).unwrap().t;
        assert!((t - 6.5).abs() < 1e-5);
        let n = c.normal_at(c.project(r.at(t)));
        assert!((n - Vec3::Z).length() < 1e-5);
        let b = c.bounds();
        assert!((b.min - Vec3::new(1.0, 1.5, 2.5)).length() < 1e-6);
        assert!((b.max - Vec3::new(5.0, 2.5, 3.5)).length() < 1e-6);
    }

    #[test]
    fn cone_hits_and_normal() {
        // Radius 1 at y = 0 to a point at y = 1: the side is at 45°.
        let c = Cone {
            base: Vec3::ZERO,
            axis: Vec3::Y,
            height: 1.0,
            r0: 1.0,
            r1: 0.0,
        };
        let r = ray([0., 0.5, 5.], [0., 0., -1.]);
        let t = c.intersect(&r, 1e-4, f32::INFINITY).unwrap().t;
        assert!((t - 4.5).abs() < 1e-5);
        let n = c.normal_at(r.at(t));
        assert!((n - Vec3::new(0.0, 1.0, 1.0).normalize()).length() < 1e-5);
        // The other nappe (above the apex) is not part of the cone.
        assert!(c
            .intersect(&ray([0., 1.5, 5.], [0., 0., -1.]), 1e-4, f32::INFINITY)
            .is_none());
        let want = std::f32::consts::PI * 2f32.sqrt();
        assert!((c.area() - want).abs() < 1e-5);
    }

    #[test]
    fn area_samples_lie_on_the_surface_with_the_radius_density() {
        let c = Cone {
            base: Vec3::new(0.0, -1.0, 0.0),
            axis: Vec3::new(1.0, 2.0, 0.5).normalize(),
            height: 2.0,
            r0: 0.3,
            r1: 1.2,
        };
        let n = 64;
        let mut mean_h = 0.0;
        for i in 0..n {
            for j in 0..4 {
                let u = Vec2::new((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / 4.0);
                let (p, normal) = c.sample_area(u);
                assert!((c.project(p) - p).length() < 1e-5);
                assert!((c.normal_at(p) - normal).length() < 1e-4);
                mean_h += (p - c.base).dot(c.axis) / (4 * n) as f32;
            }
        }
        // Density ∝ r(h) = 0.3 + 0.45 h on [0, 2]: the mean height is
        // (∫₀² 0.3h + 0.45h² dh) / (∫₀² 0.3 + 0.45h dh) = 1.8 / 1.5.
        assert!((mean_h - 1.2).abs() < 1e-2, "{mean_h}");
    }
}
