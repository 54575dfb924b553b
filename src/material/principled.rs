//! The principled material: Burley's "Physically Based Shading at Disney"
//! (2012) extended to a BSDF ("Extending the Disney BRDF to a BSDF with
//! Integrated Subsurface Scattering", 2015), term by term as Mitsuba 3's
//! `principled` plugin writes it (`src/bsdfs/principled.cpp` and
//! `principledhelpers.h`), so that the two renderers can be compared value
//! for value. Its lobes, weighted by `metallic` and `transmission`:
//!
//! - diffuse with Burley's retro-reflection: (1 − metallic)(1 − transmission)
//!   · base/π · ((1 − F_i/2)(1 − F_o/2) + R_r (F_o + F_i + F_o F_i (R_r − 1))),
//!   F_x = (1 − |cos θ_x|)⁵, R_r = 2 roughness cos²θ_d;
//! - sheen: sheen (1 − metallic) (1 − |cos θ_d|)⁵, tinted towards the base
//!   colour by `sheen_tint`;
//! - the main specular lobe, GGX with α = roughness² (stretched by
//!   `anisotropic`, aspect √(1 − 0.9 anisotropic)) and separable Smith
//!   shadowing, reflecting with a Fresnel factor that blends the dielectric's
//!   exact one, a tinted Schlick one (`specular_tint`) and the metal's
//!   Schlick one with the base colour as F0 (`metallic`); and refracting
//!   (`transmission`) with √base as its tint;
//! - clearcoat: a quarter of `clearcoat` times a GTR1 lobe (α from 0.1 to
//!   0.001 as the coat gets glossier) with Schlick F0 = 0.04.
//!
//! Like Burley's model and Mitsuba's plugin (and unlike ptsc's `plastic`,
//! whose coat takes from its base what it reflects), the diffuse and
//! specular lobes are added, not layered: a white base reflects up to 4 %
//! more than it receives seen head-on and up to 40 % at grazing angles
//! (measured: `chi2.rs`, `principled_albedo_is_mitsubas`). The metal and
//! the glass alone keep energy (white furnace, same test). Refraction
//! carries radiance scaled by (η_i/η_t)², as Mitsuba's plugin in radiance
//! mode (ptsc's `rough_dielectric` leaves that factor out; in a closed
//! object the factors of entering and leaving cancel either way).
//!
//! Sampling (as Mitsuba's): a lobe with probability in proportion to
//! (1 − metallic)(1 − transmission) for the diffuse, clearcoat/4 for the
//! coat and 1 for the specular lobes, among which a visible GGX normal
//! reflects or refracts by its Fresnel factor; below the surface only the
//! specular lobes are met. Directions are local: the normal is +z; `wo` looks
//! at the viewer and `wi` at the light, either may be below.

use super::fresnel;
use super::microfacet::anisotropic;
use super::reflect;
use crate::sampling::warp::cosine_hemisphere;
use glam::{Vec2, Vec3};
use std::f32::consts::{FRAC_1_PI, PI};

/// The principled material's parameters other than its base colour (the
/// material's `diffuse`), each in [0, 1] except `eta`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Principled {
    /// How much of a metal it is.
    pub metallic: f32,
    /// The weight of the refracting lobe (of the non-metallic part).
    pub transmission: f32,
    /// Relative index of refraction inside (the `specular` parameter maps
    /// to it: η = 2 / (1 − √(0.08 specular)) − 1).
    pub eta: f32,
    /// Perceptual roughness: GGX α = roughness² (at least 0.001).
    pub roughness: f32,
    /// Stretch of the specular lobe along the tangent.
    pub anisotropic: f32,
    /// How much of the dielectric reflection takes the base colour's hue.
    pub specular_tint: f32,
    /// The sheen lobe's weight.
    pub sheen: f32,
    /// How much of the sheen takes the base colour's hue.
    pub sheen_tint: f32,
    /// The clearcoat lobe's weight.
    pub clearcoat: f32,
    /// The clearcoat's GTR1 α (0.1 rough to 0.001 glossy).
    pub clearcoat_alpha: f32,
}

