//! Materials: the paper's weighted mix of lobes — Lambertian diffuse,
//! specular (mirror or GGX glossy) reflection, smooth dielectric — made
//! physically correct, and the models of today's renderers, one file each:
//! metals (`conductor`), coated diffuse (`plastic`), frosted glass
//! (`rough_dielectric`) and window panes (`thin_dielectric`). In the mix a
//! path picks one lobe with probability proportional to its weight; weights
//! above 1 in sum are scaled down, so the mix never creates energy.

pub mod conductor;
pub mod fresnel;
mod glossy;
pub mod medium;
pub mod microfacet;
pub mod multiscatter;
mod multiscatter_table;
pub mod phase;
pub mod plastic;
pub mod principled;
pub mod rough_dielectric;
mod specular;
pub mod thin_dielectric;

#[cfg(test)]
mod chi2;

use crate::geometry::orthonormal_basis;
use crate::sampling::warp::{cosine_hemisphere, cosine_hemisphere_pdf};
use conductor::Conductor;
use glam::{Vec2, Vec3};
use plastic::Plastic;
use principled::Principled;
use std::f32::consts::FRAC_1_PI;

/// How a material scatters light.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Kind {
    /// The paper's weighted mix of diffuse, reflection and transmission
    /// lobes (a smooth glass is a mix of transmission alone).
    Lobes,
    /// A metal: `reflection` tints it, `alpha` roughens it.
    Conductor(Conductor),
    /// `diffuse` under a dielectric coat tinted by `reflection`.
    Plastic(Plastic),
    /// Glass of index `ior` roughened by `alpha` (> 0).
    RoughDielectric,
    /// A thin pane of index `ior`.
    ThinDielectric,
    /// Burley's principled model as Mitsuba 3 writes it: `diffuse` is its
    /// base colour, `gloss` its roughness, `transmission` its refracting
    /// share and `ior` its index (the rest lives here).
    Principled(Principled),
    /// No surface at all (`type none`): light passes straight through; the
    /// boundary of a medium (fog in a box, an atmosphere's edge).
    Null,
}

/// A resolved material.
#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    /// Its scattering model.
    pub kind: Kind,
    /// Whether it has a non-delta lobe, worth sampling lights for
    /// ([`Material::has_smooth_lobe`]; kept, not derived, because the
    /// integrators ask at every bounce: deriving it cost 0.36 % of
    /// cornell's instructions).
    pub(crate) smooth_lobe: bool,
    /// Whether glossy reflection (of the mix or a metal) gets the
    /// Kulla–Conty multiple-scattering compensation (off: single
    /// scattering, as Mitsuba's and pbrt's).
    pub multiscatter: bool,
    /// Lambertian albedo (after weight normalisation).
    pub diffuse: Vec3,
    /// Specular reflectance (after weight normalisation).
    pub reflection: Vec3,
    /// GGX roughness (along the tangent, for a metal rough unevenly);
    /// 0 = perfect mirror.
    pub alpha: f32,
    /// A metal's GGX roughness along the bitangent (`alpha` when even).
    pub alpha_v: f32,
    /// The hit's tangent (∂p/∂u) for a metal rough unevenly (zero
    /// otherwise: its frame is any about the normal).
    pub tangent: Vec3,
    /// Weight of the dielectric lobe (after weight normalisation).
    pub transmission: f32,
    /// Index of refraction inside.
    pub ior: f32,
    /// Absorption coefficient of the medium inside (Beer's law).
    pub absorption: Vec3,
    /// Scattering coefficient of the medium inside.
    pub scattering: Vec3,
    /// The medium's Henyey–Greenstein asymmetry g.
    pub anisotropy: f32,
    /// Emitted radiance.
    pub emission: Vec3,
    /// Emission from both sides.
    pub two_sided: bool,
    /// Probabilities of choosing the diffuse, reflection and transmission lobes.
    pub lobe_pdf: [f32; 3],
    /// The colours that come from textures, evaluated at each hit (`None`:
    /// a constant material, used as it is).
    pub textured: Option<Box<Textured>>,
}

