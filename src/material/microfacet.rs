//! The GGX (Trowbridge–Reitz) microfacet distribution with visible-normal
//! sampling (Heitz 2018, "Sampling the GGX Distribution of Visible Normals").
//! All directions are in the local frame where the normal is +z.

use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// `gloss` in [0, 1] → GGX roughness α = gloss² (perceptually even steps;
/// the same remapping as Disney's and pbrt's "roughness").
pub fn gloss_to_alpha(gloss: f32) -> f32 {
    (gloss * gloss).max(1e-3)
}

/// GGX normal distribution D(m).
pub fn d(m: Vec3, alpha: f32) -> f32 {
    let a2 = alpha * alpha;
    let c2 = m.z * m.z;
    let denom = c2 * (a2 - 1.0) + 1.0;
    a2 / (PI * denom * denom)
}

/// Smith's Λ(ω) for GGX.
pub fn lambda(w: Vec3, alpha: f32) -> f32 {
    let c2 = w.z * w.z;
    if c2 <= 0.0 {
        return f32::INFINITY;
    }
    let t2 = (1.0 - c2).max(0.0) / c2;
    0.5 * (-1.0 + (1.0 + alpha * alpha * t2).sqrt())
}

/// Smith masking G1(ω).
pub fn g1(w: Vec3, alpha: f32) -> f32 {
    1.0 / (1.0 + lambda(w, alpha))
}

/// Height-correlated masking–shadowing G2(ωo, ωi).
pub fn g2(wo: Vec3, wi: Vec3, alpha: f32) -> f32 {
    1.0 / (1.0 + lambda(wo, alpha) + lambda(wi, alpha))
}

/// A visible normal for `wo` (wo.z > 0), Heitz 2018 listing 1.
pub fn sample_visible_normal(wo: Vec3, alpha: f32, u: Vec2) -> Vec3 {
    let vh = Vec3::new(alpha * wo.x, alpha * wo.y, wo.z).normalize();
    let lensq = vh.x * vh.x + vh.y * vh.y;
    let t1 = if lensq > 0.0 {
        Vec3::new(-vh.y, vh.x, 0.0) / lensq.sqrt()
    } else {
        Vec3::X
    };
    let t2 = vh.cross(t1);
    let r = u.x.sqrt();
    let phi = 2.0 * PI * u.y;
    let p1 = r * phi.cos();
    let mut p2 = r * phi.sin();
    let s = 0.5 * (1.0 + vh.z);
    p2 = (1.0 - s) * (1.0 - p1 * p1).max(0.0).sqrt() + s * p2;
    let nh = p1 * t1 + p2 * t2 + (1.0 - p1 * p1 - p2 * p2).max(0.0).sqrt() * vh;
    Vec3::new(alpha * nh.x, alpha * nh.y, nh.z.max(1e-6)).normalize()
}

/// Anisotropic GGX: roughness `a.x` along the local x axis (the tangent,
/// ∂p/∂u) and `a.y` along y (Heitz 2014, "Understanding the
/// Masking-Shadowing Function in Microfacet-Based BRDFs", eq. 85; Mitsuba
/// 3's `alpha_u`, `alpha_v`). The isotropic functions above are these with
/// `a.x == a.y`, kept apart so that isotropic surfaces compute what they
/// always did.
pub mod anisotropic {
    use glam::{Vec2, Vec3};
    use std::f32::consts::PI;

    /// D(m).
    pub fn d(m: Vec3, a: Vec2) -> f32 {
        let (x, y) = (m.x / a.x, m.y / a.y);
        let e = x * x + y * y + m.z * m.z;
        1.0 / (PI * a.x * a.y * e * e)
    }

    /// Smith's Λ(ω).
    pub fn lambda(w: Vec3, a: Vec2) -> f32 {
        let c2 = w.z * w.z;
        if c2 <= 0.0 {
            return f32::INFINITY;
        }
        let t2 = (a.x * a.x * w.x * w.x + a.y * a.y * w.y * w.y) / c2;
        0.5 * (-1.0 + (1.0 + t2).sqrt())
    }

    /// Smith masking G1(ω).
    pub fn g1(w: Vec3, a: Vec2) -> f32 {
        1.0 / (1.0 + lambda(w, a))
    }

    /// Height-correlated masking–shadowing G2(ωo, ωi).
    pub fn g2(wo: Vec3, wi: Vec3, a: Vec2) -> f32 {
        1.0 / (1.0 + lambda(wo, a) + lambda(wi, a))
    }

    /// A visible normal for `wo` (wo.z > 0): the isotropic sampler in the
    /// space stretched by (a.x, a.y) (Heitz 2018).
    pub fn sample_visible_normal(wo: Vec3, a: Vec2, u: Vec2) -> Vec3 {
        let stretched = Vec3::new(a.x * wo.x, a.y * wo.y, wo.z).normalize();
        let nh = super::sample_visible_normal(stretched, 1.0, u);
        Vec3::new(a.x * nh.x, a.y * nh.y, nh.z.max(1e-6)).normalize()
    }

