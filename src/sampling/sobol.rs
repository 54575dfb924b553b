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

/// Direction numbers of Sobol's second dimension (primitive polynomial
/// x + 1, m₁ = 1: the Pascal matrix mod 2), bit j of the index to the 32
/// output bits, most significant first.
const fn direction(j: u32) -> u32 {
    let mut v = 1u32 << 31;
    let mut i = 0;
    while i < j {
        v ^= v >> 1;
        i += 1;
    }
    v
}

/// The second dimension, bit-reversed, by index byte: entry `b` of table
/// `k` is the XOR of the reversed direction numbers of the bits set in
/// byte value `b` at byte `k` of the index. Four lookups replace a loop
/// over 32 index bits (a shuffled index has all of them set at random).
const REVERSED_SECOND: [[u32; 256]; 4] = {
    let mut table = [[0u32; 256]; 4];
    let mut k = 0;
    while k < 4 {
        let mut b = 0;
        while b < 256 {
            let mut x = 0u32;
            let mut bit = 0;
            while bit < 8 {
                if b & (1 << bit) != 0 {
                    x ^= direction(8 * k as u32 + bit).reverse_bits();
                }
                bit += 1;
            }
            table[k][b] = x;
            b += 1;
        }
        k += 1;
    }
    table
};

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
        let [b0, b1, b2, b3] = i.to_le_bytes();
        let second_reversed = REVERSED_SECOND[0][b0 as usize]
            ^ REVERSED_SECOND[1][b1 as usize]
            ^ REVERSED_SECOND[2][b2 as usize]
            ^ REVERSED_SECOND[3][b3 as usize];
        (
            owen_reversed(i, self.x),
            owen_reversed(second_reversed, self.y),
        )
    }
}

#[cfg(test)]
#[path = "sobol_tests.rs"]
mod tests;
