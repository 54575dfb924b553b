//! Pearson's χ² goodness-of-fit test, shared by the tests of every sampler
//! (materials, lights, distributions): observed counts per bin against the
//! counts a pdf predicts.

use glam::Vec3;
use std::f64::consts::PI;

/// Bins over the sphere: in cos θ about +z over [−1, 1], and in φ over
/// [0, 2π).
pub const N_COS: usize = 16;
/// Bins in φ (see [`N_COS`]).
pub const N_PHI: usize = 32;

/// The bin of a unit direction.
pub fn sphere_bin(w: Vec3) -> usize {
    let c = ((w.z as f64 + 1.0) * 0.5 * N_COS as f64) as usize;
    let phi = (w.y as f64).atan2(w.x as f64).rem_euclid(2.0 * PI);
    let p = (phi / (2.0 * PI) * N_PHI as f64) as usize;
    c.min(N_COS - 1) * N_PHI + p.min(N_PHI - 1)
}

/// The unit direction of a cosine about +z and an angle φ.
fn direction(cos: f64, phi: f64) -> Vec3 {
    let sin = (1.0 - cos * cos).max(0.0).sqrt();
    Vec3::new(
        (sin * phi.cos()) as f32,
        (sin * phi.sin()) as f32,
        cos as f32,
    )
}

/// The share of samples a density in solid angle puts in each bin: ∫ pdf
/// dω with dω = d(cos θ) dφ, by a `sub` × `sub` midpoint rule per bin
/// (fine enough for the pdf's narrowest feature, e.g. a glossy lobe or a
/// disk's edge).
pub fn sphere_shares(pdf: impl Fn(Vec3) -> f32, sub: usize) -> Vec<f64> {
    let (dc, dp) = (2.0 / N_COS as f64, 2.0 * PI / N_PHI as f64);
    (0..N_COS * N_PHI)
        .map(|i| {
            let (c0, p0) = (-1.0 + (i / N_PHI) as f64 * dc, (i % N_PHI) as f64 * dp);
            let mut s = 0.0;
            for a in 0..sub {
                for b in 0..sub {
                    let c = c0 + (a as f64 + 0.5) / sub as f64 * dc;
                    let p = p0 + (b as f64 + 0.5) / sub as f64 * dp;
                    s += pdf(direction(c, p)) as f64;
                }
            }
            s * dc * dp / (sub * sub) as f64
        })
        .collect()
}

/// The p-value of sampled `directions` (out of `attempts`, failed ones
/// included) against the density `pdf` that the sampler claims.
pub fn sphere_p_value(
    directions: impl IntoIterator<Item = Vec3>,
    attempts: usize,
    pdf: impl Fn(Vec3) -> f32,
    sub: usize,
) -> f64 {
    let mut observed = vec![0.0; N_COS * N_PHI];
    for d in directions {
        observed[sphere_bin(d)] += 1.0;
    }
    let expected: Vec<f64> = (sphere_shares(pdf, sub).iter())
        .map(|s| s * attempts as f64)
        .collect();
    pearson_p_value(&observed, &expected)
}

/// The p-value of `observed` counts against `expected` ones (same bins).
/// Bins expecting fewer than 5 samples are pooled into one; samples where
/// the pdf predicts almost none fail at once.
pub fn pearson_p_value(observed: &[f64], expected: &[f64]) -> f64 {
    let (mut chi2, mut dof, mut pool_o, mut pool_e) = (0.0, 0usize, 0.0, 0.0);
    for (o, e) in observed.iter().zip(expected) {
        if *e < 5.0 {
            pool_o += o;
            pool_e += e;
        } else {
            chi2 += (o - e) * (o - e) / e;
            dof += 1;
        }
    }
    if pool_e >= 5.0 {
        chi2 += (pool_o - pool_e) * (pool_o - pool_e) / pool_e;
        dof += 1;
    } else {
        assert!(
            pool_o < 5.0 + 5.0 * pool_e,
            "samples where the pdf is ~0: {pool_o}"
        );
    }
    gamma_q((dof.max(2) - 1) as f64 / 2.0, chi2 / 2.0)
}

/// Regularised upper incomplete gamma Q(a, x) (Numerical Recipes §6.2:
/// series for x < a + 1, continued fraction otherwise).
pub fn gamma_q(a: f64, x: f64) -> f64 {
    let ln_gamma_a = ln_gamma(a);
    if x < a + 1.0 {
        let (mut sum, mut term, mut n) = (1.0 / a, 1.0 / a, a);
        for _ in 0..10_000 {
            n += 1.0;
            term *= x / n;
            sum += term;
            if term.abs() < sum.abs() * 1e-15 {
                break;
            }
        }
        1.0 - sum * (-x + a * x.ln() - ln_gamma_a).exp()
    } else {
        let tiny = 1e-300;
        let mut b = x + 1.0 - a;
        let mut c = 1.0 / tiny;
        let mut d = 1.0 / b;
        let mut h = d;
        for i in 1..10_000 {
            let an = -(i as f64) * (i as f64 - a);
            b += 2.0;
            d = an * d + b;
            if d.abs() < tiny {
                d = tiny;
            }
            c = b + an / c;
            if c.abs() < tiny {
                c = tiny;
            }
            d = 1.0 / d;
            let del = d * c;
            h *= del;
            if (del - 1.0).abs() < 1e-15 {
                break;
            }
        }
        (-x + a * x.ln() - ln_gamma_a).exp() * h
    }
}

/// ln Γ(x) by the Lanczos approximation (g = 7, n = 9).
fn ln_gamma(x: f64) -> f64 {
    const C: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    let x = x - 1.0;
    let t = x + 7.5;
    let mut a = C[0];
    for (i, c) in C.iter().enumerate().skip(1) {
        a += c / (x + i as f64);
    }
    0.5 * (2.0 * PI).ln() + (x + 0.5) * t.ln() - t + a.ln()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn incomplete_gamma_matches_known_values() {
        // χ² with 1 dof at 3.841 → p = 0.05; 10 dof at 23.209 → p = 0.01.
        assert!((gamma_q(0.5, 3.841 / 2.0) - 0.05).abs() < 1e-3);
        assert!((gamma_q(5.0, 23.209 / 2.0) - 0.01).abs() < 1e-4);
        assert!((gamma_q(50.0, 50.0) - 0.4812).abs() < 1e-3);
    }
}
