//! `ptsc render FILE`: check, lower, render with progress (from a saved
//! state where asked, with checkpoints), write atomically.

use super::args::apply_overrides;
pub use super::args::{output_path, RenderArgs};
use super::farm::{self, FarmArgs};
use super::signals::Signals;
use super::{check::report, Format, Verbosity, EXIT_OK, EXIT_SCENE_ERROR, EXIT_USAGE};
use crate::check::Animation;
use crate::compile::{compile_file, Compiled, Options};
use crate::lower::cache::LowerCache;
use crate::render::film::Film;
use crate::render::state::{self, Pass, StateInfo};
use std::path::{Path, PathBuf};
use std::sync::atomic::Ordering;
use std::time::{Duration, Instant};

/// Least time between two preview writes of a render's image.
const PREVIEW_INTERVAL: Duration = Duration::from_secs(5);

/// Compiles the scene at a frame with the command line's overrides (and
/// its fingerprint, for a render's state, when `fingerprint`).
pub fn compile(
    args: &RenderArgs,
    cache: Option<&mut LowerCache>,
    animation: Animation,
    fingerprint: bool,
) -> std::io::Result<Compiled> {
    compile_file(
        &args.file,
        Options {
            adjust: &|s| apply_overrides(s, args),
            cache,
            animation,
            fingerprint,
            output_elsewhere: args.output.is_some(),
            ..Options::default()
        },
    )
}

/// Runs `render`; returns the exit code.
pub fn run(args: &RenderArgs, farm: &FarmArgs) -> u8 {
    let pool = match rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads.unwrap_or(0))
        .build()
    {
        Ok(p) => p,
        Err(e) => {
            eprintln!("error: cannot start threads: {e}");
            return EXIT_USAGE;
        }
    };
    // Every parallel stage (parsing, the BVH build, the render) keeps to
    // `--threads`.
    pool.install(|| render_frames(args, farm))
}

/// Renders each frame asked for in turn; stops at the first that fails or
/// is interrupted.
fn render_frames(args: &RenderArgs, farm: &FarmArgs) -> u8 {
    let animations = match args.animations() {
        Ok(a) => a,
        Err(why) => {
            eprintln!("error: {why}");
            return EXIT_USAGE;
        }
    };
    // Ctrl-C or SIGTERM: stop within a few samples and write every sample
    // done, and the state; a second one ends the process at once.
    let signals = Signals::install();
    let mut written: Vec<(u32, PathBuf)> = Vec::new();
    for animation in animations {
        if signals.stopped() {
            return signals.exit_code();
        }
        let code = render_frame(args, farm, animation, &signals, &mut written);
        if code != EXIT_OK {
            return code;
        }
    }
    EXIT_OK
}

