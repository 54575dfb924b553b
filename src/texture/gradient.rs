//! Patterns along one axis (POV-Ray's `gradient` and a two-colour
//! `stripes`): the pattern's coordinates are projected on the x axis of its
//! own space, which the texture's `rotate` turns; one period per unit.

use glam::Vec3;

/// A ramp from 0 to 1 along x, repeating every unit (POV-Ray's
/// `gradient x`): the fraction of `p.x`.
pub fn ramp(p: Vec3) -> f32 {
    let v = p.x - p.x.floor();
    // `x - floor(x)` rounds to 1 for tiny negative x.
    if v < 1.0 {
        v
    } else {
        0.0
    }
}

/// Stripes across x, one unit wide: 0 for even stripes ([0, 1), [2, 3), …),
/// 1 for odd ones.
pub fn stripe(p: Vec3) -> f32 {
    // In f64, as the checker: the parity of a large stripe index is exact.
    ((p.x.floor() as f64).rem_euclid(2.0)) as f32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ramp_repeats_every_unit_and_stays_in_range() {
        assert_eq!(ramp(Vec3::new(0.25, 9.0, 9.0)), 0.25);
        assert_eq!(ramp(Vec3::new(3.25, 0.0, 0.0)), 0.25);
        assert_eq!(ramp(Vec3::new(-0.75, 0.0, 0.0)), 0.25);
        for x in [-1e-9f32, -1e20, 1e20, 0.0, 0.999_999_9] {
            let v = ramp(Vec3::new(x, 0.0, 0.0));
            assert!((0.0..1.0).contains(&v), "{x} → {v}");
        }
    }

    #[test]
    fn stripes_alternate() {
        assert_eq!(stripe(Vec3::new(0.5, 0.0, 0.0)), 0.0);
        assert_eq!(stripe(Vec3::new(1.5, 0.0, 0.0)), 1.0);
        assert_eq!(stripe(Vec3::new(-0.5, 0.0, 0.0)), 1.0);
        assert_eq!(stripe(Vec3::new(2.5, 7.0, -3.0)), 0.0);
        assert_eq!(stripe(Vec3::new(1e6 + 1.5, 0.0, 0.0)), 1.0);
    }
}
