//! An OpenEXR image with more channels than its colour: the image as `R`,
//! `G`, `B` and each extra channel by its own name (`albedo.R`,
//! `normal.X`, …), all in one part, so that readers which show only a
//! file's first part (Mitsuba's `Bitmap` among them) see everything.

use glam::Vec3;
use std::path::Path;

/// Writes the image whose pixel `i` is `pixel(i)` with the `extra`
/// channels (name, one value per pixel, row-major), atomically, as a
/// ZIP-compressed float32 EXR.
pub fn write_exr_channels(
    path: &Path,
    (width, height): (u32, u32),
    pixel: impl Fn(usize) -> Vec3,
    extra: &[(&str, &[f32])],
) -> std::io::Result<()> {
    use exr::prelude::*;
    let n = width as usize * height as usize;
    if let Some((name, _)) = extra.iter().find(|(_, v)| v.len() != n) {
        return Err(std::io::Error::other(format!(
            "channel {name} does not have one value per pixel"
        )));
    }
    let colour: Vec<Vec3> = (0..n).map(pixel).collect();
    let plane = |c: usize| FlatSamples::F32(colour.iter().map(|p| p[c]).collect());
    let mut list = SmallVec::<[AnyChannel<FlatSamples>; 4]>::new();
    for (c, name) in ["R", "G", "B"].into_iter().enumerate() {
        list.push(AnyChannel::new(name, plane(c)));
    }
    for (name, values) in extra {
        list.push(AnyChannel::new(*name, FlatSamples::F32(values.to_vec())));
    }
    let layer = Layer::new(
        (width as usize, height as usize),
        LayerAttributes::default(),
        Encoding::SMALL_LOSSLESS,
        AnyChannels::sort(list),
    );
    let image = Image::from_layer(layer);
    super::write_atomically_with(path, |out| {
        image
            .write()
            .to_buffered(out)
            .map_err(std::io::Error::other)
    })
}
