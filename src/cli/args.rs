//! `ptsc render`'s and `ptsc watch`'s arguments: the overrides of the
//! scene's `render` block, the frames of an animation, and the output path
//! they give.

use super::Verbosity;
use crate::check::Animation;
use crate::ir::settings::{IntegratorKind, LightSelection, SamplerKind, Settings};
use std::path::{Path, PathBuf};

/// Command-line overrides of the scene's `render` block.
#[derive(Debug, Clone, clap::Args)]
pub struct RenderArgs {
    /// The scene file (`render -` reads it from stdin: the image then needs -o or the scene's `output`).
    pub file: PathBuf,
    /// Output image (.png, .exr or .pfm); default: the scene's `output`, else FILE with .png.
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// Samples per pixel (1 to 1000000, as the scene's `samples`; `--samples` too).
    #[arg(long, alias = "samples", value_parser = parse_spp, allow_negative_numbers = true)]
    pub spp: Option<u32>,
    /// A time budget, e.g. 90s, 5m or 1.5h: the render stops when it is
    /// spent (or at --spp, if given) and saves its state for --resume.
    #[arg(long, value_name = "T", value_parser = parse_time, allow_negative_numbers = true)]
    pub time: Option<f64>,
    /// Adaptive sampling: a pixel stops once its noise is below T, e.g.
    /// 0.01 (as the scene's `noise_threshold`; 0 < T ≤ 1); `off`: every
    /// pixel takes the samples asked.
    #[arg(long, value_name = "T", value_parser = parse_noise, allow_negative_numbers = true)]
    pub noise: Option<Noise>,
    /// With --noise: samples every pixel takes before it may stop (2 to
    /// 1000000, as the scene's `min_samples`; default 16).
    #[arg(long, value_name = "N", value_parser = parse_min_samples, allow_negative_numbers = true, requires = "noise")]
    pub min_samples: Option<u32>,
    /// Output variables written as channels of the EXR output, comma
    /// separated: albedo, normal, depth, position, object, samples,
    /// variance, or all.
    #[arg(long, value_name = "LIST", value_parser = parse_aovs)]
    pub aov: Option<AovList>,
    /// Denoise the final image with Intel Open Image Denoise, using the
    /// albedo and normal of the first surfaces (a build with the `denoise`
    /// feature: scripts/setup-oidn.sh).
    #[arg(long)]
    pub denoise: bool,
    /// Show every pass in the tev HDR viewer, listening at HOST:PORT
    /// (default 127.0.0.1:14158; start tev first).
    #[arg(long, value_name = "HOST:PORT", num_args = 0..=1, default_missing_value = crate::output::tev::DEFAULT_ADDRESS)]
    pub tev: Option<String>,
    /// Worker threads (default: all cores).
    #[arg(long, value_parser = parse_threads, allow_negative_numbers = true)]
    pub threads: Option<usize>,
    /// Random seed (0 to 4294967295, as the scene's `seed`).
    #[arg(long, value_parser = parse_seed, allow_negative_numbers = true)]
    pub seed: Option<u64>,
    /// Image size as WxH, e.g. 640x480.
    #[arg(long, value_parser = parse_resolution)]
    pub resolution: Option<(u32, u32)>,
    /// Sampler; the list and the default come from the sampler table and
    /// the default settings.
    #[arg(long, value_parser = parse_sampler, help = one_of("Sampler", &SamplerKind::WORDS, Settings::default().sampler.name()))]
    pub sampler: Option<SamplerKind>,
    /// Integrator; the list and the default come from the integrator table
    /// and the default settings.
    #[arg(long, value_parser = parse_integrator, help = one_of("Integrator", &IntegratorKind::WORDS, Settings::default().integrator.name()))]
    pub integrator: Option<IntegratorKind>,
    /// Clamp indirect light: each contribution's largest RGB component at
    /// most X (as the scene's `clamp`; biased, fights fireflies).
    #[arg(long, value_name = "X", value_parser = parse_clamp, allow_negative_numbers = true)]
    pub clamp: Option<f32>,
    /// How shadow rays choose their light; the list and the default come
    /// from its table and the default settings.
    #[arg(long, value_parser = parse_light_selection, help = one_of("How shadow rays choose their light", &LightSelection::WORDS, Settings::default().light_selection.name()))]
    pub light_selection: Option<LightSelection>,
    /// Render only this frame of an animation (`frame` in the scene; with
    /// --frames, `clock` runs from 0 at its first frame to 1 at its last).
    #[arg(long, value_name = "F", value_parser = parse_frame, allow_negative_numbers = true)]
    pub frame: Option<u32>,
    /// The animation's frames, e.g. 1..240 (both ends included, as
    /// POV-Ray's +KFI/+KFF): each is rendered in turn (or
    /// only --frame's); name the images with a # pattern (frame_####.png).
    #[arg(long, value_name = "A..B", value_parser = parse_frames)]
    pub frames: Option<(u32, u32)>,
    /// The most memory the render may take, e.g. 16G or 512MiB (default:
    /// what the machine, its control group and `ulimit -v` leave free).
    #[arg(long, value_name = "SIZE", value_parser = crate::render::memory::parse_size, allow_negative_numbers = true)]
    pub memory_limit: Option<u64>,
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

