//! Exact Fresnel reflectance of smooth interfaces for unpolarised light: a
//! dielectric (pbrt-v4 §9.5, eq. 9.4–9.6) and a conductor with a complex
//! index of refraction η + ik (pbrt-v4 §9.5.3, written in real arithmetic).

use glam::Vec3;

/// Reflectance for a ray arriving with `cos_i` (> 0, on the side of the
/// normal) at an interface with relative index `eta` = n_transmitted / n_incident.
/// Returns 1 on total internal reflection.
pub fn dielectric(cos_i: f32, eta: f32) -> f32 {
    let cos_i = cos_i.clamp(0.0, 1.0);
    let sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
    if sin2_t >= 1.0 {
        return 1.0;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    let r_parl = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    let r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    0.5 * (r_parl * r_parl + r_perp * r_perp)
}

/// Reflectance of a conductor with complex index `eta` + i`k` (relative
/// to the outside) for light arriving with `cos_i`, per channel.
pub fn conductor(cos_i: f32, eta: Vec3, k: Vec3) -> Vec3 {
    Vec3::new(
        conductor_channel(cos_i, eta.x, k.x),
        conductor_channel(cos_i, eta.y, k.y),
        conductor_channel(cos_i, eta.z, k.z),
    )
}

/// One channel of [`conductor`]: the s- and p-polarised reflectances of the
/// complex Snell and Fresnel equations with a² + b² = |η̃² − sin²θ| and
/// a = Re √(η̃² − sin²θ) (Born and Wolf, *Principles of Optics*, §14.2;
/// the same closed form as Mitsuba's `fresnel_conductor`).
fn conductor_channel(cos_i: f32, eta: f32, k: f32) -> f32 {
    let cos_i = cos_i.clamp(0.0, 1.0);
    let cos2 = cos_i * cos_i;
    let sin2 = 1.0 - cos2;
    let t0 = eta * eta - k * k - sin2;
    let a2pb2 = (t0 * t0 + 4.0 * eta * eta * k * k).sqrt();
    let a = (0.5 * (a2pb2 + t0)).max(0.0).sqrt();
    let t1 = a2pb2 + cos2;
    let t2 = 2.0 * cos_i * a;
    let r_s = (t1 - t2) / (t1 + t2);
    let t3 = cos2 * a2pb2 + sin2 * sin2;
    let t4 = t2 * sin2;
    let r_p = r_s * (t3 - t4) / (t3 + t4);
    let r = 0.5 * (r_s + r_p);
    if r.is_finite() {
        r.clamp(0.0, 1.0)
    } else {
        1.0
    }
}

/// The hemispherical average 2 ∫ F(μ) μ dμ of a reflectance `f` over
/// cosines, by the midpoint rule on 256 intervals.
pub fn average(f: impl Fn(f32) -> Vec3) -> Vec3 {
    const STEPS: usize = 256;
    let mut sum = glam::DVec3::ZERO;
    for i in 0..STEPS {
        let mu = (i as f32 + 0.5) / STEPS as f32;
        sum += (f(mu) * mu).as_dvec3();
    }
    (2.0 * sum / STEPS as f64).as_vec3()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// pbrt-v4's `FrComplex` in complex arithmetic, as an independent check.
    fn complex_fresnel(cos_i: f64, eta: f64, k: f64) -> f64 {
        #[derive(Clone, Copy)]
        struct C(f64, f64);
        let mul = |a: C, b: C| C(a.0 * b.0 - a.1 * b.1, a.0 * b.1 + a.1 * b.0);
        let div = |a: C, b: C| {
            let d = b.0 * b.0 + b.1 * b.1;
            C((a.0 * b.0 + a.1 * b.1) / d, (a.1 * b.0 - a.0 * b.1) / d)
        };
        let sqrt = |a: C| {
            let r = (a.0 * a.0 + a.1 * a.1).sqrt();
            let re = (0.5 * (r + a.0)).sqrt();
            let im = (0.5 * (r - a.0)).max(0.0).sqrt().copysign(a.1);
            C(re, im)
        };
        let n = C(eta, k);
        let sin2_i = 1.0 - cos_i * cos_i;
        let sin2_t = div(C(sin2_i, 0.0), mul(n, n));
        let cos_t = sqrt(C(1.0 - sin2_t.0, -sin2_t.1));
        let ci = C(cos_i, 0.0);
        let nci = mul(n, ci);
        let nct = mul(n, cos_t);
        let r_parl = div(
            C(nci.0 - cos_t.0, nci.1 - cos_t.1),
            C(nci.0 + cos_t.0, nci.1 + cos_t.1),
        );
        let r_perp = div(C(ci.0 - nct.0, -nct.1), C(ci.0 + nct.0, nct.1));
        let norm = |c: C| c.0 * c.0 + c.1 * c.1;
        0.5 * (norm(r_parl) + norm(r_perp))
    }

    #[test]
    fn conductor_matches_complex_arithmetic() {
        for (eta, k) in [
            (0.143f32, 3.983f32),
            (1.6575, 9.2238),
            (4.37, 5.21),
            (1.5, 0.0),
        ] {
            for cos in [1.0f32, 0.8, 0.5, 0.2, 0.05] {
                let ours = conductor_channel(cos, eta, k);
                let theirs = complex_fresnel(cos as f64, eta as f64, k as f64) as f32;
                assert!(
                    (ours - theirs).abs() < 1e-4,
                    "η {eta} k {k} cos {cos}: {ours} vs {theirs}"
                );
            }
        }
    }

    #[test]
    fn conductor_without_absorption_is_a_dielectric() {
        for cos in [1.0f32, 0.6, 0.1] {
            let c = conductor(cos, Vec3::splat(1.5), Vec3::ZERO).x;
            assert!((c - dielectric(cos, 1.5)).abs() < 1e-5);
        }
        // Gold at normal incidence: ((η−1)² + k²) / ((η+1)² + k²).
        let (eta, k) = (0.143f32, 3.983f32);
        let r0 = ((eta - 1.0).powi(2) + k * k) / ((eta + 1.0).powi(2) + k * k);
        assert!((conductor_channel(1.0, eta, k) - r0).abs() < 1e-5);
        // Grazing light is reflected whole.
        assert!((conductor_channel(0.0, eta, k) - 1.0).abs() < 1e-5);
    }

    #[test]
    fn normal_incidence_matches_schlick_r0() {
        let r0 = ((1.5f32 - 1.0) / (1.5 + 1.0)).powi(2);
        assert!((dielectric(1.0, 1.5) - r0).abs() < 1e-6);
        assert!((dielectric(1.0, 1.0 / 1.5) - r0).abs() < 1e-6);
    }

    #[test]
    fn total_internal_reflection_past_the_critical_angle() {
        let crit = (1.0f32 / 1.5).asin();
        assert_eq!(dielectric((crit + 0.01).cos(), 1.0 / 1.5), 1.0);
        assert!(dielectric((crit - 0.05).cos(), 1.0 / 1.5) < 1.0);
        assert!((dielectric(0.0, 1.5) - 1.0).abs() < 1e-6);
    }
}
