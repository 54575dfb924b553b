//! Deterministic sample streams: one per (seed, pixel, sample), so an image
//! does not depend on the thread count or the tile order (pbrt's
//! `StartPixelSample`).
//!
//! Two kinds (`render { sampler … }`): `independent` draws every number
//! from a PCG32 stream; `sobol` draws each of a sample's decisions from its
//! own slot of an Owen-scrambled Sobol sequence ([`super::sobol`]), so that
//! a pixel's samples are stratified in every decision. Slots are assigned
//! by purpose, the same in every sample: the film position, the lens and
//! the time, then for each bounce the light choice and point, the BSDF's
//! lobe and direction, and Russian roulette ([`Draws`]). Draws beyond a
//! purpose's slots (a Whitted hit's many shadow rays, the branches of its
//! tree) come from the PCG stream, never from a slot already used: a slot
//! used twice in one path would correlate two decisions and bias the image.

use super::sobol::{mix, SlotSeeds};
use glam::Vec2;

/// Which numbers a sample draws (`render { sampler … }`, `--sampler`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SamplerKind {
    /// Owen-scrambled Sobol points, one slot per decision (the default).
    Sobol,
    /// Independent uniform numbers (PCG32).
    Independent,
}

named_values!(SamplerKind {
    "sobol" => Sobol,
    "independent" => Independent,
});

/// What a bounce draws, in this order, each purpose from slots of its own.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Draws {
    /// Next-event estimation: the light (1D) and the point on it (2D).
    Light,
    /// Sampling the BSDF: the lobe (1D) and the direction (2D).
    Bsdf,
    /// Russian roulette (1D).
    Roulette,
}

impl Draws {
    /// The purpose's slots within a bounce's.
    fn slots(self) -> (u32, u32) {
        match self {
            Draws::Light => (0, 2),
            Draws::Bsdf => (2, 4),
            Draws::Roulette => (4, 5),
        }
    }
}

/// The camera's slots: the film position, the lens, the time.
const CAMERA_SLOTS: u32 = 3;

/// Slots per bounce (see [`Draws`]).
const BOUNCE_SLOTS: u32 = 5;

/// Bounces whose light and BSDF draws are Sobol points; later bounces and
/// Russian roulette draw from the PCG stream. Measured (docs/performance.md,
/// "Sobol sampler"): the first two bounces hold all of the gain, and the
/// Sobol draws cost 6–9 % of the bench scenes' render time.
const SOBOL_BOUNCES: u32 = 2;

/// Slots with seeds of their own: the camera's and the first bounces'.
const SOBOL_SLOTS: usize = (CAMERA_SLOTS + SOBOL_BOUNCES * BOUNCE_SLOTS) as usize;

/// The slot of the lens draw, and of the time draw.
const LENS_SLOT: u32 = 1;
const TIME_SLOT: u32 = 2;

/// The most samples of a [`PointBatch`].
pub const BATCH: u32 = 16;

/// The Sobol points of a run of a pixel's samples, computed together
/// ([`PixelSampler::prepare`]): one sample's scrambles are chains of
/// multiplications, 50–100 instructions a draw, that the path then waits
/// for; computed side by side for the run they cost a fraction of that,
/// and a draw becomes a load. Values equal [`SlotSeeds::get2`]'s. (Every
/// slot is computed, also for paths that leave the scene before they draw
/// from a bounce's: filling a bounce's slots when the first path got there
/// cost more instructions in checks at every draw than it saved.)
#[derive(Debug, Clone)]
struct PointBatch {
    /// The first sample's index.
    first: u32,
    /// How many samples from it have their points here.
    len: u32,
    /// Per slot and sample: the point's first coordinate.
    x: [[u32; BATCH as usize]; SOBOL_SLOTS],
    /// Per slot and sample: its second.
    y: [[u32; BATCH as usize]; SOBOL_SLOTS],
}

impl PointBatch {
    const EMPTY: PointBatch = PointBatch {
        first: 0,
        len: 0,
        x: [[0; BATCH as usize]; SOBOL_SLOTS],
        y: [[0; BATCH as usize]; SOBOL_SLOTS],
    };