/// Renders one frame: compile, start from nothing or from the saved state,
/// render with checkpoints, write the image (and the state where kept).
/// `written` lists the frames rendered so far and their images.
fn render_frame(
    args: &RenderArgs,
    farm: &FarmArgs,
    animation: Animation,
    signals: &Signals,
    written: &mut Vec<(u32, PathBuf)>,
) -> u8 {
    let verbosity = args.verbosity();
    let t0 = Instant::now();
    let compiled = match compile(args, None, animation, true) {
        Ok(c) => c,
        Err(e) => {
            eprintln!("error: cannot read {}: {e}", args.file.display());
            return EXIT_USAGE;
        }
    };
    report(
        &compiled.diagnostics,
        &compiled.sources,
        Format::Human,
        verbosity,
    );
    let Some(ir) = compiled.ir else {
        return EXIT_SCENE_ERROR;
    };
    let output = output_path(args, compiled.output.as_deref(), animation.frame);
    if let Some((other, _)) = written.iter().find(|(_, p)| *p == output) {
        eprintln!(
            "error: frames {other} and {} would both write {}: name the images with a # pattern (-o frame_####.png)",
            animation.frame,
            output.display()
        );
        return EXIT_USAGE;
    }
    let s = &ir.settings;
    let state_path = farm::state_path(&output, farm.pass);
    if let Err(why) = check_before_rendering(
        args,
        farm,
        (&output, &state_path),
        &compiled.dependencies,
        s,
    ) {
        eprintln!("error: {why}");
        return EXIT_USAGE;
    }
    if let Some(pass) = farm.pass {
        if crate::output::ImageFormat::of(&output) != Some(crate::output::ImageFormat::Exr) {
            eprintln!(
                "error: --pass {pass} writes a part file for `ptsc merge`: name an .exr output (-o part_{}.exr)",
                pass.k
            );
            return EXIT_USAGE;
        }
        if pass.n > s.samples {
            eprintln!(
                "error: --pass {pass}: {} parts of {} samples per pixel would leave some empty; split into at most {} (or raise --spp)",
                pass.n, s.samples, s.samples
            );
            return EXIT_USAGE;
        }
    }
    let now = StateInfo {
        ptsc: env!("CARGO_PKG_VERSION").to_string(),
        scene: (args.file.file_name()).map_or_else(
            || args.file.display().to_string(),
            |n| n.to_string_lossy().into(),
        ),
        fingerprint: compiled.fingerprint.unwrap_or_default(),
        settings: state::sample_settings(s),
        samples: s.samples,
        pass: farm.pass.unwrap_or(Pass::WHOLE),
        exposure: s.exposure,
    };
    let start = match farm::start(&state_path, &now, (s.width, s.height), farm) {
        Ok(start) => start,
        Err(why) => {
            eprintln!("error: {why}");
            return EXIT_USAGE;
        }
    };
    if let (Some(note), true) = (&start.note, verbosity != Verbosity::Quiet) {
        eprintln!("{note}");
    }
    written.push((animation.frame, output.clone()));
    let load_s = t0.elapsed().as_secs_f64();
    if verbosity == Verbosity::Verbose {
        eprintln!(
            "loaded in {load_s:.2} s (read and check {:.2} s, lower {:.2} s): {} primitives, {} lights",
            compiled.check_seconds,
            compiled.lower_seconds,
            ir.prim_object.len(),
            ir.lights.len()
        );
        let need = crate::render::memory::Need {
            textures: ir.texture_bytes(),
            ..memory_need(s)
        };
        let free = crate::render::memory::available(args.memory_limit)
            .map(|(bytes, which)| {
                format!(
                    "; {} free ({which})",
                    crate::render::memory::gigabytes(bytes)
                )
            })
            .unwrap_or_default();
        eprintln!(
            "memory: {} ({}){free}",
            crate::render::memory::gigabytes(need.to_allocate()),
            need.describe()
        );
    }
    let target = now.pass.range(s.samples).len() as u32;
    let samples_in = |film: &Film| film.count.iter().map(|&n| n as u64).sum::<u64>();
    let samples_before = samples_in(&start.film);
    let total = s.width as u64 * s.height as u64 * target as u64;
    let bar = progress_bar(total, verbosity);
    bar.set_position(samples_before);
    let integrator = crate::integrator::make(s.integrator);
    let t1 = Instant::now();
    let exposure = s.exposure;
    let mut write_error = None;
    let mut last_write = Instant::now();
    let mut last_pass = Instant::now();
    // A part file is written whole (image and state) at every write.
    let write_image = |film: &Film| match farm.pass {
        Some(_) => state::write_state(&output, film, &now),
        None => film.write(&output, exposure),
    };
    let mut on_pass = |film: &Film, spp: u32| {
        bar.set_message(format!("{spp} spp"));
        if verbosity == Verbosity::Verbose {
            bar.suspend(|| {
                eprintln!(
                    "pass to {spp} spp in {:.2} s",
                    last_pass.elapsed().as_secs_f64()
                )
            });
            last_pass = Instant::now();
        }
        // A long render replaces its image with the passes so far,
        // a preview that refines. The final image is written once,
        // below; writes in between are spaced (a ZIP-compressed EXR
        // of a 512×512 render takes about 60 ms, time the render loses).
        if spp < target && last_write.elapsed() >= PREVIEW_INTERVAL {
            if let Err(e) = write_image(film) {
                write_error = Some(e);
            }
            last_write = Instant::now();
        }
    };
    // Checkpoints: every `--checkpoint` seconds the render pauses, its
    // state and image are saved, and it goes on from them (the same
    // samples in the same order: the image is the uninterrupted one's).
    let every = (farm.checkpoint > 0.0).then(|| Duration::from_secs_f64(farm.checkpoint));
    let mut keep_state = farm.keep_state || start.had_state;
    let mut film = start.film;
    let mut rays = crate::accel::ray_count::RayCounts::default();
    let mut interrupted = false;
    loop {
        let deadline = every.map(|d| Instant::now() + d);
        let offset = samples_in(&film);
        let rendered = crate::render::render_from(
            &ir,
            integrator.as_ref(),
            film,
            target,
            &signals.interrupt,
            &|done| {
                bar.set_position(offset + done);
                if deadline.is_some_and(|d| Instant::now() >= d) {
                    signals.interrupt.store(true, Ordering::Relaxed);
                }
            },
            &mut on_pass,
        );
        film = rendered.film;
        rays = rays + rendered.rays;
        if rendered.outcome == crate::render::Outcome::Complete {
            break;
        }
        if signals.stopped() {
            interrupted = true;
            break;
        }
        signals.interrupt.store(false, Ordering::Relaxed);
        let saved = write_image(&film).and_then(|()| match farm.pass {
            Some(_) => Ok(()),
            None => state::write_state(&state_path, &film, &now),
        });
        if let Err(e) = saved {
            bar.finish_and_clear();
            eprintln!(
                "error: cannot save the state at {}: {e}",
                state_path.display()
            );
            return EXIT_USAGE;
        }
        keep_state = true;
        if verbosity == Verbosity::Verbose {
            bar.suspend(|| eprintln!("checkpoint: state saved to {}", state_path.display()));
        }
        // A signal during the save: stop here.
        if signals.stopped() {
            interrupted = true;
            break;
        }
    }
    bar.finish_and_clear();
    if let Some(e) = write_error {
        eprintln!("error: cannot write {}: {e}", output.display());
        return EXIT_USAGE;
    }
    let secs = t1.elapsed().as_secs_f64();
    let (least, most, mean) = film.sample_counts();
    // The image, and the state where it is kept: always for a pass (its
    // part file is both) and after an interruption.
    let state_written = match farm.pass {
        Some(_) => Some(&output),
        None if keep_state || (interrupted && most > 0) => Some(&state_path),
        None => None,
    };
    let naming = |path: &Path| {
        let path = path.to_path_buf();
        move |e: std::io::Error| format!("cannot write {}: {e}", path.display())
    };
    let result = match farm.pass {
        Some(_) => state::write_state(&output, &film, &now).map_err(naming(&output)),
        // Both at once: each waits for its disk sync.
        None if most > 0 => {
            let (image, state) = rayon::join(
                || film.write(&output, exposure).map_err(naming(&output)),
                || {
                    state_written.map_or(Ok(()), |path| {
                        state::write_state(path, &film, &now).map_err(naming(path))
                    })
                },
            );
            image.and(state)
        }
        None => Ok(()),
    };
    if let Err(e) = result {
        eprintln!("error: {e}");
        return EXIT_USAGE;
    }
    if verbosity == Verbosity::Verbose {
        let what = if state_written.is_some() && farm.pass.is_none() {
            "image and state"
        } else {
            "image"
        };
        let write_s = t1.elapsed().as_secs_f64() - secs;
        eprintln!("wrote the {what} in {write_s:.3} s");
    }
    if verbosity != Verbosity::Quiet {
        let done = samples_in(&film) - samples_before;
        let paths = done as f64;
        let samples = if interrupted {
            format!("interrupted: {least} spp in every pixel, up to {most}, {mean:.1} on average")
        } else {
            format!("{least} spp")
        };
        let of = match farm.pass {
            Some(p) => format!(" (pass {p} of {} spp)", s.samples),
            None => String::new(),
        };
        let state_note = match (state_written, farm.pass) {
            (Some(path), None) if most > 0 => format!(" (state {})", path.display()),
            _ => String::new(),
        };
        eprintln!(
            "{}: {}×{}, {samples}{of} in {:.2} s ({:.2} M paths/s, {:.2} M rays/s: {:.2} closest-hit and {:.2} shadow rays per path; load {:.2} s{}) → {}{state_note}",
            args.file.display(),
            s.width,
            s.height,
            secs,
            paths / secs / 1e6,
            rays.total() as f64 / secs / 1e6,
            rays.closest as f64 / paths.max(1.0),
            rays.shadow as f64 / paths.max(1.0),
            load_s,
            peak_memory()
                .map(|mb| format!("; peak memory {mb:.0} MB"))
                .unwrap_or_default(),
            if most > 0 || farm.pass.is_some() {
                output.display().to_string()
            } else {
                "no sample, nothing written".to_string()
            }
        );
        if interrupted && most > 0 {
            eprintln!("add --resume to the same command to continue");
        }
    }
    if interrupted {
        signals.exit_code()
    } else {
        EXIT_OK
    }
}

