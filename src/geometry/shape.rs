//! The primitives the renderer intersects, after lowering: transforms are
//! baked in, boxes are six quads (`lower`), meshes are triangles
//! (`lower::mesh`). One file per shape holds its intersection routine and tests:
//! `sphere.rs`, `quad.rs`, `disk.rs`, `triangle.rs`, `plane.rs`, and the
//! curved shapes of the registry `round.rs` (cones and cylinders, tori, one
//! file each in `round/`); this enum dispatches and holds what lights need
//! (area, sampling).

use super::round::Round;
use super::{disk, plane, quad, sphere, triangle, Aabb, Ray};
use glam::{Vec2, Vec3};

/// The geometry of one primitive.
#[derive(Debug, Clone, Copy)]
pub enum Shape {
    /// Sphere with centre and radius.
    Sphere {
        /// Centre at time 0.
        center: Vec3,
        /// Radius.
        radius: f32,
    },
    /// Parallelogram `p + s·e1 + t·e2`, s, t in [0, 1].
    Quad {
        /// Corner.
        p: Vec3,
        /// First edge.
        e1: Vec3,
        /// Second edge.
        e2: Vec3,
        /// Whether the edges are stored swapped (see [`Shape::own_uv`]).
        swapped: bool,
    },
    /// Disk.
    Disk {
        /// Centre.
        center: Vec3,
        /// Unit normal.
        normal: Vec3,
        /// Radius.
        radius: f32,
    },
    /// Triangle `p0, p0 + e1, p0 + e2`.
    Triangle {
        /// First vertex.
        p0: Vec3,
        /// Edge to the second vertex.
        e1: Vec3,
        /// Edge to the third vertex.
        e2: Vec3,
        /// Index into the scene's vertex-attribute tables (vertex normals,
        /// texture coordinates, in the triangle's own vertex order);
        /// `u32::MAX`: none (flat, barycentric UVs).
        attributes: u32,
        /// Whether the second and third vertex are stored swapped (see
        /// [`Shape::own_uv`]).
        swapped: bool,
    },
    /// Infinite plane.
    Plane {
        /// A point on it.
        point: Vec3,
        /// Unit normal.
        normal: Vec3,
    },
    /// A curved shape of the registry ([`Round`]): a cone's or cylinder's
    /// lateral surface (its end disks are disks), a torus.
    Round(Round),
}

// Every primitive's record is 64 bytes (`ir::Prim`): the registry's
// shapes must not make the enum grow.
const _: () = assert!(std::mem::size_of::<Shape>() == 44);

/// Where a ray hits a shape (before shading).
#[derive(Debug, Clone, Copy)]
pub struct ShapeHit {
    /// Ray parameter.
    pub t: f32,
    /// Surface parameters (barycentrics for triangles).
    pub uv: Vec2,
}

impl Shape {
    /// The triangle `p0, p0 + e1, p0 + e2` from `[p0, e1, e2]`, without
    /// vertex normals.
    pub fn flat_triangle([p0, e1, e2]: [Vec3; 3]) -> Shape {
        Shape::Triangle {
            p0,
            e1,
            e2,
            attributes: u32::MAX,
            swapped: false,
        }
    }

    /// The quad `p + s·e1 + t·e2` as given (not swapped).
    pub fn quad(p: Vec3, e1: Vec3, e2: Vec3) -> Shape {
        Shape::Quad {
            p,
            e1,
            e2,
            swapped: false,
        }
    }

    /// Whether the shape's two edges are stored swapped.
    #[inline(always)]
    fn is_swapped(&self) -> bool {
        matches!(
            self,
            Shape::Quad { swapped: true, .. } | Shape::Triangle { swapped: true, .. }
        )
    }

    /// The shape's own surface parameters from those of its stored form.
    ///
    /// A mirroring transform turns `e1 × e2` inwards. Lowering keeps every
    /// surface's outward side (as meshes, boxes and placed groups keep it,
    /// and as Mitsuba 3 transforms a shape's normal) by storing a mirrored
    /// quad or triangle with its edges swapped; the intersection then gives
    /// its parameters swapped too. Everything after the hit (texture
    /// coordinates, vertex attributes, tangents) reads the shape's own
    /// parameters, along the edges the scene gave: a quad's (s, t) along
    /// `edge1` and `edge2`, a triangle's barycentrics of its second and
    /// third vertex in the file's order.
    #[inline(always)]
    pub fn own_uv(&self, uv: Vec2) -> Vec2 {
        if self.is_swapped() {
            Vec2::new(uv.y, uv.x)
        } else {
            uv
        }
    }

