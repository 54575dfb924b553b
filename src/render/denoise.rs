//! Denoising a rendered image with Intel Open Image Denoise (OIDN 2), behind
//! the cargo feature `denoise`.
//!
//! The default build links nothing native: [`denoise`] is there all the same
//! and answers [`NOT_BUILT`], so callers need no `cfg`. With the feature, the
//! `oidn` crate links `libOpenImageDenoise`; `scripts/setup-oidn.sh` installs
//! it and prints the `OIDN_DIR` (build time) and `LD_LIBRARY_PATH` (run time)
//! to use.
//!
//! The filter is OIDN's "RT" (images rendered by Monte Carlo ray tracing) on
//! linear HDR colour (`hdr` on, the input scale chosen by OIDN from the
//! image), on the fastest device OIDN finds (the CPU unless a GPU device
//! module is installed).
//!
//! ## Auxiliary images
//!
//! An albedo image, and with it a normal image, of the first visible surface
//! keep edges and textures that the noise would otherwise blur. OIDN takes
//! the albedo in `[0, 1]` and the normal as any-length vectors in world or
//! camera space; a normal image is used only with an albedo image.
//!
//! - Noise-free aux images (a pinhole camera, no motion blur, albedo and
//!   normal of the first hit averaged over many samples) are OIDN's best
//!   case: they are meant to be given with `cleanAux` on.
//! - Noisy ones (depth of field, motion blur, glass in front, few samples)
//!   need `cleanAux` off: OIDN then takes them as noisy, so that their noise
//!   does not stay in the output, at the price of a somewhat blurrier result
//!   (Blender's "Fast" prefilter).
//! - OIDN's recipe for the best of noisy ones ("clean aux", Blender's
//!   "Accurate"): *prefilter* them, denoising the albedo with an RT filter
//!   of its own (the albedo its only input) and the normal likewise, then
//!   give those to the colour's filter with `cleanAux` on. Worth its cost
//!   (two more filter runs) for a final frame, not for previews.
//!
//! [`denoise`] always runs with `cleanAux` off, right for both kinds (clean
//! ones only lose a little sharpness), because the `oidn` crate 2.5.1 can
//! neither prefilter nor set `cleanAux`: its filter always takes a colour
//! input (no albedo-only or normal-only filter), and its `clean_aux` sets a
//! parameter named `clean_aux`, which OIDN ignores (OIDN's is `cleanAux`;
//! with `OIDN_VERBOSE=2` it warns "unknown filter parameter or type
//! mismatch: 'clean_aux'" on every run).

use glam::Vec3;

/// Whether this build denoises (the `denoise` feature).
pub const AVAILABLE: bool = cfg!(feature = "denoise");

/// What [`denoise`] answers in a build without the `denoise` feature.
pub const NOT_BUILT: &str =
    "ptsc was built without denoising: run scripts/setup-oidn.sh and build with --features denoise";

/// Denoises a `width` × `height` image of linear HDR `color`, row by row from
/// the top-left, with optional `albedo` and `normal` images of the same size
/// (see the module's doc for what they bring and when to prefilter them).
///
/// Errors, as a sentence: a build without the `denoise` feature
/// ([`NOT_BUILT`]), an empty image, a buffer whose length is not
/// `width * height`, a normal image without an albedo image, or a failure
/// OIDN reports (no device, out of memory).
pub fn denoise(
    width: u32,
    height: u32,
    color: &[Vec3],
    albedo: Option<&[Vec3]>,
    normal: Option<&[Vec3]>,
) -> Result<Vec<Vec3>, String> {
    denoise_as(Speed::Final, width, height, color, (albedo, normal))
}

/// How OIDN weighs quality against time.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Speed {
    /// Its best (`--denoise`, `ptsc denoise`).
    Final,
    /// Its fast network, for interactive previews (`watch`).
    Preview,
}

/// [`denoise`] at the given [`Speed`].
pub fn denoise_as(
    speed: Speed,
    width: u32,
    height: u32,
    color: &[Vec3],
    (albedo, normal): (Option<&[Vec3]>, Option<&[Vec3]>),
) -> Result<Vec<Vec3>, String> {
    #[cfg(feature = "denoise")]
    {
        check_sizes(width, height, color, albedo, normal)?;
        with_oidn(speed, (width, height), color, albedo, normal)
    }
    #[cfg(not(feature = "denoise"))]
    {
        let _ = (speed, width, height, color, albedo, normal);
        Err(NOT_BUILT.to_string())
    }
}

