//! What a session tells its caller while it runs ([`Observer`]: progress,
//! passes, checkpoints; the command line draws its bar and prints its
//! lines from them) and what it returns at the end ([`Report`]).

use crate::accel::ray_count::RayCounts;
use crate::render::film::Film;
use crate::render::Outcome;
use std::path::{Path, PathBuf};
use std::time::Duration;

/// Hears a session's events. Every method has a default that does
/// nothing; `progress` is called from the render's threads, the others
/// from the thread that runs the session.
pub trait Observer: Sync {
    /// Samples drawn so far in all pixels, those the film started with
    /// included, as tiles finish.
    fn progress(&self, _done: u64) {}

    /// The quick low-resolution preview was rendered and written (or not).
    fn preview(&self, _preview: &PreviewDone) {}

    /// A pass ended.
    fn pass(&self, _pass: &PassDone) {}

    /// A checkpoint saved the render's state at `state`; the render goes on.
    fn checkpoint(&self, _state: &Path) {}

    /// The passes are over (finished or stopped): what follows is the
    /// writing of the image and the state.
    fn rendered(&self) {}

    /// Something the user should know that changes nothing of the render
    /// (the tev viewer went away).
    fn note(&self, _text: &str) {}
}

/// A pass that ended.
#[derive(Debug)]
pub struct PassDone<'a> {
    /// Passes ended in this session so far, this one included.
    pub number: u32,
    /// Samples per pixel at the end of the pass.
    pub spp: u32,
    /// Time since the last pass ended (or the passes began).
    pub elapsed: Duration,
    /// Time since the session began.
    pub total: Duration,
    /// Where the session writes the image after every pass (`watch`):
    /// how writing it went.
    pub image: Option<&'a std::io::Result<()>>,
    /// The share of pixels adaptive sampling has stopped (`None`: the
    /// render is not adaptive).
    pub converged: Option<f64>,
    /// Pixel samples still to draw to reach the samples asked, as the
    /// pixels that sample on now tell.
    pub samples_left: u64,
}

impl PassDone<'_> {
    /// A pass that brought `film` to `spp` on the way to `target`; the
    /// share converged only when the render samples `adaptive`ly (a film
    /// may keep half images for the variance AOV alone).
    pub(super) fn of(
        film: &Film,
        adaptive: bool,
        (spp, target): (u32, u32),
        number: u32,
    ) -> PassDone<'static> {
        PassDone {
            number,
            spp,
            elapsed: Duration::ZERO,
            total: Duration::ZERO,
            image: None,
            converged: film.stopped_share().filter(|_| adaptive),
            samples_left: film.active_pixels() * target.saturating_sub(spp) as u64,
        }
    }
}

/// The preview that was rendered.
#[derive(Debug)]
pub struct PreviewDone<'a> {
    /// Its size in pixels.
    pub size: (u32, u32),
    /// Time since the session began.
    pub elapsed: Duration,
    /// Its file.
    pub path: &'a Path,
    /// How writing it went.
    pub written: &'a std::io::Result<()>,
    /// Whether it was denoised (a build with the `denoise` feature).
    pub denoised: bool,
}

/// How a session ended.
#[derive(Debug)]
pub struct Report {
    /// Whether every pass finished or the session was cancelled.
    pub outcome: Outcome,
    /// The film at the end (empty when the session was cancelled before
    /// its first pass began).
    pub film: Film,
    /// Pixel samples drawn in this session (not those it started from).
    pub samples: u64,
    /// The rays traced.
    pub rays: RayCounts,
    /// Time of the passes (from the start to the end of the last pass).
    pub render_time: Duration,
    /// Time of the writes after the passes.
    pub write_time: Duration,
    /// Whether the image holds the film's samples at the end (a batch
    /// render with no sample writes nothing; a live one may have failed
    /// to write its last pass).
    pub image_written: bool,
    /// The state file written at the end, if one was (a pass's part file
    /// is its image).
    pub state: Option<PathBuf>,
    /// Whether a time budget ran out before the samples asked (a render
    /// that reached them, or was stopped, did not spend it).
    pub budget_spent: bool,
}
