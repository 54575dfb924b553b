//! Four triangles tested against one ray at once: the leaf format of the
//! wide BVH for static triangles and quads (Embree's "Triangle4"; Wald et
//! al. 2014, "Embree: A Kernel Framework for Efficient CPU Ray Tracing").
//!
//! Each triangle is one lane of structure-of-arrays data, so Möller–Trumbore
//! ([`crate::geometry::triangle`]) runs on all four with the same few vector
//! instructions (`glam::Vec4`: SSE2 on x86-64, NEON on ARM, scalar
//! elsewhere; written as loops over `[f32; 4]` lanes, the compiler left it
//! mostly scalar), and the four triangles come from three adjacent cache
//! lines instead of four scattered primitive records. Every lane repeats the scalar test's
//! operations in the scalar test's order, so both give bit-identical hits.

use crate::geometry::shape::Shape;
use glam::{Vec3, Vec4};

/// Up to four triangles `p0, p0 + e1, p0 + e2` or parallelograms spanned by
/// `e1` and `e2` from `p0` (quads, see [`QUAD`]), one per lane; unused lanes
/// are degenerate (zero edges never hit).
#[derive(Debug, Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
#[repr(C, align(32))]
pub struct Tri4 {
    /// First vertex, per axis.
    pub p0: [[f32; 4]; 3],
    /// Edge to the second vertex, per axis.
    pub e1: [[f32; 4]; 3],
    /// Edge to the third vertex, per axis.
    pub e2: [[f32; 4]; 3],
    /// The primitive each lane is, with [`PLAIN`] set when the triangle
    /// alone describes its surface, [`QUAD`] when it is a parallelogram and
    /// [`SWAPPED`] when its edges are stored swapped (`u32::MAX` for an
    /// unused lane).
    pub prim: [u32; 4],
}

/// The bit of [`Tri4::prim`] that marks a plain triangle: one whose hit
/// needs nothing but its vertices (no vertex normals), so that the renderer
/// can shade it without fetching the primitive's record.
pub const PLAIN: u32 = 1 << 31;

/// The bit of [`Tri4::prim`] that marks a parallelogram: the same
/// Möller–Trumbore test ([`crate::geometry::quad`] shares it with triangles), with
/// `v <= 1` in place of `u + v <= 1`. Walls and floors of rooms are quads.
pub const QUAD: u32 = 1 << 30;

/// The bit of [`Tri4::prim`] that marks a primitive stored with its edges
/// swapped, to keep its outward side under a mirroring transform (see
/// [`Shape::own_uv`]).
pub const SWAPPED: u32 = 1 << 29;

/// The flag bits of [`Tri4::prim`]; primitive numbers lie below them.
pub const FLAGS: u32 = PLAIN | QUAD | SWAPPED;

/// The first primitive number a block cannot hold (2^29 records would take
/// 32 GiB).
pub const MAX_PACKED: u32 = SWAPPED;

/// A triangle (or parallelogram) to pack: its vertex and edges `[p0, e1,
/// e2]`, whether it is plain (see [`PLAIN`]), a parallelogram, and stored
/// with its edges swapped.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PackedTriangle {
    /// `[p0, e1, e2]`.
    pub vertices: [Vec3; 3],
    /// Whether the vertices alone describe the surface.
    pub plain: bool,
    /// Whether it is the parallelogram `p0 + u·e1 + v·e2`, u, v in [0, 1].
    pub quad: bool,
    /// Whether the edges are stored swapped ([`Shape::own_uv`]).
    pub swapped: bool,
}

impl PackedTriangle {
    /// A static triangle or quad `shape` to pack (`None` for other shapes),
    /// plain when it has no vertex attributes.
    pub fn of(shape: &Shape) -> Option<PackedTriangle> {
        match *shape {
            Shape::Triangle {
                p0,
                e1,
                e2,
                attributes,
                swapped,
            } => Some(PackedTriangle {
                vertices: [p0, e1, e2],
                plain: attributes == u32::MAX,
                quad: false,
                swapped,
            }),
            Shape::Quad { p, e1, e2, swapped } => Some(PackedTriangle {
                vertices: [p, e1, e2],
                plain: true,
                quad: true,
                swapped,
            }),
            _ => None,
        }
    }

    /// The primitive's own surface parameters from those of a hit on its
    /// lane (see [`Shape::own_uv`]).
    #[inline(always)]
    pub fn own_uv(&self, uv: glam::Vec2) -> glam::Vec2 {
        if self.swapped {
            glam::Vec2::new(uv.y, uv.x)
        } else {
            uv
        }
    }

    /// The shape a plain lane describes: exactly the primitive's, without
    /// vertex attributes.
    pub fn shape(&self) -> Shape {
        let [p0, e1, e2] = self.vertices;
        if self.quad {
            Shape::Quad {
                p: p0,
                e1,
                e2,
                swapped: self.swapped,
            }
        } else {
            Shape::Triangle {
                p0,
                e1,
                e2,
                attributes: u32::MAX,
                swapped: self.swapped,
            }
        }
    }
}