impl Default for Principled {
    /// Mitsuba's defaults: a dielectric of `specular` 0.5 (η 1.5), roughness
    /// 0.5, no other lobe.
    fn default() -> Principled {
        Principled {
            metallic: 0.0,
            transmission: 0.0,
            eta: Principled::eta_of_specular(0.5),
            roughness: 0.5,
            anisotropic: 0.0,
            specular_tint: 0.0,
            sheen: 0.0,
            sheen_tint: 0.0,
            clearcoat: 0.0,
            clearcoat_alpha: Principled::clearcoat_alpha(0.0),
        }
    }
}

/// Schlick's weight (1 − cos)⁵, the cosine clamped to [0, 1].
fn schlick_weight(cos: f32) -> f32 {
    let m = (1.0 - cos).clamp(0.0, 1.0);
    let m2 = m * m;
    m2 * m2 * m
}

/// Schlick's Fresnel approximation with reflectance `r0` head-on, for a
/// cosine `cos` with the microsurface (negative: from inside) of an
/// interface of index `eta`: past the critical angle, its transmitted
/// cosine is used (Mitsuba's `calc_schlick`).
fn schlick(r0: Vec3, cos: f32, eta: f32) -> Vec3 {
    let outside = cos >= 0.0;
    let (eta_it, eta_ti) = if outside {
        (eta, 1.0 / eta)
    } else {
        (1.0 / eta, eta)
    };
    let w = if eta_it > 1.0 {
        schlick_weight(cos.abs())
    } else {
        let cos_t2 = 1.0 - (1.0 - cos * cos) * eta_ti * eta_ti;
        schlick_weight(cos_t2.max(0.0).sqrt())
    };
    r0 + (Vec3::ONE - r0) * w
}

/// The exact dielectric reflectance for a cosine `cos` with the
/// microsurface, negative from inside.
fn dielectric(cos: f32, eta: f32) -> f32 {
    if cos >= 0.0 {
        fresnel::dielectric(cos, eta)
    } else {
        fresnel::dielectric(-cos, 1.0 / eta)
    }
}

/// Smith's separable masking for GGX of roughness `a` (Mitsuba's
/// `smith_g1`): zero where `v` sees the back of the microfacet `m`.
fn smith_g1(v: Vec3, m: Vec3, a: Vec2) -> f32 {
    if v.dot(m) * v.z <= 0.0 {
        return 0.0;
    }
    let xy = (a.x * v.x).powi(2) + (a.y * v.y).powi(2);
    if xy == 0.0 {
        return 1.0;
    }
    2.0 / (1.0 + (1.0 + xy / (v.z * v.z)).sqrt())
}

/// The GGX distribution, zero where negligible (Mitsuba's `eval`).
fn ggx(m: Vec3, a: Vec2) -> f32 {
    let d = anisotropic::d(m, a);
    if d * m.z > 1e-20 {
        d
    } else {
        0.0
    }
}

/// Pdf of the visible normal `m` seen from `v` (upper hemisphere).
fn visible_pdf(v: Vec3, m: Vec3, a: Vec2) -> f32 {
    ggx(m, a) * smith_g1(v, m, a) * v.dot(m).abs() / v.z
}

/// The clearcoat's GTR1 ("Berry") distribution of roughness `a`.
fn gtr1(m: Vec3, a: f32) -> f32 {
    let a2 = a * a;
    let d = (a2 - 1.0) / (PI * a2.ln() * (1.0 + (a2 - 1.0) * m.z * m.z));
    if d * m.z > 1e-20 {
        d
    } else {
        0.0
    }
}

/// The clearcoat's shadowing: Smith for GGX of α 0.25 at each direction.
fn clearcoat_g(v: Vec3, m: Vec3) -> f32 {
    if v.dot(m) * v.z <= 0.0 {
        return 0.0;
    }
    let c2 = v.z * v.z;
    if v.z == 1.0 {
        return 1.0;
    }
    2.0 / (1.0 + (1.0 + 0.0625 * (1.0 - c2) / c2).sqrt())
}

/// Whether `m` faces both directions from `wo`'s side (reflection) or faces
/// `wo` and turns away from `wi` (refraction).
fn compatible(m: Vec3, wo: Vec3, wi: Vec3, reflection: bool) -> bool {
    let m = if wo.z < 0.0 { -m } else { m };
    let wi_side = if reflection { wi.dot(m) } else { -wi.dot(m) };
    wo.dot(m) > 0.0 && wi_side > 0.0
}

/// Luminance of a linear-sRGB colour (Mitsuba's weights).
fn luminance(c: Vec3) -> f32 {
    c.dot(Vec3::new(0.212671, 0.715160, 0.072169))
}

