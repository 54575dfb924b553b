//! Adaptive sampling (`noise_threshold`, `min_samples`): a pixel stops
//! drawing samples once its noise is below the threshold, so the samples go
//! where the noise is.
//!
//! The noise of a pixel is estimated as Cycles does, after Dammertz et al.
//! 2010, "A hierarchical automatic stopping condition for Monte Carlo
//! global illumination" (§2.1): its samples split by the parity of their
//! index into two half films whose means Ē and Ō each estimate the pixel;
//! their difference measures the error, over the square root of the
//! brightness (between an absolute and a relative error, as the eye sees
//! noise):
//!
//! ```text
//! error = Σ_c |Ē_c − Ō_c| / 2  /  (10⁻⁴ + √(Σ_c mean_c))
//! ```
//!
//! (the numerator is Cycles's |I − A| per sample, where A is twice the odd
//! samples' sum). One pixel's estimate is itself noisy (two halves, a few
//! degrees of freedom), and a decision is final: a pixel is judged by the
//! mean estimate of its 3×3 window, and stops only when that and its
//! still-sampling neighbours' are below the threshold (Cycles's dilation of
//! the unconverged pixels). Judged alone, one pixel in a noisy region read
//! low by chance often enough that adaptive renders needed more samples
//! than uniform ones for the same error (docs/performance.md).
//!
//! Decisions are taken at fixed sample counts ([`is_decision`]: the first
//! at `min_samples`, then every eighth more, at least 4), after the pass
//! that ends there, for every pixel at once, from the film alone. The film
//! keeps which pixels stopped, so the image is the same on any thread
//! count, and a render stopped and resumed (from its state, which keeps
//! the half films and the stopped pixels) ends with the uninterrupted
//! render's film. A stopped pixel keeps the mean of the samples it has:
//! no sample is weighted or dropped.

use super::film::{Film, Halves};
use crate::ir::settings::Adaptive;
use crate::sampling::sampler::BATCH;
use glam::DVec3;
use std::time::Duration;

/// The first decision: `min_samples`, made even so that the two halves
/// hold as many samples each.
fn first_decision(a: &Adaptive) -> u32 {
    a.min_samples.max(2).saturating_add(1) & !1
}

/// The decision after one at `count`: an eighth more samples (even), at
/// least 4, so a pixel overshoots its convergence by at most about 12 %
/// and a render of N samples takes about 8·ln(N) passes.
fn next_decision(count: u32) -> u32 {
    count.saturating_add((count / 8).max(4) & !1)
}

/// Whether a pixel at `count` samples is decided on (see the module).
pub fn is_decision(count: u32, a: &Adaptive) -> bool {
    let mut c = first_decision(a);
    while c < count {
        c = next_decision(c);
    }
    c == count
}

/// How a render's progressive passes grow (before an adaptive render's
/// decisions, which end passes of their own).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Progression {
    /// 1, 2, 4, 8, …: an image to look at after every doubling (`watch`,
    /// whose passes are what its user sees refine).
    Doubling,
    /// 1, then [`BATCH`], 2·[`BATCH`], 4·[`BATCH`], …: after a first sample
    /// per pixel (a first image, and the time budget's first measure of
    /// speed), passes of whole runs of samples, which share their Sobol
    /// points' set-up and trace their camera rays as packets. Passes of 1,
    /// 2, 4 and 8 samples cost a 16-spp render of the 1M-triangle mesh's
    /// camera rays a fifth of its time (docs/performance.md, "Passes of
    /// whole runs").
    Runs,
}

/// A first pass slower than this turns [`Progression::Runs`] into
/// [`Progression::Doubling`]: the run to 16 samples per pixel would keep
/// the next image (and the progress a user watches) waiting fifteen
/// times as long, half a minute or more.
const SLOW_FIRST_PASS: Duration = Duration::from_secs(2);

impl Progression {
    /// How passes grow after one that ended at `end` samples per pixel and
    /// took `took`: a slow render's passes double from its first sample,
    /// so that its image refines in steps it can wait for. Only where the
    /// passes end changes, never a sample.
    pub fn after_pass(self, end: u32, took: Duration) -> Progression {
        match self {
            Progression::Runs if end == 1 && took > SLOW_FIRST_PASS => Progression::Doubling,
            p => p,
        }
    }
}

/// Sample counts at the end of each progressive pass up to `spp`, growing
/// by `progression` (at most 33 passes), or for an adaptive render so up to
/// its first decision and then every decision up to `spp`.
pub fn pass_ends(spp: u32, adaptive: Option<&Adaptive>, progression: Progression) -> Vec<u32> {
    let doubling_below = adaptive.map_or(u32::MAX, first_decision);
    let mut ends = Vec::new();
    let mut n = 1u32;
    while n < spp && n < doubling_below {
        ends.push(n);
        n = match progression {
            Progression::Runs if n < BATCH => BATCH,
            _ => n.saturating_mul(2),
        };
    }
    if adaptive.is_some() {
        let mut c = doubling_below;
        while c < spp {
            ends.push(c);
            c = next_decision(c);
        }
    }
    ends.push(spp.max(1));
    ends
}

