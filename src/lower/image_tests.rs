use super::*;
use crate::source::Disk;

/// Writes a PNG of `n` × `n` 8-bit RGB texels of `value` (3n² bytes).
fn write_png(path: &Path, n: u32, value: u8) {
    use image::ImageEncoder;
    let mut out = Vec::new();
    let samples = vec![value; (3 * n * n) as usize];
    image::codecs::png::PngEncoder::new(&mut out)
        .write_image(&samples, n, n, image::ExtendedColorType::Rgb8)
        .unwrap();
    std::fs::write(path, out).unwrap();
}

#[test]
fn a_file_is_decoded_once_whatever_its_encodings() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("wood.png");
    write_png(&path, 4, 128);
    let mut images = Images::default();
    let colour = images.get(&Disk, &path, Encoding::ByFile).unwrap();
    let data = images.get(&Disk, &path, Encoding::Linear).unwrap();
    let srgb = images.get(&Disk, &path, Encoding::Srgb).unwrap();
    assert_eq!(images.decodes, 1);
    assert!(Arc::ptr_eq(colour.texels(), data.texels()));
    assert_eq!(colour.texel(0), srgb.texel(0));
    assert!((colour.texel(0).x - 0.2158).abs() < 1e-3);
    assert!((data.texel(0).x - 128.0 / 255.0).abs() < 1e-6);
    // Counted once, also through another path to it or a link.
    let sub = dir.path().join("sub");
    std::fs::create_dir(&sub).unwrap();
    images
        .get(&Disk, &sub.join("../wood.png"), Encoding::ByFile)
        .unwrap();
    #[cfg(unix)]
    {
        let link = dir.path().join("link.png");
        std::os::unix::fs::symlink(&path, &link).unwrap();
        images.get(&Disk, &link, Encoding::Linear).unwrap();
    }
    assert_eq!(images.decodes, 1);
    assert_eq!((images.scene_bytes(), images.held_bytes()), (48, 48));
}

#[test]
fn the_image_that_crosses_the_total_is_refused_and_named_with_it() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (dir.path().join("a.png"), dir.path().join("b.png"));
    write_png(&a, 8, 1);
    write_png(&b, 8, 2);
    // Room for one image of 8 × 8 RGB (192 bytes), not two.
    let mut images = Images::with_limit(300);
    images.get(&Disk, &a, Encoding::ByFile).unwrap();
    let e = images.get(&Disk, &b, Encoding::ByFile).unwrap_err();
    assert!(
        e.contains("8 × 8 texels of 8-bit RGB") && e.contains("together"),
        "{e}"
    );
    assert_eq!(images.decodes, 1, "refused from its header");
    // The same file again is no more bytes.
    images.get(&Disk, &a, Encoding::Linear).unwrap();
    // An environment map's distribution counts too.
    assert!(images.charge(100, "its sampling distribution").is_ok());
    let e = images.charge(100, "its sampling distribution").unwrap_err();
    assert!(e.contains("its sampling distribution takes"), "{e}");
}

#[test]
fn the_cache_forgets_unused_images_before_it_decodes_past_the_limit() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (dir.path().join("a.png"), dir.path().join("b.png"));
    write_png(&a, 8, 1);
    write_png(&b, 8, 2);
    let mut images = Images::with_limit(300);
    // A compile reads a, the next b: b is decoded after a is forgotten.
    images.get(&Disk, &a, Encoding::ByFile).unwrap();
    images.keep_only_used();
    let b_image = images.get(&Disk, &b, Encoding::ByFile).unwrap();
    assert!(images.held_bytes() <= 300);
    images.keep_only_used();
    assert_eq!(images.held_bytes(), 192);
    // Within the limit, both are kept while unused (watch flips between).
    let mut roomy = Images::with_limit(1000);
    roomy.get(&Disk, &a, Encoding::ByFile).unwrap();
    roomy.keep_only_used();
    roomy.get(&Disk, &b, Encoding::ByFile).unwrap();
    assert_eq!(roomy.held_bytes(), 384);
    // A changed file drops its old texels before the new ones decode.
    write_png(&b, 9, 3);
    let mut images = Images::with_limit(250);
    images.get(&Disk, &b, Encoding::ByFile).unwrap();
    images.keep_only_used();
    write_png(&b, 8, 4);
    let again = images.get(&Disk, &b, Encoding::ByFile).unwrap();
    assert_ne!(again.texel(0), b_image.texel(0));
    assert_eq!(images.held_bytes(), 192);
}
