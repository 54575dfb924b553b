//! Image files: PNG (8-bit sRGB, clamped, exposure applied), OpenEXR
//! (linear float32) and PFM, written atomically (to a temporary file in the
//! same folder, then renamed over the target, so a failed or interrupted run
//! never leaves a broken image), and the readers the tests compare with.

mod files;
mod layers;
pub mod tev;

pub use files::{
    check_writable, frame_path, same_file, shown, write_atomically, write_atomically_with,
    MAX_FILE_NAME,
};
use glam::Vec3;
pub use layers::write_exr_channels;
use std::io::Write;
use std::path::{Path, PathBuf};

/// Writes an image of `width` × `height` whose pixel `i` (row-major, top
/// to bottom) is `pixel(i)`, atomically; the format follows the extension
/// (.png, .exr, .pfm). Pixels are read one by one and streamed to the
/// file: an 8192 × 8192 image is written in a few MB beyond its film.
pub fn write_image(
    path: &Path,
    (width, height): (u32, u32),
    pixel: impl Fn(usize) -> Vec3 + Sync,
    exposure: f32,
) -> std::io::Result<()> {
    let size = (width, height);
    match ImageFormat::of(path) {
        Some(ImageFormat::Png) => {
            write_atomically_with(path, |out| png(out, size, &pixel, exposure))
        }
        Some(ImageFormat::Exr) => write_atomically_with(path, |out| exr(out, size, &pixel)),
        Some(ImageFormat::Pfm) => write_atomically_with(path, |out| pfm(out, size, &pixel)),
        None => Err(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            format!(
                "unknown image format for {} (use .png, .exr or .pfm)",
                path.display()
            ),
        )),
    }
}

/// 8-bit sRGB PNG, exposure applied, row by row (the `image` crate's
/// encoder wants the whole image in memory).
fn png(
    out: impl Write,
    (width, height): (u32, u32),
    pixel: &(impl Fn(usize) -> Vec3 + Sync),
    exposure: f32,
) -> std::io::Result<()> {
    let scale = 2f32.powf(exposure);
    let mut encoder = png::Encoder::new(out, width, height);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_compression(png::Compression::Balanced);
    encoder.set_filter(png::Filter::Adaptive);
    let mut writer = encoder.write_header().map_err(std::io::Error::other)?;
    let mut stream = writer.stream_writer().map_err(std::io::Error::other)?;
    let w = width as usize;
    let mut row = Vec::with_capacity(w * 3);
    for y in 0..height as usize {
        row.clear();
        for i in y * w..(y + 1) * w {
            let p = pixel(i);
            for c in [p.x, p.y, p.z] {
                row.push((srgb_encode(c * scale) * 255.0 + 0.5) as u8);
            }
        }
        stream.write_all(&row)?;
    }
    stream.finish().map_err(std::io::Error::other)
}

/// Linear float32 OpenEXR, ZIP-compressed, written as its blocks are
/// compressed.
fn exr(
    out: &mut (impl Write + std::io::Seek),
    (width, height): (u32, u32),
    pixel: &(impl Fn(usize) -> Vec3 + Sync),
) -> std::io::Result<()> {
    use exr::prelude::*;
    let w = width as usize;
    // ZIP compression: lossless and deterministic, and small references.
    let img = Image::from_encoded_channels(
        (width as usize, height as usize),
        Encoding::SMALL_LOSSLESS,
        SpecificChannels::rgb(|p: Vec2<usize>| {
            let v = pixel(p.y() * w + p.x());
            (v.x, v.y, v.z)
        }),
    );
    img.write().to_buffered(out).map_err(std::io::Error::other)
}

/// Linear float32 PFM (rows bottom to top).
fn pfm(
    out: &mut impl Write,
    (width, height): (u32, u32),
    pixel: &(impl Fn(usize) -> Vec3 + Sync),
) -> std::io::Result<()> {
    write!(out, "PF\n{} {}\n-1.0\n", width, height)?;
    let mut row = Vec::with_capacity(width as usize * 12);
    // PFM rows go bottom to top.
    for y in (0..height).rev() {
        row.clear();
        for x in 0..width {
            let v = pixel((y * width + x) as usize);
            for c in [v.x, v.y, v.z] {
                row.extend(c.to_le_bytes());
            }
        }
        out.write_all(&row)?;
    }
    Ok(())
}

/// Linear → sRGB transfer function, clamped to [0, 1].
pub fn srgb_encode(c: f32) -> f32 {
    let c = c.clamp(0.0, 1.0);
    if c <= 0.003_130_8 {
        12.92 * c
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    }
}

/// The image files ptsc writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ImageFormat {
    /// 8-bit sRGB PNG, exposure applied.
    Png,
    /// Linear float32 OpenEXR.
    Exr,
    /// Linear float32 PFM.
    Pfm,
}

