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

/// A point of [0, 1] with density proportional to the line from `a` at 0
/// to `b` at 1 (both ≥ 0, not both 0), by inverting its cdf (pbrt-v4's
/// `SampleLinear`, written to stay exact as a or b goes to 0).
pub fn linear(u: f32, a: f32, b: f32) -> f32 {
    if u == 0.0 && a == 0.0 {
        return 0.0;
    }
    let x = u * (a + b) / (a + (a * a + u * (b * b - a * a)).max(0.0).sqrt());
    x.min(1.0 - f32::EPSILON / 2.0)
}

/// A point of [0, 1]² with density proportional to the bilinear
/// interpolation of the corner weights `w` = [w(0, 0), w(1, 0), w(0, 1),
/// w(1, 1)] (pbrt-v4's `SampleBilinear`): y from its marginal, x from the
/// line at that y.
pub fn bilinear(u: Vec2, w: [f32; 4]) -> Vec2 {
    let y = linear(u.y, w[0] + w[1], w[2] + w[3]);
    let x = linear(u.x, w[0] + (w[2] - w[0]) * y, w[1] + (w[3] - w[1]) * y);
    Vec2::new(x, y)
}

/// The density of [`bilinear`] at `p` (uniform when every weight is 0).
pub fn bilinear_pdf(p: Vec2, w: [f32; 4]) -> f32 {
    let sum = w[0] + w[1] + w[2] + w[3];
    if sum <= 0.0 {
        return 1.0;
    }
    let (x, y) = (p.x, p.y);
    4.0 * ((1.0 - x) * (1.0 - y) * w[0]
        + x * (1.0 - y) * w[1]
        + (1.0 - x) * y * w[2]
        + x * y * w[3])
        / sum
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bilinear_samples_follow_their_density() {
        use crate::sampling::chi2::pearson_p_value;
        let w = [0.0, 4.0, 1.0, 9.0];
        let n = 8;
        let mut observed = vec![0.0; n * n];
        let mut s = crate::sampling::sampler::Sampler::new(4, 4, 0, 0);
        let count = 100_000;
        for _ in 0..count {
            let p = bilinear(s.next_2d(), w);
            assert!((0.0..1.0).contains(&p.x) && (0.0..1.0).contains(&p.y));
            observed[(p.y * n as f32) as usize * n + (p.x * n as f32) as usize] += 1.0;
        }
        let expected: Vec<f64> = (0..n * n)
            .map(|k| {
                let c = Vec2::new(
                    ((k % n) as f32 + 0.5) / n as f32,
                    ((k / n) as f32 + 0.5) / n as f32,
                );
                // Bilinear: the midpoint rule is exact.
                bilinear_pdf(c, w) as f64 / (n * n) as f64 * count as f64
            })
            .collect();
        assert!(pearson_p_value(&observed, &expected) > 1e-3);
        assert_eq!(bilinear_pdf(Vec2::splat(0.3), [0.0; 4]), 1.0);
        assert_eq!(linear(0.5, 1.0, 1.0), 0.5);
        assert_eq!(linear(0.0, 0.0, 1.0), 0.0);
        assert!((linear(0.25, 0.0, 1.0) - 0.5).abs() < 1e-6);
    }

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
