//! A 4-wide BVH collapsed from the binary SAH BVH (the "QBVH" of Dammertz et
//! al. 2008, "Shallow Bounding Volume Hierarchies for Fast SIMD Ray Tracing of
//! Incoherent Rays"): each node holds the boxes of up to four children in
//! structure-of-arrays form, so one ray is tested against all four with the
//! same few vector instructions. Portable code: plain `[f32; 4]` lanes that
//! the compiler turns into SSE on x86-64 (or NEON), no target-specific build.
//!
//! Fewer, wider nodes mean half the traversal steps of the binary tree; the
//! hit children are visited nearest first.

use super::bvh::Bvh;
use super::pages::PagedVec;
use super::tri4::{PackedTriangle, Tri4, FLAGS, MAX_PACKED, PLAIN};
use crate::geometry::shape::Shape;
use crate::geometry::shape::ShapeHit;
use crate::geometry::{Aabb, Ray};
use arrayvec::ArrayVec;
use glam::{Vec2, Vec3};

/// One node: four child boxes, each child a node or a leaf range.
#[derive(Debug, Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
#[repr(C, align(64))]
pub struct Node4 {
    /// Box minima per axis, one lane per child.
    pub min: [[f32; 4]; 3],
    /// Box maxima per axis, one lane per child.
    pub max: [[f32; 4]; 3],
    /// Inner child: node index; block: index into [`Bvh4::tris`]; other
    /// leaf: first primitive; empty: unused.
    pub child: [u32; 4],
    /// 0 for an inner child, [`BLOCK`] for a leaf of triangles packed in
    /// a [`Tri4`] (`BLOCK - 1` for two consecutive blocks, and so on: see
    /// [`blocks`]), else the number of primitives of the leaf.
    pub count: [u32; 4],
}

/// The `count` of a leaf stored as one [`Tri4`].
pub const BLOCK: u32 = u32::MAX;

/// The most blocks in a leaf (a mesh's leaves hold up to twelve
/// triangles: see `bvh.rs`).
pub const MAX_BLOCKS: u32 = 3;

/// The smallest `count` that stands for blocks.
pub(super) const FIRST_BLOCKS: u32 = blocks_count(MAX_BLOCKS);

/// The `count` of a leaf of `k` consecutive blocks (1 to [`MAX_BLOCKS`]).
const fn blocks_count(k: u32) -> u32 {
    BLOCK - (k - 1)
}

/// How many consecutive blocks a lane of `count` holds (0: none); the
/// inverse of `blocks_count`.
#[inline(always)]
pub fn blocks(count: u32) -> u32 {
    if count >= FIRST_BLOCKS {
        BLOCK - count + 1
    } else {
        0
    }
}

const EMPTY_NODE: Node4 = Node4 {
    min: [[f32::INFINITY; 4]; 3],
    max: [[f32::NEG_INFINITY; 4]; 3],
    child: [u32::MAX; 4],
    count: [0; 4],
};

/// The closest hit found by [`Bvh4::closest`].
#[derive(Debug, Clone, Copy)]
pub struct TreeHit {
    /// The primitive hit.
    pub prim: u32,
    /// Where.
    pub hit: ShapeHit,
    /// The primitive when it is a plain triangle or quad of a block (see
    /// [`PLAIN`]): all its hit needs, without the primitive's record.
    pub plain: Option<PackedTriangle>,
}

/// The wide BVH. Leaves index primitives directly: a leaf's primitives have
/// consecutive numbers, a block's lanes each their own.
#[derive(Debug, Clone, Default)]
pub struct Bvh4 {
    /// Nodes; the root is node 0.
    pub nodes: PagedVec<Node4>,
    /// Blocks of up to four static triangles or quads, tested together; a
    /// leaf holds up to [`MAX_BLOCKS`] consecutive ones.
    pub tris: PagedVec<Tri4>,
    /// The first plain primitive's number: plain lanes are numbered from it
    /// in block order (see [`Bvh4::renumber`]).
    pub plain_from: u32,
    /// Per block, the plain lanes in the blocks before it: the block of a
    /// plain primitive by binary search ([`Bvh4::plain_lane`]), 4 bytes a
    /// block (1 a triangle).
    plain_before: Vec<u32>,
}

