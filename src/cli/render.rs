//! `ptsc render FILE`: check, lower, render with progress (from a saved
//! state where asked, with checkpoints), write atomically.

use super::args::{apply_overrides, flag_warnings};
pub use super::args::{output_path, RenderArgs};
use super::farm::FarmArgs;
use super::signals::Signals;
use super::{check::report, Format, Verbosity, EXIT_OK, EXIT_SCENE_ERROR, EXIT_USAGE};
use crate::check::Animation;
use crate::compile::{compile_bytes, compile_file, Compiled, Options};
use crate::lower::cache::LowerCache;
use crate::render::session::{Mode, Observer, PassDone, Plan, Report, Session, StatePolicy};
use crate::render::state::Pass;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// Compiles the scene at a frame with the command line's overrides (and
/// its fingerprint, for a render's state, when `fingerprint`); `stdin`
/// holds the scene when FILE is `-`.
pub fn compile(
    args: &RenderArgs,
    stdin: Option<&[u8]>,
    cache: Option<&mut LowerCache>,
    animation: Animation,
    fingerprint: bool,
) -> std::io::Result<Compiled> {
    let options = Options {
        adjust: &|s| apply_overrides(s, args),
        cache,
        animation,
        fingerprint,
        output_elsewhere: args.output.is_some(),
        memory_limit: args.memory_limit,
        ..Options::default()
    };
    compile_input(args, stdin, options)
}

/// Compiles FILE, or the scene read from stdin when `stdin` holds it.
fn compile_input(
    args: &RenderArgs,
    stdin: Option<&[u8]>,
    options: Options,
) -> std::io::Result<Compiled> {
    match stdin {
        Some(bytes) => Ok(compile_bytes(
            Path::new(super::STDIN_NAME),
            bytes.to_vec(),
            options,
        )),
        None => compile_file(&args.file, options),
    }
}

/// Whether FILE is `-`: the scene comes from stdin.
pub fn reads_stdin(args: &RenderArgs) -> bool {
    args.file == Path::new("-")
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
    // A scene on stdin is read once, for every frame, before anything else.
    let stdin = match reads_stdin(args).then(super::read_stdin) {
        None => None,
        Some(Ok(bytes)) => Some(bytes),
        Some(Err(why)) => {
            eprintln!("error: {why}");
            return EXIT_USAGE;
        }
    };
    // Every parallel stage (parsing, the BVH build, the render) keeps to
    // `--threads`.
    pool.install(|| render_frames(args, stdin.as_deref(), farm))
}

/// Renders each frame asked for in turn; stops at the first that fails or
/// is interrupted.
fn render_frames(args: &RenderArgs, stdin: Option<&[u8]>, farm: &FarmArgs) -> u8 {
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
    let last = animations.last().copied();
    for animation in animations {
        if signals.stopped() {
            return signals.exit_code();
        }
        let frames = (animation, last.filter(|l| l.frame != animation.frame));
        let code = render_frame(args, stdin, farm, frames, &signals, &mut written);
        if code != EXIT_OK {
            return code;
        }
    }
    EXIT_OK
}

/// Whether the `last` frame would write `first_image` too (`-o`, the
/// scene's `output` or FILE's `.png` without a `#` run): asked once the
/// first frame is compiled, before it renders. The last frame's `output`
/// comes from a check of it (the scene may compute it from the clock; a
/// check with errors is left to that frame's render). Frames between
/// that clash are refused as each comes.
fn last_frame_writes(
    args: &RenderArgs,
    stdin: Option<&[u8]>,
    first_image: &Path,
    last: Animation,
) -> bool {
    let scene_output = if args.output.is_some() {
        None
    } else {
        let options = Options {
            lower: false,
            animation: last,
            output_elsewhere: true,
            ..Options::default()
        };
        match compile_input(args, stdin, options) {
            Ok(c) if !c.diagnostics.has_errors() => c.output,
            _ => return false,
        }
    };
    output_path(args, scene_output.as_deref(), last.frame) == first_image
}

