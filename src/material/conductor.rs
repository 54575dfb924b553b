//! Metals: reflection weighted by the Fresnel reflectance of a complex index
//! of refraction η + ik per channel, from a mirror (roughness 0) to GGX
//! microfacets (Walter et al. 2007) with visible-normal sampling and the
//! Kulla–Conty multiple-scattering compensation tinted by the metal's
//! average Fresnel (Kulla and Conty 2017, "Revisiting Physically Based
//! Shading at Imageworks", slide "Fresnel"). Mitsuba 3's `conductor` and
//! `roughconductor` leave out the compensation: rough metals here are
//! brighter by the light their microfacets bounce more than once, unless
//! `multiscatter` is off.
//!
//! Directions are local: the normal is +z, on the side of `wo`.

use super::fresnel;
use super::microfacet::{anisotropic, reflection_brdf, reflection_pdf, sample_visible_normal};
use super::multiscatter;
use super::reflect;
use crate::sampling::warp::{cosine_hemisphere, cosine_hemisphere_pdf};
use glam::{Vec2, Vec3};

/// A metal's optical constants per RGB channel, with the average of its
/// Fresnel reflectance (for the compensation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Conductor {
    /// Real part of the index of refraction.
    pub eta: Vec3,
    /// Extinction coefficient (imaginary part).
    pub k: Vec3,
    /// F_avg = 2 ∫ F(μ) μ dμ per channel.
    pub f_avg: Vec3,
}

/// Named metals: (name, η, k) per linear-sRGB channel. The spectral data of
/// Palik's *Handbook of Optical Constants of Solids* (1985) as shipped with
/// Mitsuba 3 (`data/ior/*.spd`), reduced to RGB by Mitsuba 3.9.1's
/// `scalar_rgb` variant (`mi.traverse(conductor{material=…})`), so that a
/// preset here and the same name there are the same metal.
pub const PRESETS: &[(&str, [f32; 3], [f32; 3])] = &[
    (
        "gold",
        [0.143036, 0.375307, 1.44205],
        [3.983, 2.38556, 1.60336],
    ),
    (
        "silver",
        [0.155276, 0.116728, 0.138388],
        [4.82835, 3.12222, 2.1469],
    ),
    (
        "copper",
        [0.201005, 0.92375, 1.10222],
        [3.91326, 2.45305, 2.14209],
    ),
    (
        "aluminium",
        [1.6575, 0.880405, 0.521244],
        [9.22381, 6.2695, 4.837],
    ),
    (
        "chromium",
        [4.36967, 2.91651, 1.6549],
        [5.20655, 4.23131, 3.7547],
    ),
];

/// A named metal: one row of [`PRESETS`], in its order.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Metal {
    /// Gold.
    Gold,
    /// Silver.
    Silver,
    /// Copper.
    Copper,
    /// Aluminium.
    Aluminium,
    /// Chromium.
    Chromium,
}

named_values!(Metal {
    "gold" => Gold,
    "silver" => Silver,
    "copper" => Copper,
    "aluminium" => Aluminium,
    "chromium" => Chromium,
});

impl Metal {
    /// The metal's η and k per linear-sRGB channel (its row of [`PRESETS`]).
    pub fn constants(self) -> ([f32; 3], [f32; 3]) {
        let (_, eta, k) = PRESETS[self as usize];
        (eta, k)
    }
}

impl Conductor {
    /// The metal with index `eta` + i`k`.
    pub fn new(eta: Vec3, k: Vec3) -> Conductor {
        Conductor {
            eta,
            k,
            f_avg: fresnel::average(|mu| fresnel::conductor(mu, eta, k)),
        }
    }

    /// A named metal of [`PRESETS`].
    pub fn preset(name: &str) -> Option<Conductor> {
        let &(_, eta, k) = PRESETS.iter().find(|(n, _, _)| *n == name)?;
        Some(Conductor::new(Vec3::from_array(eta), Vec3::from_array(k)))
    }

    /// Fresnel reflectance for a cosine `cos` between the light and the
    /// (micro)surface normal.
    pub fn fresnel(&self, cos: f32) -> Vec3 {
        fresnel::conductor(cos, self.eta, self.k)
    }

    /// The share of the compensation lobe that a metal reflects: the
    /// light bouncing twice or more meets the Fresnel factor each time,
    /// F_avg² E_avg / (1 − F_avg (1 − E_avg)) (Kulla and Conty 2017).
    fn multiscatter_fresnel(&self, alpha: f32) -> Vec3 {
        let e_avg = multiscatter::average_albedo(alpha);
        self.f_avg * self.f_avg * e_avg / (Vec3::ONE - self.f_avg * (1.0 - e_avg))
    }

