//! The primitives the renderer intersects, after lowering: transforms are
//! baked in, boxes are six quads, meshes are triangles.
//!
//! Formulas: sphere (pbrt-v4 §6.2, with the numerically careful discriminant of
//! Haines et al., Ray Tracing Gems ch. 7), triangle (Möller–Trumbore 1997),
//! quad and disk (plane intersection plus barycentric/radial test).

use super::{Aabb, Ray};
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
        /// Index into the vertex-normal table (`u32::MAX` = flat).
        normals: u32,
    },
    /// Infinite plane.
    Plane {
        /// A point on it.
        point: Vec3,
        /// Unit normal.
        normal: Vec3,
    },
}

/// Where a ray hits a shape (before shading).
#[derive(Debug, Clone, Copy)]
pub struct ShapeHit {
    /// Ray parameter.
    pub t: f32,
    /// Surface parameters (barycentrics for triangles).
    pub uv: Vec2,
}

impl Shape {
    /// Bounds (infinite for planes).
    pub fn bounds(&self) -> Aabb {
        match *self {
            Shape::Sphere { center, radius } => Aabb {
                min: center - Vec3::splat(radius),
                max: center + Vec3::splat(radius),
            },
            Shape::Quad { p, e1, e2 } => Aabb::EMPTY
                .grow(p)
                .grow(p + e1)
                .grow(p + e2)
                .grow(p + e1 + e2),
            Shape::Disk {
                center,
                normal,
                radius,
            } => {
                // Extent of a disk along each axis: r·sqrt(1 − n_i²).
                let k = (Vec3::ONE - normal * normal).max(Vec3::ZERO);
                let e = radius * Vec3::new(k.x.sqrt(), k.y.sqrt(), k.z.sqrt());
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
        }
    }

    /// The closest hit in `(t_min, t_max)` of a ray already moved into the
    /// shape's frame at the ray's time.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<ShapeHit> {
        match *self {
            Shape::Sphere { center, radius } => {
                let oc = ray.o - center;
                let a = ray.d.length_squared();
                let b = oc.dot(ray.d);
                // Ray Tracing Gems ch. 7: compute the discriminant from the
                // perpendicular distance, which is accurate for far rays.
                let perp = oc - (b / a) * ray.d;
                let disc = radius * radius - perp.length_squared();
                if disc < 0.0 {
                    return None;
                }
                // Roots of a·t² + 2b·t + c = 0 with b² − ac = a·disc, in the
                // cancellation-free form t0 = q/a, t1 = c/q.
                let sq = (a * disc).sqrt();
                let q = -(b + sq.copysign(b));
                let c = oc.length_squared() - radius * radius;
                let (mut t0, mut t1) = (q / a, if q != 0.0 { c / q } else { 0.0 });
                if t0 > t1 {
                    std::mem::swap(&mut t0, &mut t1);
                }
                let t = if t0 > t_min && t0 < t_max {
                    t0
                } else if t1 > t_min && t1 < t_max {
                    t1
                } else {
                    return None;
                };
                Some(ShapeHit { t, uv: Vec2::ZERO })
            }
            Shape::Quad { p, e1, e2 } => {
                let (t, u, v) = parallelogram(ray, p, e1, e2)?;
                (t > t_min && t < t_max && (0.0..=1.0).contains(&u) && (0.0..=1.0).contains(&v))
                    .then_some(ShapeHit {
                        t,
                        uv: Vec2::new(u, v),
                    })
            }
            Shape::Triangle { p0, e1, e2, .. } => {
                let (t, u, v) = parallelogram(ray, p0, e1, e2)?;
                (t > t_min && t < t_max && u >= 0.0 && v >= 0.0 && u + v <= 1.0).then_some(
                    ShapeHit {
                        t,
                        uv: Vec2::new(u, v),
                    },
                )
            }
            Shape::Disk {
                center,
                normal,
                radius,
            } => {
                let denom = normal.dot(ray.d);
                if denom == 0.0 {
                    return None;
                }
                let t = (center - ray.o).dot(normal) / denom;
                if !(t > t_min && t < t_max) {
                    return None;
                }
                ((ray.at(t) - center).length_squared() <= radius * radius)
                    .then_some(ShapeHit { t, uv: Vec2::ZERO })
            }
            Shape::Plane { point, normal } => {
                let denom = normal.dot(ray.d);
                if denom == 0.0 {
                    return None;
                }
                let t = (point - ray.o).dot(normal) / denom;
                (t > t_min && t < t_max).then_some(ShapeHit { t, uv: Vec2::ZERO })
            }
        }
    }

