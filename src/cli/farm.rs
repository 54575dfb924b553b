//! Long renders and render farms on the command line: the options of
//! `ptsc render` that say what becomes of the render's state, `--pass
//! K/N`, and `ptsc merge`. The policy is the library's
//! ([`crate::render::session`], [`crate::render::merge`]), the file format
//! [`crate::render::state`]'s; the schedulers' scripts are in `deploy/`;
//! docs/farm.md tells the story.

use crate::render::merge::Merged;
use crate::render::state::Pass;
use std::path::{Path, PathBuf};

/// Default seconds between two saves of a long render's state.
pub const CHECKPOINT_SECONDS: f64 = 300.0;

/// `ptsc render`'s options for long renders and farms.
#[derive(Debug, Clone, clap::Args)]
pub struct FarmArgs {
    /// Render only the K-th of N disjoint parts of every pixel's samples
    /// (1 ≤ K ≤ N ≤ spp) into an EXR part file; `ptsc merge` adds the parts up.
    #[arg(long, value_name = "K/N", value_parser = Pass::parse)]
    pub pass: Option<Pass>,
    /// Continue from the saved state (after Ctrl-C, a kill, or to add
    /// samples with a higher --spp); starts from the first sample if there is none.
    #[arg(long, conflicts_with = "restart")]
    pub resume: bool,
    /// Start over, replacing a saved state.
    #[arg(long)]
    pub restart: bool,
    /// Keep the state of a render that ends before its first checkpoint,
    /// so that samples can be added later.
    #[arg(long)]
    pub keep_state: bool,
    /// Replace an output that holds a render's state (a part file, a saved
    /// state) with this render's image: its samples are lost.
    #[arg(long)]
    pub force: bool,
    /// Seconds between two saves of the state of a long render (0: never).
    #[arg(long, value_name = "SECONDS", default_value_t = CHECKPOINT_SECONDS, value_parser = parse_seconds)]
    pub checkpoint: f64,
}

/// 0 (never), or seconds from 0.1 (a render that saved its state more
/// often would spend its time saving) to a year.
fn parse_seconds(s: &str) -> Result<f64, String> {
    (s.trim().parse::<f64>().ok())
        .filter(|v| *v == 0.0 || (0.1..=3.2e7).contains(v))
        .ok_or_else(|| {
            format!("`{s}` is not 0 (never) or a number of seconds from 0.1 to 32000000")
        })
}

/// `ptsc merge`'s arguments.
#[derive(Debug, Clone, clap::Args)]
pub struct MergeArgs {
    /// The part files (`ptsc render --pass K/N -o part.exr`), in any order.
    #[arg(required = true)]
    pub parts: Vec<PathBuf>,
    /// The image to write (.png, .exr or .pfm).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Merge an incomplete set (missing or unfinished parts), with a
    /// warning: each pixel is the mean of the samples it has.
    #[arg(long)]
    pub partial: bool,
    /// The most memory the merge may take, e.g. 16G (default: what the
    /// machine leaves free).
    #[arg(long, value_name = "SIZE", value_parser = crate::render::memory::parse_size)]
    pub memory_limit: Option<u64>,
    /// Replace an output that holds a render's state (another part file):
    /// its samples are lost.
    #[arg(long)]
    pub force: bool,
    /// Only errors: no warnings or summary.
    #[arg(short, long)]
    pub quiet: bool,
}

/// Runs `merge`; returns the exit code.
pub fn merge(args: &MergeArgs) -> u8 {
    let request = crate::render::merge::Request {
        parts: &args.parts,
        output: &args.output,
        partial: args.partial,
        memory_limit: args.memory_limit,
        force: args.force,
    };
    match crate::render::merge::merge(&request) {
        Ok(merged) => {
            if !args.quiet {
                eprintln!("{}", summary(&merged, &args.output));
            }
            super::EXIT_OK
        }
        Err(why) => {
            eprintln!("error: {why}");
            super::EXIT_USAGE
        }
    }
}

/// What `merge` says it did: its warnings, then one line.
fn summary(merged: &Merged, output: &Path) -> String {
    let mut summary = String::new();
    for w in &merged.warnings {
        summary.push_str(&format!(
            "warning: {w}; each pixel is the mean of the samples it has\n"
        ));
    }
    let (least, most) = merged.spp;
    let samples = if least == most {
        format!("{least} spp")
    } else {
        format!("{least} to {most} spp")
    };
    summary.push_str(&format!(
        "merged {} of {} passes of {} ({}×{}, {samples} of {}) → {}",
        merged.parts,
        merged.passes,
        merged.scene,
        merged.size.0,
        merged.size.1,
        merged.samples,
        output.display()
    ));
    summary
}
