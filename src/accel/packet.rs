//! Closest hits of a packet of coherent rays (a pixel's camera rays) in one
//! walk of the wide BVH: each node is tested once for the whole packet by
//! interval arithmetic over the rays' origins and inverse directions (Boulos
//! et al. 2006, "Geometric and Arithmetic Culling Methods for Entire Ray
//! Packets", §3); each block of four triangles a walk reaches is tested by
//! each ray with [`Tri4`]'s own test.
//!
//! Every ray gets the hit it gets alone: the packet's box test is
//! conservative (it visits every node any of its rays would), and the
//! primitives' tests are the single ray's, so the hits are bit for bit the
//! single ray's, except that of two triangles hit at the very same distance
//! (a ray through a shared edge) the packet may keep the other one.
//! (Testing a block's triangles one at a time across the packet's rays,
//! eight or sixteen rays to a vector, ran fewer instructions and took
//! longer: docs/performance.md, "Camera-ray packets".)

use super::bvh4::{blocks, far_to_near, Bvh4, Node4, Stack, TreeHit, FIRST_BLOCKS};
use super::tri4::Tri4;
use crate::geometry::shape::ShapeHit;
use crate::geometry::Ray;
use glam::Vec2;

/// The most rays of a packet.
pub const PACKET: usize = 16;

/// A packet's rays in structure-of-arrays form, for the vector code that
/// finds their [`Bounds`]; lanes past its length repeat its last ray.
struct Lanes {
    o: [[f32; PACKET]; 3],
    d: [[f32; PACKET]; 3],
}

/// What the packet's node test needs: per axis the interval of the rays'
/// origins and of their inverse directions (all of one sign).
struct Bounds {
    o_lo: [f32; 3],
    o_hi: [f32; 3],
    inv_lo: [f32; 3],
    inv_hi: [f32; 3],
}

impl Bounds {
    /// The intervals of the first `L` rays of `rays`, or `None` when a
    /// direction component is zero or changes sign among them (the rays then
    /// go alone).
    #[inline(always)]
    fn new<const L: usize>(rays: &Lanes) -> Option<Bounds> {
        let mut b = Bounds {
            o_lo: [0.0; 3],
            o_hi: [0.0; 3],
            inv_lo: [0.0; 3],
            inv_hi: [0.0; 3],
        };
        let mut usable = true;
        for axis in 0..3 {
            let (o, d) = (&rays.o[axis][..L], &rays.d[axis][..L]);
            let mut inv = [0.0f32; L];
            for r in 0..L {
                inv[r] = 1.0 / d[r];
            }
            let least = |v: &[f32]| v.iter().fold(f32::INFINITY, |m, &x| m.min(x));
            let most = |v: &[f32]| v.iter().fold(f32::NEG_INFINITY, |m, &x| m.max(x));
            b.o_lo[axis] = least(o);
            b.o_hi[axis] = most(o);
            b.inv_lo[axis] = least(&inv);
            b.inv_hi[axis] = most(&inv);
            let (lo, hi) = (b.inv_lo[axis], b.inv_hi[axis]);
            let finite = [lo, hi, b.o_lo[axis], b.o_hi[axis]]
                .iter()
                .all(|v| v.is_finite());
            usable &= finite && (lo > 0.0 || hi < 0.0);
        }
        usable.then_some(b)
    }

