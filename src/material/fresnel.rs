//! Exact Fresnel reflectance of a smooth dielectric interface for unpolarised
//! light (pbrt-v4 §9.5, eq. 9.4–9.6).

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

#[cfg(test)]
mod tests {
    use super::*;

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
