//! Sampling a sphere lamp by the cone of directions it subtends from the
//! shading point (pbrt-v4 §6.2.4, `Sphere::Sample(ctx, u)`), rather than by
//! area: every sample lands on the visible cap, and the pdf is constant over
//! the cone. From inside the sphere, area sampling remains.

use crate::geometry::orthonormal_basis;
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// sin² of 1.5°: below it, 1 − cos θ_max is taken from its Taylor series
/// (pbrt-v4: the subtraction loses every digit for tiny or distant spheres).
const SMALL_SIN2: f32 = 0.000_685_23;

/// 1 − cos θ_max of the cone whose sin² θ_max is `sin2`.
#[inline]
fn one_minus_cos_max(sin2: f32) -> f32 {
    if sin2 < SMALL_SIN2 {
        0.5 * sin2
    } else {
        1.0 - (1.0 - sin2).max(0.0).sqrt()
    }
}

/// The solid-angle pdf of [`sample_cone`] from `p` (the same for every
/// direction in the cone); `None` from inside the sphere.
#[inline]
pub fn cone_pdf(center: Vec3, radius: f32, p: Vec3) -> Option<f32> {
    let d2 = (p - center).length_squared();
    let r2 = radius * radius;
    if d2 <= r2 * (1.0 + 1e-4) {
        return None;
    }
    let omc = one_minus_cos_max(r2 / d2);
    (omc > 0.0).then(|| 1.0 / (2.0 * PI * omc))
}

/// A point on the part of the sphere seen from `p`, sampled uniformly in the
/// cone it subtends: the point, its outward normal and the solid-angle pdf;
/// `None` from inside the sphere.
#[inline]
pub fn sample_cone(center: Vec3, radius: f32, p: Vec3, u: Vec2) -> Option<(Vec3, Vec3, f32)> {
    let to_center = center - p;
    let d2 = to_center.length_squared();
    let r2 = radius * radius;
    if d2 <= r2 * (1.0 + 1e-4) {
        return None;
    }
    let sin2_max = r2 / d2;
    let sin_max = sin2_max.sqrt();
    let omc = one_minus_cos_max(sin2_max);
    if omc <= 0.0 {
        return None;
    }
    // A direction in the cone: cos θ uniform in [cos θ_max, 1].
    let mut cos_theta = 1.0 - omc * u.x;
    let mut sin2_theta = 1.0 - cos_theta * cos_theta;
    if sin2_max < SMALL_SIN2 {
        sin2_theta = sin2_max * u.x;
        cos_theta = (1.0 - sin2_theta).sqrt();
    }
    // The angle α at the centre between the axis and the point where that
    // direction meets the sphere.
    let cos_alpha =
        sin2_theta / sin_max + cos_theta * (1.0 - sin2_theta / sin2_max).max(0.0).sqrt();
    let sin_alpha = (1.0 - cos_alpha * cos_alpha).max(0.0).sqrt();
    let phi = 2.0 * PI * u.y;
    let axis = to_center / d2.sqrt();
    let (t, b) = orthonormal_basis(axis);
    // The outward normal points back towards p's side of the sphere.
    let n = (-(axis * cos_alpha) + (t * phi.cos() + b * phi.sin()) * sin_alpha).normalize();
    let q = center + radius * n;
    Some((q, n, 1.0 / (2.0 * PI * omc)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn samples_are_on_the_visible_cap_and_the_pdf_integrates_to_the_cone() {
        let (c, r) = (Vec3::new(0.3, 1.0, -0.2), 0.4);
        for p in [
            Vec3::ZERO,
            Vec3::new(5.0, -3.0, 40.0),
            Vec3::new(0.3, 1.5, -0.2),
        ] {
            let pdf = cone_pdf(c, r, p).unwrap();
            let mut count = 0;
            for i in 0..64 {
                for j in 0..64 {
                    let u = Vec2::new((i as f32 + 0.5) / 64.0, (j as f32 + 0.5) / 64.0);
                    let (q, n, pq) = sample_cone(c, r, p, u).unwrap();
                    assert!(((q - c).length() - r).abs() < 1e-4 * (1.0 + (p - c).length()));
                    assert!(n.dot(p - q) >= -1e-3, "a point on the far side");
                    assert_eq!(pq, pdf);
                    count += 1;
                }
            }
            // The cone's solid angle is 2π(1 − cos θ_max) = 1/pdf.
            let d = (p - c).length() as f64;
            let exact = 2.0 * std::f64::consts::PI * (1.0 - (1.0 - (r as f64 / d).powi(2)).sqrt());
            assert!(
                ((1.0 / pdf as f64) / exact - 1.0).abs() < 2e-3,
                "{} vs {exact}",
                1.0 / pdf
            );
            assert_eq!(count, 4096);
        }
        assert!(cone_pdf(c, r, c + Vec3::new(0.1, 0.0, 0.0)).is_none());
    }

    #[test]
    fn directions_are_uniform_in_the_cone() {
        // The mean of cos θ (to the axis) over uniform directions in a cone
        // is (1 + cos θ_max) / 2.
        let (c, r, p) = (Vec3::new(0.0, 0.0, -3.0), 1.0f32, Vec3::ZERO);
        let cos_max = (1.0 - (r / 3.0).powi(2)).sqrt();
        let mut sum = 0.0f64;
        let k = 256;
        for i in 0..k {
            for j in 0..k {
                let u = Vec2::new((i as f32 + 0.5) / k as f32, (j as f32 + 0.5) / k as f32);
                let (q, _, _) = sample_cone(c, r, p, u).unwrap();
                sum += (q - p).normalize().dot(-Vec3::Z) as f64;
            }
        }
        let mean = sum / (k * k) as f64;
        assert!((mean - (1.0 + cos_max as f64) / 2.0).abs() < 1e-4, "{mean}");
    }
}
