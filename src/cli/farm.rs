//! Long renders and render farms on the command line: the render's state
//! (where it lives, when a render starts from it), `--pass K/N`, and
//! `ptsc merge`. The file format is [`crate::render::state`]'s; the
//! schedulers' scripts are in `deploy/`; docs/farm.md tells the story.

use crate::render::film::Film;
use crate::render::state::{
    add_state, is_state_file, read_state, read_state_header, read_state_info, Pass, StateInfo,
};
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

/// Where a render keeps its state: a pass's part file is its output; a
/// whole render's state sits beside its image, named `IMAGE.state.exr`.
pub fn state_path(output: &Path, pass: Option<Pass>) -> PathBuf {
    match pass {
        Some(_) => output.to_path_buf(),
        None => {
            let mut name = output.as_os_str().to_os_string();
            name.push(".state.exr");
            PathBuf::from(name)
        }
    }
}

/// How a render begins: from a saved state, or from nothing.
pub struct Start {
    /// The film to render on from.
    pub film: Film,
    /// Whether a state file is there to keep current (it was resumed, or
    /// replaced with `--restart`).
    pub had_state: bool,
    /// A note for the user (resumed from how many samples).
    pub note: Option<String>,
}

/// The film a render starts from, given its state file and what it asks:
/// refuses to overwrite a saved state without `--resume` or `--restart`,
/// and a state of another scene, setting, pass or sample count.
pub fn start(
    state: &Path,
    now: &StateInfo,
    (width, height): (u32, u32),
    farm: &FarmArgs,
) -> Result<Start, String> {
    let fresh = |had_state, note| Start {
        film: Film::new(width, height, now.pass.range(now.samples).start),
        had_state,
        note,
    };
    if farm.restart {
        return Ok(fresh(state.is_file(), None));
    }
    // Only a state file counts (by its headers): an image at a part's path
    // from elsewhere is replaced like any output. Its description is
    // checked before its pixels are read.
    let saved = is_state_file(state).then(|| read_state_info(state));
    match saved {
        None => Ok(fresh(
            false,
            farm.resume.then(|| {
                format!(
                    "no saved state at {}: starting from the first sample",
                    state.display()
                )
            }),
        )),
        Some(Err(why)) if farm.resume => {
            Err(format!("cannot resume from {}: {why}", state.display()))
        }
        Some(Err(why)) => Err(format!(
            "{} holds a render state that cannot be read ({why}); add --restart to replace it, or name another output",
            state.display()
        )),
        Some(Ok(info)) if farm.resume => resumed(state, &info, now),
        Some(Ok(info)) => Err(format!(
            "{} holds the state of a render ({}); add --resume to continue it or --restart to start over",
            state.display(),
            describe_info(&info)
        )),
    }
}

/// The saved film, if it can hold samples of the render `now`: its
/// description is checked first, its pixels read only then.
fn resumed(state: &Path, saved: &StateInfo, now: &StateInfo) -> Result<Start, String> {
    let refuse = |why: String| Err(format!("cannot resume from {}: {why}", state.display()));
    if let Some(why) = saved.mismatch(now) {
        return refuse(why);
    }
    if saved.pass != now.pass {
        return refuse(format!(
            "it holds pass {} of the samples, this render is {}",
            saved.pass,
            match now.pass {
                Pass::WHOLE => "the whole render".to_string(),
                p => format!("pass {p}"),
            }
        ));
    }
    if size_of(saved) != size_of(now) {
        return refuse("its image size differs".into());
    }
    // A pass's sample run depends on the render's samples per pixel; a
    // whole render's only grows.
    if saved.pass != Pass::WHOLE && saved.samples != now.samples {
        return refuse(format!(
            "it is a pass of {} samples per pixel, this render asks {} (a pass's share changes with them)",
            saved.samples, now.samples
        ));
    }
    let film = match read_state(state) {
        Ok((film, _)) if (film.width, film.height) == size_of(now) => film,
        Ok(_) => return refuse("its image size differs".into()),
        Err(why) => return refuse(why),
    };
    let most = film.sample_counts().1;
    if most > now.samples {
        return refuse(format!(
            "it already has {most} samples per pixel, more than the {} asked",
            now.samples
        ));
    }
    let note = format!("resuming from {}", describe(&film, saved));
    Ok(Start {
        film,
        had_state: true,
        note: Some(note),
    })
}

/// The image size a state description's settings name.
fn size_of(info: &StateInfo) -> (u32, u32) {
    let get = |name: &str| {
        (info.settings.iter())
            .find(|(n, _)| n == name)
            .and_then(|(_, v)| v.parse().ok())
            .unwrap_or(0)
    };
    (get("width"), get("height"))
}

/// "pass 2/4 of 64 spp" (from a description alone).
fn describe_info(info: &StateInfo) -> String {
    match info.pass {
        Pass::WHOLE => format!("{} spp", info.samples),
        p => format!("pass {p} of {} spp", info.samples),
    }
}