    /// Pdf (solid angle of ωi) of reflecting `wo` about a visible normal into `wi`.
    pub fn reflection_pdf(wo: Vec3, wi: Vec3, a: Vec2) -> f32 {
        let m = (wo + wi).normalize_or_zero();
        if m == Vec3::ZERO || wo.z <= 0.0 {
            return 0.0;
        }
        g1(wo, a) * d(m, a) / (4.0 * wo.z)
    }

    /// The reflection BRDF value without the reflectance colour.
    pub fn reflection_brdf(wo: Vec3, wi: Vec3, a: Vec2) -> f32 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        let m = (wo + wi).normalize();
        d(m, a) * g2(wo, wi, a) / (4.0 * wo.z * wi.z)
    }
}

/// Visible normals for `wo` at the centres of a `strata` × `strata` grid of
/// sample points: a stratified quadrature over the visible normals, for
/// the albedo tables.
pub fn stratified_visible_normals(
    wo: Vec3,
    alpha: f32,
    strata: usize,
) -> impl Iterator<Item = Vec3> {
    (0..strata * strata).map(move |k| {
        let u = Vec2::new(
            ((k / strata) as f32 + 0.5) / strata as f32,
            ((k % strata) as f32 + 0.5) / strata as f32,
        );
        sample_visible_normal(wo, alpha, u)
    })
}

/// Pdf (solid angle of ωi) of reflecting `wo` about a visible normal into `wi`.
pub fn reflection_pdf(wo: Vec3, wi: Vec3, alpha: f32) -> f32 {
    let m = (wo + wi).normalize_or_zero();
    if m == Vec3::ZERO || wo.z <= 0.0 {
        return 0.0;
    }
    g1(wo, alpha) * d(m, alpha) / (4.0 * wo.z)
}

/// The reflection BRDF value without the reflectance colour: D·G2 / (4 cos_o cos_i).
pub fn reflection_brdf(wo: Vec3, wi: Vec3, alpha: f32) -> f32 {
    if wo.z <= 0.0 || wi.z <= 0.0 {
        return 0.0;
    }
    let m = (wo + wi).normalize();
    d(m, alpha) * g2(wo, wi, alpha) / (4.0 * wo.z * wi.z)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn d_is_normalised_over_projected_area() {
        // ∫ D(m) cos θm dω = 1.
        for alpha in [0.1f32, 0.5, 1.0] {
            let n = 400;
            let mut sum = 0.0f64;
            for i in 0..n {
                let theta = (i as f32 + 0.5) / n as f32 * PI / 2.0;
                let m = Vec3::new(theta.sin(), 0.0, theta.cos());
                sum += (d(m, alpha) * m.z * theta.sin()) as f64
                    * 2.0
                    * PI as f64
                    * (PI as f64 / 2.0 / n as f64);
            }
            assert!((sum - 1.0).abs() < 0.01, "alpha {alpha}: {sum}");
        }
    }

    #[test]
    fn anisotropic_d_is_normalised_and_equal_roughness_is_isotropic() {
        // ∫ D(m) cos θm dω = 1 over the hemisphere, for uneven roughness.
        let a = Vec2::new(0.1, 0.5);
        let (n, mut sum) = (400, 0.0f64);
        for i in 0..n {
            for j in 0..n {
                let theta = (i as f32 + 0.5) / n as f32 * PI / 2.0;
                let phi = (j as f32 + 0.5) / n as f32 * 2.0 * PI;
                let m = Vec3::new(
                    theta.sin() * phi.cos(),
                    theta.sin() * phi.sin(),
                    theta.cos(),
                );
                let dw = theta.sin() * (PI / 2.0 / n as f32) * (2.0 * PI / n as f32);
                sum += (anisotropic::d(m, a) * m.z * dw) as f64;
            }
        }
        assert!((sum - 1.0).abs() < 0.01, "{sum}");
        let (m, w) = (
            Vec3::new(0.3, -0.2, 0.93).normalize(),
            Vec3::new(0.5, 0.4, 0.77).normalize(),
        );
        let even = Vec2::splat(0.3);
        assert!((anisotropic::d(m, even) - d(m, 0.3)).abs() < 1e-4 * d(m, 0.3));
        assert!((anisotropic::lambda(w, even) - lambda(w, 0.3)).abs() < 1e-6);
    }

    #[test]
    fn visible_normals_face_the_viewer() {
        let wo = Vec3::new(0.6, 0.0, 0.8);
        for i in 0..64 {
            let u = Vec2::new((i % 8) as f32 / 8.0 + 0.05, (i / 8) as f32 / 8.0 + 0.05);
            let m = sample_visible_normal(wo, 0.5, u);
            assert!(m.z > 0.0 && m.dot(wo) > -1e-4);
        }
    }
}
