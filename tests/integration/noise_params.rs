//! The noise textures' POV-Ray parameters (`omega`, `lambda`, and
//! marble's and wood's `turbulence`, `frequency` and `phase`): at their
//! defaults every pattern is bit for bit what it was before they existed,
//! and each moves the pattern the way its name says.

use glam::Vec3;
use proptest::prelude::*;
use ptsc::texture::noise::{perlin, NoiseKind, NoiseParams};

/// The patterns as they were computed before the parameters existed
/// (octaves the only one; the amounts 2 and 0.25 fixed).
fn before(kind: NoiseKind, p: Vec3, octaves: u32) -> f32 {
    let sum = |abs: bool| {
        let (mut sum, mut amplitude, mut norm, mut q) = (0.0, 1.0, 0.0, p);
        for _ in 0..octaves.max(1) {
            let n = perlin(q);
            sum += amplitude * if abs { n.abs() } else { n };
            norm += amplitude;
            amplitude *= 0.5;
            q *= 2.0;
        }
        sum / norm
    };
    let v: f32 = match kind {
        NoiseKind::Noise => 0.5 + 0.5 * sum(false),
        NoiseKind::Turbulence => sum(true),
        NoiseKind::Marble => {
            let phase = p.x + 2.0 * sum(true);
            0.5 + 0.5 * (std::f32::consts::TAU * phase).sin()
        }
        NoiseKind::Wood => {
            let r = (p.x * p.x + p.z * p.z).sqrt() + 0.25 * sum(false);
            let rings = 4.0 * r;
            rings - rings.floor()
        }
    };
    if v.is_finite() {
        v.clamp(0.0, 1.0)
    } else {
        0.0
    }
}

proptest! {
    #[test]
    fn the_defaults_give_the_patterns_of_before_bit_for_bit(
        x in -300.0f32..300.0, y in -300.0f32..300.0, z in -300.0f32..300.0,
        octaves in 1u32..=16,
    ) {
        let p = Vec3::new(x, y, z);
        for (name, kind) in NoiseKind::NAMES {
            let params = NoiseParams { octaves, ..NoiseParams::defaults(kind) };
            let (now, then) = (kind.value(p, &params), before(kind, p, octaves));
            prop_assert_eq!(now.to_bits(), then.to_bits(), "{} at {}", name, p);
        }
    }
}

/// Points spread over a few cells of noise.
fn points() -> impl Iterator<Item = Vec3> {
    (0..2000).map(|i| {
        let t = i as f32 * 0.618;
        Vec3::new(
            (t * 0.9).sin() * 5.0,
            (t * 1.7).cos() * 5.0,
            t * 0.004 - 4.0,
        )
    })
}

/// How much `kind` with `params` changes over a step of 0.01: the mean
/// difference of neighbouring values (rougher patterns change more).
fn roughness(kind: NoiseKind, params: &NoiseParams) -> f32 {
    let step = Vec3::new(0.01, 0.007, 0.003);
    let sum: f32 = points()
        .map(|p| (kind.value(p, params) - kind.value(p + step, params)).abs())
        .sum();
    sum / 2000.0
}

fn with(kind: NoiseKind, f: impl FnOnce(&mut NoiseParams)) -> NoiseParams {
    let mut p = NoiseParams::defaults(kind);
    f(&mut p);
    p
}