/// The noise of a pixel with `count` samples summing to `sum`, of which
/// those of odd index sum to `odd` (see the module); 0 for a black pixel.
pub fn error(sum: DVec3, odd: DVec3, count: u32) -> f64 {
    let Some((even_mean, odd_mean)) = half_means(sum, odd, count) else {
        return f64::INFINITY;
    };
    let difference = (even_mean - odd_mean).abs().element_sum() / 2.0;
    let brightness = (sum / count as f64).element_sum().max(0.0);
    difference / (1e-4 + brightness.sqrt())
}

/// The means of a pixel's even and odd samples (indices 0, 2, … and 1,
/// 3, …) from the sum of all `count` of them and of the odd ones; `None`
/// below two samples.
pub fn half_means(sum: DVec3, odd: DVec3, count: u32) -> Option<(DVec3, DVec3)> {
    let n_odd = (count / 2) as f64;
    let n_even = (count - count / 2) as f64;
    (n_odd > 0.0).then(|| ((sum - odd) / n_even, odd / n_odd))
}

/// Decides after the pass that brought every sampling pixel to `count`
/// samples: stops each pixel at `count` whose noise, and that of each
/// neighbour that still samples, is below `threshold`, where a pixel's
/// noise is the mean of its 3×3 window's [`error`]s. Returns how many
/// stopped. (A pixel still sampling at another count, as in a film resumed
/// mid-pass, keeps its neighbours going.)
pub fn decide(film: &mut Film, count: u32, threshold: f32) -> u64 {
    let (w, h) = (film.width as usize, film.height as usize);
    let Some(halves) = film.halves.as_mut() else {
        return 0;
    };
    let (sum, counts) = (&film.sum, &film.count);
    let threshold = threshold as f64;
    // A pixel's own estimate: at its count if it stopped or is at
    // `count`; unknown (infinite) if it samples on elsewhere.
    let raw_row = |halves: &Halves, y: usize| -> Vec<f64> {
        (y * w..(y + 1) * w)
            .map(|i| match halves.stopped[i] || counts[i] == count {
                true => error(sum[i], halves.odd[i], counts[i]),
                false => f64::INFINITY,
            })
            .collect()
    };
    // Whether each pixel of row `y` keeps its neighbours sampling: it
    // samples on and its window's noise is not below the threshold. One
    // pixel's estimate compares two halves of its samples, a handful of
    // degrees of freedom: alone it often reads low by chance and would
    // stop a noisy pixel for good; the window's mean reads nine.
    // The raw rows around the busy row asked (it is asked row by row):
    // rows `raw_first ..` of them, at most three.
    let mut raw: std::collections::VecDeque<Vec<f64>> = Default::default();
    let mut raw_first = 0;
    let mut busy_row = |halves: &Halves, y: usize| -> Vec<bool> {
        while raw_first + raw.len() < (y + 2).min(h) {
            raw.push_back(raw_row(halves, raw_first + raw.len()));
        }
        while raw_first + 1 < y {
            raw.pop_front();
            raw_first += 1;
        }
        (0..w)
            .map(|x| {
                let i = y * w + x;
                let (x0, x1) = (x.saturating_sub(1), (x + 1).min(w - 1));
                let window = raw.iter().flat_map(|row| &row[x0..=x1]);
                let noise = window.clone().sum::<f64>() / window.count() as f64;
                !halves.stopped[i] && (counts[i] != count || noise >= threshold)
            })
            .collect()
    };
    let mut stopped = 0;
    // Three rows of `busy` at a time: the film's memory and no more.
    let mut above = vec![false; w];
    let mut here = busy_row(halves, 0);
    for y in 0..h {
        let below = match y + 1 < h {
            true => busy_row(halves, y + 1),
            false => vec![false; w],
        };
        for x in 0..w {
            let i = y * w + x;
            if halves.stopped[i] || here[x] {
                continue;
            }
            let (x0, x1) = (x.saturating_sub(1), (x + 1).min(w - 1));
            let neighbours_busy = [&above, &here, &below]
                .iter()
                .any(|row| row[x0..=x1].iter().any(|&b| b));
            if !neighbours_busy {
                halves.stopped[i] = true;
                stopped += 1;
            }
        }
        above = std::mem::replace(&mut here, below);
    }
    stopped
}

#[cfg(test)]
#[path = "adaptive_tests.rs"]
mod tests;
