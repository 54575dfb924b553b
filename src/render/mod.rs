//! The pixel loop — the only one in ptsc: rayon over tiles, progressive
//! passes (a batch render's 1, 16, 32, … samples per pixel, `watch`'s 1, 2,
//! 4, …: [`Progression`]), a cancellation flag checked between
//! tiles, a progress callback. Every sample draws from its own random stream
//! (seed, pixel, sample index), so the image is the same for any thread count.

pub mod adaptive;
pub mod aov;
pub mod denoise;
pub mod film;
pub mod memory;
pub mod merge;
mod packet_gauge;
pub mod session;
pub mod state;

use crate::accel::ray_count::{self, RayCounts};
use crate::geometry::Ray;
use crate::integrator::T_MIN;
use crate::integrator::{Integrator, Splat};
use crate::ir::Scene;
use crate::sampling::sampler::{PixelSampler, Sampler, BATCH};
pub use adaptive::Progression;
use arrayvec::ArrayVec;
use film::{Film, Halves};
use glam::{DVec3, Vec2, Vec3};
use packet_gauge::PacketGauge;
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
    /// Its rows of odd samples' sums (adaptive sampling).
    odd: Option<Vec<&'a mut [DVec3]>>,
}

/// A film's per-pixel values (row-major, `width` a row) cut into the tiles
/// of TILE × TILE (fewer at the right and bottom edges), in row-major
/// order of tiles, each a list of its rows.
fn tiles_of<T>(values: &mut [T], width: u32) -> Vec<Vec<&mut [T]>> {
    let (w, tile) = (width as usize, TILE as usize);
    let across = w.div_ceil(tile);
    let mut tiles: Vec<Vec<&mut [T]>> = Vec::new();
    for band in values.chunks_mut(w * tile) {
        let first = tiles.len();
        tiles.extend((0..across).map(|_| Vec::with_capacity(tile)));
        for row in band.chunks_mut(w) {
            for (tx, cell) in row.chunks_mut(tile).enumerate() {
                tiles[first + tx].push(cell);
            }
        }
    }
    tiles
}

/// The film's pixels as tiles, with what the pass reads of it whole: which
/// pixels adaptive sampling stopped.
fn tile_rows(film: &mut Film) -> (Vec<TileRows<'_>>, Option<&[bool]>) {
    let (w, tile) = (film.width, TILE);
    let across = w.div_ceil(tile);
    let (odd, stopped) = match film.halves.as_mut() {
        Some(Halves { odd, stopped }) => (Some(tiles_of(odd, w)), Some(&stopped[..])),
        None => (None, None),
    };
    let mut odd = odd.map(Vec::into_iter);
    let sums = tiles_of(&mut film.sum, w);
    let counts = tiles_of(&mut film.count, w);
    let tiles = (sums.into_iter().zip(counts).enumerate())
        .map(|(t, (sums, counts))| TileRows {
            corner: ((t as u32 % across) * tile, (t as u32 / across) * tile),
            sums,
            counts,
            odd: odd.as_mut().and_then(Iterator::next),
        })
        .collect();
    (tiles, stopped)
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
    let film = Film::for_settings(s, 0);
    let to = (s.samples, Progression::Runs);
    render_from(scene, integrator, film, to, cancel, progress, on_pass)
}