/// "pass 2/4 of 64 spp: 16 of 16 samples in every pixel".
fn describe(film: &Film, info: &StateInfo) -> String {
    let (least, most, _) = film.sample_counts();
    let share = info.pass.range(info.samples).len();
    let of = describe_info(info);
    if least == most {
        format!("{of}: {least} of {share} samples in every pixel")
    } else {
        format!("{of}: {least} to {most} of {share} samples per pixel")
    }
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

/// Why an image must not be written at `output`: it holds a render's
/// state (a part file, a saved state), whose samples the image would
/// replace, and `--force` was not given.
pub fn refuse_to_replace_state(output: &Path, force: bool) -> Result<(), String> {
    if force || !is_state_file(output) {
        return Ok(());
    }
    let what = read_state_info(output).map_or_else(
        |_| "a render state".to_string(),
        |info| {
            format!(
                "the samples of a render of {} ({})",
                info.scene,
                describe_info(&info)
            )
        },
    );
    Err(format!(
        "{} holds {what}; writing an image there would lose them: name another output, or add --force to replace it",
        output.display()
    ))
}

/// Runs `merge`; returns the exit code.
pub fn merge(args: &MergeArgs) -> u8 {
    match merge_parts(args) {
        Ok(summary) => {
            if !args.quiet {
                eprintln!("{summary}");
            }
            super::EXIT_OK
        }
        Err(why) => {
            eprintln!("error: {why}");
            super::EXIT_USAGE
        }
    }
}

/// Checks the parts against each other, adds them up in pass order (so the
/// order given changes nothing) and writes the image; returns the summary
/// line, or why not.
fn merge_parts(args: &MergeArgs) -> Result<String, String> {
    let output = &args.output;
    if let Some(part) = (args.parts.iter()).find(|p| crate::output::same_file(p, output)) {
        return Err(format!(
            "cannot write {}: it is one of the parts (name another image with -o)",
            part.display()
        ));
    }
    refuse_to_replace_state(output, args.force)?;
    crate::output::check_image_writable(output)
        .map_err(|why| format!("cannot write {}: {why}", output.display()))?;
    // First every description (headers only), so that a foreign or
    // duplicate part is refused before any pixel is read.
    let mut parts: Vec<(PathBuf, StateInfo)> = Vec::new();
    let mut size = (0, 0);
    for path in &args.parts {
        let (info, part_size) =
            read_state_header(path).map_err(|why| format!("{}: {why}", path.display()))?;
        if let Some((first, reference)) = parts.first() {
            let foreign = |why: String| {
                Err(format!(
                    "{} is not a part of the render {} belongs to: {why}",
                    path.display(),
                    first.display()
                ))
            };
            if let Some(why) = reference.mismatch(&info) {
                return foreign(why);
            }
            if (info.samples, info.pass.n) != (reference.samples, reference.pass.n) {
                return foreign(format!(
                    "it is pass {} of {} spp, the other pass {} of {} spp",
                    info.pass, info.samples, reference.pass, reference.samples
                ));
            }
            if reference.exposure != info.exposure {
                return foreign("its exposure differs".into());
            }
            if part_size != size {
                return foreign("its image size differs".into());
            }
        }
        size = part_size;
        if let Some((other, _)) = parts.iter().find(|(_, i)| i.pass == info.pass) {
            return Err(format!(
                "{} and {} both hold pass {}: merge each part once",
                other.display(),
                path.display(),
                info.pass
            ));
        }
        parts.push((path.clone(), info));
    }
    parts.sort_by_key(|(_, info)| info.pass.k);
    let reference = parts[0].1.clone();
    let n = reference.pass.n;
    let missing: Vec<u32> = (1..=n)
        .filter(|k| parts.iter().all(|(_, i)| i.pass.k != *k))
        .collect();
    let mut warnings = Vec::new();
    if !missing.is_empty() {
        let list = missing
            .iter()
            .map(u32::to_string)
            .collect::<Vec<_>>()
            .join(", ");
        let why = match missing.len() {
            1 => format!("pass {list} of {n} is missing"),
            _ => format!("passes {list} of {n} are missing"),
        };
        if !args.partial {
            return Err(format!("{why}; merge them all, or add --partial"));
        }
        warnings.push(why);
    }
    crate::render::memory::check(&crate::render::memory::Need::film(size), args.memory_limit)?;
    // One film: each part is added into it as it is read, in pass order.
    let mut film = Film::new(size.0, size.1, 0);
    for (path, info) in &parts {
        let (_, least) =
            add_state(path, &mut film).map_err(|why| format!("{}: {why}", path.display()))?;
        let share = info.pass.range(info.samples).len() as u32;
        if least < share {
            let why = format!(
                "{} is unfinished (pass {}: {} samples in some pixel of {share})",
                path.display(),
                info.pass,
                least
            );
            if !args.partial {
                return Err(format!("{why}; resume it (--resume), or add --partial"));
            }
            warnings.push(why);
        }
    }
    film.write(&args.output, reference.exposure)
        .map_err(|e| format!("cannot write {}: {e}", args.output.display()))?;
    let (least, most, _) = film.sample_counts();
    let mut summary = String::new();
    for w in &warnings {
        summary.push_str(&format!(
            "warning: {w}; each pixel is the mean of the samples it has\n"
        ));
    }
    let samples = if least == most {
        format!("{least} spp")
    } else {
        format!("{least} to {most} spp")
    };
    summary.push_str(&format!(
        "merged {} of {n} passes of {} ({}×{}, {samples} of {}) → {}",
        parts.len(),
        reference.scene,
        film.width,
        film.height,
        reference.samples,
        args.output.display()
    ));
    Ok(summary)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_whole_renders_state_sits_beside_its_image_a_pass_is_its_own() {
        assert_eq!(
            state_path(Path::new("out/a.png"), None),
            PathBuf::from("out/a.png.state.exr")
        );
        let pass = Some(Pass { k: 1, n: 2 });
        assert_eq!(
            state_path(Path::new("p1.exr"), pass),
            PathBuf::from("p1.exr")
        );
    }
}
