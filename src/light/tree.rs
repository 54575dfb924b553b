//! A bounding volume hierarchy over bounded lights, for choosing one among
//! thousands by its estimated contribution at a shading point (Conty Estevez
//! & Kulla 2018; pbrt-v4 §12.6.3, `BVHLightSampler`). Each node holds the
//! [`LightBounds`] of the lights below it; a light is chosen by walking down
//! from the root, picking a child in proportion to its importance. The
//! probability of a given light is found by walking the same path again
//! (its bit trail), so that the pmf used for MIS is exactly the one sampled.

use super::bounds::{CompactLightBounds, LightBounds};
use crate::geometry::Aabb;
use glam::Vec3;

/// A node: an inner node's first child follows it, its second is at
/// `index`; a leaf's `index` is the light's (its position in the input).
#[derive(Debug, Clone, Copy)]
struct Node {
    bounds: CompactLightBounds,
    index: u32,
    leaf: bool,
}

/// Depth from which splits are by count, so that no trail exceeds 64 bits
/// (32 levels of cost-driven splits, then at most 32 of halving).
const BALANCED_FROM_DEPTH: u32 = 32;

/// Buckets per axis for the split cost (pbrt-v4 uses 12).
const BUCKETS: usize = 12;

/// The light hierarchy.
#[derive(Debug, Clone, Default)]
pub struct LightTree {
    nodes: Vec<Node>,
    /// Per light (input order): the branches from the root to its leaf,
    /// one bit per level (1 = second child), lowest bit first.
    trails: Vec<u64>,
}

impl LightTree {
    /// Builds the tree over `lights` (none may have zero power).
    pub fn build(lights: &[LightBounds]) -> LightTree {
        let mut tree = LightTree {
            nodes: Vec::with_capacity(2 * lights.len()),
            trails: vec![0; lights.len()],
        };
        if lights.is_empty() {
            return tree;
        }
        let mut order: Vec<u32> = (0..lights.len() as u32).collect();
        tree.build_range(lights, &mut order, 0, 0);
        tree
    }

    /// Builds the subtree of `order` (light indices) at `depth` with the
    /// given trail; returns the bounds of the subtree.
    fn build_range(
        &mut self,
        lights: &[LightBounds],
        order: &mut [u32],
        trail: u64,
        depth: u32,
    ) -> LightBounds {
        if let [only] = order {
            let bounds = lights[*only as usize];
            self.nodes.push(Node {
                bounds: CompactLightBounds::from(&bounds),
                index: *only,
                leaf: true,
            });
            self.trails[*only as usize] = trail;
            return bounds;
        }
        let mid = if depth < BALANCED_FROM_DEPTH {
            split_by_cost(lights, order)
        } else {
            None
        }
        .unwrap_or(order.len() / 2);
        let at = self.nodes.len();
        self.nodes.push(Node {
            bounds: CompactLightBounds::from(&lights[order[0] as usize]),
            index: 0,
            leaf: false,
        });
        let (first, second) = order.split_at_mut(mid);
        let a = self.build_range(lights, first, trail, depth + 1);
        self.nodes[at].index = self.nodes.len() as u32;
        let b = self.build_range(lights, second, trail | (1u64 << depth), depth + 1);
        let bounds = LightBounds::union(&a, &b);
        self.nodes[at].bounds = CompactLightBounds::from(&bounds);
        bounds
    }

    /// The tree's estimate of its lights' contribution at `p` (normal `n`):
    /// the sum its root's choice is made in proportion to (its one light's
    /// estimate when it holds one).
    pub fn weight(&self, p: Vec3, n: Vec3) -> f64 {
        match self.nodes.first() {
            None => 0.0,
            Some(root) if root.leaf => root.bounds.importance(p, n),
            Some(root) => {
                let first = self.nodes[1].bounds.importance(p, n);
                first + self.nodes[root.index as usize].bounds.importance(p, n)
            }
        }
    }

