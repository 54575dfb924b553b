//! Image files → texels, header first: a file's header is read and checked
//! before a texel is allocated (its size against the limits, its size
//! against the file's length, then the caller's `admit`, which keeps a
//! scene's images within their total), and the texels are decoded straight
//! into their final layout (`texture::texels`: the file's own samples,
//! alpha dropped in place), never through a wider copy.
//!
//! A file too short for the texels its header claims is refused from its
//! length: no format packs texels tighter than
//! - PNG: deflate's densest code, 2 bits for a run of 258 bytes (a ratio of
//!   1032 : 1, over the pixels' bits alone);
//! - JPEG: one Huffman code of a bit at least per 8 × 8 block of every
//!   component (the first time a block is coded), and a component covers a
//!   sixteenth of the texels' blocks at least (sampling factors are at
//!   most 4): a bit per 256 texels;
//! - Radiance HDR: 4 bytes a scanline;
//! - OpenEXR: 16 bytes a chunk (its offset, its coordinates and size).
//!
//! While an image decodes, memory holds the file, the texels in their
//! final layout, and for a file with alpha a third more (dropped in
//! place), or for a progressive JPEG its coefficients (2 bytes a sample):
//! never more than 12 bytes a texel, as much as a float image holds.

use crate::source::human_bytes;
use crate::texture::texels::{Layout, Samples, Texels, MAX_TEXEL};
use std::io::Cursor;
use std::path::Path;

/// The formats ptsc reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Format {
    /// PNG (8 or 16 bits; grey, colour or palette).
    Png,
    /// Baseline or progressive JPEG.
    Jpeg,
    /// Radiance HDR (RGBE).
    Hdr,
    /// OpenEXR (its first layer with R, G and B channels).
    Exr,
}

impl Format {
    /// Every format.
    pub const ALL: [Format; 4] = [Format::Png, Format::Jpeg, Format::Hdr, Format::Exr];

    /// The `image` crate's format for the formats it decodes (`None`:
    /// OpenEXR, which the `exr` crate reads).
    fn raster(self) -> Option<image::ImageFormat> {
        match self {
            Format::Png => Some(image::ImageFormat::Png),
            Format::Jpeg => Some(image::ImageFormat::Jpeg),
            Format::Hdr => Some(image::ImageFormat::Hdr),
            Format::Exr => None,
        }
    }

    /// The format of the file `bytes` at `path`: by its first bytes when
    /// they are one of the four formats' signatures (a `.jpg` that is
    /// really a PNG decodes as the PNG it is, as image viewers open it),
    /// else by the extension.
    pub fn sniff(path: &Path, bytes: &[u8]) -> Result<Format, String> {
        const SIGNATURES: [(&[u8], Format); 5] = [
            (b"\x89PNG\r\n\x1a\n", Format::Png),
            (b"\xff\xd8\xff", Format::Jpeg),
            (b"#?RADIANCE", Format::Hdr),
            (b"#?RGBE", Format::Hdr),
            (b"\x76\x2f\x31\x01", Format::Exr),
        ];
        (SIGNATURES.iter())
            .find(|(magic, _)| bytes.starts_with(magic))
            .map_or_else(|| Format::of(path), |&(_, format)| Ok(format))
    }

    /// The format of the file at `path`, by its extension.
    pub fn of(path: &Path) -> Result<Format, String> {
        let ext = path.extension().and_then(|e| e.to_str());
        match ext.map(str::to_ascii_lowercase).as_deref() {
            Some("png") => Ok(Format::Png),
            Some("jpg" | "jpeg") => Ok(Format::Jpeg),
            Some("hdr") => Ok(Format::Hdr),
            Some("exr") => Ok(Format::Exr),
            _ => Err("unknown image format (expected .png, .jpg, .hdr or .exr)".into()),
        }
    }
}

/// What an image may claim, checked on its header.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limits {
    /// The longest side, in texels.
    pub side: u32,
    /// The most texels.
    pub texels: u64,
    /// The most bytes its texels may take in their final layout.
    pub bytes: u64,
}