/// The colour's hue at luminance 1 (white when it is black).
fn hue(c: Vec3) -> Vec3 {
    let lum = luminance(c);
    if lum > 0.0 {
        c / lum
    } else {
        Vec3::ONE
    }
}

/// The lobes' weights and the side, for a view `wo`.
struct Lobes {
    /// (1 − metallic)(1 − transmission).
    brdf: f32,
    /// (1 − metallic) transmission.
    bsdf: f32,
    /// Whether `wo` is above the surface.
    front: bool,
}

impl Principled {
    /// The index of refraction Mitsuba gives a `specular` of `s` (0.5: 1.5).
    pub fn eta_of_specular(s: f32) -> f32 {
        2.0 / (1.0 - (0.08 * s).sqrt()) - 1.0
    }

    /// The clearcoat's GTR1 α for a `clearcoat_roughness` of `r` (Mitsuba's
    /// `clearcoat_gloss` is 1 − r).
    pub fn clearcoat_alpha(r: f32) -> f32 {
        let gloss = 1.0 - r;
        0.1 + (0.001 - 0.1) * gloss
    }

    /// The specular lobe's GGX α along the tangent and the bitangent.
    fn alpha(&self) -> Vec2 {
        let r2 = self.roughness * self.roughness;
        let aspect = (1.0 - 0.9 * self.anisotropic).sqrt();
        Vec2::new((r2 / aspect).max(1e-3), (r2 * aspect).max(1e-3))
    }

    /// The index of the far side relative to `wo`'s.
    fn eta_path(&self, front: bool) -> f32 {
        if front {
            self.eta
        } else {
            1.0 / self.eta
        }
    }

    fn lobes(&self, wo: Vec3) -> Lobes {
        Lobes {
            brdf: (1.0 - self.metallic) * (1.0 - self.transmission),
            bsdf: (1.0 - self.metallic) * self.transmission,
            front: wo.z > 0.0,
        }
    }

    /// The probabilities of the diffuse, clearcoat, specular reflection and
    /// specular transmission lobes, for a view with lobes `l` and the
    /// dielectric's reflectance `f` at the microfacet.
    fn probabilities(&self, l: &Lobes, f: f32) -> [f32; 4] {
        let p = if l.front {
            [
                l.brdf,
                0.25 * self.clearcoat,
                1.0 - l.bsdf * (1.0 - f),
                l.bsdf * (1.0 - f),
            ]
        } else {
            [0.0, 0.0, f, 1.0 - f]
        };
        let total: f32 = p.iter().sum();
        p.map(|x| x / total)
    }

    /// The half vector of `wo` → `wi` (the generalised one across the
    /// surface), turned up.
    fn half(&self, wo: Vec3, wi: Vec3, front: bool) -> Vec3 {
        let scale = if wo.z * wi.z > 0.0 {
            1.0
        } else {
            self.eta_path(front)
        };
        let h = (wo + wi * scale).normalize_or_zero();
        if h.z < 0.0 {
            -h
        } else {
            h
        }
    }

    /// BSDF value (f, without the cosine) and pdf for local `wo` → `wi` of
    /// the material with base colour `base`.
    pub fn eval(&self, base: Vec3, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        if wo.z == 0.0 || wi.z == 0.0 {
            return (Vec3::ZERO, 0.0);
        }
        let l = self.lobes(wo);
        let reflect = wo.z * wi.z > 0.0;
        let h = self.half(wo, wi, l.front);
        if h == Vec3::ZERO {
            return (Vec3::ZERO, 0.0);
        }
        let f_dielectric = dielectric(wo.dot(h), self.eta);
        let value = self.value(base, &l, (wo, wi, h), f_dielectric, true);
        let pdf = self.pdf(&l, wo, wi, h, f_dielectric, reflect);
        (value / wi.z.abs(), pdf)
    }