impl ImageFormat {
    /// The format a path's extension names (any case).
    pub fn of(path: &Path) -> Option<ImageFormat> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "png" => Some(ImageFormat::Png),
            "exr" => Some(ImageFormat::Exr),
            "pfm" => Some(ImageFormat::Pfm),
            _ => None,
        }
    }
}

/// Whether an image can be written at `path`, found before a render starts
/// rather than after it: a known format, and a path a file can be written
/// at ([`check_writable`]).
pub fn check_image_writable(path: &Path) -> Result<(), String> {
    if ImageFormat::of(path).is_none() && !path.is_dir() {
        return Err("unknown image format (use .png, .exr or .pfm)".into());
    }
    check_writable(path)
}

/// Why an image cannot be written at `output`, found before rendering: an
/// unknown format, a folder, a missing or read-only folder, or a file the
/// scene reads (`inputs`: the scene itself, an include, a mesh), which the
/// image would replace.
pub fn check_output(output: &Path, inputs: &[PathBuf]) -> Result<(), String> {
    for input in inputs {
        if same_file(output, input) {
            return Err(format!(
                "{} is a file of the scene; the image would replace it (name another image)",
                input.display()
            ));
        }
    }
    check_image_writable(output)
}

/// Reads the RGB channels of an OpenEXR file (ours or another renderer's):
/// width, height, linear pixels top to bottom.
pub fn read_exr(path: &Path) -> Result<(u32, u32, Vec<Vec3>), String> {
    use exr::prelude::*;
    let image = read_first_rgba_layer_from_file(
        path,
        |size, _| (size.width(), vec![Vec3::ZERO; size.area()]),
        |(w, px): &mut (usize, Vec<Vec3>), p: Vec2<usize>, (r, g, b, _a): (f32, f32, f32, f32)| {
            px[p.y() * *w + p.x()] = Vec3::new(r, g, b);
        },
    )
    .map_err(|e| format!("{}: {e}", path.display()))?;
    let size = image.layer_data.size;
    let (_, px) = image.layer_data.channel_data.pixels;
    Ok((size.width() as u32, size.height() as u32, px))
}

/// Reads a PFM image (for tests): width, height, linear pixels top to bottom.
pub fn read_pfm(bytes: &[u8]) -> Option<(u32, u32, Vec<Vec3>)> {
    let mut parts = bytes.splitn(4, |&b| b == b'\n');
    if parts.next()? != b"PF" {
        return None;
    }
    let dims = std::str::from_utf8(parts.next()?).ok()?;
    let mut it = dims.split_whitespace();
    let (w, h): (u32, u32) = (it.next()?.parse().ok()?, it.next()?.parse().ok()?);
    parts.next()?;
    let data = parts.next()?;
    if data.len() < (w as usize) * (h as usize) * 12 {
        return None;
    }
    let mut px = vec![Vec3::ZERO; (w * h) as usize];
    for y in 0..h {
        for x in 0..w {
            let i = (((h - 1 - y) * w + x) * 12) as usize;
            let f = |k: usize| f32::from_le_bytes(data[i + k..i + k + 4].try_into().unwrap());
            px[(y * w + x) as usize] = Vec3::new(f(0), f(4), f(8));
        }
    }
    Some((w, h, px))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_endpoints() {
        assert_eq!(srgb_encode(0.0), 0.0);
        assert!((srgb_encode(1.0) - 1.0).abs() < 1e-6);
        assert!((srgb_encode(0.5) - 0.7354).abs() < 1e-3);
    }

    #[test]
    fn atomic_write_keeps_the_old_file_on_failure() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("img.png");
        let black = |_| Vec3::ZERO;
        write_image(&p, (2, 2), black, 0.0).unwrap();
        let before = std::fs::read(&p).unwrap();
        assert!(write_image(&dir.path().join("img.bmp"), (2, 2), black, 0.0).is_err());
        assert!(write_atomically(&dir.path().join("missing/img.png"), b"x").is_err());
        assert_eq!(std::fs::read(&p).unwrap(), before);
        assert_eq!(
            std::fs::read_dir(dir.path()).unwrap().count(),
            1,
            "no temporary files left"
        );
    }

    #[test]
    fn exr_round_trip() {
        let dir = tempfile::tempdir().unwrap();
        let px: Vec<Vec3> = (0..12).map(|i| Vec3::new(i as f32, 0.5, -1.0)).collect();
        let p = dir.path().join("a.exr");
        write_image(&p, (4, 3), |i| px[i], 0.0).unwrap();
        assert_eq!(read_exr(&p).unwrap(), (4, 3, px));
    }

    #[test]
    fn pfm_round_trip() {
        let v = Vec3::new(1.0, 2.0, 3.0);
        let mut bytes = Vec::new();
        pfm(&mut bytes, (3, 2), &|i| if i == 2 { v } else { Vec3::ZERO }).unwrap();
        let (w, h, px) = read_pfm(&bytes).unwrap();
        assert_eq!((w, h), (3, 2));
        assert_eq!(px[2], Vec3::new(1.0, 2.0, 3.0));
    }
}