    /// Fills the lanes of the Sobol slots (bits of `sobol`) for the `L`
    /// samples from the run's first.
    #[inline(always)]
    fn fill<const L: usize>(&mut self, seeds: &[SlotSeeds; SOBOL_SLOTS], sobol: u32) {
        let first = self.first;
        for (slot, seeds) in seeds.iter().enumerate() {
            if sobol & (1 << slot) != 0 {
                let (xs, ys) = seeds.get2_lanes::<L>(first);
                self.x[slot][..L].copy_from_slice(&xs);
                self.y[slot][..L].copy_from_slice(&ys);
            }
        }
    }
}

/// [`PointBatch::fill`] for `len` samples as a kernel for `pulp` to build
/// for each instruction set (a closure is not inlined into it).
struct Fill<'a> {
    batch: &'a mut PointBatch,
    seeds: &'a [SlotSeeds; SOBOL_SLOTS],
    sobol: u32,
}

impl pulp::WithSimd for Fill<'_> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _: S) {
        let Fill {
            batch,
            seeds,
            sobol,
        } = self;
        match batch.len {
            0..=4 => batch.fill::<4>(seeds, sobol),
            5..=8 => batch.fill::<8>(seeds, sobol),
            _ => batch.fill::<{ BATCH as usize }>(seeds, sobol),
        }
    }
}

/// One pixel's sampling: for `sobol`, each slot's seeds (the same for all
/// the pixel's samples, so computed once), which slots draw Sobol points,
/// and the points of the run of samples being drawn.
#[derive(Debug, Clone)]
pub struct PixelSampler {
    seed: u64,
    x: u32,
    y: u32,
    seeds: [SlotSeeds; SOBOL_SLOTS],
    /// Bit `s` set: slot `s` draws Sobol points (none for `independent`).
    sobol: u32,
    batch: PointBatch,
}

impl PixelSampler {
    /// Pixel (`x`, `y`) under `seed`, of the given kind; `lens` and `time`
    /// say whether the camera uses its lens and time draws (a pinhole, a
    /// closed shutter: those draws are then not worth a Sobol point).
    pub fn new(kind: SamplerKind, seed: u64, (x, y): (u32, u32), lens: bool, time: bool) -> Self {
        let mut pixel = PixelSampler {
            seed,
            x,
            y,
            seeds: [SlotSeeds::default(); SOBOL_SLOTS],
            sobol: 0,
            batch: PointBatch::EMPTY,
        };
        if kind == SamplerKind::Sobol {
            let mut sobol: u32 = (1 << SOBOL_SLOTS) - 1;
            for bounce in 0..SOBOL_BOUNCES {
                let (roulette, _) = Draws::Roulette.slots();
                sobol &= !(1 << (CAMERA_SLOTS + bounce * BOUNCE_SLOTS + roulette));
            }
            if !lens {
                sobol &= !(1 << LENS_SLOT);
            }
            if !time {
                sobol &= !(1 << TIME_SLOT);
            }
            pixel.sobol = sobol;
        }
        pixel.move_to((x, y));
        pixel
    }

    /// Makes this the sampling of pixel (`x`, `y`), same seed and kind: a
    /// render's tile keeps one and moves it from pixel to pixel (a new
    /// one per pixel copied its slots' seeds every time).
    #[inline]
    pub fn move_to(&mut self, (x, y): (u32, u32)) {
        (self.x, self.y) = (x, y);
        self.batch.len = 0;
        if self.sobol != 0 {
            let pixel = ((y as u64) << 32) | x as u64;
            let key = mix(mix(self.seed ^ 0x5b0b_0150_b01a_5eed) ^ pixel);
            for (slot, s) in self.seeds.iter_mut().enumerate() {
                *s = SlotSeeds::new(key, slot as u32);
            }
        }
    }

