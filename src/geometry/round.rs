//! The registry of round shapes: the curved shapes stored exactly by
//! centres, axes and radii (cones and cylinders, tori, capsules), which
//! keep their kind only under similarity transforms (an uneven scale would
//! make an elliptic one). The checker builds a shape's object-space
//! description in f64 ([`RoundDesc`]), lowering places it under the
//! object's transform ([`RoundDesc::place`]) as world-space f32 primitives
//! ([`Round`], inside `Shape::Round`), and everything after (the BVH,
//! lights, texture frames, the cache) asks [`Round`] and [`RoundDesc`],
//! never a kind.
//!
//! Adding a round shape: its file in `round/` with its two types (the
//! description implementing [`Description`], the primitive implementing
//! [`Surface`]) and their tests, then its `mod` line and its one line in
//! [`registry!`]'s list below. Spheres and disks are round too but stay
//! plain variants of `Shape` (hot paths: one inlined test each); the
//! round shapes here sit behind one cold call in `Shape::intersect`.

pub mod capsule;
pub mod cone;
pub mod torus;

use super::shape::{Shape, ShapeHit};
use super::{Aabb, Ray};
use glam::{DMat4, Vec2, Vec3};
use std::hash::Hasher;

/// A round shape's object-space description, as the checker makes it.
pub trait Description {
    /// Its name for messages (`cylinder` and `cone` share one kind).
    fn name(&self) -> &'static str;
    /// Its primitives under the similarity `m` of uniform scale `scale`
    /// (an end disk too for a closed cylinder), pushed onto `out`.
    fn place(&self, m: &DMat4, scale: f64, out: &mut Vec<Shape>);
    /// Every number it is made of, in a fixed order, for the geometry
    /// cache's key (an equal list is the same shape).
    fn numbers(&self) -> Vec<f64>;
}

/// A round primitive in the world (or a group's frame), in f32.
///
/// Its `intersect`, `project`, `normal_at` and `area` are
/// `#[inline(never)]`: [`Round`]'s dispatch is inlined into `Shape`'s
/// matches, which run for every primitive, and a round shape's code
/// inlined there would cost the others' registers (docs/performance.md,
/// "Instancing").
pub trait Surface {
    /// Its bounding box.
    fn bounds(&self) -> Aabb;
    /// The closest hit in `(t_min, t_max)`, from outside or inside; a hit's
    /// surface parameters are zero (its texture coordinates are computed
    /// from the point, see [`Surface::texcoord`]).
    fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<ShapeHit>;
    /// The point of the surface nearest `p` (a hit point moved onto the
    /// surface, accurate to a few ulps: see `Shape::surface_point`).
    fn project(&self, p: Vec3) -> Vec3;
    /// The outward unit normal at the surface point `p`.
    fn normal_at(&self, p: Vec3) -> Vec3;
    /// Its area.
    fn area(&self) -> f32;
    /// A point uniform by area from `u` in [0,1)², with its outward
    /// normal (the light's pdf by area is then 1 / area).
    fn sample_area(&self, u: Vec2) -> (Vec3, Vec3);
    /// The origin and the axis (any length: it is unit in the record's
    /// frame) that its texture coordinates are laid about: points are
    /// given to [`Surface::texcoord`] in the frame of
    /// `texcoord::axis_frame` of the axis, in the object's own frame.
    fn uv_frame(&self) -> (Vec3, Vec3);
    /// The texture coordinates of the point `local` (relative to the
    /// origin, y along the axis, in the object's frame, whose lengths are
    /// `scale` times the record's).
    fn texcoord(&self, local: Vec3, scale: f32) -> Vec2;
    /// (∂p/∂u, ∂p/∂v) of [`Surface::texcoord`] at `local`, in the same
    /// frame.
    fn texcoord_derivatives(&self, local: Vec3, scale: f32) -> (Vec3, Vec3);
}

