//! Where a batch render's state lives and how the render begins from it:
//! from nothing, or from the samples a saved state holds. A state holding
//! a user's samples is never replaced without being asked (`--resume` to
//! continue it, `--restart` to start over), and a state of another scene,
//! setting, pass or sample count is refused before its pixels are read.

use crate::render::film::Film;
use crate::render::state::{held_state, read_state, read_state_info, HeldState, Pass, StateInfo};
use std::path::{Path, PathBuf};
use std::time::Duration;

/// How a batch render (`ptsc render`) treats its state: the command
/// line's options for long renders and farms, and what the state says of
/// the scene.
#[derive(Debug, Clone, Default)]
pub struct StatePolicy {
    /// Only the K-th of N disjoint parts of every pixel's samples, into a
    /// part file at the output (`--pass K/N`); `None`: the whole render.
    pub pass: Option<Pass>,
    /// Continue from the saved state, if there is one (`--resume`).
    pub resume: bool,
    /// Start over, replacing a saved state (`--restart`).
    pub restart: bool,
    /// Keep the state of a render that ends before its first checkpoint
    /// (`--keep-state`).
    pub keep_state: bool,
    /// Replace an output that holds a render's state (`--force`).
    pub force: bool,
    /// Time between two saves of the state (`None`: never).
    pub checkpoint: Option<Duration>,
    /// The scene file's name, which the state gives for messages.
    pub scene: String,
    /// The scene's fingerprint (its objects, materials, lights, camera and
    /// data files): a state of another scene is refused.
    pub fingerprint: u64,
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
pub(super) struct Start {
    /// The film to render on from.
    pub(super) film: Film,
    /// Whether a state file is there to keep current (it was resumed, or
    /// replaced with `--restart`).
    pub(super) had_state: bool,
    /// A note for the user (resumed from how many samples).
    pub(super) note: Option<String>,
}

/// The film a render starts from, given its state file and what it asks:
/// refuses to overwrite a saved state without `resume` or `restart`,
/// and a state of another scene, setting, pass or sample count.
pub(super) fn start(
    state: &Path,
    now: &StateInfo,
    (width, height): (u32, u32),
    policy: &StatePolicy,
) -> Result<Start, String> {
    let new_film = || {
        let film = Film::new(width, height, now.pass.range(now.samples).start);
        let film = match now.keeps_halves() {
            true => film.with_halves(),
            false => film,
        };
        match now.keeps_light() {
            true => film.with_light(),
            false => film,
        }
    };
    let fresh = |had_state, note| Start {
        film: new_film(),
        had_state,
        note,
    };
    if policy.restart {
        return Ok(fresh(state.is_file(), None));
    }
    // Only a state file counts (by its headers): an image at a part's path
    // from elsewhere is replaced like any output. An OpenEXR file whose
    // headers cannot be read may be a damaged state: it is refused like an
    // unreadable one. A description is checked before its pixels are read.
    let saved = match held_state(state) {
        HeldState::Absent => None,
        HeldState::Other(why) => Some(why),
        HeldState::Damaged(why) => {
            return unreadable(state, format!("may hold a render state, but {why}"), why, policy.resume)
        }
        HeldState::State => match read_state_info(state) {
            Ok(info) if policy.resume => return resumed(state, &info, now),
            Ok(info) => {
                return Err(format!(
                    "{} holds the state of a render ({}); add --resume to continue it or --restart to start over",
                    state.display(),
                    info.describe()
                ))
            }
            Err(why) => {
                let claim = format!("holds a render state that cannot be read ({why})");
                return unreadable(state, claim, why, policy.resume);
            }
        },
    };
    let note = policy.resume.then(|| match saved {
        None => format!(
            "no saved state at {}: starting from the first sample",
            state.display()
        ),
        Some(why) => format!(
            "no saved state at {} ({why}): starting from the first sample",
            state.display()
        ),
    });
    Ok(fresh(false, note))
}

/// The refusal of a state file that cannot be read (`claim`: what the
/// file is said to be, `why`: what failed): it may still hold samples, so
/// only `--restart` replaces it.
fn unreadable(state: &Path, claim: String, why: String, resume: bool) -> Result<Start, String> {
    Err(match resume {
        true => format!("cannot resume from {}: {why}", state.display()),
        false => format!(
            "{} {claim}; add --restart to replace it, or name another output",
            state.display()
        ),
    })
}

/// The saved film, if it can hold samples of the render `now`: its
/// description is checked first, its pixels read only then.
fn resumed(state: &Path, saved: &StateInfo, now: &StateInfo) -> Result<Start, String> {
    let refuse = |why: String| Err(format!("cannot resume from {}: {why}", state.display()));
    if let Some(why) = saved.mismatch(now) {
        return refuse(why.for_resume());
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
    let (least, most, _) = film.sample_counts();
    if most > now.samples {
        return refuse(too_many(least, most, saved.samples, now.samples));
    }
    let note = format!("resuming {}", describe(&film, saved));
    Ok(Start {
        film,
        had_state: true,
        note: Some(note),
    })
}

/// Why a state with `least` to `most` samples in its pixels, of a render
/// started for `started` per pixel, cannot be resumed to `asked`: an
/// interrupted render's pixels differ, and the way on is the samples it
/// was started for.
fn too_many(least: u32, most: u32, started: u32, asked: u32) -> String {
    let has = match least == most {
        true => format!("it already has {most} samples in every pixel"),
        false => format!("some of its pixels already have {most} samples"),
    };
    // A budget's render asks no samples (it is given the most there are).
    let way_on = match started {
        s if s == crate::ir::settings::MAX_SAMPLES => {
            " (it was started with a time budget: repeat its --time to go on)".to_string()
        }
        s if s > asked && s > least => {
            format!(" (it was started for {s}: repeat --spp {s} to go on)")
        }
        _ => String::new(),
    };
    format!("{has}, more than the {asked} asked{way_on}")
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

/// "pass 2/4 of 64 spp: 8 of its 16 samples done in every pixel", "a
/// render of 1000 spp: 256 to 512 of its 1000 samples done per pixel".
fn describe(film: &Film, info: &StateInfo) -> String {
    let (least, most, _) = film.sample_counts();
    let share = info.pass.range(info.samples).len();
    let of = match info.pass {
        Pass::WHOLE => format!("a render of {}", info.describe()),
        _ => info.describe(),
    };
    if least == most {
        format!("{of}: {least} of its {share} samples done in every pixel")
    } else {
        format!("{of}: {least} to {most} of its {share} samples done per pixel")
    }
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

    #[test]
    fn a_state_with_too_many_samples_says_which_pixels_and_how_to_go_on() {
        // Interrupted at 256 to 512 spp of a render of 5000.
        assert_eq!(
            too_many(256, 512, 5000, 300),
            "some of its pixels already have 512 samples, more than the 300 asked (it was started for 5000: repeat --spp 5000 to go on)"
        );
        assert_eq!(
            too_many(256, 256, 256, 100),
            "it already has 256 samples in every pixel, more than the 100 asked"
        );
        let budget = too_many(40, 40, crate::ir::settings::MAX_SAMPLES, 16);
        assert!(budget.contains("repeat its --time"), "{budget}");
    }
}
