//! Issue 35, class 4: images are read header first. The largest image ptsc
//! accepts (16,384² texels) decodes into its final layout within a small
//! memory limit, used twice in two encodings and decoded once; headers
//! claiming more than the limits, or more than their file can hold, are
//! refused at once, before a texel is allocated; a scene's images stay
//! within their documented total, and the lowered scene says how many
//! bytes they take. Hostile files are generated here and run through the
//! binary under the hostile suite's memory and time limits.

use crate::hostile::{check_case, generated, CAMERA};
use glam::Vec3;
use ptsc::compile::{compile_str, Options};
use ptsc::lower::cache::LowerCache;
use ptsc::lower::image::Images;
use std::path::Path;

/// Writes a 1-bit grey PNG of `n` × `n` zeros: 33 KiB for 16,384², whose
/// texels took 3 GiB as linear f32 RGB (and 6 GB at the peak of decoding).
fn write_one_bit_png(path: &Path, n: u32) {
    let file = std::fs::File::create(path).unwrap();
    let mut e = png::Encoder::new(std::io::BufWriter::new(file), n, n);
    e.set_color(png::ColorType::Grayscale);
    e.set_depth(png::BitDepth::One);
    let mut w = e.write_header().unwrap();
    w.write_image_data(&vec![0u8; (n as usize).div_ceil(8) * n as usize])
        .unwrap();
    w.finish().unwrap();
}

/// A scene with a sphere whose colour and bump map are `file`.
fn textured(file: &str) -> String {
    format!(
        "{CAMERA}point_light {{ position <0, 5, 5> intensity rgb 10 }}\n\
         render {{ resolution <8, 8> samples 1 }}\n\
         sphere {{ center <0, 0, 0> radius 1 material {{ diffuse image {{ file \"{file}\" }} bump image {{ file \"{file}\" }} }} }}\n"
    )
}

#[test]
fn the_largest_image_decodes_once_within_a_small_memory() {
    let dir = tempfile::tempdir().unwrap();
    write_one_bit_png(&dir.path().join("bits.png"), 16_384);
    let scene = dir.path().join("bits_scene.pts");
    std::fs::write(&scene, textured("bits.png")).unwrap();
    // 256 MiB of 8-bit grey texels, read as a colour and as a height
    // field from the one decode: within 768 MiB of address space for the
    // whole process (the f32 copies of before needed 6 GB).
    for command in ["check {scene}", "render {scene} -o {out}.exr"] {
        let case = generated(
            command,
            &format!("// run: {command}\n// exit: 0\n// timeout: 30\n// memory: 768"),
        );
        check_case(&case, &scene, dir.path());
    }
}

/// A JPEG of 8 × 8 texels whose frame header claims `side` × `side`.
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

/// An OpenEXR scanline image's header (ZIP, three half channels) claiming
/// `side` × `side` texels, followed by `offsets` of its chunk offsets and
/// no chunk.
fn exr_claiming(side: i32, offsets: usize) -> Vec<u8> {
    fn attribute(out: &mut Vec<u8>, name: &str, kind: &str, value: &[u8]) {
        for s in [name, kind] {
            out.extend_from_slice(s.as_bytes());
            out.push(0);
        }
        out.extend_from_slice(&(value.len() as i32).to_le_bytes());
        out.extend_from_slice(value);
    }
    let mut channels = Vec::new();
    for c in ["B", "G", "R"] {
        channels.extend_from_slice(c.as_bytes());
        channels.push(0);
        // Half, linear, reserved, sampled 1 × 1.
        channels.extend_from_slice(&[1, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0]);
    }
    channels.push(0);
    let window: Vec<u8> = [0, 0, side - 1, side - 1]
        .iter()
        .flat_map(|v: &i32| v.to_le_bytes())
        .collect();
    let mut out = vec![0x76, 0x2f, 0x31, 0x01, 2, 0, 0, 0];
    attribute(&mut out, "channels", "chlist", &channels);
    attribute(&mut out, "compression", "compression", &[3]);
    attribute(&mut out, "dataWindow", "box2i", &window);
    attribute(&mut out, "displayWindow", "box2i", &window);
    attribute(&mut out, "lineOrder", "lineOrder", &[0]);
    attribute(&mut out, "pixelAspectRatio", "float", &1f32.to_le_bytes());
    attribute(&mut out, "screenWindowCenter", "v2f", &[0; 8]);
    attribute(&mut out, "screenWindowWidth", "float", &1f32.to_le_bytes());
    out.push(0);
    let end = (out.len() + 8 * offsets) as u64;
    for _ in 0..offsets {
        out.extend_from_slice(&end.to_le_bytes());
    }
    out
}

#[test]
fn headers_claiming_huge_images_are_refused_at_once() {
    let dir = tempfile::tempdir().unwrap();
    // Issue 35's reproductions: a 630-byte JPEG claiming 32,768² (decoded
    // for 21 s and 3.1 GB before it was refused), one claiming 16,384²
    // (accepted after 85 s and 6 GB), an EXR header claiming 16,384² with
    // no data (8 s and 3 GB per read), with its offset table and no
    // chunk.
    let files: [(&str, Vec<u8>, &str); 4] = [
        (
            "claims32k.jpg",
            jpeg_claiming(32_768),
            "more than ptsc reads",
        ),
        ("claims16k.jpg", jpeg_claiming(16_384), "too few"),
        ("header.exr", exr_claiming(16_384, 0), "too few"),
        ("offsets.exr", exr_claiming(16_384, 1024), "too few"),
    ];
    for (name, bytes, why) in files {
        std::fs::write(dir.path().join(name), bytes).unwrap();
        let scene = dir.path().join(format!("{name}.pts"));
        std::fs::write(&scene, textured(name)).unwrap();
        let env = dir.path().join(format!("{name}.env.pts"));
        std::fs::write(&env, format!("{CAMERA}environment {{ file \"{name}\" }}\n")).unwrap();
        for scene in [&scene, &env] {
            for command in ["check {scene}", "render {scene} -o {out}.png"] {
                let case = generated(
                    &format!("{name}: {command}"),
                    &format!("// run: {command}\n// exit: 1\n// stderr: {name}\n// stderr: {why}\n// timeout: 5\n// memory: 256"),
                );
                check_case(&case, scene, dir.path());
            }
        }
    }
}

