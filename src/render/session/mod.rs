//! A render from the scene to the files, with the policy the pixel loop
//! ([`crate::render::render_from`]) leaves out: the passes, the image
//! written as they go, checkpoints, the render's state (never replacing
//! one that holds a user's samples without being asked, resuming, parts
//! of a render split with `--pass K/N`), the preview of a live render, and
//! cancellation. `ptsc render` runs batch sessions, `ptsc watch` live ones;
//! the command line only turns its arguments into a [`Plan`], prints what
//! the [`Observer`] hears and what [`Session::run`] returns, and sets the
//! [`Cancel`] token from its signal handler.
//!
//! A session starts in two steps, so that a caller can act between them:
//! [`Plan::check`] finds whether the files it writes can be written
//! (changing nothing), [`Session::new`] then checks the state and the
//! memory and reads a saved state. (`watch` stops the render in flight
//! between the two: a save with an image that cannot be written keeps it
//! running, and the new film's memory is counted once the old one is
//! freed.)

mod batch;
mod budget;
mod cancel;
mod error;
mod final_image;
mod live;
mod observer;
mod start;
mod viewer;

pub use batch::PREVIEW_INTERVAL;
pub use cancel::Cancel;
pub use error::Error;
pub use live::{preview_path, PREVIEW_DIVISOR};
pub use observer::{Observer, PassDone, PreviewDone, Report};
pub use start::{state_path, StatePolicy};

use crate::ir::Scene;
use crate::render::film::Film;
use std::path::{Path, PathBuf};

/// What a session renders to, and by which rules.
#[derive(Debug, Clone)]
pub struct Plan {
    /// The image (or, for a pass, the part file).
    pub output: PathBuf,
    /// The files the scene was made from: the image must not replace one.
    pub inputs: Vec<PathBuf>,
    /// The most memory the render may take (`None`: what the machine
    /// leaves free).
    pub memory_limit: Option<u64>,
    /// Batch or live.
    pub mode: Mode,
    /// The AOVs a batch render writes with its final image, as channels of
    /// its EXR (a live render writes none).
    pub aovs: Vec<crate::render::aov::Aov>,
    /// Whether a batch render's final image is denoised (`--denoise`).
    pub denoise: bool,
    /// Where the tev viewer listens, for a batch render to show its passes
    /// there (`--tev`; a live render sends nothing).
    pub tev: Option<String>,
}

/// The two kinds of session.
#[derive(Debug, Clone)]
pub enum Mode {
    /// `ptsc render`: passes to the samples asked, the image rewritten
    /// every [`PREVIEW_INTERVAL`] at most, checkpoints; at the end the
    /// image, and the state where the policy keeps it, after a stop too.
    Batch(StatePolicy),
    /// `ptsc watch`: a preview at 1/[`PREVIEW_DIVISOR`] of the resolution
    /// to [`preview_path`], then every pass written to the image; no
    /// state, and nothing written after a stop.
    Live,
}

/// A plan whose files can be written: the first step of a session.
#[derive(Debug, Clone)]
pub struct Checked {
    /// The plan.
    plan: Plan,
    /// The live preview's file, when it can be written.
    preview: Option<PathBuf>,
    /// The live preview's file and why it cannot be written: the preview
    /// is left out, the passes are not.
    pub no_preview: Option<(PathBuf, String)>,
}

impl Plan {
    /// The first step: whether the image can be written (not a file of the
    /// scene, a known format, a folder that takes it), and for a live
    /// render its preview (left out, with why, when it cannot). Changes
    /// nothing.
    pub fn check(self) -> Result<Checked, Error> {
        crate::output::check_output(&self.output, &self.inputs).map_err(|why| Error::Output {
            path: self.output.clone(),
            why,
        })?;
        let exr =
            crate::output::ImageFormat::of(&self.output) == Some(crate::output::ImageFormat::Exr);
        if self.denoise && !crate::render::denoise::AVAILABLE {
            return Err(Error::Refused(
                crate::render::denoise::NOT_BUILT.to_string(),
            ));
        }
        if !self.aovs.is_empty() && !exr {
            return Err(Error::Output {
                path: self.output.clone(),
                why: "--aov writes its layers as channels of an EXR: name an .exr output".into(),
            });
        }
        let (mut preview, mut no_preview) = (None, None);
        if let Mode::Live = self.mode {
            let path = preview_path(&self.output);
            match crate::output::check_output(&path, &self.inputs)
                .and_then(|()| crate::render::state::refuse_to_replace(&path, None))
            {
                Ok(()) => preview = Some(path),
                Err(why) => no_preview = Some((path, why)),
            }
        }
        Ok(Checked {
            plan: self,
            preview,
            no_preview,
        })
    }
}

