//! `ptsc denoise IN.exr -o OUT`: denoises a saved render (its colour, with
//! the albedo and normal channels of `--aov` when it has them).

use super::{EXIT_OK, EXIT_USAGE};
use std::path::PathBuf;

/// `ptsc denoise`'s arguments.
#[derive(Debug, Clone, clap::Args)]
pub struct DenoiseArgs {
    /// The EXR to denoise (R, G, B; albedo.R/G/B and normal.X/Y/Z used when present).
    pub input: PathBuf,
    /// The denoised image (.png, .exr or .pfm).
    #[arg(short, long)]
    pub output: PathBuf,
}

/// Runs `ptsc denoise`; returns the exit status.
pub fn run(args: &DenoiseArgs) -> u8 {
    let inputs = [args.input.clone()];
    if let Err(why) = crate::output::check_output(&args.output, &inputs) {
        eprintln!("error: cannot write {}: {why}", args.output.display());
        return EXIT_USAGE;
    }
    let started = std::time::Instant::now();
    let (w, h, pixels) = match denoise_file(&args.input) {
        Ok(done) => done,
        Err(why) => {
            eprintln!("error: cannot denoise {}: {why}", args.input.display());
            return EXIT_USAGE;
        }
    };
    if let Err(e) = crate::output::write_image(&args.output, (w, h), |i| pixels[i], 0.0) {
        eprintln!("error: cannot write {}: {e}", args.output.display());
        return EXIT_USAGE;
    }
    let secs = started.elapsed().as_secs_f64();
    eprintln!(
        "{}: {w}×{h} denoised in {secs:.2} s → {}",
        args.input.display(),
        args.output.display()
    );
    EXIT_OK
}

/// The file read and decoded as textures are (size caps from its header
/// before a sample is allocated, at most a scene's texture memory), then
/// denoised.
fn denoise_file(path: &std::path::Path) -> Result<(u32, u32, Vec<glam::Vec3>), String> {
    use crate::lower::decode::{decode_exr_channels, Limits};
    use crate::lower::image::{MAX_IMAGE_SIDE, MAX_IMAGE_TEXELS, MAX_TEXTURE_BYTES};
    use crate::render::denoise::{denoise_planes, CHANNELS};
    let bytes = crate::source::read_file(path, MAX_TEXTURE_BYTES).map_err(|e| e.to_string())?;
    let limits = Limits {
        side: MAX_IMAGE_SIDE,
        texels: MAX_IMAGE_TEXELS,
        bytes: MAX_TEXTURE_BYTES,
    };
    let (w, h, planes) = decode_exr_channels(&bytes, &limits, &CHANNELS)?;
    Ok((w, h, denoise_planes(w, h, &planes)?))
}
