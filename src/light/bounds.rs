//! Bounds of the light a bounded emitter (or a set of them) can send: where
//! it is, which way it faces, how much it emits. From these, a shading point
//! estimates each light's contribution without sampling it (Conty Estevez &
//! Kulla 2018, "Importance Sampling of Many Lights with Adaptive Tree
//! Splitting"; pbrt-v4 §12.6.3, `LightBounds`).

use crate::geometry::Aabb;
use glam::Vec3;
use std::f32::consts::PI;

/// A cone of directions: unit axis and the cosine of its half-angle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DirectionCone {
    /// Unit axis.
    pub w: Vec3,
    /// Cosine of the half-angle (−1: every direction).
    pub cos_theta: f32,
}

impl DirectionCone {
    /// Every direction.
    pub const SPHERE: DirectionCone = DirectionCone {
        w: Vec3::Z,
        cos_theta: -1.0,
    };

    /// The smallest cone (of this construction) holding both (pbrt-v4
    /// §3.8.4, `Union(DirectionCone, DirectionCone)`). Slightly widened so
    /// that rounding never leaves a direction of either outside.
    pub fn union(a: DirectionCone, b: DirectionCone) -> DirectionCone {
        let theta_a = safe_acos(a.cos_theta);
        let theta_b = safe_acos(b.cos_theta);
        let theta_d = angle_between(a.w, b.w);
        if (theta_d + theta_b).min(PI) <= theta_a {
            return a;
        }
        if (theta_d + theta_a).min(PI) <= theta_b {
            return b;
        }
        // The new half-angle spans both; its axis turns from a's towards b's.
        let theta_o = 0.5 * (theta_a + theta_d + theta_b) + 1e-4;
        if theta_o >= PI {
            return DirectionCone::SPHERE;
        }
        let theta_r = theta_o - theta_a;
        let axis = a.w.cross(b.w);
        if axis.length_squared() < 1e-12 {
            return DirectionCone::SPHERE;
        }
        let towards_b = axis.normalize().cross(a.w);
        let w = (a.w * theta_r.cos() + towards_b * theta_r.sin()).normalize();
        DirectionCone {
            w,
            cos_theta: theta_o.cos(),
        }
    }
}

/// What a shading point needs to know about a light (or a group of them) to
/// estimate its contribution: bounds, power and the cones of its normals and
/// of its emission around them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LightBounds {
    /// Where the emitters are (over the whole shutter interval).
    pub bounds: Aabb,
    /// Axis of the normals' cone.
    pub w: Vec3,
    /// Emitted power (any positive estimate; in f64 so that sums over many
    /// bright, large lights stay finite).
    pub phi: f64,
    /// Cosine of the half-angle of the normals' cone (θ_o).
    pub cos_o: f32,
    /// Cosine of the angle beyond the normals' cone that light still leaves
    /// at (θ_e: π/2 for diffuse emitters).
    pub cos_e: f32,
    /// Whether the emitters emit on both sides of their normals.
    pub two_sided: bool,
}

/// cos(max(0, θa − θb)) from sines and cosines (pbrt-v4's `cosSubClamped`).
#[inline]
fn cos_sub_clamped(sin_a: f32, cos_a: f32, sin_b: f32, cos_b: f32) -> f32 {
    if cos_a > cos_b {
        1.0
    } else {
        cos_a * cos_b + sin_a * sin_b
    }
}

/// sin(max(0, θa − θb)) from sines and cosines.
#[inline]
fn sin_sub_clamped(sin_a: f32, cos_a: f32, sin_b: f32, cos_b: f32) -> f32 {
    if cos_a > cos_b {
        0.0
    } else {
        sin_a * cos_b - cos_a * sin_b
    }
}

#[inline]
fn safe_sqrt(x: f32) -> f32 {
    x.max(0.0).sqrt()
}

#[inline]
fn safe_acos(x: f32) -> f32 {
    x.clamp(-1.0, 1.0).acos()
}

/// The angle between two unit vectors, accurate for small and large angles.
fn angle_between(a: Vec3, b: Vec3) -> f32 {
    if a.dot(b) < 0.0 {
        PI - 2.0 * safe_asin(0.5 * (a + b).length())
    } else {
        2.0 * safe_asin(0.5 * (b - a).length())
    }
}

#[inline]
fn safe_asin(x: f32) -> f32 {
    x.clamp(-1.0, 1.0).asin()
}