    /// f·|cos θi| (Mitsuba's `eval`) for `wo` → `wi` about the half vector
    /// `h`: every lobe, or (not `all`) the main specular ones alone.
    fn value(
        &self,
        base: Vec3,
        l: &Lobes,
        (wo, wi, h): (Vec3, Vec3, Vec3),
        f_dielectric: f32,
        all: bool,
    ) -> Vec3 {
        let reflect = wo.z * wi.z > 0.0;
        let a = self.alpha();
        let d = ggx(h, a);
        let g = smith_g1(wo, h, a) * smith_g1(wi, h, a);
        let (cos_o, cos_i) = (wo.z.abs(), wi.z.abs());
        let mut value = Vec3::ZERO;
        if reflect && compatible(h, wo, wi, true) && f_dielectric > 0.0 {
            let f = self.fresnel(base, l, wo.dot(h), f_dielectric);
            value += f * d * g / (4.0 * cos_o);
        }
        if !reflect && l.bsdf > 0.0 && compatible(h, wo, wi, false) && f_dielectric < 1.0 {
            let eta = self.eta_path(l.front);
            let (oh, ih) = (wo.dot(h), wi.dot(h));
            let t = (1.0 - f_dielectric) * d * g * oh * ih / (wo.z * (oh + eta * ih).powi(2));
            value += base.max(Vec3::ZERO).powf(0.5) * l.bsdf * t.abs();
        }
        if !(all && reflect && l.front) {
            return value;
        }
        if self.clearcoat > 0.0 && compatible(h, wo, wi, true) {
            let f = schlick(Vec3::splat(0.04), wo.dot(h), self.eta).x;
            let dc = gtr1(h, self.clearcoat_alpha);
            let gc = clearcoat_g(wo, h) * clearcoat_g(wi, h);
            value += Vec3::splat(0.25 * self.clearcoat * f * dc * gc * cos_i);
        }
        if l.brdf > 0.0 {
            let (fo, fi) = (schlick_weight(cos_i), schlick_weight(cos_o));
            let diffuse = (1.0 - 0.5 * fi) * (1.0 - 0.5 * fo);
            let cos_d = h.dot(wi);
            let rr = 2.0 * self.roughness * cos_d * cos_d;
            let retro = rr * (fo + fi + fo * fi * (rr - 1.0));
            value += l.brdf * cos_i * base * FRAC_1_PI * (diffuse + retro);
            if self.sheen > 0.0 && self.metallic < 1.0 {
                let tint = Vec3::ONE + (hue(base) - Vec3::ONE) * self.sheen_tint;
                let fd = schlick_weight(cos_d.abs());
                value += self.sheen * (1.0 - self.metallic) * fd * tint * cos_i;
            }
        }
        value
    }

    /// The specular lobe's reflectance at a microfacet seen at `cos` (Mitsuba's
    /// `principled_fresnel`): below the surface the dielectric's alone.
    fn fresnel(&self, base: Vec3, l: &Lobes, cos: f32, f_dielectric: f32) -> Vec3 {
        if !l.front {
            return Vec3::splat(l.bsdf * f_dielectric);
        }
        let eta_it = if cos >= 0.0 { self.eta } else { 1.0 / self.eta };
        let r0 = ((eta_it - 1.0) / (eta_it + 1.0)).powi(2);
        let metal = self.metallic * schlick(base, cos, self.eta);
        let tinted =
            (1.0 - self.metallic) * self.specular_tint * schlick(hue(base) * r0, cos, self.eta);
        Vec3::splat((1.0 - self.metallic) * (1.0 - self.specular_tint) * f_dielectric)
            + metal
            + tinted
    }

    /// The sampler's pdf of `wi` (solid angle).
    fn pdf(&self, l: &Lobes, wo: Vec3, wi: Vec3, h: Vec3, f_dielectric: f32, reflect: bool) -> f32 {
        let [p_diffuse, p_coat, p_reflect, p_refract] = self.probabilities(l, f_dielectric);
        let (oh, ih) = (wo.dot(h), wi.dot(h));
        let jacobian = if reflect {
            (1.0 / (4.0 * ih)).abs()
        } else {
            let eta = self.eta_path(l.front);
            (eta * eta * ih / (oh + eta * ih).powi(2)).abs()
        };
        let up = if wo.z < 0.0 { -wo } else { wo };
        let visible = visible_pdf(up, h, self.alpha());
        let mut pdf = 0.0;
        if reflect {
            if compatible(h, wo, wi, true) {
                pdf += p_reflect * visible * jacobian;
                pdf += p_coat * h.z * gtr1(h, self.clearcoat_alpha) * jacobian;
            }
            pdf += p_diffuse * wi.z.max(0.0) * FRAC_1_PI;
        } else if compatible(h, wo, wi, false) {
            pdf += p_refract * visible * jacobian;
        }
        pdf
    }