/// Refuses what OIDN would refuse or misread: an empty image, buffers of
/// the wrong length, a normal image alone.
#[cfg(feature = "denoise")]
fn check_sizes(
    width: u32,
    height: u32,
    color: &[Vec3],
    albedo: Option<&[Vec3]>,
    normal: Option<&[Vec3]>,
) -> Result<(), String> {
    if width == 0 || height == 0 {
        return Err(format!(
            "cannot denoise an empty image ({width} × {height})"
        ));
    }
    let pixels = width as usize * height as usize;
    let buffers = [
        ("colour", Some(color)),
        ("albedo", albedo),
        ("normal", normal),
    ];
    for (name, buffer) in buffers {
        if let Some(buffer) = buffer.filter(|b| b.len() != pixels) {
            return Err(format!(
                "the {name} image has {} pixels, but a {width} × {height} image has {pixels}",
                buffer.len()
            ));
        }
    }
    if normal.is_some() && albedo.is_none() {
        return Err("OIDN uses a normal image only with an albedo image: give both".to_string());
    }
    Ok(())
}

/// The OIDN device, started at the first denoising.
#[cfg(feature = "denoise")]
static DEVICE: std::sync::Mutex<Option<oidn::Device>> = std::sync::Mutex::new(None);

/// Runs OIDN's RT filter on buffers already checked by [`check_sizes`].
#[cfg(feature = "denoise")]
fn with_oidn(
    speed: Speed,
    (width, height): (u32, u32),
    color: &[Vec3],
    albedo: Option<&[Vec3]>,
    normal: Option<&[Vec3]>,
) -> Result<Vec<Vec3>, String> {
    let fail = |what: &str, e: oidn::Error| format!("Open Image Denoise could not {what}: {e}");
    let floats = |image: &[Vec3]| -> Vec<f32> { image.iter().flat_map(|v| v.to_array()).collect() };
    // One device for the process: starting one costs tens of milliseconds,
    // which a live preview's denoising would pay at every save.
    let mut held = DEVICE
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    if held.is_none() {
        *held = Some(oidn::Device::new().map_err(|e| fail("start a device", e))?);
    }
    let device = held.as_ref().expect("just started");
    let mut filter =
        oidn::RayTracing::try_new(device).map_err(|e| fail("create its RT filter", e))?;
    // `cleanAux` stays off, OIDN's default: the crate's `clean_aux` would not
    // change it anyway (see the module's doc).
    let quality = match speed {
        Speed::Final => oidn::Quality::High,
        Speed::Preview => oidn::Quality::Fast,
    };
    filter
        .hdr(true)
        .srgb(false)
        .filter_quality(quality)
        .image_dimensions(width as usize, height as usize);
    // Buffers made here rather than by the filter's `albedo`/`albedo_normal`,
    // which panic when OIDN cannot allocate them.
    let buffer = |image: &[Vec3]| device.create_buffer(&floats(image));
    match (albedo, normal) {
        (Some(albedo), Some(normal)) => {
            let albedo = buffer(albedo).map_err(|e| fail("hold the albedo image", e))?;
            let normal = buffer(normal).map_err(|e| fail("hold the normal image", e))?;
            filter
                .albedo_normal_buffer(albedo, normal)
                .map_err(|e| fail("take the albedo and normal images", e))?;
        }
        (Some(albedo), None) => {
            let albedo = buffer(albedo).map_err(|e| fail("hold the albedo image", e))?;
            filter
                .albedo_buffer(albedo)
                .map_err(|e| fail("take the albedo image", e))?;
        }
        // A normal image alone is refused by `check_sizes`.
        (None, _) => {}
    }
    let mut output = vec![0.0; color.len() * 3];
    filter
        .filter(&floats(color), &mut output)
        .map_err(|e| fail("denoise the image", e))?;
    Ok(output.chunks_exact(3).map(Vec3::from_slice).collect())
}

/// The channels of a saved render that [`denoise_planes`] takes, in its
/// order: the colour, then the albedo and normal of `--aov`.
pub const CHANNELS: [&str; 9] = [
    "R", "G", "B", "albedo.R", "albedo.G", "albedo.B", "normal.X", "normal.Y", "normal.Z",
];