const _: () = assert!(std::mem::size_of::<Tri4>() == 160);

/// The closest hit of a [`Tri4`]: lane, distance and barycentrics.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LaneHit {
    /// Which lane (triangle) was hit.
    pub lane: usize,
    /// Distance along the ray.
    pub t: f32,
    /// Barycentric coordinates of the second and third vertex.
    pub u: f32,
    /// See `u`.
    pub v: f32,
}

impl Tri4 {
    /// Packs up to four `(prim, triangle)` pairs; `prim` must be below
    /// [`MAX_PACKED`].
    pub fn new(tris: &[(u32, PackedTriangle)]) -> Tri4 {
        assert!(tris.len() <= 4, "a Tri4 holds at most four triangles");
        let mut block = Tri4 {
            p0: [[0.0; 4]; 3],
            e1: [[0.0; 4]; 3],
            e2: [[0.0; 4]; 3],
            prim: [u32::MAX; 4],
        };
        for (lane, &(prim, tri)) in tris.iter().enumerate() {
            debug_assert!(prim < MAX_PACKED);
            let [p0, e1, e2] = tri.vertices;
            for axis in 0..3 {
                block.p0[axis][lane] = p0[axis];
                block.e1[axis][lane] = e1[axis];
                block.e2[axis][lane] = e2[axis];
            }
            let plain = if tri.plain { PLAIN } else { 0 };
            let quad = if tri.quad { QUAD } else { 0 };
            let swapped = if tri.swapped { SWAPPED } else { 0 };
            block.prim[lane] = prim | plain | quad | swapped;
        }
        block
    }

    /// The primitive in `lane`, and whether it is plain.
    #[inline]
    pub fn prim(&self, lane: usize) -> (u32, bool) {
        (self.prim[lane] & !FLAGS, self.prim[lane] & PLAIN != 0)
    }

    /// The primitive packed in `lane` (a used lane).
    pub fn packed(&self, lane: usize) -> PackedTriangle {
        let bits = self.prim[lane];
        PackedTriangle {
            vertices: self.vertices(lane),
            plain: bits & PLAIN != 0,
            quad: bits & QUAD != 0,
            swapped: bits & SWAPPED != 0,
        }
    }

    /// The triangle `[p0, e1, e2]` in `lane`.
    pub fn vertices(&self, lane: usize) -> [Vec3; 3] {
        let v = |a: &[[f32; 4]; 3]| Vec3::new(a[0][lane], a[1][lane], a[2][lane]);
        [v(&self.p0), v(&self.e1), v(&self.e2)]
    }

    /// Möller–Trumbore on all four lanes: per lane the hit distance and
    /// barycentrics, and the mask of lanes hit in `(t_min, t_max)`.
    #[inline(always)]
    fn test(&self, o: Vec3, d: Vec3, t_min: f32, t_max: f32) -> (Vec4, Vec4, Vec4, u32) {
        let [e1x, e1y, e1z] = self.e1.map(Vec4::from_array);
        let [e2x, e2y, e2z] = self.e2.map(Vec4::from_array);
        let [px, py, pz] = self.p0.map(Vec4::from_array);
        let (dx, dy, dz) = (Vec4::splat(d.x), Vec4::splat(d.y), Vec4::splat(d.z));
        // pv = d × e2, det = e1 · pv (glam's cross and dot, term by term).
        let pvx = dy * e2z - e2y * dz;
        let pvy = dz * e2x - e2z * dx;
        let pvz = dx * e2y - e2x * dy;
        let det = e1x * pvx + e1y * pvy + e1z * pvz;
        let inv = Vec4::ONE / det;
        let (tvx, tvy, tvz) = (
            Vec4::splat(o.x) - px,
            Vec4::splat(o.y) - py,
            Vec4::splat(o.z) - pz,
        );
        let u = (tvx * pvx + tvy * pvy + tvz * pvz) * inv;
        // qv = tv × e1.
        let qvx = tvy * e1z - e1y * tvz;
        let qvy = tvz * e1x - e1z * tvx;
        let qvz = tvx * e1y - e1x * tvy;
        let v = (dx * qvx + dy * qvy + dz * qvz) * inv;
        let t = (e2x * qvx + e2y * qvy + e2z * qvz) * inv;
        let ok = det.abs().cmpge(Vec4::splat(1e-20))
            & u.cmpge(Vec4::ZERO)
            & u.cmple(Vec4::ONE)
            & v.cmpge(Vec4::ZERO)
            & t.cmpgt(Vec4::splat(t_min))
            & t.cmplt(Vec4::splat(t_max));
        // The far edge: u + v <= 1 for a triangle, v <= 1 for a parallelogram.
        let quads = self.quads();
        let far_edge =
            ((u + v).cmple(Vec4::ONE).bitmask() & !quads) | (v.cmple(Vec4::ONE).bitmask() & quads);
        (t, u, v, ok.bitmask() & far_edge)
    }

