//! The final image of a batch render that finished: the AOVs it writes
//! beside its colour and, with `--denoise`, the colour denoised with the
//! albedo and normal of the first surfaces (computed for it if not asked
//! for). The state keeps the noisy samples: a resumed render denoises its
//! own end again.

use crate::ir::Scene;
use crate::render::aov::{render_aovs, Aov};
use crate::render::film::Film;
use glam::Vec3;
use std::path::Path;
use std::sync::atomic::AtomicBool;

/// The AOVs' values: each with its channels' planes.
pub(super) type AovValues = Vec<(Aov, Vec<Vec<f32>>)>;

/// What the final write adds to the film's image.
#[derive(Default)]
pub(super) struct FinalImage {
    /// The denoised colour, in place of the film's mean.
    pub(super) denoised: Option<Vec<Vec3>>,
    /// The AOVs asked for.
    pub(super) aovs: Option<AovValues>,
    /// Why denoising failed (the noisy image is written instead).
    pub(super) denoise_error: Option<String>,
}

/// The AOVs `asked` and, when `denoise`, the denoised colour of `film`
/// (nothing once `cancel` is set).
pub(super) fn final_image(
    scene: &Scene,
    film: &Film,
    asked: &[Aov],
    denoise: bool,
    cancel: &AtomicBool,
) -> FinalImage {
    let mut needed = asked.to_vec();
    if denoise {
        for aov in [Aov::Albedo, Aov::Normal] {
            if !needed.contains(&aov) {
                needed.push(aov);
            }
        }
    }
    if needed.is_empty() {
        return FinalImage::default();
    }
    let Some(values) = render_aovs(scene, &needed, film, cancel) else {
        return FinalImage::default();
    };
    let mut image = FinalImage::default();
    if denoise {
        let vectors = |aov: Aov| -> Vec<Vec3> {
            let planes = &values.iter().find(|(a, _)| *a == aov).expect("computed").1;
            (0..film.count.len())
                .map(|i| Vec3::new(planes[0][i], planes[1][i], planes[2][i]))
                .collect()
        };
        let (albedo, normal) = (vectors(Aov::Albedo), vectors(Aov::Normal));
        let colour = film.pixels();
        let (w, h) = (film.width, film.height);
        match crate::render::denoise::denoise(w, h, &colour, Some(&albedo), Some(&normal)) {
            Ok(pixels) => image.denoised = Some(pixels),
            Err(why) => image.denoise_error = Some(why),
        }
    }
    let kept: AovValues = values
        .into_iter()
        .filter(|(a, _)| asked.contains(a))
        .collect();
    image.aovs = (!kept.is_empty()).then_some(kept);
    image
}

/// Writes the image at `output`: the denoised colour or the film's, with
/// the AOVs as channels of an EXR.
pub(super) fn write(
    output: &Path,
    film: &Film,
    exposure: f32,
    image: &FinalImage,
) -> std::io::Result<()> {
    let colour = |i: usize| match &image.denoised {
        Some(pixels) => pixels[i],
        None => film.pixel(i),
    };
    let size = (film.width, film.height);
    match &image.aovs {
        Some(aovs) => {
            let mut extra = Vec::new();
            for (aov, planes) in aovs {
                for (name, plane) in aov.channels().iter().zip(planes) {
                    extra.push((*name, plane.as_slice()));
                }
            }
            crate::output::write_exr_channels(output, size, colour, &extra)
        }
        None => crate::output::write_image(output, size, colour, exposure),
    }
}