/// The textured parameters of a material: indices into the scene's
/// textures, with the material's parameters to complete at each hit.
#[derive(Debug, Clone, PartialEq)]
pub struct Textured {
    /// The parameters (the textured ones are replaced at each hit).
    pub params: Params,
    /// Which parameters textures give, and the texture of each.
    pub inputs: Vec<(Input, u32)>,
    /// How a texture bends the shading normal, if one does.
    pub normal: Option<NormalInput>,
    /// A plastic's coats when a texture gives its gloss (each hit's coat
    /// is blended from them).
    pub coats: Option<std::sync::Arc<plastic::CoatFamily>>,
    /// Whether each hit's tangent is needed (a metal rough unevenly).
    pub tangent: bool,
    /// Whether the diffuse colour is multiplied by the mesh's vertex
    /// colours at the hit.
    pub vertex_color: bool,
}

/// A material parameter a texture can give.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Input {
    /// The Lambertian albedo (a colour).
    Diffuse,
    /// The specular reflectance (a colour).
    Reflection,
    /// The roughness (the texture's luminance, within [0, 1]).
    Gloss,
    /// The dielectric lobe's weight (likewise).
    Transmission,
    /// The absorption coefficient inside (a colour, read where a path
    /// leaves the object).
    Absorption,
    /// The emitted radiance (a colour; light sampling reads it at the
    /// sampled point).
    Emission,
    /// A principled material's metallic share (the texture's luminance,
    /// within [0, 1]).
    Metallic,
}

/// A texture that bends the shading normal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NormalInput {
    /// A tangent-space normal map (see `texture::shading_normal`).
    Map {
        /// The texture.
        texture: u32,
        /// Its tangent and bitangent components' scale.
        scale: f32,
    },
    /// A bump map: the texture's luminance times `height` displaces the
    /// surface along its normal.
    Bump {
        /// The texture.
        texture: u32,
        /// World units of displacement per unit of the texture.
        height: f32,
    },
}

/// A material's parameters as written in a scene (`material { … }`), in
/// the renderer's f32.
#[derive(Debug, Clone, PartialEq)]
pub struct Params {
    /// Lambertian albedo.
    pub diffuse: Vec3,
    /// Specular (mirror or glossy) reflectance.
    pub reflection: Vec3,
    /// Roughness of the reflection lobe, 0 = mirror.
    pub gloss: f32,
    /// Weight of the smooth dielectric lobe.
    pub transmission: f32,
    /// Index of refraction inside.
    pub ior: f32,
    /// Absorption coefficient of the medium inside.
    pub absorption: Vec3,
    /// Scattering coefficient of the medium inside.
    pub scattering: Vec3,
    /// The medium's Henyey–Greenstein asymmetry g.
    pub anisotropy: f32,
    /// Emitted radiance.
    pub emission: Vec3,
    /// Emission from both sides.
    pub two_sided: bool,
    /// The scattering model.
    pub kind: Kind,
    /// Whether glossy reflection gets the multiple-scattering compensation.
    pub multiscatter: bool,
    /// A metal's GGX roughness along the tangent and the bitangent, when
    /// given as such (`gloss` is then unused).
    pub roughness: Option<Vec2>,
}

impl Default for Params {
    /// Black, no lobes, the IOR of glass.
    fn default() -> Params {
        Params {
            kind: Kind::Lobes,
            multiscatter: true,
            diffuse: Vec3::ZERO,
            reflection: Vec3::ZERO,
            gloss: 0.0,
            transmission: 0.0,
            ior: 1.5,
            absorption: Vec3::ZERO,
            scattering: Vec3::ZERO,
            anisotropy: 0.0,
            emission: Vec3::ZERO,
            two_sided: false,
            roughness: None,
        }
    }
}

/// A direction sampled from a material.
#[derive(Debug, Clone, Copy)]
pub struct BsdfSample {
    /// Incident direction (world, away from the surface).
    pub wi: Vec3,
    /// f·|cos θi| / pdf.
    pub weight: Vec3,
    /// Pdf in solid angle (of the non-delta mixture; 0 for delta lobes).
    pub pdf: f32,
    /// Whether the sample came from a delta (mirror, dielectric) lobe.
    pub delta: bool,
    /// Whether the direction crosses the surface (refraction).
    pub transmitted: bool,
}