    /// Chooses a light for the point `p` with normal `n` (zero: none) from
    /// `u` in [0, 1): its index and probability; `None` when no light can
    /// reach `p`.
    pub fn sample(&self, p: Vec3, n: Vec3, mut u: f64) -> Option<(u32, f64)> {
        let mut at = 0usize;
        let mut pmf = 1.0f64;
        loop {
            let node = self.nodes.get(at)?;
            if node.leaf {
                // A lone light is still checked: it may face away.
                return (at > 0 || node.bounds.importance(p, n) > 0.0).then_some((node.index, pmf));
            }
            let (first, second) = (at + 1, node.index as usize);
            let i0 = self.nodes[first].bounds.importance(p, n);
            let i1 = self.nodes[second].bounds.importance(p, n);
            let total = i0 + i1;
            if total <= 0.0 || total.is_nan() {
                return None;
            }
            let inv_total = total.recip();
            let p0 = i0 * inv_total;
            if u < p0 {
                u = (u / p0).min(ONE_BELOW);
                pmf *= p0;
                at = first;
            } else {
                let p1 = i1 * inv_total;
                u = ((u - p0) / p1).clamp(0.0, ONE_BELOW);
                pmf *= p1;
                at = second;
            }
        }
    }

    /// The probability that [`LightTree::sample`] at `p`, `n` chooses
    /// `light`: the same products along its trail.
    pub fn pmf(&self, p: Vec3, n: Vec3, light: u32) -> f64 {
        let Some(&trail) = self.trails.get(light as usize) else {
            return 0.0;
        };
        let mut at = 0usize;
        let mut pmf = 1.0f64;
        let mut depth = 0;
        loop {
            let Some(node) = self.nodes.get(at) else {
                return 0.0;
            };
            if node.leaf {
                if at == 0 && node.bounds.importance(p, n) <= 0.0 {
                    return 0.0;
                }
                return pmf;
            }
            let (first, second) = (at + 1, node.index as usize);
            let i0 = self.nodes[first].bounds.importance(p, n);
            let i1 = self.nodes[second].bounds.importance(p, n);
            let total = i0 + i1;
            if total <= 0.0 || total.is_nan() {
                return 0.0;
            }
            // The same arithmetic as `sample`, so that the two agree exactly.
            let inv_total = total.recip();
            if trail >> depth & 1 == 0 {
                pmf *= i0 * inv_total;
                at = first;
            } else {
                pmf *= i1 * inv_total;
                at = second;
            }
            depth += 1;
        }
    }

    /// Number of nodes (for tests and statistics).
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }
}

/// The largest f64 below 1.
const ONE_BELOW: f64 = 1.0 - f64::EPSILON / 2.0;