/// Renders one frame: compile, then drive a batch session (from nothing
/// or from the saved state, with checkpoints; the image and the state
/// where kept). `written` lists the frames rendered so far and their
/// images; `last`, the animation's last frame when it is another, is
/// checked against the first frame's image before anything renders.
fn render_frame(
    args: &RenderArgs,
    stdin: Option<&[u8]>,
    farm: &FarmArgs,
    (animation, last): (Animation, Option<Animation>),
    signals: &Signals,
    written: &mut Vec<(u32, PathBuf)>,
) -> u8 {
    let verbosity = args.verbosity();
    let t0 = Instant::now();
    let compiled = match compile(args, stdin, None, animation, true) {
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
    if verbosity != Verbosity::Quiet {
        for warning in flag_warnings(args, &ir) {
            eprintln!("{warning}");
        }
    }
    if stdin.is_some() && args.output.is_none() && compiled.output.is_none() {
        eprintln!(
            "error: a scene read from stdin has no name to give its image: add -o FILE (or `output \"FILE\"` to its render block)"
        );
        return EXIT_USAGE;
    }
    let output = output_path(args, compiled.output.as_deref(), animation.frame);
    let clash = match last {
        Some(last) if written.is_empty() && last_frame_writes(args, stdin, &output, last) => {
            Some((animation.frame, last.frame))
        }
        _ => (written.iter().find(|(_, p)| *p == output)).map(|(o, _)| (*o, animation.frame)),
    };
    if let Some((one, other)) = clash {
        eprintln!(
            "error: frames {one} and {other} would both write {}: name the images with a # pattern (-o frame_####.png)",
            output.display()
        );
        return EXIT_USAGE;
    }
    let plan = batch_plan(
        args,
        farm,
        &output,
        compiled.dependencies,
        compiled.fingerprint,
    );
    let session = match plan.check().and_then(|checked| Session::new(ir, checked)) {
        Ok(session) => session,
        Err(why) => {
            eprintln!("error: {why}");
            return EXIT_USAGE;
        }
    };
    if let (Some(note), true) = (session.note(), verbosity != Verbosity::Quiet) {
        eprintln!("{note}");
    }
    written.push((animation.frame, output.clone()));
    let load_s = t0.elapsed().as_secs_f64();
    if verbosity == Verbosity::Verbose {
        let times = (compiled.check_seconds, compiled.lower_seconds);
        print_loaded(&session, load_s, times, args.memory_limit);
    }
    // A time budget's bar runs with the time; else with the samples.
    let budget = session.scene().settings.time;
    let total = budget.map_or(session.samples_total(), |t| (t * 1000.0) as u64);
    let bar = progress_bar(total, verbosity);
    if budget.is_none() {
        bar.set_position(session.samples_done());
    }
    let started = std::time::Instant::now();
    let observer = Bar {
        bar,
        verbosity,
        budget: budget.map(|_| started),
    };
    let settings = session.scene().settings.clone();
    let report = match session.run(&observer, &signals.cancel) {
        Ok(report) => report,
        Err(why) => {
            eprintln!("error: {why}");
            return EXIT_USAGE;
        }
    };
    let summary = Summary {
        file: match stdin {
            Some(_) => Path::new(super::STDIN_NAME),
            None => &args.file,
        },
        output: &output,
        settings: &settings,
        pass: farm.pass,
        load_s,
    };
    summary.print(&report, verbosity);
    match report.outcome {
        crate::render::Outcome::Cancelled => signals.exit_code(),
        crate::render::Outcome::Complete => EXIT_OK,
    }
}

/// The batch session a frame asks for: its image, what the scene read,
/// and the command line's state options.
fn batch_plan(
    args: &RenderArgs,
    farm: &FarmArgs,
    output: &Path,
    inputs: Vec<PathBuf>,
    fingerprint: Option<u64>,
) -> Plan {
    Plan {
        output: output.to_path_buf(),
        inputs,
        memory_limit: args.memory_limit,
        aovs: args.aov.clone().unwrap_or_default().0,
        denoise: args.denoise,
        tev: args.tev.clone(),
        mode: Mode::Batch(StatePolicy {
            pass: farm.pass,
            resume: farm.resume,
            restart: farm.restart,
            keep_state: farm.keep_state,
            force: farm.force,
            checkpoint: (farm.checkpoint > 0.0).then(|| Duration::from_secs_f64(farm.checkpoint)),
            scene: (args.file.file_name()).map_or_else(
                || args.file.display().to_string(),
                |n| n.to_string_lossy().into(),
            ),
            fingerprint: fingerprint.unwrap_or_default(),
        }),
    }
}

/// `--verbose`'s account of the loaded scene: load times, primitives,
/// lights, and the memory the render takes.
fn print_loaded(
    session: &Session,
    load_s: f64,
    (check_s, lower_s): (f64, f64),
    limit: Option<u64>,
) {
    use crate::render::memory;
    let ir = session.scene();
    eprintln!(
        "loaded in {load_s:.2} s (read and check {check_s:.2} s, lower {lower_s:.2} s): {} primitives, {} lights",
        ir.prim_object.len(),
        ir.lights.len()
    );
    // What the session checked (half images and output variables
    // included), with the scene's textures.
    let film = memory::Need::film((ir.settings.width, ir.settings.height));
    let need = memory::Need {
        textures: ir.texture_bytes(),
        ..session.memory_need().unwrap_or(film)
    };
    let free = memory::available(limit)
        .map(|(bytes, which)| format!("; {} free ({which})", memory::gigabytes(bytes)))
        .unwrap_or_default();
    eprintln!(
        "memory: {} ({}){free}",
        memory::gigabytes(need.to_allocate()),
        need.describe()
    );
}

/// The progress bar, and the lines `--verbose` adds, drawn from a
/// session's events.
struct Bar {
    bar: indicatif::ProgressBar,
    verbosity: Verbosity,
    /// When the render started, for a time budget's bar (in milliseconds).
    budget: Option<std::time::Instant>,
}

impl Observer for Bar {
    fn progress(&self, done: u64) {
        match self.budget {
            Some(start) => self.bar.set_position(start.elapsed().as_millis() as u64),
            None => self.bar.set_position(done),
        }
    }

    fn pass(&self, pass: &PassDone) {
        let converged = pass
            .converged
            .map(|share| format!(", {:.0} % converged", share * 100.0));
        self.bar.set_message(format!(
            "{} spp{}",
            pass.spp,
            converged.as_deref().unwrap_or("")
        ));
        // Adaptive sampling shortens the road as pixels stop.
        if pass.converged.is_some() && self.budget.is_none() {
            self.bar.set_length(self.bar.position() + pass.samples_left);
        }
        if self.verbosity == Verbosity::Verbose {
            self.bar.suspend(|| {
                eprintln!(
                    "pass to {} spp in {:.2} s{}",
                    pass.spp,
                    pass.elapsed.as_secs_f64(),
                    converged.as_deref().unwrap_or("")
                )
            });
        }
    }

    fn checkpoint(&self, state: &Path) {
        if self.verbosity == Verbosity::Verbose {
            self.bar
                .suspend(|| eprintln!("checkpoint: state saved to {}", state.display()));
        }
    }

    fn rendered(&self) {
        self.bar.finish_and_clear();
    }

    fn note(&self, text: &str) {
        if self.verbosity != Verbosity::Quiet {
            self.bar.suspend(|| eprintln!("{text}"));
        }
    }
}

/// What the summary line of a frame names beside the session's report.
struct Summary<'a> {
    file: &'a Path,
    output: &'a Path,
    settings: &'a crate::ir::settings::Settings,
    pass: Option<Pass>,
    load_s: f64,
}

