use super::*;
use crate::sampling::chi2::pearson_p_value;
use proptest::prelude::*;

/// Direction numbers of Sobol's second dimension (primitive polynomial
/// x + 1, m₁ = 1: the Pascal matrix mod 2), bit j of the index to the 32
/// output bits, most significant first.
fn direction(j: u32) -> u32 {
    let mut v = 1u32 << 31;
    let mut i = 0;
    while i < j {
        v ^= v >> 1;
        i += 1;
    }
    v
}

/// Sample `index` of a pixel's sequence keyed by `key`.
struct SobolPoint {
    key: u64,
    index: u32,
}

impl SobolPoint {
    fn new(key: u64, index: u32) -> SobolPoint {
        SobolPoint { key, index }
    }

    fn get1(&self, slot: u32) -> u32 {
        SlotSeeds::new(self.key, slot).get1(self.index.reverse_bits())
    }

    fn get2(&self, slot: u32) -> (u32, u32) {
        SlotSeeds::new(self.key, slot).get2(self.index.reverse_bits())
    }
}

/// Sobol's second dimension unscrambled, from the direction numbers.
fn plain_second(index: u32) -> u32 {
    (0..32)
        .filter(|j| index & (1 << j) != 0)
        .fold(0, |x, j| x ^ direction(j))
}

#[test]
fn the_second_dimension_is_sobols() {
    // Joe and Kuo's dimension 2: m = 1, 3, 5, 15, 17, …
    let m: Vec<u32> = (0..6).map(|j| direction(j) >> (31 - j)).collect();
    assert_eq!(m, [1, 3, 5, 15, 17, 51]);
    let eighths: Vec<u32> = (0..8).map(|i| plain_second(i) >> 29).collect();
    assert_eq!(eighths, [0, 4, 6, 2, 5, 1, 3, 7]);
    // The sum over supersets gives the same values, bit-reversed: every
    // index bit alone (the matrix's columns), and mixtures.
    let singles = (0..32).map(|j| 1u32 << j);
    for i in singles.chain([0u32, 7, 255, 256, 0x1234_5678, 0xdead_beef, u32::MAX]) {
        assert_eq!(
            second_reversed(i).reverse_bits(),
            plain_second(i),
            "index {i:#x}"
        );
    }
}

proptest! {
    /// A batch keeps only `get2`'s values, and a one-dimensional draw of a
    /// batched sample reads its first coordinate where the scalar draw calls
    /// `get1`: the two must be one number. (That the batch's lanes equal
    /// single draws is tested through the sampler, `a_batch_draws_what_single_samples_draw`,
    /// where the lanes run as the dispatched vector code.)
    #[test]
    fn a_one_dimensional_draw_is_the_first_coordinate(key: u64, slot in 0u32..16, index: u32) {
        let seeds = SlotSeeds::new(key, slot);
        prop_assert_eq!(seeds.get1(index.reverse_bits()), seeds.get2(index.reverse_bits()).0);
    }
}

#[test]
fn the_scramble_is_a_bijection_that_keeps_prefixes() {
    // Owen scrambling maps every dyadic interval onto a dyadic interval of
    // the same length: values agreeing on their top k bits still agree on
    // their top k bits after the scramble.
    let seed = 0x5eed_1234;
    for k in 1..12 {
        for x in [0u32, 0x8000_0000, 0x1234_5678, 0xdead_beef] {
            let y = x ^ (1 << (31 - k)) ^ 0x0000_0f0f >> k.min(8);
            let (sx, sy) = (
                owen_reversed(x.reverse_bits(), seed),
                owen_reversed(y.reverse_bits(), seed),
            );
            assert_eq!(sx >> (32 - k), sy >> (32 - k), "k {k} x {x:#x}");
        }
    }
    let mut seen = std::collections::HashSet::new();
    for x in 0..1u32 << 16 {
        assert!(seen.insert(owen_reversed((x << 16).reverse_bits(), seed) >> 16));
    }
}