/// Partitions `order` at the cheapest of the bucket boundaries along each
/// axis (pbrt-v4's `EvaluateCost`: power × cone measure × surface area,
/// with a penalty for thin boxes cut across); the index of the split, or
/// `None` when no boundary separates the lights.
fn split_by_cost(lights: &[LightBounds], order: &mut [u32]) -> Option<usize> {
    let centroid = |i: u32| lights[i as usize].bounds.center();
    let mut all = Aabb::EMPTY;
    let mut centroids = Aabb::EMPTY;
    for &i in order.iter() {
        all = all.union(lights[i as usize].bounds);
        centroids = centroids.grow(centroid(i));
    }
    let diagonal = all.max - all.min;
    let cost = |b: &LightBounds, axis: usize| -> f64 {
        // Boxes thin along the cut axis are penalised (pbrt-v4's K_r).
        let along = diagonal[axis].max(f32::MIN_POSITIVE);
        let kr = (diagonal.max_element() / along) as f64;
        b.phi * b.cone_measure() as f64 * kr * b.bounds.area() as f64
    };
    let mut best: Option<(f64, usize, usize)> = None;
    for axis in 0..3 {
        let (lo, hi) = (centroids.min[axis], centroids.max[axis]);
        if hi <= lo || hi.is_nan() || lo.is_nan() {
            continue;
        }
        let bucket_of = |i: u32| {
            let t = (centroid(i)[axis] - lo) / (hi - lo);
            ((t * BUCKETS as f32) as usize).min(BUCKETS - 1)
        };
        let mut buckets: [Option<LightBounds>; BUCKETS] = [None; BUCKETS];
        for &i in order.iter() {
            let b = &mut buckets[bucket_of(i)];
            let l = &lights[i as usize];
            *b = Some(b.map_or(*l, |acc| LightBounds::union(&acc, l)));
        }
        // Unions of the buckets below and above each boundary, by one sweep
        // each way (not one union per pair of boundary and bucket).
        let sweep = |acc: &mut Option<LightBounds>, b: &Option<LightBounds>| {
            if let Some(b) = b {
                *acc = Some(acc.map_or(*b, |a| LightBounds::union(&a, b)));
            }
            *acc
        };
        let mut acc = None;
        let below: Vec<Option<LightBounds>> = buckets.iter().map(|b| sweep(&mut acc, b)).collect();
        let mut acc = None;
        let mut above: Vec<Option<LightBounds>> =
            buckets.iter().rev().map(|b| sweep(&mut acc, b)).collect();
        above.reverse();
        for split in 0..BUCKETS - 1 {
            let (Some(below), Some(above)) = (below[split], above[split + 1]) else {
                continue;
            };
            let c = cost(&below, axis) + cost(&above, axis);
            if c.is_finite() && best.is_none_or(|(b, _, _)| c < b) {
                best = Some((c, axis, split));
            }
        }
    }
    let (_, axis, split) = best?;
    let (lo, hi) = (centroids.min[axis], centroids.max[axis]);
    let below = |i: u32| {
        let t = (centroid(i)[axis] - lo) / (hi - lo);
        ((t * BUCKETS as f32) as usize).min(BUCKETS - 1) <= split
    };
    // Partition in place: the lights of the lower buckets first.
    let mut mid = 0;
    for j in 0..order.len() {
        if below(order[j]) {
            order.swap(j, mid);
            mid += 1;
        }
    }
    (mid > 0 && mid < order.len()).then_some(mid)
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::light::test_rng as rng;

    fn random_lights(n: usize, seed: u64) -> Vec<LightBounds> {
        let mut r = rng(seed);
        (0..n)
            .map(|_| {
                let c = Vec3::new(r() * 20.0 - 10.0, r() * 4.0, r() * 20.0 - 10.0);
                let half = Vec3::splat(0.01 + r() * 0.3);
                let w = Vec3::new(r() - 0.5, r() - 0.5, r() - 0.5).normalize_or(Vec3::Y);
                let kind = r();
                LightBounds {
                    bounds: Aabb {
                        min: c - half,
                        max: c + half,
                    },
                    w,
                    phi: (0.1 + 10.0 * r() as f64).powi(2),
                    cos_o: if kind < 0.5 { 1.0 } else { -1.0 },
                    cos_e: 0.0,
                    two_sided: kind < 0.25,
                }
            })
            .collect()
    }

    #[test]
    fn every_light_has_one_leaf_and_a_trail_to_it() {
        let lights = random_lights(1000, 3);
        let tree = LightTree::build(&lights);
        assert_eq!(tree.node_count(), 2 * lights.len() - 1);
        let mut seen = vec![false; lights.len()];
        for n in tree.nodes.iter().filter(|n| n.leaf) {
            assert!(!seen[n.index as usize]);
            seen[n.index as usize] = true;
        }
        assert!(seen.iter().all(|&s| s));
    }

    #[test]
    fn the_pmf_is_the_sampled_frequency_and_equals_the_sampled_pmf() {
        let lights = random_lights(300, 11);
        let tree = LightTree::build(&lights);
        let mut r = rng(5);
        // Stratified u: each light owns one interval of [0, 1) of length
        // its pmf, so its count is within one stratum of pmf × K; the
        // remainder is the chance that no light can reach the point.
        const K: usize = 20_000;
        for _ in 0..40 {
            let p = Vec3::new(r() * 30.0 - 15.0, r() * 6.0 - 1.0, r() * 30.0 - 15.0);
            let n = Vec3::new(r() - 0.5, r() - 0.5, r() - 0.5).normalize_or(Vec3::Y);
            let mut counts = vec![0usize; lights.len()];
            let mut none = 0;
            for k in 0..K {
                match tree.sample(p, n, (k as f64 + 0.5) / K as f64) {
                    Some((i, pmf)) => {
                        assert_eq!(pmf, tree.pmf(p, n, i));
                        counts[i as usize] += 1;
                    }
                    None => none += 1,
                }
            }
            let mut total = 0.0;
            for (i, &c) in counts.iter().enumerate() {
                let pmf = tree.pmf(p, n, i as u32);
                total += pmf;
                assert!(
                    (c as f64 / K as f64 - pmf).abs() <= 1.01 / K as f64,
                    "{c} {pmf}"
                );
            }
            assert!((none as f64 / K as f64 - (1.0 - total)).abs() <= 40.0 / K as f64);
        }
        // Lights that shine everywhere, seen from no surface: no remainder.
        let omni: Vec<LightBounds> = lights
            .iter()
            .map(|l| LightBounds { cos_o: -1.0, ..*l })
            .collect();
        let tree = LightTree::build(&omni);
        let total: f64 = (0..omni.len() as u32)
            .map(|i| tree.pmf(Vec3::new(1.0, 2.0, 3.0), Vec3::ZERO, i))
            .sum();
        assert!((total - 1.0).abs() < 1e-9, "{total}");
    }

    #[test]
    fn lights_at_one_point_still_split() {
        let one = random_lights(1, 1)[0];
        let lights = vec![one; 100];
        let tree = LightTree::build(&lights);
        let total: f64 = (0..100)
            .map(|i| tree.pmf(Vec3::splat(20.0), Vec3::ZERO, i))
            .sum();
        assert!((total - 1.0).abs() < 1e-9);
    }

    #[test]
    fn a_lone_light_facing_away_is_not_chosen() {
        let light = LightBounds {
            bounds: Aabb {
                min: Vec3::new(-1.0, 0.0, -1.0),
                max: Vec3::new(1.0, 0.0, 1.0),
            },
            w: Vec3::Y,
            phi: 1.0,
            cos_o: 1.0,
            cos_e: 0.0,
            two_sided: false,
        };
        let tree = LightTree::build(&[light]);
        assert_eq!(
            tree.sample(Vec3::new(0.0, 1.0, 0.0), Vec3::ZERO, 0.3),
            Some((0, 1.0))
        );
        // Below, beyond the bounding sphere (inside it, the estimate is
        // conservatively positive).
        assert_eq!(
            tree.sample(Vec3::new(0.0, -5.0, 0.0), Vec3::ZERO, 0.3),
            None
        );
        assert_eq!(tree.pmf(Vec3::new(0.0, -5.0, 0.0), Vec3::ZERO, 0), 0.0);
    }

    #[test]
    fn near_lights_are_chosen_more_often() {
        // Two groups of equal lights; a point beside one group picks it far
        // more often than the other.
        let mut lights = Vec::new();
        for i in 0..64 {
            for x in [-100.0f32, 100.0] {
                let c = Vec3::new(x + (i % 8) as f32, 1.0, (i / 8) as f32);
                lights.push(LightBounds {
                    bounds: Aabb {
                        min: c - 0.1,
                        max: c + 0.1,
                    },
                    w: Vec3::Y,
                    phi: 1.0,
                    cos_o: -1.0,
                    cos_e: 0.0,
                    two_sided: false,
                });
            }
        }
        let tree = LightTree::build(&lights);
        let p = Vec3::new(-96.0, 0.0, 4.0);
        let near: f64 = (0..lights.len() as u32)
            .filter(|&i| lights[i as usize].bounds.center().x < 0.0)
            .map(|i| tree.pmf(p, Vec3::Y, i))
            .sum();
        assert!(near > 0.99, "{near}");
    }
}
