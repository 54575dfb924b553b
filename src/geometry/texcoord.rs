//! Texture coordinates (u, v) of a point on each shape, in the shape's own
//! frame (y up, as ptsc's world). Images are addressed with (0, 0) at their
//! bottom-left corner and (1, 1) at the top-right, as in OpenGL, pbrt and
//! OBJ's `vt`; Mitsuba's `bitmap` reads v = 0 at an image's top row (its OBJ
//! loader flips v to match), so its test flips v.
//!
//! | shape | u | v | differs from Mitsuba 3 |
//! |---|---|---|---|
//! | sphere | longitude / 2π: 0 at −z, ¼ at −x, ½ at +z, ¾ at +x (POV-Ray's `map_type spherical` turned to face +z) | latitude, 0 at −y (south pole), 1 at +y | Mitsuba's pole is its local +z, u from +x: the test rotates its sphere |
//! | quad, box face | along `edge1`, 0 to 1 | along `edge2`, 0 to 1 | Mitsuba's `rectangle` has (0, 0) at its (−1, −1) corner: the same with edges along its x and y |
//! | disk | planar: 0.5 + x / 2r | 0.5 + z / 2r | Mitsuba's `disk` is polar (r, φ / 2π) |
//! | triangle | the mesh's vertex UVs interpolated; without any, the barycentrics (b1, b2) | | the same |
//! | plane | planar: x / scale | z / scale | Mitsuba has no infinite plane |
//! | cylinder, cone | the angle around the axis / 2π, from the frame's x towards its z | the height / the full height, 0 at the base | Mitsuba's `cylinder` has u = φ / 2π from its local +x, v along its length: the same up to where φ starts |
//! | torus | the angle around the axis / 2π, as a cylinder's | the angle around the tube / 2π, 0 on the outer equator, ¼ on top | Mitsuba has no torus |
//!
//! A disk's and a plane's frame has their normal as y and x, z from
//! [`axis_frame`] of it, in the object's own frame: for a normal +y (a
//! floor), u runs along +x and v along −z, away from a camera on +z, so an
//! image on the floor is seen upright.
//!
//! Sphere, disk and plane take a point already moved into their frame;
//! quads and triangles are parametric, so their intersection's (s, t) or
//! barycentrics are their texture coordinates.

use glam::{Vec2, Vec3};
use std::f32::consts::{FRAC_1_PI, TAU};

/// The frame (x, z) about a unit axis `n` that the texture coordinates of
/// disks, planes, cylinders, cones and tori are laid in: x is world +x made
/// perpendicular to `n` (∓z instead when `n` lies within 26° of ±x), and
/// z = n × x. For an axis +y, x is +x and z is −z (a floor's image is
/// upright seen from +z); for ±x, z is +y (a wall's image is upright seen
/// from the side it faces). The frame turns continuously with the axis except
/// across that 26° cone around ±x, where no axis an author writes lies:
/// the axis of an object turned or placed by a rotation, recovered in its
/// own frame with rounding errors, keeps its frame (an orthonormal basis
/// that branches on the sign of n.z, as the renderer's local frames do,
/// would flip for every axis in the plane z = 0, a vertical cylinder's
/// among them).
pub fn axis_frame(n: Vec3) -> (Vec3, Vec3) {
    let reference = if n.x.abs() < 0.9 {
        Vec3::X
    } else {
        -n.x.signum() * Vec3::Z
    };
    let x = (reference - n * n.dot(reference)).normalize();
    (x, n.cross(x))
}

/// Texture coordinates of the point of a sphere in direction `dir` (unit)
/// from its centre, in the sphere's frame: u is the longitude, 0 (the seam)
/// at −z, then −x (¼), +z (½), +x (¾), so that an equirectangular image
/// seen from +z has its centre column facing the camera and is not
/// mirrored; v is the latitude from the south pole (−y, 0) to the north
/// pole (+y, 1).
pub fn sphere(dir: Vec3) -> Vec2 {
    // The angle from −z towards −x (the left of a camera on +z), in [0, 2π).
    let phi = (-dir.x).atan2(-dir.z);
    let u = if phi < 0.0 { phi + TAU } else { phi } / TAU;
    let v = 1.0 - dir.y.clamp(-1.0, 1.0).acos() * FRAC_1_PI;
    Vec2::new(u.clamp(0.0, 1.0), v)
}

