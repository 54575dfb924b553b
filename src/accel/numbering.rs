//! The final primitive numbers, chosen once the wide BVH is packed.
//!
//! The primitives that need a 64-byte record (all but the plain triangles of
//! [`Tri4`](crate::accel::tri4::Tri4) blocks) come first, in leaf order,
//! so that a leaf's records are contiguous in memory and its primitives stay
//! consecutive; then room for the planes; then the plain triangles in leaf
//! order, numbers without records. A bit per place and a running count per
//! 64 places answer "which number" (a rank query, as in succinct data
//! structures) in 0.16 bytes per primitive instead of an array of 4.

use crate::accel::bvh4::Bvh4;

/// Maps places in the binary BVH's order to final primitive numbers.
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

    /// The number of the primitive at `place`.
    pub fn id(&self, place: u32) -> u32 {
        let (word, bit) = ((place / 64) as usize, place % 64);
        let w = self.plain_bits[word];
        let plain_before = self.plain_before[word] + (w & ((1u64 << bit) - 1)).count_ones();
        if w & (1 << bit) != 0 {
            self.plain_from + plain_before
        } else {
            place - plain_before
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::tri4::{PackedTriangle, Tri4};

    #[test]
    fn records_first_then_planes_then_plain_triangles() {
        // 150 places (three words); the plain ones are every third place.
        let places = 150u32;
        let plain: Vec<u32> = (0..places).filter(|p| p % 3 == 0).collect();
        let tri = |p: u32| {
            let plain = PackedTriangle {
                vertices: [glam::Vec3::ZERO; 3],
                plain: true,
                quad: false,
            };
            (p, plain)
        };
        let wide = Bvh4 {
            nodes: Vec::new(),
            tris: plain
                .chunks(4)
                .map(|c| Tri4::new(&c.iter().map(|&p| tri(p)).collect::<Vec<_>>()))
                .collect(),
        };
        let numbering = Numbering::new(&wide, places as usize, 2);
        assert_eq!(numbering.plain, 50);
        assert_eq!(numbering.plain_from, 102);
        let ids: Vec<u32> = (0..places).map(|p| numbering.id(p)).collect();
        // Records 0..100 and plain 102..152 in place order: a permutation
        // that leaves 100 and 101 to the planes.
        let (mut record, mut next_plain) = (0, 102);
        for (p, &id) in ids.iter().enumerate() {
            let counter = if p % 3 == 0 {
                &mut next_plain
            } else {
                &mut record
            };
            assert_eq!(id, *counter, "place {p}");
            *counter += 1;
        }
    }
}