/// What a file's header says it holds, read before any texel is allocated.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Header {
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// The layout its texels will take.
    pub layout: Layout,
}

impl Header {
    /// Its number of texels.
    pub fn texels(&self) -> u64 {
        self.width as u64 * self.height as u64
    }

    /// The bytes its texels will take.
    pub fn bytes(&self) -> u64 {
        self.texels() * self.layout.bytes_per_texel()
    }

    /// "W × H texels of LAYOUT (N)", for messages.
    pub fn describe(&self) -> String {
        format!(
            "{} × {} texels of {} ({})",
            self.width,
            self.height,
            self.layout.name(),
            human_bytes(self.bytes())
        )
    }
}

/// Decodes the image file `bytes` of `format`: its header first, refused
/// when it claims more than `limits` or than the file can hold, then
/// `admit`ted by the caller, and only then its texels.
pub fn decode(
    bytes: &[u8],
    format: Format,
    limits: &Limits,
    admit: impl FnOnce(&Header) -> Result<(), String>,
) -> Result<Texels, String> {
    match format.raster() {
        Some(raster) => decode_raster(bytes, raster, limits, admit),
        None => decode_exr(bytes, limits, admit),
    }
}

/// The alpha channel of the image file `bytes` as a grey image (8 or 16
/// bits, as stored), its header checked as [`decode`] checks one; an image
/// without alpha is opaque: one texel of 1. OpenEXR alpha is not read.
pub fn decode_alpha(
    bytes: &[u8],
    format: Format,
    limits: &Limits,
    admit: impl FnOnce(&Header) -> Result<(), String>,
) -> Result<Texels, String> {
    use image::ImageDecoder;
    let format =
        (format.raster()).ok_or("the alpha channel of an OpenEXR image is not read: use a PNG")?;
    let decoder = raster_decoder(bytes, format, limits)?;
    let (width, height) = decoder.dimensions();
    let color = decoder.color_type();
    use image::ColorType as C;
    let layout = match color {
        C::La8 | C::Rgba8 => Layout::Gray8,
        C::La16 | C::Rgba16 => Layout::Gray16,
        C::Rgba32F => return Err("the alpha channel of a float image is not read".into()),
        _ => {
            let opaque = Header {
                width: 1,
                height: 1,
                layout: Layout::Gray8,
            };
            admit(&opaque)?;
            return Ok(Texels::new(1, 1, Samples::Gray8(vec![u8::MAX])));
        }
    };
    let header = admitted(bytes, format, limits, (width, height, layout), admit)?;
    let channels = color.channel_count() as usize;
    let count = header.texels() as usize * channels;
    let samples = match layout {
        Layout::Gray8 => Samples::Gray8(keep_alpha(read(decoder, count)?, channels)),
        _ => Samples::Gray16(keep_alpha(read(decoder, count)?, channels)),
    };
    Ok(Texels::new(width as usize, height as usize, samples))
}

/// The `image` crate's decoder of `bytes`, its sides and allocations
/// within `limits`.
fn raster_decoder<'a>(
    bytes: &'a [u8],
    format: image::ImageFormat,
    limits: &Limits,
) -> Result<impl image::ImageDecoder + use<'a>, String> {
    let mut reader = image::ImageReader::with_format(Cursor::new(bytes), format);
    let mut image_limits = image::Limits::default();
    image_limits.max_image_width = Some(limits.side);
    image_limits.max_image_height = Some(limits.side);
    image_limits.max_alloc = Some(limits.bytes);
    reader.limits(image_limits);
    reader.into_decoder().map_err(cannot_decode)
}

/// Keeps the last sample (alpha) of every texel of `channels` samples, in
/// place.
fn keep_alpha<T: Copy>(mut v: Vec<T>, channels: usize) -> Vec<T> {
    let n = v.len() / channels;
    for i in 0..n {
        v[i] = v[i * channels + channels - 1];
    }
    v.truncate(n);
    v.shrink_to_fit();
    v
}