    /// For each child box, a distance no ray of the packet enters it before
    /// (at least 0) and the mask of children some ray may hit before
    /// `t_max`. Rounding is monotonic in each operand, so the least of the
    /// four corner products bounds every ray's own `(plane - o) · inv` from
    /// below, the greatest from above: a ray whose slab test passes alone
    /// passes here.
    #[inline(always)]
    fn slab4(&self, n: &Node4, t_max: f32) -> ([f32; 4], u32) {
        let mut t0 = [0.0f32; 4];
        let mut t1 = [t_max; 4];
        for axis in 0..3 {
            let (near, far) = if self.inv_lo[axis] < 0.0 {
                (&n.max[axis], &n.min[axis])
            } else {
                (&n.min[axis], &n.max[axis])
            };
            let (o_lo, o_hi) = (self.o_lo[axis], self.o_hi[axis]);
            let (i_lo, i_hi) = (self.inv_lo[axis], self.inv_hi[axis]);
            for lane in 0..4 {
                let (a_lo, a_hi) = (near[lane] - o_hi, near[lane] - o_lo);
                let (b_lo, b_hi) = (far[lane] - o_hi, far[lane] - o_lo);
                let enter = (a_lo * i_lo)
                    .min(a_lo * i_hi)
                    .min(a_hi * i_lo)
                    .min(a_hi * i_hi);
                let leave = (b_lo * i_lo)
                    .max(b_lo * i_hi)
                    .max(b_hi * i_lo)
                    .max(b_hi * i_hi);
                t0[lane] = if enter > t0[lane] { enter } else { t0[lane] };
                t1[lane] = if leave < t1[lane] { leave } else { t1[lane] };
            }
        }
        let mut mask = 0;
        for lane in 0..4 {
            mask |= ((t0[lane] <= t1[lane]) as u32) << lane;
        }
        (t0, mask)
    }
}

/// Each ray's closest hit so far: its distance (the bound of its further
/// tests), barycentrics, and what was hit: [`NONE`], a block's lane
/// (`block · 4 + lane`) or a primitive outside blocks ([`RECORD`] set).
/// After the walk, each ray's closest hit ([`Closest::get`]).
pub struct Closest {
    /// How many blocks and primitives the walk tested, each with every ray.
    pub leaf_tests: u32,
    t: [f32; PACKET],
    u: [f32; PACKET],
    v: [f32; PACKET],
    what: [u32; PACKET],
}

/// Nothing hit.
const NONE: u32 = u32::MAX;

/// The bit of [`Closest::what`] that marks a primitive's number.
const RECORD: u32 = 1 << 31;

impl Closest {
    /// The largest distance a ray of the packet still looks up to.
    #[inline(always)]
    fn reach<const L: usize>(&self) -> f32 {
        self.t[..L].iter().fold(f32::NEG_INFINITY, |m, &t| m.max(t))
    }

    /// Ray `r`'s closest hit in `bvh`, as the single ray's walk returns it.
    #[inline(always)]
    pub fn get(&self, r: usize, bvh: &Bvh4) -> Option<TreeHit> {
        let what = self.what[r];
        if what == NONE {
            return None;
        }
        let hit = ShapeHit {
            t: self.t[r],
            uv: Vec2::new(self.u[r], self.v[r]),
        };
        if what & RECORD != 0 {
            return Some(TreeHit {
                prim: what & !RECORD,
                hit,
                plain: None,
            });
        }
        let (block, lane) = (&bvh.tris[(what / 4) as usize], (what % 4) as usize);
        let (prim, plain) = block.prim(lane);
        Some(TreeHit {
            prim,
            hit,
            plain: plain.then(|| block.packed(lane)),
        })
    }
}

/// [`Bvh4::closest_packet`]'s walk, a kernel for `pulp` to build for each
/// instruction set (the packet's bounds are loops across its rays).
struct Walk<'a, F> {
    bvh: &'a Bvh4,
    rays: &'a [Ray],
    t_min: f32,
    t_max: f32,
    hit: F,
}

impl<F: FnMut(usize, u32, f32) -> Option<ShapeHit>> pulp::WithSimd for Walk<'_, F> {
    type Output = Option<Closest>;

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _: S) -> Self::Output {
        // Lanes for the rays there are.
        match self.rays.len() {
            0..=4 => self.run::<4>(),
            5..=8 => self.run::<8>(),
            _ => self.run::<PACKET>(),
        }
    }
}

