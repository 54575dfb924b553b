//! Textures on every material input: colour maps and named textures,
//! numbers read from textures, normal and bump maps bending the shading
//! normal, textured emitters under light sampling, and images kept across
//! `watch` compiles.

use glam::Vec3;
use ptsc::compile::{compile_str, Options};
use ptsc::geometry::Ray;
use ptsc::integrator;
use ptsc::ir::{Hit, Scene};
use ptsc::lower::cache::LowerCache;
use std::path::Path;
use std::sync::atomic::AtomicBool;

/// A wall in the plane z = 0 from (−4, −4) to (4, 4), facing +z, with
/// `material`, under a white sky; compiled without diagnostics.
fn wall(scene_path: &Path, before: &str, material: &str) -> Scene {
    let text = format!(
        "camera {{ position <0, 0, 9> look_at <0, 0, 0> }}\nbackground rgb 1\n{before}\n\
         quad {{ corner <-4, -4, 0> edge1 <8, 0, 0> edge2 <0, 8, 0> material {{ {material} }} }}\n"
    );
    let c = compile_str(scene_path, &text, Options::default());
    assert!(
        c.diagnostics.items.is_empty(),
        "{}",
        c.diagnostics.render_human(&c.sources, false)
    );
    c.ir.expect("the scene compiles")
}

/// The hit straight down the z axis at (x, y), its material evaluated (and
/// its shading normal set).
fn shade(ir: &Scene, x: f32, y: f32) -> (Hit, ptsc::material::Material) {
    let ray = Ray::new(Vec3::new(x, y, 9.0), -Vec3::Z, 0.0);
    let mut hit = ir.intersect(&ray, 0.0, f32::INFINITY).expect("the wall");
    let mut slot = None;
    let m = ir.material_at(&mut hit, -ray.d, 0.0, &mut slot).clone();
    (hit, m)
}

#[test]
fn named_textures_and_colour_maps_give_colours_and_numbers() {
    // One named texture for two materials: the wall's colour and the
    // roughness of a glossy strip in front of it (y from 2 to 3).
    let ir = wall(
        Path::new("t.pts"),
        "texture ramp gradient { space world stop 0 rgb 0 stop 0.5 rgb 1 stop 1 rgb 0.5 }\n\
         quad { corner <-4, 2, 1> edge1 <8, 0, 0> edge2 <0, 1, 0> \
                material { reflection rgb 0.5 gloss ramp } }",
        "diffuse ramp",
    );
    // The ramp along x, one period per unit, through the stops.
    for (x, want) in [(0.25, 0.5), (0.5, 1.0), (0.75, 0.75), (2.25, 0.5)] {
        let (_, m) = shade(&ir, x, 0.3);
        assert!((m.diffuse.x - want).abs() < 1e-4, "x {x}: {}", m.diffuse);
    }
    // `gloss` reads the texture's luminance: a rougher surface where the
    // ramp is higher.
    let alpha = |x| shade(&ir, x, 2.5).1.alpha;
    assert!(alpha(0.5) > alpha(0.75) && alpha(0.75) > alpha(0.25) && alpha(0.25) > 0.0);
    // Stripes read the map at 0 and 1.
    let ir = wall(
        Path::new("t.pts"),
        "",
        "diffuse stripes { space world low rgb 0.2 high rgb 0.6 scale 0.5 }",
    );
    let d = |x| shade(&ir, x, 0.0).1.diffuse.x;
    assert!((d(0.25) - 0.2).abs() < 1e-6 && (d(0.75) - 0.6).abs() < 1e-6);
    assert!((d(1.25) - 0.2).abs() < 1e-6 && (d(-0.25) - 0.6).abs() < 1e-6);
}

#[test]
fn a_bump_map_tilts_the_shading_normal_against_the_slope() {
    // Height rising by 0.1 per unit of x (a gradient's ramp times 0.1).
    let ir = wall(
        Path::new("t.pts"),
        "",
        "diffuse rgb 0.5 bump gradient { space world } bump_height 0.1",
    );
    let (hit, _) = shade(&ir, 0.3, 0.2);
    let want = Vec3::new(-0.1, 0.0, 1.0).normalize();
    assert!((hit.n_shading - want).length() < 2e-3, "{}", hit.n_shading);
    assert_eq!(hit.n_geo, Vec3::Z);
    // Turned by 90° about z, the slope runs along y.
    let ir = wall(
        Path::new("t.pts"),
        "",
        "diffuse rgb 0.5 bump gradient { space world rotate <0, 0, 90> } bump_height 0.1",
    );
    let (hit, _) = shade(&ir, 0.3, 0.2);
    let want = Vec3::new(0.0, -0.1, 1.0).normalize();
    assert!((hit.n_shading - want).length() < 2e-3, "{}", hit.n_shading);
}

/// A PNG of one texel of 8-bit RGB.
fn write_texel(path: &Path, rgb: [u8; 3]) {
    use image::ImageEncoder;
    let mut out = Vec::new();
    image::codecs::png::PngEncoder::new(&mut out)
        .write_image(&rgb, 1, 1, image::ExtendedColorType::Rgb8)
        .unwrap();
    std::fs::write(path, out).unwrap();
}