/// The header of a raster file of `width` × `height` texels in `layout`,
/// checked against `limits` and the file's length, then `admit`ted.
fn admitted(
    bytes: &[u8],
    format: image::ImageFormat,
    limits: &Limits,
    (width, height, layout): (u32, u32, Layout),
    admit: impl FnOnce(&Header) -> Result<(), String>,
) -> Result<Header, String> {
    let header = Header {
        width,
        height,
        layout,
    };
    check(&header, limits)?;
    check_length(bytes.len(), least_bytes(bytes, format, &header), &header)?;
    admit(&header)?;
    Ok(header)
}

fn cannot_decode(e: impl std::fmt::Display) -> String {
    format!("cannot decode the image: {e}")
}

/// Refuses a header that claims an empty image or more than `limits`.
fn check(header: &Header, limits: &Limits) -> Result<(), String> {
    let (w, h) = (header.width, header.height);
    if w == 0 || h == 0 {
        return Err("the image has no texels".into());
    }
    if w > limits.side || h > limits.side || header.texels() > limits.texels {
        let root = (limits.texels as f64).sqrt() as u64;
        let most = match root * root == limits.texels {
            true => format!("{root}²"),
            false => limits.texels.to_string(),
        };
        return Err(format!(
            "{w} × {h} texels is more than ptsc reads (at most {} a side and {most} in all)",
            limits.side
        ));
    }
    if header.bytes() > limits.bytes {
        return Err(format!(
            "{} is more than an image may take ({})",
            header.describe(),
            human_bytes(limits.bytes)
        ));
    }
    Ok(())
}

/// Refuses a file shorter than the least its header's texels take (see
/// the module's documentation).
fn check_length(len: usize, least: u64, header: &Header) -> Result<(), String> {
    if (len as u64) < least {
        return Err(format!(
            "the file has {len} bytes, too few for {} × {} texels (at least {least}): it is truncated or its header is wrong",
            header.width, header.height
        ));
    }
    Ok(())
}

/// The bits of a PNG's pixel as its IHDR gives them (bit depth × samples;
/// palette images count their index), 8 when it cannot be read.
fn png_pixel_bits(bytes: &[u8]) -> u64 {
    let (Some(&depth), Some(&colour)) = (bytes.get(24), bytes.get(25)) else {
        return 8;
    };
    let samples = match colour {
        2 => 3,
        4 => 2,
        6 => 4,
        _ => 1,
    };
    depth as u64 * samples
}

/// The least bytes a file of `format` holding `header`'s texels takes.
fn least_bytes(bytes: &[u8], format: image::ImageFormat, header: &Header) -> u64 {
    match format {
        image::ImageFormat::Png => (header.texels() * png_pixel_bits(bytes)).div_ceil(8) / 1032,
        image::ImageFormat::Jpeg => header.texels() / 2048,
        _ => 4 * header.height as u64,
    }
}

/// The layout an `image` colour type decodes into (alpha dropped).
fn layout_of(color: image::ColorType) -> Option<Layout> {
    use image::ColorType as C;
    Some(match color {
        C::L8 | C::La8 => Layout::Gray8,
        C::Rgb8 | C::Rgba8 => Layout::Rgb8,
        C::L16 | C::La16 => Layout::Gray16,
        C::Rgb16 | C::Rgba16 => Layout::Rgb16,
        C::Rgb32F | C::Rgba32F => Layout::RgbF32,
        _ => return None,
    })
}