/// Renders on from `film` (a render's saved state, or a new film whose runs
/// start at another sample index) until every pixel has `samples` samples:
/// pixel (x, y) gets sample indices `film.first + film.count[i] ..
/// film.first + samples`, in passes that grow by `progression`. The film
/// must have the scene's size.
pub fn render_from(
    scene: &Scene,
    integrator: &dyn Integrator,
    film: Film,
    (samples, progression): (u32, Progression),
    cancel: &AtomicBool,
    progress: &(dyn Fn(u64) + Sync),
    on_pass: &mut dyn FnMut(&Film, u32),
) -> Rendered {
    let view = View {
        width: film.width,
        height: film.height,
        samples,
        progression,
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
        progression: Progression::Runs,
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
    /// How its passes grow.
    progression: Progression,
    scale: u32,
}

/// The pixel loop: tiles over rayon, progressive passes. Each pixel's
/// samples are added to its sum one by one in sample-index order, from the
/// sum `film` holds: however a render is stopped and continued, the same
/// additions happen in the same order. An adaptive render's film decides
/// which pixels stop after the passes that end at a decision.
fn render_view(
    scene: &Scene,
    integrator: &dyn Integrator,
    mut film: Film,
    view: View,
    cancel: &AtomicBool,
    progress: &(dyn Fn(u64) + Sync),
    on_pass: &mut dyn FnMut(&Film, u32),
) -> Rendered {
    debug_assert_eq!((film.width, film.height), (view.width, view.height));
    if integrator.splats() && film.light.is_none() {
        film = film.with_light();
    }
    let done = AtomicU64::new(0);
    let mut rays = RayCounts::default();
    let adaptive_sampling = (scene.settings.adaptive).filter(|_| film.halves.is_some());
    // A resumed film skips the passes its every sampling pixel has done
    // (all of them when every pixel has stopped).
    let mut reached = film.least_active().unwrap_or(u32::MAX);
    let mut progression = view.progression;
    let next_end = |reached: u32, progression| {
        let ends = adaptive::pass_ends(view.samples, adaptive_sampling.as_ref(), progression);
        ends.into_iter().find(|&e| e > reached)
    };
    // Per tile, whether its camera rays go as packets: on where they can,
    // until a pass finds that they do not pay there ([`PacketGauge`]).
    let packets = integrator.takes_first_hit(scene) && scene.traces_packets();
    let tiles_across = view.width.div_ceil(TILE);
    let tile_count = tiles_across as usize * view.height.div_ceil(TILE) as usize;
    let packet_tiles: Vec<AtomicBool> = (0..tile_count).map(|_| AtomicBool::new(packets)).collect();
    while let Some(end) = next_end(reached, progression) {
        let started = std::time::Instant::now();
        let shared = PassShared {
            scene,
            integrator,
            view: &view,
            packet_tiles: &packet_tiles,
            tiles_across,
            cancel,
            progress,
            done: &done,
        };
        let results = run_pass(&shared, &mut film, end);
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
        let mut all_stopped = false;
        if let Some(a) = adaptive_sampling.filter(|a| adaptive::is_decision(end, a)) {
            adaptive::decide(&mut film, end, a.threshold);
            all_stopped = film.active_pixels() == 0;
        }
        on_pass(&film, end);
        if all_stopped {
            break;
        }
        (reached, progression) = (end, progression.after_pass(end, started.elapsed()));
    }
    Rendered {
        film,
        outcome: Outcome::Complete,
        rays,
    }
}

/// What every pass of a render shares.
struct PassShared<'a> {
    scene: &'a Scene,
    integrator: &'a dyn Integrator,
    view: &'a View,
    packet_tiles: &'a [AtomicBool],
    tiles_across: u32,
    cancel: &'a AtomicBool,
    progress: &'a (dyn Fn(u64) + Sync),
    done: &'a AtomicU64,
}

/// Splats a step of a splatting pass may hold at once, about: the pass
/// goes in steps of fewer samples per pixel, and of fewer tiles, so that
/// their splats (a few per sample, 20 bytes each) stay near 64 MB.
const SPLAT_STEP_SAMPLES: u64 = 1 << 20;

/// Brings every pixel's samples to `end`: each tile's result (cancelled,
/// rays traced). An integrator that splats goes in steps of samples and
/// of tiles, its splats added to the light film in tile order after each
/// step, so that the film is the same on any number of threads.
fn run_pass(shared: &PassShared, film: &mut Film, end: u32) -> Vec<(bool, RayCounts)> {
    let first = film.first;
    let mut light = film.light.take();
    let (mut tiles, stopped) = tile_rows(film);
    let pixels = shared.view.width as u64 * shared.view.height as u64;
    let (step_samples, step_tiles) = match light {
        Some(_) => {
            let per_pixel = (SPLAT_STEP_SAMPLES / pixels.max(1)).max(1);
            let tiles = SPLAT_STEP_SAMPLES / (per_pixel * (TILE * TILE) as u64);
            (per_pixel.min(u32::MAX as u64) as u32, tiles.max(1) as usize)
        }
        None => (u32::MAX, usize::MAX),
    };
    // Steps start from the fewest samples a pixel has (a pass without
    // splats is one step: its pixels' counts are not read).
    let least = match light {
        Some(_) => (tiles.iter())
            .flat_map(|t| t.counts.iter().flat_map(|r| r.iter().copied()))
            .min()
            .unwrap_or(end),
        None => 0,
    };
    let mut results: Vec<(bool, RayCounts)> = Vec::new();
    let mut step_end = end.min(least.saturating_add(step_samples));
    loop {
        results.clear();
        let pass = TilePass {
            scene: shared.scene,
            integrator: shared.integrator,
            first,
            end: step_end,
            scale: shared.view.scale as f32,
            width: shared.view.width,
            stopped,
            packet_tiles: shared.packet_tiles,
            tiles_across: shared.tiles_across,
            cancel: shared.cancel,
        };
        for group in tiles.chunks_mut(step_tiles) {
            let done: Vec<(bool, RayCounts, u64, Vec<Splat>)> = group
                .par_iter_mut()
                .map(|tile| {
                    let rays_before = ray_count::this_thread();
                    let mut splats = Vec::new();
                    let (samples, stopped) = render_tile(&pass, tile, &mut splats);
                    (shared.progress)(shared.done.fetch_add(samples, Ordering::Relaxed) + samples);
                    (
                        stopped,
                        ray_count::this_thread() - rays_before,
                        samples,
                        splats,
                    )
                })
                .collect();
            for (stopped, rays, samples, splats) in done {
                if let Some(light) = light.as_mut() {
                    add_splats(light, shared.view, &splats);
                    light.paths += samples;
                }
                results.push((stopped, rays));
            }
            if results.iter().any(|r| r.0) {
                break;
            }
        }
        if step_end >= end || results.iter().any(|r| r.0) {
            break;
        }
        step_end = end.min(step_end.saturating_add(step_samples));
    }
    drop(tiles);
    film.light = light;
    results
}