#[test]
fn without_turbulence_marble_is_a_function_of_x_and_wood_of_the_radius() {
    let marble = with(NoiseKind::Marble, |p| p.turbulence = 0.0);
    let wood = with(NoiseKind::Wood, |p| p.turbulence = 0.0);
    let (mut marble_moved, mut wood_moved) = (0.0f32, 0.0f32);
    for p in points() {
        let elsewhere = Vec3::new(p.x, p.y * 3.0 + 1.7, p.z - 2.3);
        let m = NoiseKind::Marble;
        assert_eq!(m.value(p, &marble), m.value(elsewhere, &marble), "{p}");
        let expect = 0.5 + 0.5 * (std::f32::consts::TAU * p.x).sin();
        assert!((m.value(p, &marble) - expect).abs() < 1e-6);
        marble_moved += (m.value(p, &NoiseParams::defaults(m))
            - m.value(elsewhere, &NoiseParams::defaults(m)))
        .abs();
        // The same distance from the y axis, turned about it, higher.
        let turned = Vec3::new(p.z, p.y + 5.0, p.x);
        let w = NoiseKind::Wood;
        assert_eq!(w.value(p, &wood), w.value(turned, &wood), "{p}");
        wood_moved += (w.value(p, &NoiseParams::defaults(w))
            - w.value(turned, &NoiseParams::defaults(w)))
        .abs();
    }
    // With their default turbulence they do depend on the rest.
    assert!(
        marble_moved > 100.0 && wood_moved > 100.0,
        "{marble_moved} {wood_moved}"
    );
}

#[test]
fn more_turbulence_displaces_the_bands_further() {
    for kind in [NoiseKind::Marble, NoiseKind::Wood] {
        let clean = with(kind, |p| p.turbulence = 0.0);
        let displaced = |t: f32| {
            let params = with(kind, |p| p.turbulence = t);
            points()
                .map(|p| (kind.value(p, &params) - kind.value(p, &clean)).abs())
                .sum::<f32>()
        };
        let (a, b, c) = (displaced(0.05), displaced(0.2), displaced(1.0));
        assert!(0.0 < a && a < b && b < c, "{kind:?}: {a} {b} {c}");
    }
}

#[test]
fn omega_and_lambda_make_the_noise_rougher() {
    for kind in [NoiseKind::Noise, NoiseKind::Turbulence] {
        let omega = |o: f32| roughness(kind, &with(kind, |p| p.omega = o));
        let (smooth, default, rough) = (omega(0.2), omega(0.5), omega(0.9));
        assert!(
            smooth < default && default < rough,
            "{kind:?} omega: {smooth} {default} {rough}"
        );
        let lambda = |l: f32| roughness(kind, &with(kind, |p| p.lambda = l));
        let (near, default, far) = (lambda(1.5), lambda(2.0), lambda(3.0));
        assert!(
            near < default && default < far,
            "{kind:?} lambda: {near} {default} {far}"
        );
    }
}

#[test]
fn frequency_multiplies_the_bands_and_phase_shifts_them() {
    let kind = NoiseKind::Marble;
    let clean = with(kind, |p| p.turbulence = 0.0);
    let twice = with(kind, |p| {
        p.turbulence = 0.0;
        p.frequency = 2.0;
    });
    let shifted = with(kind, |p| {
        p.turbulence = 0.0;
        p.phase = 0.25;
    });
    for p in points() {
        let v = |q: Vec3, params: &NoiseParams| kind.value(q, params);
        assert!(
            (v(p, &twice) - v(p * Vec3::new(2.0, 1.0, 1.0), &clean)).abs() < 1e-4,
            "{p}"
        );
        assert!(
            (v(p, &shifted) - v(p + Vec3::X * 0.25, &clean)).abs() < 1e-4,
            "{p}"
        );
    }
    // Wood: twice the rings, each a quarter further on.
    let kind = NoiseKind::Wood;
    let clean = with(kind, |p| p.turbulence = 0.0);
    let both = with(kind, |p| {
        p.turbulence = 0.0;
        p.frequency = 2.0;
        p.phase = 0.25;
    });
    for p in points() {
        let r = (p.x * p.x + p.z * p.z).sqrt();
        let expect = (8.0 * r + 0.25).fract();
        let got = kind.value(p, &both);
        // Equal, or either side of a ring's edge.
        let d = (got - expect).abs();
        assert!(!(1e-3..=0.999).contains(&d), "{p}: {got} vs {expect}");
        let once = (4.0 * r).fract();
        let d = (kind.value(p, &clean) - once).abs();
        assert!(!(1e-3..=0.999).contains(&d), "{p}");
    }
}