impl Summary<'_> {
    /// What `verbosity` asks to be said of the frame at the end: the time
    /// of the writes (`--verbose`), the summary line and, after an
    /// interruption, how to go on.
    fn print(&self, report: &Report, verbosity: Verbosity) {
        if verbosity == Verbosity::Verbose {
            let what = if report.state.is_some() && self.pass.is_none() {
                "image and state"
            } else {
                "image"
            };
            let write_s = report.write_time.as_secs_f64();
            eprintln!("wrote the {what} in {write_s:.3} s");
        }
        if verbosity != Verbosity::Quiet {
            self.print_line(report);
        }
    }

    /// The summary line (and, after an interruption, how to go on).
    fn print_line(&self, report: &Report) {
        let s = self.settings;
        let secs = report.render_time.as_secs_f64();
        let (least, most, mean) = report.film.sample_counts();
        let interrupted = report.outcome == crate::render::Outcome::Cancelled;
        let paths = report.samples as f64;
        let rays = report.rays;
        // (A uniform render may keep half images, for the variance AOV.)
        let converged = report.film.stopped_share().filter(|_| s.adaptive.is_some());
        let samples = match (interrupted, converged) {
            (true, _) => format!(
                "interrupted: {least} spp in every pixel, up to {most}, {mean:.1} on average"
            ),
            (false, Some(share)) => format!(
                "adaptive: {least} to {most} spp, {mean:.1} on average, {:.1} % of pixels converged",
                share * 100.0
            ),
            (false, None) => format!("{least} spp"),
        };
        let of = match self.pass {
            Some(p) => format!(" (pass {p} of {} spp)", s.samples),
            None => String::new(),
        };
        let state_note = match (&report.state, self.pass) {
            (Some(path), None) if most > 0 => format!(" (state {})", path.display()),
            _ => String::new(),
        };
        eprintln!(
            "{}: {}×{}, {samples}{of} in {:.2} s ({:.2} M paths/s, {:.2} M rays/s: {:.2} closest-hit and {:.2} shadow rays per path; load {:.2} s{}) → {}{state_note}",
            self.file.display(),
            s.width,
            s.height,
            secs,
            paths / secs / 1e6,
            rays.total() as f64 / secs / 1e6,
            rays.closest as f64 / paths.max(1.0),
            rays.shadow as f64 / paths.max(1.0),
            self.load_s,
            peak_memory()
                .map(|mb| format!("; peak memory {mb:.0} MB"))
                .unwrap_or_default(),
            if report.image_written {
                self.output.display().to_string()
            } else {
                "no sample, nothing written".to_string()
            }
        );
        if interrupted && most > 0 {
            eprintln!("add --resume to the same command to continue");
        } else if let (Some(t), Some(_), None) = (s.time, &report.state, self.pass) {
            // Only a budget that ran out was spent: a render that reached
            // --spp first is told how to add samples past them.
            match report.budget_spent {
                true => eprintln!(
                    "time budget of {t} s spent: add --resume to the same command to add samples"
                ),
                false => eprintln!(
                    "reached the {} spp asked within the time budget of {t} s: add --resume and a higher --spp to add samples",
                    s.samples
                ),
            }
        }
    }
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
