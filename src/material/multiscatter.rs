//! Energy compensation for GGX reflection (Kulla and Conty 2017, "Revisiting
//! Physically Based Shading at Imageworks", §"Multiple scattering").
//!
//! Single-scattering GGX loses the light that bounces more than once between
//! microfacets: up to ~60 % at α = 1 for grazing views. The compensation adds
//! a diffuse-like lobe
//!
//!   f_ms(ωo, ωi) = (1 − E(μo)) (1 − E(μi)) / (π (1 − E_avg)),
//!
//! where E(μ) is the directional albedo of the single-scattering lobe and
//! E_avg = 2 ∫ E(μ) μ dμ its cosine-weighted average. It is symmetric in ωo and
//! ωi (reciprocal) and reflects exactly 1 − E(μo), so a white glossy surface
//! reflects everything it receives (the white furnace test).
//!
//! E is tabulated once per process over (μ, √α) by stratified quadrature of
//! visible-normal samples, where each sample weighs G2/G1 (with F = 1).

use super::microfacet::{g1, g2, stratified_visible_normals};
use super::reflect;
use glam::Vec3;
use std::f32::consts::PI;
use std::sync::OnceLock;

/// Table resolution along μ = cos θ and along √α.
const N: usize = 32;
/// Stratified samples per table entry (per side of the grid).
const STRATA: usize = 64;

struct Table {
    /// E[a][m]: albedo for √α = a/(N−1) (clamped to the smallest α) and μ = m/(N−1).
    e: [[f32; N]; N],
    /// E_avg per √α.
    e_avg: [f32; N],
}

fn grid(k: usize) -> f32 {
    k as f32 / (N - 1) as f32
}

fn alpha_at(a: usize) -> f32 {
    let s = grid(a);
    (s * s).max(super::microfacet::gloss_to_alpha(0.0))
}

/// Single-scattering directional albedo by quadrature (no table).
pub fn albedo_by_quadrature(mu: f32, alpha: f32) -> f32 {
    let mu = mu.clamp(1e-3, 1.0);
    let wo = Vec3::new((1.0 - mu * mu).sqrt(), 0.0, mu);
    let g1o = g1(wo, alpha);
    let mut sum = 0.0f64;
    for m in stratified_visible_normals(wo, alpha, STRATA) {
        let wi = reflect(wo, m);
        if wi.z > 0.0 {
            sum += (g2(wo, wi, alpha) / g1o) as f64;
        }
    }
    (sum / (STRATA * STRATA) as f64) as f32
}

fn table() -> &'static Table {
    static TABLE: OnceLock<Table> = OnceLock::new();
    TABLE.get_or_init(|| {
        let mut e = [[0.0; N]; N];
        let mut e_avg = [0.0; N];
        for (a, row) in e.iter_mut().enumerate() {
            for (m, entry) in row.iter_mut().enumerate() {
                *entry = albedo_by_quadrature(grid(m), alpha_at(a)).min(1.0);
            }
            // E_avg = 2 ∫ E(μ) μ dμ, by the trapezoid rule on a fine μ grid
            // through the table's own interpolation.
            let fine = 512;
            let mut s = 0.0f64;
            for k in 0..=fine {
                let mu = k as f32 / fine as f32;
                let w = if k == 0 || k == fine { 0.5 } else { 1.0 };
                s += w * (lerp_row(row, mu) * mu) as f64;
            }
            e_avg[a] = (2.0 * s / fine as f64) as f32;
        }
        Table { e, e_avg }
    })
}

fn lerp_row(row: &[f32; N], mu: f32) -> f32 {
    let x = mu.clamp(0.0, 1.0) * (N - 1) as f32;
    let i = (x as usize).min(N - 2);
    let t = x - i as f32;
    row[i] * (1.0 - t) + row[i + 1] * t
}

/// Index and weight along the √α axis.
fn alpha_coord(alpha: f32) -> (usize, f32) {
    let x = alpha.max(0.0).sqrt().clamp(0.0, 1.0) * (N - 1) as f32;
    let i = (x as usize).min(N - 2);
    (i, x - i as f32)
}

/// E(μ): the fraction of light that single-scattering GGX reflects for a view
/// at cos θ = μ (tabulated, bilinear).
pub fn directional_albedo(mu: f32, alpha: f32) -> f32 {
    let t = table();
    let (i, w) = alpha_coord(alpha);
    lerp_row(&t.e[i], mu) * (1.0 - w) + lerp_row(&t.e[i + 1], mu) * w
}

/// E_avg: the cosine-weighted hemispherical average of E.
pub fn average_albedo(alpha: f32) -> f32 {
    let t = table();
    let (i, w) = alpha_coord(alpha);
    t.e_avg[i] * (1.0 - w) + t.e_avg[i + 1] * w
}

/// The compensation lobe f_ms for cosines `mu_o`, `mu_i` (both > 0).
pub fn brdf(mu_o: f32, mu_i: f32, alpha: f32) -> f32 {
    let e_avg = average_albedo(alpha);
    if e_avg >= 1.0 {
        return 0.0;
    }
    (1.0 - directional_albedo(mu_o, alpha)) * (1.0 - directional_albedo(mu_i, alpha))
        / (PI * (1.0 - e_avg))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn albedo_matches_a_brute_force_integral() {
        // E(μ) = ∫ D G2 / (4 μo μi) μi dωi by a 2000×4000 midpoint rule over
        // the hemisphere (numpy, independent of the sampling code here).
        for (mu, alpha, expect) in [
            (0.1f32, 1.0f32, 0.76021f32),
            (0.5, 1.0, 0.45069),
            (0.99, 1.0, 0.30880),
            (0.5, 0.5, 0.69825),
            (0.99, 0.5, 0.68739),
        ] {
            let e = albedo_by_quadrature(mu, alpha);
            assert!(
                (e - expect).abs() < 2e-3,
                "mu {mu} alpha {alpha}: {e} vs {expect}"
            );
        }
        // A nearly smooth surface loses nothing.
        assert!((directional_albedo(0.8, 1e-3) - 1.0).abs() < 2e-3);
    }

    #[test]
    fn the_table_interpolates_the_quadrature() {
        for (mu, alpha) in [(0.3f32, 0.2f32), (0.75, 0.6), (0.5, 0.05)] {
            let table = directional_albedo(mu, alpha);
            let exact = albedo_by_quadrature(mu, alpha);
            assert!(
                (table - exact).abs() < 5e-3,
                "mu {mu} alpha {alpha}: {table} vs {exact}"
            );
        }
    }

    #[test]
    fn compensation_restores_white_albedo() {
        // ∫ f_ms cos dωi = 1 − E(μo), so E + that = 1 for every view.
        for alpha in [0.1f32, 0.5, 1.0] {
            for mu_o in [0.2f32, 0.5, 0.9] {
                let n = 2000;
                let mut s = 0.0f64;
                for k in 0..n {
                    let mu_i = (k as f32 + 0.5) / n as f32;
                    // dω = 2π dμ (azimuth integrated out).
                    s += (brdf(mu_o, mu_i, alpha) * mu_i * 2.0 * PI) as f64 / n as f64;
                }
                let total = directional_albedo(mu_o, alpha) as f64 + s;
                assert!(
                    (total - 1.0).abs() < 2e-3,
                    "alpha {alpha} mu {mu_o}: {total}"
                );
            }
        }
    }
}