    /// Samples `wi` for `wo` with the lobe number `u_lobe` and the point
    /// `u`: the direction, its weight f·|cos θi|/pdf and its pdf.
    pub fn sample(&self, base: Vec3, wo: Vec3, u_lobe: f32, u: Vec2) -> Option<(Vec3, Vec3, f32)> {
        if wo.z == 0.0 {
            return None;
        }
        let l = self.lobes(wo);
        if !l.front && l.bsdf <= 0.0 {
            return None;
        }
        let up = if wo.z < 0.0 { -wo } else { wo };
        let m = anisotropic::sample_visible_normal(up, self.alpha(), u);
        let f_dielectric = dielectric(wo.dot(m), self.eta);
        let [p_diffuse, p_coat, p_reflect, _] = self.probabilities(&l, f_dielectric);
        // Each lobe's direction must stay on its side of the surface and
        // of its microfacet (Mitsuba's checks): a reflection below the
        // horizon is not a refraction.
        let (wi, normal, reflected) = if u_lobe < p_diffuse {
            (cosine_hemisphere(u), None, true)
        } else if u_lobe < p_diffuse + p_coat {
            let mc = self.sample_gtr1(u);
            (reflect(wo, mc), Some(mc), true)
        } else if u_lobe < p_diffuse + p_coat + p_reflect {
            (reflect(wo, m), Some(m), true)
        } else {
            let n = if wo.dot(m) < 0.0 { -m } else { m };
            (
                super::refract(wo, n, self.eta_path(l.front))?,
                Some(m),
                false,
            )
        };
        if (wo.z * wi.z > 0.0) != reflected
            || normal.is_some_and(|n| !compatible(n, wo, wi, reflected))
        {
            return None;
        }
        let (f, pdf) = self.eval(base, wo, wi);
        // (A NaN pdf fails too.)
        if pdf.is_nan() || pdf <= 0.0 {
            return None;
        }
        Some((wi, f * wi.z.abs() / pdf, pdf))
    }

    /// Samples the main specular lobes alone (Whitted's glossy branches):
    /// `wi`, its weight and whether it refracts.
    pub fn sample_specular(
        &self,
        base: Vec3,
        wo: Vec3,
        u_lobe: f32,
        u: Vec2,
    ) -> Option<(Vec3, Vec3, bool)> {
        let l = self.lobes(wo);
        if wo.z == 0.0 || (!l.front && l.bsdf <= 0.0) {
            return None;
        }
        let up = if wo.z < 0.0 { -wo } else { wo };
        let a = self.alpha();
        let m = anisotropic::sample_visible_normal(up, a, u);
        let f_dielectric = dielectric(wo.dot(m), self.eta);
        let [_, _, p_reflect, p_refract] = self.probabilities(&l, f_dielectric);
        let share = p_reflect / (p_reflect + p_refract);
        let eta = self.eta_path(l.front);
        let (wi, p) = if u_lobe < share {
            (reflect(wo, m), share)
        } else {
            let n = if wo.dot(m) < 0.0 { -m } else { m };
            (super::refract(wo, n, eta)?, 1.0 - share)
        };
        let reflected = wo.z * wi.z > 0.0;
        if !compatible(m, wo, wi, reflected) || wi.z == 0.0 {
            return None;
        }
        let (oh, ih) = (wo.dot(m), wi.dot(m));
        let jacobian = if reflected {
            (1.0 / (4.0 * ih)).abs()
        } else {
            (eta * eta * ih / (oh + eta * ih).powi(2)).abs()
        };
        let pdf = p * visible_pdf(up, m, a) * jacobian;
        let value = self.value(base, &l, (wo, wi, m), f_dielectric, false);
        (pdf > 0.0).then(|| (wi, value / pdf, !reflected))
    }

    /// A clearcoat microfacet normal drawn from GTR1 times its cosine.
    fn sample_gtr1(&self, u: Vec2) -> Vec3 {
        let a2 = self.clearcoat_alpha * self.clearcoat_alpha;
        let phi = 2.0 * PI * u.x;
        let cos2 = (1.0 - a2.powf(1.0 - u.y)) / (1.0 - a2);
        let sin = (1.0 - cos2).max(0.0).sqrt();
        let cos = cos2.max(0.0).sqrt();
        Vec3::new(phi.cos() * sin, phi.sin() * sin, cos)
    }
}
