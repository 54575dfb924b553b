//! The final numbers of the primitives with records, chosen once the wide
//! BVH is packed.
//!
//! The primitives that need a 64-byte record (all but the plain triangles of
//! [`Tri4`](crate::accel::tri4::Tri4) blocks) come first, in leaf order,
//! so that a leaf's records are contiguous in memory and its primitives stay
//! consecutive; then room for the planes; then the plain triangles, numbers
//! without records, which [`Bvh4::renumber`] gives in block order. A bit
//! per place and a running count per 64 places answer "which number" (a
//! rank query, as in succinct data structures) in 0.16 bytes per primitive
//! instead of an array of 4.

use crate::accel::bvh4::Bvh4;

/// Maps places in the binary BVH's order to the numbers of records.
#[derive(Debug)]
pub struct Numbering {
    /// Bit `place` set when the primitive there is a plain triangle.
    plain_bits: Vec<u64>,
    /// Plain triangles before each word of `plain_bits`.
    plain_before: Vec<u32>,
    /// The first plain triangle's number (records and planes come before).
    pub plain_from: u32,
    /// How many plain triangles.
    pub plain: u32,
}

impl Numbering {
    /// The numbering of `places` primitives whose plain triangles are those
    /// marked plain in `wide`'s blocks (numbered by place), with `planes`
    /// planes to number after the records.
    pub fn new(wide: &Bvh4, places: usize, planes: usize) -> Numbering {
        let mut plain_bits = vec![0u64; places.div_ceil(64)];
        for place in wide.plain_prims() {
            plain_bits[place as usize / 64] |= 1 << (place % 64);
        }
        let mut plain = 0u32;
        let plain_before = plain_bits
            .iter()
            .map(|w| {
                let before = plain;
                plain += w.count_ones();
                before
            })
            .collect();
        Numbering {
            plain_bits,
            plain_before,
            plain_from: (places + planes) as u32 - plain,
            plain,
        }
    }

    /// Whether the primitive at `place` is a plain triangle (numbered by
    /// the blocks, not here).
    pub fn is_plain(&self, place: u32) -> bool {
        self.plain_bits[(place / 64) as usize] & (1 << (place % 64)) != 0
    }

    /// The number of the record at `place` (not a plain triangle): its
    /// place less the plain triangles before it.
    pub fn record_id(&self, place: u32) -> u32 {
        debug_assert!(!self.is_plain(place));
        let (word, bit) = ((place / 64) as usize, place % 64);
        let w = self.plain_bits[word];
        place - (self.plain_before[word] + (w & ((1u64 << bit) - 1)).count_ones())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::tri4::{PackedTriangle, Tri4};

    #[test]
    fn records_first_then_planes_then_plain_triangles_in_block_order() {
        // 150 places (three words); the plain ones are every third place,
        // packed in blocks in descending order of place.
        let places = 150u32;
        let plain: Vec<u32> = (0..places).rev().filter(|p| p % 3 == 0).collect();
        let tri = |p: u32| {
            let plain = PackedTriangle {
                vertices: [glam::Vec3::new(p as f32, 0.0, 0.0); 3],
                plain: true,
                quad: false,
                swapped: p.is_multiple_of(2),
            };
            (p, plain)
        };
        let mut wide = Bvh4::default();
        wide.tris = plain
            .chunks(4)
            .map(|c| Tri4::new(&c.iter().map(|&p| tri(p)).collect::<Vec<_>>()))
            .collect();
        let numbering = Numbering::new(&wide, places as usize, 2);
        assert_eq!(numbering.plain, 50);
        assert_eq!(numbering.plain_from, 102);
        // Records 0..100 in place order, leaving 100 and 101 to the planes.
        let records: Vec<u32> = (0..places)
            .filter(|&p| !numbering.is_plain(p))
            .map(|p| numbering.record_id(p))
            .collect();
        assert_eq!(records, (0..100).collect::<Vec<u32>>());
        // Plain triangles 102..152 in block order, found again by number.
        let mut given = Vec::new();
        wide.renumber(
            |p| numbering.record_id(p),
            numbering.plain_from,
            |old, new| given.push((old, new)),
        );
        let want: Vec<(u32, u32)> = plain.iter().zip(102..).map(|(&p, n)| (p, n)).collect();
        assert_eq!(given, want);
        for (old, new) in want {
            let lane = wide.plain_lane(new).expect("a plain lane");
            assert_eq!(lane, tri(old).1);
        }
        assert!(wide.plain_lane(101).is_none() && wide.plain_lane(152).is_none());
    }
}
