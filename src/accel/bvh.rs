//! Bounding volume hierarchy: binned SAH build (Wald 2007, "On fast
//! Construction of SAH-based Bounding Volume Hierarchies"), parallel with rayon
//! for large nodes; a flat node array. It is not traversed itself:
//! `bvh4.rs` collapses it into the 4-wide tree the renderer uses.

use super::bvh4::MAX_BLOCKS;
use crate::geometry::Aabb;
use glam::{Vec3, Vec3A};

/// One node: bounds plus either two children (`count == 0`: left child at
/// `index`, right child at `index + 1`) or a leaf range of primitives.
#[derive(Debug, Clone, Copy)]
pub struct Node {
    /// Bounds of everything below.
    pub bounds: Aabb,
    /// Leaf: first primitive in [`Bvh::order`]; inner: index of the left child (right = left + 1).
    pub index: u32,
    /// Number of primitives (0 for inner nodes).
    pub count: u16,
}

/// A BVH over primitives given by their bounds.
#[derive(Debug, Clone, Default)]
pub struct Bvh {
    /// Nodes (see [`Bvh::node`]); the root is node 0. Halves built in
    /// parallel may leave gaps of zeroed slots between them, which no node
    /// points to and which take no memory.
    slots: Vec<Slot>,
    /// How many nodes (slots that are not gaps).
    nodes: usize,
    /// Primitive indices in leaf order.
    pub order: Vec<u32>,
}

const BINS: usize = 16;
const MAX_LEAF: usize = 4;

/// Nodes of up to this many static triangles or quads stay leaves of up to
/// [`MAX_BLOCKS`] blocks, whatever the SAH says (if small, see
/// [`SHARED_LEAF_AREA`]): on dense meshes traversal dominates, and a node
/// visit costs more than its share of a triangle test; fewer, fuller leaves
/// also mean fewer nodes and less memory. Measurements: docs/performance.md, "Why the BVH and traversal are as they are".
const SHARED_LEAF: usize = 4 * MAX_BLOCKS as usize;

/// Only nodes whose surface area is at most this fraction of the scene's
/// (about a hundredth of its size) become shared leaves: the SAH's premise,
/// rays from outside the box, holds for small boxes, and fails for a room
/// of a few big triangles with the camera inside. The mesh's leaves are
/// about 10⁻⁵ of its scene. Measurements: docs/performance.md, "Why the BVH and traversal are as they are".
const SHARED_LEAF_AREA: f32 = 1e-4;

const PARALLEL_THRESHOLD: usize = 16 * 1024;

impl Bvh {
    /// Builds a BVH over the given primitive bounds. `packable(i)` says
    /// whether primitive `i` is one the wide tree tests four at a time
    /// (static triangles and quads, see `bvh4.rs`): nodes of up to four such
    /// primitives stay leaves, small nodes of up to twelve too (three
    /// blocks).
    pub fn build(bounds: &[Aabb], packable: &(dyn Fn(u32) -> bool + Sync)) -> Bvh {
        if bounds.is_empty() {
            return Bvh::default();
        }
        let mut order: Vec<u32> = (0..bounds.len() as u32).collect();
        // Room for the most nodes a tree over n primitives can have (2n - 1,
        // leaves of one): the halves built in parallel get disjoint parts of
        // this one array instead of arrays of their own that were copied
        // into their parent's (which held every node twice at the peak).
        // Zeroed slots, so that the pages no node is written to are never
        // mapped: the mesh's tree needs a quarter of them.
        let mut slots = vec![[0u32; 8]; 2 * bounds.len() - 1];
        let (root, below) = slots.split_at_mut(1);
        // Asked once per primitive here rather than at every level.
        let packable: Vec<bool> = (0..bounds.len() as u32).map(packable).collect();
        let scene = bounds.iter().fold(Aabb::EMPTY, |a, &b| a.union(b));
        let input = Input {
            bounds,
            packable: &packable,
            shared_leaf_area: scene.area() * SHARED_LEAF_AREA,
        };
        let (used, nodes) = build_node(&input, &mut order, 0, &mut root[0], below, 1);
        // Give back the room after the last node (freed pages, not a copy).
        slots.truncate(1 + used);
        slots.shrink_to_fit();
        Bvh {
            slots,
            nodes: 1 + nodes,
            order,
        }
    }

