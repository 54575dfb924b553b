//! A live render (`ptsc watch`): a quick preview at a fraction of the
//! resolution, to its own file beside the image, then full-resolution
//! passes of 1, 2, 4, … spp, the image replaced after each. Nothing is
//! kept: a stopped live render is replaced by the next one, and writes
//! nothing more.

use super::cancel::Cancel;
use super::error::Error;
use super::observer::{Observer, PassDone, PreviewDone, Report};
use crate::ir::Scene;
use crate::render::denoise::{denoise_as, Speed};
use crate::render::film::Film;
use crate::render::memory::{self, Need};
use crate::render::{Outcome, Progression};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// A live render's preview is this many times smaller on each side.
pub const PREVIEW_DIVISOR: u32 = 4;

/// Where a live render writes the quick preview of the image `output`:
/// beside it, `.preview` before the extension (`shot.png` →
/// `shot.preview.png`).
pub fn preview_path(output: &Path) -> PathBuf {
    let stem = output.file_stem().unwrap_or_default().to_string_lossy();
    let name = match output.extension() {
        Some(ext) => format!("{stem}.preview.{}", ext.to_string_lossy()),
        None => format!("{stem}.preview"),
    };
    output.with_file_name(name)
}

/// Why the live render must not start: the image it replaces holds a
/// render's state, or its film does not fit in the memory left.
pub(super) fn prepare(
    scene: &Scene,
    output: &Path,
    memory_limit: Option<u64>,
) -> Result<(), Error> {
    let s = &scene.settings;
    let need = Need::film((s.width, s.height)).with_halves(s.adaptive.is_some());
    crate::render::state::refuse_to_replace(output, None)
        .and_then(|()| memory::check(&need, memory_limit))
        .map_err(Error::Refused)
}

/// Rays per pixel for the albedo and normal that guide the preview's
/// denoising: one, as the preview's colour has (more cost the preview's
/// time; OIDN takes guides as noisy as the colour).
const PREVIEW_GUIDE_RAYS: u32 = 1;

/// The preview `film` denoised with the albedo and normal of its first
/// surfaces, in a build with the `denoise` feature; `None` without it,
/// when cancelled, or when denoising fails (the noisy preview then shows).
fn denoised_preview(scene: &Scene, film: &Film, cancel: &Cancel) -> Option<Vec<glam::Vec3>> {
    if !crate::render::denoise::AVAILABLE {
        return None;
    }
    let size = (film.width, film.height);
    let (albedo, normal) = crate::render::aov::denoiser_guides(
        scene,
        size,
        PREVIEW_DIVISOR,
        PREVIEW_GUIDE_RAYS,
        cancel.polled(),
    )?;
    let colour = film.pixels();
    let guides = (Some(&albedo[..]), Some(&normal[..]));
    // OIDN's fast network: the preview's time is the latency of a save.
    denoise_as(Speed::Preview, size.0, size.1, &colour, guides).ok()
}

/// The preview (to `preview`, when there is one and the image is large
/// enough to shrink), then the passes, each written to `output`.
pub(super) fn run(
    scene: &Scene,
    (output, preview): (&Path, Option<&Path>),
    observer: &dyn Observer,
    cancel: &Cancel,
) -> Report {
    let s = &scene.settings;
    let integrator = crate::integrator::make(s.integrator, scene);
    let (w, h) = (s.width, s.height);
    let t0 = Instant::now();
    let wants_preview = w >= 4 * PREVIEW_DIVISOR && h >= 4 * PREVIEW_DIVISOR;
    if let Some(preview) = preview.filter(|_| wants_preview && s.samples > 1) {
        let rendered = crate::render::render_preview(
            scene,
            integrator.as_ref(),
            cancel.polled(),
            PREVIEW_DIVISOR,
        );
        let Some(film) = rendered else {
            return stopped_early(t0.elapsed());
        };
        // A build that denoises shows a denoised preview: one sample per
        // pixel says little, denoised a good deal.
        let denoised = denoised_preview(scene, &film, cancel);
        if cancel.is_cancelled() {
            return stopped_early(t0.elapsed());
        }
        // At its own size: encoding it enlarged to the image's took as long
        // as rendering it (cornell: 171 M instructions of 348 M, mostly
        // sRGB conversion and deflate), and its own file needs no match.
        let size = (film.width, film.height);
        let written = match &denoised {
            Some(pixels) => crate::output::write_image(preview, size, |i| pixels[i], s.exposure),
            None => film.write(preview, s.exposure),
        };
        observer.preview(&PreviewDone {
            size,
            elapsed: t0.elapsed(),
            path: preview,
            written: &written,
            denoised: denoised.is_some(),
        });
    }
    let mut number = 0;
    let mut last = Instant::now();
    // Whether the last pass's image reached the disk.
    let mut written = false;
    let rendered = crate::render::render_from(
        scene,
        integrator.as_ref(),
        Film::for_settings(s, 0),
        (s.samples, Progression::Doubling),
        cancel.polled(),
        &|done| observer.progress(done),
        &mut |film, spp| {
            number += 1;
            let result = film.write(output, s.exposure);
            written = result.is_ok();
            observer.pass(&PassDone {
                elapsed: last.elapsed(),
                total: t0.elapsed(),
                image: Some(&result),
                ..PassDone::of(film, s.adaptive.is_some(), (spp, s.samples), number)
            });
            last = Instant::now();
        },
    );
    observer.rendered();
    Report {
        outcome: rendered.outcome,
        samples: rendered.film.total_samples(),
        film: rendered.film,
        rays: rendered.rays,
        render_time: t0.elapsed(),
        write_time: Duration::ZERO,
        image_written: written,
        state: None,
        budget_spent: false,
    }
}

/// The report of a live render stopped during its preview.
fn stopped_early(render_time: Duration) -> Report {
    Report {
        outcome: Outcome::Cancelled,
        film: Film::new(0, 0, 0),
        samples: 0,
        rays: Default::default(),
        render_time,
        write_time: Duration::ZERO,
        image_written: false,
        state: None,
        budget_spent: false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_preview_goes_beside_the_image_in_its_format() {
        let p = |s: &str| preview_path(Path::new(s));
        assert_eq!(p("out/shot.png"), Path::new("out/shot.preview.png"));
        assert_eq!(p("frame_0012.exr"), Path::new("frame_0012.preview.exr"));
        assert_eq!(p("a.b.pfm"), Path::new("a.b.preview.pfm"));
    }
}