fn max3(v: Vec3) -> f32 {
    v.max_element()
}

/// Mirror `w` about `n`.
pub fn reflect(w: Vec3, n: Vec3) -> Vec3 {
    2.0 * w.dot(n) * n - w
}

/// Refracts `w` (pointing away from the surface, on the side of `n`) with
/// relative index `eta` = n_t / n_i; `None` on total internal reflection.
pub fn refract(w: Vec3, n: Vec3, eta: f32) -> Option<Vec3> {
    let cos_i = w.dot(n);
    let sin2_t = (1.0 - cos_i * cos_i).max(0.0) / (eta * eta);
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some(-w / eta + (cos_i / eta - cos_t) * n)
}

impl Material {
    /// Builds a material from its parameters: the lobe weights are
    /// normalised when they sum above 1 and become the lobe probabilities.
    pub fn new(p: &Params) -> Material {
        let (mut diffuse, mut reflection, mut transmission) =
            (p.diffuse, p.reflection, p.transmission);
        // Rough glass stays rough where a texture's gloss reaches 0 (its
        // smooth case is the mix's transmission lobe).
        let alpha = if p.gloss > 0.0 || p.kind == Kind::RoughDielectric {
            microfacet::gloss_to_alpha(p.gloss)
        } else {
            0.0
        };
        // A metal's roughness given as α along u and v (both 0: a mirror;
        // one alone 0 is floored as `gloss_to_alpha` floors).
        let (alpha, alpha_v) = match p.roughness {
            Some(r) if r.max_element() > 0.0 => (r.x.max(1e-3), r.y.max(1e-3)),
            Some(_) => (0.0, 0.0),
            None => (alpha, alpha),
        };
        let kind = match p.kind {
            Kind::Principled(mut pr) => {
                pr.roughness = p.gloss;
                pr.transmission = p.transmission;
                // An index of 1 bends nothing and its rough refraction has
                // no half vector (Mitsuba likewise moves it to 1.001).
                pr.eta = if p.ior == 1.0 && p.transmission > 0.0 {
                    1.001
                } else {
                    p.ior
                };
                Kind::Principled(pr)
            }
            kind => kind,
        };
        let lobe_pdf = match kind {
            Kind::Principled(pr) => {
                reflection = Vec3::ZERO;
                // What refracts meets Beer's law inside.
                transmission *= 1.0 - pr.metallic;
                [
                    (1.0 - pr.metallic) * (1.0 - pr.transmission),
                    1.0,
                    transmission,
                ]
            }
            Kind::Lobes => {
                let w = [max3(diffuse), max3(reflection), transmission];
                let sum: f32 = w.iter().sum();
                if sum > 1.0 {
                    diffuse /= sum;
                    reflection /= sum;
                    transmission /= sum;
                }
                if sum > 0.0 {
                    [w[0] / sum, w[1] / sum, w[2] / sum]
                } else {
                    [0.0; 3]
                }
            }
            // The other models choose among their parts themselves; the
            // mix's probabilities only say which parts exist (the
            // integrators' ambient term reads the diffuse one).
            Kind::Conductor(_) => {
                diffuse = Vec3::ZERO;
                transmission = 0.0;
                [0.0, 1.0, 0.0]
            }
            Kind::Plastic(_) => {
                transmission = 0.0;
                [1.0, 0.0, 0.0]
            }
            Kind::RoughDielectric | Kind::ThinDielectric => {
                diffuse = Vec3::ZERO;
                reflection = Vec3::ZERO;
                // Beer's law applies inside rough glass, not in a pane.
                transmission = if p.kind == Kind::RoughDielectric {
                    1.0
                } else {
                    0.0
                };
                [0.0, 0.0, 1.0]
            }
            // Nothing to choose: the integrators pass through it.
            Kind::Null => {
                diffuse = Vec3::ZERO;
                reflection = Vec3::ZERO;
                transmission = 0.0;
                [0.0; 3]
            }
        };
        let smooth_lobe = match p.kind {
            Kind::Lobes | Kind::Conductor(_) => {
                lobe_pdf[0] > 0.0 || (lobe_pdf[1] > 0.0 && alpha > 0.0)
            }
            Kind::Plastic(_) | Kind::RoughDielectric | Kind::Principled(_) => true,
            Kind::ThinDielectric | Kind::Null => false,
        };
        Material {
            kind,
            smooth_lobe,
            multiscatter: p.multiscatter,
            diffuse,
            reflection,
            alpha,
            alpha_v,
            tangent: Vec3::ZERO,
            transmission,
            ior: p.ior,
            absorption: p.absorption,
            scattering: p.scattering,
            anisotropy: p.anisotropy,
            emission: p.emission,
            two_sided: p.two_sided,
            lobe_pdf,
            textured: None,
        }
    }

