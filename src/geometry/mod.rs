//! Geometry: rays, bounds, the shapes (one file each) and the BVH over them.

pub mod disk;
pub mod plane;
pub mod polynomial;
pub mod quad;
pub mod round;
pub mod shape;
pub mod sphere;
pub mod texcoord;
pub mod triangle;

use glam::{DVec3, Vec3};

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

/// Minimum ray distance (rays start offset from surfaces already).
pub const T_MIN: f32 = 1e-5;

/// Offsets a ray origin off a surface along the geometric normal, on the side
/// `dir` leaves towards, by an amount that scales with the hit point's
/// coordinates: 256 ulps of each coordinate, or 1/65536 near the origin where
/// ulps vanish (Wächter and Binder 2019, "A Fast and Robust Method for Avoiding
/// Self-Intersection", Ray Tracing Gems ch. 6). The paper's fixed 1e-5 gives
/// acne at large scales and leaks at small ones. `p` must be accurate to a few
/// ulps: hits are re-projected onto their surface (see `Shape::surface_point`).
pub fn offset_origin(p: Vec3, n_geo: Vec3, dir: Vec3) -> Vec3 {
    const ORIGIN: f32 = 1.0 / 32.0;
    const FLOAT_SCALE: f32 = 1.0 / 65536.0;
    const INT_SCALE: f32 = 256.0;
    let n = if n_geo.dot(dir) >= 0.0 { n_geo } else { -n_geo };
    let offset = |p: f32, n: f32| {
        if p.abs() < ORIGIN {
            return p + FLOAT_SCALE * n;
        }
        // Moving the bit pattern moves by whole ulps; the sign of p decides
        // which way the integer grows.
        let of = (INT_SCALE * n) as i32;
        let bits = p.to_bits() as i32;
        f32::from_bits(bits.wrapping_add(if p < 0.0 { -of } else { of }) as u32)
    };
    Vec3::new(offset(p.x, n.x), offset(p.y, n.y), offset(p.z, n.z))
}

/// The unit vector along `v`, computed without overflow or underflow
/// (`<1e200, 1e200, 0>` and `<1e-200, 0, 0>` have directions); `None` for a
/// zero or non-finite vector.
pub fn unit(v: DVec3) -> Option<DVec3> {
    let big = v.abs().max_element();
    if big == 0.0 || !big.is_finite() {
        return None;
    }
    Some((v / big).normalize())
}

/// [`unit`] rounded to f32 (zero for a vector without a direction).
pub fn unit_f32(v: DVec3) -> Vec3 {
    unit(v).map_or(Vec3::ZERO, |u| u.as_vec3())
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
    fn directions_survive_f32() {
        let u = unit_f32(DVec3::new(3.4e300, 1.0, 0.0));
        assert_eq!(u, Vec3::X);
        let u = unit_f32(DVec3::new(1e-300, 1e-300, 0.0));
        assert!((u.length() - 1.0).abs() < 1e-6);
        assert_eq!(unit_f32(DVec3::ZERO), Vec3::ZERO);
    }

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
        // 256 ulps of 1e4 (ulp = 2^-10): 0.25, on the side the ray leaves to.
        for x in [1e4f32, -1e4] {
            let p = Vec3::new(x, 0.0, 0.0);
            assert_eq!(offset_origin(p, Vec3::X, Vec3::X).x - x, 0.25);
            assert_eq!(offset_origin(p, Vec3::X, -Vec3::X).x - x, -0.25);
        }
        // Near the origin a fixed small step: away from the surface, not zero.
        let small = offset_origin(Vec3::new(1e-3, 0.0, 0.0), Vec3::Y, -Vec3::Y);
        assert!(small.y < 0.0 && small.y > -1e-4, "{small}");
        // A slanted normal moves every coordinate.
        let n = Vec3::new(1.0, 1.0, 1.0).normalize();
        let o = offset_origin(Vec3::splat(3.0), n, n);
        assert!(o.cmpgt(Vec3::splat(3.0)).all());
    }
}
