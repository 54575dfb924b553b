//! Image files for textures: PNG and JPEG (8-bit colour, decoded from sRGB
//! to linear), Radiance HDR and OpenEXR (linear), each read once per
//! compile and refused before allocation when absurdly large.

use crate::texture::image::{srgb_to_linear, Image};
use glam::Vec3;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// The largest image file read, in bytes.
pub const MAX_IMAGE_BYTES: u64 = 1 << 30;
/// The longest side an image may have, in texels.
pub const MAX_IMAGE_SIDE: u32 = 32_768;
/// The most texels an image may have (16,384²: 3 GiB as linear f32 RGB).
pub const MAX_IMAGE_TEXELS: u64 = 1 << 28;

/// The images of one compile, each file read once.
#[derive(Debug, Default)]
pub struct Images {
    loaded: HashMap<PathBuf, Arc<Image>>,
}

impl Images {
    /// The image at `path`, read on first use; the error is a sentence for
    /// a diagnostic.
    pub fn get(&mut self, path: &Path) -> Result<Arc<Image>, String> {
        if let Some(image) = self.loaded.get(path) {
            return Ok(image.clone());
        }
        let image = Arc::new(load(path)?);
        self.loaded.insert(path.to_path_buf(), image.clone());
        Ok(image)
    }
}

/// Reads and decodes an image file by its extension.
pub fn load(path: &Path) -> Result<Image, String> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let format = match ext.as_deref() {
        Some("png") => image::ImageFormat::Png,
        Some("jpg" | "jpeg") => image::ImageFormat::Jpeg,
        Some("hdr") => image::ImageFormat::Hdr,
        Some("exr") => return load_exr(path),
        _ => return Err("unknown image format (expected .png, .jpg, .hdr or .exr)".into()),
    };
    let bytes = crate::source::read_file(path, MAX_IMAGE_BYTES)
        .map_err(|e| format!("cannot read the file: {e}"))?;
    decode(&bytes, format)
}

/// Decodes `bytes` in `format` (PNG, JPEG: sRGB; HDR: linear).
pub fn decode(bytes: &[u8], format: image::ImageFormat) -> Result<Image, String> {
    let mut reader = image::ImageReader::with_format(std::io::Cursor::new(bytes), format);
    let mut limits = image::Limits::default();
    limits.max_image_width = Some(MAX_IMAGE_SIDE);
    limits.max_image_height = Some(MAX_IMAGE_SIDE);
    limits.max_alloc = Some(4 * MAX_IMAGE_TEXELS * 4);
    reader.limits(limits);
    let decoded = reader
        .decode()
        .map_err(|e| format!("cannot decode the image: {e}"))?;
    let (width, height) = (decoded.width() as usize, decoded.height() as usize);
    if width == 0 || height == 0 {
        return Err("the image has no texels".into());
    }
    if (width as u64) * (height as u64) > MAX_IMAGE_TEXELS {
        return Err(format!("{width} × {height} texels is more than ptsc reads"));
    }
    let texels = if format == image::ImageFormat::Hdr {
        let rgb = decoded.into_rgb32f();
        rgb.pixels()
            .map(|p| Vec3::new(p[0], p[1], p[2]).max(Vec3::ZERO))
            .collect()
    } else {
        let rgb = decoded.into_rgb32f();
        rgb.pixels()
            .map(|p| {
                Vec3::new(
                    srgb_to_linear(p[0]),
                    srgb_to_linear(p[1]),
                    srgb_to_linear(p[2]),
                )
            })
            .collect()
    };
    finite(Image {
        width,
        height,
        texels,
    })
}

/// An OpenEXR image (linear), through the reader the tests use.
fn load_exr(path: &Path) -> Result<Image, String> {
    let meta = std::fs::metadata(path).map_err(|e| format!("cannot read the file: {e}"))?;
    if !meta.is_file() || meta.len() > MAX_IMAGE_BYTES {
        return Err("not a regular file of at most 1 GiB".into());
    }
    let (w, h, texels) = crate::output::read_exr(path)?;
    if w == 0 || h == 0 || (w as u64) * (h as u64) > MAX_IMAGE_TEXELS {
        return Err(format!("{w} × {h} texels is not an image ptsc reads"));
    }
    finite(Image {
        width: w as usize,
        height: h as usize,
        texels,
    })
}

/// Refuses texels that are not finite or negative (a texture is a colour).
fn finite(image: Image) -> Result<Image, String> {
    if image
        .texels
        .iter()
        .any(|t| !t.is_finite() || t.min_element() < 0.0)
    {
        return Err("the image has texels that are not finite, non-negative numbers".into());
    }
    Ok(image)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A PNG of the given 8-bit RGB texels.
    fn png(width: u32, height: u32, rgb: &[u8]) -> Vec<u8> {
        use image::ImageEncoder;
        let mut out = Vec::new();
        image::codecs::png::PngEncoder::new(&mut out)
            .write_image(rgb, width, height, image::ExtendedColorType::Rgb8)
            .unwrap();
        out
    }

    #[test]
    fn eight_bit_images_are_decoded_from_srgb() {
        let bytes = png(2, 1, &[255, 0, 128, 0, 0, 0]);
        let im = decode(&bytes, image::ImageFormat::Png).unwrap();
        assert_eq!((im.width, im.height), (2, 1));
        assert!((im.texels[0].x - 1.0).abs() < 1e-6 && im.texels[0].y == 0.0);
        // sRGB 128 is linear 0.2158.
        assert!((im.texels[0].z - 0.2158).abs() < 1e-3, "{}", im.texels[0].z);
        assert_eq!(im.texels[1], Vec3::ZERO);
    }

    #[test]
    fn broken_and_absurd_images_are_errors_not_panics_or_allocations() {
        assert!(decode(b"not a png", image::ImageFormat::Png).is_err());
        let mut bytes = png(1, 1, &[1, 2, 3]);
        // Claim 100,000 × 100,000 in the header: refused before any allocation.
        bytes[16..20].copy_from_slice(&100_000u32.to_be_bytes());
        bytes[20..24].copy_from_slice(&100_000u32.to_be_bytes());
        assert!(decode(&bytes, image::ImageFormat::Png).is_err());
        assert!(load(Path::new("missing.png")).is_err());
        assert!(load(Path::new("wood.gif"))
            .unwrap_err()
            .contains("unknown image format"));
    }
}
