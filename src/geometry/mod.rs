//! Geometry: rays, bounds, the shapes (one file each) and the BVH over them.

pub mod bvh;
pub mod shape;

use glam::Vec3;

/// A ray with the time it was sent (for motion blur).
#[derive(Debug, Clone, Copy)]
pub struct Ray {
    /// Origin.
    pub o: Vec3,
    /// Direction (not necessarily unit length for shadow rays; unit elsewhere).
    pub d: Vec3,
    /// Time within the shutter interval.
    pub time: f32,
}

impl Ray {
    /// A ray from `o` along `d` at `time`.
    pub fn new(o: Vec3, d: Vec3, time: f32) -> Ray {
        Ray { o, d, time }
    }

    /// The point at parameter `t`.
    pub fn at(&self, t: f32) -> Vec3 {
        self.o + self.d * t
    }
}

/// An axis-aligned bounding box.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aabb {
    /// Minimum corner.
    pub min: Vec3,
    /// Maximum corner.
    pub max: Vec3,
}

impl Aabb {
    /// The empty box (union identity).
    pub const EMPTY: Aabb = Aabb {
        min: Vec3::splat(f32::INFINITY),
        max: Vec3::splat(f32::NEG_INFINITY),
    };

    /// The smallest box holding both.
    pub fn union(self, o: Aabb) -> Aabb {
        Aabb {
            min: self.min.min(o.min),
            max: self.max.max(o.max),
        }
    }

    /// The box grown to hold `p`.
    pub fn grow(self, p: Vec3) -> Aabb {
        Aabb {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    /// Surface area (0 for an empty box).
    pub fn area(&self) -> f32 {
        let e = (self.max - self.min).max(Vec3::ZERO);
        2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
    }

    /// Centre point.
    pub fn center(&self) -> Vec3 {
        0.5 * (self.min + self.max)
    }
}

/// Offsets a ray origin off a surface along the geometric normal, by an amount
/// that scales with the magnitude of the hit point's coordinates (float error
/// grows with them), on the side `dir` leaves towards. The paper's fixed 1e-5
/// gives acne at large scales and leaks at small ones.
pub fn offset_origin(p: Vec3, n_geo: Vec3, dir: Vec3) -> Vec3 {
    let eps = 1e-4 * (1.0 + p.abs().max_element());
    let n = if n_geo.dot(dir) >= 0.0 { n_geo } else { -n_geo };
    p + n * eps
}

/// An orthonormal basis around a unit normal (Duff et al. 2017, "Building an
/// Orthonormal Basis, Revisited").
pub fn orthonormal_basis(n: Vec3) -> (Vec3, Vec3) {
    let sign = 1.0f32.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (
        Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        Vec3::new(b, sign + n.y * n.y * a, -n.y),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn basis_is_orthonormal() {
        for n in [
            Vec3::Z,
            -Vec3::Z,
            Vec3::X,
            Vec3::new(0.3, -0.5, 0.8).normalize(),
        ] {
            let (t, b) = orthonormal_basis(n);
            assert!((t.length() - 1.0).abs() < 1e-5 && (b.length() - 1.0).abs() < 1e-5);
            assert!(t.dot(n).abs() < 1e-5 && b.dot(n).abs() < 1e-5 && t.dot(b).abs() < 1e-5);
        }
    }

    #[test]
    fn offset_scales_with_magnitude_and_picks_the_side() {
        let p = Vec3::new(1e4, 0.0, 0.0);
        let o = offset_origin(p, Vec3::Y, -Vec3::Y);
        assert!(o.y < -0.5, "offset {} too small at magnitude 1e4", o.y);
        let small = offset_origin(Vec3::ZERO, Vec3::Y, Vec3::Y);
        assert!(small.y > 0.0 && small.y < 1e-3);
    }
}