    /// Computes the Sobol points of the `len` samples from index `first`
    /// (at most [`BATCH`]: the rest draw theirs one by one) at once, for the
    /// [`PixelSampler::sample`]s that follow; the same numbers either way.
    /// A run of one sample (a preview's, a first pass's) draws its own:
    /// four lanes cost what one sample's every draw costs, and a path that
    /// leaves the scene draws only its film position.
    #[inline]
    pub fn prepare(&mut self, first: u32, len: u32) {
        self.batch.len = 0;
        if self.sobol == 0 || len < 2 {
            return;
        }
        (self.batch.first, self.batch.len) = (first, len.min(BATCH));
        // Built for the widest vectors the CPU has (AVX2 where there is,
        // chosen at run time): the lanes' multiplications and bit
        // reversals are single instructions there.
        pulp::Arch::new().dispatch(Fill {
            batch: &mut self.batch,
            seeds: &self.seeds,
            sobol: self.sobol,
        });
    }

    /// The numbers of the pixel's sample `index`; the first draws are the
    /// camera's: the film position, the lens, the time.
    #[inline]
    pub fn sample(&self, index: u32) -> Sampler<'_> {
        let mut s = Sampler::new(self.seed, self.x, self.y, index);
        if self.sobol != 0 {
            let lane = index.wrapping_sub(self.batch.first);
            s.lane = if lane < self.batch.len { lane } else { NO_LANE };
            s.index_reversed = index.reverse_bits();
            s.end = CAMERA_SLOTS;
            s.pixel = Some(self);
        }
        s
    }
}

/// A sample's numbers: a PCG32 generator (O'Neill 2014) seeded per sample,
/// and for `sobol` the pixel's slots with the range the next draws take.
#[derive(Debug, Clone)]
pub struct Sampler<'a> {
    state: u64,
    inc: u64,
    pixel: Option<&'a PixelSampler>,
    index_reversed: u32,
    /// The sample's lane in the pixel's batch of points, or [`NO_LANE`].
    lane: u32,
    /// The next slot to draw from, while below `end`; then the PCG stream.
    slot: u32,
    end: u32,
}

/// A sample whose points are not in its pixel's batch.
const NO_LANE: u32 = u32::MAX;

/// The top 24 bits of `x` as a number in [0, 1).
#[inline(always)]
fn unit_f32(x: u32) -> f32 {
    (x >> 8) as f32 * (1.0 / 16_777_216.0)
}