impl LightBounds {
    /// The bounds of both sets (pbrt-v4's `Union(LightBounds, LightBounds)`).
    pub fn union(a: &LightBounds, b: &LightBounds) -> LightBounds {
        if a.phi <= 0.0 {
            return *b;
        }
        if b.phi <= 0.0 {
            return *a;
        }
        let cone = DirectionCone::union(
            DirectionCone {
                w: a.w,
                cos_theta: a.cos_o,
            },
            DirectionCone {
                w: b.w,
                cos_theta: b.cos_o,
            },
        );
        LightBounds {
            bounds: a.bounds.union(b.bounds),
            w: cone.w,
            phi: a.phi + b.phi,
            cos_o: cone.cos_theta,
            cos_e: a.cos_e.min(b.cos_e),
            two_sided: a.two_sided || b.two_sided,
        }
    }

    /// An estimate of the light arriving at `p`: see
    /// [`CompactLightBounds::importance`].
    pub fn importance(&self, p: Vec3, n: Vec3) -> f64 {
        CompactLightBounds::from(self).importance(p, n)
    }

    /// The measure M_Ω of the emission cones (Conty Estevez & Kulla 2018;
    /// pbrt-v4 §12.6.3, `EvaluateCost`: the integral of cos θ' over the normals' cone widened by θ_e), used
    /// by the tree's build cost.
    pub fn cone_measure(&self) -> f32 {
        let theta_o = safe_acos(self.cos_o);
        let theta_e = safe_acos(self.cos_e);
        let theta_w = (theta_o + theta_e).min(PI);
        let sin_o = safe_sqrt(1.0 - self.cos_o * self.cos_o);
        2.0 * PI * (1.0 - self.cos_o)
            + PI / 2.0
                * (2.0 * theta_w * sin_o - (theta_o - 2.0 * theta_w).cos() - 2.0 * theta_o * sin_o
                    + self.cos_o)
    }
}

/// [`LightBounds`] as the samplers read them: the bounding sphere instead of
/// the box, the sine of the normals' cone precomputed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CompactLightBounds {
    /// Centre of the bounding sphere.
    pub center: Vec3,
    /// Its radius.
    pub radius: f32,
    /// Axis of the normals' cone.
    pub w: Vec3,
    /// Cosine of the normals' cone's half-angle (−1: every direction).
    pub cos_o: f32,
    /// Its sine.
    pub sin_o: f32,
    /// Cosine of the emission's spread beyond the normals' cone.
    pub cos_e: f32,
    /// Whether the emitters emit on both sides.
    pub two_sided: bool,
    /// Emitted power.
    pub phi: f64,
    /// Half extents of the box.
    pub half: Vec3,
}

impl From<&LightBounds> for CompactLightBounds {
    fn from(b: &LightBounds) -> Self {
        CompactLightBounds {
            center: b.bounds.center(),
            radius: 0.5 * (b.bounds.max - b.bounds.min).length(),
            w: b.w,
            cos_o: b.cos_o,
            sin_o: safe_sqrt(1.0 - b.cos_o * b.cos_o),
            cos_e: b.cos_e,
            two_sided: b.two_sided,
            phi: b.phi,
            half: 0.5 * (b.bounds.max - b.bounds.min),
        }
    }
}