impl Bvh4 {
    /// Collapses a binary BVH. Leaves number their primitives by place in
    /// `bvh.order` (a leaf's are consecutive); [`Bvh4::renumber`] maps them
    /// to other numbers. No leaf is a block yet: see [`Bvh4::pack_triangles`].
    pub fn from_binary(bvh: &Bvh) -> Bvh4 {
        let mut out = Bvh4::default();
        if bvh.is_empty() {
            return out;
        }
        // At most one wide node per binary inner node (the dense binary tree
        // has n = 2·leaves − 1 nodes, leaves − 1 of them inner; in practice
        // about half that), reserved up front so that the vector never grows
        // (old and new buffers at once) at the load's peak; pages never
        // written cost no memory.
        out.nodes.reserve_exact(bvh.len() / 2);
        let mut collapse = Collapse { bvh, out: &mut out };
        if bvh.node(0).count > 0 {
            // A single leaf: one node with one child.
            let mut n = EMPTY_NODE;
            collapse.set_child(&mut n, 0, 0);
            out.nodes.push(n);
        } else {
            collapse.node(0);
        }
        out
    }

    /// Turns every leaf of primitives that `triangle(prim)` packs (static
    /// triangles and quads) into [`Tri4`] blocks, four primitives to a block. A pass of its own after the
    /// collapse, so that lowering can drop the binary tree before it reads
    /// the triangles (the load's peak memory is here).
    pub fn pack_triangles(&mut self, triangle: impl Fn(u32) -> Option<PackedTriangle>) {
        let most_blocks = self
            .nodes
            .iter()
            .flat_map(|n| n.count)
            .filter(|&c| packable_count(c))
            .map(|c| c.div_ceil(4) as usize)
            .sum();
        self.tris.reserve_exact(most_blocks);
        if !self.nodes.is_empty() {
            self.pack_below(0, &triangle);
        }
    }

    /// Packs the leaves under `node`, depth first with lanes in order: the
    /// blocks lie in the order the collapse met them, as when the collapse
    /// made them.
    fn pack_below(&mut self, node: usize, triangle: &impl Fn(u32) -> Option<PackedTriangle>) {
        let unused = PackedTriangle {
            vertices: [Vec3::ZERO; 3],
            plain: false,
            quad: false,
            swapped: false,
        };
        for lane in 0..4 {
            let n = &self.nodes[node];
            let (first, count) = (n.child[lane], n.count[lane]);
            if count == 0 {
                if first != u32::MAX {
                    self.pack_below(first as usize, triangle);
                }
                continue;
            }
            // (Primitive numbers from MAX_PACKED up cannot be packed.)
            if !packable_count(count) || first + count >= MAX_PACKED {
                continue;
            }
            let mut tris = [(0, unused); 4 * MAX_BLOCKS as usize];
            let packed = (0..count).all(|k| {
                let p = first + k;
                triangle(p).map(|t| tris[k as usize] = (p, t)).is_some()
            });
            // A lone quad is cheaper to test from its record.
            let lone_quad = count == 1 && tris[0].1.quad;
            if packed && !lone_quad {
                let n = &mut self.nodes[node];
                n.child[lane] = self.tris.len() as u32;
                n.count[lane] = blocks_count(count.div_ceil(4));
                for block in tris[..count as usize].chunks(4) {
                    self.tris.push(Tri4::new(block));
                }
            }
        }
    }

    /// Gives every primitive its final number: `record(old)` for the
    /// primitives with records (as the first primitive of a leaf, whose
    /// primitives must keep consecutive numbers: `record(old + k) ==
    /// record(old) + k`, and in the blocks' other lanes), and `plain_from`,
    /// `plain_from + 1`, … to the plain lanes in block order, each
    /// reported as `plain(old, new)`. Numbered in block order, a plain
    /// primitive's lane is found again from its number alone
    /// ([`Bvh4::plain_lane`]).
    pub fn renumber(
        &mut self,
        record: impl Fn(u32) -> u32,
        plain_from: u32,
        mut plain: impl FnMut(u32, u32),
    ) {
        for n in self.nodes.iter_mut() {
            for lane in 0..4 {
                if n.count[lane] != 0 && blocks(n.count[lane]) == 0 {
                    n.child[lane] = record(n.child[lane]);
                }
            }
        }
        self.plain_from = plain_from;
        self.plain_before = Vec::with_capacity(self.tris.len());
        let mut next = plain_from;
        for block in self.tris.iter_mut() {
            self.plain_before.push(next - plain_from);
            for p in block.prim.iter_mut().filter(|p| **p != u32::MAX) {
                let old = *p & !FLAGS;
                let id = if *p & PLAIN != 0 {
                    next += 1;
                    plain(old, next - 1);
                    next - 1
                } else {
                    record(old)
                };
                debug_assert!(id < MAX_PACKED);
                *p = id | (*p & FLAGS);
            }
        }
    }

