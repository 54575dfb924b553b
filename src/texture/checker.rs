//! The checker pattern: cells of two colours.
//!
//! In (u, v) it is Mitsuba 3's `checkerboard`: four cells in the unit
//! square, the cell at (0, 0) "even" (Mitsuba's `color0`), repeating with
//! period 1 in both directions (so a texture transform scaling (u, v) by 1/4
//! gives 8 × 8 cells). As a solid pattern it is POV-Ray's `checker`: unit
//! cubes in alternating colours, the cube [0, 1)³ even.

use glam::{Vec2, Vec3};

/// Whether (u, v) lies in an odd cell: the halves of the unit square
/// disagree (Mitsuba: `mask = (u mod 1 > 0.5) == (v mod 1 > 0.5)` picks
/// `color0`).
pub fn odd_uv(uv: Vec2) -> bool {
    let upper = |x: f32| x - x.floor() > 0.5;
    upper(uv.x) != upper(uv.y)
}

/// Whether the point `p` lies in an odd unit cube (the sum of its cells'
/// integer coordinates is odd).
pub fn odd_solid(p: Vec3) -> bool {
    let cell = p.floor();
    // The parity of each coordinate apart, in f64: an f32 sum of three
    // large cell indices would round and lose it.
    let parity = |x: f32| (x as f64).rem_euclid(2.0) as u32;
    (parity(cell.x) + parity(cell.y) + parity(cell.z)) % 2 == 1
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uv_cells_follow_mitsuba() {
        assert!(!odd_uv(Vec2::new(0.25, 0.25)));
        assert!(odd_uv(Vec2::new(0.75, 0.25)));
        assert!(odd_uv(Vec2::new(0.25, 0.75)));
        assert!(!odd_uv(Vec2::new(0.75, 0.75)));
        // Period 1, negative coordinates included.
        assert_eq!(
            odd_uv(Vec2::new(0.75, 0.25)),
            odd_uv(Vec2::new(-0.25, 3.25))
        );
    }

    #[test]
    fn solid_cells_alternate_along_every_axis() {
        assert!(!odd_solid(Vec3::splat(0.5)));
        for axis in [Vec3::X, Vec3::Y, Vec3::Z] {
            assert!(odd_solid(Vec3::splat(0.5) + axis));
            assert!(odd_solid(Vec3::splat(0.5) - axis));
            assert!(!odd_solid(Vec3::splat(0.5) + 2.0 * axis));
        }
        // Far from the origin the parity is still exact.
        assert!(
            odd_solid(Vec3::new(1e6 + 1.5, 0.5, 0.5)) != odd_solid(Vec3::new(1e6 + 0.5, 0.5, 0.5))
        );
        assert!(odd_solid(Vec3::new(3e6 + 0.5, 2e6 + 0.5, 1e6 + 1.5)));
    }
}