/// Why the render must not start: a path it will write that cannot be
/// written (the image, and the state that checkpoints, interruptions and
/// --keep-state write), an output holding a render's state that the image
/// would replace, or more memory than is free for its film.
fn check_before_rendering(
    args: &RenderArgs,
    farm: &FarmArgs,
    (output, state_path): (&Path, &Path),
    inputs: &[PathBuf],
    settings: &crate::ir::settings::Settings,
) -> Result<(), String> {
    crate::output::check_output(output, inputs)
        .map_err(|why| format!("cannot write {}: {why}", crate::output::shown(output)))?;
    if farm.pass.is_none() {
        farm::refuse_to_replace_state(output, farm.force)?;
        crate::output::check_writable(state_path).map_err(|why| {
            format!(
                "cannot write the render's state at {} (where checkpoints, Ctrl-C and --keep-state save it): {why}",
                crate::output::shown(state_path)
            )
        })?;
    }
    crate::render::memory::check(&memory_need(settings), args.memory_limit)
}

/// What a render of `settings` needs beyond what its scene holds.
fn memory_need(settings: &crate::ir::settings::Settings) -> crate::render::memory::Need {
    crate::render::memory::Need::film((settings.width, settings.height))
}

/// The process's peak resident memory so far in MB (10^6 bytes), where the
/// system tells it (Linux: `VmHWM` in /proc/self/status).
fn peak_memory() -> Option<f64> {
    peak_memory_in(&std::fs::read_to_string("/proc/self/status").ok()?)
}

