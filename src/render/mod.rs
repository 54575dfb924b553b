//! The pixel loop — the only one in ptsc: rayon over tiles, progressive
//! passes (1, 2, 4, … samples per pixel), a cancellation flag checked between
//! tiles, a progress callback. Every sample draws from its own random stream
//! (seed, pixel, sample index), so the image is the same for any thread count.

pub mod film;

use crate::accel::ray_count::{self, RayCounts};
use crate::integrator::Integrator;
use crate::ir::Scene;
use crate::sampling::sampler::Sampler;
use film::Film;
use glam::{Vec2, Vec3};
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

/// Side of a square tile in pixels.
pub const TILE: u32 = 16;

/// What a tile of a pass produced.
struct TileResult {
    /// Its top-left pixel.
    corner: (u32, u32),
    /// The sample sums of its pixels, row-major: all of them, or (when the
    /// pass was cancelled) those begun.
    sums: Vec<Vec3>,
    /// When cancelled: the samples the last pixel of `sums` got (the ones
    /// before it got the whole pass).
    cut: Option<u32>,
    /// The rays traced for it.
    rays: RayCounts,
}

/// How a render went.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Outcome {
    /// Every pass finished.
    Complete,
    /// Cancelled; the film holds every sample done (the passes that
    /// finished, and the part of the last one that ran).
    Cancelled,
}

/// What a render produced.
#[derive(Debug, Clone)]
pub struct Rendered {
    /// The accumulated image.
    pub film: Film,
    /// Whether every pass finished.
    pub outcome: Outcome,
    /// The rays traced (all passes that ran).
    pub rays: RayCounts,
}

/// Sample counts at the end of each progressive pass: 1, 2, 4, … up to `spp`
/// (at most 33 passes, whatever `spp`).
pub fn pass_ends(spp: u32) -> Vec<u32> {
    let mut ends = Vec::new();
    let mut n = 1u32;
    while n < spp {
        ends.push(n);
        n = n.saturating_mul(2);
    }
    ends.push(spp.max(1));
    ends
}

/// How often a tile polls the cancellation flag: every this many samples
/// of a pixel (and at every pixel). A relaxed atomic load costs next to
/// nothing beside a sample, and Ctrl-C answers within a few samples' time
/// however long the pass.
const CANCEL_POLL: u32 = 4;

/// The largest value one sample may add to a pixel (its largest channel):
/// a million of them still sum to a finite f32. Only a sample that divides
/// by a vanishing pdf comes near it; it is scaled down, keeping its colour.
pub const MAX_SAMPLE: f32 = 1e30;

/// Renders `scene` into a new film. After each pass, `on_pass(film, samples)`
/// is called (preview writes); `progress(done_pixel_samples)` is called as
/// tiles finish. `cancel` is polled between tiles.
pub fn render(
    scene: &Scene,
    integrator: &dyn Integrator,
    cancel: &AtomicBool,
    progress: &(dyn Fn(u64) + Sync),
    on_pass: &mut dyn FnMut(&Film, u32),
) -> Rendered {
    let s = &scene.settings;
    let view = View {
        width: s.width,
        height: s.height,
        samples: s.samples,
        scale: 1,
    };
    render_view(scene, integrator, view, cancel, progress, on_pass)
}

/// A quick preview: one sample per pixel of an image `divisor` times smaller
/// on each side than the scene's (each preview pixel covers divisor² pixels of
/// the full image). `None` when cancelled.
pub fn render_preview(
    scene: &Scene,
    integrator: &dyn Integrator,
    cancel: &AtomicBool,
    divisor: u32,
) -> Option<Film> {
    let view = View {
        width: (scene.settings.width / divisor).max(1),
        height: (scene.settings.height / divisor).max(1),
        samples: 1,
        scale: divisor,
    };
    let r = render_view(scene, integrator, view, cancel, &|_| {}, &mut |_, _| {});
    (r.outcome == Outcome::Complete).then_some(r.film)
}

/// The image to render: its size, samples per pixel, and how many pixels of
/// the scene's image one of its pixels covers on each side.
#[derive(Debug, Clone, Copy)]
struct View {
    width: u32,
    height: u32,
    samples: u32,
    scale: u32,
}