    /// BRDF value (without the tint) and pdf of the rough metal of GGX
    /// roughness `a` (along the local x and y axes: anisotropic when they
    /// differ) for local `wo` → `wi`, with the compensation lobe when
    /// `multiscatter`; zero when either is below the surface.
    pub fn eval(&self, wo: Vec3, wi: Vec3, a: Vec2, multiscatter: bool) -> (Vec3, f32) {
        if wo.z <= 0.0 || wi.z <= 0.0 || a.x == 0.0 {
            return (Vec3::ZERO, 0.0);
        }
        let m = (wo + wi).normalize();
        let (brdf, pdf) = if a.x == a.y {
            (reflection_brdf(wo, wi, a.x), reflection_pdf(wo, wi, a.x))
        } else {
            (
                anisotropic::reflection_brdf(wo, wi, a),
                anisotropic::reflection_pdf(wo, wi, a),
            )
        };
        // The compensation of an anisotropic surface takes the isotropic
        // one of the same mean slope, √(αu αv) (an approximation: Mitsuba's
        // `roughconductor` has none; `multiscatter false` matches it).
        let alpha = if a.x == a.y { a.x } else { (a.x * a.y).sqrt() };
        let single = self.fresnel(wo.dot(m)) * brdf;
        let (multi, k) = if multiscatter {
            let f_ms = self.multiscatter_fresnel(alpha);
            (
                f_ms * multiscatter::brdf(wo.z, wi.z, alpha),
                multiscatter_fraction(wo.z, alpha),
            )
        } else {
            (Vec3::ZERO, 0.0)
        };
        let pdf = (1.0 - k) * pdf + k * cosine_hemisphere_pdf(wi.z);
        (single + multi, pdf)
    }

    /// Samples `wi` for local `wo`: the mirror direction when smooth (its
    /// weight the Fresnel reflectance, pdf 0), else a visible normal's
    /// reflection or, with probability 1 − E(μo), the compensation lobe.
    /// Returns (wi, weight f·cos/pdf without the tint, pdf).
    pub fn sample(
        &self,
        wo: Vec3,
        a: Vec2,
        multiscatter: bool,
        u_lobe: f32,
        u: Vec2,
    ) -> Option<(Vec3, Vec3, f32)> {
        if wo.z <= 0.0 {
            return None;
        }
        if a.x == 0.0 {
            return Some((Vec3::new(-wo.x, -wo.y, wo.z), self.fresnel(wo.z), 0.0));
        }
        let alpha = if a.x == a.y { a.x } else { (a.x * a.y).sqrt() };
        let wi = if multiscatter && u_lobe < multiscatter_fraction(wo.z, alpha) {
            cosine_hemisphere(u)
        } else if a.x == a.y {
            reflect(wo, sample_visible_normal(wo, a.x, u))
        } else {
            reflect(wo, anisotropic::sample_visible_normal(wo, a, u))
        };
        let (f, pdf) = self.eval(wo, wi, a, multiscatter);
        (pdf > 0.0).then(|| (wi, f * wi.z / pdf, pdf))
    }
}

/// Probability of sampling the compensation lobe for a view at `cos_o`.
pub fn multiscatter_fraction(cos_o: f32, alpha: f32) -> f32 {
    (1.0 - multiscatter::directional_albedo(cos_o, alpha)).clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_metal_is_its_row_of_the_presets() {
        assert_eq!(Metal::NAMES.len(), PRESETS.len());
        for (name, metal) in Metal::NAMES {
            let row = PRESETS.iter().find(|p| p.0 == name).unwrap();
            assert_eq!(metal.constants(), (row.1, row.2), "{name}");
        }
    }

    #[test]
    fn every_preset_is_a_metal() {
        for (name, _, _) in PRESETS {
            let c = Conductor::preset(name).unwrap();
            // Metals reflect most light at normal incidence, all at grazing.
            let f0 = c.fresnel(1.0);
            assert!(
                f0.min_element() > 0.3 && f0.max_element() < 1.0,
                "{name}: {f0}"
            );
            assert!(f0.max_element() > 0.5, "{name}: {f0}");
            assert!((c.fresnel(0.0) - Vec3::ONE).abs().max_element() < 1e-4);
            // F dips a little below F0 at middle angles before rising to
            // 1; its average stays near F0.
            assert!(
                c.f_avg.cmpge(f0 - 0.05).all(),
                "{name}: {} vs {f0}",
                c.f_avg
            );
        }
        // Gold is yellow: red reflects more than blue.
        let gold = Conductor::preset("gold").unwrap().fresnel(1.0);
        assert!(gold.x > gold.z + 0.3);
    }

    #[test]
    fn a_perfect_reflector_reflects_everything_at_any_roughness() {
        // k → ∞ makes F ≡ 1: the compensation must then restore a white
        // furnace whatever the roughness.
        let c = Conductor::new(Vec3::ONE, Vec3::splat(1e4));
        assert!((c.f_avg - Vec3::ONE).abs().max_element() < 1e-3);
        let mut s = crate::sampling::sampler::Sampler::new(1, 2, 3, 0);
        for alpha in [0.05f32, 0.3, 1.0] {
            for cos in [0.2f32, 0.7, 1.0] {
                let wo = Vec3::new((1.0 - cos * cos).sqrt(), 0.0, cos);
                let n = 40_000;
                let mut sum = 0.0f64;
                for _ in 0..n {
                    let a = Vec2::splat(alpha);
                    if let Some((_, w, _)) = c.sample(wo, a, true, s.next_f32(), s.next_2d()) {
                        sum += w.x as f64;
                    }
                }
                let albedo = sum / n as f64;
                assert!((albedo - 1.0).abs() < 0.01, "α {alpha} cos {cos}: {albedo}");
            }
        }
    }
}