    /// Whether the material reflects or transmits anything.
    pub fn scatters(&self) -> bool {
        self.lobe_pdf.iter().any(|&p| p > 0.0)
    }

    /// Whether it has a non-delta lobe (worth sampling lights for).
    #[inline]
    pub fn has_smooth_lobe(&self) -> bool {
        self.smooth_lobe
    }

    /// The reflectance the ambient term lights (biased, `render { ambient
    /// }`): the diffuse lobe's albedo, if the material has one.
    #[inline]
    pub fn ambient_albedo(&self) -> Option<Vec3> {
        (self.lobe_pdf[0] > 0.0).then_some(self.diffuse)
    }

    /// The medium inside, if light passing through the surface meets one
    /// (inside transmissive materials and null boundaries that absorb or
    /// scatter).
    #[inline]
    pub fn interior(&self) -> Option<medium::Medium> {
        (self.has_inside() && (self.absorption != Vec3::ZERO || self.scattering != Vec3::ZERO))
            .then_some(medium::Medium {
                absorption: self.absorption,
                scattering: self.scattering,
                anisotropy: self.anisotropy,
            })
    }

    /// Whether light can travel inside the object (it refracts into it, or
    /// the surface is a null boundary): its inside is then a medium or
    /// empty space, not the space around it.
    #[inline]
    pub fn has_inside(&self) -> bool {
        self.transmission > 0.0 || self.is_null()
    }

    /// Whether the surface is a null boundary (`type none`).
    #[inline]
    pub fn is_null(&self) -> bool {
        matches!(self.kind, Kind::Null)
    }

    /// Emitted radiance towards `wo` from a surface with geometric normal `n`.
    pub fn emitted(&self, wo: Vec3, n: Vec3) -> Vec3 {
        if self.two_sided || wo.dot(n) > 0.0 {
            self.emission
        } else {
            Vec3::ZERO
        }
    }

    /// Value (f) and mixture pdf of the non-delta lobes for `wo` → `wi` at a
    /// surface with normal `n` (either orientation).
    // Inlined, its glossy lobe out of line: called out of line, a diffuse
    // surface's evaluation (twice a bounce: light sample and BSDF sample)
    // spent more on the call than on its few products.
    #[inline(always)]
    pub fn eval(&self, wo: Vec3, wi: Vec3, n: Vec3) -> (Vec3, f32) {
        if !matches!(self.kind, Kind::Lobes) {
            return self.eval_model(wo, wi, n);
        }
        let nf = if wo.dot(n) < 0.0 { -n } else { n };
        let cos_i = wi.dot(nf);
        let cos_o = wo.dot(nf);
        if cos_i <= 0.0 || cos_o <= 0.0 {
            return (Vec3::ZERO, 0.0);
        }
        let mut f = Vec3::ZERO;
        let mut pdf = 0.0;
        if self.lobe_pdf[0] > 0.0 {
            f += self.diffuse * FRAC_1_PI;
            pdf += self.lobe_pdf[0] * cosine_hemisphere_pdf(cos_i);
        }
        if self.lobe_pdf[1] > 0.0 && self.alpha > 0.0 {
            let (glossy, glossy_pdf) = self.eval_glossy(wo, wi, nf, [cos_o, cos_i]);
            f += glossy;
            pdf += glossy_pdf;
        }
        (f, pdf)
    }