/// The pixel loop: tiles over rayon, progressive passes.
fn render_view(
    scene: &Scene,
    integrator: &dyn Integrator,
    view: View,
    cancel: &AtomicBool,
    progress: &(dyn Fn(u64) + Sync),
    on_pass: &mut dyn FnMut(&Film, u32),
) -> Rendered {
    let (w, h) = (view.width, view.height);
    let scale = view.scale as f32;
    let mut film = Film::new(w, h);
    let tiles: Vec<(u32, u32)> = (0..h.div_ceil(TILE))
        .flat_map(|ty| (0..w.div_ceil(TILE)).map(move |tx| (tx * TILE, ty * TILE)))
        .collect();
    let done = AtomicU64::new(0);
    let mut rays = RayCounts::default();
    let mut start = 0;
    for end in pass_ends(view.samples) {
        let results: Vec<TileResult> = tiles
            .par_iter()
            .map(|&(x0, y0)| {
                let (x1, y1) = ((x0 + TILE).min(w), (y0 + TILE).min(h));
                let rays_before = ray_count::this_thread();
                let mut sums = Vec::with_capacity(((x1 - x0) * (y1 - y0)) as usize);
                let mut cut = None;
                'pixels: for y in y0..y1 {
                    for x in x0..x1 {
                        let mut sum = Vec3::ZERO;
                        for s in start..end {
                            if (s - start).is_multiple_of(CANCEL_POLL)
                                && cancel.load(Ordering::Relaxed)
                            {
                                sums.push(sum);
                                cut = Some(s - start);
                                break 'pixels;
                            }
                            sum += sample(scene, integrator, x, y, s, scale);
                        }
                        sums.push(sum);
                    }
                }
                if cut.is_none() {
                    let samples = sums.len() as u64 * (end - start) as u64;
                    progress(done.fetch_add(samples, Ordering::Relaxed) + samples);
                }
                TileResult {
                    corner: (x0, y0),
                    sums,
                    cut,
                    rays: ray_count::this_thread() - rays_before,
                }
            })
            .collect();
        // A cancelled pass keeps every sample done: its pixels count their
        // own samples beyond the film's whole passes.
        let cancelled = results.iter().any(|t| t.cut.is_some());
        for t in results {
            rays = rays + t.rays;
            let (x0, y0) = t.corner;
            let x1 = (x0 + TILE).min(w);
            let last = t.sums.len().saturating_sub(1);
            for (i, v) in t.sums.into_iter().enumerate() {
                let (x, y) = (x0 + i as u32 % (x1 - x0), y0 + i as u32 / (x1 - x0));
                if cancelled {
                    let n = if i == last {
                        t.cut.unwrap_or(end - start)
                    } else {
                        end - start
                    };
                    film.add_partial(x, y, v, n);
                } else {
                    film.add(x, y, v);
                }
            }
        }
        if cancelled {
            return Rendered {
                film,
                outcome: Outcome::Cancelled,
                rays,
            };
        }
        film.samples = end;
        on_pass(&film, end);
        start = end;
    }
    Rendered {
        film,
        outcome: Outcome::Complete,
        rays,
    }
}

/// One sample of pixel (x, y): a jittered position (box filter), lens and
/// time; `scale` > 1 for the pixels of a smaller preview image.
#[inline]
fn sample(scene: &Scene, integrator: &dyn Integrator, x: u32, y: u32, s: u32, scale: f32) -> Vec3 {
    let mut sampler = Sampler::new(scene.settings.seed, x, y, s);
    let film = (Vec2::new(x as f32, y as f32) + sampler.next_2d()) * scale;
    let lens = sampler.next_2d();
    let t = sampler.next_f32();
    let ray = scene.camera.ray(film, lens, t);
    let l = integrator.li(scene, ray, &mut sampler);
    limit_sample(l)
}

/// A sample as it enters a pixel's sum: a NaN or infinite one would poison
/// the pixel and is dropped (counted as black); a huge one is scaled down to
/// [`MAX_SAMPLE`].
#[inline]
fn limit_sample(l: Vec3) -> Vec3 {
    if !l.is_finite() {
        return Vec3::ZERO;
    }
    let big = l.max_element();
    if big > MAX_SAMPLE {
        l * (MAX_SAMPLE / big)
    } else {
        l
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn passes_double_up_to_the_target() {
        assert_eq!(pass_ends(1), vec![1]);
        assert_eq!(pass_ends(6), vec![1, 2, 4, 6]);
        assert_eq!(pass_ends(8), vec![1, 2, 4, 8]);
        // The doubling saturates instead of wrapping to 0 and looping.
        let ends = pass_ends(u32::MAX);
        assert_eq!(ends.len(), 33);
        assert_eq!(*ends.last().unwrap(), u32::MAX);
        assert_eq!(pass_ends(3_000_000_000).len(), 33);
    }

    #[test]
    fn samples_enter_a_pixel_finite_and_bounded() {
        assert_eq!(limit_sample(Vec3::new(f32::NAN, 1.0, 1.0)), Vec3::ZERO);
        assert_eq!(limit_sample(Vec3::new(f32::INFINITY, 1.0, 1.0)), Vec3::ZERO);
        let big = limit_sample(Vec3::new(2e30, 1e30, 0.0));
        assert!((big.x - MAX_SAMPLE).abs() <= MAX_SAMPLE * 1e-6 && (big.y - 0.5e30).abs() < 1e24);
        // A million of the largest samples sum to a finite value.
        assert!((MAX_SAMPLE * 1e6).is_finite());
        assert_eq!(limit_sample(Vec3::ONE), Vec3::ONE);
    }
}
