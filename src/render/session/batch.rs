//! A batch render (`ptsc render`): passes up to the samples asked, the
//! image rewritten between them now and then (a preview that refines),
//! checkpoints that save the state and go on, and at the end the image
//! and, where it is kept, the state: after a stop too, so that a resumed
//! render ends with the image of an uninterrupted one.

use super::budget::Budget;
use super::cancel::Cancel;
use super::error::Error;
use super::final_image::{self, final_image, FinalImage};
use super::observer::{Observer, PassDone, Report};
use super::start::{self, state_path, StatePolicy};
use crate::accel::ray_count::RayCounts;
use crate::ir::Scene;
use crate::output::tev::Tev;
use crate::render::aov::Aov;
use crate::render::film::Film;
use crate::render::memory::{self, Need};
use crate::render::state::{self, Pass, StateInfo};
use crate::render::{Outcome, Progression};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// Least time between two writes of a batch render's image between passes.
pub const PREVIEW_INTERVAL: Duration = Duration::from_secs(5);

/// A batch render ready to run: its state's path and description (the
/// film it starts from is held beside it).
pub(super) struct Batch {
    /// What the command line asked of the state.
    pub(super) policy: StatePolicy,
    /// Where the state lives (a pass's part file is its output).
    pub(super) state: PathBuf,
    /// The description of this render's state.
    pub(super) now: StateInfo,
    /// Whether a state file is there to keep current.
    pub(super) had_state: bool,
    /// What the start says (resumed from how many samples).
    pub(super) note: Option<String>,
    /// The AOVs written with the final image.
    pub(super) aovs: Vec<Aov>,
    /// Whether the final image is denoised.
    pub(super) denoise: bool,
    /// The tev viewer the passes are shown in (`--tev`).
    pub(super) tev: Option<crate::output::tev::Tev>,
    /// The memory the render takes beyond the scene (checked before it
    /// starts; `--verbose` prints it).
    pub(super) need: Need,
}

/// Why the render must not start (a state the image would replace, a
/// state path that cannot be written, more memory than is free, a pass
/// that cannot be written or would be empty, a state that cannot be
/// continued), else the render ready to run and the film it starts from
/// (a resumed state's, or a new one).
pub(super) fn prepare(
    scene: &Scene,
    output: &Path,
    policy: StatePolicy,
    memory_limit: Option<u64>,
    (aovs, denoise, tev): (Vec<Aov>, bool, Option<String>),
) -> Result<(Batch, Film), Error> {
    let s = &scene.settings;
    let state = state_path(output, policy.pass);
    if policy.pass.is_none() {
        state::refuse_to_replace(output, Some(policy.force)).map_err(Error::Refused)?;
        crate::output::check_writable(&state).map_err(|why| {
            Error::Refused(format!(
                "cannot write the render's state at {} (where checkpoints, Ctrl-C and --keep-state save it): {why}",
                crate::output::shown(&state)
            ))
        })?;
    }
    // Denoising takes the albedo and normal, and copies of the colour.
    let channels =
        aovs.iter().map(|a| a.channels().len() as u32).sum::<u32>() + if denoise { 12 } else { 0 };
    // The variance AOV is read from the half images: a whole render that
    // writes it keeps them (a pass writes no AOV).
    let halves = s.adaptive.is_some() || (aovs.contains(&Aov::Variance) && policy.pass.is_none());
    let light = crate::integrator::splats(s.integrator, scene);
    let need = (Need::film((s.width, s.height)).with_halves(halves)).with_aovs(channels);
    let need = need.with_light(light);
    memory::check(&need, memory_limit).map_err(Error::Refused)?;
    if let Some(pass) = policy.pass {
        if crate::output::ImageFormat::of(output) != Some(crate::output::ImageFormat::Exr) {
            return Err(Error::Refused(format!(
                "--pass {pass} writes a part file for `ptsc merge`: name an .exr output (-o part_{}.exr)",
                pass.k
            )));
        }
        if s.adaptive.is_some() {
            return Err(Error::Refused(format!(
                "--pass {pass} renders a fixed share of every pixel's samples for `ptsc merge`; adaptive sampling stops each pixel at its own count, which no share of the samples can know: drop the noise threshold (--noise, or `noise_threshold` in the scene's render block)"
            )));
        }
        if s.time.is_some() {
            return Err(Error::Refused(format!(
                "--pass {pass} renders a fixed share of the samples for `ptsc merge`: drop the time budget (--time, or `time` in the scene's render block)"
            )));
        }
        // A part file holds the colour's samples alone, which `merge` adds
        // up; the AOVs and the denoised image belong to the merged render.
        if !aovs.is_empty() || denoise {
            let asked = match (aovs.is_empty(), denoise) {
                (false, true) => "--aov and --denoise",
                (true, _) => "--denoise",
                (false, false) => "--aov",
            };
            return Err(Error::Refused(format!(
                "--pass {pass} writes the colour's samples alone for `ptsc merge`, which does not carry {asked} yet: leave {asked} out of the parts (`ptsc denoise merged.exr -o clean.png` denoises the merged colour), or render the AOVs in one whole render"
            )));
        }
        if pass.n > s.samples {
            return Err(Error::Refused(format!(
                "--pass {pass}: {} parts of {} samples per pixel would leave some empty; split into at most {} (or raise --spp)",
                pass.n, s.samples, s.samples
            )));
        }
    }
    let mut now = StateInfo {
        ptsc: env!("CARGO_PKG_VERSION").to_string(),
        scene: policy.scene.clone(),
        fingerprint: policy.fingerprint,
        settings: state::sample_settings(s),
        samples: s.samples,
        pass: policy.pass.unwrap_or(Pass::WHOLE),
        exposure: s.exposure,
    };
    if halves {
        now = now.with_halves();
    }
    if light {
        now = now.with_light();
    }
    let start = start::start(&state, &now, (s.width, s.height), &policy).map_err(Error::Refused)?;
    // Last: the viewer shows a new image only for a render that starts.
    let name = output.file_name().map(|n| n.to_string_lossy().into_owned());
    let tev = (tev.as_deref())
        .map(|address| {
            Tev::open(
                address,
                name.as_deref().unwrap_or("ptsc"),
                (s.width, s.height),
            )
        })
        .transpose()
        .map_err(Error::Refused)?;
    let batch = Batch {
        policy,
        state,
        now,
        had_state: start.had_state,
        note: start.note,
        aovs,
        denoise,
        tev,
        need,
    };
    Ok((batch, start.film))
}

