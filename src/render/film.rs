//! The film: linear float accumulation, then PNG (sRGB, clamped, exposure),
//! OpenEXR (linear float32) or PFM. Every file is written atomically: to a
//! temporary file in the same folder, then renamed over the target, so a
//! failed or interrupted run never leaves a broken image.

use glam::Vec3;
use std::io::Write;
use std::path::{Path, PathBuf};

/// Accumulated radiance.
#[derive(Debug, Clone)]
pub struct Film {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Sum of samples per pixel, row-major.
    pub sum: Vec<Vec3>,
    /// Samples per pixel in every pixel (the passes that finished).
    pub samples: u32,
    /// Samples of a cancelled pass, per pixel, beyond `samples` (absent
    /// while every pixel has `samples`).
    pub extra: Option<Vec<u32>>,
}

impl Film {
    /// A black film.
    pub fn new(width: u32, height: u32) -> Film {
        Film {
            width,
            height,
            sum: vec![Vec3::ZERO; (width * height) as usize],
            samples: 0,
            extra: None,
        }
    }

    /// A film holding finished pixels (one sample each), e.g. to write an image read elsewhere.
    pub fn from_pixels(width: u32, height: u32, pixels: Vec<Vec3>) -> Film {
        assert_eq!(pixels.len(), (width * height) as usize);
        Film {
            width,
            height,
            sum: pixels,
            samples: 1,
            extra: None,
        }
    }

    /// Adds to a pixel's sum.
    pub fn add(&mut self, x: u32, y: u32, v: Vec3) {
        self.sum[(y * self.width + x) as usize] += v;
    }

    /// The mean radiance of each pixel.
    pub fn pixels(&self) -> Vec<Vec3> {
        (0..self.sum.len()).map(|i| self.pixel(i)).collect()
    }

    /// The mean radiance of pixel `i` (row-major); black without a sample.
    /// The encoders read pixels one by one: a copy of a 8192 × 8192 film is
    /// 805 MB.
    #[inline]
    pub fn pixel(&self, i: usize) -> Vec3 {
        let n = self.samples + self.extra.as_ref().map_or(0, |e| e[i]);
        self.sum[i] * (1.0 / n.max(1) as f32)
    }

    /// Adds `samples` samples of a pass that did not finish to a pixel.
    pub fn add_partial(&mut self, x: u32, y: u32, v: Vec3, samples: u32) {
        let i = (y * self.width + x) as usize;
        self.sum[i] += v;
        let n = self.sum.len();
        self.extra.get_or_insert_with(|| vec![0; n])[i] += samples;
    }

    /// Samples in every pixel, the most in any pixel, and the mean.
    pub fn sample_counts(&self) -> (u32, u32, f64) {
        match &self.extra {
            None => (self.samples, self.samples, self.samples as f64),
            Some(e) => {
                let min = e.iter().copied().min().unwrap_or(0);
                let max = e.iter().copied().max().unwrap_or(0);
                let mean = e.iter().map(|&n| n as f64).sum::<f64>() / e.len().max(1) as f64;
                (
                    self.samples + min,
                    self.samples + max,
                    self.samples as f64 + mean,
                )
            }
        }
    }

    /// Writes the image; the format follows the extension (.png, .exr, .pfm).
    pub fn write(&self, path: &Path, exposure: f32) -> std::io::Result<()> {
        let bytes = match ImageFormat::of(path) {
            Some(ImageFormat::Png) => self.png(exposure)?,
            Some(ImageFormat::Exr) => self.exr()?,
            Some(ImageFormat::Pfm) => self.pfm(),
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

    fn png(&self, exposure: f32) -> std::io::Result<Vec<u8>> {
        let scale = 2f32.powf(exposure);
        let mut rgb = Vec::with_capacity(self.sum.len() * 3);
        for i in 0..self.sum.len() {
            let p = self.pixel(i);
            for c in [p.x, p.y, p.z] {
                rgb.push((srgb_encode(c * scale) * 255.0 + 0.5) as u8);
            }
        }
        let mut out = Vec::new();
        image::codecs::png::PngEncoder::new(&mut out)
            .write_image(
                &rgb,
                self.width,
                self.height,
                image::ExtendedColorType::Rgb8,
            )
            .map_err(std::io::Error::other)?;
        Ok(out)
    }

    fn exr(&self) -> std::io::Result<Vec<u8>> {
        use exr::prelude::*;
        let w = self.width as usize;
        // ZIP compression: lossless and deterministic, and small references.
        let img = Image::from_encoded_channels(
            (self.width as usize, self.height as usize),
            Encoding::SMALL_LOSSLESS,
            SpecificChannels::rgb(|p: Vec2<usize>| {
                let v = self.pixel(p.y() * w + p.x());
                (v.x, v.y, v.z)
            }),
        );
        let mut cur = std::io::Cursor::new(Vec::new());
        img.write()
            .to_buffered(&mut cur)
            .map_err(std::io::Error::other)?;
        Ok(cur.into_inner())
    }

    fn pfm(&self) -> Vec<u8> {
        let mut out = format!("PF\n{} {}\n-1.0\n", self.width, self.height).into_bytes();
        // PFM rows go bottom to top.
        for y in (0..self.height).rev() {
            for x in 0..self.width {
                let v = self.pixel((y * self.width + x) as usize);
                for c in [v.x, v.y, v.z] {
                    out.extend(c.to_le_bytes());
                }
            }
        }
        out
    }
}

use image::ImageEncoder;

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
        let mut f = Film::new(2, 2);
        f.samples = 1;
        f.write(&p, 0.0).unwrap();
        let before = std::fs::read(&p).unwrap();
        assert!(f.write(&dir.path().join("img.bmp"), 0.0).is_err());
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
        Film::from_pixels(4, 3, px.clone()).write(&p, 0.0).unwrap();
        assert_eq!(read_exr(&p).unwrap(), (4, 3, px));
    }

    #[test]
    fn pfm_round_trip() {
        let mut f = Film::new(3, 2);
        f.samples = 1;
        f.add(2, 0, Vec3::new(1.0, 2.0, 3.0));
        let (w, h, px) = read_pfm(&f.pfm()).unwrap();
        assert_eq!((w, h), (3, 2));
        assert_eq!(px[2], Vec3::new(1.0, 2.0, 3.0));
    }
}