/// Adds a tile's splats to the light film, in order.
fn add_splats(light: &mut film::LightFilm, view: &View, splats: &[Splat]) {
    let scale = view.scale as f32;
    for splat in splats {
        let p = splat.film / scale;
        let (x, y) = (p.x.floor(), p.y.floor());
        if x < 0.0 || y < 0.0 || x >= view.width as f32 || y >= view.height as f32 {
            continue;
        }
        let i = y as usize * view.width as usize + x as usize;
        light.sum[i] += limit_sample(splat.value).as_dvec3();
    }
}

/// What the tiles of a pass share.
struct TilePass<'a> {
    scene: &'a Scene,
    integrator: &'a dyn Integrator,
    /// The film's first sample index.
    first: u32,
    /// The samples per pixel the pass ends at.
    end: u32,
    /// Pixels of the scene's image one pixel of the view covers on a side.
    scale: f32,
    /// The view's width.
    width: u32,
    /// Which pixels adaptive sampling stopped.
    stopped: Option<&'a [bool]>,
    /// Per tile, whether its pixels' camera rays go as packets (the
    /// integrator takes their hits, the scene traces packets, and they
    /// paid in the tile so far).
    packet_tiles: &'a [AtomicBool],
    /// Tiles in a row of the view.
    tiles_across: u32,
    cancel: &'a AtomicBool,
}

/// Brings a tile's pixels to the pass's end, or stops when the pass is
/// cancelled: the samples drawn, and whether it was cancelled.
fn render_tile(pass: &TilePass, tile: &mut TileRows, splats: &mut Vec<Splat>) -> (u64, bool) {
    let (x0, y0) = tile.corner;
    let mut samples = 0u64;
    let mut pixel = pixel_sampler(pass.scene, x0, y0);
    let packets = &pass.packet_tiles[(y0 / TILE * pass.tiles_across + x0 / TILE) as usize];
    let mut gauge = PacketGauge::new(packets.load(Ordering::Relaxed));
    let rows = tile.sums.iter_mut().zip(tile.counts.iter_mut());
    for (row, (y, (sums, counts))) in (y0..).zip(rows).enumerate() {
        let mut odd_row = tile.odd.as_mut().map(|rows| &mut *rows[row]);
        for (col, (sum, count)) in sums.iter_mut().zip(counts.iter_mut()).enumerate() {
            let x = x0 + col as u32;
            let from = *count;
            let stopped = || {
                pass.stopped
                    .is_some_and(|s| s[(y * pass.width + x) as usize])
            };
            if from >= pass.end || stopped() {
                continue;
            }
            pixel.move_to((x, y));
            let odd = odd_row.as_mut().map(|r| &mut r[col]);
            let run = (&mut pixel, &mut gauge);
            *count = render_pixel(pass, run, (x, y), from, (sum, odd), splats);
            samples += (*count - from) as u64;
            if *count < pass.end {
                packets.store(gauge.on, Ordering::Relaxed);
                return (samples, true);
            }
        }
    }
    packets.store(gauge.on, Ordering::Relaxed);
    (samples, false)
}

