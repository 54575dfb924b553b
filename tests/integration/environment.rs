//! Environment maps beyond the Mitsuba comparison: what importance sampling
//! gains over uniform sampling on a map with a sun, and a white furnace.

use glam::Vec3;
use ptsc::compile::{compile_file, compile_str, Options};
use ptsc::integrator;
use ptsc::ir::Scene;
use ptsc::light::Light;
use ptsc::output::read_exr;
use ptsc::render::render;
use std::sync::atomic::AtomicBool;
use std::sync::Arc;

fn pixels(ir: &Scene) -> Vec<Vec3> {
    let integ = integrator::make(ir.settings.integrator, ir);
    render(
        ir,
        integ.as_ref(),
        &AtomicBool::new(false),
        &|_| {},
        &mut |_, _| {},
    )
    .film
    .pixels()
}

/// Median MAE/mean against `reference` over 8 seeds.
fn median_mae(ir: &mut Scene, reference: &[Vec3]) -> f64 {
    let mean: f64 = reference
        .iter()
        .map(|p| (p.x + p.y + p.z) as f64)
        .sum::<f64>()
        / (3 * reference.len()) as f64;
    let mut maes: Vec<f64> = (0..8)
        .map(|seed| {
            ir.settings.seed = 500 + seed;
            let px = pixels(ir);
            let abs: f64 = px
                .iter()
                .zip(reference)
                .map(|(a, b)| {
                    let d = (*a - *b).abs();
                    (d.x + d.y + d.z) as f64
                })
                .sum();
            abs / (3 * px.len()) as f64 / mean
        })
        .collect();
    maes.sort_by(f64::total_cmp);
    0.5 * (maes[3] + maes[4])
}

#[test]
fn importance_sampling_the_map_beats_uniform_sampling_threefold() {
    let dir = crate::root().join("tests/mitsuba");
    let (_, _, reference) = read_exr(&dir.join("envmap_ref_64_16384spp.exr")).unwrap();
    let options = Options {
        adjust: &|s| (s.width, s.height, s.samples) = (64, 64, 64),
        ..Options::default()
    };
    let c = compile_file(&dir.join("envmap.pts"), options).unwrap();
    let mut importance = c.ir.expect("the scene compiles");
    let mut uniform = importance.clone();
    for light in &mut uniform.lights {
        if let Light::Environment { map: Some(m), .. } = light {
            *m = Arc::new((**m).clone().with_uniform_sampling());
        }
    }
    let (a, b) = (
        median_mae(&mut importance, &reference),
        median_mae(&mut uniform, &reference),
    );
    eprintln!("sun and sky, 64 spp: MAE/mean {a:.4} importance-sampled, {b:.4} uniform");
    assert!(b >= 3.0 * a, "importance {a} vs uniform {b}");
}

#[test]
fn a_white_ball_under_a_white_sky_is_white() {
    // The furnace: a constant map of 1 around a white diffuse ball; every
    // path returns 1 however it bounces, so every pixel is 1 in the mean.
    let dir = tempfile::tempdir().unwrap();
    ptsc::output::write_image(&dir.path().join("white.exr"), (8, 4), |_| Vec3::ONE, 0.0).unwrap();
    let text = "render { resolution <16, 16> samples 256 max_depth 64 rr_depth 64 }\n\
        camera { position <0, 0, 3> look_at <0, 0, 0> fov 40 }\n\
        environment { file \"white.exr\" rotate <10, 20, 30> }\n\
        sphere { center <0, 0, 0> radius 1 material { diffuse rgb 1 } }\n";
    let c = compile_str(&dir.path().join("s.pts"), text, Options::default());
    let ir =
        c.ir.unwrap_or_else(|| panic!("{}", c.diagnostics.render_human(&c.sources, false)));
    let px = pixels(&ir);
    let mean = px.iter().fold(Vec3::ZERO, |a, p| a + *p) / px.len() as f32;
    assert!((mean - Vec3::ONE).abs().max_element() < 0.01, "mean {mean}");
    for p in &px {
        assert!((*p - Vec3::ONE).abs().max_element() < 0.15, "pixel {p}");
    }
}

#[test]
fn the_brightest_map_at_the_largest_intensity_renders_finite() {
    // A texel at f32's largest value, scaled by the largest intensity the
    // checker accepts: texels are capped at 10^12 when read, the light's
    // power is computed in f64, the sampling weights are capped.
    let dir = tempfile::tempdir().unwrap();
    let texel = |i: usize| {
        if i == 10 {
            Vec3::splat(3.4e38)
        } else {
            Vec3::ONE
        }
    };
    ptsc::output::write_image(&dir.path().join("sun.exr"), (8, 4), texel, 0.0).unwrap();
    let text = "render { resolution <8, 8> samples 16 }\n\
        camera { position <0, 0, 3> look_at <0, 0, 0> }\n\
        environment { file \"sun.exr\" intensity rgb 1e12 }\n\
        sphere { center <0, 0, 0> radius 1 material { diffuse rgb 0.5 } }\n";
    let c = compile_str(&dir.path().join("s.pts"), text, Options::default());
    let ir =
        c.ir.unwrap_or_else(|| panic!("{}", c.diagnostics.render_human(&c.sources, false)));
    assert!(ir.env_light.is_some());
    let px = pixels(&ir);
    assert!(px.iter().all(|p| p.is_finite()), "a pixel is not finite");
    assert!(
        px.iter().any(|p| p.max_element() > 1e20),
        "the sun's light is lost"
    );
}
