//! The capsule: every point within `radius` of the segment from `base` to
//! `top` (written `capsule { base <0,0,0> top <0,2,0> radius 0.5 }`, the
//! words of `cylinder`). Its surface is a cylinder about the segment,
//! clipped to it, closed by two hemispheres; `base = top` is a sphere.
//!
//! A ray meets the infinite cylinder about the axis and the two end
//! spheres in up to six roots; a root belongs to the surface when its
//! height along the axis lies in that piece's part (the cylinder's between
//! the ends, a sphere's beyond its end). The roots are taken in f64, in the
//! cancellation-free form of the quadratic (pbrt-v4 §6.3; Haines et al.,
//! Ray Tracing Gems ch. 7), from the ray's origin moved to where it enters
//! the bounding sphere, as the torus does, so that a far origin costs no
//! digits.
//!
//! Texture coordinates: u is the angle around the axis / 2π, from the same
//! frame and reference direction as a cylinder's (`texcoord::axis_frame`
//! of the axis, u = 0 along its x, a quarter turn towards its z); v is the
//! arc length along the meridian from the base's pole (v = 0) over the
//! base cap, up the side and over the top cap to the top's pole (v = 1),
//! divided by the meridian's length πr + h, so that an image keeps its
//! proportions along the whole profile (it does not stretch over the
//! caps) and runs on across the seams where the caps meet the side.

use super::cone::quadratic_roots;
use super::{Description, Round, Surface};
use crate::geometry::shape::{Shape, ShapeHit};
use crate::geometry::{orthonormal_basis, texcoord, unit, unit_f32, Aabb, Ray};
use glam::{DMat4, DVec3, Vec2, Vec3};
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// A capsule in its object's frame.
#[derive(Debug, Clone, PartialEq)]
pub struct CapsuleDesc {
    /// One end of the segment (the centre of the base's hemisphere).
    pub base: DVec3,
    /// The other end (the centre of the top's hemisphere).
    pub top: DVec3,
    /// Distance of the surface from the segment.
    pub radius: f64,
}

impl Description for CapsuleDesc {
    fn name(&self) -> &'static str {
        "capsule"
    }

    /// The axis is taken in f64 before rounding, so that a short capsule
    /// far from the origin keeps its direction; a capsule without length
    /// (a sphere) takes its object's y as its axis, which its texture
    /// coordinates are laid about.
    fn place(&self, m: &DMat4, scale: f64, out: &mut Vec<Shape>) {
        let along = self.top - self.base;
        let axis = unit(along).unwrap_or(DVec3::Y);
        out.push(Shape::Round(Round::Capsule(Capsule {
            base: m.transform_point3(self.base).as_vec3(),
            axis: unit_f32(m.transform_vector3(axis)),
            height: (along.length() * scale) as f32,
            radius: (self.radius * scale) as f32,
        })));
    }

    fn numbers(&self) -> Vec<f64> {
        let [b, t] = [self.base, self.top].map(|p| p.to_array());
        [&b[..], &t[..], &[self.radius]].concat()
    }
}

/// A capsule placed: the segment from `base` along the unit `axis` for
/// `height`, and the distance `radius` from it.
#[derive(Debug, Clone, Copy)]
pub struct Capsule {
    /// Centre of the base's hemisphere.
    pub base: Vec3,
    /// Unit axis from the base to the top.
    pub axis: Vec3,
    /// Length of the segment (0: a sphere).
    pub height: f32,
    /// Distance of the surface from the segment.
    pub radius: f32,
}

impl Capsule {
    /// The base, the unit axis (normalised again in f64: the stored one
    /// is a rounding away from unit), the height and the radius, in f64.
    fn f64s(&self) -> (DVec3, DVec3, f64, f64) {
        let a = self.axis.as_dvec3();
        let a = a / a.length();
        (
            self.base.as_dvec3(),
            a,
            self.height as f64,
            self.radius as f64,
        )
    }

    /// From the base to `p` (f64): its height along the axis, and its part
    /// across the axis seen from the nearest point of the segment.
    fn split(&self, p: Vec3) -> (f64, DVec3) {
        let (base, a, h_max, _) = self.f64s();
        let d = p.as_dvec3() - base;
        let h = d.dot(a);
        (h, d - h.clamp(0.0, h_max) * a)
    }
}

impl Surface for Capsule {
    #[inline(never)]
    fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<ShapeHit> {
        let (base, a, h_max, r) = self.f64s();
        let d = ray.d.as_dvec3();
        // The stretch of the ray inside the bounding sphere.
        let mid = 0.5 * h_max * a;
        let o = ray.o.as_dvec3() - base - mid;
        let bound = 0.5 * h_max + r;
        let dd = d.length_squared();
        let (s0, s1) = quadratic_roots(dd, 2.0 * o.dot(d), o.length_squared() - bound * bound)?;
        let lo = s0.max(t_min as f64);
        if lo >= s1.min(t_max as f64) {
            return None;
        }
        // From the origin moved to `lo`, relative to the base.
        let o = o + lo * d + mid;
        let (oa, da) = (o.dot(a), d.dot(a));
        // The pieces overlap by a hair at the seams, so that no rounding
        // of the height opens a crack between them; there the cylinder
        // and the sphere differ by (hair)² / 2r.
        let hair = 1e-9 * bound;
        let (op, dp) = (o - oa * a, d - da * a);
        let side = quadratic_roots(
            dp.length_squared(),
            2.0 * op.dot(dp),
            op.length_squared() - r * r,
        );
        let ends = [0.0, h_max].map(|h| {
            let oc = o - h * a;
            quadratic_roots(dd, 2.0 * oc.dot(d), oc.length_squared() - r * r)
        });
        let parts = [
            (side, -hair, h_max + hair),
            (ends[0], f64::NEG_INFINITY, hair),
            (ends[1], h_max - hair, f64::INFINITY),
        ];
        let mut best: Option<f32> = None;
        for (roots, h0, h1) in parts {
            let Some((r0, r1)) = roots else { continue };
            for s in [r0, r1] {
                let t = (lo + s) as f32;
                let h = oa + s * da;
                if t > t_min && t < t_max && h >= h0 && h <= h1 && best.is_none_or(|b| t < b) {
                    best = Some(t);
                }
            }
        }
        best.map(|t| ShapeHit { t, uv: Vec2::ZERO })
    }