    /// A quad's or triangle's own edges (`edge1`, `edge2`, or the edges to
    /// the second and third vertex in the file's order): see
    /// [`Shape::own_uv`].
    pub fn own_edges(&self) -> Option<(Vec3, Vec3)> {
        match *self {
            Shape::Quad { e1, e2, .. } | Shape::Triangle { e1, e2, .. } => {
                Some(if self.is_swapped() {
                    (e2, e1)
                } else {
                    (e1, e2)
                })
            }
            _ => None,
        }
    }

    /// Bounds (infinite for planes).
    pub fn bounds(&self) -> Aabb {
        match *self {
            Shape::Sphere { center, radius } => Aabb {
                min: center - Vec3::splat(radius),
                max: center + Vec3::splat(radius),
            },
            Shape::Quad { p, e1, e2, .. } => Aabb::EMPTY
                .grow(p)
                .grow(p + e1)
                .grow(p + e2)
                .grow(p + e1 + e2),
            Shape::Disk {
                center,
                normal,
                radius,
            } => {
                let e = disk::extent(normal, radius);
                Aabb {
                    min: center - e,
                    max: center + e,
                }
            }
            Shape::Triangle { p0, e1, e2, .. } => Aabb::EMPTY.grow(p0).grow(p0 + e1).grow(p0 + e2),
            Shape::Plane { .. } => Aabb {
                min: Vec3::splat(f32::NEG_INFINITY),
                max: Vec3::splat(f32::INFINITY),
            },
            Shape::Round(r) => r.bounds(),
        }
    }

    /// The closest hit in `(t_min, t_max)` of a ray already moved into the
    /// shape's frame at the ray's time.
    #[inline(always)]
    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<ShapeHit> {
        match *self {
            Shape::Sphere { center, radius } => {
                sphere::intersect(center, radius, ray, t_min, t_max)
            }
            Shape::Quad { p, e1, e2, .. } => quad::intersect(p, e1, e2, ray, t_min, t_max),
            Shape::Triangle { p0, e1, e2, .. } => {
                triangle::intersect(p0, e1, e2, ray, t_min, t_max)
            }
            Shape::Disk {
                center,
                normal,
                radius,
            } => disk::intersect(center, normal, radius, ray, t_min, t_max),
            Shape::Plane { point, normal } => plane::intersect(point, normal, ray, t_min, t_max),
            Shape::Round(_) => self.intersect_curved(ray, t_min, t_max),
        }
    }

