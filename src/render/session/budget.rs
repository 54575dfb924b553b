//! A batch render's time budget (`--time`, `render { time … }`): the
//! passes go on growing as usual (one sample per pixel, then runs of 16,
//! doubling: [`Progression::Runs`]) while the next one fits in the time
//! left, measured by the passes so far; the last one renders as many
//! samples per pixel as fit, so that every pixel ends with the same count.
//! A pass that runs later than foreseen is cut at a tenth of the budget
//! past its end (its pixels then end with counts one pass apart).

use crate::ir::settings::Adaptive;
use crate::render::adaptive::{pass_ends, Progression};
use crate::render::film::Film;
use std::time::{Duration, Instant};

/// The time budget of a render and what it has spent.
#[derive(Debug, Clone)]
pub(super) struct Budget {
    start: Instant,
    end: Instant,
    /// When a pass in flight is cut.
    cut: Instant,
    /// The film's samples when the budget started (a resumed render's).
    samples_before: u64,
    /// Adaptive sampling's settings: its passes end at its decisions.
    adaptive: Option<Adaptive>,
    /// How the passes grow: runs, or doubling after a slow first pass
    /// ([`Progression::after_pass`]), as a render without a budget.
    progression: Progression,
}

impl Budget {
    /// A budget of `seconds` from now for rendering on from `film`, with
    /// `adaptive` sampling or not.
    pub(super) fn new(seconds: f64, film: &Film, adaptive: Option<Adaptive>) -> Budget {
        let start = Instant::now();
        let length = Duration::from_secs_f64(seconds);
        Budget {
            start,
            end: start + length,
            cut: start + length + length / 10,
            samples_before: film.total_samples(),
            adaptive,
            progression: Progression::Runs,
        }
    }

    /// The samples per pixel the next pass should end at, on the way to
    /// `target`: the usual growth while it fits in the time left, else as
    /// many as fit; `None` when the film has `target` (in every pixel
    /// still sampling) or not one more sample per pixel fits.
    pub(super) fn next_target(&mut self, film: &Film, target: u32) -> Option<u32> {
        let least = film.least_active()?;
        let now = Instant::now();
        if least >= target || now >= self.end {
            return None;
        }
        let done = film.total_samples().saturating_sub(self.samples_before);
        if self.samples_before == 0 && least == 1 {
            self.progression = self.progression.after_pass(1, now - self.start);
        }
        let next = (pass_ends(target, self.adaptive.as_ref(), self.progression).into_iter())
            .find(|&e| e > least)?;
        if done == 0 {
            // A resumed render has no measure of its speed yet, and its
            // next pass could take many times as long as all before it
            // (1 to 16 spp: fifteen times; it would
            // be cut past the budget, its pixels a pass apart): one sample
            // per pixel measures it first.
            return Some(match self.samples_before {
                0 => next,
                _ => next.min(least.saturating_add(1)),
            });
        }
        // Seconds for one sample in every pixel still sampling, from the
        // passes so far.
        let per_sample = (now - self.start).as_secs_f64() / done as f64;
        let per_spp = per_sample * film.active_pixels() as f64;
        let left = (self.end - now).as_secs_f64();
        let affordable = (left / per_spp.max(1e-12)).floor().min(u32::MAX as f64) as u32;
        let end = next.min(least.saturating_add(affordable));
        (end > least).then_some(end)
    }

    /// Whether the pass in flight has run past the budget by more than a
    /// tenth of it: it is then cut.
    pub(super) fn overrun(&self) -> bool {
        Instant::now() >= self.cut
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Pretends the budget of `length` seconds started `ago`.
    fn spent(budget: &mut Budget, ago: Duration, length: u64) {
        budget.start = Instant::now() - ago;
        budget.end = budget.start + Duration::from_secs(length);
    }

    /// A budget of `length` seconds whose first pass (one sample per
    /// pixel: it has nothing to go by) took `took`, and its film.
    fn after_first_pass(length: u64, took: Duration) -> (Film, Budget) {
        let mut film = Film::new(2, 2, 0);
        let mut budget = Budget::new(length as f64, &film, None);
        assert_eq!(budget.next_target(&film, 1000), Some(1));
        film.count.fill(1);
        spent(&mut budget, took, length);
        (film, budget)
    }

    #[test]
    fn passes_grow_while_they_fit_and_the_last_takes_what_fits() {
        // After the first sample, a run of 16 where it fits: 1 spp in
        // 0.5 s, 9.5 s left → 19 more fit; 1 spp in 1.5 s, 8.5 s left → 5
        // more, not the run.
        let (mut film, mut budget) = after_first_pass(10, Duration::from_millis(500));
        assert_eq!(budget.next_target(&film, 1000), Some(16));
        spent(&mut budget, Duration::from_millis(1500), 10);
        assert_eq!(budget.next_target(&film, 1000), Some(6));
        // Pretend 8 spp took 2 s: 0.25 s per spp, 8 s left → 32 more fit.
        film.count.fill(8);
        spent(&mut budget, Duration::from_secs(2), 10);
        assert_eq!(budget.next_target(&film, 1000), Some(16));
        film.count.fill(32);
        // 32 spp in 2 s: 1/16 s per spp, 8 s left → 128 fit, the growth
        // asks for 64.
        assert_eq!(budget.next_target(&film, 1000), Some(64));
        // The target caps it; a film at the target is done.
        assert_eq!(budget.next_target(&film, 40), Some(40));
        assert_eq!(budget.next_target(&film, 32), None);
        // 32 spp took 7.9 s of 10: 2.1 s left fits 8 more, not the 32 of
        // the growth.
        spent(&mut budget, Duration::from_millis(7900), 10);
        assert_eq!(budget.next_target(&film, 1000), Some(40));
        // Spent: nothing more.
        budget.end = Instant::now();
        assert_eq!(budget.next_target(&film, 1000), None);
    }

    #[test]
    fn after_a_slow_first_pass_the_passes_double() {
        // 1 spp took 2.5 s: 16 would fit, but 2 comes next, then 4.
        let (mut film, mut budget) = after_first_pass(100, Duration::from_millis(2500));
        assert_eq!(budget.next_target(&film, 1000), Some(2));
        film.count.fill(2);
        assert_eq!(budget.next_target(&film, 1000), Some(4));
    }

    #[test]
    fn a_resumed_render_measures_its_speed_before_its_next_pass() {
        let mut film = Film::new(2, 2, 0);
        film.count.fill(100);
        let mut budget = Budget::new(0.3, &film, None);
        // Not the doubling to 128, which may not fit: one sample first.
        assert_eq!(budget.next_target(&film, 1000), Some(101));
    }
}