    /// The nearest point of the segment, then `radius` from it towards `p`.
    #[inline(never)]
    fn project(&self, p: Vec3) -> Vec3 {
        let (h, across) = self.split(p);
        let len = across.length();
        if len == 0.0 {
            return p;
        }
        let (base, a, h_max, r) = self.f64s();
        (base + h.clamp(0.0, h_max) * a + across * (r / len)).as_vec3()
    }

    /// Away from the nearest point of the segment.
    #[inline(never)]
    fn normal_at(&self, p: Vec3) -> Vec3 {
        let (_, across) = self.split(p);
        let len = across.length();
        if len == 0.0 {
            return self.axis;
        }
        (across / len).as_vec3()
    }

    /// The side's 2πr·h and a whole sphere's 4πr².
    #[inline(never)]
    fn area(&self) -> f32 {
        let (h, r) = (self.height, self.radius);
        std::f32::consts::TAU * r * (h + 2.0 * r)
    }

    /// Uniform by area is uniform along the axis: the side has 2πr of area
    /// per unit of height, and so has a sphere between two planes across
    /// it (Archimedes' hat-box theorem). The height z runs over
    /// [−r, h + r] with u.x and the angle around the axis with u.y.
    fn sample_area(&self, u: Vec2) -> (Vec3, Vec3) {
        let (_, a, h_max, r) = self.f64s();
        let z = -r + u.x as f64 * (h_max + 2.0 * r);
        let beyond = z - z.clamp(0.0, h_max);
        let rho = (r * r - beyond * beyond).max(0.0).sqrt();
        let phi = TAU * u.y as f64;
        let (x, y) = orthonormal_basis(self.axis);
        let radial = phi.cos() * x.as_dvec3() + phi.sin() * y.as_dvec3();
        let p = self.base.as_dvec3() + z * a + rho * radial;
        let n = (beyond * a + rho * radial) / r;
        (p.as_vec3(), n.normalize().as_vec3())
    }

    /// The boxes of the two end spheres, a few ulps wider: the ends are
    /// computed in f64 and rounded.
    fn bounds(&self) -> Aabb {
        let (base, a, h_max, r) = self.f64s();
        let top = base + h_max * a;
        let (lo, hi) = (base.min(top) - r, base.max(top) + r);
        let slack = lo.abs().max(hi.abs()) * (4.0 * f32::EPSILON as f64);
        Aabb {
            min: (lo - slack).as_vec3(),
            max: (hi + slack).as_vec3(),
        }
    }

    fn uv_frame(&self) -> (Vec3, Vec3) {
        (self.base, self.axis)
    }

    fn texcoord(&self, local: Vec3, scale: f32) -> Vec2 {
        let (h_max, r) = ((self.height * scale) as f64, (self.radius * scale) as f64);
        // u as a cylinder's (its v is not used).
        let u = texcoord::cone(local, 1.0).x;
        let (y, rho) = (local.y as f64, local.x.hypot(local.z) as f64);
        let arc = if y < 0.0 {
            r * rho.atan2(-y)
        } else if y > h_max {
            PI * r + h_max - r * rho.atan2(y - h_max)
        } else {
            FRAC_PI_2 * r + y
        };
        Vec2::new(u, (arc / (PI * r + h_max)).clamp(0.0, 1.0) as f32)
    }

    /// ∂p/∂u is 2π times the parallel's tangent, as a cylinder's; ∂p/∂v is
    /// the meridian's length times its unit tangent towards the top (the
    /// normal turned a quarter towards the top). At a pole, where every
    /// meridian meets, the tangent of the meridian along x.
    fn texcoord_derivatives(&self, local: Vec3, scale: f32) -> (Vec3, Vec3) {
        let (h_max, r) = ((self.height * scale) as f64, (self.radius * scale) as f64);
        let l = local.as_dvec3();
        let dpdu = TAU * DVec3::new(-l.z, 0.0, l.x);
        let rho = l.x.hypot(l.z);
        let radial = if rho > 0.0 {
            DVec3::new(l.x / rho, 0.0, l.z / rho)
        } else {
            DVec3::X
        };
        let beyond = l.y - l.y.clamp(0.0, h_max);
        let dist = rho.hypot(beyond);
        let tangent = if dist > 0.0 {
            (-beyond * radial + DVec3::new(0.0, rho, 0.0)) / dist
        } else {
            DVec3::Y
        };
        (dpdu.as_vec3(), ((PI * r + h_max) * tangent).as_vec3())
    }
}

#[cfg(test)]
#[path = "capsule_tests.rs"]
mod tests;
