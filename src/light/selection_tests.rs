//! Tests of [`super`]: the light selection rules.
use super::*;

#[test]
fn every_light_keeps_its_share_however_large_the_others() {
    // The largest powers the numeric domain allows beside a dim light:
    // in f32 their sum overflowed and the table turned every light off.
    let huge = 2.0 * std::f64::consts::PI * 1e12 * 4e18;
    let (pmf, cdf) = table(&[huge, huge, 1.0]).expect("lights");
    assert!(pmf.iter().all(|p| *p > 0.0 && p.is_finite()), "{pmf:?}");
    assert_eq!(*cdf.last().unwrap(), 1.0);
    assert!(cdf.windows(2).all(|w| w[0] <= w[1]));
    // A light that cannot emit gets no share; none at all, no table.
    let (pmf, _) = table(&[0.0, f64::NAN, 2.0]).expect("one light");
    assert_eq!(pmf, vec![0.0, 0.0, 1.0]);
    assert!(table(&[0.0, 0.0]).is_none());
}

use crate::light::test_rng as rng;

/// Random lights of every kind: infinite ones, points, one-sided and
/// two-sided quads, spots (narrow cones), lights of no power.
fn mixed_lights(n: usize, seed: u64) -> (Vec<Selectable>, Vec<f64>) {
    let mut r = rng(seed);
    let mut selectable = Vec::new();
    let mut power = Vec::new();
    for k in 0..n {
        let c = Vec3::new(r() * 10.0 - 5.0, r() * 4.0, r() * 10.0 - 5.0);
        let w = Vec3::new(r() - 0.5, r() - 0.5, r() - 0.5).normalize_or(Vec3::Y);
        let half = Vec3::splat(0.01 + 0.5 * r());
        let kind = k % 6;
        let b = LightBounds {
            bounds: crate::geometry::Aabb {
                min: c - half * (kind % 2) as f32,
                max: c + half * (kind % 2) as f32,
            },
            w,
            phi: (1.0 + 100.0 * r() as f64).powi(2),
            cos_o: [-1.0, 1.0, 0.9, 1.0, -1.0, 1.0][kind],
            cos_e: [0.0, 0.0, 0.95, 0.0, 0.0, 0.0][kind],
            two_sided: kind == 3,
        };
        selectable.push(if kind == 4 && k % 4 == 0 {
            // Some from one direction, some from every direction.
            let axis = if k % 8 == 0 { w } else { Vec3::ZERO };
            Selectable::Infinite {
                weight: b.phi * 0.01,
                axis,
            }
        } else {
            Selectable::Bounded(b)
        });
        power.push(if k % 17 == 5 { 0.0 } else { b.phi });
    }
    (selectable, power)
}

#[test]
fn the_sampled_pmf_is_the_mis_pmf_and_the_frequencies_follow_it() {
    // For the exhaustive rule and the tree, with lights at infinity
    // among the bounded ones: at random shading points each sample's
    // probability equals `pmf` of the light it gives, the pmfs sum to
    // one less the chance of no light (none can reach the point), and
    // stratified samples fall on each light as often as its pmf says.
    for (n, seed) in [(9, 1), (40, 2), (700, 3)] {
        let (selectable, power) = mixed_lights(n, seed);
        for rule in [
            LightSelection::Exhaustive,
            LightSelection::Bvh,
            LightSelection::Auto,
        ] {
            let sampler = LightSampler::new(rule, &selectable, &power).unwrap();
            let mut r = rng(seed + 10);
            for _ in 0..20 {
                let p = Vec3::new(r() * 14.0 - 7.0, r() * 6.0 - 1.0, r() * 14.0 - 7.0);
                let normal = Vec3::new(r() - 0.5, r() - 0.5, r() - 0.5).normalize_or(Vec3::Y);
                let pmfs: Vec<f64> = (0..n as u32)
                    .map(|i| sampler.pmf(p, normal, i) as f64)
                    .collect();
                for (i, &pmf) in pmfs.iter().enumerate() {
                    if power[i] == 0.0 {
                        assert_eq!(pmf, 0.0, "a light of no power is never chosen");
                    }
                }
                const K: usize = 20_000;
                let mut counts = vec![0usize; n];
                let mut none = 0usize;
                for k in 0..K {
                    match sampler.sample(p, normal, (k as f64 + 0.5) / K as f64) {
                        Some((i, pmf)) => {
                            assert_eq!(pmf, sampler.pmf(p, normal, i), "{rule:?}");
                            counts[i as usize] += 1;
                        }
                        None => none += 1,
                    }
                }
                let total: f64 = pmfs.iter().sum();
                assert!(total <= 1.0 + 1e-5, "{total}");
                for (i, &c) in counts.iter().enumerate() {
                    let f = c as f64 / K as f64;
                    assert!(
                        (f - pmfs[i]).abs() <= 2.0 / K as f64 + 1e-6,
                        "{rule:?} light {i}: {f} vs {}",
                        pmfs[i]
                    );
                }
                assert!(((none as f64 / K as f64) - (1.0 - total)).abs() <= 50.0 / K as f64);
            }
        }
    }
}