    /// The plain triangle or quad numbered `prim` (`None`: not a plain
    /// primitive), as its block holds it.
    pub fn plain_lane(&self, prim: u32) -> Option<PackedTriangle> {
        let k = prim.checked_sub(self.plain_from)?;
        let b = self.plain_before.partition_point(|&before| before <= k);
        let b = b.checked_sub(1)?;
        let block = &self.tris[b];
        let nth = (k - self.plain_before[b]) as usize;
        let lane = (0..4)
            .filter(|&lane| block.prim[lane] != u32::MAX && block.prim(lane).1)
            .nth(nth)?;
        debug_assert_eq!(block.prim(lane).0, prim);
        Some(block.packed(lane))
    }

    /// The blocks' lanes that hold plain triangles and parallelograms (see
    /// [`PLAIN`]), in block order.
    fn plain_lanes(&self) -> impl Iterator<Item = (&Tri4, usize)> + '_ {
        self.tris.iter().flat_map(|block| {
            (0..4)
                .filter(move |&lane| block.prim[lane] != u32::MAX && block.prim(lane).1)
                .map(move |lane| (block, lane))
        })
    }

    /// The primitives in the blocks' plain lanes (plain triangles and
    /// parallelograms, see [`PLAIN`]), in block order.
    pub fn plain_prims(&self) -> impl Iterator<Item = u32> + '_ {
        self.plain_lanes().map(|(block, lane)| block.prim(lane).0)
    }

    /// The primitives of the plain lanes (as `plain_prims`) and their shapes.
    pub fn plain_shapes(&self) -> impl Iterator<Item = (u32, Shape)> + '_ {
        self.plain_lanes()
            .map(|(block, lane)| (block.prim(lane).0, block.packed(lane).shape()))
    }

    /// The closest hit beyond `t_min` and before `t_max`: `hit(prim, t_max)`
    /// tests a primitive that is not in a block and returns its hit if
    /// closer than `t_max`. Returns the primitive and its hit.
    #[inline(always)]
    pub fn closest<F: FnMut(u32, f32) -> Option<ShapeHit>>(
        &self,
        ray: &Ray,
        t_min: f32,
        mut t_max: f32,
        mut hit: F,
    ) -> Option<TreeHit> {
        // The buffers once, not at every step (see `PagedVec`'s deref).
        let (nodes, tris): (&[Node4], &[Tri4]) = (&self.nodes, &self.tris);
        if nodes.is_empty() {
            return None;
        }
        let r = RayLanes::new(ray);
        let mut best: Option<TreeHit> = None;
        // The block and lane of the best hit, if it is in a block.
        let mut best_lane = None;
        // Children of every kind wait on the stack, nearest on top: a leaf
        // is tested only when nothing nearer is left (measurements:
        // docs/performance.md, "Why the BVH and traversal are as they are").
        // An entry is `(child, count, t_enter)` as in a node's lane.
        let mut stack = Stack::new((0u32, 0u32, 0.0f32));
        // The nearest child of the node just tested skips the stack.
        let mut next = None;
        while let Some((first, count, t_enter)) = next.take().or_else(|| stack.pop()) {
            if t_enter > t_max {
                continue;
            }
            if count >= FIRST_BLOCKS {
                for b in first..first + blocks(count) {
                    let block = &tris[b as usize];
                    if let Some(h) = block.closest(ray.o, ray.d, t_min, t_max) {
                        t_max = h.t;
                        best = Some(TreeHit {
                            prim: block.prim(h.lane).0,
                            hit: ShapeHit {
                                t: h.t,
                                uv: Vec2::new(h.u, h.v),
                            },
                            plain: None,
                        });
                        best_lane = Some((block, h.lane));
                    }
                }
                continue;
            }
            if count > 0 {
                for p in first..first + count {
                    if let Some(hit) = hit(p, t_max) {
                        t_max = hit.t;
                        best = Some(TreeHit {
                            prim: p,
                            hit,
                            plain: None,
                        });
                        best_lane = None;
                    }
                }
                continue;
            }
            // A ray with a NaN coordinate passes the slab test of empty
            // lanes (min and max drop NaN), whose child is u32::MAX: the
            // bounds check that every index pays skips it instead of
            // panicking, at no extra cost.
            let Some(n) = nodes.get(first as usize) else {
                continue;
            };
            let (t_near, mask) = r.slab4(n, t_max);
            if mask == 0 {
                continue;
            }
            // Children hit, sorted far to near so the nearest is popped
            // first: `far_to_near` written out, which here ran fewer
            // instructions than the call (Cornell box 508.7 against
            // 512.2 M, 64², 16 spp), than one helper for both walks that
            // also pushes (492.6 against 503.1 M) or a macro of it (493.4).
            let mut order = [0usize; 4];
            let mut k = 0;
            for lane in 0..4 {
                if mask & (1 << lane) != 0 {
                    let mut j = k;
                    while j > 0 && t_near[order[j - 1]] < t_near[lane] {
                        order[j] = order[j - 1];
                        j -= 1;
                    }
                    order[j] = lane;
                    k += 1;
                }
            }
            for &lane in &order[..k - 1] {
                stack.push((n.child[lane], n.count[lane], t_near[lane]));
            }
            let nearest = order[k - 1];
            next = Some((n.child[nearest], n.count[nearest], t_near[nearest]));
        }
        // The hit block was read last or recently: still in the cache.
        if let (Some(hit), Some((block, lane))) = (&mut best, best_lane) {
            if block.prim(lane).1 {
                hit.plain = Some(block.packed(lane));
            }
        }
        best
    }

    /// Whether anything is hit beyond `t_min` and before `t_max` (shadow
    /// rays); `hit` tests a primitive that is not in a block.
    #[inline]
    pub fn any<F: FnMut(u32, f32) -> bool>(
        &self,
        ray: &Ray,
        t_min: f32,
        t_max: f32,
        mut hit: F,
    ) -> bool {
        let (nodes, tris): (&[Node4], &[Tri4]) = (&self.nodes, &self.tris);
        if nodes.is_empty() {
            return false;
        }
        let r = RayLanes::new(ray);
        let mut stack = Stack::new(0u32);
        while let Some(node) = stack.pop() {
            // An empty lane, reached by a NaN ray: see `closest`.
            let Some(n) = nodes.get(node as usize) else {
                continue;
            };
            let (_, mask) = r.slab4(n, t_max);
            for lane in 0..4 {
                if mask & (1 << lane) == 0 {
                    continue;
                }
                let (count, first) = (n.count[lane], n.child[lane]);
                let blocked = match count {
                    0 => {
                        stack.push(first);
                        false
                    }
                    FIRST_BLOCKS..=BLOCK => (first..first + blocks(count))
                        .any(|b| tris[b as usize].any(ray.o, ray.d, t_min, t_max)),
                    _ => (first..first + count).any(|p| hit(p, t_max)),
                };
                if blocked {
                    return true;
                }
            }
        }
        false
    }
}

