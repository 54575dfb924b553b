//! Explicit lights and the light selection table.

use crate::check;
use crate::light::Light;
use glam::{DVec3, Vec3};

fn v3(v: DVec3) -> Vec3 {
    v.as_vec3()
}

fn rgb(c: &[f64; 3]) -> Vec3 {
    Vec3::new(c[0] as f32, c[1] as f32, c[2] as f32)
}

/// An explicit light (point, spot, directional) in the renderer's f32.
pub fn lower_light(l: &check::Light) -> Light {
    match l {
        check::Light::Point {
            position,
            intensity,
        } => Light::Point {
            position: v3(*position),
            intensity: rgb(intensity),
        },
        check::Light::Spot {
            position,
            direction,
            intensity,
            angle,
            falloff,
        } => Light::Spot {
            position: v3(*position),
            direction: v3(*direction),
            intensity: rgb(intensity),
            cos_total: angle.to_radians().cos() as f32,
            cos_falloff: falloff.to_radians().cos() as f32,
        },
        check::Light::Directional {
            direction,
            irradiance,
        } => Light::Directional {
            direction: v3(*direction),
            irradiance: rgb(irradiance),
        },
    }
}

/// The probability of choosing each light (its share of the total power)
/// and the running sums, the last exactly 1; `None` when nothing emits.
/// Summed in f64, so that no light's power, however large, overflows the
/// table and turns every light off.
pub fn light_table(powers: &[f64]) -> Option<(Vec<f32>, Vec<f32>)> {
    let clean = |p: f64| if p.is_finite() && p > 0.0 { p } else { 0.0 };
    let total: f64 = powers.iter().map(|&p| clean(p)).sum();
    if !(total > 0.0 && total.is_finite()) {
        return None;
    }
    let pmf: Vec<f32> = powers.iter().map(|&p| (clean(p) / total) as f32).collect();
    let mut acc = 0.0f64;
    let mut cdf: Vec<f32> = powers
        .iter()
        .map(|&p| {
            acc += clean(p) / total;
            acc as f32
        })
        .collect();
    *cdf.last_mut().expect("at least one light") = 1.0;
    Some((pmf, cdf))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_light_keeps_its_share_however_large_the_others() {
        // The largest powers the numeric domain allows beside a dim light:
        // in f32 their sum overflowed and the table turned every light off.
        let huge = 2.0 * std::f64::consts::PI * 1e12 * 4e18;
        let (pmf, cdf) = light_table(&[huge, huge, 1.0]).expect("lights");
        assert!(pmf.iter().all(|p| *p > 0.0 && p.is_finite()), "{pmf:?}");
        assert_eq!(*cdf.last().unwrap(), 1.0);
        assert!(cdf.windows(2).all(|w| w[0] <= w[1]));
        // A light that cannot emit gets no share; none at all, no table.
        let (pmf, _) = light_table(&[0.0, f64::NAN, 2.0]).expect("one light");
        assert_eq!(pmf, vec![0.0, 0.0, 1.0]);
        assert!(light_table(&[0.0, 0.0]).is_none());
    }
}