#[test]
fn a_scenes_images_stay_within_their_total_named_when_crossed() {
    let dir = tempfile::tempdir().unwrap();
    for (name, n) in [("a.png", 64), ("b.png", 64)] {
        write_one_bit_png(&dir.path().join(name), n);
    }
    let text = format!(
        "{CAMERA}background rgb 1\n\
         sphere {{ center <0, 0, 0> radius 1 material {{ diffuse image {{ file \"a.png\" }} }} }}\n\
         sphere {{ center <2, 0, 0> radius 1 material {{ diffuse image {{ file \"b.png\" }} bump image {{ file \"a.png\" }} }} }}\n"
    );
    let path = dir.path().join("s.pts");
    let compile = |cache: &mut LowerCache| {
        let options = Options {
            cache: Some(cache),
            ..Options::default()
        };
        compile_str(&path, &text, options)
    };
    // Each file once: 2 × 64² bytes of grey.
    let mut cache = LowerCache::default();
    let c = compile(&mut cache);
    let ir = c.ir.expect("compiles");
    assert_eq!(ir.texture_bytes(), 2 * 64 * 64);
    assert_eq!(cache.images.decodes, 2);
    // With room for one of them: the second is refused, named, with the total.
    let mut cache = LowerCache::default();
    cache.images = Images::with_limit(6000);
    let c = compile(&mut cache);
    let report = c.diagnostics.render_human(&c.sources, false);
    assert!(c.ir.is_none(), "{report}");
    assert!(
        report.contains("cannot load image `") && report.contains("b.png"),
        "{report}"
    );
    assert!(
        report.contains("64 × 64 texels of 8-bit grey") && report.contains("together"),
        "{report}"
    );
}

#[test]
fn an_environment_maps_bytes_count_its_distribution() {
    let dir = tempfile::tempdir().unwrap();
    let exr = dir.path().join("sky.exr");
    ptsc::output::write_image(&exr, (8, 4), |i| Vec3::splat(1.0 + i as f32), 0.0).unwrap();
    write_one_bit_png(&dir.path().join("a.png"), 16);
    let text = format!(
        "{CAMERA}environment {{ file \"sky.exr\" }}\n\
         sphere {{ center <0, 0, 0> radius 1 material {{ diffuse image {{ file \"a.png\" }} gloss image {{ file \"a.png\" }} }} }}\n"
    );
    let c = compile_str(&dir.path().join("s.pts"), &text, Options::default());
    let ir = c.ir.expect("compiles");
    // The EXR's 32 float texels, its distribution over 8 × 3 cells (each
    // row's values and sums, and the marginal's), the PNG's 256 once.
    let distribution = 4 * (3 * (2 * 8 + 1) + 2 * 3 + 1);
    assert_eq!(ir.texture_bytes(), 32 * 12 + distribution + 256);
}

#[test]
fn the_largest_alpha_plane_decodes_within_a_small_memory() {
    // 16,384² texels of 8-bit grey and alpha (zeros: 260 KiB of file),
    // written a row at a time.
    let n = 16_384u32;
    let dir = tempfile::tempdir().unwrap();
    let file = std::fs::File::create(dir.path().join("alpha.png")).unwrap();
    let mut e = png::Encoder::new(std::io::BufWriter::new(file), n, n);
    e.set_color(png::ColorType::GrayscaleAlpha);
    e.set_depth(png::BitDepth::Eight);
    let mut w = e.write_header().unwrap();
    {
        use std::io::Write;
        let mut stream = w.stream_writer().unwrap();
        let row = vec![0u8; 2 * n as usize];
        for _ in 0..n {
            stream.write_all(&row).unwrap();
        }
        stream.finish().unwrap();
    }
    // The file is complete (its buffer flushed) before ptsc reads it.
    drop(w);
    let scene = dir.path().join("alpha_scene.pts");
    std::fs::write(
        &scene,
        format!(
            "{CAMERA}point_light {{ position <0, 5, 5> intensity rgb 10 }}\n\
             render {{ resolution <8, 8> samples 1 }}\n\
             sphere {{ center <0, 0, 0> radius 1 material {{ diffuse rgb 0.5\n\
               opacity image {{ file \"alpha.png\" channel a }} opacity_cutoff 0.5 }} }}\n"
        ),
    )
    .unwrap();
    // The decoder's 512 MiB of grey and alpha, of which the 256 MiB alpha
    // plane is kept: within 768 MiB of address space for the process.
    for command in ["check {scene}", "render {scene} -o {out}.exr"] {
        let case = generated(
            command,
            &format!("// run: {command}\n// exit: 0\n// timeout: 30\n// memory: 768"),
        );
        check_case(&case, &scene, dir.path());
    }
}