    /// Samples an incident direction for `wo` at a surface whose outward
    /// geometric normal is `n`.
    #[inline(always)]
    pub fn sample(&self, wo: Vec3, n: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        if !matches!(self.kind, Kind::Lobes) {
            return self.sample_model(wo, n, u_lobe, u);
        }
        let outside = wo.dot(n) >= 0.0;
        let nf = if outside { n } else { -n };
        let [pd, pr, _] = self.lobe_pdf;
        if u_lobe < pd + pr {
            // Diffuse or specular reflection.
            let wi = if u_lobe < pd {
                let (t, b) = orthonormal_basis(nf);
                let l = cosine_hemisphere(u);
                l.x * t + l.y * b + l.z * nf
            } else if self.alpha == 0.0 {
                let wi = reflect(wo, nf);
                return Some(BsdfSample {
                    wi,
                    weight: self.reflection / pr,
                    pdf: 0.0,
                    delta: true,
                    transmitted: false,
                });
            } else {
                let (t, b) = orthonormal_basis(nf);
                let lo = Vec3::new(wo.dot(t), wo.dot(b), wo.dot(nf));
                // The rest of u_lobe within the reflection lobe picks between
                // the compensation lobe and the single-scattering one.
                let u_ms = (u_lobe - pd) / pr;
                let li = if u_ms < self.multiscatter_fraction(lo.z) {
                    cosine_hemisphere(u)
                } else {
                    reflect(lo, microfacet::sample_visible_normal(lo, self.alpha, u))
                };
                if li.z <= 0.0 {
                    return None;
                }
                li.x * t + li.y * b + li.z * nf
            };
            let (f, pdf) = self.eval(wo, wi, n);
            if pdf <= 0.0 {
                return None;
            }
            let cos = wi.dot(nf).abs();
            return Some(BsdfSample {
                wi,
                weight: f * cos / pdf,
                pdf,
                delta: false,
                transmitted: false,
            });
        }
        // Smooth dielectric: reflect with probability F, refract otherwise;
        // F cancels against its own probability.
        let pt = self.lobe_pdf[2];
        if pt <= 0.0 {
            return None;
        }
        let eta = if outside { self.ior } else { 1.0 / self.ior };
        let cos_o = wo.dot(nf);
        let f = fresnel::dielectric(cos_o, eta);
        let u_f = (u_lobe - pd - pr) / pt;
        let weight = Vec3::splat(self.transmission / pt);
        if u_f < f {
            Some(BsdfSample {
                wi: reflect(wo, nf),
                weight,
                pdf: 0.0,
                delta: true,
                transmitted: false,
            })
        } else {
            let wi = refract(wo, nf, eta)?;
            Some(BsdfSample {
                wi,
                weight,
                pdf: 0.0,
                delta: true,
                transmitted: true,
            })
        }
    }

    /// The albedo shown by the debug integrator.
    pub fn albedo(&self) -> Vec3 {
        match self.kind {
            Kind::Lobes => self.diffuse + self.reflection + Vec3::splat(self.transmission),
            Kind::Conductor(c) => self.reflection * c.fresnel(1.0),
            Kind::Plastic(_) | Kind::Principled(_) => self.diffuse,
            Kind::RoughDielectric | Kind::ThinDielectric => Vec3::ONE,
            Kind::Null => Vec3::ZERO,
        }
    }

    /// The tangent and bitangent of the local frame about the normal `nf`:
    /// along the hit's ∂p/∂u (made perpendicular to `nf`) for a metal rough
    /// unevenly, any pair otherwise.
    #[inline]
    fn frame(&self, nf: Vec3) -> (Vec3, Vec3) {
        if self.tangent != Vec3::ZERO {
            let t = (self.tangent - nf * nf.dot(self.tangent)).normalize_or_zero();
            if t != Vec3::ZERO {
                return (t, nf.cross(t));
            }
        }
        orthonormal_basis(nf)
    }