/// PNG, JPEG and HDR through the `image` crate: its decoder reads the
/// header (refusing sides over the limit itself), then the texels go
/// straight into a buffer of the file's samples.
fn decode_raster(
    bytes: &[u8],
    format: image::ImageFormat,
    limits: &Limits,
    admit: impl FnOnce(&Header) -> Result<(), String>,
) -> Result<Texels, String> {
    use image::ImageDecoder;
    let decoder = raster_decoder(bytes, format, limits)?;
    let (width, height) = decoder.dimensions();
    let color = decoder.color_type();
    let layout = layout_of(color).ok_or_else(|| format!("{color:?} images are not read"))?;
    let header = admitted(bytes, format, limits, (width, height, layout), admit)?;
    let channels = color.channel_count() as usize;
    let count = header.texels() as usize * channels;
    let samples = match layout {
        Layout::Gray8 => Samples::Gray8(drop_alpha(read(decoder, count)?, channels)),
        Layout::Rgb8 => Samples::Rgb8(drop_alpha(read(decoder, count)?, channels)),
        Layout::Gray16 => Samples::Gray16(drop_alpha(read(decoder, count)?, channels)),
        Layout::Rgb16 => Samples::Rgb16(drop_alpha(read(decoder, count)?, channels)),
        Layout::RgbF32 => {
            let mut v = drop_alpha(read(decoder, count)?, channels);
            finite(&mut v)?;
            Samples::RgbF32(v)
        }
    };
    Ok(Texels::new(width as usize, height as usize, samples))
}

/// `count` zeroed samples, or an error where memory cannot hold them.
fn zeroed<T: bytemuck::Zeroable + Clone>(count: usize) -> Result<Vec<T>, String> {
    let mut v = Vec::new();
    v.try_reserve_exact(count).map_err(|_| {
        let bytes = (count * std::mem::size_of::<T>()) as u64;
        format!("not enough memory for its texels ({})", human_bytes(bytes))
    })?;
    v.resize(count, T::zeroed());
    Ok(v)
}

/// The decoder's `count` samples of type `T`, read into their own buffer.
fn read<T: bytemuck::Pod>(
    decoder: impl image::ImageDecoder,
    count: usize,
) -> Result<Vec<T>, String> {
    if decoder.total_bytes() != (count * std::mem::size_of::<T>()) as u64 {
        return Err(cannot_decode("its samples are not of the size it says"));
    }
    let mut v: Vec<T> = zeroed(count)?;
    decoder
        .read_image(bytemuck::cast_slice_mut(&mut v))
        .map_err(cannot_decode)?;
    Ok(v)
}

/// Drops the alpha sample of every texel of `channels` samples (2: grey
/// and alpha, 4: RGBA), in place.
fn drop_alpha<T: Copy>(mut v: Vec<T>, channels: usize) -> Vec<T> {
    if !channels.is_multiple_of(2) {
        return v;
    }
    let keep = channels - 1;
    let n = v.len() / channels;
    for i in 0..n {
        for c in 0..keep {
            v[i * keep + c] = v[i * channels + c];
        }
    }
    v.truncate(n * keep);
    v.shrink_to_fit();
    v
}

/// Refuses samples that are not finite or negative (a texture is a
/// colour) and caps the others at [`MAX_TEXEL`].
fn finite(samples: &mut [f32]) -> Result<(), String> {
    if samples.iter().any(|s| !s.is_finite() || *s < 0.0) {
        return Err("the image has texels that are not finite, non-negative numbers".into());
    }
    samples.iter_mut().for_each(|s| *s = s.min(MAX_TEXEL));
    Ok(())
}

/// An OpenEXR file's headers, read and checked before any sample: every
/// part's size against `limits` (and against `part_check`), the file's
/// length against its chunks (16 bytes each at least). Returns the largest
/// part's size, as an RGB float image.
fn exr_header(
    bytes: &[u8],
    limits: &Limits,
    part_check: impl Fn(&exr::meta::header::Header, &Header) -> Result<(), String>,
) -> Result<Header, String> {
    let mut cursor = Cursor::new(bytes);
    let meta =
        exr::meta::MetaData::read_from_buffered(&mut cursor, false).map_err(cannot_decode)?;
    let (mut largest, mut chunks) = (None::<Header>, 0u64);
    for part in meta.headers.iter() {
        let side = |n: usize| u32::try_from(n).unwrap_or(u32::MAX);
        let header = Header {
            width: side(part.layer_size.width()),
            height: side(part.layer_size.height()),
            layout: Layout::RgbF32,
        };
        check(&header, limits)?;
        part_check(part, &header)?;
        chunks += part.chunk_count as u64;
        if largest.is_none_or(|l| header.texels() > l.texels()) {
            largest = Some(header);
        }
    }
    let header = largest.ok_or_else(|| cannot_decode("the file has no image"))?;
    check_length(bytes.len(), cursor.position() + 16 * chunks, &header)?;
    Ok(header)
}

