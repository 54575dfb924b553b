//! Image files for textures: PNG and JPEG (8-bit: colours decoded from sRGB
//! to linear, data such as normal and bump maps read as they are),
//! Radiance HDR and OpenEXR (linear), each read once per compile (and kept
//! by `watch` while the file is unchanged), refused before allocation when
//! absurdly large.

use crate::texture::image::{srgb_to_linear, Image};
use glam::Vec3;
use std::collections::hash_map::DefaultHasher;
use std::collections::{HashMap, HashSet};
use std::hash::{Hash, Hasher};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::SystemTime;

/// The largest image file read, in bytes.
pub const MAX_IMAGE_BYTES: u64 = 1 << 30;
/// The longest side an image may have, in texels.
pub const MAX_IMAGE_SIDE: u32 = 32_768;
/// The most texels an image may have (16,384²: 3 GiB as linear f32 RGB).
pub const MAX_IMAGE_TEXELS: u64 = 1 << 28;

/// How an image's values become linear ones.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Encoding {
    /// By the file: 8-bit values through the sRGB curve, floating-point
    /// ones (HDR, EXR) as they are (colours, by default).
    ByFile,
    /// Every value as it is (data maps by default; `color_space linear`).
    Linear,
    /// Every value through the sRGB curve (`color_space srgb`).
    Srgb,
}

/// An image file as a texture reads it: its path and encoding.
type ImageKey = (PathBuf, Encoding);

/// The images read so far, each file read once per compile; kept between
/// compiles (`watch`) while the file's length, modification time and bytes
/// are unchanged.
#[derive(Debug, Default)]
pub struct Images {
    loaded: HashMap<ImageKey, CachedImage>,
    /// The keys read since the last [`Images::keep_only_used`].
    used: HashSet<ImageKey>,
    /// Image files decoded so far (a cache hit does not count).
    pub decodes: usize,
}

#[derive(Debug)]
struct CachedImage {
    stamp: (u64, Option<SystemTime>),
    content: u64,
    image: Arc<Image>,
}

fn stamp(path: &Path) -> (u64, Option<SystemTime>) {
    std::fs::metadata(path).map_or((u64::MAX, None), |m| (m.len(), m.modified().ok()))
}

impl Images {
    /// The image at `path` read with `encoding`, on first use; the error
    /// is a sentence for a diagnostic.
    pub fn get(&mut self, path: &Path, encoding: Encoding) -> Result<Arc<Image>, String> {
        let key = (path.to_path_buf(), encoding);
        let now = stamp(path);
        if let Some(c) = self.loaded.get(&key) {
            if self.used.contains(&key) || (c.stamp == now && now.1.is_some()) {
                self.used.insert(key.clone());
                return Ok(c.image.clone());
            }
        }
        let bytes = crate::source::read_file(path, MAX_IMAGE_BYTES)
            .map_err(|e| format!("cannot read the file: {e}"))?;
        let content = {
            let mut h = DefaultHasher::new();
            bytes.hash(&mut h);
            h.finish()
        };
        if let Some(c) = self.loaded.get_mut(&key) {
            if c.content == content {
                c.stamp = now;
                self.used.insert(key.clone());
                return Ok(c.image.clone());
            }
        }
        let image = Arc::new(decode_encoded(path, &bytes, encoding)?);
        self.decodes += 1;
        self.used.insert(key.clone());
        self.loaded.insert(
            key,
            CachedImage {
                stamp: now,
                content,
                image: image.clone(),
            },
        );
        Ok(image)
    }

    /// Forgets the images not read since the last call: a texture removed
    /// from the scene releases its memory at the next compile.
    pub fn keep_only_used(&mut self) {
        let used = std::mem::take(&mut self.used);
        self.loaded.retain(|k, _| used.contains(k));
    }
}

/// Reads and decodes an image file by its extension (`data`: 8-bit values
/// read linearly).
pub fn load(path: &Path, data: bool) -> Result<Image, String> {
    let bytes = crate::source::read_file(path, MAX_IMAGE_BYTES)
        .map_err(|e| format!("cannot read the file: {e}"))?;
    decode_file(path, &bytes, data)
}

/// [`decode_file`] with an encoding: 8-bit values read linearly unless
/// sRGB, floating-point ones put through the sRGB curve when `Srgb`.
fn decode_encoded(path: &Path, bytes: &[u8], encoding: Encoding) -> Result<Image, String> {
    let mut image = decode_file(path, bytes, encoding == Encoding::Linear)?;
    if encoding == Encoding::Srgb && is_floating_point(path) {
        for t in &mut image.texels {
            *t = Vec3::new(
                srgb_to_linear(t.x),
                srgb_to_linear(t.y),
                srgb_to_linear(t.z),
            );
        }
        image = finite(image)?;
    }
    Ok(image)
}

/// Whether the file holds floating-point values (HDR, EXR), by its name.
pub fn is_floating_point(path: &Path) -> bool {
    let ext = path.extension().and_then(|e| e.to_str());
    ext.is_some_and(|e| e.eq_ignore_ascii_case("hdr") || e.eq_ignore_ascii_case("exr"))
}

/// Decodes the bytes of the file at `path` by its extension (`data`: 8-bit
/// values read linearly).
fn decode_file(path: &Path, bytes: &[u8], data: bool) -> Result<Image, String> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let format = match ext.as_deref() {
        Some("png") => image::ImageFormat::Png,
        Some("jpg" | "jpeg") => image::ImageFormat::Jpeg,
        Some("hdr") => image::ImageFormat::Hdr,
        Some("exr") => return decode_exr(bytes),
        _ => return Err("unknown image format (expected .png, .jpg, .hdr or .exr)".into()),
    };
    decode(bytes, format, data)
}