    /// The frames to render, each with its `frame` and `clock`: --frame's
    /// alone, else every frame of --frames, else frame 0 at clock 0.
    pub fn animations(&self) -> Result<Vec<Animation>, String> {
        let (a, b) = self.frames.unwrap_or_else(|| {
            let f = self.frame.unwrap_or(0);
            (f, f)
        });
        let span = (b - a) as f64;
        let at = |frame: u32| Animation {
            frame,
            clock: if b > a {
                (frame - a) as f64 / span
            } else {
                0.0
            },
            clock_delta: if b > a { 1.0 / span } else { 0.0 },
        };
        match self.frame {
            Some(f) if !(a..=b).contains(&f) => {
                Err(format!("--frame {f} is not one of --frames {a}..{b}"))
            }
            Some(f) => Ok(vec![at(f)]),
            None => Ok((a..=b).map(at).collect()),
        }
    }
}

/// The most frames one `--frames` range holds.
pub const MAX_FRAMES: u32 = 1_000_000;

fn parse_frame(s: &str) -> Result<u32, String> {
    let setting = crate::check::WholeSetting {
        name: "frame",
        min: 0,
        max: 99_999_999,
    };
    setting.parse(s).map(|n| n as u32)
}

fn parse_frames(s: &str) -> Result<(u32, u32), String> {
    let (a, b) = s.split_once("..").ok_or("expected A..B, e.g. 1..240")?;
    let (a, b) = (parse_frame(a.trim())?, parse_frame(b.trim())?);
    if a > b {
        return Err(format!("the first frame ({a}) comes after the last ({b})"));
    }
    if b - a >= MAX_FRAMES {
        return Err(format!("at most {MAX_FRAMES} frames at once"));
    }
    Ok((a, b))
}

/// The most worker threads `--threads` starts.
pub const MAX_THREADS: usize = 1024;

fn parse_spp(s: &str) -> Result<u32, String> {
    crate::check::SAMPLES.parse(s).map(|n| n as u32)
}

fn parse_min_samples(s: &str) -> Result<u32, String> {
    crate::check::MIN_SAMPLES.parse(s).map(|n| n as u32)
}

/// `--noise`: a threshold, or adaptive sampling off.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Noise {
    /// Adaptive sampling with this threshold.
    Threshold(f32),
    /// Uniform sampling, whatever the scene says.
    Off,
}

