//! Owen-scrambled Sobol points, one sequence per pixel: Burley 2020,
//! "Practical Hash-based Owen Scrambling" (JCGT 9(4)), as pbrt-v4's
//! `PaddedSobolSampler` uses it.
//!
//! Every draw of a sample ("slot": the film position, the lens, a bounce's
//! light point, its BSDF direction, …) takes the first two dimensions of
//! the Sobol sequence, a (0, 2)-sequence in base 2, under its own
//! randomisation: the sample index is shuffled by a nested uniform
//! scramble, and each coordinate is Owen-scrambled. The shuffle keeps the
//! index's low bits a permutation of themselves, and Sobol's generator
//! matrices are upper triangular (index bit j moves output bits j and
//! finer only), so the first 2^k samples of any slot still form a
//! (0, k, 2)-net; the scrambles decorrelate slots from each other and
//! pixels from each other. Only two dimensions are ever needed (no table
//! of direction numbers to run out of), and a point is a pure function of
//! (key, slot, sample index) for indices up to 2^32 — the key being the
//! render's seed and the pixel —, whatever the number
//! of samples per pixel.

/// Sobol's second dimension of the index `i`, bit-reversed. Its generator
/// is the Pascal matrix mod 2: index bit j sets output bit 31 − k where
/// C(j, k) is odd, which by Lucas' theorem is where k's bits are a subset
/// of j's. So bit k of the reversed value is the XOR of the index bits at
/// the positions j ⊇ k: a sum over supersets of the 5-bit positions, five
/// shifted XORs. No table loads, so a batch's lanes compute it side by side.
#[inline(always)]
fn second_reversed(mut i: u32) -> u32 {
    i ^= (i >> 1) & 0x5555_5555;
    i ^= (i >> 2) & 0x3333_3333;
    i ^= (i >> 4) & 0x0f0f_0f0f;
    i ^= (i >> 8) & 0x00ff_00ff;
    i ^= (i >> 16) & 0x0000_ffff;
    i
}

/// Laine and Karras's hash as improved by Burley (2020, listing 2): a
/// bijection of 32 bits in which each output bit depends on the same and
/// less significant input bits only. Applied to bit-reversed values, it
/// flips each bit by a hash of the bits above it: an Owen scramble.
#[inline(always)]
fn laine_karras(mut x: u32, seed: u32) -> u32 {
    x = x.wrapping_add(seed);
    x ^= x.wrapping_mul(0x6c50_b47c);
    x ^= x.wrapping_mul(0xb82f_1e52);
    x ^= x.wrapping_mul(0xc7af_e638);
    x ^= x.wrapping_mul(0x8d22_f6e6);
    x
}

/// The nested uniform (Owen) scramble of `x` under `seed`, given `x`
/// bit-reversed: reversing, hashing and reversing back.
#[inline(always)]
fn owen_reversed(x_reversed: u32, seed: u32) -> u32 {
    laine_karras(x_reversed, seed).reverse_bits()
}

/// SplitMix64's finaliser (Steele et al. 2014), to spread structured keys:
/// the samplers' seeds hash pixels, samples and slots with it.
#[inline(always)]
pub(crate) fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The randomisation of one slot of one pixel's sequence: the seeds of the
/// shuffle of the sample index and of the two coordinates' scrambles. A
/// pixel's seeds serve all its samples (computed once per pixel).
#[derive(Debug, Clone, Copy, Default)]
pub struct SlotSeeds {
    shuffle: u32,
    x: u32,
    y: u32,
}

impl SlotSeeds {
    /// The seeds of `slot` in the sequence keyed by `key` (the render's
    /// seed and the pixel, hashed): one 64-bit hash gives its halves and
    /// their sum rotated (a third value that neither half determines alone).
    pub fn new(key: u64, slot: u32) -> SlotSeeds {
        let h = mix(key ^ (slot as u64 + 1).wrapping_mul(0x9e37_79b9_7f4a_7c15));
        let (lo, hi) = (h as u32, (h >> 32) as u32);
        SlotSeeds {
            shuffle: lo,
            x: hi,
            y: lo.wrapping_add(hi).rotate_left(16) ^ 0x5851_f42d,
        }
    }

    /// The sample index as this slot shuffles it (a nested uniform
    /// scramble of the index, given bit-reversed), in natural bit order.
    #[inline(always)]
    fn shuffled(self, index_reversed: u32) -> u32 {
        owen_reversed(index_reversed, self.shuffle)
    }

    /// The slot's value for the sample whose index, bit-reversed, is
    /// `index_reversed`: 32 bits, uniform. Coordinate 0 of the shuffled
    /// index, scrambled; the van der Corput value is the index reversed,
    /// so the scramble's own reversal gives the index back.
    #[inline(always)]
    pub fn get1(self, index_reversed: u32) -> u32 {
        owen_reversed(self.shuffled(index_reversed), self.x)
    }

    /// The slot's two values for a sample (see [`SlotSeeds::get1`]): both
    /// coordinates of the shuffled index, each scrambled.
    #[inline(always)]
    pub fn get2(self, index_reversed: u32) -> (u32, u32) {
        let i = self.shuffled(index_reversed);
        (
            owen_reversed(i, self.x),
            owen_reversed(second_reversed(i), self.y),
        )
    }

    /// [`SlotSeeds::get2`] of the samples `first`, `first + 1`, … (`L` of
    /// them, wrapping past `u32::MAX`), both coordinates apart: one pass over
    /// the lanes with the same operations in each, which the compiler turns
    /// into vector instructions.
    #[inline(always)]
    pub fn get2_lanes<const L: usize>(self, first: u32) -> ([u32; L], [u32; L]) {
        let (mut xs, mut ys) = ([0; L], [0; L]);
        for lane in 0..L {
            let index = first.wrapping_add(lane as u32);
            (xs[lane], ys[lane]) = self.get2(index.reverse_bits());
        }
        (xs, ys)
    }
}

#[cfg(test)]
#[path = "sobol_tests.rs"]
mod tests;