    /// The hit point recomputed on the surface from the hit, accurate to a few
    /// ulps whatever the ray's length (the ray's `o + t·d` carries the error of
    /// `t` times the distance travelled), which keeps `offset_origin` small.
    #[inline]
    pub fn surface_point(&self, ray: &Ray, hit: &ShapeHit) -> Vec3 {
        match *self {
            Shape::Sphere { center, radius } => {
                let d = ray.at(hit.t) - center;
                center + d * (radius / d.length())
            }
            Shape::Quad { p, e1, e2 } | Shape::Triangle { p0: p, e1, e2, .. } => {
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
        }
    }

    /// The geometric normal at a hit point (unit; outward / along e1 × e2).
    pub fn normal_at(&self, p: Vec3) -> Vec3 {
        match *self {
            Shape::Sphere { center, .. } => (p - center).normalize(),
            Shape::Quad { e1, e2, .. } | Shape::Triangle { e1, e2, .. } => e1.cross(e2).normalize(),
            Shape::Disk { normal, .. } | Shape::Plane { normal, .. } => normal,
        }
    }

    /// Surface area (infinite for planes).
    pub fn area(&self) -> f32 {
        match *self {
            Shape::Sphere { radius, .. } => 4.0 * std::f32::consts::PI * radius * radius,
            Shape::Quad { e1, e2, .. } => e1.cross(e2).length(),
            Shape::Triangle { e1, e2, .. } => 0.5 * e1.cross(e2).length(),
            Shape::Disk { radius, .. } => std::f32::consts::PI * radius * radius,
            Shape::Plane { .. } => f32::INFINITY,
        }
    }

    /// A point sampled uniformly by area from `u` in [0,1)², with its normal.
    pub fn sample_area(&self, u: Vec2) -> (Vec3, Vec3) {
        match *self {
            Shape::Sphere { center, radius } => {
                let n = crate::render::sampling::uniform_sphere(u);
                (center + radius * n, n)
            }
            Shape::Quad { p, e1, e2 } => (p + u.x * e1 + u.y * e2, e1.cross(e2).normalize()),
            Shape::Triangle { p0, e1, e2, .. } => {
                let b = crate::render::sampling::uniform_triangle(u);
                (p0 + b.x * e1 + b.y * e2, e1.cross(e2).normalize())
            }
            Shape::Disk {
                center,
                normal,
                radius,
            } => {
                let d = crate::render::sampling::concentric_disk(u);
                let (t, b) = super::orthonormal_basis(normal);
                (center + radius * (d.x * t + d.y * b), normal)
            }
            Shape::Plane { point, normal } => (point, normal),
        }
    }
}

/// Möller–Trumbore on the parallelogram spanned by `e1`, `e2`: returns t and
/// the coordinates (u, v) of the hit in that basis.
#[inline]
fn parallelogram(ray: &Ray, p: Vec3, e1: Vec3, e2: Vec3) -> Option<(f32, f32, f32)> {
    let pv = ray.d.cross(e2);
    let det = e1.dot(pv);
    if det.abs() < 1e-20 {
        return None;
    }
    let inv = 1.0 / det;
    let tv = ray.o - p;
    let u = tv.dot(pv) * inv;
    let qv = tv.cross(e1);
    let v = ray.d.dot(qv) * inv;
    let t = e2.dot(qv) * inv;
    Some((t, u, v))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ray(o: [f32; 3], d: [f32; 3]) -> Ray {
        Ray::new(Vec3::from(o), Vec3::from(d).normalize(), 0.0)
    }

    #[test]
    fn sphere_hit_miss_inside_grazing() {
        let s = Shape::Sphere {
            center: Vec3::ZERO,
            radius: 1.0,
        };
        let h = s
            .intersect(&ray([0., 0., 5.], [0., 0., -1.]), 1e-4, f32::INFINITY)
            .unwrap();
        assert!((h.t - 4.0).abs() < 1e-5);
        assert!(s
            .intersect(&ray([0., 2., 5.], [0., 0., -1.]), 1e-4, f32::INFINITY)
            .is_none());
        let inside = s
            .intersect(&ray([0., 0., 0.], [1., 0., 0.]), 1e-4, f32::INFINITY)
            .unwrap();
        assert!((inside.t - 1.0).abs() < 1e-5);
        let graze = s.intersect(&ray([0., 0.9999, 5.], [0., 0., -1.]), 1e-4, f32::INFINITY);
        assert!(graze.is_some());
        // Far away and small: the careful discriminant still hits.
        let far = Shape::Sphere {
            center: Vec3::new(0., 0., -1e5),
            radius: 0.5,
        };
        assert!(far
            .intersect(&ray([0., 0.4, 0.], [0., 0., -1.]), 1e-4, f32::INFINITY)
            .is_some());
    }

    #[test]
    fn quad_and_triangle() {
        let q = Shape::Quad {
            p: Vec3::new(-1., 0., -1.),
            e1: Vec3::new(0., 0., 2.),
            e2: Vec3::new(2., 0., 0.),
        };
        assert!((q.normal_at(Vec3::ZERO) - Vec3::Y).length() < 1e-6);
        let h = q
            .intersect(&ray([0.5, 1., 0.5], [0., -1., 0.]), 1e-4, f32::INFINITY)
            .unwrap();
        assert!((h.t - 1.0).abs() < 1e-6);
        assert!(q
            .intersect(&ray([1.5, 1., 0.], [0., -1., 0.]), 1e-4, f32::INFINITY)
            .is_none());
        // Hit from behind: quads are two-sided for intersection.
        assert!(q
            .intersect(&ray([0., -1., 0.], [0., 1., 0.]), 1e-4, f32::INFINITY)
            .is_some());
        // Parallel (grazing) rays miss.
        assert!(q
            .intersect(&ray([0., 0., -5.], [0., 0., 1.]), 1e-4, f32::INFINITY)
            .is_none());
        let t = Shape::Triangle {
            p0: Vec3::ZERO,
            e1: Vec3::X,
            e2: Vec3::Y,
            normals: u32::MAX,
        };
        assert!(t
            .intersect(&ray([0.2, 0.2, 1.], [0., 0., -1.]), 1e-4, f32::INFINITY)
            .is_some());
        assert!(t
            .intersect(&ray([0.8, 0.8, 1.], [0., 0., -1.]), 1e-4, f32::INFINITY)
            .is_none());
    }

    #[test]
    fn disk_and_plane() {
        let d = Shape::Disk {
            center: Vec3::ZERO,
            normal: Vec3::Y,
            radius: 1.0,
        };
        assert!(d
            .intersect(&ray([0.5, 1., 0.5], [0., -1., 0.]), 1e-4, f32::INFINITY)
            .is_some());
        assert!(d
            .intersect(&ray([0.9, 1., 0.9], [0., -1., 0.]), 1e-4, f32::INFINITY)
            .is_none());
        let b = d.bounds();
        assert!((b.max.x - 1.0).abs() < 1e-6 && b.max.y.abs() < 1e-6);
        let p = Shape::Plane {
            point: Vec3::ZERO,
            normal: Vec3::Y,
        };
        assert!(p
            .intersect(&ray([100., 1., 0.], [0., -1., 0.]), 1e-4, f32::INFINITY)
            .is_some());
        assert!(p
            .intersect(&ray([0., 1., 0.], [0., 1., 0.]), 1e-4, f32::INFINITY)
            .is_none());
    }

    #[test]
    fn area_samples_lie_on_the_shape() {
        let shapes = [
            Shape::Sphere {
                center: Vec3::ONE,
                radius: 2.0,
            },
            Shape::Quad {
                p: Vec3::ZERO,
                e1: Vec3::X,
                e2: Vec3::Z,
            },
            Shape::Disk {
                center: Vec3::ZERO,
                normal: Vec3::Y,
                radius: 1.0,
            },
            Shape::Triangle {
                p0: Vec3::ZERO,
                e1: Vec3::X,
                e2: Vec3::Y,
                normals: u32::MAX,
            },
        ];
        for s in shapes {
            for i in 0..16 {
                let u = Vec2::new((i % 4) as f32 / 4.0 + 0.1, (i / 4) as f32 / 4.0 + 0.1);
                let (p, n) = s.sample_area(u);
                let r = Ray::new(p + n, -n, 0.0);
                let h = s.intersect(&r, 1e-4, 2.0).expect("sample on the surface");
                assert!((h.t - 1.0).abs() < 1e-3);
            }
        }
    }
}