impl<F: FnMut(usize, u32, f32) -> Option<ShapeHit>> Walk<'_, F> {
    #[inline(always)]
    fn run<const L: usize>(mut self) -> Option<Closest> {
        let (nodes, tris): (&[Node4], &[Tri4]) = (&self.bvh.nodes, &self.bvh.tris);
        let n = self.rays.len();
        let mut lanes = Lanes {
            o: [[0.0; PACKET]; 3],
            d: [[0.0; PACKET]; 3],
        };
        for r in 0..L {
            let ray = &self.rays[r.min(n - 1)];
            for axis in 0..3 {
                lanes.o[axis][r] = ray.o[axis];
                lanes.d[axis][r] = ray.d[axis];
            }
        }
        let bounds = Bounds::new::<L>(&lanes)?;
        let mut best = Closest {
            leaf_tests: 0,
            t: [f32::NEG_INFINITY; PACKET],
            u: [0.0; PACKET],
            v: [0.0; PACKET],
            what: [NONE; PACKET],
        };
        best.t[..n].fill(self.t_max);
        // As the single ray's walk: `(child, count, t_enter)` entries, the
        // nearest child of a node taken next without the stack.
        if nodes.is_empty() {
            return Some(best);
        }
        let mut stack = Stack::new((0u32, 0u32, 0.0f32));
        let mut next = None;
        let mut reach = self.t_max;
        while let Some((first, count, t_enter)) = next.take().or_else(|| stack.pop()) {
            if t_enter > reach {
                continue;
            }
            if count >= FIRST_BLOCKS {
                best.leaf_tests += blocks(count);
                for b in first..first + blocks(count) {
                    let block = &tris[b as usize];
                    for (r, ray) in self.rays.iter().enumerate() {
                        if let Some(h) = block.closest(ray.o, ray.d, self.t_min, best.t[r]) {
                            (best.t[r], best.u[r], best.v[r]) = (h.t, h.u, h.v);
                            best.what[r] = b * 4 + h.lane as u32;
                        }
                    }
                }
                reach = best.reach::<L>();
                continue;
            }
            if count > 0 {
                best.leaf_tests += count;
                for p in first..first + count {
                    for r in 0..n {
                        if let Some(h) = (self.hit)(r, p, best.t[r]) {
                            (best.t[r], best.u[r], best.v[r]) = (h.t, h.uv.x, h.uv.y);
                            best.what[r] = p | RECORD;
                        }
                    }
                }
                reach = best.reach::<L>();
                continue;
            }
            // An empty lane's child (u32::MAX) is never hit: its box is
            // empty and every bound here is finite.
            let Some(node) = nodes.get(first as usize) else {
                continue;
            };
            let (t_near, mask) = bounds.slab4(node, reach);
            if mask == 0 {
                continue;
            }
            let (order, k) = far_to_near(t_near, mask);
            for &lane in &order[..k - 1] {
                stack.push((node.child[lane], node.count[lane], t_near[lane]));
            }
            let nearest = order[k - 1];
            next = Some((node.child[nearest], node.count[nearest], t_near[nearest]));
        }
        Some(best)
    }
}

impl Bvh4 {
    /// The closest hit of each of `rays` (at most [`PACKET`]) beyond
    /// `t_min` and before `t_max` ([`Closest::get`]), as [`Bvh4::closest`]
    /// finds it for each alone; `hit(ray, prim, t_max)` tests a primitive
    /// that is not in a block. `None` when the rays are not coherent enough
    /// to go together (see [`Bounds::new`]): then trace them one by one.
    pub fn closest_packet<F: FnMut(usize, u32, f32) -> Option<ShapeHit>>(
        &self,
        rays: &[Ray],
        t_min: f32,
        t_max: f32,
        hit: F,
    ) -> Option<Closest> {
        assert!(
            (1..=PACKET).contains(&rays.len()),
            "a packet holds 1 to {PACKET} rays"
        );
        let walk = Walk {
            bvh: self,
            rays,
            t_min,
            t_max,
            hit,
        };
        pulp::Arch::new().dispatch(walk)
    }
}