/// The `VmHWM` of a /proc/PID/status text (KiB) in MB.
fn peak_memory_in(status: &str) -> Option<f64> {
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024.0 / 1e6)
}

fn progress_bar(total: u64, verbosity: Verbosity) -> indicatif::ProgressBar {
    use indicatif::{ProgressBar, ProgressDrawTarget, ProgressState, ProgressStyle};
    let bar = ProgressBar::new(total);
    if super::stderr_is_terminal() && verbosity != Verbosity::Quiet {
        bar.set_style(
            ProgressStyle::with_template("{bar:40} {percent:>3}% {msg} · {rate} · ETA {eta}")
                .unwrap_or_else(|_| ProgressStyle::default_bar())
                .with_key(
                    "rate",
                    |state: &ProgressState, w: &mut dyn std::fmt::Write| {
                        let _ = w.write_str(&samples_per_second(state.per_sec()));
                    },
                ),
        );
    } else {
        bar.set_draw_target(ProgressDrawTarget::hidden());
    }
    bar
}

/// A rate of samples in human units: `1.51 M samples/s`, `820 k samples/s`.
fn samples_per_second(rate: f64) -> String {
    if rate >= 1e6 {
        format!("{:.2} M samples/s", rate / 1e6)
    } else if rate >= 1e3 {
        format!("{:.0} k samples/s", rate / 1e3)
    } else {
        format!("{rate:.0} samples/s")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rates_read_in_human_units() {
        assert_eq!(samples_per_second(1_508_066.182_1), "1.51 M samples/s");
        assert_eq!(samples_per_second(820_400.0), "820 k samples/s");
        assert_eq!(samples_per_second(12.3), "12 samples/s");
    }

    #[test]
    fn peak_memory_reads_vm_hwm_in_kib() {
        let status =
            "Name:\tptsc\nVmPeak:\t  200000 kB\nVmHWM:\t   74500 kB\nVmRSS:\t   70000 kB\n";
        assert_eq!(peak_memory_in(status), Some(74500.0 * 1024.0 / 1e6));
        assert_eq!(peak_memory_in("Name:\tptsc\n"), None);
        // This process has one on Linux.
        if cfg!(target_os = "linux") {
            assert!(peak_memory().is_some_and(|mb| mb > 0.0));
        }
    }
}
