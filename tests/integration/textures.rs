//! Textures from the scene language to the pixels: checked, lowered,
//! evaluated at each hit (`Scene::material_at`) in their space, seen by every
//! integrator.

use glam::{Vec2, Vec3};
use ptsc::compile::{compile_str, Options};
use ptsc::geometry::Ray;
use ptsc::integrator;
use ptsc::ir::Scene;
use std::path::Path;
use std::sync::atomic::AtomicBool;

const EVEN: f32 = 0.9;
const ODD: f32 = 0.1;

/// A unit quad facing the camera under a white sky, its diffuse colour a
/// checker in (u, v): four cells, as Mitsuba's `checkerboard`.
fn checkered_quad(integrator: &str) -> Scene {
    let text = format!(
        "render {{ resolution <16, 16> samples 64 integrator {integrator} max_depth 2 }}\n\
         camera {{ position <0.5, 0.5, 2> look_at <0.5, 0.5, 0> fov 28.07 }}\n\
         background rgb 1\n\
         quad {{ corner <0, 0, 0> edge1 <1, 0, 0> edge2 <0, 1, 0>\n\
                material {{ diffuse checker {{ even rgb {EVEN} odd rgb {ODD} }} }} }}\n"
    );
    let c = compile_str(Path::new("t.pts"), &text, Options::default());
    assert!(c.diagnostics.items.is_empty(), "{:?}", c.diagnostics.items);
    c.ir.expect("the scene compiles")
}

/// The texture's colour at the world point `p` of a one-object scene
/// whose material's diffuse is `texture`.
fn colour_at(object: &str, texture: &str, p: [f32; 3]) -> f32 {
    let text = format!(
        "camera {{ position <0, 0, 9> look_at <0, 0, 0> }}\nbackground rgb 1\n\
         {object} material {{ diffuse {texture} }} }}\n"
    );
    let c = compile_str(Path::new("t.pts"), &text, Options::default());
    let ir =
        c.ir.unwrap_or_else(|| panic!("{}", c.diagnostics.render_human(&c.sources, false)));
    // A ray straight down the z axis through (p.x, p.y).
    let ray = Ray::new(Vec3::new(p[0], p[1], 9.0), -Vec3::Z, 0.0);
    let mut hit = ir.intersect(&ray, 0.0, f32::INFINITY).expect("a hit");
    assert!((hit.p.z - p[2]).abs() < 1e-4, "hit at {}", hit.p);
    ir.material_at(&mut hit, -ray.d, 0.0, &mut None).diffuse.x
}

#[test]
fn spaces_and_transforms_of_a_checker() {
    let checker = |extra: &str| format!("checker {{ even rgb 1 odd rgb 0 {extra} }}");
    let wall = "quad { corner <-4, -4, 0> edge1 <8, 0, 0> edge2 <0, 8, 0> translate <0.25, 0, 0>";
    // World space: unit cubes of the world, whatever the object does.
    assert_eq!(
        colour_at(wall, &checker("space world"), [0.5, 0.5, 0.0]),
        1.0
    );
    assert_eq!(
        colour_at(wall, &checker("space world"), [1.5, 0.5, 0.0]),
        0.0
    );
    // Object space: the cubes move with the object (translated by 0.25).
    assert_eq!(
        colour_at(wall, &checker("space object"), [0.2, 0.5, 0.0]),
        0.0
    );
    assert_eq!(
        colour_at(wall, &checker("space object"), [0.3, 0.5, 0.0]),
        1.0
    );
    // Scaled by 2: cells twice as large.
    assert_eq!(
        colour_at(wall, &checker("space world scale 2"), [1.5, 0.5, 0.0]),
        1.0
    );
    assert_eq!(
        colour_at(wall, &checker("space world scale 2"), [2.5, 0.5, 0.0]),
        0.0
    );
    // (u, v): the 8 × 8 wall's unit square holds 2 × 2 cells of 4 units.
    assert_eq!(colour_at(wall, &checker(""), [-2.0, -2.0, 0.0]), 1.0);
    assert_eq!(colour_at(wall, &checker(""), [2.0, -2.0, 0.0]), 0.0);
    // Translated by a quarter of (u, v): the cell boundary moves by 2 units.
    assert_eq!(
        colour_at(wall, &checker("translate <0.25, 0, 0>"), [2.0, -2.0, 0.0]),
        1.0
    );
}

#[test]
fn a_textured_colour_is_evaluated_at_each_hit() {
    let ir = checkered_quad("path");
    let at = |u: f32, v: f32| {
        let ray = Ray::new(Vec3::new(u, v, 1.0), -Vec3::Z, 0.0);
        let mut hit = ir.intersect(&ray, 0.0, f32::INFINITY).expect("the quad");
        assert!(
            (ir.texcoords(&hit, 0.0) - Vec2::new(u, v))
                .abs()
                .max_element()
                < 1e-5
        );
        ir.material_at(&mut hit, -ray.d, 0.0, &mut None).diffuse.x
    };
    assert!((at(0.25, 0.25) - EVEN).abs() < 1e-6);
    assert!((at(0.75, 0.25) - ODD).abs() < 1e-6);
    assert!((at(0.25, 0.75) - ODD).abs() < 1e-6);
    assert!((at(0.75, 0.75) - EVEN).abs() < 1e-6);
}