/// An OpenEXR image (linear): its headers and their chunk counts are read
/// first; every layer's size is checked, the file's length against its
/// chunks, and the largest layer admitted, before the first valid layer's
/// texels are allocated and read into them.
fn decode_exr(
    bytes: &[u8],
    limits: &Limits,
    admit: impl FnOnce(&Header) -> Result<(), String>,
) -> Result<Texels, String> {
    use exr::prelude::*;
    let header = exr_header(bytes, limits, |_, _| Ok(()))?;
    admit(&header)?;
    let prepared = std::cell::Cell::new(Some(zeroed::<f32>(3 * header.texels() as usize)?));
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .rgba_channels(
            |size, _| {
                // The layer read is one of those checked: at most the largest.
                let mut texels = prepared.take().unwrap_or_default();
                texels.resize(3 * size.area(), 0.0);
                (size.width(), texels)
            },
            |(w, texels): &mut (usize, Vec<f32>),
             p: Vec2<usize>,
             (r, g, b, _a): (f32, f32, f32, f32)| {
                let at = 3 * (p.y() * *w + p.x());
                if let Some(t) = texels.get_mut(at..at + 3) {
                    t.copy_from_slice(&[r, g, b]);
                }
            },
        )
        .first_valid_layer()
        .all_attributes()
        .from_buffered(Cursor::new(bytes))
        .map_err(cannot_decode)?;
    let size = image.layer_data.size;
    let (_, mut texels) = image.layer_data.channel_data.pixels;
    finite(&mut texels)?;
    Ok(Texels::new(
        size.width(),
        size.height(),
        Samples::RgbF32(texels),
    ))
}

/// Named channels of an OpenEXR image's first valid part: its size, and
/// for each name asked the channel's samples (row-major) or `None`.
pub type ExrChannels = (u32, u32, Vec<Option<Vec<f32>>>);

/// Decodes the channels `names` of an OpenEXR file (a render with its AOVs,
/// for `ptsc denoise`) under the discipline of [`decode`]: every part's
/// size is checked against `limits` from its header, with all of its
/// channels (the reader allocates each), the file's length against its
/// chunks, and only then are samples read; a sample that is not finite is
/// refused.
pub fn decode_exr_channels(
    bytes: &[u8],
    limits: &Limits,
    names: &[&str],
) -> Result<ExrChannels, String> {
    use exr::prelude::*;
    // The reader allocates every channel of the part it reads.
    exr_header(bytes, limits, |part, header| {
        let channels = part.channels.list.len();
        let all = 4 * header.texels() * channels as u64;
        if all <= limits.bytes {
            return Ok(());
        }
        Err(format!(
            "its {channels} channels of {} × {} take {}, more than ptsc reads ({})",
            header.width,
            header.height,
            human_bytes(all),
            human_bytes(limits.bytes)
        ))
    })?;
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .first_valid_layer()
        .all_attributes()
        .from_buffered(Cursor::new(bytes))
        .map_err(cannot_decode)?;
    let size = image.layer_data.size;
    let list = &image.layer_data.channel_data.list;
    let mut planes = Vec::with_capacity(names.len());
    for name in names {
        let found = list.iter().find(|c| c.name.to_string() == *name);
        let plane = found.map(|c| c.sample_data.values_as_f32().collect::<Vec<f32>>());
        if plane
            .as_ref()
            .is_some_and(|p| p.iter().any(|s| !s.is_finite()))
        {
            return Err(format!(
                "its channel {name} has samples that are not finite"
            ));
        }
        planes.push(plane);
    }
    Ok((size.width() as u32, size.height() as u32, planes))
}

#[cfg(test)]
#[path = "decode_tests.rs"]
mod tests;