/// A render ready to run.
pub struct Session {
    /// What it renders.
    scene: Scene,
    /// The image (or part file).
    output: PathBuf,
    /// What the kind of session holds.
    kind: Kind,
}

/// A batch session's state and starting film, or a live one's preview.
enum Kind {
    Batch(Box<batch::Batch>, Film),
    Live { preview: Option<PathBuf> },
}

impl Session {
    /// The second step: the state and memory checks (for a batch render,
    /// also its pass and the saved state it starts from, read here).
    pub fn new(scene: Scene, checked: Checked) -> Result<Session, Error> {
        let Checked { plan, preview, .. } = checked;
        let kind = match plan.mode {
            Mode::Batch(policy) => {
                let extras = (plan.aovs, plan.denoise, plan.tev);
                let (batch, film) =
                    batch::prepare(&scene, &plan.output, policy, plan.memory_limit, extras)?;
                Kind::Batch(Box::new(batch), film)
            }
            Mode::Live => {
                live::prepare(&scene, &plan.output, plan.memory_limit)?;
                Kind::Live { preview }
            }
        };
        Ok(Session {
            scene,
            output: plan.output,
            kind,
        })
    }

    /// The scene it renders.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The image (or part file) it writes.
    pub fn output(&self) -> &Path {
        &self.output
    }

    /// What the start says: resumed from how many samples, or that no
    /// state was there to resume.
    pub fn note(&self) -> Option<&str> {
        match &self.kind {
            Kind::Batch(batch, _) => batch.note.as_deref(),
            Kind::Live { .. } => None,
        }
    }

    /// Where a batch render keeps its state.
    pub fn state_path(&self) -> Option<&Path> {
        match &self.kind {
            Kind::Batch(batch, _) => Some(&batch.state),
            Kind::Live { .. } => None,
        }
    }

    /// Pixel samples the film starts with (a resumed state's).
    pub fn samples_done(&self) -> u64 {
        match &self.kind {
            Kind::Batch(_, film) => film.total_samples(),
            Kind::Live { .. } => 0,
        }
    }

    /// The memory a batch render takes beyond the scene's own (its film,
    /// half images and output variables), as checked before it starts;
    /// `None` for a live render.
    pub fn memory_need(&self) -> Option<crate::render::memory::Need> {
        match &self.kind {
            Kind::Batch(batch, _) => Some(batch.need),
            Kind::Live { .. } => None,
        }
    }

    /// Pixel samples the film ends with.
    pub fn samples_total(&self) -> u64 {
        let s = &self.scene.settings;
        let spp = match &self.kind {
            Kind::Batch(batch, _) => batch.target(),
            Kind::Live { .. } => s.samples,
        };
        s.width as u64 * s.height as u64 * spp as u64
    }

    /// Renders, telling `observer` as it goes, until the passes end or
    /// `cancel` is set; returns how it ended, or why the image or state
    /// could not be written.
    pub fn run(self, observer: &dyn Observer, cancel: &Cancel) -> Result<Report, Error> {
        match self.kind {
            Kind::Batch(batch, film) => {
                batch::run(&self.scene, &self.output, (*batch, film), observer, cancel)
            }
            Kind::Live { preview } => Ok(live::run(
                &self.scene,
                (&self.output, preview.as_deref()),
                observer,
                cancel,
            )),
        }
    }
}
