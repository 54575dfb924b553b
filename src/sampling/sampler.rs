//! Deterministic random streams: one per (seed, pixel, sample), so an image
//! does not depend on the thread count or the tile order (pbrt's
//! `StartPixelSample`).

use glam::Vec2;

/// A PCG32 generator (O'Neill 2014) seeded per sample.
#[derive(Debug, Clone)]
pub struct Sampler {
    state: u64,
    inc: u64,
}

/// SplitMix64 finaliser, to spread structured seeds.
fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

impl Sampler {
    /// The stream of sample `sample` of pixel (`x`, `y`) under `seed`.
    pub fn new(seed: u64, x: u32, y: u32, sample: u32) -> Sampler {
        let pixel = ((y as u64) << 32) | x as u64;
        let state = mix(seed ^ mix(pixel ^ mix(sample as u64 + 0x9e37_79b9)));
        let inc = (mix(pixel.wrapping_add(seed.rotate_left(17))) << 1) | 1;
        let mut s = Sampler { state: 0, inc };
        s.next_u32();
        s.state = s.state.wrapping_add(state);
        s.next_u32();
        s
    }

    /// The next 32 random bits.
    #[inline]
    pub fn next_u32(&mut self) -> u32 {
        let old = self.state;
        self.state = old
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(self.inc);
        let xorshifted = (((old >> 18) ^ old) >> 27) as u32;
        let rot = (old >> 59) as u32;
        xorshifted.rotate_right(rot)
    }

    /// A uniform number in [0, 1).
    #[inline]
    pub fn next_f32(&mut self) -> f32 {
        (self.next_u32() >> 8) as f32 * (1.0 / 16_777_216.0)
    }

    /// A uniform number in [0, 1) with 32 bits (from one draw, as
    /// [`Sampler::next_f32`]): for choices among many (a light of a tree).
    #[inline]
    pub fn next_f64(&mut self) -> f64 {
        self.next_u32() as f64 * (1.0 / 4_294_967_296.0)
    }

    /// A uniform point in [0, 1)².
    #[inline]
    pub fn next_2d(&mut self) -> Vec2 {
        Vec2::new(self.next_f32(), self.next_f32())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn streams_are_reproducible_and_distinct() {
        let a: Vec<u32> = (0..8)
            .map({
                let mut s = Sampler::new(1, 2, 3, 4);
                move |_| s.next_u32()
            })
            .collect();
        let b: Vec<u32> = (0..8)
            .map({
                let mut s = Sampler::new(1, 2, 3, 4);
                move |_| s.next_u32()
            })
            .collect();
        let c: Vec<u32> = (0..8)
            .map({
                let mut s = Sampler::new(1, 2, 3, 5);
                move |_| s.next_u32()
            })
            .collect();
        assert_eq!(a, b);
        assert_ne!(a, c);
    }

    #[test]
    fn uniform_mean() {
        let mut s = Sampler::new(7, 0, 0, 0);
        let m: f64 = (0..100_000).map(|_| s.next_f32() as f64).sum::<f64>() / 100_000.0;
        assert!((m - 0.5).abs() < 0.01);
    }
}
