//! `ptsc render FILE`: check, lower, render with progress, write atomically.

use super::signals::Signals;
use super::{check::report, Format, Verbosity, EXIT_OK, EXIT_SCENE_ERROR, EXIT_USAGE};
use crate::compile::{compile_file, Compiled, Options};
use crate::ir::settings::{IntegratorKind, LightSelection, Settings};
use crate::lower::cache::LowerCache;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// Least time between two preview writes of a render's image.
const PREVIEW_INTERVAL: Duration = Duration::from_secs(5);

/// Command-line overrides of the scene's `render` block.
#[derive(Debug, Clone, clap::Args)]
pub struct RenderArgs {
    /// The scene file.
    pub file: PathBuf,
    /// Output image (.png, .exr or .pfm); default: the scene's `output`, else FILE with .png.
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// Samples per pixel (1 to 1000000, as the scene's `samples`).
    #[arg(long, value_parser = parse_spp)]
    pub spp: Option<u32>,
    /// Worker threads (default: all cores).
    #[arg(long, value_parser = parse_threads)]
    pub threads: Option<usize>,
    /// Random seed (0 to 4294967295, as the scene's `seed`).
    #[arg(long, value_parser = parse_seed)]
    pub seed: Option<u64>,
    /// Image size as WxH, e.g. 640x480.
    #[arg(long, value_parser = parse_resolution)]
    pub resolution: Option<(u32, u32)>,
    /// Integrator: path, whitted, hybrid, normals, albedo, depth or uv.
    #[arg(long, value_parser = parse_integrator)]
    pub integrator: Option<IntegratorKind>,
    /// How shadow rays choose their light: auto, bvh, exhaustive, power or uniform.
    #[arg(long, value_parser = parse_light_selection)]
    pub light_selection: Option<LightSelection>,
    /// Only errors: no warnings, progress or figures.
    #[arg(short, long, conflicts_with = "verbose")]
    pub quiet: bool,
    /// Also the time of each stage and of each pass, and the scene's size.
    #[arg(short, long)]
    pub verbose: bool,
}

impl RenderArgs {
    /// How much to print.
    pub fn verbosity(&self) -> Verbosity {
        Verbosity::from_flags(self.quiet, self.verbose)
    }
}

/// The most worker threads `--threads` starts.
pub const MAX_THREADS: usize = 1024;

fn parse_spp(s: &str) -> Result<u32, String> {
    crate::check::SAMPLES.parse(s).map(|n| n as u32)
}

fn parse_seed(s: &str) -> Result<u64, String> {
    crate::check::SEED.parse(s)
}

fn parse_threads(s: &str) -> Result<usize, String> {
    let setting = crate::check::WholeSetting {
        name: "threads",
        min: 1,
        max: MAX_THREADS as u64,
    };
    setting.parse(s).map(|n| n as usize)
}

fn parse_resolution(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or("expected WxH, e.g. 640x480")?;
    let w: u32 = w
        .trim()
        .parse()
        .map_err(|_| format!("`{w}` is not a width"))?;
    let h: u32 = h
        .trim()
        .parse()
        .map_err(|_| format!("`{h}` is not a height"))?;
    use crate::check::{MAX_PIXELS, MAX_SIDE};
    let side = 1.0..=MAX_SIDE;
    if !side.contains(&(w as f64))
        || !side.contains(&(h as f64))
        || w as f64 * h as f64 > MAX_PIXELS
    {
        return Err("each side must be 1..=16384 and the image at most 8192×8192 pixels".into());
    }
    Ok((w, h))
}

fn parse_integrator(s: &str) -> Result<IntegratorKind, String> {
    IntegratorKind::from_name(s).ok_or_else(|| expected_one_of(&IntegratorKind::WORDS))
}

fn parse_light_selection(s: &str) -> Result<LightSelection, String> {
    LightSelection::from_name(s).ok_or_else(|| expected_one_of(&LightSelection::WORDS))
}

/// "expected a, b or c".
fn expected_one_of(words: &[&str]) -> String {
    match words.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("expected {} or {last}", rest.join(", ")),
        _ => format!("expected {}", words.join("")),
    }
}

/// Applies the command line's overrides to the scene's settings.
pub fn apply_overrides(settings: &mut Settings, args: &RenderArgs) {
    if let Some(n) = args.spp {
        settings.samples = n;
    }
    if let Some(s) = args.seed {
        settings.seed = s;
    }
    if let Some((w, h)) = args.resolution {
        settings.width = w;
        settings.height = h;
    }
    if let Some(k) = args.integrator {
        settings.integrator = k;
    }
    if let Some(rule) = args.light_selection {
        settings.light_selection = rule;
    }
}