    /// [`Material::eval`] for the models other than the mix, in the local
    /// frame of the normal (turned towards `wo` for the opaque ones).
    #[inline(never)]
    fn eval_model(&self, wo: Vec3, wi: Vec3, n: Vec3) -> (Vec3, f32) {
        let nf = match self.kind {
            Kind::RoughDielectric => n,
            Kind::Principled(pr) if pr.transmission > 0.0 => n,
            _ if wo.dot(n) < 0.0 => -n,
            _ => n,
        };
        let (t, b) = self.frame(nf);
        let local = |w: Vec3| Vec3::new(w.dot(t), w.dot(b), w.dot(nf));
        let (lo, li) = (local(wo), local(wi));
        match self.kind {
            Kind::Conductor(c) => {
                let a = Vec2::new(self.alpha, self.alpha_v);
                let (f, pdf) = c.eval(lo, li, a, self.multiscatter);
                (self.reflection * f, pdf)
            }
            Kind::Plastic(coat) => coat.eval(self.diffuse, self.reflection, lo, li),
            Kind::RoughDielectric => {
                let (f, pdf) = rough_dielectric::eval(lo, li, self.ior, self.alpha);
                (Vec3::splat(f), pdf)
            }
            Kind::Principled(pr) => pr.eval(self.diffuse, lo, li),
            Kind::ThinDielectric | Kind::Lobes | Kind::Null => (Vec3::ZERO, 0.0),
        }
    }

    /// [`Material::sample`] for the models other than the mix.
    #[inline(never)]
    fn sample_model(&self, wo: Vec3, n: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        let nf = match self.kind {
            Kind::RoughDielectric | Kind::ThinDielectric => n,
            // Glass-like when it refracts (its two sides differ), else
            // two-sided as the other opaque models.
            Kind::Principled(pr) if pr.transmission > 0.0 => n,
            _ if wo.dot(n) < 0.0 => -n,
            _ => n,
        };
        let (t, b) = self.frame(nf);
        let lo = Vec3::new(wo.dot(t), wo.dot(b), wo.dot(nf));
        let world = |l: Vec3| l.x * t + l.y * b + l.z * nf;
        let smooth = |wi: Vec3, weight: Vec3, pdf: f32, transmitted: bool| BsdfSample {
            wi,
            weight,
            pdf,
            delta: false,
            transmitted,
        };
        let delta = |wi: Vec3, weight: Vec3, transmitted: bool| BsdfSample {
            wi,
            weight,
            pdf: 0.0,
            delta: true,
            transmitted,
        };
        match self.kind {
            Kind::Conductor(c) => {
                let a = Vec2::new(self.alpha, self.alpha_v);
                let (li, w, pdf) = c.sample(lo, a, self.multiscatter, u_lobe, u)?;
                let w = self.reflection * w;
                Some(if pdf == 0.0 {
                    delta(world(li), w, false)
                } else {
                    smooth(world(li), w, pdf, false)
                })
            }
            Kind::Plastic(coat) => {
                let (li, w, pdf, mirror) =
                    coat.sample(self.diffuse, self.reflection, lo, u_lobe, u)?;
                Some(if mirror {
                    delta(world(li), w, false)
                } else {
                    smooth(world(li), w, pdf, false)
                })
            }
            Kind::RoughDielectric => {
                let (li, w, pdf) = rough_dielectric::sample(lo, self.ior, self.alpha, u_lobe, u)?;
                Some(smooth(world(li), Vec3::splat(w), pdf, li.z * lo.z < 0.0))
            }
            Kind::Principled(pr) => {
                let (li, w, pdf) = pr.sample(self.diffuse, lo, u_lobe, u)?;
                Some(smooth(world(li), w, pdf, li.z * lo.z < 0.0))
            }
            Kind::ThinDielectric => {
                if u_lobe < thin_dielectric::reflectance(lo.z, self.ior) {
                    Some(delta(
                        world(Vec3::new(-lo.x, -lo.y, lo.z)),
                        Vec3::ONE,
                        false,
                    ))
                } else {
                    Some(delta(-wo, Vec3::ONE, true))
                }
            }
            Kind::Null => Some(delta(-wo, Vec3::ONE, true)),
            Kind::Lobes => None,
        }
    }
}

#[cfg(test)]
mod tests;