impl Sampler<'_> {
    /// The independent stream of sample `sample` of pixel (`x`, `y`) under
    /// `seed`.
    pub fn new(seed: u64, x: u32, y: u32, sample: u32) -> Sampler<'static> {
        let pixel = ((y as u64) << 32) | x as u64;
        let state = mix(seed ^ mix(pixel ^ mix(sample as u64 + 0x9e37_79b9)));
        let inc = (mix(pixel.wrapping_add(seed.rotate_left(17))) << 1) | 1;
        let mut s = Sampler {
            state: 0,
            inc,
            pixel: None,
            index_reversed: 0,
            lane: NO_LANE,
            slot: 0,
            end: 0,
        };
        s.next_u32();
        s.state = s.state.wrapping_add(state);
        s.next_u32();
        s
    }

    /// Points the next draws at `draws` of bounce `bounce` (0: at the
    /// first hit). Draws beyond that purpose's slots, and every draw of
    /// the independent kind, come from the PCG stream.
    #[inline(always)]
    pub fn start(&mut self, bounce: u32, draws: Draws) {
        let (from, to) = draws.slots();
        let base = CAMERA_SLOTS.saturating_add(bounce.saturating_mul(BOUNCE_SLOTS));
        self.slot = base.saturating_add(from);
        self.end = base.saturating_add(to);
    }

    /// Sends the next draws to the PCG stream until the next
    /// [`Sampler::start`]: after a branch of a tree of rays has drawn from
    /// later bounces' slots, its sibling must not draw from them again.
    #[inline(always)]
    pub fn pad(&mut self) {
        self.end = 0;
    }

    /// Passes over the next slot without drawing from it (a camera's lens
    /// draw, or its time, where the camera does not use them): the draws
    /// after it keep their own slots, and the PCG stream is not touched.
    #[inline(always)]
    pub fn skip(&mut self) {
        if self.slot < self.end {
            self.slot += 1;
        }
    }

    /// The pixel and the next slot, if the draw is a Sobol point.
    #[inline(always)]
    fn next_slot(&mut self) -> Option<(&PixelSampler, usize)> {
        let pixel = self.pixel?;
        let slot = self.slot;
        if slot >= self.end || slot >= SOBOL_SLOTS as u32 {
            return None;
        }
        self.slot += 1;
        (pixel.sobol & (1 << slot) != 0).then_some((pixel, slot as usize))
    }

    /// The first coordinate of the next slot's point, if the draw is a
    /// Sobol point: from the batch, or computed.
    #[inline(always)]
    fn next_point1(&mut self) -> Option<u32> {
        let (lane, index_reversed) = (self.lane as usize, self.index_reversed);
        let (pixel, slot) = self.next_slot()?;
        Some(match pixel.batch.x[slot].get(lane) {
            Some(&x) => x,
            None => pixel.seeds[slot].get1(index_reversed),
        })
    }

    /// Both coordinates of the next slot's point, if the draw is a Sobol
    /// point.
    #[inline(always)]
    fn next_point2(&mut self) -> Option<(u32, u32)> {
        let (lane, index_reversed) = (self.lane as usize, self.index_reversed);
        let (pixel, slot) = self.next_slot()?;
        Some(
            match (pixel.batch.x[slot].get(lane), pixel.batch.y[slot].get(lane)) {
                (Some(&x), Some(&y)) => (x, y),
                _ => pixel.seeds[slot].get2(index_reversed),
            },
        )
    }

    /// The next 32 random bits of the PCG stream.
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
        if let Some(x) = self.next_point1() {
            return unit_f32(x);
        }
        unit_f32(self.next_u32())
    }

    /// A uniform number in [0, 1) with 32 bits (from one draw, as
    /// [`Sampler::next_f32`]): for choices among many (a light of a tree).
    #[inline]
    pub fn next_f64(&mut self) -> f64 {
        let x = match self.next_point1() {
            Some(x) => x,
            None => self.next_u32(),
        };
        x as f64 * (1.0 / 4_294_967_296.0)
    }

    /// A uniform point in [0, 1)².
    #[inline]
    pub fn next_2d(&mut self) -> Vec2 {
        if let Some((x, y)) = self.next_point2() {
            return Vec2::new(unit_f32(x), unit_f32(y));
        }
        let x = unit_f32(self.next_u32());
        Vec2::new(x, unit_f32(self.next_u32()))
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
    fn independent_pixels_draw_the_pcg_stream_and_sobol_ones_are_stratified() {
        let draws = |s: &mut Sampler| -> Vec<f32> {
            let mut v = vec![s.next_2d().x, s.next_f32()];
            s.start(0, Draws::Bsdf);
            v.extend([s.next_f32(), s.next_2d().y]);
            v
        };
        let independent = PixelSampler::new(SamplerKind::Independent, 3, (5, 6), true, true);
        let mut a = independent.sample(9);
        let mut b = Sampler::new(3, 5, 6, 9);
        let mut plain = vec![b.next_2d().x, b.next_f32()];
        plain.extend([b.next_f32(), b.next_2d().y]);
        assert_eq!(draws(&mut a), plain);
        // 16 samples of a Sobol pixel: one in each sixteenth of [0, 1) in
        // the film's x, the BSDF's lobe and its direction's y alike.
        let pixel = PixelSampler::new(SamplerKind::Sobol, 3, (5, 6), true, true);
        let mut strata = [[false; 16]; 3];
        for i in 0..16 {
            let d = draws(&mut pixel.sample(i));
            for (k, v) in [d[0], d[2], d[3]].into_iter().enumerate() {
                let cell = (v * 16.0) as usize;
                assert!(
                    !strata[k][cell],
                    "draw {k} of sample {i}: stratum {cell} twice"
                );
                strata[k][cell] = true;
            }
        }
    }

    #[test]
    fn draws_past_a_purpose_or_after_pad_are_independent() {
        let pixel = PixelSampler::new(SamplerKind::Sobol, 1, (0, 0), false, false);
        let mut s = pixel.sample(4);
        s.start(0, Draws::Roulette);
        let mut pcg = Sampler::new(1, 0, 0, 4);
        assert_eq!(s.next_f32(), pcg.next_f32(), "roulette draws from PCG");
        s.start(0, Draws::Light);
        let (choice, point) = (s.next_f64(), s.next_2d());
        let past = s.next_f32();
        assert_eq!(past, pcg.next_f32(), "a third draw of the light's slots");
        s.start(0, Draws::Light);
        assert_eq!(
            (s.next_f64(), s.next_2d()),
            (choice, point),
            "slots are repeatable"
        );
        s.pad();
        assert_eq!(s.next_2d(), pcg.next_2d());
        // A pinhole camera's lens draw comes from PCG too.
        let mut camera = pixel.sample(4);
        let mut pcg = Sampler::new(1, 0, 0, 4);
        let _film = camera.next_2d();
        assert_eq!(camera.next_2d(), pcg.next_2d());
    }

    #[test]
    fn a_skipped_lens_slot_leaves_the_time_its_own_stratified_slot() {
        // A pinhole with an open shutter: the camera skips the lens slot
        // (`render::camera_ray`), and the times of a pixel's 16 samples
        // still fill the 16 strata of the time's slot.
        let pixel = PixelSampler::new(SamplerKind::Sobol, 9, (5, 2), false, true);
        let mut strata = [false; 16];
        for i in 0..16 {
            let mut s = pixel.sample(i);
            let _film = s.next_2d();
            s.skip();
            let cell = (s.next_f32() * 16.0) as usize;
            assert!(!strata[cell], "sample {i}: stratum {cell} twice");
            strata[cell] = true;
        }
        // Skipping draws nothing: the PCG stream is where it was.
        let (mut skipped, mut pcg) = (pixel.sample(3), Sampler::new(9, 5, 2, 3));
        skipped.skip();
        skipped.pad();
        assert_eq!(skipped.next_u32(), pcg.next_u32());
    }

    /// Every draw of a sample's first bounces, from the camera's slots on.
    fn all_draws(mut s: Sampler) -> Vec<u32> {
        let bits = |x: f32| x.to_bits();
        let mut v = vec![bits(s.next_2d().x), bits(s.next_2d().y), bits(s.next_f32())];
        for bounce in 0..SOBOL_BOUNCES + 1 {
            for draws in [Draws::Light, Draws::Bsdf, Draws::Roulette] {
                s.start(bounce, draws);
                let p = s.next_2d();
                v.extend([s.next_f64().to_bits() as u32, bits(p.x), bits(p.y)]);
                v.push(bits(s.next_f32()));
            }
        }
        v
    }

    proptest::proptest! {
        #[test]
        fn a_batch_draws_what_single_samples_draw(
            seed: u64,
            x in 0u32..100_000,
            y in 0u32..100_000,
            first: u32,
            len in 0u32..40,
            lens: bool,
        ) {
            let single = PixelSampler::new(SamplerKind::Sobol, seed, (x, y), lens, true);
            let mut batched = single.clone();
            batched.prepare(first, len);
            // The batch's samples, one beyond it, and one before it.
            for k in (0..len.min(BATCH) + 1).chain([u32::MAX]) {
                let index = first.wrapping_add(k);
                proptest::prop_assert_eq!(
                    all_draws(batched.sample(index)),
                    all_draws(single.sample(index)),
                    "sample {}", index
                );
            }
        }
    }

    #[test]
    fn uniform_mean() {
        let mut s = Sampler::new(7, 0, 0, 0);
        let m: f64 = (0..100_000).map(|_| s.next_f32() as f64).sum::<f64>() / 100_000.0;
        assert!((m - 0.5).abs() < 0.01);
    }
}