/// Texture coordinates of the point `local` of a disk of `radius`, given
/// in the disk's frame (its centre at the origin, its normal along +y):
/// planar, the disk inscribed in the unit square.
pub fn disk(local: Vec3, radius: f32) -> Vec2 {
    let scale = 0.5 / radius;
    Vec2::new(0.5 + local.x * scale, 0.5 + local.z * scale)
}

/// Texture coordinates of the point `local` of an infinite plane, given in
/// the plane's frame (normal along +y): one unit square of texture every
/// `scale` units of the plane.
pub fn plane(local: Vec3, scale: f32) -> Vec2 {
    Vec2::new(local.x, local.z) / scale
}

/// The angle of (x, z) from +x towards +z, as a fraction of a turn in [0, 1).
fn turn(x: f32, z: f32) -> f32 {
    let phi = z.atan2(x);
    (if phi < 0.0 { phi + TAU } else { phi } / TAU).clamp(0.0, 1.0)
}

/// Texture coordinates of the point `local` of a cylinder or cone of
/// `height`, given relative to the centre of its base in the frame of
/// its axis (y along the axis, x and z across, as for a disk).
pub fn cone(local: Vec3, height: f32) -> Vec2 {
    Vec2::new(turn(local.x, local.z), local.y / height)
}

/// (∂p/∂u, ∂p/∂v) of [`cone`]'s mapping at `local`, in the same frame, for
/// a cone whose radius grows by `dr` from base to top.
pub fn cone_derivatives(local: Vec3, height: f32, dr: f32) -> (Vec3, Vec3) {
    let rho = (local.x * local.x + local.z * local.z).sqrt();
    let dpdu = TAU * Vec3::new(-local.z, 0.0, local.x);
    if rho == 0.0 {
        return (dpdu, Vec3::new(0.0, height, 0.0));
    }
    (
        dpdu,
        Vec3::new(dr * local.x / rho, height, dr * local.z / rho),
    )
}

/// Texture coordinates of the point `local` of a torus of radius `major`,
/// given relative to its centre in the frame of its axis (y along it).
pub fn torus(local: Vec3, major: f32) -> Vec2 {
    let rho = (local.x * local.x + local.z * local.z).sqrt();
    Vec2::new(turn(local.x, local.z), turn(rho - major, local.y))
}

/// (∂p/∂u, ∂p/∂v) of [`torus`]'s mapping at `local`, in the same frame.
pub fn torus_derivatives(local: Vec3, major: f32) -> (Vec3, Vec3) {
    let rho = (local.x * local.x + local.z * local.z).sqrt();
    let dpdu = TAU * Vec3::new(-local.z, 0.0, local.x);
    if rho == 0.0 {
        return (dpdu, Vec3::Y);
    }
    let (cx, cz) = (local.x / rho, local.z / rho);
    // Around the tube: r(−sin θ · radial + cos θ · axis), with r sin θ = y
    // and r cos θ = ρ − R.
    let dpdv = TAU * Vec3::new(-local.y * cx, rho - major, -local.y * cz);
    (dpdu, dpdv)
}

/// Texture coordinates of a triangle's point with barycentrics (b1, b2)
/// (weights of the second and third vertex) from its vertices' `uvs`.
pub fn triangle(barycentrics: Vec2, uvs: [Vec2; 3]) -> Vec2 {
    let b0 = 1.0 - barycentrics.x - barycentrics.y;
    b0 * uvs[0] + barycentrics.x * uvs[1] + barycentrics.y * uvs[2]
}

/// The texture coordinates a triangle without vertex UVs gives its
/// vertices: its barycentrics are its texture coordinates.
pub const TRIANGLE_DEFAULT: [Vec2; 3] = [Vec2::ZERO, Vec2::X, Vec2::Y];

/// How a sphere's point moves with its texture coordinates: (∂p/∂u,
/// ∂p/∂v) at the point `local` (relative to the centre, in the sphere's
/// frame) of [`sphere`]'s mapping. u is the longitude φ / 2π, so ∂p/∂u is
/// 2π times the tangent of the parallel, (z, 0, −x); v is 1 − θ / π, so
/// ∂p/∂v is π times the tangent of the meridian towards the north pole.
/// Both vanish at the poles.
pub fn sphere_derivatives(local: Vec3) -> (Vec3, Vec3) {
    let rho = (local.x * local.x + local.z * local.z).sqrt();
    let dpdu = TAU * Vec3::new(local.z, 0.0, -local.x);
    if rho == 0.0 {
        return (dpdu, Vec3::ZERO);
    }
    let k = -local.y / rho;
    let dpdv = std::f32::consts::PI * Vec3::new(k * local.x, rho, k * local.z);
    (dpdu, dpdv)
}