    /// Node `i`.
    #[inline]
    pub fn node(&self, i: usize) -> Node {
        Node::from_slot(&self.slots[i])
    }

    /// How many nodes there are.
    pub fn len(&self) -> usize {
        self.nodes
    }

    /// Whether there are no nodes (no primitives).
    pub fn is_empty(&self) -> bool {
        self.slots.is_empty()
    }

    /// Bounds of everything.
    pub fn bounds(&self) -> Aabb {
        self.slots
            .first()
            .map_or(Aabb::EMPTY, |s| Node::from_slot(s).bounds)
    }
}

fn leaf(bounds: Aabb, first: usize, count: usize) -> Node {
    Node {
        bounds,
        index: first as u32,
        count: count as u16,
    }
}

/// A node's bits, as the tree stores them. Plain integers, so that
/// `vec![[0; 8]; n]` is one zeroed allocation whose pages are mapped only
/// when written: the `Vec<Node>` filled with a placeholder that this
/// replaced wrote all 2n − 1 slots (mesh: 64 MB for 17 MB of nodes).
type Slot = [u32; 8];
/// Where [`Node::index`] and [`Node::count`] sit in a [`Slot`].
const SLOT_INDEX: usize = 6;
const SLOT_COUNT: usize = 7;

impl Node {
    fn to_slot(self) -> Slot {
        let (lo, hi) = (self.bounds.min, self.bounds.max);
        let f = |x: f32| x.to_bits();
        [
            f(lo.x),
            f(lo.y),
            f(lo.z),
            f(hi.x),
            f(hi.y),
            f(hi.z),
            self.index,
            self.count as u32,
        ]
    }

    fn from_slot(s: &Slot) -> Node {
        let v = |i: usize| {
            Vec3::new(
                f32::from_bits(s[i]),
                f32::from_bits(s[i + 1]),
                f32::from_bits(s[i + 2]),
            )
        };
        Node {
            bounds: Aabb {
                min: v(0),
                max: v(3),
            },
            index: s[SLOT_INDEX],
            count: s[SLOT_COUNT] as u16,
        }
    }
}

/// What every step of the build reads.
struct Input<'a> {
    bounds: &'a [Aabb],
    packable: &'a [bool],
    /// The largest surface area of a node that may become a shared leaf.
    shared_leaf_area: f32,
}

impl Input<'_> {
    /// Whether primitive `i` goes in a block.
    #[inline]
    fn packable(&self, i: u32) -> bool {
        self.packable[i as usize]
    }

    /// The centroid of primitive `i`'s box, computed where needed: an array
    /// of them would cost 12 bytes per primitive at the load's peak.
    #[inline]
    fn centroid(&self, i: u32) -> Vec3 {
        self.bounds[i as usize].center()
    }
}

