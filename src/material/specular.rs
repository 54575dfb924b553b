//! A material's specular part as Whitted's integrator traces it: the
//! mirror, refracted and glossy branches, each handed to the integrator's
//! tracer with the factor it counts with in the pixel. Diffuse light there
//! comes from shadow rays alone (`integrator::whitted`).

use super::{fresnel, reflect, refract, thin_dielectric, BsdfSample, Kind, Material};
use crate::geometry::orthonormal_basis;
use crate::sampling::sampler::Sampler;
use glam::{Vec2, Vec3};

/// Samples taken around the mirror direction of a glossy surface.
pub const GLOSSY_SAMPLES: u32 = 4;

impl Material {
    /// The light the specular part reflects and transmits towards `wo` at a
    /// surface with shading normal `n`, seen from `outside` its geometric
    /// surface or from inside (which decides the side of the mirror and
    /// refraction normal, and the index ratio). `trace(sampler, k, wi)`
    /// is the radiance arriving along `wi` for a branch that the pixel sees
    /// through the factor `k` (the tracer may skip branches of small `k`).
    /// Branches are traced in a fixed order, each drawing its numbers from
    /// `sampler` before it is traced.
    pub fn specular_light(
        &self,
        wo: Vec3,
        n: Vec3,
        outside: bool,
        sampler: &mut Sampler,
        trace: impl Fn(&mut Sampler, f32, Vec3) -> Vec3,
    ) -> Vec3 {
        let nf = if outside { n } else { -n };
        match self.kind {
            Kind::Lobes => self.mix_light(wo, nf, outside, sampler, trace),
            Kind::Null => trace(sampler, 1.0, -wo),
            Kind::ThinDielectric => {
                let r = thin_dielectric::reflectance(wo.dot(nf), self.ior);
                let mut l = r * trace(sampler, r, reflect(wo, nf));
                l += (1.0 - r) * trace(sampler, 1.0 - r, -wo);
                l
            }
            Kind::Conductor(_) | Kind::Plastic(_) | Kind::RoughDielectric | Kind::Principled(_) => {
                // A metal, a plastic's coat or frosted glass: one branch when
                // it is a mirror, else a few importance-sampled ones.
                let mut acc = Vec3::ZERO;
                let mut count = 0;
                while count < GLOSSY_SAMPLES {
                    count += 1;
                    let u = (sampler.next_f32(), sampler.next_2d());
                    if let Some(b) = self.sample_specular(wo, n, u.0, u.1) {
                        let share = if b.delta { 1.0 } else { GLOSSY_SAMPLES as f32 };
                        acc += b.weight * trace(sampler, b.weight.max_element() / share, b.wi);
                        if b.delta {
                            break;
                        }
                    }
                }
                acc / count as f32
            }
        }
    }

    /// [`Material::specular_light`] of the paper's mix: the mirror, a few
    /// directions around it when glossy, and the smooth dielectric's
    /// Fresnel-weighted pair.
    fn mix_light(
        &self,
        wo: Vec3,
        nf: Vec3,
        outside: bool,
        sampler: &mut Sampler,
        trace: impl Fn(&mut Sampler, f32, Vec3) -> Vec3,
    ) -> Vec3 {
        let mut l = Vec3::ZERO;
        if self.reflection != Vec3::ZERO {
            if self.alpha == 0.0 {
                let wi = reflect(wo, nf);
                l += self.reflection * trace(sampler, self.reflection.max_element(), wi);
            } else {
                // Glossy: a few importance-sampled directions around the
                // mirror one, drawn from the reflection lobe alone.
                let only_gloss = self.glossy_lobe();
                let mut acc = Vec3::ZERO;
                for _ in 0..GLOSSY_SAMPLES {
                    if let Some(b) =
                        only_gloss.sample(wo, nf, sampler.next_f32(), sampler.next_2d())
                    {
                        let k = b.weight.max_element() / GLOSSY_SAMPLES as f32;
                        acc += b.weight * trace(sampler, k, b.wi);
                    }
                }
                l += acc / GLOSSY_SAMPLES as f32;
            }
        }
        if self.transmission > 0.0 {
            let eta = if outside { self.ior } else { 1.0 / self.ior };
            let f = fresnel::dielectric(wo.dot(nf), eta);
            let wr = reflect(wo, nf);
            let mut t = f * trace(sampler, self.transmission * f, wr);
            if f < 1.0 {
                if let Some(wt) = refract(wo, nf, eta) {
                    t += (1.0 - f) * trace(sampler, self.transmission * (1.0 - f), wt);
                }
            }
            l += self.transmission * t;
        }
        l
    }

    /// The mix's glossy reflection lobe alone, chosen always (its textures
    /// already evaluated: the copy leaves them behind).
    fn glossy_lobe(&self) -> Material {
        Material {
            kind: self.kind,
            smooth_lobe: self.smooth_lobe,
            multiscatter: self.multiscatter,
            diffuse: Vec3::ZERO,
            reflection: self.reflection,
            alpha: self.alpha,
            alpha_v: self.alpha_v,
            tangent: self.tangent,
            transmission: self.transmission,
            ior: self.ior,
            absorption: self.absorption,
            scattering: self.scattering,
            anisotropy: self.anisotropy,
            emission: self.emission,
            two_sided: self.two_sided,
            lobe_pdf: [0.0, 1.0, 0.0],
            textured: None,
        }
    }

    /// Samples only the specular part of a metal, a plastic's coat or
    /// rough glass (for Whitted's reflected and refracted branches; diffuse
    /// light there comes from shadow rays alone).
    pub fn sample_specular(&self, wo: Vec3, n: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        match self.kind {
            Kind::Plastic(coat) => {
                let nf = if wo.dot(n) < 0.0 { -n } else { n };
                let (t, b) = orthonormal_basis(nf);
                let lo = Vec3::new(wo.dot(t), wo.dot(b), wo.dot(nf));
                let (li, weight) = coat.sample_coat(self.reflection, lo, u)?;
                Some(BsdfSample {
                    wi: li.x * t + li.y * b + li.z * nf,
                    weight,
                    pdf: 0.0,
                    delta: coat.alpha == 0.0,
                    transmitted: false,
                })
            }
            Kind::Principled(pr) => {
                // The diffuse, sheen and clearcoat come from shadow rays.
                let nf = if pr.transmission > 0.0 || wo.dot(n) >= 0.0 {
                    n
                } else {
                    -n
                };
                let (t, b) = self.frame(nf);
                let lo = Vec3::new(wo.dot(t), wo.dot(b), wo.dot(nf));
                let (li, weight, transmitted) = pr.sample_specular(self.diffuse, lo, u_lobe, u)?;
                Some(BsdfSample {
                    wi: li.x * t + li.y * b + li.z * nf,
                    weight,
                    pdf: 0.0,
                    delta: false,
                    transmitted,
                })
            }
            _ => self.sample(wo, n, u_lobe, u),
        }
    }
}