impl Batch {
    /// Samples per pixel this render ends with: its pass's share.
    pub(super) fn target(&self) -> u32 {
        self.now.pass.range(self.now.samples).len() as u32
    }
}

/// What the passes left.
struct Passes {
    film: Film,
    rays: RayCounts,
    /// Whether a stop was asked (the passes did not all finish).
    interrupted: bool,
    /// Whether the state is saved at the end (a checkpoint made one).
    keep_state: bool,
    /// Whether the time budget ran out before the samples asked.
    budget_spent: bool,
    /// The last image write between passes that failed.
    write_error: Option<std::io::Error>,
}

/// Runs the render: passes with checkpoints, then the final writes.
pub(super) fn run(
    scene: &Scene,
    output: &Path,
    (batch, film): (Batch, Film),
    observer: &dyn Observer,
    cancel: &Cancel,
) -> Result<Report, Error> {
    let samples_before = film.total_samples();
    let t1 = Instant::now();
    let mut batch = batch;
    let tev = batch.tev.take();
    let passes = render_passes(scene, output, (&batch, tev), film, observer, cancel);
    observer.rendered();
    let passes = passes?;
    if let Some(error) = passes.write_error {
        return Err(Error::Write {
            path: output.to_path_buf(),
            error,
        });
    }
    let render_time = t1.elapsed();
    let film = passes.film;
    let most = film.sample_counts().1;
    let pass = batch.policy.pass;
    // The image, and the state where it is kept: always for a pass (its
    // part file is both) and after an interruption.
    let state_written = match pass {
        Some(_) => Some(output.to_path_buf()),
        None if passes.keep_state || (passes.interrupted && most > 0) => Some(batch.state.clone()),
        None => None,
    };
    let mut denoise_error = None;
    let naming = |path: &Path| {
        let path = path.to_path_buf();
        move |error| Error::Write { path, error }
    };
    match pass {
        Some(_) => state::write_state(output, &film, &batch.now).map_err(naming(output))?,
        // Both at once: each waits for its disk sync.
        None if most > 0 => {
            let exposure = scene.settings.exposure;
            // The AOVs and denoising of a render that finished (a stopped
            // one's image goes without them, its resumed end gets them).
            let finished = match passes.interrupted {
                false => final_image(scene, &film, &batch.aovs, batch.denoise, cancel.polled()),
                true => FinalImage::default(),
            };
            denoise_error = finished.denoise_error.clone();
            let (image, state) = rayon::join(
                || final_image::write(output, &film, exposure, &finished).map_err(naming(output)),
                || {
                    (state_written.as_deref()).map_or(Ok(()), |path| {
                        state::write_state(path, &film, &batch.now).map_err(naming(path))
                    })
                },
            );
            image.and(state)?
        }
        None => {}
    }
    if let Some(why) = denoise_error {
        return Err(Error::Denoise {
            path: output.to_path_buf(),
            why,
        });
    }
    Ok(Report {
        outcome: match passes.interrupted {
            true => Outcome::Cancelled,
            false => Outcome::Complete,
        },
        samples: film.total_samples() - samples_before,
        image_written: most > 0 || pass.is_some(),
        film,
        rays: passes.rays,
        write_time: t1.elapsed().saturating_sub(render_time),
        render_time,
        state: state_written,
        budget_spent: passes.budget_spent,
    })
}