/// The mean of each quarter of a 16 × 16 image.
fn quarters(ir: &Scene) -> [f32; 4] {
    let integ = integrator::make(ir.settings.integrator, ir);
    let film = ptsc::render::render(
        ir,
        integ.as_ref(),
        &AtomicBool::new(false),
        &|_| {},
        &mut |_, _| {},
    )
    .film;
    let px = film.pixels();
    let mut sums = [0.0f32; 4];
    for y in 0..16 {
        for x in 0..16 {
            // Image rows go down; v goes up.
            let q = (x / 8) + 2 * (1 - y / 8);
            sums[q as usize] += px[(y * 16 + x) as usize].x / 64.0;
        }
    }
    sums
}

#[test]
fn every_integrator_sees_the_texture() {
    // Albedo: exact. Path: a diffuse surface under a white sky of radiance 1
    // reflects its albedo (the quad sees the sky only), within noise (64
    // samples in each of 64 pixels per quarter: about 1 %).
    // Whitted: the sky is a light it samples with shadow rays, the same.
    for (integrator, tolerance) in [("albedo", 1e-6), ("path", 0.03), ("whitted", 0.03)] {
        let q = quarters(&checkered_quad(integrator));
        let expect = [EVEN, ODD, ODD, EVEN];
        for i in 0..4 {
            assert!(
                (q[i] - expect[i]).abs() <= tolerance * expect[i],
                "{integrator}: quarter {i} is {} (expected {})",
                q[i],
                expect[i]
            );
        }
    }
}

/// A PNG of 2 × 2 texels: top row red, green; bottom row blue, white.
fn write_png(path: &Path) {
    use image::ImageEncoder;
    let rgb = [255u8, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255];
    let mut out = Vec::new();
    image::codecs::png::PngEncoder::new(&mut out)
        .write_image(&rgb, 2, 2, image::ExtendedColorType::Rgb8)
        .unwrap();
    std::fs::write(path, out).unwrap();
}

#[test]
fn an_image_texture_is_read_once_bilinear_and_a_dependency() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("maps")).unwrap();
    write_png(&dir.path().join("maps/rgbw.png"));
    let scene = dir.path().join("s.pts");
    let text = "camera { position <0.5, 0.5, 2> look_at <0.5, 0.5, 0> }\nbackground rgb 1\n\
        material m { diffuse image { file \"maps/rgbw.png\" wrap clamp } }\n\
        quad { corner <0, 0, 0> edge1 <1, 0, 0> edge2 <0, 1, 0> material m }\n\
        quad { corner <2, 0, 0> edge1 <1, 0, 0> edge2 <0, 1, 0> material m }\n";
    let c = compile_str(&scene, text, Options::default());
    let ir =
        c.ir.unwrap_or_else(|| panic!("{}", c.diagnostics.render_human(&c.sources, false)));
    assert!(c.dependencies.iter().any(|d| d.ends_with("maps/rgbw.png")));
    // One material, one texture, one image read once.
    let at = |u: f32, v: f32| {
        let ray = Ray::new(Vec3::new(u, v, 1.0), -Vec3::Z, 0.0);
        let mut hit = ir.intersect(&ray, 0.0, f32::INFINITY).expect("the quad");
        ir.material_at(&mut hit, -ray.d, 0.0, &mut None).diffuse
    };
    // Texel centres; the bottom-left texel is blue. Diffuse colours are
    // the image's, scaled only if the lobes exceed 1 (they do not).
    assert!((at(0.25, 0.25) - Vec3::Z).abs().max_element() < 1e-5);
    assert!((at(0.25, 0.75) - Vec3::X).abs().max_element() < 1e-5);
    assert!((at(0.75, 0.75) - Vec3::Y).abs().max_element() < 1e-5);
    // Bilinear between the bottom texels.
    assert!(
        (at(0.5, 0.25) - Vec3::new(0.5, 0.5, 1.0))
            .abs()
            .max_element()
            < 1e-5
    );

    // A PNG saved under another image extension is read as the PNG it is.
    std::fs::copy(
        dir.path().join("maps/rgbw.png"),
        dir.path().join("maps/rgbw.jpg"),
    )
    .unwrap();
    let c = compile_str(
        &scene,
        &text.replace("rgbw.png", "rgbw.jpg"),
        Options::default(),
    );
    let named_jpg =
        c.ir.unwrap_or_else(|| panic!("{}", c.diagnostics.render_human(&c.sources, false)));
    let ray = Ray::new(Vec3::new(0.25, 0.25, 1.0), -Vec3::Z, 0.0);
    let mut hit = named_jpg
        .intersect(&ray, 0.0, f32::INFINITY)
        .expect("the quad");
    let texel = named_jpg
        .material_at(&mut hit, -ray.d, 0.0, &mut None)
        .diffuse;
    assert!((texel - Vec3::Z).abs().max_element() < 1e-5);

    // A missing image: a diagnostic on the file name, the scene not rendered.
    let text = text.replace("maps/rgbw.png", "maps/none.png");
    let c = compile_str(&scene, &text, Options::default());
    assert!(c.ir.is_none());
    let d = c.diagnostics.items.iter().find(|d| d.is_error()).unwrap();
    assert_eq!(d.code, "pts::lower::image_file");
    let span = d.span.unwrap();
    assert_eq!(
        &text[span.start as usize..span.end as usize],
        "\"maps/none.png\""
    );
}