/// Compiles the scene with the command line's overrides.
pub fn compile(args: &RenderArgs, cache: Option<&mut LowerCache>) -> std::io::Result<Compiled> {
    compile_file(
        &args.file,
        Options {
            adjust: &|s| apply_overrides(s, args),
            cache,
            ..Options::default()
        },
    )
}

/// The output image: `-o`, else the scene's `output`, else FILE with `.png`.
pub fn output_path(args: &RenderArgs, scene_output: Option<&Path>) -> PathBuf {
    args.output
        .clone()
        .or_else(|| scene_output.map(Path::to_path_buf))
        .unwrap_or_else(|| args.file.with_extension("png"))
}

/// Why the image cannot be written at `output`, found before rendering: an
/// unknown format, a folder, a missing or read-only folder, or a file the
/// scene reads (the scene itself, an include, a mesh), which the image would
/// replace.
pub fn check_output(output: &Path, dependencies: &[PathBuf]) -> Result<(), String> {
    let same = |a: &Path, b: &Path| match (std::fs::canonicalize(a), std::fs::canonicalize(b)) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    };
    let inputs = dependencies.iter();
    for input in inputs {
        if same(output, input) {
            return Err(format!(
                "{} is a file of the scene; the image would replace it (name another with -o)",
                input.display()
            ));
        }
    }
    crate::output::check_writable(output)
}

/// Runs `render`; returns the exit code.
pub fn run(args: &RenderArgs) -> u8 {
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
    pool.install(|| run_on_pool(args))
}

fn run_on_pool(args: &RenderArgs) -> u8 {
    let verbosity = args.verbosity();
    let t0 = Instant::now();
    let compiled = match compile(args, None) {
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
    let output = output_path(args, compiled.output.as_deref());
    if let Err(why) = check_output(&output, &compiled.dependencies) {
        eprintln!("error: cannot write {}: {why}", output.display());
        return EXIT_USAGE;
    }
    let load_s = t0.elapsed().as_secs_f64();
    if verbosity == Verbosity::Verbose {
        eprintln!(
            "loaded in {load_s:.2} s (read and check {:.2} s, lower {:.2} s): {} primitives, {} lights",
            compiled.check_seconds,
            compiled.lower_seconds,
            ir.prim_object.len(),
            ir.lights.len()
        );
    }
    // Ctrl-C or SIGTERM: stop within a few samples and write every sample
    // done; a second one ends the process at once.
    let signals = Signals::install();
    let s = &ir.settings;
    let total = s.width as u64 * s.height as u64 * s.samples as u64;
    let bar = progress_bar(total, verbosity);
    let integrator = crate::integrator::make(s.integrator);
    let t1 = Instant::now();
    let exposure = s.exposure;
    let mut write_error = None;
    let mut last_write = Instant::now();
    let mut last_pass = Instant::now();
    let crate::render::Rendered {
        film,
        outcome,
        rays,
    } = crate::render::render(
        &ir,
        integrator.as_ref(),
        &signals.stop,
        &|done| bar.set_position(done),
        &mut |film, spp| {
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
            if spp < s.samples && last_write.elapsed() >= PREVIEW_INTERVAL {
                if let Err(e) = film.write(&output, exposure) {
                    write_error = Some(e);
                }
                last_write = Instant::now();
            }
        },
    );
    bar.finish_and_clear();
    if let Some(e) = write_error {
        eprintln!("error: cannot write {}: {e}", output.display());
        return EXIT_USAGE;
    }
    let secs = t1.elapsed().as_secs_f64();
    let (least, most, mean) = film.sample_counts();
    if most > 0 {
        if let Err(e) = film.write(&output, exposure) {
            eprintln!("error: cannot write {}: {e}", output.display());
            return EXIT_USAGE;
        }
    }
    let interrupted = outcome == crate::render::Outcome::Cancelled;
    if verbosity != Verbosity::Quiet {
        let paths = s.width as f64 * s.height as f64 * mean;
        let samples = if interrupted {
            format!("interrupted: {least} spp in every pixel, up to {most}, {mean:.1} on average")
        } else {
            format!("{least} spp")
        };
        eprintln!(
            "{}: {}×{}, {samples} in {:.2} s ({:.2} M paths/s, {:.2} M rays/s: {:.2} closest-hit and {:.2} shadow rays per path; load {:.2} s{}) → {}",
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
            if most > 0 {
                output.display().to_string()
            } else {
                "no sample, nothing written".to_string()
            }
        );
    }
    if interrupted || signals.stopped() {
        signals.exit_code()
    } else {
        EXIT_OK
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