/// Builds the subtree over `order` (which starts at `offset` in the full
/// order): its root into `root`, its other nodes into `below`, which starts
/// at node `base` of the whole array and has room for them all (2·len − 2).
/// Returns how many slots of `below` it spans (the last used one + 1) and
/// how many nodes it wrote there. The two children of a node sit side by
/// side, their subtrees after them.
fn build_node(
    input: &Input,
    order: &mut [u32],
    offset: usize,
    root: &mut Slot,
    below: &mut [Slot],
    base: usize,
) -> (usize, usize) {
    // The node's bounds and its centroids' bounds, in one pass.
    let (node_bounds, cb) = order.iter().fold((Aabb::EMPTY, Aabb::EMPTY), |(b, c), &i| {
        let i = i as usize;
        let bounds = input.bounds[i];
        (b.union(bounds), c.grow(bounds.center()))
    });
    let n = order.len();
    let mid = if n <= MAX_LEAF {
        small_split(input, order, &node_bounds, &cb)
    } else if n <= SHARED_LEAF
        && node_bounds.area() <= input.shared_leaf_area
        && order.iter().all(|&i| input.packable(i))
    {
        None
    } else {
        Some(large_split(input, order, &cb))
    };
    let Some(mid) = mid else {
        *root = leaf(node_bounds, offset, order.len()).to_slot();
        return (0, 0);
    };
    *root = Node {
        bounds: node_bounds,
        index: base as u32,
        count: 0,
    }
    .to_slot();
    let n = order.len();
    let (lo, hi) = order.split_at_mut(mid);
    let (pair, rest) = below.split_at_mut(2);
    let (left, right) = pair.split_at_mut(1);
    if n >= PARALLEL_THRESHOLD {
        // Each half gets the most room it can need (2·len − 2 slots). The
        // room the left half leaves unused stays a gap of zeroed slots that
        // no node points to: never written, its pages are never mapped.
        // Moving the right half down to close it would write each moved node
        // to a fresh page while its old page stays mapped, at every parallel
        // level (33 MB more at the mesh's peak).
        let room_lo = 2 * lo.len() - 2;
        let (rest_lo, rest_hi) = rest.split_at_mut(room_lo);
        let hi_base = base + 2 + room_lo;
        let ((_, nodes_lo), (used_hi, nodes_hi)) = rayon::join(
            || build_node(input, lo, offset, &mut left[0], rest_lo, base + 2),
            || build_node(input, hi, offset + mid, &mut right[0], rest_hi, hi_base),
        );
        (2 + room_lo + used_hi, 2 + nodes_lo + nodes_hi)
    } else {
        let (used_lo, nodes_lo) = build_node(input, lo, offset, &mut left[0], rest, base + 2);
        let (_, rest_hi) = rest.split_at_mut(used_lo);
        let hi_base = base + 2 + used_lo;
        let (used_hi, nodes_hi) =
            build_node(input, hi, offset + mid, &mut right[0], rest_hi, hi_base);
        (2 + used_lo + used_hi, 2 + nodes_lo + nodes_hi)
    }
}

/// The widest axis of the centroid bounds `cb`.
fn widest_axis(cb: &Aabb) -> usize {
    let extent = cb.max - cb.min;
    if extent.x >= extent.y && extent.x >= extent.z {
        0
    } else if extent.y >= extent.z {
        1
    } else {
        2
    }
}

/// Where a node of more than [`MAX_LEAF`] primitives splits: always, as with
/// the 4-wide traversal (bvh4.rs) a node test is cheaper than testing more
/// primitives. Binned SAH over all three axes (Wald 2007 bins only the
/// widest; pbrt-v4 and Embree try all three: better trees for a slower
/// build), except in nodes of up to [`SMALL_NODE`] primitives; `cb` bounds
/// the centroids. `order` is partitioned, the left side is `order[..mid]`.
/// Measurements: docs/performance.md, "Why the BVH and traversal are as they are".
fn large_split(input: &Input, order: &mut [u32], cb: &Aabb) -> usize {
    let widest = widest_axis(cb);
    let bins = if order.len() >= PARALLEL_THRESHOLD {
        // The top of the tree would otherwise bin a million primitives on
        // one thread.
        use rayon::prelude::*;
        order
            .par_chunks(PARALLEL_THRESHOLD / 2)
            .map(|part| AxisBins::fill(input, part, cb))
            .reduce(|| AxisBins::new(cb), AxisBins::merge)
    } else {
        AxisBins::fill(input, order, cb)
    };
    let axes = if order.len() <= SMALL_NODE {
        widest..widest + 1
    } else {
        0..3
    };
    let best = axes
        .filter_map(|axis| {
            bins.cheapest_split(axis)
                .map(|(cost, bin)| (cost, axis, bin))
        })
        .min_by(|a, b| a.0.total_cmp(&b.0));
    let Some((_, axis, split_bin)) = best else {
        // All centroids coincide (or are infinite): split in the middle of the list.
        return order.len() / 2;
    };
    let (mut l, mut r) = (0, order.len());
    while l < r {
        if bins.bin_of(input.centroid(order[l]), axis) <= split_bin {
            l += 1;
        } else {
            r -= 1;
            order.swap(l, r);
        }
    }
    l
}