    /// The lanes that hold parallelograms, as a bit mask (unused lanes too:
    /// they never hit).
    #[inline(always)]
    fn quads(&self) -> u32 {
        let bit = |lane: usize| ((self.prim[lane] & QUAD) >> 30) << lane;
        bit(0) | bit(1) | bit(2) | bit(3)
    }

    /// The closest hit in `(t_min, t_max)` of the ray `o + t·d`; on equal
    /// distances the lowest lane, as testing the lanes in turn would.
    #[inline(always)]
    pub fn closest(&self, o: Vec3, d: Vec3, t_min: f32, t_max: f32) -> Option<LaneHit> {
        let (t, u, v, mask) = self.test(o, d, t_min, t_max);
        if mask == 0 {
            return None;
        }
        let mut best: Option<LaneHit> = None;
        for lane in 0..4 {
            if mask & (1 << lane) != 0 && best.is_none_or(|b| t[lane] < b.t) {
                best = Some(LaneHit {
                    lane,
                    t: t[lane],
                    u: u[lane],
                    v: v[lane],
                });
            }
        }
        best
    }

    /// Whether any lane is hit in `(t_min, t_max)`.
    #[inline(always)]
    pub fn any(&self, o: Vec3, d: Vec3, t_min: f32, t_max: f32) -> bool {
        self.test(o, d, t_min, t_max).3 != 0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Ray;
    use crate::geometry::{quad, triangle};
    use proptest::prelude::*;

    fn vec3() -> impl Strategy<Value = Vec3> {
        (-3f32..3.0, -3f32..3.0, -3f32..3.0).prop_map(|(x, y, z)| Vec3::new(x, y, z))
    }

    proptest! {
        /// Every lane gives exactly the scalar test's hit, and the block's
        /// closest is the first of the nearest scalar hits.
        #[test]
        fn lanes_equal_the_scalar_test(
            tris in prop::collection::vec((vec3(), vec3(), vec3()), 1..=4),
            o in vec3(),
            d in vec3(),
            t_max in prop_oneof![Just(f32::INFINITY), 0.1f32..10.0],
        ) {
            prop_assume!(d.length_squared() > 1e-3);
            let ray = Ray::new(o, d.normalize(), 0.0);
            let packed: Vec<(u32, PackedTriangle)> = tris
                .iter()
                .enumerate()
                .map(|(i, &(p, e1, e2))| {
                    let tri = PackedTriangle {
                        vertices: [p, e1, e2],
                        plain: i % 2 == 0,
                        quad: i % 3 == 1,
                        swapped: i % 4 == 3,
                    };
                    (i as u32 + 10, tri)
                })
                .collect();
            let block = Tri4::new(&packed);
            let mut want: Option<LaneHit> = None;
            let mut t_best = t_max;
            for (lane, &(prim, tri)) in packed.iter().enumerate() {
                prop_assert_eq!(block.prim(lane), (prim, tri.plain));
                prop_assert_eq!(block.vertices(lane), tri.vertices);
                let [p, e1, e2] = tri.vertices;
                prop_assert_eq!(block.packed(lane), tri);
                let scalar = if tri.quad { quad::intersect } else { triangle::intersect };
                if let Some(h) = scalar(p, e1, e2, &ray, 1e-4, t_best) {
                    t_best = h.t;
                    want = Some(LaneHit { lane, t: h.t, u: h.uv.x, v: h.uv.y });
                }
            }
            let got = block.closest(ray.o, ray.d, 1e-4, t_max);
            prop_assert_eq!(got, want);
            prop_assert_eq!(block.any(ray.o, ray.d, 1e-4, t_max), want.is_some());
        }
    }

    #[test]
    fn unused_lanes_never_hit() {
        let block = Tri4::new(&[]);
        // A ray through the origin, where the degenerate lanes sit.
        assert_eq!(block.closest(Vec3::Z, -Vec3::Z, 0.0, f32::INFINITY), None);
        assert!(!block.any(Vec3::Z, -Vec3::Z, 0.0, f32::INFINITY));
        let vertices = [Vec3::new(-1.0, -1.0, 0.0), Vec3::X * 3.0, Vec3::Y * 3.0];
        let one = Tri4::new(&[(
            7,
            PackedTriangle {
                vertices,
                plain: false,
                quad: false,
                swapped: false,
            },
        )]);
        let hit = one.closest(Vec3::Z, -Vec3::Z, 0.0, f32::INFINITY).unwrap();
        assert_eq!((hit.lane, one.prim(hit.lane), hit.t), (0, (7, false), 1.0));
    }
}
