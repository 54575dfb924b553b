//! Solid noise and the patterns built on it: Perlin's improved gradient
//! noise (Perlin 2002, "Improving Noise"), fractal sums of it (fBm,
//! turbulence: Perlin 1985; pbrt-v4 §10.6) and the classic marble and wood
//! of Perlin's 1985 paper and POV-Ray. Every function is deterministic (a
//! fixed permutation) and returns a value in [0, 1] for the colours of a
//! texture to blend.

use glam::Vec3;

/// Ken Perlin's permutation of 0..256 (the reference implementation's).
const PERMUTATION: [u8; 256] = [
    151, 160, 137, 91, 90, 15, 131, 13, 201, 95, 96, 53, 194, 233, 7, 225, 140, 36, 103, 30, 69,
    142, 8, 99, 37, 240, 21, 10, 23, 190, 6, 148, 247, 120, 234, 75, 0, 26, 197, 62, 94, 252, 219,
    203, 117, 35, 11, 32, 57, 177, 33, 88, 237, 149, 56, 87, 174, 20, 125, 136, 171, 168, 68, 175,
    74, 165, 71, 134, 139, 48, 27, 166, 77, 146, 158, 231, 83, 111, 229, 122, 60, 211, 133, 230,
    220, 105, 92, 41, 55, 46, 245, 40, 244, 102, 143, 54, 65, 25, 63, 161, 1, 216, 80, 73, 209, 76,
    132, 187, 208, 89, 18, 169, 200, 196, 135, 130, 116, 188, 159, 86, 164, 100, 109, 198, 173,
    186, 3, 64, 52, 217, 226, 250, 124, 123, 5, 202, 38, 147, 118, 126, 255, 82, 85, 212, 207, 206,
    59, 227, 47, 16, 58, 17, 182, 189, 28, 42, 223, 183, 170, 213, 119, 248, 152, 2, 44, 154, 163,
    70, 221, 153, 101, 155, 167, 43, 172, 9, 129, 22, 39, 253, 19, 98, 108, 110, 79, 113, 224, 232,
    178, 185, 112, 104, 218, 246, 97, 228, 251, 34, 242, 193, 238, 210, 144, 12, 191, 179, 162,
    241, 81, 51, 145, 235, 249, 14, 239, 107, 49, 192, 214, 31, 181, 199, 106, 157, 184, 84, 204,
    176, 115, 121, 50, 45, 127, 4, 150, 254, 138, 236, 205, 93, 222, 114, 67, 29, 24, 72, 243, 141,
    128, 195, 78, 66, 215, 61, 156, 180,
];

fn perm(i: i64) -> i64 {
    PERMUTATION[(i & 255) as usize] as i64
}

/// Perlin's quintic fade curve 6t⁵ − 15t⁴ + 10t³.
fn fade(t: f32) -> f32 {
    t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
}

/// The dot product of the gradient chosen by `hash` with (x, y, z).
fn grad(hash: i64, x: f32, y: f32, z: f32) -> f32 {
    let h = hash & 15;
    let u = if h < 8 { x } else { y };
    let v = if h < 4 {
        y
    } else if h == 12 || h == 14 {
        x
    } else {
        z
    };
    (if h & 1 == 0 { u } else { -u }) + (if h & 2 == 0 { v } else { -v })
}

fn lerp(t: f32, a: f32, b: f32) -> f32 {
    a + t * (b - a)
}

