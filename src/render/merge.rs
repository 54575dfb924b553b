//! Adding up the parts of a render made in passes (`--pass K/N`, `ptsc
//! merge`): every part's description is checked against the others before
//! a pixel is read, then the parts are added in pass order into one film
//! (so the order they are given in changes nothing) and written as the
//! image. The parts' format is [`super::state`]'s.

use super::film::Film;
use super::state::{add_state, read_state_header, refuse_to_replace, StateInfo};
use std::path::{Path, PathBuf};

/// What to merge, and how.
#[derive(Debug, Clone, Copy)]
pub struct Request<'a> {
    /// The part files, in any order.
    pub parts: &'a [PathBuf],
    /// The image to write (.png, .exr or .pfm).
    pub output: &'a Path,
    /// Whether an incomplete set (missing or unfinished parts) is merged,
    /// with a warning, rather than refused.
    pub partial: bool,
    /// The most memory the merge may take (`None`: what the machine leaves free).
    pub memory_limit: Option<u64>,
    /// Whether an output that holds a render's state may be replaced.
    pub force: bool,
}

/// What a merge wrote.
#[derive(Debug, Clone)]
pub struct Merged {
    /// Why the image is incomplete (a missing pass, an unfinished part),
    /// when a partial merge was allowed.
    pub warnings: Vec<String>,
    /// The parts added up.
    pub parts: usize,
    /// The passes the render was split into.
    pub passes: u32,
    /// The scene file's name, as the parts give it.
    pub scene: String,
    /// The image's size.
    pub size: (u32, u32),
    /// The samples in every pixel and the most in any pixel.
    pub spp: (u32, u32),
    /// The samples per pixel of the whole render.
    pub samples: u32,
}

/// The parts' files and descriptions.
type Parts = Vec<(PathBuf, StateInfo)>;

/// Checks the parts against each other, adds them up in pass order and
/// writes the image; says what it wrote, or why not.
pub fn merge(request: &Request) -> Result<Merged, String> {
    let output = request.output;
    if let Some(part) = (request.parts.iter()).find(|p| crate::output::same_file(p, output)) {
        return Err(format!(
            "cannot write {}: it is one of the parts (name another image with -o)",
            part.display()
        ));
    }
    refuse_to_replace(output, Some(request.force))?;
    crate::output::check_image_writable(output)
        .map_err(|why| format!("cannot write {}: {why}", output.display()))?;
    let (parts, size) = read_descriptions(request.parts)?;
    let Some((_, reference)) = parts.first().cloned() else {
        return Err("no part to merge".into());
    };
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
        if !request.partial {
            return Err(format!("{why}; merge them all, or add --partial"));
        }
        warnings.push(why);
    }
    crate::render::memory::check(
        &crate::render::memory::Need::film(size),
        request.memory_limit,
    )?;
    let film = add_parts(&parts, size, request.partial, &mut warnings)?;
    film.write(output, reference.exposure)
        .map_err(|e| format!("cannot write {}: {e}", output.display()))?;
    let (least, most, _) = film.sample_counts();
    Ok(Merged {
        warnings,
        parts: parts.len(),
        passes: n,
        scene: reference.scene,
        size,
        spp: (least, most),
        samples: reference.samples,
    })
}

/// Every part's description (headers only), checked against the first's,
/// in pass order, and the image size: a foreign or duplicate part is
/// refused before any pixel is read.
fn read_descriptions(paths: &[PathBuf]) -> Result<(Parts, (u32, u32)), String> {
    let mut parts: Parts = Vec::new();
    let mut size = (0, 0);
    for path in paths {
        let (info, part_size) =
            read_state_header(path).map_err(|why| format!("{}: {why}", path.display()))?;
        // Its pixels stopped at counts that hang on the whole film: no
        // share of the samples is a part of it, and its own image is the
        // render's (`--resume` finishes it).
        if info.adaptive() {
            return Err(format!(
                "{} is the state of an adaptive render (noise_threshold), which is not split into parts: resume it with --resume to finish it, or render without the noise threshold to split the work with --pass",
                path.display()
            ));
        }
        if let Some((first, reference)) = parts.first() {
            let foreign = |why: String| {
                Err(format!(
                    "{} is not a part of the render {} belongs to: {why}",
                    path.display(),
                    first.display()
                ))
            };
            if let Some(why) = reference.mismatch(&info) {
                return foreign(why.between_parts(&first.display().to_string()));
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
    Ok((parts, size))
}

/// One film, each part added into it as it is read, in pass order; an
/// unfinished part is refused, or a warning when `partial`.
fn add_parts(
    parts: &[(PathBuf, StateInfo)],
    size: (u32, u32),
    partial: bool,
    warnings: &mut Vec<String>,
) -> Result<Film, String> {
    let mut film = Film::new(size.0, size.1, 0);
    for (path, info) in parts {
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
            if !partial {
                return Err(format!("{why}; resume it (--resume), or add --partial"));
            }
            warnings.push(why);
        }
    }
    Ok(film)
}
