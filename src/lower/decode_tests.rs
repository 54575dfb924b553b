use super::*;
use crate::texture::texels::Curve;
use glam::Vec3;

/// The limits ptsc reads images under.
const LIMITS: Limits = Limits {
    side: crate::lower::image::MAX_IMAGE_SIDE,
    texels: crate::lower::image::MAX_IMAGE_TEXELS,
    bytes: crate::lower::image::MAX_TEXTURE_BYTES,
};

/// A PNG of `samples` in `color`.
fn png(width: u32, height: u32, samples: &[u8], color: image::ExtendedColorType) -> Vec<u8> {
    use image::ImageEncoder;
    let mut out = Vec::new();
    image::codecs::png::PngEncoder::new(&mut out)
        .write_image(samples, width, height, color)
        .unwrap();
    out
}

/// CRC-32 (ISO 3309, as PNG's chunks carry it).
fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &b in bytes {
        crc ^= b as u32;
        for _ in 0..8 {
            crc = if crc & 1 == 1 {
                (crc >> 1) ^ 0xedb8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

/// Makes a PNG's header claim `width` × `height` (with a valid checksum).
fn claim_png(bytes: &mut [u8], width: u32, height: u32) {
    bytes[16..20].copy_from_slice(&width.to_be_bytes());
    bytes[20..24].copy_from_slice(&height.to_be_bytes());
    let crc = crc32(&bytes[12..29]);
    bytes[29..33].copy_from_slice(&crc.to_be_bytes());
}

/// Decodes with everything admitted; also returns what was admitted.
fn decoded(bytes: &[u8], format: Format) -> Result<(Texels, Header), String> {
    let mut admitted = None;
    let t = decode(bytes, format, &LIMITS, |h| {
        admitted = Some(*h);
        Ok(())
    })?;
    Ok((t, admitted.unwrap()))
}

/// Decodes; panics if `admit` is reached (the header alone must refuse it).
fn refused_from_header(bytes: &[u8], format: Format) -> String {
    decode(bytes, format, &LIMITS, |h| panic!("{h:?} was admitted")).unwrap_err()
}

#[test]
fn eight_bit_images_keep_their_samples_and_read_through_either_curve() {
    let bytes = png(
        2,
        1,
        &[255, 0, 128, 0, 0, 0],
        image::ExtendedColorType::Rgb8,
    );
    let (t, h) = decoded(&bytes, Format::Png).unwrap();
    assert_eq!(
        (t.width(), t.height(), t.layout(), t.bytes()),
        (2, 1, Layout::Rgb8, 6)
    );
    assert_eq!(h.bytes(), 6);
    let colour = t.get(0, Curve::Srgb);
    assert!((colour.x - 1.0).abs() < 1e-6 && colour.y == 0.0);
    // sRGB 128 is linear 0.2158.
    assert!((colour.z - 0.2158).abs() < 1e-3, "{}", colour.z);
    assert_eq!(t.get(1, Curve::Srgb), Vec3::ZERO);
    // Data (a normal map) reads the same samples as they are: 128 / 255.
    assert!((t.get(0, Curve::Linear).z - 128.0 / 255.0).abs() < 1e-6);
}

#[test]
fn alpha_is_dropped_and_grey_and_sixteen_bits_stay_as_they_are() {
    let rgba = png(
        1,
        2,
        &[10, 20, 30, 40, 50, 60, 70, 80],
        image::ExtendedColorType::Rgba8,
    );
    let (t, h) = decoded(&rgba, Format::Png).unwrap();
    assert_eq!((t.layout(), h.bytes(), t.bytes()), (Layout::Rgb8, 6, 6));
    assert_eq!(t.get(1, Curve::Linear), Vec3::new(50.0, 60.0, 70.0) / 255.0);
    let grey_alpha = png(2, 1, &[7, 1, 9, 2], image::ExtendedColorType::La8);
    let (t, _) = decoded(&grey_alpha, Format::Png).unwrap();
    assert_eq!((t.layout(), t.bytes()), (Layout::Gray8, 2));
    assert_eq!(t.get(1, Curve::Linear), Vec3::splat(9.0 / 255.0));
    // 16 bits: two bytes a sample.
    let samples: Vec<u8> = [65535u16, 32768, 1, 4660]
        .iter()
        .flat_map(|s| s.to_ne_bytes())
        .collect();
    let deep = png(1, 1, &samples, image::ExtendedColorType::Rgba16);
    let (t, _) = decoded(&deep, Format::Png).unwrap();
    assert_eq!((t.layout(), t.bytes()), (Layout::Rgb16, 6));
    assert_eq!(t.get(0, Curve::Linear).x, 1.0);
    assert_eq!(t.get(0, Curve::Linear).y, 32768.0 / 65535.0);
}

/// A 1-bit grey PNG of `n` × `n` zeros, compressed as tightly as the
/// encoder can.
fn one_bit_png(n: u32) -> Vec<u8> {
    let mut out = Vec::new();
    let mut e = png::Encoder::new(&mut out, n, n);
    e.set_color(png::ColorType::Grayscale);
    e.set_depth(png::BitDepth::One);
    e.set_compression(png::Compression::High);
    let mut w = e.write_header().unwrap();
    w.write_image_data(&vec![0u8; (n as usize).div_ceil(8) * n as usize])
        .unwrap();
    w.finish().unwrap();
    out
}

#[test]
fn a_one_bit_png_takes_a_byte_a_texel_and_its_length_is_plausible() {
    let bytes = one_bit_png(1024);
    let (t, h) = decoded(&bytes, Format::Png).unwrap();
    assert_eq!(
        (t.layout(), t.bytes(), h.bytes()),
        (Layout::Gray8, 1 << 20, 1 << 20)
    );
    // Its pixels take 1 bit each: its length is plausible for 1 bit, not 8.
    assert!((bytes.len() as u64) < (1 << 20) / 1032);
    // The same header over a cut-off stream: refused from its length.
    let mut claims = bytes[..bytes.len().min(60)].to_vec();
    claim_png(&mut claims, 16_384, 16_384);
    assert!(refused_from_header(&claims, Format::Png).contains("too few"));
}

#[test]
fn headers_claiming_too_much_are_refused_before_admission() {
    let mut bytes = png(1, 1, &[1, 2, 3], image::ExtendedColorType::Rgb8);
    claim_png(&mut bytes, 100_000, 100_000);
    refused_from_header(&bytes, Format::Png);
    // At the side limit but past the texel limit.
    claim_png(&mut bytes, 32_768, 32_768);
    assert!(refused_from_header(&bytes, Format::Png).contains("more than ptsc reads"));
    // Within the limits, but not in a file of 70 bytes.
    claim_png(&mut bytes, 16_384, 16_384);
    assert!(refused_from_header(&bytes, Format::Png).contains("too few"));
    // A limit on bytes: 2 × 2 RGB is 12 bytes.
    let small = Limits {
        bytes: 11,
        ..LIMITS
    };
    let four = png(2, 2, &[0; 12], image::ExtendedColorType::Rgb8);
    let e = decode(&four, Format::Png, &small, |_| panic!("admitted")).unwrap_err();
    assert!(e.contains("more than an image may take"), "{e}");
}

/// A JPEG of 8 × 8 grey texels whose frame header claims `side` × `side`.
fn jpeg_claiming(side: u16) -> Vec<u8> {
    let mut out = Vec::new();
    image::codecs::jpeg::JpegEncoder::new(&mut out)
        .encode(&[128u8; 8 * 8 * 3], 8, 8, image::ExtendedColorType::Rgb8)
        .unwrap();
    let sof = out.windows(2).position(|w| w == [0xff, 0xc0]).unwrap();
    out[sof + 5..sof + 7].copy_from_slice(&side.to_be_bytes());
    out[sof + 7..sof + 9].copy_from_slice(&side.to_be_bytes());
    out
}

#[test]
fn jpeg_headers_are_checked_against_the_limits_and_the_files_length() {
    let (t, _) = decoded(&jpeg_claiming(8), Format::Jpeg).unwrap();
    assert_eq!((t.width(), t.layout()), (8, Layout::Rgb8));
    // 32,768² (issue 35: decoded for 21 s and 3.1 GB, then refused).
    assert!(refused_from_header(&jpeg_claiming(32_768), Format::Jpeg).contains("more than"));
    // 16,384² in 630 bytes: a bit per 256 texels at least is 128 KiB.
    assert!(refused_from_header(&jpeg_claiming(16_384), Format::Jpeg).contains("too few"));
}

#[test]
fn exr_images_are_read_and_absurd_headers_refused_before_allocation() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.exr");
    let px = |i: usize| Vec3::new(i as f32, 0.5, 2.0);
    crate::output::write_image(&path, (3, 2), px, 0.0).unwrap();
    let mut bytes = std::fs::read(&path).unwrap();
    let (t, h) = decoded(&bytes, Format::Exr).unwrap();
    assert_eq!((t.width(), t.height(), h.bytes()), (3, 2, 72));
    assert_eq!(t.get(4, Curve::Linear), px(4));
    // The header claims 100,000² texels, then 16,384² (at the limit) with
    // a few hundred bytes for their chunks: both refused from the header.
    let name = b"dataWindow\0box2i\0";
    let at = bytes.windows(name.len()).position(|w| w == name).unwrap() + name.len() + 4;
    bytes[at + 8..at + 12].copy_from_slice(&99_999i32.to_le_bytes());
    bytes[at + 12..at + 16].copy_from_slice(&99_999i32.to_le_bytes());
    assert!(refused_from_header(&bytes, Format::Exr).contains("more than ptsc reads"));
    bytes[at + 8..at + 12].copy_from_slice(&16_383i32.to_le_bytes());
    bytes[at + 12..at + 16].copy_from_slice(&16_383i32.to_le_bytes());
    let e = refused_from_header(&bytes, Format::Exr);
    assert!(e.contains("too few") || e.contains("cannot decode"), "{e}");
}

#[test]
fn hdr_images_are_read_as_floats() {
    let mut bytes = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 2\n".to_vec();
    // Two flat RGBE texels: (0.5, 0.5, 0.5) and (2, 0, 1).
    bytes.extend_from_slice(&[128, 128, 128, 128, 128, 0, 64, 130]);
    let (t, _) = decoded(&bytes, Format::Hdr).unwrap();
    assert_eq!((t.layout(), t.bytes()), (Layout::RgbF32, 24));
    assert_eq!(t.get(0, Curve::Linear), Vec3::splat(0.5));
    assert_eq!(t.get(1, Curve::Linear), Vec3::new(2.0, 0.0, 1.0));
    // 2 billion rows claimed by 60 bytes.
    let mut huge = bytes.clone();
    let at = huge.windows(4).position(|w| w == b"-Y 1").unwrap();
    huge.splice(at..at + 4, b"-Y 16000".iter().copied());
    refused_from_header(&huge, Format::Hdr);
}

#[test]
fn broken_images_and_refused_admissions_are_errors_not_panics() {
    assert!(decoded(b"not a png", Format::Png).is_err());
    assert!(decoded(b"v/1\x01 not an exr", Format::Exr).is_err());
    assert!(Format::of(Path::new("wood.gif"))
        .unwrap_err()
        .contains("unknown image format"));
    assert_eq!(Format::of(Path::new("a.JPEG")), Ok(Format::Jpeg));
    // The caller's refusal is the error.
    let bytes = png(1, 1, &[1, 2, 3], image::ExtendedColorType::Rgb8);
    let e = decode(&bytes, Format::Png, &LIMITS, |_| Err("no room".into()));
    assert_eq!(e.unwrap_err(), "no room");
}

#[test]
fn a_file_is_decoded_as_its_first_bytes_say_whatever_its_extension() {
    let png_bytes = png(1, 1, &[1, 2, 3], image::ExtendedColorType::Rgb8);
    assert_eq!(
        Format::sniff(Path::new("photo.jpg"), &png_bytes),
        Ok(Format::Png)
    );
    assert!(decoded(
        &png_bytes,
        Format::sniff(Path::new("photo.jpg"), &png_bytes).unwrap()
    )
    .is_ok());
    for (bytes, format) in [
        (&b"\xff\xd8\xff\xe0 jfif"[..], Format::Jpeg),
        (b"#?RADIANCE\n", Format::Hdr),
        (b"#?RGBE\n", Format::Hdr),
        (b"v/1\x01", Format::Exr),
    ] {
        assert_eq!(Format::sniff(Path::new("a.png"), bytes), Ok(format));
    }
    // No signature: the extension decides, and says what it expects.
    assert_eq!(
        Format::sniff(Path::new("a.png"), b"not a png"),
        Ok(Format::Png)
    );
    assert!(Format::sniff(Path::new("a.gif"), b"GIF89a")
        .unwrap_err()
        .contains("unknown image format"));
    assert!(Format::sniff(Path::new("a.jpg"), b"").is_ok());
}

#[test]
fn exr_channels_are_read_by_name_and_absurd_headers_refused_before_allocation() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.exr");
    let albedo = [0.25f32; 6];
    let px = |i: usize| Vec3::new(i as f32, 0.5, 2.0);
    crate::output::write_exr_channels(&path, (3, 2), px, &[("albedo.R", &albedo)]).unwrap();
    let mut bytes = std::fs::read(&path).unwrap();
    let names = ["R", "albedo.R", "normal.X"];
    let (w, h, planes) = decode_exr_channels(&bytes, &LIMITS, &names).unwrap();
    assert_eq!((w, h), (3, 2));
    assert_eq!(
        planes[0].as_deref(),
        Some(&[0.0, 1.0, 2.0, 3.0, 4.0, 5.0][..])
    );
    assert_eq!(planes[1].as_deref(), Some(&albedo[..]));
    assert_eq!(planes[2], None);
    // Four channels of 16,384² floats are 4 GiB, more than the 1 MiB
    // allowed here; at the largest size allowed (16,384²) the chunks of a
    // few hundred bytes are too few: both refused from the header.
    let small = Limits {
        bytes: 1 << 20,
        ..LIMITS
    };
    let name = b"dataWindow\0box2i\0";
    let at = bytes.windows(name.len()).position(|w| w == name).unwrap() + name.len() + 4;
    bytes[at + 8..at + 12].copy_from_slice(&279i32.to_le_bytes());
    bytes[at + 12..at + 16].copy_from_slice(&279i32.to_le_bytes());
    let e = decode_exr_channels(&bytes, &small, &names).unwrap_err();
    assert!(
        e.contains("4 channels") && e.contains("more than ptsc reads"),
        "{e}"
    );
    bytes[at + 8..at + 12].copy_from_slice(&16_383i32.to_le_bytes());
    bytes[at + 12..at + 16].copy_from_slice(&16_383i32.to_le_bytes());
    let e = decode_exr_channels(&bytes, &LIMITS, &names).unwrap_err();
    assert!(e.contains("too few") || e.contains("cannot decode"), "{e}");
    assert!(decode_exr_channels(b"v/1\x01 not an exr", &LIMITS, &names).is_err());
}

#[test]
fn the_alpha_plane_keeps_the_alpha_samples_and_an_image_without_alpha_is_opaque() {
    use image::ExtendedColorType as C;
    let alpha = |bytes: &[u8], format: Format| {
        let mut admitted = None;
        let t = decode_alpha(bytes, format, &LIMITS, |h| {
            admitted = Some(*h);
            Ok(())
        });
        (t, admitted)
    };
    // RGBA: the fourth sample of each texel.
    let rgba = png(2, 1, &[10, 20, 30, 40, 50, 60, 70, 200], C::Rgba8);
    let (t, header) = alpha(&rgba, Format::Png);
    let t = t.unwrap();
    assert_eq!((t.width(), t.height(), t.layout()), (2, 1, Layout::Gray8));
    assert_eq!(header.unwrap().layout, Layout::Gray8);
    let linear = |t: &Texels, i: usize| t.get(i, Curve::Linear).x;
    assert_eq!(
        (linear(&t, 0), linear(&t, 1)),
        (40.0 / 255.0, 200.0 / 255.0)
    );
    // Grey and alpha, 16 bits.
    let la16: Vec<u8> = [1000u16, 65535, 2000, 7]
        .iter()
        .flat_map(|v| v.to_ne_bytes())
        .collect();
    let (t, _) = alpha(&png(2, 1, &la16, C::La16), Format::Png);
    let t = t.unwrap();
    assert_eq!(t.layout(), Layout::Gray16);
    assert_eq!((linear(&t, 0), linear(&t, 1)), (1.0, 7.0 / 65535.0));
    // No alpha: one opaque texel.
    let (t, _) = alpha(&png(2, 1, &[1, 2, 3, 4, 5, 6], C::Rgb8), Format::Png);
    let t = t.unwrap();
    assert_eq!((t.width(), t.height(), linear(&t, 0)), (1, 1, 1.0));
    // A header over the limits is refused before admission, as colours are.
    let mut huge = rgba.clone();
    claim_png(&mut huge, 1 << 20, 1 << 20);
    assert!(decode_alpha(&huge, Format::Png, &LIMITS, |h| panic!("{h:?} admitted")).is_err());
    assert!(alpha(b"not an exr", Format::Exr)
        .0
        .unwrap_err()
        .contains("OpenEXR"));
}