#[test]
fn a_normal_map_is_data_in_the_tangent_frame() {
    let dir = tempfile::tempdir().unwrap();
    // Half way between the tangent (+x, the quad's edge1) and the normal,
    // read linearly: (255, 128, 255) is (1, 0.004, 1) after 2c − 1; as an
    // sRGB colour it would be (1, −0.57, 1).
    write_texel(&dir.path().join("n.png"), [255, 128, 255]);
    let ir = wall(
        &dir.path().join("s.pts"),
        "",
        "diffuse rgb 0.5 normal_map image { file \"n.png\" }",
    );
    let (hit, _) = shade(&ir, 0.1, 0.1);
    let want = Vec3::new(1.0, 1.0 / 255.0, 1.0).normalize();
    assert!((hit.n_shading - want).length() < 1e-4, "{}", hit.n_shading);
    // The same image as a colour is decoded from sRGB.
    let ir = wall(
        &dir.path().join("s.pts"),
        "",
        "diffuse image { file \"n.png\" }",
    );
    let (_, m) = shade(&ir, 0.1, 0.1);
    assert!((m.diffuse.y - 0.2158).abs() < 1e-3, "{}", m.diffuse);
}

/// The mean of the left and of the right half of an image rendered with or
/// without light sampling.
fn half_means(text: &str, light_sampling: bool) -> [Vec3; 2] {
    let c = compile_str(Path::new("t.pts"), text, Options::default());
    let mut ir =
        c.ir.unwrap_or_else(|| panic!("{}", c.diagnostics.render_human(&c.sources, false)));
    ir.settings.light_sampling = light_sampling;
    let integ = integrator::make(ir.settings.integrator, &ir);
    let px = ptsc::render::render(
        &ir,
        integ.as_ref(),
        &AtomicBool::new(false),
        &|_| {},
        &mut |_, _| {},
    )
    .film
    .pixels();
    let w = ir.settings.width as usize;
    let mut halves = [Vec3::ZERO; 2];
    for (i, p) in px.iter().enumerate() {
        halves[(i % w >= w / 2) as usize] += *p / (px.len() / 2) as f32;
    }
    halves
}

#[test]
fn a_textured_emitter_is_sampled_with_its_texture() {
    // A floor lit only by a lamp whose left half emits 8 and right half
    // nothing (stripes in u): next-event estimation (reading the texture
    // at the sampled point) and BSDF sampling alone (reading it where rays
    // hit) agree on each half of the image, and the left half is brighter.
    let scene = "render { resolution <8, 8> samples 1024 max_depth 2 }\n\
         camera { position <0, 3, 3> look_at <0, 0, 0> fov 50 }\n\
         quad { corner <-2, 0, 2> edge1 <4, 0, 0> edge2 <0, 0, -4> material { diffuse rgb 0.8 } }\n\
         quad { corner <-1, 1, -1> edge1 <2, 0, 0> edge2 <0, 0, 2>\n\
                material { emission stripes { low rgb 8 high rgb 0 scale 0.5 } } }\n";
    let with_nee = half_means(scene, true);
    let without = half_means(scene, false);
    for (a, b) in with_nee.iter().zip(&without) {
        let relative = ((*a - *b) / *b).abs().max_element();
        assert!(
            relative < 0.04,
            "NEE {with_nee:?} vs BSDF sampling {without:?}"
        );
    }
    assert!(with_nee[0].x > 1.3 * with_nee[1].x, "{with_nee:?}");
}

/// A PNG of 2 × 1 texels.
fn write_pair(path: &Path, a: u8, b: u8) {
    use image::ImageEncoder;
    let mut out = Vec::new();
    image::codecs::png::PngEncoder::new(&mut out)
        .write_image(&[a, a, a, b, b, b], 2, 1, image::ExtendedColorType::Rgb8)
        .unwrap();
    std::fs::write(path, out).unwrap();
}

#[test]
fn images_are_kept_across_watch_compiles_until_their_file_changes() {
    let dir = tempfile::tempdir().unwrap();
    let image = dir.path().join("wood.png");
    write_pair(&image, 10, 200);
    let path = dir.path().join("s.pts");
    let text = "camera { position <0, 0, 9> look_at <0, 0, 0> }\nbackground rgb 1\n\
        quad { corner <-4, -4, 0> edge1 <8, 0, 0> edge2 <0, 8, 0> material { diffuse image { file \"wood.png\" } } }\n\
        sphere { center <0, 0, -3> radius 1 material { diffuse image { file \"wood.png\" } bump image { file \"wood.png\" } } }\n";
    let mut cache = LowerCache::default();
    // Compiles `text` with the cache; the image decodes so far.
    let mut compile = |text: &str| {
        let options = Options {
            cache: Some(&mut cache),
            ..Options::default()
        };
        let c = compile_str(&path, text, options);
        assert!(
            c.ir.is_some(),
            "{}",
            c.diagnostics.render_human(&c.sources, false)
        );
        cache.images.decodes
    };
    // One file read as a colour and as data: decoded once (issue 35), the
    // two encodings read the same texels.
    assert_eq!(compile(text), 1);
    assert_eq!(
        compile(&text.replace("background rgb 1", "background rgb 0.5")),
        1
    );
    // The file rewritten with the same bytes (touched): not decoded again.
    std::thread::sleep(std::time::Duration::from_millis(20));
    write_pair(&image, 10, 200);
    assert_eq!(compile(text), 1);
    // New texels: decoded again, once.
    std::thread::sleep(std::time::Duration::from_millis(20));
    write_pair(&image, 10, 201);
    assert_eq!(compile(text), 2);
}
