//! The pixel loop — the only one in ptsc: rayon over tiles, progressive
//! passes (1, 2, 4, … samples per pixel), a cancellation flag checked between
//! tiles, a progress callback. Every sample draws from its own random stream
//! (seed, pixel, sample index), so the image is the same for any thread count.

pub mod aov;
pub mod denoise;
pub mod film;
pub mod memory;
pub mod merge;
pub mod session;
pub mod state;

use crate::accel::ray_count::{self, RayCounts};
use crate::geometry::Ray;
use crate::integrator::Integrator;
use crate::ir::Scene;
use crate::sampling::sampler::{PixelSampler, Sampler};
use film::Film;
use glam::{DVec3, Vec2, Vec3};
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

/// Side of a square tile in pixels.
pub const TILE: u32 = 16;

/// A tile's pixels in the film, borrowed row by row: the tiles of a pass
/// add their samples in place, in parallel, with no copy of the film (a
/// copy of an 8192 × 8192 film is 1.9 GB).
struct TileRows<'a> {
    /// Its top-left pixel.
    corner: (u32, u32),
    /// Its rows of sample sums.
    sums: Vec<&'a mut [DVec3]>,
    /// Its rows of sample counts.
    counts: Vec<&'a mut [u32]>,
}

/// The film's pixels cut into tiles of TILE × TILE (fewer at the right and
/// bottom edges), in row-major order of tiles.
fn tile_rows<'a>(sums: &'a mut [DVec3], counts: &'a mut [u32], width: u32) -> Vec<TileRows<'a>> {
    let (w, tile) = (width as usize, TILE as usize);
    let across = w.div_ceil(tile);
    let mut tiles: Vec<TileRows> = Vec::new();
    let bands = sums.chunks_mut(w * tile).zip(counts.chunks_mut(w * tile));
    for (band, (band_sums, band_counts)) in bands.enumerate() {
        let first = tiles.len();
        tiles.extend((0..across).map(|tx| TileRows {
            corner: ((tx * tile) as u32, (band * tile) as u32),
            sums: Vec::with_capacity(tile),
            counts: Vec::with_capacity(tile),
        }));
        for (row_sums, row_counts) in band_sums.chunks_mut(w).zip(band_counts.chunks_mut(w)) {
            let cells = row_sums.chunks_mut(tile).zip(row_counts.chunks_mut(tile));
            for (tx, (s, c)) in cells.enumerate() {
                tiles[first + tx].sums.push(s);
                tiles[first + tx].counts.push(c);
            }
        }
    }
    tiles
}

/// How a render went.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Outcome {
    /// Every pass finished.
    Complete,
    /// Cancelled; the film holds every sample done (the passes that
    /// finished, and the part of the last one that ran): rendering on from
    /// it ends with the film an uninterrupted render makes.
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

/// Renders `scene` into a new film, the scene's samples per pixel. After
/// each pass, `on_pass(film, samples)` is called (preview writes);
/// `progress(done_pixel_samples)` is called as tiles finish. `cancel` is
/// polled every few samples.
pub fn render(
    scene: &Scene,
    integrator: &dyn Integrator,
    cancel: &AtomicBool,
    progress: &(dyn Fn(u64) + Sync),
    on_pass: &mut dyn FnMut(&Film, u32),
) -> Rendered {
    let s = &scene.settings;
    let film = Film::new(s.width, s.height, 0);
    render_from(
        scene, integrator, film, s.samples, cancel, progress, on_pass,
    )
}