/// Whether `points` (2^k of them, as 32-bit fixed point) form a
/// (0, k, 2)-net: exactly one point in each of the 2^k cells of every grid
/// of 2^a × 2^(k − a) cells.
fn is_net(points: &[(u32, u32)], k: u32) -> bool {
    (0..=k).all(|a| {
        let mut cells = vec![0u32; 1 << k];
        for &(x, y) in points {
            let cx = if a == 0 { 0 } else { x >> (32 - a) };
            let cy = if a == k { 0 } else { y >> (32 - (k - a)) };
            cells[((cx << (k - a)) | cy) as usize] += 1;
        }
        cells.iter().all(|&c| c == 1)
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// The first 2^k samples of every slot, and any aligned block of 2^k,
    /// are a (0, k, 2)-net; a one-dimensional slot puts one sample in each
    /// interval of length 2^-k.
    #[test]
    fn every_slot_is_stratified(
        key in any::<u64>(),
        slot in 0u32..64,
        k in 1u32..=10,
        block in 0u32..1000,
    ) {
        let indices = (block << k)..((block + 1) << k);
        let points: Vec<(u32, u32)> = indices
            .clone()
            .map(|i| SobolPoint::new(key, i).get2(slot))
            .collect();
        prop_assert!(is_net(&points, k));
        let mut strata = vec![false; 1 << k];
        for i in indices {
            let x = SobolPoint::new(key, i).get1(slot) >> (32 - k);
            prop_assert!(!strata[x as usize], "two samples in one stratum");
            strata[x as usize] = true;
        }
    }
}

/// Pearson's χ² p-value of `values` (pairs in [0, 2^32)²) in an 8 × 8 grid
/// against the uniform distribution.
fn uniform_p_value(values: impl Iterator<Item = (u32, u32)>) -> f64 {
    let mut observed = vec![0.0; 64];
    let mut n = 0.0;
    for (x, y) in values {
        observed[((x >> 29) * 8 + (y >> 29)) as usize] += 1.0;
        n += 1.0;
    }
    pearson_p_value(&observed, &vec![n / 64.0; 64])
}

#[test]
fn pixels_and_slots_are_decorrelated() {
    // One sample index across 20,000 pixels: uniform (pixels' sequences are
    // scrambled independently, so they do not all start at one point).
    let pixels = (0..20_000u64).map(|p| SobolPoint::new(p * 0x9e37_79b9 + 7, 5).get2(3));
    let p = uniform_p_value(pixels);
    assert!(p > 1e-4, "pixels: p = {p}");
    // Two slots of one pixel against each other over 4,096 samples, and
    // the two coordinates of one slot across pixels: no dependence.
    let slots = (0..4096u32).map(|i| {
        let s = SobolPoint::new(42, i);
        (s.get1(2), s.get2(7).1)
    });
    let p = uniform_p_value(slots);
    assert!(p > 1e-4, "slots 2 and 7: p = {p}");
    let adjacent = (0..4096u32).map(|i| {
        let s = SobolPoint::new(42, i);
        (s.get2(0).0, s.get2(1).0)
    });
    let p = uniform_p_value(adjacent);
    assert!(p > 1e-4, "slots 0 and 1: p = {p}");
}

#[test]
fn points_are_a_pure_function_of_key_slot_and_index() {
    let a = SobolPoint::new(9, 1234).get2(4);
    assert_eq!(a, SobolPoint::new(9, 1234).get2(4));
    assert_ne!(a, SobolPoint::new(10, 1234).get2(4));
    assert_ne!(a, SobolPoint::new(9, 1235).get2(4));
    assert_ne!(a, SobolPoint::new(9, 1234).get2(5));
    // The largest indices work too (no table to run out of).
    let last = SobolPoint::new(9, u32::MAX).get2(4);
    assert_ne!(last, SobolPoint::new(9, u32::MAX - 1).get2(4));
}