impl CompactLightBounds {
    /// An estimate of the light arriving at `p` (on a surface with normal
    /// `n`, or `Vec3::ZERO` for none): power × the cosine of the smallest
    /// angle between the emitters' cone and the direction to `p` ÷ the
    /// squared distance, × the smallest incident cosine at `p` (pbrt-v4
    /// §12.6.3, `LightBounds::Importance`). Zero only where none of the
    /// emitters can send light to `p` (so that choosing by it stays
    /// unbiased). The distance is to the box, where pbrt-v4 takes it to the
    /// centre clamped to the half diagonal: on a flat grid of 10,000 lamps
    /// over a floor (examples/many_lights.pts) every floor point lies within
    /// the upper nodes' clamp, which then choose by power alone; with the
    /// box distance the noise at equal samples fell from 1.49× below power
    /// selection's to 6× below (docs/performance.md, "Light selection").
    #[inline]
    pub fn importance(&self, p: Vec3, n: Vec3) -> f64 {
        let to = p - self.center;
        let d2 = to.length_squared();
        let r2 = self.radius * self.radius;
        // The squared distance to the box (not to its centre): a point
        // beside a long row of lamps is near some of them. Floored at a
        // thousandth of the squared radius, so that a point inside a box
        // does not take every sample from a neighbour just across its side.
        let outside = (to.abs() - self.half).max(Vec3::ZERO);
        let dist2 = (outside.length_squared() as f64)
            .max(1e-3 * r2 as f64)
            .max(1e-30);
        if d2 <= r2 {
            // Inside the bounding sphere every direction is possible.
            return self.phi / dist2;
        }
        let inv_d = d2.sqrt().recip();
        let wi = to * inv_d;
        // The cone of directions from p that the bounding sphere subtends.
        let sin_b = (self.radius * inv_d).min(1.0);
        let cos_b = safe_sqrt(1.0 - sin_b * sin_b);
        // θ' = max(0, θ_w − θ_o − θ_b): the smallest angle between an
        // emitter's normal and a direction towards p (1 when the normals
        // span every direction).
        let cos_p = if self.cos_o <= -1.0 {
            1.0
        } else {
            let mut cos_w = self.w.dot(wi);
            if self.two_sided {
                cos_w = cos_w.abs();
            }
            let sin_w = safe_sqrt(1.0 - cos_w * cos_w);
            let cos_x = cos_sub_clamped(sin_w, cos_w, self.sin_o, self.cos_o);
            let sin_x = sin_sub_clamped(sin_w, cos_w, self.sin_o, self.cos_o);
            cos_sub_clamped(sin_x, cos_x, sin_b, cos_b)
        };
        // Strictly beyond: a hard-edged spot (θ_e = 0) still lights the
        // points inside its cone (pbrt-v4's `<=` turns it off).
        if cos_p < self.cos_e {
            return 0.0;
        }
        let mut cosines = cos_p;
        if n != Vec3::ZERO {
            let cos_i = wi.dot(n).abs();
            let sin_i = safe_sqrt(1.0 - cos_i * cos_i);
            cosines *= cos_sub_clamped(sin_i, cos_i, sin_b, cos_b);
        }
        (self.phi * cosines.max(0.0) as f64 / dist2).max(0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point_light(p: Vec3, phi: f64) -> LightBounds {
        LightBounds {
            bounds: Aabb { min: p, max: p },
            w: Vec3::Z,
            phi,
            cos_o: -1.0,
            cos_e: 0.0,
            two_sided: false,
        }
    }

    fn quad_light(center: Vec3, half: f32, normal: Vec3, two_sided: bool) -> LightBounds {
        LightBounds {
            bounds: Aabb {
                min: center - Vec3::splat(half) * (Vec3::ONE - normal.abs()),
                max: center + Vec3::splat(half) * (Vec3::ONE - normal.abs()),
            },
            w: normal,
            phi: 1.0,
            cos_o: 1.0,
            cos_e: 0.0,
            two_sided,
        }
    }

    #[test]
    fn a_point_light_falls_off_with_the_square_of_the_distance() {
        let l = point_light(Vec3::ZERO, 4.0);
        let a = l.importance(Vec3::new(0.0, 0.0, 1.0), Vec3::ZERO);
        let b = l.importance(Vec3::new(0.0, 0.0, 2.0), Vec3::ZERO);
        assert!((a - 4.0).abs() < 1e-6 && (b - 1.0).abs() < 1e-6, "{a} {b}");
        // On the light itself: large and finite.
        let at = l.importance(Vec3::ZERO, Vec3::Y);
        assert!(at.is_finite() && at > 1e20);
    }

    #[test]
    fn the_incident_cosine_bounds_a_surface_point() {
        let l = point_light(Vec3::new(0.0, 1.0, 0.0), 1.0);
        let facing = l.importance(Vec3::ZERO, Vec3::Y);
        let grazing = l.importance(Vec3::ZERO, Vec3::X);
        let tilted = l.importance(Vec3::ZERO, Vec3::new(1.0, 1.0, 0.0).normalize());
        assert!((facing - 1.0).abs() < 1e-6);
        assert!(grazing.abs() < 1e-6, "{grazing}");
        assert!((tilted - 0.5f64.sqrt()).abs() < 1e-5, "{tilted}");
    }

    #[test]
    fn a_one_sided_emitter_is_dark_behind_and_a_two_sided_one_is_not() {
        let one = quad_light(Vec3::ZERO, 0.5, Vec3::Y, false);
        let two = quad_light(Vec3::ZERO, 0.5, Vec3::Y, true);
        let above = Vec3::new(0.3, 2.0, 0.1);
        let below = Vec3::new(0.3, -2.0, 0.1);
        assert!(one.importance(above, Vec3::ZERO) > 0.0);
        assert_eq!(one.importance(below, Vec3::ZERO), 0.0);
        assert!(two.importance(below, Vec3::ZERO) > 0.0);
        // Beside the quad, outside its plane but close to it: the bounds
        // reach there, so the estimate is positive.
        assert!(one.importance(Vec3::new(2.0, 0.01, 0.0), Vec3::ZERO) > 0.0);
    }

    #[test]
    fn a_spot_light_is_dark_outside_its_cone() {
        let spot = LightBounds {
            cos_o: 30f32.to_radians().cos(),
            cos_e: (40f32 - 30.0).to_radians().cos(),
            ..point_light(Vec3::ZERO, 1.0)
        };
        let on_axis = spot.importance(Vec3::new(0.0, 0.0, 3.0), Vec3::ZERO);
        let in_falloff = spot.importance(
            3.0 * Vec3::new(35f32.to_radians().sin(), 0.0, 35f32.to_radians().cos()),
            Vec3::ZERO,
        );
        let outside = spot.importance(
            3.0 * Vec3::new(45f32.to_radians().sin(), 0.0, 45f32.to_radians().cos()),
            Vec3::ZERO,
        );
        assert!(on_axis > 0.0 && in_falloff > 0.0 && in_falloff < on_axis);
        assert_eq!(outside, 0.0);
        // A hard cone (θ_e = 0) lights its inside.
        let hard = LightBounds { cos_e: 1.0, ..spot };
        assert!(hard.importance(Vec3::new(0.0, 0.0, 3.0), Vec3::ZERO) > 0.0);
        assert_eq!(
            hard.importance(
                3.0 * Vec3::new(35f32.to_radians().sin(), 0.0, 35f32.to_radians().cos()),
                Vec3::ZERO
            ),
            0.0
        );
    }

    #[test]
    fn cone_union_holds_both_cones() {
        let mut rnd = crate::light::test_rng(7);
        for _ in 0..2000 {
            let dir = |a: f32, b: f32| {
                let z = 2.0 * a - 1.0;
                let r = safe_sqrt(1.0 - z * z);
                let phi = 2.0 * PI * b;
                Vec3::new(r * phi.cos(), r * phi.sin(), z)
            };
            let a = DirectionCone {
                w: dir(rnd(), rnd()),
                cos_theta: 2.0 * rnd() - 1.0,
            };
            let b = DirectionCone {
                w: dir(rnd(), rnd()),
                cos_theta: 2.0 * rnd() - 1.0,
            };
            let u = DirectionCone::union(a, b);
            // Each cone's axis and the edge directions towards and away from the
            // other's axis must lie inside the union.
            for c in [a, b] {
                let theta = safe_acos(c.cos_theta);
                let other = if c == a { b.w } else { a.w };
                let side = other - c.w * c.w.dot(other);
                let side = if side.length_squared() > 1e-8 {
                    side.normalize()
                } else {
                    c.w.any_orthonormal_vector()
                };
                for s in [-1.0f32, 1.0] {
                    let edge = c.w * theta.cos() + side * s * theta.sin();
                    let angle = angle_between(u.w, edge.normalize());
                    assert!(
                        angle <= safe_acos(u.cos_theta) + 1e-3,
                        "{a:?} {b:?} → {u:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn a_hemisphere_of_diffuse_emission_has_the_cosine_measure() {
        // A one-sided diffuse emitter: θ_o = 0, θ_e = π/2, θ_w = π/2:
        // 2π(1 − 1) + π/2 (0 − cos(−π) − 0 + 1) = π.
        let l = quad_light(Vec3::ZERO, 0.5, Vec3::Y, false);
        assert!((l.cone_measure() - PI).abs() < 1e-5, "{}", l.cone_measure());
        // Emission in every direction: θ_o = θ_w = π:
        // 2π·2 + π/2 (0 − cos(−π) − 0 − 1) = 4π.
        let p = point_light(Vec3::ZERO, 1.0);
        assert!(
            (p.cone_measure() - 4.0 * PI).abs() < 1e-4,
            "{}",
            p.cone_measure()
        );
    }
}
