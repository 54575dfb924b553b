//! Four spheres tested against one ray at once: the leaf format of the wide
//! BVH for static spheres, as [`super::tri4`] is for triangles.
//!
//! Each lane repeats the scalar test's operations
//! ([`crate::geometry::sphere::intersect`]: the discriminant from the
//! perpendicular distance, Haines et al., Ray Tracing Gems ch. 7, and the
//! cancellation-free roots) in the scalar test's order, so both give
//! bit-identical distances. Spheres keep their records: a hit is finished
//! from the record, as before; the block only spares the traversal the last
//! level of nodes and the records of the spheres a ray misses.

use glam::{Vec3, Vec4};

/// Up to four spheres, one per lane; unused lanes have `prim` `u32::MAX`.
#[derive(Debug, Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
#[repr(C, align(16))]
pub struct Sph4 {
    /// Centre, per axis.
    pub center: [[f32; 4]; 3],
    /// Radius.
    pub radius: [f32; 4],
    /// The primitive each lane is (`u32::MAX`: unused).
    pub prim: [u32; 4],
}

const _: () = assert!(std::mem::size_of::<Sph4>() == 80);

impl Sph4 {
    /// Packs up to four `(prim, centre, radius)` spheres.
    pub fn new(spheres: &[(u32, Vec3, f32)]) -> Sph4 {
        assert!(spheres.len() <= 4, "a Sph4 holds at most four spheres");
        let mut block = Sph4 {
            center: [[0.0; 4]; 3],
            radius: [0.0; 4],
            prim: [u32::MAX; 4],
        };
        for (lane, &(prim, center, radius)) in spheres.iter().enumerate() {
            for axis in 0..3 {
                block.center[axis][lane] = center[axis];
            }
            block.radius[lane] = radius;
            block.prim[lane] = prim;
        }
        block
    }

    /// The lanes in use, as a bit mask.
    #[inline(always)]
    fn used(&self) -> u32 {
        let bit = |lane: usize| ((self.prim[lane] != u32::MAX) as u32) << lane;
        bit(0) | bit(1) | bit(2) | bit(3)
    }

    /// Per lane the distance of the first root in `(t_min, t_max)`, and the
    /// mask of lanes that have one.
    #[inline(always)]
    fn test(&self, o: Vec3, d: Vec3, t_min: f32, t_max: f32) -> (Vec4, u32) {
        let [cx, cy, cz] = self.center.map(Vec4::from_array);
        let r = Vec4::from_array(self.radius);
        let (dx, dy, dz) = (Vec4::splat(d.x), Vec4::splat(d.y), Vec4::splat(d.z));
        let (ocx, ocy, ocz) = (
            Vec4::splat(o.x) - cx,
            Vec4::splat(o.y) - cy,
            Vec4::splat(o.z) - cz,
        );
        // As the scalar test: a = |d|², b = oc · d, term by term.
        let a = Vec4::splat(d.length_squared());
        let b = ocx * dx + ocy * dy + ocz * dz;
        let s = b / a;
        let (px, py, pz) = (ocx - s * dx, ocy - s * dy, ocz - s * dz);
        let disc = r * r - (px * px + py * py + pz * pz);
        // Most rays that reach a block miss all its spheres: stop here, as
        // the scalar test does, before the square root and the divisions.
        let live = disc.cmpge(Vec4::ZERO).bitmask() & self.used();
        if live == 0 {
            return (Vec4::ZERO, 0);
        }
        // (Per lane: glam's Vec4 has no square root; this is `sqrtps`.)
        let sq = Vec4::from_array((a * disc).to_array().map(f32::sqrt));
        let q = -(b + sq.copysign(b));
        let c = (ocx * ocx + ocy * ocy + ocz * ocz) - r * r;
        let t0 = q / a;
        // c / q where q ≠ 0, else 0 (a sphere the ray grazes at its origin).
        let t1 = Vec4::select(q.cmpne(Vec4::ZERO), c / q, Vec4::ZERO);
        let swap = t0.cmpgt(t1);
        let (near, far) = (Vec4::select(swap, t1, t0), Vec4::select(swap, t0, t1));
        let (lo, hi) = (Vec4::splat(t_min), Vec4::splat(t_max));
        let near_ok = near.cmpgt(lo) & near.cmplt(hi);
        let far_ok = far.cmpgt(lo) & far.cmplt(hi);
        let t = Vec4::select(near_ok, near, far);
        (t, (near_ok | far_ok).bitmask() & live)
    }