/// (∂p/∂u, ∂p/∂v) of a triangle with edges `e1` = p1 − p0 and `e2` =
/// p2 − p0 whose vertices have texture coordinates `uvs` (pbrt-v4's
/// `Triangle::InteractionFromIntersection`: the 2 × 2 system of the edges
/// in (u, v)); `None` when the UVs are degenerate (the triangle is a line
/// or a point in (u, v)).
pub fn triangle_derivatives(e1: Vec3, e2: Vec3, uvs: [Vec2; 3]) -> Option<(Vec3, Vec3)> {
    let (duv1, duv2) = (uvs[1] - uvs[0], uvs[2] - uvs[0]);
    let det = duv1.x * duv2.y - duv1.y * duv2.x;
    if det.abs() < 1e-12 {
        return None;
    }
    let inv = 1.0 / det;
    let dpdu = (duv2.y * e1 - duv1.y * e2) * inv;
    let dpdv = (duv1.x * e2 - duv2.x * e1) * inv;
    (dpdu.is_finite() && dpdv.is_finite()).then_some((dpdu, dpdv))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec2, b: Vec2) -> bool {
        (a - b).abs().max_element() < 1e-5
    }

    #[test]
    fn sphere_coordinates_at_known_points() {
        // Facing a camera on +z: the middle of the image, on the equator.
        assert!(close(sphere(Vec3::Z), Vec2::new(0.5, 0.5)));
        // Poles: v is 0 at the bottom, 1 at the top.
        assert!((sphere(Vec3::Y).y - 1.0).abs() < 1e-6);
        assert!(sphere(-Vec3::Y).y.abs() < 1e-6);
        // A quarter turn towards +x is a quarter further in u.
        assert!(close(sphere(Vec3::X), Vec2::new(0.75, 0.5)));
        assert!(close(sphere(-Vec3::X), Vec2::new(0.25, 0.5)));
        // The seam is at −z: both sides of it, u near 0 and near 1.
        let just_past = sphere(Vec3::new(1e-3, 0.0, -1.0).normalize());
        let just_before = sphere(Vec3::new(-1e-3, 0.0, -1.0).normalize());
        assert!(just_past.x > 0.999 && just_before.x < 0.001);
        // 45° north.
        let north = sphere(Vec3::new(0.0, 1.0, 1.0).normalize());
        assert!(close(north, Vec2::new(0.5, 0.75)));
        // Always in the unit square.
        for i in 0..1000 {
            let t = i as f32 * 0.137;
            let d = Vec3::new(t.sin() * (3.0 * t).cos(), (2.0 * t).cos(), t.cos()).normalize();
            let uv = sphere(d);
            assert!((0.0..=1.0).contains(&uv.x) && (0.0..=1.0).contains(&uv.y));
        }
    }

    #[test]
    fn disk_plane_and_triangle_coordinates_at_known_points() {
        assert!(close(disk(Vec3::ZERO, 2.0), Vec2::splat(0.5)));
        assert!(close(
            disk(Vec3::new(2.0, 0.0, 0.0), 2.0),
            Vec2::new(1.0, 0.5)
        ));
        assert!(close(
            disk(Vec3::new(0.0, 0.0, -2.0), 2.0),
            Vec2::new(0.5, 0.0)
        ));
        assert!(close(
            plane(Vec3::new(3.0, 0.0, -1.5), 1.5),
            Vec2::new(2.0, -1.0)
        ));
        let uvs = [
            Vec2::new(0.1, 0.2),
            Vec2::new(0.9, 0.2),
            Vec2::new(0.1, 0.8),
        ];
        assert!(close(triangle(Vec2::ZERO, uvs), uvs[0]));
        assert!(close(triangle(Vec2::X, uvs), uvs[1]));
        assert!(close(triangle(Vec2::Y, uvs), uvs[2]));
        assert!(close(
            triangle(Vec2::splat(1.0 / 3.0), uvs),
            (uvs[0] + uvs[1] + uvs[2]) / 3.0
        ));
        let b = Vec2::new(0.3, 0.6);
        assert!(close(triangle(b, TRIANGLE_DEFAULT), b));
    }

    #[test]
    fn the_axis_frame_is_orthonormal_documented_and_continuous_across_z_0() {
        let (x, z) = axis_frame(Vec3::Y);
        assert!((x - Vec3::X).length() < 1e-6 && (z + Vec3::Z).length() < 1e-6);
        // Walls facing ±x see their images upright (v up).
        for n in [Vec3::X, -Vec3::X] {
            assert!((axis_frame(n).1 - Vec3::Y).length() < 1e-6, "{n}");
        }
        for n in [
            Vec3::X,
            -Vec3::X,
            Vec3::Z,
            Vec3::new(0.3, 0.9, -0.2).normalize(),
        ] {
            let (x, z) = axis_frame(n);
            assert!(x.is_normalized() && z.is_normalized());
            assert!(x.dot(z).abs() < 1e-6 && x.dot(n).abs() < 1e-6 && z.dot(n).abs() < 1e-6);
            assert!((n.cross(x) - z).length() < 1e-5, "z = n × x");
        }
        // An axis in the plane z = 0 and its neighbours a rounding error
        // away on either side keep one frame.
        let n = Vec3::new(0.1, 1.1, 0.0).normalize();
        for dz in [1e-7f32, -1e-7] {
            let (a, b) = (axis_frame(n), axis_frame((n + Vec3::Z * dz).normalize()));
            assert!((a.0 - b.0).length() < 1e-5 && (a.1 - b.1).length() < 1e-5);
        }
    }

    /// A derivative checked against a finite difference of the mapping.
    fn near(a: Vec3, b: Vec3, tolerance: f32) -> bool {
        (a - b).length() <= tolerance * (1.0 + b.length())
    }

    #[test]
    fn sphere_derivatives_match_finite_differences() {
        // Points p(u, v) on a sphere of radius 2 from the inverse mapping.
        let point = |u: f32, v: f32| {
            let (theta, phi) = ((1.0 - v) * std::f32::consts::PI, u * TAU);
            2.0 * Vec3::new(
                -theta.sin() * phi.sin(),
                theta.cos(),
                -theta.sin() * phi.cos(),
            )
        };
        for &(u, v) in &[(0.5, 0.5), (0.1, 0.3), (0.8, 0.9), (0.3, 0.05)] {
            let p = point(u, v);
            assert!(close(sphere(p / 2.0), Vec2::new(u, v)));
            let h = 1e-3;
            let du = (point(u + h, v) - point(u - h, v)) / (2.0 * h);
            let dv = (point(u, v + h) - point(u, v - h)) / (2.0 * h);
            let (dpdu, dpdv) = sphere_derivatives(p);
            assert!(near(dpdu, du, 1e-2), "{dpdu} vs {du}");
            assert!(near(dpdv, dv, 1e-2), "{dpdv} vs {dv}");
        }
        // Facing +z: u runs towards +x, v up.
        let (dpdu, dpdv) = sphere_derivatives(Vec3::Z);
        assert!(dpdu.x > 0.0 && dpdv.y > 0.0);
        assert_eq!(sphere_derivatives(Vec3::Y).1, Vec3::ZERO);
    }

    #[test]
    fn triangle_derivatives_invert_the_uv_mapping() {
        let (e1, e2) = (Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 0.0, -3.0));
        // Default UVs are the barycentrics: the edges themselves.
        let (dpdu, dpdv) = triangle_derivatives(e1, e2, TRIANGLE_DEFAULT).unwrap();
        assert!(near(dpdu, e1, 1e-6) && near(dpdv, e2, 1e-6));
        // Swapped and scaled UVs.
        let uvs = [Vec2::ZERO, Vec2::new(0.0, 0.5), Vec2::new(0.25, 0.0)];
        let (dpdu, dpdv) = triangle_derivatives(e1, e2, uvs).unwrap();
        assert!(near(dpdu, e2 * 4.0, 1e-6) && near(dpdv, e1 * 2.0, 1e-6));
        let line = [Vec2::ZERO, Vec2::X, Vec2::X * 2.0];
        assert!(triangle_derivatives(e1, e2, line).is_none());
    }
}
