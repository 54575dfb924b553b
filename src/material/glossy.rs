//! The glossy reflection lobe of the lobed material (`reflection` with
//! `roughness`): a GGX microfacet lobe (Walter et al. 2007) with the
//! multiple-scattering compensation of Kulla and Conty 2017
//! ([`super::multiscatter`]), evaluated out of line so that the diffuse
//! lobe's evaluation stays small enough to inline into the integrators.

use super::{microfacet, multiscatter, Material};
use crate::geometry::orthonormal_basis;
use crate::sampling::warp::cosine_hemisphere_pdf;
use glam::Vec3;

impl Material {
    /// The glossy reflection lobe's value and its share of the mixture pdf
    /// (both cosines positive, `nf` on `wo`'s side).
    #[inline(never)]
    pub(super) fn eval_glossy(
        &self,
        wo: Vec3,
        wi: Vec3,
        nf: Vec3,
        [cos_o, cos_i]: [f32; 2],
    ) -> (Vec3, f32) {
        let (t, b) = orthonormal_basis(nf);
        let lo = Vec3::new(wo.dot(t), wo.dot(b), cos_o);
        let li = Vec3::new(wi.dot(t), wi.dot(b), cos_i);
        // Single scattering plus the multiple-scattering compensation,
        // sampled as a mix: VNDF with probability E(μo), cosine otherwise.
        let single = microfacet::reflection_brdf(lo, li, self.alpha);
        let multi = if self.multiscatter {
            multiscatter::brdf(cos_o, cos_i, self.alpha)
        } else {
            0.0
        };
        let k = self.multiscatter_fraction(cos_o);
        let pdf = self.lobe_pdf[1]
            * ((1.0 - k) * microfacet::reflection_pdf(lo, li, self.alpha)
                + k * cosine_hemisphere_pdf(cos_i));
        (self.reflection * (single + multi), pdf)
    }

    /// Probability of sampling the multiple-scattering lobe of glossy
    /// reflection for a view at cosine `cos_o`: the energy it carries, 1 − E(μo).
    pub(super) fn multiscatter_fraction(&self, cos_o: f32) -> f32 {
        if !self.multiscatter {
            return 0.0;
        }
        (1.0 - multiscatter::directional_albedo(cos_o, self.alpha)).clamp(0.0, 1.0)
    }
}