/// Declares the round shapes: for each, a variant of [`RoundDesc`] holding
/// its description and one of [`Round`] holding its primitive, and one
/// match per method forwarding to the kind's [`Description`] or
/// [`Surface`].
macro_rules! registry {
    ($($(#[$doc:meta])* $kind:ident($desc:ty, $prim:ty),)*) => {
        /// A round shape's object-space description (f64), one variant per
        /// kind.
        #[derive(Debug, Clone, PartialEq)]
        pub enum RoundDesc {
            $($(#[$doc])* $kind($desc),)*
        }

        /// A round primitive (f32, placed), one variant per kind.
        #[derive(Debug, Clone, Copy)]
        pub enum Round {
            $($(#[$doc])* $kind($prim),)*
        }

        impl RoundDesc {
            /// Its name for messages.
            pub fn name(&self) -> &'static str {
                match self { $(RoundDesc::$kind(d) => d.name(),)* }
            }

            /// Its primitives under `m`, pushed onto `out`, or `Err` when
            /// `m` is not a similarity (it scales unevenly or shears).
            pub fn place(&self, m: &DMat4, out: &mut Vec<Shape>) -> Result<(), NotSimilar> {
                let scale = similarity_scale(m).ok_or(NotSimilar)?;
                match self { $(RoundDesc::$kind(d) => d.place(m, scale, out),)* }
                Ok(())
            }

            /// Feeds its kind and numbers to the geometry cache's hasher.
            pub fn hash_key(&self, h: &mut impl Hasher) {
                let (kind, numbers) = match self {
                    $(RoundDesc::$kind(d) => (stringify!($kind), d.numbers()),)*
                };
                h.write(kind.as_bytes());
                numbers.iter().for_each(|x| h.write_u64(x.to_bits()));
            }
        }

        impl Round {
            /// See [`Surface::bounds`].
            pub fn bounds(&self) -> Aabb {
                match self { $(Round::$kind(s) => s.bounds(),)* }
            }

            /// See [`Surface::intersect`].
            #[inline(always)]
            pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<ShapeHit> {
                match self { $(Round::$kind(s) => s.intersect(ray, t_min, t_max),)* }
            }

            /// See [`Surface::project`].
            #[inline(always)]
            pub fn project(&self, p: Vec3) -> Vec3 {
                match self { $(Round::$kind(s) => s.project(p),)* }
            }

            /// See [`Surface::normal_at`].
            #[inline(always)]
            pub fn normal_at(&self, p: Vec3) -> Vec3 {
                match self { $(Round::$kind(s) => s.normal_at(p),)* }
            }

            /// See [`Surface::area`].
            #[inline(always)]
            pub fn area(&self) -> f32 {
                match self { $(Round::$kind(s) => s.area(),)* }
            }

            /// See [`Surface::sample_area`].
            pub fn sample_area(&self, u: Vec2) -> (Vec3, Vec3) {
                match self { $(Round::$kind(s) => s.sample_area(u),)* }
            }

            /// See [`Surface::uv_frame`].
            pub fn uv_frame(&self) -> (Vec3, Vec3) {
                match self { $(Round::$kind(s) => s.uv_frame(),)* }
            }

            /// See [`Surface::texcoord`].
            pub fn texcoord(&self, local: Vec3, scale: f32) -> Vec2 {
                match self { $(Round::$kind(s) => s.texcoord(local, scale),)* }
            }

            /// See [`Surface::texcoord_derivatives`].
            pub fn texcoord_derivatives(&self, local: Vec3, scale: f32) -> (Vec3, Vec3) {
                match self { $(Round::$kind(s) => s.texcoord_derivatives(local, scale),)* }
            }
        }
    };
}

registry! {
    /// A cone, a truncated cone or (equal radii) a cylinder.
    Cone(cone::ConeDesc, cone::Cone),
    /// A torus.
    Torus(torus::TorusDesc, torus::Torus),
    /// A capsule: a cylinder closed by two hemispheres.
    Capsule(capsule::CapsuleDesc, capsule::Capsule),
}

/// The refusal of [`RoundDesc::place`]: the transform is not a similarity.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct NotSimilar;

/// The uniform scale factor of a similarity transform, or `None` if the
/// linear part shears or scales unevenly.
pub fn similarity_scale(m: &DMat4) -> Option<f64> {
    let (x, y, z) = (
        m.x_axis.truncate(),
        m.y_axis.truncate(),
        m.z_axis.truncate(),
    );
    let s = x.length();
    let ok = (y.length() - s).abs() <= 1e-9 * s.max(1.0)
        && (z.length() - s).abs() <= 1e-9 * s.max(1.0)
        && x.dot(y).abs() <= 1e-9 * s * s
        && y.dot(z).abs() <= 1e-9 * s * s
        && x.dot(z).abs() <= 1e-9 * s * s;
    ok.then_some(s)
}

#[cfg(test)]
mod tests {
    use super::cone::ConeDesc;
    use super::torus::TorusDesc;
    use super::*;
    use glam::DVec3;
    use std::hash::DefaultHasher;

    fn cylinder(open: bool) -> RoundDesc {
        RoundDesc::Cone(ConeDesc {
            base: DVec3::ZERO,
            top: DVec3::Y,
            base_radius: 0.5,
            top_radius: 0.5,
            open,
        })
    }

    fn torus() -> RoundDesc {
        RoundDesc::Torus(TorusDesc {
            center: DVec3::ZERO,
            axis: DVec3::Y,
            major: 1.0,
            minor: 0.25,
        })
    }

    #[test]
    fn placing_takes_similarities_only_and_scales_the_radii() {
        let m = DMat4::from_scale_rotation_translation(
            DVec3::splat(2.0),
            glam::DQuat::from_rotation_x(0.3),
            DVec3::new(1.0, 2.0, 3.0),
        );
        let mut out = Vec::new();
        torus().place(&m, &mut out).unwrap();
        let [Shape::Round(Round::Torus(t))] = out[..] else {
            panic!("{out:?}")
        };
        assert_eq!((t.major, t.minor), (2.0, 0.5));
        assert!((t.area() - 4.0 * std::f32::consts::PI.powi(2)).abs() < 1e-4);
        let uneven = DMat4::from_scale(DVec3::new(1.0, 2.0, 1.0));
        assert_eq!(torus().place(&uneven, &mut out), Err(NotSimilar));
        assert_eq!(out.len(), 1, "nothing placed when refused");
        // A closed cylinder brings its two end disks.
        out.clear();
        cylinder(false).place(&DMat4::IDENTITY, &mut out).unwrap();
        cylinder(true).place(&DMat4::IDENTITY, &mut out).unwrap();
        let disks = out.iter().filter(|s| matches!(s, Shape::Disk { .. }));
        assert_eq!((out.len(), disks.count()), (4, 2));
    }

    #[test]
    fn names_and_cache_keys() {
        assert_eq!(cylinder(false).name(), "cylinder");
        assert_eq!(torus().name(), "torus");
        let mut cone = cylinder(false);
        if let RoundDesc::Cone(c) = &mut cone {
            c.top_radius = 0.0;
        }
        assert_eq!(cone.name(), "cone");
        let key = |d: &RoundDesc| {
            let mut h = DefaultHasher::new();
            d.hash_key(&mut h);
            h.finish()
        };
        assert_eq!(key(&torus()), key(&torus()));
        let all = [cylinder(false), cylinder(true), cone, torus()].map(|d| key(&d));
        for (i, a) in all.iter().enumerate() {
            assert!(all[i + 1..].iter().all(|b| b != a), "{all:?}");
        }
    }
}