/// The lanes of `mask` (not empty) ordered by `t_near`, farthest first,
/// and how many there are: an insertion sort, whose branches the CPU
/// predicts (a sorting network without branches was slower:
/// docs/performance.md, session 7). The packet walk's; the single ray's
/// [`Bvh4::closest`] has it written out.
#[inline(always)]
pub(super) fn far_to_near(t_near: [f32; 4], mask: u32) -> ([usize; 4], usize) {
    let mut order = [0usize; 4];
    let mut k = 0;
    for lane in 0..4 {
        if mask & (1 << lane) != 0 {
            let mut j = k;
            while j > 0 && t_near[order[j - 1]] < t_near[lane] {
                order[j] = order[j - 1];
                j -= 1;
            }
            order[j] = lane;
            k += 1;
        }
    }
    (order, k)
}

/// The traversal stack: a small array (cheap to set up for every ray: an
/// `ArrayVec` leaves its slots unwritten until pushed, where an array of
/// entries was zero-filled per ray) that spills to the heap in the rare deep
/// trees binned SAH can make from very unevenly spaced primitives.
pub(super) struct Stack<T: Copy> {
    inline: ArrayVec<T, STACK>,
    spill: Vec<T>,
}

const STACK: usize = 48;

impl<T: Copy> Stack<T> {
    /// A stack holding the root.
    #[inline(always)]
    pub(super) fn new(root: T) -> Self {
        let mut inline = ArrayVec::new();
        inline.push(root);
        Stack {
            inline,
            spill: Vec::new(),
        }
    }

