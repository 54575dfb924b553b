//! A packet of camera rays traced together ([`crate::accel::packet`]): the
//! same hits as [`Scene::intersect`] gives each ray, in scenes whose
//! primitives all sit in the scene's own tree.

use super::{cutout, Hit, Scene};
use crate::accel::bvh4::TreeHit;
use crate::accel::packet::Closest;
use crate::accel::ray_count;
use crate::geometry::Ray;

/// The fewest wide nodes of a tree that packets walk.
const PACKET_NODES: usize = 64;

/// The first hits of a packet of rays, each found by [`PacketHits::get`].
pub struct PacketHits<'a> {
    scene: &'a Scene,
    rays: &'a [Ray],
    t_min: f32,
    closest: Closest,
}

impl PacketHits<'_> {
    /// How many blocks and primitives the packet's walk tested, each with
    /// every ray of the packet.
    pub fn leaf_tests(&self) -> u32 {
        self.closest.leaf_tests
    }

    /// Ray `r`'s closest hit, as [`Scene::intersect`] gives it (counted
    /// as a closest-hit query).
    #[inline(always)]
    pub fn get(&self, r: usize) -> Option<Hit> {
        ray_count::closest();
        let (scene, ray, t_min) = (self.scene, &self.rays[r], self.t_min);
        let mut best = self.closest.get(r, &scene.wide);
        for &i in scene.unbounded.iter() {
            let p = &scene.prims[i as usize];
            let tmax = best.map_or(f32::INFINITY, |b| b.hit.t);
            if let Some(hit) = cutout::first_kept(p, ray, (t_min, tmax), |_| false) {
                best = Some(TreeHit {
                    prim: i,
                    hit,
                    plain: None,
                });
            }
        }
        best.map(|b| scene.finish_own(ray, b))
    }
}

impl Scene {
    /// Whether [`Scene::intersect_packet`] traces packets here: scenes
    /// without placements of groups and cutouts, whose hits the tree's
    /// own walk finds, and whose tree is deep enough for a packet to pay
    /// (the Cornell box's few nodes cost a single ray less than a packet's
    /// set-up: docs/performance.md, "Camera-ray packets").
    pub fn traces_packets(&self) -> bool {
        self.instances.is_empty() && self.cutouts.is_none() && self.wide.nodes.len() >= PACKET_NODES
    }

    /// The closest hit of each of `rays` (1 to [`PACKET`](crate::accel::packet::PACKET), from one pixel:
    /// coherent) beyond `t_min`, equal to what [`Scene::intersect`] finds
    /// for each. `None` where the scene or the rays do not go as a packet
    /// ([`Scene::traces_packets`], rays of mixed direction signs): trace
    /// them one by one.
    pub fn intersect_packet<'a>(&'a self, rays: &'a [Ray], t_min: f32) -> Option<PacketHits<'a>> {
        if !self.traces_packets() {
            return None;
        }
        let closest = self
            .wide
            .closest_packet(rays, t_min, f32::INFINITY, |r, i, tmax| {
                let p = &self.prims[i as usize];
                cutout::first_kept(p, &rays[r], (t_min, tmax), |_| false)
            })?;
        Some(PacketHits {
            scene: self,
            rays,
            t_min,
            closest,
        })
    }
}