    /// [`Shape::intersect`] for the round shapes: one cold call out of the
    /// dispatch, so that the common shapes' code around it keeps its
    /// registers.
    #[cold]
    #[inline(never)]
    fn intersect_curved(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<ShapeHit> {
        match self {
            Shape::Round(r) => r.intersect(ray, t_min, t_max),
            _ => None,
        }
    }

    /// The hit point recomputed on the surface from the hit, accurate to a few
    /// ulps whatever the ray's length (the ray's `o + t·d` carries the error of
    /// `t` times the distance travelled), which keeps `offset_origin` small.
    // `always`, like `intersect`: with the round shapes' arm (out of
    // line) LLVM stopped inlining it into the hit's finishing, +1.3 % of a
    // render's instructions.
    #[inline(always)]
    pub fn surface_point(&self, ray: &Ray, hit: &ShapeHit) -> Vec3 {
        match *self {
            Shape::Sphere { center, radius } => {
                let d = ray.at(hit.t) - center;
                center + d * (radius / d.length())
            }
            Shape::Quad { p, e1, e2, .. } | Shape::Triangle { p0: p, e1, e2, .. } => {
                p + hit.uv.x * e1 + hit.uv.y * e2
            }
            Shape::Disk {
                center: point,
                normal,
                ..
            }
            | Shape::Plane { point, normal } => {
                let q = ray.at(hit.t);
                q - normal * (q - point).dot(normal)
            }
            Shape::Round(ref r) => r.project(ray.at(hit.t)),
        }
    }

    /// The geometric normal at a hit point (unit; outward / along e1 × e2).
    #[inline(always)]
    pub fn normal_at(&self, p: Vec3) -> Vec3 {
        match *self {
            Shape::Sphere { center, .. } => (p - center).normalize(),
            Shape::Quad { e1, e2, .. } | Shape::Triangle { e1, e2, .. } => e1.cross(e2).normalize(),
            Shape::Disk { normal, .. } | Shape::Plane { normal, .. } => normal,
            Shape::Round(ref r) => r.normal_at(p),
        }
    }

    /// Surface area (infinite for planes).
    #[inline]
    pub fn area(&self) -> f32 {
        match *self {
            Shape::Sphere { radius, .. } => 4.0 * std::f32::consts::PI * radius * radius,
            Shape::Quad { e1, e2, .. } => e1.cross(e2).length(),
            Shape::Triangle { e1, e2, .. } => 0.5 * e1.cross(e2).length(),
            Shape::Disk { radius, .. } => std::f32::consts::PI * radius * radius,
            Shape::Plane { .. } => f32::INFINITY,
            Shape::Round(ref r) => r.area(),
        }
    }

    /// A point sampled uniformly by area from `u` in [0,1)², with its normal
    /// and its own surface parameters (as a finished hit there has them: a
    /// quad's (s, t), a triangle's barycentrics, zero for the others; see
    /// [`Shape::own_uv`]).
    pub fn sample_area(&self, u: Vec2) -> (Vec3, Vec3, Vec2) {
        let own = |uv: Vec2, swapped: bool| if swapped { Vec2::new(uv.y, uv.x) } else { uv };
        match *self {
            Shape::Sphere { center, radius } => {
                let n = crate::sampling::warp::uniform_sphere(u);
                (center + radius * n, n, Vec2::ZERO)
            }
            Shape::Quad { p, e1, e2, swapped } => (
                p + u.x * e1 + u.y * e2,
                e1.cross(e2).normalize(),
                own(u, swapped),
            ),
            Shape::Triangle {
                p0,
                e1,
                e2,
                swapped,
                ..
            } => {
                let b = crate::sampling::warp::uniform_triangle(u);
                (
                    p0 + b.x * e1 + b.y * e2,
                    e1.cross(e2).normalize(),
                    own(b, swapped),
                )
            }
            Shape::Disk {
                center,
                normal,
                radius,
            } => {
                let d = crate::sampling::warp::concentric_disk(u);
                let (t, b) = super::orthonormal_basis(normal);
                (center + radius * (d.x * t + d.y * b), normal, Vec2::ZERO)
            }
            Shape::Plane { point, normal } => (point, normal, Vec2::ZERO),
            Shape::Round(ref r) => {
                let (p, n) = r.sample_area(u);
                (p, n, Vec2::ZERO)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::round::{cone::Cone, torus::Torus};

    #[test]
    fn area_samples_lie_on_the_shape() {
        let shapes = [
            Shape::Sphere {
                center: Vec3::ONE,
                radius: 2.0,
            },
            Shape::quad(Vec3::ZERO, Vec3::X, Vec3::Z),
            Shape::Disk {
                center: Vec3::ZERO,
                normal: Vec3::Y,
                radius: 1.0,
            },
            Shape::flat_triangle([Vec3::ZERO, Vec3::X, Vec3::Y]),
            Shape::Round(Round::Cone(Cone {
                base: Vec3::new(0.0, -1.0, 0.5),
                axis: Vec3::new(0.6, 0.0, 0.8),
                height: 1.5,
                r0: 0.7,
                r1: 0.2,
            })),
            Shape::Round(Round::Torus(Torus {
                center: Vec3::ONE,
                axis: Vec3::X,
                major: 1.0,
                minor: 0.3,
            })),
        ];
        for s in shapes {
            for i in 0..16 {
                let u = Vec2::new((i % 4) as f32 / 4.0 + 0.1, (i / 4) as f32 / 4.0 + 0.1);
                let (p, n, _) = s.sample_area(u);
                let r = Ray::new(p + n, -n, 0.0);
                let h = s.intersect(&r, 1e-4, 2.0).expect("sample on the surface");
                assert!((h.t - 1.0).abs() < 1e-3);
            }
        }
    }
}