    #[inline(always)]
    pub(super) fn push(&mut self, v: T) {
        if let Err(full) = self.inline.try_push(v) {
            self.spill.push(full.element());
        }
    }

    #[inline(always)]
    pub(super) fn pop(&mut self) -> Option<T> {
        if self.spill.is_empty() {
            self.inline.pop()
        } else {
            self.spill.pop()
        }
    }
}

/// A ray prepared for slab tests: origin, inverse direction, and per axis
/// which box side is near.
struct RayLanes {
    o: [f32; 3],
    inv: [f32; 3],
    neg: [bool; 3],
}

impl RayLanes {
    fn new(ray: &Ray) -> RayLanes {
        let inv = ray.d.recip();
        RayLanes {
            o: ray.o.to_array(),
            inv: inv.to_array(),
            neg: [inv.x < 0.0, inv.y < 0.0, inv.z < 0.0],
        }
    }

    /// Entry distances of the four child boxes and the mask of those hit
    /// within `[0, t_max]`.
    #[inline(always)]
    fn slab4(&self, n: &Node4, t_max: f32) -> ([f32; 4], u32) {
        let mut t0 = [0.0f32; 4];
        let mut t1 = [t_max; 4];
        for axis in 0..3 {
            let (near, far) = if self.neg[axis] {
                (&n.max[axis], &n.min[axis])
            } else {
                (&n.min[axis], &n.max[axis])
            };
            for lane in 0..4 {
                let a = (near[lane] - self.o[axis]) * self.inv[axis];
                let b = (far[lane] - self.o[axis]) * self.inv[axis];
                // max/min that drop a NaN (0 · ∞ on a box face) for the other side.
                t0[lane] = if a > t0[lane] { a } else { t0[lane] };
                t1[lane] = if b < t1[lane] { b } else { t1[lane] };
            }
        }
        let mut mask = 0;
        for lane in 0..4 {
            mask |= ((t0[lane] <= t1[lane]) as u32) << lane;
        }
        (t0, mask)
    }
}

/// Whether a leaf of `count` primitives fits in blocks.
fn packable_count(count: u32) -> bool {
    (1..=4 * MAX_BLOCKS).contains(&count)
}

fn set_lane(n: &mut Node4, lane: usize, b: &Aabb, child: u32, count: u32) {
    for axis in 0..3 {
        n.min[axis][lane] = b.min[axis];
        n.max[axis][lane] = b.max[axis];
    }
    n.child[lane] = child;
    n.count[lane] = count;
}

/// The collapse of a binary tree into wide nodes.
struct Collapse<'a> {
    bvh: &'a Bvh,
    out: &'a mut Bvh4,
}