/// Renders on from `film` (a render's saved state, or a new film whose runs
/// start at another sample index) until every pixel has `samples` samples:
/// pixel (x, y) gets sample indices `film.first + film.count[i] ..
/// film.first + samples`. The film must have the scene's size.
pub fn render_from(
    scene: &Scene,
    integrator: &dyn Integrator,
    film: Film,
    samples: u32,
    cancel: &AtomicBool,
    progress: &(dyn Fn(u64) + Sync),
    on_pass: &mut dyn FnMut(&Film, u32),
) -> Rendered {
    let view = View {
        width: film.width,
        height: film.height,
        samples,
        scale: 1,
    };
    render_view(scene, integrator, film, view, cancel, progress, on_pass)
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
    let film = Film::new(view.width, view.height, 0);
    let r = render_view(
        scene,
        integrator,
        film,
        view,
        cancel,
        &|_| {},
        &mut |_, _| {},
    );
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

/// The pixel loop: tiles over rayon, progressive passes. Each pixel's
/// samples are added to its sum one by one in sample-index order, from the
/// sum `film` holds: however a render is stopped and continued, the same
/// additions happen in the same order.
fn render_view(
    scene: &Scene,
    integrator: &dyn Integrator,
    mut film: Film,
    view: View,
    cancel: &AtomicBool,
    progress: &(dyn Fn(u64) + Sync),
    on_pass: &mut dyn FnMut(&Film, u32),
) -> Rendered {
    let (w, h) = (view.width, view.height);
    debug_assert_eq!((film.width, film.height), (w, h));
    let scale = view.scale as f32;
    let first = film.first;
    let done = AtomicU64::new(0);
    let mut rays = RayCounts::default();
    // A resumed film skips the passes its every pixel has done.
    let least = film.count.iter().copied().min().unwrap_or(0);
    for end in pass_ends(view.samples).into_iter().filter(|&e| e > least) {
        let mut tiles = tile_rows(&mut film.sum, &mut film.count, w);
        let results: Vec<(bool, RayCounts)> = tiles
            .par_iter_mut()
            .map(|tile| {
                let (x0, y0) = tile.corner;
                let rays_before = ray_count::this_thread();
                let mut stopped = false;
                let mut samples = 0u64;
                let rows = tile.sums.iter_mut().zip(tile.counts.iter_mut());
                let mut pixel = pixel_sampler(scene, x0, y0);
                'pixels: for (y, (sums, counts)) in (y0..).zip(rows) {
                    for (x, (sum_held, count_held)) in
                        (x0..).zip(sums.iter_mut().zip(counts.iter_mut()))
                    {
                        let (mut sum, from) = (*sum_held, *count_held);
                        pixel.move_to((x, y));
                        for s in from..end {
                            if (s - from).is_multiple_of(CANCEL_POLL)
                                && cancel.load(Ordering::Relaxed)
                            {
                                (*sum_held, *count_held) = (sum, s);
                                samples += (s - from) as u64;
                                stopped = true;
                                break 'pixels;
                            }
                            let l = sample(scene, integrator, &pixel, x, y, first + s, scale);
                            sum += l.as_dvec3();
                        }
                        (*sum_held, *count_held) = (sum, from.max(end));
                        samples += end.saturating_sub(from) as u64;
                    }
                }
                progress(done.fetch_add(samples, Ordering::Relaxed) + samples);
                (stopped, ray_count::this_thread() - rays_before)
            })
            .collect();
        drop(tiles);
        // A stopped pass keeps every sample done: each pixel counts its own.
        let stopped = results.iter().any(|t| t.0);
        for (_, tile_rays) in results {
            rays = rays + tile_rays;
        }
        if stopped {
            return Rendered {
                film,
                outcome: Outcome::Cancelled,
                rays,
            };
        }
        on_pass(&film, end);
    }
    Rendered {
        film,
        outcome: Outcome::Complete,
        rays,
    }
}

/// The sampling of pixel (x, y) of the scene's render.
pub(crate) fn pixel_sampler(scene: &Scene, x: u32, y: u32) -> PixelSampler {
    let (s, camera) = (&scene.settings, &scene.camera);
    PixelSampler::new(
        s.sampler,
        s.seed,
        (x, y),
        camera.uses_lens(),
        camera.uses_time(),
    )
}

/// One sample of pixel (x, y): a jittered position (box filter), lens and
/// time; `scale` > 1 for the pixels of a smaller preview image.
#[inline]
fn sample(
    scene: &Scene,
    integrator: &dyn Integrator,
    pixel: &PixelSampler,
    x: u32,
    y: u32,
    s: u32,
    scale: f32,
) -> Vec3 {
    // Sample `s` of a pixel is the same wherever and whenever it is drawn:
    // what lets a render stop, continue, and split across machines.
    let mut sampler = pixel.sample(s);
    let ray = camera_ray(scene, &mut sampler, (x, y), scale);
    let l = integrator.li(scene, ray, &mut sampler);
    limit_sample(l)
}

/// A sample's camera ray through pixel (x, y): the first draws of its
/// sampler are the position in the pixel (box filter), the lens and the
/// time; `scale` > 1 for the pixels of a smaller preview image.
#[inline]
pub(crate) fn camera_ray(
    scene: &Scene,
    sampler: &mut Sampler,
    (x, y): (u32, u32),
    scale: f32,
) -> Ray {
    let film = (Vec2::new(x as f32, y as f32) + sampler.next_2d()) * scale;
    let lens = sampler.next_2d();
    let t = sampler.next_f32();
    scene.camera.ray(film, lens, t)
}

/// A sample as it enters a pixel's sum: a NaN or infinite one would poison
/// the pixel and is dropped (counted as black); a huge one is scaled down to
/// [`MAX_SAMPLE`].
#[inline]
fn limit_sample(l: Vec3) -> Vec3 {
    if !l.is_finite() {
        return Vec3::ZERO;
    }
    crate::integrator::scaled_within(l, MAX_SAMPLE)
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