fn parse_noise(s: &str) -> Result<Noise, String> {
    match s.trim() {
        "off" => Ok(Noise::Off),
        t => match t.parse::<f64>() {
            // The scene's range: greater than 0, at most 1.
            Ok(x) if x > 0.0 && x <= crate::check::MAX_NOISE => Ok(Noise::Threshold(x as f32)),
            _ => Err(
                "expected a noise threshold greater than 0 and at most 1, e.g. 0.01, or `off`"
                    .into(),
            ),
        },
    }
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

fn parse_clamp(s: &str) -> Result<f32, String> {
    match s.trim().parse::<f64>() {
        // The scene's range: greater than 0 (and within f32, the renderer's).
        Ok(x) if x > 0.0 && x <= f32::MAX as f64 => Ok(x as f32),
        _ => Err("expected a number greater than 0, e.g. 10".into()),
    }
}

fn parse_integrator(s: &str) -> Result<IntegratorKind, String> {
    IntegratorKind::from_name(s).ok_or_else(|| expected_one_of(&IntegratorKind::WORDS))
}

/// The AOVs `--aov` names (one argument: clap would take a `Vec` for
/// several).
#[derive(Debug, Clone, Default)]
pub struct AovList(pub Vec<crate::render::aov::Aov>);

/// A list of AOVs, or `all`.
fn parse_aovs(s: &str) -> Result<AovList, String> {
    use crate::render::aov::Aov;
    if s.trim() == "all" {
        return Ok(AovList(Aov::NAMES.iter().map(|(_, a)| *a).collect()));
    }
    let mut list = Vec::new();
    for word in s.split(',').map(str::trim) {
        let aov = Aov::from_name(word).ok_or_else(|| {
            format!(
                "unknown AOV `{word}`: use {}, or all",
                Aov::WORDS.join(", ")
            )
        })?;
        if !list.contains(&aov) {
            list.push(aov);
        }
    }
    Ok(AovList(list))
}

/// A duration: a number of seconds, or with a unit `s`, `m` or `h`.
fn parse_time(s: &str) -> Result<f64, String> {
    let t = s.trim();
    let (number, unit) = match t.find(|c: char| c.is_ascii_alphabetic()) {
        Some(i) => t.split_at(i),
        None => (t, "s"),
    };
    let scale = match unit {
        "s" | "sec" => 1.0,
        "m" | "min" => 60.0,
        "h" => 3600.0,
        _ => {
            return Err(format!(
                "unknown unit `{unit}`: use s, m or h, e.g. 90s, 5m, 1.5h"
            ))
        }
    };
    match number.trim().parse::<f64>() {
        Ok(x) if x > 0.0 && x * scale <= crate::ir::settings::MAX_TIME => Ok(x * scale),
        _ => Err("expected a time greater than 0 and at most a year, e.g. 90s, 5m or 1.5h".into()),
    }
}

fn parse_sampler(s: &str) -> Result<SamplerKind, String> {
    SamplerKind::from_name(s).ok_or_else(|| expected_one_of(&SamplerKind::WORDS))
}

fn parse_light_selection(s: &str) -> Result<LightSelection, String> {
    LightSelection::from_name(s).ok_or_else(|| expected_one_of(&LightSelection::WORDS))
}

/// A flag's help, "WHAT: a, b or c (default: the scene's, else b)", from its vocabulary's
/// table and the default settings, so that a new word or another default
/// shows in `--help` without an edit here.
fn one_of(what: &str, words: &[&str], default: &str) -> String {
    format!(
        "{what}: {} (default: the scene's, else {default})",
        listed(words)
    )
}

/// "expected a, b or c".
fn expected_one_of(words: &[&str]) -> String {
    format!("expected {}", listed(words))
}

/// "a, b or c".
fn listed(words: &[&str]) -> String {
    match words.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} or {last}", rest.join(", ")),
        _ => words.join(""),
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
    if let Some(t) = args.time {
        settings.time = Some(t);
        if args.spp.is_none() {
            settings.samples = crate::check::SAMPLES.max as u32;
        }
    }
    match args.noise {
        Some(Noise::Threshold(threshold)) => {
            let min_samples = (args.min_samples)
                .or(settings.adaptive.map(|a| a.min_samples))
                .unwrap_or(crate::ir::settings::DEFAULT_MIN_SAMPLES);
            settings.adaptive = Some(crate::ir::settings::Adaptive {
                threshold,
                min_samples,
            });
        }
        Some(Noise::Off) => settings.adaptive = None,
        None => {}
    }
    if let Some(k) = args.sampler {
        settings.sampler = k;
    }
    if let Some(k) = args.integrator {
        settings.integrator = k;
    }
    if let Some(x) = args.clamp {
        settings.clamp = Some(x);
    }
    if let Some(rule) = args.light_selection {
        settings.light_selection = rule;
    }
}