/// Improved Perlin noise at `p`: zero at the integer lattice, within about
/// ±1, smooth (C²).
pub fn perlin(p: Vec3) -> f32 {
    if !p.is_finite() {
        return 0.0;
    }
    let cell = p.floor();
    // Lattice indices wrap every 256 cells (the permutation's period); far
    // from the origin f32 keeps whole cells, so the index is exact.
    let (xi, yi, zi) = (
        (cell.x as f64).rem_euclid(256.0) as i64,
        (cell.y as f64).rem_euclid(256.0) as i64,
        (cell.z as f64).rem_euclid(256.0) as i64,
    );
    let f = p - cell;
    let (u, v, w) = (fade(f.x), fade(f.y), fade(f.z));
    let a = perm(xi) + yi;
    let (aa, ab) = (perm(a) + zi, perm(a + 1) + zi);
    let b = perm(xi + 1) + yi;
    let (ba, bb) = (perm(b) + zi, perm(b + 1) + zi);
    let (x, y, z) = (f.x, f.y, f.z);
    lerp(
        w,
        lerp(
            v,
            lerp(u, grad(perm(aa), x, y, z), grad(perm(ba), x - 1.0, y, z)),
            lerp(
                u,
                grad(perm(ab), x, y - 1.0, z),
                grad(perm(bb), x - 1.0, y - 1.0, z),
            ),
        ),
        lerp(
            v,
            lerp(
                u,
                grad(perm(aa + 1), x, y, z - 1.0),
                grad(perm(ba + 1), x - 1.0, y, z - 1.0),
            ),
            lerp(
                u,
                grad(perm(ab + 1), x, y - 1.0, z - 1.0),
                grad(perm(bb + 1), x - 1.0, y - 1.0, z - 1.0),
            ),
        ),
    )
}

/// Fractional Brownian motion: `octaves` of noise, each at `lambda` times
/// the frequency and `omega` times the amplitude of the last (POV-Ray's
/// defaults 2 and 0.5), normalised by the amplitudes' sum to about ±1.
pub fn fbm(p: Vec3, octaves: u32, omega: f32, lambda: f32) -> f32 {
    let (mut sum, mut amplitude, mut norm, mut q) = (0.0, 1.0, 0.0, p);
    for _ in 0..octaves.max(1) {
        sum += amplitude * perlin(q);
        norm += amplitude;
        amplitude *= omega;
        q *= lambda;
    }
    sum / norm
}

/// Turbulence: as [`fbm`] with the absolute value of each octave, in [0, 1).
pub fn turbulence(p: Vec3, octaves: u32, omega: f32, lambda: f32) -> f32 {
    let (mut sum, mut amplitude, mut norm, mut q) = (0.0, 1.0, 0.0, p);
    for _ in 0..octaves.max(1) {
        sum += amplitude * perlin(q).abs();
        norm += amplitude;
        amplitude *= omega;
        q *= lambda;
    }
    sum / norm
}

/// The solid patterns made of noise.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NoiseKind {
    /// fBm, mapped from ±1 to [0, 1].
    Noise,
    /// Turbulence.
    Turbulence,
    /// Veins along x: 0.5 + 0.5 sin(2π (frequency · (x + amount ·
    /// turbulence) + phase)) (Perlin 1985; amount 2 by default).
    Marble,
    /// Rings about the y axis, disturbed by noise: the fraction of
    /// frequency · 4 · (distance from the axis + amount · fbm) + phase
    /// (amount 0.25 by default).
    Wood,
}

/// How a noise pattern's octaves add up and how marble's and wood's bands
/// are disturbed and spaced: POV-Ray's pattern modifiers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NoiseParams {
    /// Octaves of the fractal sum.
    pub octaves: u32,
    /// Each octave's amplitude over the last's.
    pub omega: f32,
    /// Each octave's frequency over the last's.
    pub lambda: f32,
    /// How far noise displaces marble's and wood's bands (unused by the
    /// others).
    pub turbulence: f32,
    /// Bands per band: marble's and wood's bands are this many times as
    /// many.
    pub frequency: f32,
    /// Shift of marble's and wood's bands, a fraction of one.
    pub phase: f32,
}

impl NoiseParams {
    /// The parameters a texture of `kind` that sets none has (today's
    /// patterns: marble's turbulence 2 and wood's 0.25 were fixed).
    pub const fn defaults(kind: NoiseKind) -> NoiseParams {
        NoiseParams {
            octaves: 6,
            omega: 0.5,
            lambda: 2.0,
            turbulence: kind.default_turbulence(),
            frequency: 1.0,
            phase: 0.0,
        }
    }
}

named_values!(NoiseKind {
    "noise" => Noise,
    "turbulence" => Turbulence,
    "marble" => Marble,
    "wood" => Wood,
});