#[test]
fn every_share_keeps_its_floor_and_weights_split_the_rest() {
    // A dim light at infinity beside 300 bounded lights (tree) and
    // beside 9 (every one evaluated): however small its estimate, it
    // keeps its part of the floor, and a bright one takes most.
    for n in [9, 300] {
        let (mut selectable, mut power) = mixed_lights(n, 4);
        let infinite = |selectable: &[Selectable], power: &[f64]| {
            (selectable.iter().zip(power))
                .filter(|(s, &p)| matches!(s, Selectable::Infinite { .. }) && p > 0.0)
                .count()
        };
        let shares = infinite(&selectable, &power) + 2;
        selectable.push(Selectable::Infinite {
            weight: 1e-9,
            axis: Vec3::ZERO,
        });
        power.push(1e-6);
        let sampler = LightSampler::new(LightSelection::Auto, &selectable, &power).unwrap();
        let share = sampler.pmf(Vec3::ZERO, Vec3::Y, n as u32) as f64;
        assert!(share >= FLOOR / shares as f64 * 0.999, "{n}: {share}");
        assert!(share < FLOOR / shares as f64 * 1.01, "{n}: {share}");
        *selectable.last_mut().unwrap() = Selectable::Infinite {
            weight: 1e12,
            axis: Vec3::ZERO,
        };
        let sampler = LightSampler::new(LightSelection::Auto, &selectable, &power).unwrap();
        let share = sampler.pmf(Vec3::ZERO, Vec3::Y, n as u32) as f64;
        assert!(share > 1.0 - FLOOR, "{n}: {share}");
    }
}

#[test]
fn every_light_that_reaches_a_point_can_be_chosen() {
    // Nine evaluated lights, one a thousand million times dimmer than
    // the others: it is still chosen, in proportion to its estimate.
    let quad = |x: f32, phi: f64| {
        Selectable::Bounded(LightBounds {
            bounds: crate::geometry::Aabb {
                min: Vec3::new(x - 0.1, 2.0, -0.1),
                max: Vec3::new(x + 0.1, 2.0, 0.1),
            },
            w: -Vec3::Y,
            phi,
            cos_o: 1.0,
            cos_e: 0.0,
            two_sided: false,
        })
    };
    let mut selectable: Vec<Selectable> = (0..8).map(|k| quad(k as f32, 1e3)).collect();
    selectable.push(quad(8.0, 1e-6));
    let power = vec![1.0; 9];
    let sampler = LightSampler::new(LightSelection::Auto, &selectable, &power).unwrap();
    let dim = sampler.pmf(Vec3::new(4.0, 0.0, 0.0), Vec3::Y, 8);
    assert!(dim > 0.0 && dim < 1e-6, "{dim}");
    // Above the lights' plane none can reach: no choice at all.
    assert!(sampler
        .sample(Vec3::new(4.0, 3.0, 0.0), Vec3::Y, 0.5)
        .is_none());
}

#[test]
fn uniform_and_power_rules_do_not_depend_on_the_point() {
    let (selectable, power) = mixed_lights(12, 5);
    let uniform = LightSampler::new(LightSelection::Uniform, &selectable, &power).unwrap();
    let lit = power.iter().filter(|&&p| p > 0.0).count() as f32;
    assert_eq!(uniform.pmf(Vec3::ONE, Vec3::Y, 0), 1.0 / lit);
    let by_power = LightSampler::new(LightSelection::Power, &selectable, &power).unwrap();
    let total: f64 = power.iter().sum();
    assert!((by_power.pmf(Vec3::ZERO, Vec3::X, 1) as f64 - power[1] / total).abs() < 1e-6);
}