/// Nodes of up to this many primitives split along their widest centroid
/// axis only. A room of a few big walls is where the SAH's assumptions
/// (rays from far outside) fail most, and trying all three axes there makes
/// worse trees. Measurements: docs/performance.md, "Why the BVH and traversal are as they are".
const SMALL_NODE: usize = 16;

/// Primitives binned by centroid along each axis: bounds and counts.
#[derive(Clone)]
struct AxisBins {
    /// Centroid bounds' minimum and bins per unit length, per axis (scale 0
    /// for an axis without extent: everything in bin 0).
    min: Vec3A,
    scale: Vec3A,
    /// Per axis and bin: box minimum and maximum (SIMD vectors: the union
    /// of a primitive's box is two instructions).
    lo: [[Vec3A; BINS]; 3],
    hi: [[Vec3A; BINS]; 3],
    count: [[u32; BINS]; 3],
    /// How many of `count` are packable.
    packed: [[u32; BINS]; 3],
}

impl AxisBins {
    fn new(cb: &Aabb) -> AxisBins {
        let extent = cb.max - cb.min;
        let scale = Vec3::select(
            extent.cmpgt(Vec3::ZERO) & extent.is_finite_mask(),
            BINS as f32 / extent,
            Vec3::ZERO,
        );
        AxisBins {
            min: cb.min.into(),
            scale: scale.into(),
            lo: [[Vec3A::INFINITY; BINS]; 3],
            hi: [[Vec3A::NEG_INFINITY; BINS]; 3],
            count: [[0; BINS]; 3],
            packed: [[0; BINS]; 3],
        }
    }

    /// The bin of `centroid` on each axis.
    #[inline]
    fn bins_of(&self, centroid: Vec3) -> [usize; 3] {
        let k = (Vec3A::from(centroid) - self.min) * self.scale;
        // `as` saturates (and maps NaN to 0): never out of range.
        k.to_array().map(|k| (k as usize).min(BINS - 1))
    }

    #[inline]
    fn bin_of(&self, centroid: Vec3, axis: usize) -> usize {
        self.bins_of(centroid)[axis]
    }

    /// One pass over `part`: each primitive into its bin on every axis.
    fn fill(input: &Input, part: &[u32], cb: &Aabb) -> AxisBins {
        let mut bins = AxisBins::new(cb);
        for &i in part {
            let b = input.bounds[i as usize];
            let (lo, hi) = (Vec3A::from(b.min), Vec3A::from(b.max));
            let k = bins.bins_of(b.center());
            let packed = input.packable(i) as u32;
            for axis in 0..3 {
                let k = k[axis];
                bins.lo[axis][k] = bins.lo[axis][k].min(lo);
                bins.hi[axis][k] = bins.hi[axis][k].max(hi);
                bins.count[axis][k] += 1;
                bins.packed[axis][k] += packed;
            }
        }
        bins
    }

    fn merge(mut self, other: AxisBins) -> AxisBins {
        for axis in 0..3 {
            for k in 0..BINS {
                self.lo[axis][k] = self.lo[axis][k].min(other.lo[axis][k]);
                self.hi[axis][k] = self.hi[axis][k].max(other.hi[axis][k]);
                self.count[axis][k] += other.count[axis][k];
                self.packed[axis][k] += other.packed[axis][k];
            }
        }
        self
    }