/// The passes up to the target, paused for a checkpoint every
/// `policy.checkpoint` (the state and image saved, then on from them: the
/// same samples in the same order, so the image is the uninterrupted
/// one's), until they finish or a stop is asked.
fn render_passes(
    scene: &Scene,
    output: &Path,
    (batch, tev): (&Batch, Option<Tev>),
    mut film: Film,
    observer: &dyn Observer,
    cancel: &Cancel,
) -> Result<Passes, Error> {
    let s = &scene.settings;
    let target = batch.target();
    let integrator = crate::integrator::make(s.integrator, scene);
    let t1 = Instant::now();
    let mut write_error = None;
    let mut last_write = Instant::now();
    let mut last_pass = Instant::now();
    let mut number = 0;
    let mut viewer = super::viewer::Viewer::new(tev);
    // A part file is written whole (image and state) at every write.
    let write_image = |film: &Film| match batch.policy.pass {
        Some(_) => state::write_state(output, film, &batch.now),
        None => film.write(output, s.exposure),
    };
    let mut on_pass = |film: &Film, spp: u32| {
        number += 1;
        observer.pass(&PassDone {
            elapsed: last_pass.elapsed(),
            total: t1.elapsed(),
            ..PassDone::of(film, s.adaptive.is_some(), (spp, target), number)
        });
        last_pass = Instant::now();
        viewer.pass(film, spp >= target, observer);
        // A long render replaces its image with the passes so far, a
        // preview that refines. The final image is written once, at the
        // end; writes in between are spaced (a ZIP-compressed EXR of a
        // 512×512 render takes about 60 ms, time the render loses).
        if spp < target && last_write.elapsed() >= PREVIEW_INTERVAL {
            if let Err(e) = write_image(film) {
                write_error = Some(e);
            }
            last_write = Instant::now();
        }
    };
    let every = batch.policy.checkpoint;
    let mut keep_state = batch.policy.keep_state || batch.had_state;
    let mut rays = RayCounts::default();
    // With a time budget, one pass per run, each as long as fits.
    let mut budget = s
        .time
        .map(|seconds| Budget::new(seconds, &film, s.adaptive));
    let cut = std::sync::atomic::AtomicBool::new(false);
    let interrupted = loop {
        let run_target = match &mut budget {
            Some(budget) => match budget.next_target(&film, target) {
                Some(end) => end,
                None => break false,
            },
            None => target,
        };
        let deadline = every.map(|d: Duration| Instant::now() + d);
        let offset = film.total_samples();
        let rendered = crate::render::render_from(
            scene,
            integrator.as_ref(),
            film,
            (run_target, Progression::Runs),
            cancel.polled(),
            &|done| {
                observer.progress(offset + done);
                // Only once this run has drawn a sample: a run that paused
                // while it skipped the tiles done already would save the
                // same state again and again.
                if done > 0 && deadline.is_some_and(|d| Instant::now() >= d) {
                    cancel.pause();
                }
                if budget.as_ref().is_some_and(Budget::overrun) {
                    cut.store(true, std::sync::atomic::Ordering::Relaxed);
                    cancel.pause();
                }
            },
            &mut on_pass,
        );
        film = rendered.film;
        rays = rays + rendered.rays;
        if rendered.outcome == Outcome::Complete {
            if budget.is_some() {
                continue;
            }
            break false;
        }
        if cancel.is_cancelled() {
            break true;
        }
        cancel.resume();
        if cut.load(std::sync::atomic::Ordering::Relaxed) {
            break false;
        }
        let saved = write_image(&film).and_then(|()| match batch.policy.pass {
            Some(_) => Ok(()),
            None => state::write_state(&batch.state, &film, &batch.now),
        });
        if let Err(error) = saved {
            return Err(Error::SaveState {
                path: batch.state.clone(),
                error,
            });
        }
        keep_state = true;
        observer.checkpoint(&batch.state);
        // A stop asked during the save: stop here.
        if cancel.is_cancelled() {
            break true;
        }
    };
    viewer.finish(&film, observer);
    // A time budget's state is kept, spent or not (README, `--time`):
    // `--resume` adds more, for another budget or to a higher --spp.
    let short = film.least_active().is_some_and(|c| c < target);
    keep_state |= budget.is_some() && !interrupted;
    Ok(Passes {
        film,
        rays,
        interrupted,
        keep_state,
        budget_spent: budget.is_some() && short && !interrupted,
        write_error,
    })
}