impl Collapse<'_> {
    /// Builds the wide node for binary inner node `b`; returns its index.
    fn node(&mut self, b: usize) -> u32 {
        let bvh = self.bvh;
        let node = bvh.node(b);
        let mut children = vec![node.index as usize, node.index as usize + 1];
        // Open the largest inner child until there are four.
        while children.len() < 4 {
            let Some((i, _)) = children
                .iter()
                .enumerate()
                .filter(|(_, &c)| bvh.node(c).count == 0)
                .max_by(|a, b| {
                    let area = |c: usize| bvh.node(c).bounds.area();
                    area(*a.1).total_cmp(&area(*b.1))
                })
            else {
                break;
            };
            let c = children.swap_remove(i);
            let first = bvh.node(c).index as usize;
            children.push(first);
            children.push(first + 1);
        }
        let index = self.out.nodes.len();
        self.out.nodes.push(EMPTY_NODE);
        let mut n = EMPTY_NODE;
        for (lane, &c) in children.iter().enumerate() {
            self.set_child(&mut n, lane, c);
        }
        self.out.nodes[index] = n;
        index as u32
    }

    /// Fills `lane` of `n` with binary node `c`: a wide node or a leaf range.
    fn set_child(&mut self, n: &mut Node4, lane: usize, c: usize) {
        let cn = self.bvh.node(c);
        if cn.count == 0 {
            let child = self.node(c);
            set_lane(n, lane, &cn.bounds, child, 0);
        } else {
            set_lane(n, lane, &cn.bounds, cn.index, cn.count as u32);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::bvh::tests::{brute, shape_strategy};
    use crate::geometry::shape::Shape;
    use glam::Vec3;
    use proptest::prelude::*;

    /// The binary BVH with its primitives renumbered into leaf order, as
    /// lowering does.
    fn wide(shapes: &mut Vec<Shape>) -> Bvh4 {
        let bounds: Vec<Aabb> = shapes.iter().map(Shape::bounds).collect();
        let packable = |i: u32| {
            matches!(
                shapes[i as usize],
                Shape::Triangle { .. } | Shape::Quad { .. }
            )
        };
        let mut bvh = Bvh::build(&bounds, &packable);
        *shapes = bvh.order.iter().map(|&i| shapes[i as usize]).collect();
        bvh.order = (0..shapes.len() as u32).collect();
        let mut w = Bvh4::from_binary(&bvh);
        w.pack_triangles(|p| {
            PackedTriangle::of(&shapes[p as usize]).map(|t| PackedTriangle {
                plain: p % 2 == 0,
                ..t
            })
        });
        w
    }

    #[test]
    fn rays_that_are_not_finite_hit_nothing() {
        // A NaN ray passes the slab test of empty lanes; their child does
        // not exist (it was a panic).
        for n in [2, 3, 5, 50] {
            let mut shapes: Vec<Shape> = (0..n)
                .map(|i| Shape::Sphere {
                    center: Vec3::new(i as f32 * 3.0, 0.0, 0.0),
                    radius: 0.4,
                })
                .collect();
            let w = wide(&mut shapes);
            nothing_is_hit(&w, &shapes);
        }
    }

    fn nothing_is_hit(w: &Bvh4, shapes: &[Shape]) {
        for (o, d) in [
            (Vec3::new(f32::NAN, 0.0, -5.0), Vec3::Z),
            (Vec3::new(0.0, 0.0, -5.0), Vec3::new(0.0, f32::NAN, 1.0)),
            (Vec3::new(f32::INFINITY, 0.0, -5.0), Vec3::Z),
            (Vec3::new(0.0, 0.0, -5.0), Vec3::splat(f32::NAN)),
            (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NAN)),
        ] {
            let ray = Ray::new(o, d, 0.0);
            let hit = |i: u32, t| shapes[i as usize].intersect(&ray, 1e-4, t);
            assert!(w.closest(&ray, 1e-4, f32::INFINITY, hit).is_none());
            assert!(!w.any(&ray, 1e-4, f32::INFINITY, |i, t| hit(i, t).is_some()));
        }
    }

    proptest! {
        #[test]
        fn agrees_with_brute_force(
            spec in prop::collection::vec(shape_strategy(), 1..200),
            rays in prop::collection::vec(
                (-12f32..12.0, -12f32..12.0, -12f32..12.0, -1f32..1.0, -1f32..1.0, -1f32..1.0), 1..40),
        ) {
            let mut shapes = spec;
            let w = wide(&mut shapes);
            for (ox, oy, oz, dx, dy, dz) in rays {
                let d = Vec3::new(dx, dy, dz);
                if d.length_squared() < 1e-4 {
                    continue;
                }
                let ray = Ray::new(Vec3::new(ox, oy, oz), d.normalize(), 0.0);
                let got = w.closest(&ray, 1e-4, f32::INFINITY, |i, tmax| {
                    shapes[i as usize].intersect(&ray, 1e-4, tmax)
                });
                let want = brute(&shapes, &ray);
                prop_assert_eq!(got.map(|g| g.hit.t), want.map(|w| w.1));
                if let Some(TreeHit { prim, plain: Some(lane), .. }) = got {
                    // Only even triangles and quads are packed as plain, and
                    // the block hands back the primitive itself.
                    let own = PackedTriangle::of(&shapes[prim as usize]);
                    prop_assert!(prim % 2 == 0);
                    prop_assert_eq!(Some(PackedTriangle { plain: true, ..lane }), own.map(|t| PackedTriangle { plain: true, ..t }));
                }
                let any = w.any(&ray, 1e-4, f32::INFINITY, |i, tmax| {
                    shapes[i as usize].intersect(&ray, 1e-4, tmax).is_some()
                });
                prop_assert_eq!(any, want.is_some());
                if let Some((_, t)) = want {
                    // Any-hit bounded just before the closest hit sees nothing.
                    let blocked = w.any(&ray, 1e-4, t * 0.999, |i, tmax| {
                        shapes[i as usize].intersect(&ray, 1e-4, tmax).is_some()
                    });
                    prop_assert!(!blocked);
                }
            }
        }
    }

    #[test]
    fn deep_trees_spill_the_stack_instead_of_overflowing() {
        // Spheres at exponentially growing distances: binned SAH peels one off
        // per level, so the tree is as deep as there are spheres.
        let mut shapes: Vec<Shape> = (0..120)
            .map(|i| Shape::Sphere {
                center: Vec3::new(1.2f32.powi(i), 0.0, 0.0),
                radius: 0.01,
            })
            .collect();
        let w = wide(&mut shapes);
        let ray = Ray::new(Vec3::new(-1.0, 0.0, 0.0), Vec3::X, 0.0);
        let hit = w.closest(&ray, 1e-4, f32::INFINITY, |i, tmax| {
            shapes[i as usize].intersect(&ray, 1e-4, tmax)
        });
        assert!(
            hit.is_some_and(|h| (h.hit.t - 1.99).abs() < 1e-3),
            "{hit:?}"
        );
        let mut stack = Stack::new(0u32);
        for i in 1..200 {
            stack.push(i);
        }
        for i in (0..200).rev() {
            assert_eq!(stack.pop(), Some(i));
        }
        assert_eq!(stack.pop(), None);
    }

    #[test]
    fn a_plain_block_hit_hands_back_its_triangle() {
        // Two triangles far apart in one block; `wide` packs the even one
        // (in leaf order) as plain: it comes back with its vertices, the
        // odd one without.
        let tri = |x: f32| Shape::flat_triangle([Vec3::new(x, 0.0, 0.0), Vec3::X, Vec3::Y]);
        let mut shapes = vec![tri(0.0), tri(5.0)];
        let w = wide(&mut shapes);
        assert_eq!(w.tris.len(), 1);
        let mut seen = Vec::new();
        for x in [0.2, 5.2] {
            let ray = Ray::new(Vec3::new(x, 0.2, 1.0), -Vec3::Z, 0.0);
            let not_alone = |_, _| panic!("a block's triangle tested alone");
            let hit = w.closest(&ray, 1e-4, f32::INFINITY, not_alone).unwrap();
            let plain = hit.prim.is_multiple_of(2);
            let own = PackedTriangle::of(&shapes[hit.prim as usize]);
            assert_eq!(hit.plain, own.filter(|_| plain), "{x}");
            seen.push(plain);
        }
        seen.sort();
        assert_eq!(seen, [false, true]);
    }

    #[test]
    fn a_single_leaf_and_an_empty_tree() {
        let mut one = vec![Shape::Sphere {
            center: Vec3::ZERO,
            radius: 1.0,
        }];
        let w = wide(&mut one);
        let ray = Ray::new(Vec3::new(0.0, 0.0, 5.0), -Vec3::Z, 0.0);
        let hit = w.closest(&ray, 1e-4, f32::INFINITY, |i, tmax| {
            one[i as usize].intersect(&ray, 1e-4, tmax)
        });
        assert_eq!(hit.map(|h| h.prim), Some(0));
        let empty = Bvh4::default();
        assert!(empty.closest(&ray, 0.0, 1.0, |_, _| None).is_none());
        assert!(!empty.any(&ray, 0.0, 1.0, |_, _| true));
    }
}
