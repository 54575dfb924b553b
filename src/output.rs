//! Image files: PNG (8-bit sRGB, clamped, exposure applied), OpenEXR
//! (linear float32) and PFM, written atomically (to a temporary file in the
//! same folder, then renamed over the target, so a failed or interrupted run
//! never leaves a broken image), and the readers the tests compare with.

use glam::Vec3;
use image::ImageEncoder;
use std::io::Write;
use std::path::{Path, PathBuf};

/// Writes an image of `width` × `height` whose pixel `i` (row-major, top
/// to bottom) is `pixel(i)`, atomically; the format follows the extension
/// (.png, .exr, .pfm). Pixels are read one by one: a copy of an
/// 8192 × 8192 image would be 805 MB.
pub fn write_image(
    path: &Path,
    (width, height): (u32, u32),
    pixel: impl Fn(usize) -> Vec3 + Sync,
    exposure: f32,
) -> std::io::Result<()> {
    let bytes = match ImageFormat::of(path) {
        Some(ImageFormat::Png) => png((width, height), &pixel, exposure)?,
        Some(ImageFormat::Exr) => exr((width, height), &pixel)?,
        Some(ImageFormat::Pfm) => pfm((width, height), &pixel),
        None => {
            return Err(std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                format!(
                    "unknown image format for {} (use .png, .exr or .pfm)",
                    path.display()
                ),
            ))
        }
    };
    write_atomically(path, &bytes)
}

/// 8-bit sRGB PNG, exposure applied.
fn png(
    (width, height): (u32, u32),
    pixel: &(impl Fn(usize) -> Vec3 + Sync),
    exposure: f32,
) -> std::io::Result<Vec<u8>> {
    let scale = 2f32.powf(exposure);
    let n = width as usize * height as usize;
    let mut rgb = Vec::with_capacity(n * 3);
    for i in 0..n {
        let p = pixel(i);
        for c in [p.x, p.y, p.z] {
            rgb.push((srgb_encode(c * scale) * 255.0 + 0.5) as u8);
        }
    }
    let mut out = Vec::new();
    image::codecs::png::PngEncoder::new(&mut out)
        .write_image(&rgb, width, height, image::ExtendedColorType::Rgb8)
        .map_err(std::io::Error::other)?;
    Ok(out)
}

/// Linear float32 OpenEXR, ZIP-compressed.
fn exr(
    (width, height): (u32, u32),
    pixel: &(impl Fn(usize) -> Vec3 + Sync),
) -> std::io::Result<Vec<u8>> {
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
    let mut cur = std::io::Cursor::new(Vec::new());
    img.write()
        .to_buffered(&mut cur)
        .map_err(std::io::Error::other)?;
    Ok(cur.into_inner())
}

/// Linear float32 PFM (rows bottom to top).
fn pfm((width, height): (u32, u32), pixel: &(impl Fn(usize) -> Vec3 + Sync)) -> Vec<u8> {
    let mut out = format!("PF\n{} {}\n-1.0\n", width, height).into_bytes();
    // PFM rows go bottom to top.
    for y in (0..height).rev() {
        for x in 0..width {
            let v = pixel((y * width + x) as usize);
            for c in [v.x, v.y, v.z] {
                out.extend(c.to_le_bytes());
            }
        }
    }
    out
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
/// rather than after it: a known format, not a folder, a folder that exists
/// and takes a new file (a temporary one is created and removed).
pub fn check_writable(path: &Path) -> Result<(), String> {
    if path.is_dir() {
        return Err("it is a folder; name an image file in it".into());
    }
    if ImageFormat::of(path).is_none() {
        return Err("unknown image format (use .png, .exr or .pfm)".into());
    }
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    if !dir.is_dir() {
        return Err(format!("the folder {} does not exist", dir.display()));
    }
    let probe = temporary_beside(path).map_err(|e| e.to_string())?;
    std::fs::File::create(&probe)
        .map_err(|e| format!("the folder {} does not take new files: {e}", dir.display()))?;
    let _ = std::fs::remove_file(&probe);
    Ok(())
}

/// An output path with each run of `#` replaced by `frame`, zero-padded to
/// the run's length (`frame_####.png` → `frame_0012.png`).
pub fn frame_path(path: &Path, frame: u32) -> PathBuf {
    match path.to_str() {
        Some(text) if text.contains('#') => PathBuf::from(number_frame(text, frame)),
        _ => path.to_path_buf(),
    }
}

/// Replaces each run of `#` with `frame`, zero-padded to the run's length.
fn number_frame(pattern: &str, frame: u32) -> String {
    let mut out = String::with_capacity(pattern.len() + 8);
    let mut run = 0;
    let flush = |out: &mut String, run: &mut usize| {
        if *run > 0 {
            out.push_str(&format!("{frame:0width$}", width = *run));
            *run = 0;
        }
    };
    for c in pattern.chars() {
        if c == '#' {
            run += 1;
        } else {
            flush(&mut out, &mut run);
            out.push(c);
        }
    }
    flush(&mut out, &mut run);
    out
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
    check_writable(output)
}

/// Whether two paths name one existing file (through links and `..`).
pub fn same_file(a: &Path, b: &Path) -> bool {
    match (std::fs::canonicalize(a), std::fs::canonicalize(b)) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    }
}

/// The temporary file an atomic write of `path` goes through.
fn temporary_beside(path: &Path) -> std::io::Result<PathBuf> {
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let name = path
        .file_name()
        .ok_or_else(|| std::io::Error::new(std::io::ErrorKind::InvalidInput, "no file name"))?;
    Ok(dir.join(format!(
        ".{}.{}.tmp",
        name.to_string_lossy(),
        std::process::id()
    )))
}

/// Writes `bytes` to a temporary file beside `path`, then renames it over `path`.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let tmp = temporary_beside(path)?;
    let result = (|| {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
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
    #[test]
    fn runs_of_hashes_become_the_frame_number_padded_to_their_length() {
        use super::number_frame;
        assert_eq!(number_frame("frame_####.png", 12), "frame_0012.png");
        assert_eq!(number_frame("a#/b_##.exr", 7), "a7/b_07.exr");
        // A number longer than its run is written whole.
        assert_eq!(number_frame("f_##.png", 12345), "f_12345.png");
        assert_eq!(number_frame("plain.png", 3), "plain.png");
    }

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
        let bytes = pfm((3, 2), &|i| if i == 2 { v } else { Vec3::ZERO });
        let (w, h, px) = read_pfm(&bytes).unwrap();
        assert_eq!((w, h), (3, 2));
        assert_eq!(px[2], Vec3::new(1.0, 2.0, 3.0));
    }
}
