//! What fills an object's inside (or the scene's air): a homogeneous
//! participating medium of absorption and scattering coefficients per RGB
//! channel and a Henyey–Greenstein phase function. Absorption alone is the
//! seed paper's coloured glass (Beer's law).
//!
//! Distance sampling draws a distance from one channel's extinction (the
//! path's "hero" channel) and reports every channel's density of the same
//! event, so that the integrator can weigh the three channels' sampling
//! strategies over the whole path by the balance heuristic (spectral MIS:
//! pbrt-v4 §14.2.2, its `r_u` rescaled path probabilities; Wilkie et al.
//! 2014, "Hero wavelength spectral sampling"). Chromatic media stay
//! unbiased, and a path's weight stays bounded where one channel's
//! extinction is far from another's.

use glam::Vec3;

/// A homogeneous medium.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Medium {
    /// Absorption coefficient σa per unit length, per channel.
    pub absorption: Vec3,
    /// Scattering coefficient σs per unit length, per channel.
    pub scattering: Vec3,
    /// The Henyey–Greenstein asymmetry g in (−1, 1): > 0 forward.
    pub anisotropy: f32,
}

/// Where a distance sample along a segment landed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DistanceSample {
    /// Distance from the segment's start (the segment's length when it
    /// passed through).
    pub t: f32,
    /// Whether light scattered inside the medium at `t` (else it reached
    /// the segment's end).
    pub scattered: bool,
    /// What the event contributes per channel: σs·Tr(t) at a scattering
    /// point, Tr(length) at the end.
    pub value: Vec3,
    /// The density of the event had each channel been the hero: σt·Tr(t)
    /// at a scattering point, Tr(length) at the end.
    pub pdf: Vec3,
}

impl Medium {
    /// The extinction coefficient σt = σa + σs.
    #[inline]
    pub fn extinction(&self) -> Vec3 {
        self.absorption + self.scattering
    }

    /// Whether light scatters in it (else it only absorbs).
    #[inline]
    pub fn scatters(&self) -> bool {
        self.scattering.max_element() > 0.0
    }

    /// The fraction of light that survives `distance` inside (Beer–Lambert:
    /// T = exp(−σt d)); channels without extinction keep all of it, also
    /// over an infinite distance.
    #[inline]
    pub fn transmittance(&self, distance: f32) -> Vec3 {
        let s = self.extinction();
        let tr = |s: f32| if s > 0.0 { (-s * distance).exp() } else { 1.0 };
        Vec3::new(tr(s.x), tr(s.y), tr(s.z))
    }

    /// Samples where light travelling a segment of length `length` (may be
    /// infinite) scatters, from the extinction of channel `hero`, with `u`.
    /// The caller divides by the hero's density, or (spectral MIS) by the
    /// channels' average: see `integrator::volpath`.
    pub fn sample_distance(&self, length: f32, hero: usize, u: f32) -> DistanceSample {
        let sigma_t = self.extinction();
        let s = sigma_t[hero.min(2)];
        let t = if s > 0.0 {
            -(1.0 - u).ln() / s
        } else {
            f32::INFINITY
        };
        if t < length {
            let tr = self.transmittance(t);
            return DistanceSample {
                t,
                scattered: true,
                value: self.scattering * tr,
                pdf: sigma_t * tr,
            };
        }
        let tr = self.transmittance(length);
        DistanceSample {
            t: length,
            scattered: false,
            value: tr,
            pdf: tr,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::sampler::Sampler;

    fn fog(sa: Vec3, ss: Vec3) -> Medium {
        Medium {
            absorption: sa,
            scattering: ss,
            anisotropy: 0.0,
        }
    }

    /// The estimator's expected weights: E[weight · 1(passed)] = Tr(L),
    /// and E[weight · 1(scattered) · f(t)] = ∫ σs Tr(t) f(t) dt.
    #[test]
    fn distance_sampling_is_unbiased_per_channel() {
        let m = fog(Vec3::new(0.1, 0.5, 0.0), Vec3::new(0.9, 0.2, 0.05));
        let length = 2.0;
        let mut s = Sampler::new(7, 0, 0, 0);
        let (mut passed, mut scattered, mut scattered_t) = (Vec3::ZERO, Vec3::ZERO, Vec3::ZERO);
        let n = 400_000;
        for _ in 0..n {
            let hero = ((s.next_f32() * 3.0) as usize).min(2);
            let d = m.sample_distance(length, hero, s.next_f32());
            // The one-sample balance heuristic over the hero channels.
            let weight = d.value / (d.pdf.element_sum() / 3.0);
            if d.scattered {
                scattered += weight;
                scattered_t += weight * d.t;
            } else {
                passed += weight;
            }
        }
        let n = n as f32;
        let want_pass = m.transmittance(length);
        let st = m.extinction();
        // ∫0^L σs e^{−σt t} dt and ∫0^L σs t e^{−σt t} dt in closed form.
        let want_scatter = m.scattering / st * (Vec3::ONE - want_pass);
        let want_scatter_t =
            m.scattering * (Vec3::ONE - want_pass * (Vec3::ONE + st * length)) / (st * st);
        for (got, want) in [
            (passed / n, want_pass),
            (scattered / n, want_scatter),
            (scattered_t / n, want_scatter_t),
        ] {
            assert!(
                (got - want).abs().max_element() < 0.01 * want.max_element().max(0.1),
                "{got} vs {want}"
            );
        }
    }

    #[test]
    fn infinite_segments_and_clear_channels_stay_finite() {
        let m = fog(Vec3::ZERO, Vec3::new(0.5, 0.0, 0.0));
        for hero in 0..3 {
            for u in [0.0, 0.3, 0.5, 0.9, 0.999_999] {
                let d = m.sample_distance(f32::INFINITY, hero, u);
                let ok = d.value.is_finite() && d.pdf.is_finite();
                assert!(ok && d.t.is_finite() == d.scattered, "{d:?}");
                assert!(!d.scattered || d.pdf[hero] > 0.0, "{d:?}");
            }
        }
        assert_eq!(m.transmittance(f32::INFINITY), Vec3::new(0.0, 1.0, 1.0));
        let dense = fog(Vec3::splat(1e6), Vec3::splat(1e6));
        let d = dense.sample_distance(1.0, 1, 0.5);
        assert!(d.scattered && d.value.is_finite() && d.t < 1e-5);
        let d = dense.sample_distance(1.0, 1, 1.0 - 1e-7);
        assert!(d.value.is_finite() && d.pdf.is_finite(), "{d:?}");
    }
}
