//! Warps from the unit square to the distributions the renderer samples
//! (pbrt-v4 §A.5), each with its pdf.

use glam::{Vec2, Vec3};
use std::f32::consts::{FRAC_1_PI, PI};

/// Cosine-weighted direction on the hemisphere around +z (Malley's method).
pub fn cosine_hemisphere(u: Vec2) -> Vec3 {
    let d = concentric_disk(u);
    let z = (1.0 - d.length_squared()).max(0.0).sqrt();
    Vec3::new(d.x, d.y, z)
}

/// Pdf (solid angle) of [`cosine_hemisphere`] for a direction with `cos_theta`.
pub fn cosine_hemisphere_pdf(cos_theta: f32) -> f32 {
    cos_theta.max(0.0) * FRAC_1_PI
}

/// Uniform point on the unit disk, Shirley–Chiu concentric mapping.
pub fn concentric_disk(u: Vec2) -> Vec2 {
    let o = 2.0 * u - Vec2::ONE;
    if o == Vec2::ZERO {
        return Vec2::ZERO;
    }
    let (r, theta) = if o.x.abs() > o.y.abs() {
        (o.x, PI / 4.0 * (o.y / o.x))
    } else {
        (o.y, PI / 2.0 - PI / 4.0 * (o.x / o.y))
    };
    r * Vec2::new(theta.cos(), theta.sin())
}

/// Uniform direction on the unit sphere.
pub fn uniform_sphere(u: Vec2) -> Vec3 {
    let z = 1.0 - 2.0 * u.x;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = 2.0 * PI * u.y;
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// Pdf of [`uniform_sphere`].
pub const UNIFORM_SPHERE_PDF: f32 = 1.0 / (4.0 * PI);

/// Uniform barycentrics (b1, b2) on a triangle (Heitz 2019, low distortion).
pub fn uniform_triangle(u: Vec2) -> Vec2 {
    let (b0, b1);
    if u.x < u.y {
        b0 = u.x / 2.0;
        b1 = u.y - b0;
    } else {
        b1 = u.y / 2.0;
        b0 = u.x - b1;
    }
    Vec2::new(b0, b1)
}

/// Power heuristic with β = 2 (Veach 1997, §9.2.4). A pdf above about
/// 1.8e19 (an emitter seen at a grazing angle from afar) squares to
/// infinity: the weight then comes from the ratio of the pdfs, so it stays
/// in [0, 1] instead of becoming NaN.
pub fn power_heuristic(pdf_a: f32, pdf_b: f32) -> f32 {
    let (a, b) = (pdf_a * pdf_a, pdf_b * pdf_b);
    let sum = a + b;
    if sum == 0.0 {
        0.0
    } else if sum.is_finite() {
        a / sum
    } else if pdf_a.is_infinite() {
        if pdf_b.is_infinite() {
            0.5
        } else {
            1.0
        }
    } else {
        let r = pdf_b / pdf_a;
        1.0 / (1.0 + r * r)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn warps_stay_in_their_domains() {
        for i in 0..32 {
            for j in 0..32 {
                let u = Vec2::new((i as f32 + 0.5) / 32.0, (j as f32 + 0.5) / 32.0);
                assert!(concentric_disk(u).length() <= 1.0 + 1e-6);
                let c = cosine_hemisphere(u);
                assert!(c.z >= 0.0 && (c.length() - 1.0).abs() < 1e-5);
                assert!((uniform_sphere(u).length() - 1.0).abs() < 1e-5);
                let b = uniform_triangle(u);
                assert!(b.x >= 0.0 && b.y >= 0.0 && b.x + b.y <= 1.0 + 1e-6);
            }
        }
    }

    #[test]
    fn cosine_hemisphere_has_the_mean_of_its_pdf() {
        // E[cos θ] under p = cos θ/π is 2/3.
        let n = 256;
        let mut sum = 0.0;
        for i in 0..n {
            for j in 0..n {
                let u = Vec2::new((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32);
                sum += cosine_hemisphere(u).z as f64;
            }
        }
        assert!((sum / (n * n) as f64 - 2.0 / 3.0).abs() < 1e-3);
    }

    #[test]
    fn power_heuristic_weights_sum_to_one() {
        let (a, b) = (0.3, 1.7);
        assert!((power_heuristic(a, b) + power_heuristic(b, a) - 1.0).abs() < 1e-6);
        // Pdfs whose squares overflow, and infinite ones.
        for (a, b) in [
            (1e30f32, 1.0f32),
            (1e30, 2e30),
            (f32::INFINITY, 5.0),
            (f32::INFINITY, f32::INFINITY),
        ] {
            let (wa, wb) = (power_heuristic(a, b), power_heuristic(b, a));
            assert!(
                (0.0..=1.0).contains(&wa) && (wa + wb - 1.0).abs() < 1e-6,
                "{a} {b}: {wa} {wb}"
            );
        }
        assert!((power_heuristic(1e30, 2e30) - 0.2).abs() < 1e-6);
    }
}