impl NoiseKind {
    /// Whether its bands take `turbulence`, `frequency` and `phase`.
    pub fn has_bands(self) -> bool {
        matches!(self, NoiseKind::Marble | NoiseKind::Wood)
    }

    /// How far noise displaces its bands when the scene does not say.
    pub const fn default_turbulence(self) -> f32 {
        match self {
            NoiseKind::Marble => 2.0,
            NoiseKind::Wood => 0.25,
            NoiseKind::Noise | NoiseKind::Turbulence => 0.0,
        }
    }

    /// The pattern's value at `p`, in [0, 1].
    pub fn value(self, p: Vec3, n: &NoiseParams) -> f32 {
        let (octaves, omega, lambda) = (n.octaves, n.omega, n.lambda);
        let v = match self {
            NoiseKind::Noise => 0.5 + 0.5 * fbm(p, octaves, omega, lambda),
            NoiseKind::Turbulence => turbulence(p, octaves, omega, lambda),
            NoiseKind::Marble => {
                let x = p.x + n.turbulence * turbulence(p, octaves, omega, lambda);
                // Exact at the defaults (× 1 + 0): images made before
                // frequency and phase existed are unchanged.
                let bands = x * n.frequency + n.phase;
                0.5 + 0.5 * (std::f32::consts::TAU * bands).sin()
            }
            NoiseKind::Wood => {
                let r =
                    (p.x * p.x + p.z * p.z).sqrt() + n.turbulence * fbm(p, octaves, omega, lambda);
                let rings = 4.0 * r * n.frequency + n.phase;
                rings - rings.floor()
            }
        };
        if v.is_finite() {
            v.clamp(0.0, 1.0)
        } else {
            0.0
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn points() -> impl Iterator<Item = Vec3> {
        (0..4000).map(|i| {
            let t = i as f32 * 0.7311;
            Vec3::new(
                t.sin() * 37.0,
                (t * 1.3).cos() * 11.0 + t * 0.01,
                t * 0.173 - 50.0,
            )
        })
    }

    #[test]
    fn perlin_noise_is_zero_on_the_lattice_bounded_and_deterministic() {
        for p in [
            Vec3::ZERO,
            Vec3::new(3.0, -7.0, 255.0),
            Vec3::splat(-1000.0),
        ] {
            assert_eq!(perlin(p), 0.0);
        }
        let mut seen = (f32::MAX, f32::MIN);
        for p in points() {
            let n = perlin(p);
            assert!(n.abs() <= 1.05, "{p}: {n}");
            assert_eq!(n, perlin(p));
            seen = (seen.0.min(n), seen.1.max(n));
        }
        // It varies over most of its range.
        assert!(seen.0 < -0.5 && seen.1 > 0.5, "{seen:?}");
        // Continuous: a tiny step changes it a little.
        let p = Vec3::new(0.37, 1.61, -2.23);
        assert!((perlin(p) - perlin(p + Vec3::splat(1e-4))).abs() < 1e-3);
        // Periodic over 256 cells, and finite everywhere.
        assert!((perlin(p) - perlin(p + Vec3::new(256.0, 0.0, 0.0))).abs() < 1e-4);
        assert_eq!(perlin(Vec3::new(f32::NAN, 0.0, 0.0)), 0.0);
        assert!(perlin(Vec3::splat(1e30)).is_finite());
    }

    #[test]
    fn every_pattern_stays_in_the_unit_interval() {
        for (name, kind) in NoiseKind::NAMES {
            let (mut lo, mut hi) = (f32::MAX, f32::MIN);
            for p in points() {
                let v = kind.value(p, &NoiseParams::defaults(kind));
                assert!((0.0..=1.0).contains(&v), "{name} at {p}: {v}");
                lo = lo.min(v);
                hi = hi.max(v);
            }
            assert!(hi - lo > 0.5, "{name} hardly varies: {lo}..{hi}");
        }
        assert!((0.0..1.0).contains(&turbulence(Vec3::splat(0.3), 0, 0.5, 2.0)));
        assert!(fbm(Vec3::splat(1e30), 8, 0.5, 2.0).is_finite());
    }
}