    /// The closest hit in `(t_min, t_max)` of the ray `o + t·d`: lane and
    /// distance; on equal distances the lowest lane, as testing the lanes in
    /// turn would.
    #[inline(always)]
    pub fn closest(&self, o: Vec3, d: Vec3, t_min: f32, t_max: f32) -> Option<(usize, f32)> {
        let (t, mask) = self.test(o, d, t_min, t_max);
        if mask == 0 {
            return None;
        }
        let mut best: Option<(usize, f32)> = None;
        for lane in 0..4 {
            if mask & (1 << lane) != 0 && best.is_none_or(|b| t[lane] < b.1) {
                best = Some((lane, t[lane]));
            }
        }
        best
    }

    /// Whether any sphere is hit in `(t_min, t_max)`.
    #[inline(always)]
    pub fn any(&self, o: Vec3, d: Vec3, t_min: f32, t_max: f32) -> bool {
        self.test(o, d, t_min, t_max).1 != 0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::sphere;
    use crate::geometry::Ray;
    use proptest::prelude::*;

    proptest! {
        /// Every lane gives the scalar test's answer, bit for bit, and the
        /// block's closest hit is the scalar tests' first minimum.
        #[test]
        fn lanes_match_the_scalar_test(
            spheres in prop::collection::vec((-4f32..4.0, -4f32..4.0, -4f32..4.0, 0.01f32..3.0), 1..=4),
            o in (-6f32..6.0, -6f32..6.0, -6f32..6.0),
            d in (-1f32..1.0, -1f32..1.0, -1f32..1.0),
            far in prop::bool::ANY,
            t_min in prop::sample::select(vec![0.0f32, 1e-4, 0.5]),
            t_max in prop::sample::select(vec![f32::INFINITY, 2.0, 0.3]),
        ) {
            let d = Vec3::new(d.0, d.1, d.2);
            prop_assume!(d.length_squared() > 1e-4);
            // Far origins exercise the careful discriminant.
            let scale = if far { 1e4 } else { 1.0 };
            let ray = Ray::new(Vec3::new(o.0, o.1, o.2) * scale, d.normalize(), 0.0);
            let list: Vec<(u32, Vec3, f32)> = spheres
                .iter()
                .enumerate()
                .map(|(k, s)| (k as u32 * 7, Vec3::new(s.0, s.1, s.2), s.3))
                .collect();
            let block = Sph4::new(&list);
            let mut want: Option<(usize, f32)> = None;
            for (lane, &(_, c, r)) in list.iter().enumerate() {
                let one = sphere::intersect(c, r, &ray, t_min, t_max).map(|h| h.t);
                let (t, mask) = block.test(ray.o, ray.d, t_min, t_max);
                prop_assert_eq!(one.map(f32::to_bits), (mask & (1 << lane) != 0).then(|| t[lane].to_bits()));
                if let Some(t) = one {
                    if want.is_none_or(|w| t < w.1) {
                        want = Some((lane, t));
                    }
                }
            }
            let got = block.closest(ray.o, ray.d, t_min, t_max);
            prop_assert_eq!(got.map(|(l, t)| (l, t.to_bits())), want.map(|(l, t)| (l, t.to_bits())));
            prop_assert_eq!(block.any(ray.o, ray.d, t_min, t_max), want.is_some());
        }
    }

    #[test]
    fn unused_lanes_never_hit() {
        let block = Sph4::new(&[(3, Vec3::new(0.0, 0.0, -5.0), 1.0)]);
        // A ray through the origin, where the unused lanes' zero spheres sit.
        let ray = Ray::new(Vec3::new(0.0, 0.0, 1.0), -Vec3::Z, 0.0);
        assert_eq!(
            block
                .closest(ray.o, ray.d, 1e-4, f32::INFINITY)
                .map(|h| h.0),
            Some(0)
        );
        let away = Ray::new(Vec3::new(0.0, 0.0, 1.0), Vec3::Z, 0.0);
        assert!(!block.any(away.o, away.d, 1e-4, f32::INFINITY));
    }
}