#[test]
fn noise_patterns_blend_their_colours_by_the_pattern_in_its_space() {
    use ptsc::texture::noise::{NoiseKind, NoiseParams};
    let wall = "quad { corner <-4, -4, 0> edge1 <8, 0, 0> edge2 <0, 8, 0> translate <0, 0, 0.5>";
    for (name, kind) in NoiseKind::NAMES {
        let defaults = NoiseParams::defaults(kind);
        for p in [[0.3, 0.7, 0.5], [-2.2, 1.4, 0.5], [3.9, -3.1, 0.5]] {
            // World space, scaled by 2: the pattern reads half the coordinates.
            let texture =
                format!("{name} {{ low rgb 0 high rgb 1 space world scale 2 octaves 3 }}");
            let three = NoiseParams {
                octaves: 3,
                ..defaults
            };
            let expect = kind.value(Vec3::from(p) / 2.0, &three);
            let got = colour_at(wall, &texture, p);
            assert!(
                (got - expect).abs() < 1e-5,
                "{name} at {p:?}: {got} vs {expect}"
            );
            // Object space by default: the wall's translate takes z back to 0.
            let texture = format!("{name} {{ low rgb 0 high rgb 1 }}");
            let expect = kind.value(Vec3::new(p[0], p[1], 0.0), &defaults);
            let got = colour_at(wall, &texture, p);
            assert!(
                (got - expect).abs() < 1e-5,
                "{name} (object) at {p:?}: {got} vs {expect}"
            );
            // Every parameter reaches the pattern.
            let (bands, set) = match kind.has_bands() {
                true => ("turbulence 0.7 frequency 3 phase 0.2", (0.7, 3.0, 0.2)),
                false => ("", (defaults.turbulence, 1.0, 0.0)),
            };
            let texture = format!("{name} {{ low rgb 0 high rgb 1 omega 0.8 lambda 2.5 {bands} }}");
            let params = NoiseParams {
                omega: 0.8,
                lambda: 2.5,
                turbulence: set.0,
                frequency: set.1,
                phase: set.2,
                ..defaults
            };
            let expect = kind.value(Vec3::new(p[0], p[1], 0.0), &params);
            let got = colour_at(wall, &texture, p);
            // Three times the bands: three times the hit point's float noise.
            assert!(
                (got - expect).abs() < 1e-4,
                "{name} ({bands}) at {p:?}: {got} vs {expect}"
            );
            assert_ne!(expect, kind.value(Vec3::new(p[0], p[1], 0.0), &defaults));
        }
    }
}

/// A textured lamp weighs in light selection by its texture's mean over its
/// surface, in the units of a plain lamp of that colour: the hot-spot lamp
/// of `tests/mitsuba/lights_textured.pts` (16 × 16 texels of 2 but a
/// 2 × 2 spot of 100: mean 3.53, brightest 100) on a quad, where bilinear
/// filtering with `repeat` keeps the texels' mean.
#[test]
fn a_textured_emitter_weighs_its_mean_emission() {
    let lamp = crate::root().join("tests/mitsuba/hotspot_lamp.exr");
    let text = format!(
        "camera {{ position <0, 0, 9> look_at <0, 0, 0> }}\n\
         quad {{ corner <0, 2, 0> edge1 <1, 0, 0> edge2 <0, 0, 1>\n\
                material {{ diffuse rgb 0 emission image {{ file \"{}\" }} }} }}\n\
         quad {{ corner <5, 2, 0> edge1 <1, 0, 0> edge2 <0, 0, 1> material {{ emission rgb 2 }} }}\n",
        lamp.display()
    );
    let c = compile_str(Path::new("t.pts"), &text, Options::default());
    let ir = c.ir.expect("compiles");
    let mut seen = 0;
    for light in &ir.lights {
        let ptsc::light::Light::Area { prim, shape, .. } = light else {
            continue;
        };
        let weighed = ir.mean_emission(*prim, shape, 1024);
        let want = match ir.material_of(*prim).textured {
            Some(_) => (252.0 * 2.0 + 4.0 * 100.0) / 256.0,
            None => 2.0,
        };
        assert!((weighed / want - 1.0).abs() < 0.02, "{weighed} vs {want}");
        seen += 1;
    }
    assert_eq!(seen, 2);
}
