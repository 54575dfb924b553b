//! The Henyey–Greenstein phase function (Henyey & Greenstein 1941), the
//! angular distribution of light scattered in a medium, and its exact
//! sampling (pbrt-v4 §11.3.1, `SampleHenyeyGreenstein`; Mitsuba 3's `hg`).
//!
//! Convention: `wo` points back along the arriving light's path (towards
//! where the light goes, as a BSDF's `wo`) and `wi` towards where light
//! comes from; g > 0 scatters forward, i.e. `wi` near `−wo`.

use crate::geometry::orthonormal_basis;
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// The density of scattering by an angle whose cosine is `cos` (between
/// the propagation directions before and after), per steradian.
#[inline]
pub fn henyey_greenstein(cos: f32, g: f32) -> f32 {
    let denom = 1.0 + g * g - 2.0 * g * cos;
    (1.0 - g * g) / (4.0 * PI * denom * denom.max(1e-12).sqrt())
}

/// The phase function's value (also its pdf) for `wo` → `wi`.
#[inline]
pub fn eval(wo: Vec3, wi: Vec3, g: f32) -> f32 {
    // The propagation directions are −wi (arriving) and wo (leaving).
    henyey_greenstein(-wi.dot(wo), g)
}

/// Samples `wi` for `wo` from the phase function; returns it with its pdf
/// (which equals the value: the phase function is sampled exactly).
pub fn sample(wo: Vec3, g: f32, u: Vec2) -> (Vec3, f32) {
    // The cosine between the leaving direction wo and the arriving
    // propagation direction −wi, by inverting HG's cumulative distribution.
    let cos = if g.abs() < 1e-3 {
        1.0 - 2.0 * u.x
    } else {
        let s = (1.0 - g * g) / (1.0 + g - 2.0 * g * u.x);
        ((1.0 + g * g - s * s) / (2.0 * g)).clamp(-1.0, 1.0)
    };
    let sin = (1.0 - cos * cos).max(0.0).sqrt();
    let phi = 2.0 * PI * u.y;
    let (t, b) = orthonormal_basis(wo);
    // The propagation direction after scattering, at angle acos(cos) from the one before (−wi).
    let before = sin * phi.cos() * t + sin * phi.sin() * b + cos * wo;
    let wi = -before;
    (wi, henyey_greenstein(cos, g))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::chi2::sphere_p_value;
    use crate::sampling::sampler::Sampler;

    #[test]
    fn sampling_follows_the_phase_function() {
        let wo = Vec3::new(0.3, -0.5, 0.8).normalize();
        for (k, g) in [-0.9f32, -0.3, 0.0, 0.0005, 0.5, 0.95]
            .into_iter()
            .enumerate()
        {
            let mut s = Sampler::new(11, k as u32, 0, 0);
            let n = 200_000;
            let mut dirs = Vec::with_capacity(n);
            for _ in 0..n {
                let (wi, pdf) = sample(wo, g, s.next_2d());
                assert!(
                    (pdf - eval(wo, wi, g)).abs() <= 1e-3 * pdf.max(1.0),
                    "g {g}"
                );
                dirs.push(wi);
            }
            let p = sphere_p_value(dirs, n, |wi| eval(wo, wi, g), 6);
            assert!(p > 1e-4, "g {g}: χ² p-value {p}");
        }
    }

    #[test]
    fn a_wrong_asymmetry_fails_the_test() {
        let wo = Vec3::Z;
        let mut s = Sampler::new(3, 0, 0, 0);
        let n = 200_000;
        let dirs: Vec<Vec3> = (0..n).map(|_| sample(wo, 0.3, s.next_2d()).0).collect();
        assert!(sphere_p_value(dirs, n, |wi| eval(wo, wi, 0.35), 6) < 1e-6);
    }

    #[test]
    fn it_integrates_to_one_and_scatters_forward_for_positive_g() {
        // (At |g| = 0.999 the peak is too narrow for this rule: checked below by sampling.)
        for g in [-0.9f32, -0.5, 0.0, 0.7, 0.9] {
            // ∫ p dω = 2π ∫_{−1}^{1} p(μ) dμ by the midpoint rule (finer near μ = −1 for g ≈ 1).
            let n = 2_000_000;
            let integral: f64 = (0..n)
                .map(|i| henyey_greenstein(-1.0 + (i as f32 + 0.5) * 2.0 / n as f32, g) as f64)
                .sum::<f64>()
                * 2.0
                / n as f64
                * 2.0
                * std::f64::consts::PI;
            assert!((integral - 1.0).abs() < 0.02, "g {g}: {integral}");
        }
        // Forward: light going along +z keeps going along +z (wo = +z, wi = −z).
        assert!(eval(Vec3::Z, -Vec3::Z, 0.8) > eval(Vec3::Z, Vec3::Z, 0.8));
        let (wi, _) = sample(Vec3::Z, 0.999, Vec2::new(0.5, 0.2));
        assert!(wi.z < -0.9, "{wi}");
        let mut s = Sampler::new(5, 0, 0, 0);
        for g in [-0.999f32, 0.999] {
            for _ in 0..10_000 {
                let (wi, pdf) = sample(Vec3::Z, g, s.next_2d());
                assert!(
                    wi.is_finite() && pdf.is_finite() && pdf > 0.0,
                    "g {g}: {wi} {pdf}"
                );
                assert!((wi.length() - 1.0).abs() < 1e-3);
            }
        }
    }
}