/// Decodes `bytes` in `format` (PNG, JPEG: sRGB colours, or linear `data`;
/// HDR: linear).
pub fn decode(bytes: &[u8], format: image::ImageFormat, data: bool) -> Result<Image, String> {
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
    let texels = if format == image::ImageFormat::Hdr || data {
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

/// An OpenEXR image (linear): its headers are read first, and a layer
/// larger than ptsc reads is refused before its texels are allocated.
pub fn decode_exr(bytes: &[u8]) -> Result<Image, String> {
    use exr::prelude::*;
    let meta = exr::meta::MetaData::read_from_buffered(std::io::Cursor::new(bytes), false)
        .map_err(|e| format!("cannot decode the image: {e}"))?;
    for header in meta.headers.iter() {
        let (w, h) = (header.layer_size.width(), header.layer_size.height());
        let side = MAX_IMAGE_SIDE as usize;
        if w > side || h > side || (w as u64) * (h as u64) > MAX_IMAGE_TEXELS {
            return Err(format!("{w} × {h} texels is more than ptsc reads"));
        }
    }
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .rgba_channels(
            |size, _| (size.width(), vec![Vec3::ZERO; size.area()]),
            |(w, px): &mut (usize, Vec<Vec3>),
             p: Vec2<usize>,
             (r, g, b, _a): (f32, f32, f32, f32)| {
                if let Some(t) = px.get_mut(p.y() * *w + p.x()) {
                    *t = Vec3::new(r, g, b);
                }
            },
        )
        .first_valid_layer()
        .all_attributes()
        .from_buffered(std::io::Cursor::new(bytes))
        .map_err(|e| format!("cannot decode the image: {e}"))?;
    let size = image.layer_data.size;
    let (width, height) = (size.width(), size.height());
    if width == 0 || height == 0 {
        return Err("the image has no texels".into());
    }
    let (_, texels) = image.layer_data.channel_data.pixels;
    finite(crate::texture::image::Image {
        width,
        height,
        texels,
    })
}

/// Texels above this are read as it: the largest radiance the checker
/// accepts, so that a texel times any accepted scale stays finite in f32.
pub const MAX_TEXEL: f32 = 1e12;

/// Refuses texels that are not finite or negative (a texture is a colour)
/// and caps the others at [`MAX_TEXEL`].
fn finite(mut image: Image) -> Result<Image, String> {
    if image
        .texels
        .iter()
        .any(|t| !t.is_finite() || t.min_element() < 0.0)
    {
        return Err("the image has texels that are not finite, non-negative numbers".into());
    }
    for t in &mut image.texels {
        *t = t.min(Vec3::splat(MAX_TEXEL));
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
        let im = decode(&bytes, image::ImageFormat::Png, false).unwrap();
        assert_eq!((im.width, im.height), (2, 1));
        assert!((im.texels[0].x - 1.0).abs() < 1e-6 && im.texels[0].y == 0.0);
        // sRGB 128 is linear 0.2158.
        assert!((im.texels[0].z - 0.2158).abs() < 1e-3, "{}", im.texels[0].z);
        assert_eq!(im.texels[1], Vec3::ZERO);
        // Data (a normal map) is read as it is: 128 is 128 / 255.
        let data = decode(&bytes, image::ImageFormat::Png, true).unwrap();
        assert!((data.texels[0].z - 128.0 / 255.0).abs() < 1e-6);
    }

    #[test]
    fn exr_images_are_read_and_absurd_headers_refused_before_allocation() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.exr");
        let px = |i: usize| Vec3::new(i as f32, 0.5, 2.0);
        crate::output::write_image(&path, (3, 2), px, 0.0).unwrap();
        let mut bytes = std::fs::read(&path).unwrap();
        let im = decode_exr(&bytes).unwrap();
        assert_eq!((im.width, im.height), (3, 2));
        assert_eq!(im.texels[4], px(4));
        // The header claims a 100,000 × 100,000 data window: refused from
        // the header, before 120 GB of texels would be allocated.
        let name = b"dataWindow\0box2i\0";
        let at = bytes.windows(name.len()).position(|w| w == name).unwrap() + name.len() + 4;
        bytes[at + 8..at + 12].copy_from_slice(&99_999i32.to_le_bytes());
        bytes[at + 12..at + 16].copy_from_slice(&99_999i32.to_le_bytes());
        let e = decode_exr(&bytes).unwrap_err();
        assert!(e.contains("more than ptsc reads"), "{e}");
    }

    #[test]
    fn broken_and_absurd_images_are_errors_not_panics_or_allocations() {
        assert!(decode(b"not a png", image::ImageFormat::Png, false).is_err());
        let mut bytes = png(1, 1, &[1, 2, 3]);
        // Claim 100,000 × 100,000 in the header: refused before any allocation.
        bytes[16..20].copy_from_slice(&100_000u32.to_be_bytes());
        bytes[20..24].copy_from_slice(&100_000u32.to_be_bytes());
        assert!(decode(&bytes, image::ImageFormat::Png, false).is_err());
        assert!(load(Path::new("missing.png"), false).is_err());
        assert!(decode_file(Path::new("wood.gif"), b"GIF89a", false)
            .unwrap_err()
            .contains("unknown image format"));
        assert!(decode_exr(b"v/1\x01 not an exr").is_err());
    }
}