    /// The cheapest split along `axis`: SAH cost and the last bin of the
    /// left side; `None` when one side would be empty. Packable primitives
    /// count in blocks of four (Embree's cost for its four-triangle leaves),
    /// so that cuts leave full blocks (mesh: 3.2 -> 3.6 triangles per block
    /// by this count alone, 3.8 with all three axes tried).
    fn cheapest_split(&self, axis: usize) -> Option<(f32, usize)> {
        let cost = |n: u32, packed: u32| (n - packed + packed.div_ceil(4)) as f32;
        let (count, packed) = (&self.count[axis], &self.packed[axis]);
        let bounds = |b: usize| Aabb {
            min: self.lo[axis][b].into(),
            max: self.hi[axis][b].into(),
        };
        let mut right_area = [0.0f32; BINS];
        let mut right_count = [(0u32, 0u32); BINS];
        let (mut acc, mut cnt) = (Aabb::EMPTY, (0, 0));
        for b in (1..BINS).rev() {
            acc = acc.union(bounds(b));
            cnt = (cnt.0 + count[b], cnt.1 + packed[b]);
            right_area[b] = acc.area();
            right_count[b] = cnt;
        }
        let mut best: Option<(f32, usize)> = None;
        let (mut acc, mut cnt) = (Aabb::EMPTY, (0, 0));
        for b in 0..BINS - 1 {
            acc = acc.union(bounds(b));
            cnt = (cnt.0 + count[b], cnt.1 + packed[b]);
            let right = right_count[b + 1];
            let c = acc.area() * cost(cnt.0, cnt.1) + right_area[b + 1] * cost(right.0, right.1);
            if cnt.0 > 0 && right.0 > 0 && best.is_none_or(|(bc, _)| c < bc) {
                best = Some((c, b));
            }
        }
        best
    }
}

/// The traversal cost of an inner node relative to one primitive test, in
/// the surface area heuristic that decides small leaves. pbrt-v4 uses 0.5;
/// below 0.89 the walls of a Cornell box part, which costs its renders.
const NODE_COST: f32 = 0.85;