/// Warnings about flags that the scene's check could not see: `check`
/// warns of the same settings made in the scene, at their spans.
pub fn flag_warnings(args: &RenderArgs, scene: &crate::ir::Scene) -> Vec<String> {
    let integrator = scene.settings.integrator;
    let renders_with = integrator.renders_with(scene.volumetric);
    let mut warnings = Vec::new();
    if renders_with != integrator && args.integrator.is_some() {
        warnings.push(format!(
            "warning: --integrator {}: {}",
            integrator.name(),
            IntegratorKind::MEDIA_LEFT_TO_PATH
        ));
    }
    if renders_with.is_bidirectional() && args.clamp.is_some() {
        warnings.push(format!(
            "warning: --clamp has no effect with the {} integrator",
            integrator.name()
        ));
    }
    // Every pixel takes `min_samples` before it may stop: with no more
    // samples than that, none stops early.
    let settings = &scene.settings;
    if let (Some(adaptive), Some(_)) = (settings.adaptive, args.noise) {
        if settings.samples <= adaptive.min_samples && settings.time.is_none() {
            // A lower --min-samples helps only where one below the samples
            // is allowed: not at the least there is.
            let least = crate::check::MIN_SAMPLES.min as u32;
            let advice = match settings.samples > least {
                true => "ask for more samples, or a lower --min-samples",
                false => "ask for more samples",
            };
            warnings.push(format!(
                "warning: --noise has no effect at {} spp: a pixel may stop only after {} samples (--min-samples); {advice}",
                settings.samples, adaptive.min_samples
            ));
        }
    }
    warnings
}

/// The output image: `-o`, else the scene's `output`, else FILE with `.png`;
/// each run of `#` in it becomes the frame's number, zero-padded to the
/// run's length (`frame_####.png` → `frame_0012.png`).
pub fn output_path(args: &RenderArgs, scene_output: Option<&Path>, frame: u32) -> PathBuf {
    let path = args
        .output
        .clone()
        .or_else(|| scene_output.map(Path::to_path_buf))
        .unwrap_or_else(|| args.file.with_extension("png"));
    crate::output::frame_path(&path, frame)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_clock_runs_from_0_at_the_first_frame_to_1_at_the_last() {
        use clap::Parser;
        #[derive(Parser)]
        struct Cli {
            #[command(flatten)]
            args: RenderArgs,
        }
        let frames = |argv: &[&str]| {
            let cli = Cli::try_parse_from([&["ptsc", "s.pts"], argv].concat()).unwrap();
            cli.args.animations()
        };
        let all = frames(&["--frames", "10..14"]).unwrap();
        let clocks: Vec<f64> = all.iter().map(|a| a.clock).collect();
        assert_eq!(clocks, vec![0.0, 0.25, 0.5, 0.75, 1.0]);
        assert_eq!(all[4].frame, 14);
        let one = frames(&["--frames", "10..14", "--frame", "12"]).unwrap();
        assert_eq!(
            one,
            vec![Animation {
                frame: 12,
                clock: 0.5,
                clock_delta: 0.25,
            }]
        );
        let still = frames(&["--frame", "5"]).unwrap();
        assert_eq!(
            still,
            vec![Animation {
                frame: 5,
                clock: 0.0,
                clock_delta: 0.0,
            }]
        );
        assert_eq!(frames(&[]).unwrap(), vec![Animation::default()]);
        assert!(frames(&["--frames", "1..3", "--frame", "4"]).is_err());
        assert!(Cli::try_parse_from(["ptsc", "s.pts", "--frames", "5..2"]).is_err());
    }
}
