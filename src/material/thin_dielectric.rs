//! A thin pane of glass (a window): both faces' Fresnel reflections summed
//! over the light bouncing between them, and the rest passing straight
//! through, undeviated (the two refractions cancel). With F the single
//! interface's reflectance, the pane reflects
//!
//!   R = F + (1 − F)² F / (1 − F²) = 2F / (1 + F)
//!
//! and transmits 1 − R (pbrt-v4 §9.5.4, Mitsuba 3's `thindielectric`).
//! Both lobes are delta; a pane seen edge-on reflects everything.

use super::fresnel;

/// The pane's reflectance for light arriving at cosine `cos` (either side)
/// on a pane of index `ior`.
pub fn reflectance(cos: f32, ior: f32) -> f32 {
    let f = fresnel::dielectric(cos.abs(), ior);
    if f >= 1.0 {
        1.0
    } else {
        2.0 * f / (1.0 + f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_pane_reflects_both_faces() {
        // Normal incidence, η = 1.5: F = 0.04, R = 0.08 / 1.04.
        assert!((reflectance(1.0, 1.5) - 0.08 / 1.04).abs() < 1e-6);
        assert!((reflectance(-1.0, 1.5) - reflectance(1.0, 1.5)).abs() < 1e-7);
        assert!((reflectance(0.0, 1.5) - 1.0).abs() < 1e-6);
        // More than one face, less than twice one face.
        let f = fresnel::dielectric(0.5, 1.5);
        assert!(reflectance(0.5, 1.5) > f && reflectance(0.5, 1.5) < 2.0 * f);
    }
}