/// Whether a node of at most [`MAX_LEAF`] primitives is better split (by the
/// surface area heuristic, every split along the widest centroid axis
/// tried): `mid`, with `order` sorted along that axis. Up to four packable
/// primitives (static triangles and quads: the walls of a room share a
/// block) always stay together; scattered spheres end in leaves of one,
/// small overlapping primitives that cannot be packed (moving triangles) in
/// shared leaves. Measurements: docs/performance.md, "Why the BVH and traversal are as they are".
fn small_split(input: &Input, order: &mut [u32], node: &Aabb, cb: &Aabb) -> Option<usize> {
    let n = order.len();
    // Four packable primitives cost one test: always cheaper than a node
    // and a test on each side.
    if n < 2 || order.iter().all(|&i| input.packable(i)) {
        return None;
    }
    let axis = widest_axis(cb);
    let centroid = |i: u32| input.centroid(i)[axis];
    order.sort_by(|&a, &b| centroid(a).total_cmp(&centroid(b)));
    let area = |part: &[u32]| {
        part.iter()
            .fold(Aabb::EMPTY, |b, &i| b.union(input.bounds[i as usize]))
            .area()
    };
    let (cost, mid) = (1..n)
        .map(|k| {
            (
                area(&order[..k]) * k as f32 + area(&order[k..]) * (n - k) as f32,
                k,
            )
        })
        .min_by(|a, b| a.0.total_cmp(&b.0))?;
    (NODE_COST * node.area() + cost < n as f32 * node.area()).then_some(mid)
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::geometry::shape::Shape;
    use crate::geometry::Ray;
    use proptest::prelude::*;

    /// The closest hit by testing every shape (the reference for BVH tests).
    pub(crate) fn brute(shapes: &[Shape], ray: &Ray) -> Option<(u32, f32)> {
        let mut best: Option<(u32, f32)> = None;
        for (i, s) in shapes.iter().enumerate() {
            if let Some(h) = s.intersect(ray, 1e-4, best.map_or(f32::INFINITY, |b| b.1)) {
                best = Some((i as u32, h.t));
            }
        }
        best
    }

    /// Random spheres, triangles and quads in a 20-unit cube.
    pub(crate) fn shape_strategy() -> impl Strategy<Value = Shape> {
        let v = || {
            (-10.0f32..10.0, -10.0f32..10.0, -10.0f32..10.0)
                .prop_map(|(x, y, z)| Vec3::new(x, y, z))
        };
        let e =
            || (-2.0f32..2.0, -2.0f32..2.0, -2.0f32..2.0).prop_map(|(x, y, z)| Vec3::new(x, y, z));
        prop_oneof![
            (v(), 0.05f32..2.0).prop_map(|(center, radius)| Shape::Sphere { center, radius }),
            (v(), e(), e(), any::<bool>()).prop_map(|(p0, e1, e2, swapped)| Shape::Triangle {
                p0,
                e1,
                e2,
                attributes: u32::MAX,
                swapped,
            }),
            (v(), e(), e(), any::<bool>()).prop_map(|(p, e1, e2, swapped)| Shape::Quad {
                p,
                e1,
                e2,
                swapped
            }),
        ]
    }

    #[test]
    fn small_leaves_split_room_walls_but_keep_triangles_together() {
        let b = |lo: [f32; 3], hi: [f32; 3]| Aabb {
            min: Vec3::from(lo),
            max: Vec3::from(hi),
        };
        let leaves =
            |bounds: &[Aabb], packable: bool| leaf_sizes(&Bvh::build(bounds, &|_| packable));
        // Two walls of a room meeting in an edge, or two small spheres apart:
        // a ray rarely meets both boxes, so each is its own leaf.
        let walls = [
            b([-1., -1., -1.], [1., -1., 1.]),
            b([-1., -1., -1.], [-1., 1., 1.]),
        ];
        assert_eq!(leaves(&walls, false), vec![1, 1]);
        let spheres = [
            b([0., 0., 0.], [0.2, 0.2, 0.2]),
            b([1., 0., 0.], [1.2, 0.2, 0.2]),
        ];
        assert_eq!(leaves(&spheres, false), vec![1, 1]);
        // Two neighbouring triangles of a strip, boxes overlapping by half:
        // splitting saves too little for a node (it would below a node cost
        // of 2/3), so they share a leaf.
        let pair = [
            b([0., 0., 0.], [0.01, 0.01, 0.]),
            b([0.005, 0., 0.], [0.015, 0.01, 0.]),
        ];
        assert_eq!(leaves(&pair, false), vec![2]);
        // Up to four packable primitives (tested at once) always share a
        // leaf, even far apart.
        assert_eq!(leaves(&walls, true), vec![2]);
        let strip: Vec<Aabb> = (0..13)
            .map(|i| b([i as f32, 0., 0.], [i as f32 + 0.5, 0.5, 0.]))
            .collect();
        assert_eq!(leaves(&strip[..4], true), vec![4]);
        // Up to twelve, small against their scene, share leaves of up to
        // three blocks; a thirteenth splits. The scene: the strip and, far away,
        // a second one that makes it large (sizes 0.5 in a scene of 10^4).
        let far = |d: f32| {
            strip
                .iter()
                .map(move |s| b([s.min.x + d, d, 0.], [s.max.x + d, 0.5 + d, 0.]))
        };
        let scene = |n: usize| -> Vec<Aabb> { far(0.0).take(n).chain(far(1e4).take(n)).collect() };
        assert_eq!(leaves(&scene(12), true), vec![12, 12]);
        let split = leaves(&scene(13), true);
        assert!(
            split.len() > 2 && split.iter().all(|&n| n <= 12),
            "{split:?}"
        );
        // Five that are the whole scene (a room's walls) split.
        assert_eq!(leaves(&strip[..5], true).iter().sum::<u16>(), 5);
        assert!(leaves(&strip[..5], true).len() > 1);
    }

    /// Leaf sizes of a build, ascending.
    fn leaf_sizes(bvh: &Bvh) -> Vec<u16> {
        let mut sizes: Vec<u16> = bvh
            .slots
            .iter()
            .map(Node::from_slot)
            .filter(|n| n.count > 0)
            .map(|n| n.count)
            .collect();
        sizes.sort();
        sizes
    }

    #[test]
    fn splits_across_the_best_axis_not_only_the_widest() {
        // Two flat layers far apart in y, each spread wide in x: cutting
        // along x (the widest centroid axis) leaves both layers in both
        // halves; cutting along y separates them.
        let bounds: Vec<Aabb> = (0..64)
            .map(|i| {
                let p = Vec3::new((i % 32) as f32, if i < 32 { 0.0 } else { 10.0 }, 0.0);
                Aabb {
                    min: p,
                    max: p + Vec3::new(0.9, 0.1, 0.1),
                }
            })
            .collect();
        let bvh = Bvh::build(&bounds, &|_| false);
        for c in [bvh.node(1), bvh.node(2)] {
            assert!(c.bounds.max.y - c.bounds.min.y < 1.0, "{:?}", c.bounds);
        }
    }

    #[test]
    fn packable_primitives_fill_blocks_of_four() {
        // Small boxes scattered through a cube (a fixed pseudo-random
        // sequence). Counted one by one the SAH cuts anywhere, leaving many
        // leaves of one to three; counted in blocks of four it prefers cuts
        // that leave full blocks.
        let mut sampler = crate::sampling::sampler::Sampler::new(1, 2, 3, 4);
        let mut next = || sampler.next_f32();
        let bounds: Vec<Aabb> = (0..4000)
            .map(|_| {
                let p = Vec3::new(next(), next(), next()) * 20.0;
                Aabb {
                    min: p,
                    max: p + Vec3::splat(0.2),
                }
            })
            .collect();
        // Measured: 3.56 per leaf in blocks, 3.02 counted one by one.
        let leaves = leaf_sizes(&Bvh::build(&bounds, &|_| true)).len();
        assert!(4000.0 / leaves as f32 > 3.4, "{leaves} leaves");
    }

    #[test]
    fn large_build_keeps_every_primitive_once() {
        // Boxes in identical pairs, which stay together in leaves of two:
        // the halves built in parallel then leave room unused.
        let bounds: Vec<Aabb> = (0..50_000)
            .map(|i| {
                let i = i / 2;
                let p = Vec3::new(
                    (i % 97) as f32,
                    (i % 89) as f32 * 0.5,
                    (i / 97) as f32 * 0.1,
                );
                Aabb {
                    min: p,
                    max: p + Vec3::splat(0.3),
                }
            })
            .collect();
        let bvh = Bvh::build(&bounds, &|_| false);
        let mut seen = vec![0u8; bounds.len()];
        let mut stack = vec![0usize];
        let mut reached = 0;
        while let Some(n) = stack.pop() {
            reached += 1;
            let node = bvh.node(n);
            if node.count > 0 {
                for &p in &bvh.order[node.index as usize..node.index as usize + node.count as usize]
                {
                    seen[p as usize] += 1;
                    let b = bounds[p as usize];
                    assert!(
                        node.bounds.min.cmple(b.min).all() && node.bounds.max.cmpge(b.max).all()
                    );
                }
            } else {
                stack.push(node.index as usize);
                stack.push(node.index as usize + 1);
            }
        }
        assert!(seen.iter().all(|&c| c == 1));
        // Built in parallel (50,000 > PARALLEL_THRESHOLD): the nodes reached
        // are all the nodes, and every other slot is an unwritten gap.
        assert_eq!(reached, bvh.len());
        let written = bvh.slots.iter().filter(|s| **s != [0; 8]).count();
        assert_eq!(written, bvh.len());
        assert!(bvh.slots.len() > bvh.len(), "the pairs leave gaps");
    }
}