/// Denoises a saved render given as the planes of [`CHANNELS`] (each
/// row-major, `None` where the file lacks it): the colour is needed, the
/// albedo and then the normal are used when all three of theirs are there.
pub fn denoise_planes(
    width: u32,
    height: u32,
    planes: &[Option<Vec<f32>>],
) -> Result<Vec<Vec3>, String> {
    let vectors = |first: usize| -> Option<Vec<Vec3>> {
        let [a, b, c] = [0, 1, 2].map(|k| planes.get(first + k).and_then(Option::as_ref));
        let (a, b, c) = (a?, b?, c?);
        Some((0..a.len()).map(|i| Vec3::new(a[i], b[i], c[i])).collect())
    };
    let colour = vectors(0).ok_or("it has no R, G, B channels to denoise")?;
    let albedo = vectors(3);
    let normal = albedo.as_ref().and(vectors(6));
    denoise(width, height, &colour, albedo.as_deref(), normal.as_deref())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[cfg(not(feature = "denoise"))]
    #[test]
    fn without_the_feature_says_how_to_get_it() {
        let color = vec![Vec3::ONE; 4];
        let err = denoise(2, 2, &color, None, None).unwrap_err();
        assert_eq!(err, NOT_BUILT);
        assert!(err.contains("scripts/setup-oidn.sh") && err.contains("--features denoise"));
    }

    /// A smooth HDR gradient, and the same with seeded noise of mean zero
    /// (each channel times 1 ± 0.5, uniform), as from a few samples a pixel.
    #[cfg(feature = "denoise")]
    fn gradient(width: u32, height: u32) -> (Vec<Vec3>, Vec<Vec3>) {
        use crate::sampling::sampler::Sampler;
        let mut clean = Vec::new();
        let mut noisy = Vec::new();
        for y in 0..height {
            for x in 0..width {
                let (u, v) = (x as f32 / width as f32, y as f32 / height as f32);
                let c = Vec3::new(0.2 + 1.8 * u, 0.5 + v, 1.5 - u * v);
                let mut rng = Sampler::new(7, x, y, 0);
                let mut jitter = || 1.0 + (rng.next_f32() - 0.5);
                noisy.push(c * Vec3::new(jitter(), jitter(), jitter()));
                clean.push(c);
            }
        }
        (clean, noisy)
    }

    #[cfg(feature = "denoise")]
    fn mse(a: &[Vec3], b: &[Vec3]) -> f64 {
        let sum: f64 = a
            .iter()
            .zip(b)
            .map(|(a, b)| (*a - *b).length_squared() as f64)
            .sum();
        sum / (3 * a.len()) as f64
    }

    #[cfg(feature = "denoise")]
    #[test]
    fn noise_goes_and_the_gradient_stays() {
        let (w, h) = (96, 64);
        let (clean, noisy) = gradient(w, h);
        let denoised = denoise(w, h, &noisy, None, None).unwrap();
        assert_eq!(denoised.len(), clean.len());
        let (before, after) = (mse(&noisy, &clean), mse(&denoised, &clean));
        assert!(
            after < before / 10.0,
            "MSE {before} before denoising, {after} after"
        );
    }

    #[cfg(feature = "denoise")]
    #[test]
    fn albedo_and_normal_are_taken() {
        let (w, h) = (48, 32);
        let (clean, noisy) = gradient(w, h);
        let albedo = vec![Vec3::splat(0.8); clean.len()];
        let normal = vec![Vec3::Z; clean.len()];
        let with_albedo = denoise(w, h, &noisy, Some(&albedo), None).unwrap();
        let with_both = denoise(w, h, &noisy, Some(&albedo), Some(&normal)).unwrap();
        let before = mse(&noisy, &clean);
        for denoised in [with_albedo, with_both] {
            let after = mse(&denoised, &clean);
            assert!(
                after < before / 10.0,
                "MSE {before} before denoising, {after} after"
            );
        }
    }

    #[cfg(feature = "denoise")]
    #[test]
    fn wrong_sizes_are_errors() {
        let (w, h) = (8, 4);
        let (clean, noisy) = gradient(w, h);
        let short = &noisy[1..];
        let err = denoise(w, h, short, None, None).unwrap_err();
        assert!(err.contains("colour image has 31 pixels"), "{err}");
        let err = denoise(w, h, &noisy, Some(short), None).unwrap_err();
        assert!(err.contains("albedo image has 31 pixels"), "{err}");
        let err = denoise(w, h, &noisy, Some(&clean), Some(short)).unwrap_err();
        assert!(err.contains("normal image has 31 pixels"), "{err}");
        let err = denoise(w, h, &noisy, None, Some(&clean)).unwrap_err();
        assert!(err.contains("only with an albedo image"), "{err}");
        let err = denoise(0, h, &[], None, None).unwrap_err();
        assert!(err.contains("empty image"), "{err}");
        let err = denoise(w + 1, h, &noisy, None, None).unwrap_err();
        assert!(err.contains("a 9 × 4 image has 36"), "{err}");
    }
}