/// Adds pixel (x, y)'s samples from index `from` to the pass's end into
/// its sum (and those of odd index into `odd`, for adaptive sampling);
/// returns the count reached: the end, or less when the pass is cancelled.
/// Runs of up to [`BATCH`] samples draw their Sobol points together and,
/// where the integrator takes a first hit, trace their camera rays as a
/// packet; either way each sample adds what it adds alone, in index order.
#[inline]
fn render_pixel(
    pass: &TilePass,
    (pixel, gauge): (&mut PixelSampler, &mut PacketGauge),
    (x, y): (u32, u32),
    from: u32,
    (sum, mut odd): (&mut DVec3, Option<&mut DVec3>),
    splats: &mut Vec<Splat>,
) -> u32 {
    // Sample `s` of a pixel is the same wherever and whenever it is drawn:
    // what lets a render stop, continue, and split across machines.
    let first = pass.first;
    let mut add = |s: u32, l: Vec3| {
        *sum += l.as_dvec3();
        if let Some(odd) = odd.as_deref_mut().filter(|_| (first + s) % 2 == 1) {
            *odd += l.as_dvec3();
        }
    };
    let mut s = from;
    while s < pass.end {
        pixel.prepare(first + s, pass.end - s);
        let run_end = pass.end.min(s + BATCH);
        if gauge.on && run_end - s >= 2 {
            let run = (pixel as &PixelSampler, &mut *gauge);
            if let Err(stopped) = render_packet(pass, run, (x, y), s..run_end, &mut add) {
                return stopped;
            }
            s = run_end;
            continue;
        }
        for s in s..run_end {
            if (s - from).is_multiple_of(CANCEL_POLL) && pass.cancel.load(Ordering::Relaxed) {
                return s;
            }
            let mut sampler = pixel.sample(first + s);
            let ray = camera_ray(pass.scene, &mut sampler, (x, y), pass.scale);
            let l = (pass.integrator).li_splatting(pass.scene, ray, &mut sampler, splats);
            add(s, limit_sample(l));
        }
        s = run_end;
    }
    pass.end
}

/// The samples `run` of pixel (x, y) with their camera rays traced as one
/// packet (one by one where they do not go together), each added by
/// `add(s, l)` in order; `Err(s)` when the pass is cancelled before sample
/// `s`.
#[inline]
fn render_packet(
    pass: &TilePass,
    (pixel, gauge): (&PixelSampler, &mut PacketGauge),
    (x, y): (u32, u32),
    run: std::ops::Range<u32>,
    add: &mut impl FnMut(u32, Vec3),
) -> Result<(), u32> {
    if pass.cancel.load(Ordering::Relaxed) {
        return Err(run.start);
    }
    let (scene, integrator) = (pass.scene, pass.integrator);
    let mut samplers: ArrayVec<Sampler, { BATCH as usize }> = ArrayVec::new();
    let mut rays: ArrayVec<Ray, { BATCH as usize }> = ArrayVec::new();
    for s in run.clone() {
        let mut sampler = pixel.sample(pass.first + s);
        rays.push(camera_ray(scene, &mut sampler, (x, y), pass.scale));
        samplers.push(sampler);
    }
    let hits = scene.intersect_packet(&rays, T_MIN);
    if let Some(h) = &hits {
        gauge.add(h.leaf_tests());
    }
    for (i, (s, mut sampler)) in run.clone().zip(samplers).enumerate() {
        if i > 0 && (i as u32).is_multiple_of(CANCEL_POLL) && pass.cancel.load(Ordering::Relaxed) {
            return Err(s);
        }
        let l = match &hits {
            Some(hits) => integrator.li_from(scene, rays[i], hits.get(i), &mut sampler),
            None => integrator.li(scene, rays[i], &mut sampler),
        };
        add(s, limit_sample(l));
    }
    Ok(())
}

/// The sampling of pixel (x, y) of the scene's render.
pub fn pixel_sampler(scene: &Scene, x: u32, y: u32) -> PixelSampler {
    let (s, camera) = (&scene.settings, &scene.camera);
    PixelSampler::new(
        s.sampler,
        s.seed,
        (x, y),
        camera.uses_lens(),
        camera.uses_time(),
    )
}

/// A sample's camera ray through pixel (x, y): the first draws of its
/// sampler are the position in the pixel (box filter), then the lens and
/// the time where the camera uses them. A pinhole's ray is the same for
/// any lens point, a closed shutter's for any time: their slots are
/// skipped, not drawn (three numbers of the PCG stream a path drew and
/// dropped), so that the time keeps its own stratified slot behind an
/// unused lens. `scale` > 1 for the pixels of a smaller preview image.
#[inline]
pub fn camera_ray(scene: &Scene, sampler: &mut Sampler, (x, y): (u32, u32), scale: f32) -> Ray {
    let camera = &scene.camera;
    let film = (Vec2::new(x as f32, y as f32) + sampler.next_2d()) * scale;
    let lens = if camera.uses_lens() {
        sampler.next_2d()
    } else {
        sampler.skip();
        Vec2::ZERO
    };
    let t = if camera.uses_time() {
        sampler.next_f32()
    } else {
        sampler.skip();
        0.0
    };
    camera.ray(film, lens, t)
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
