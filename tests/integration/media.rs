//! Participating media: against Mitsuba 3's `volpath` (references by
//! `scripts/mitsuba_media.py`), the white furnace, closed forms of
//! transmittance (the camera inside nested media and an atmosphere), and
//! the hostile cases (densities up to 1e6, g at ±0.999, media in media,
//! lights and cameras inside, overlaps): finite images in bounded time.

use crate::mitsuba::measure;
use crate::render_pixels;
use ptsc::compile::{compile_str, Options};
use ptsc::ir::Scene;
use std::path::Path;

/// The bound on ptsc's noise at equal spp against Mitsuba's own.
const NOISE_BOUND: f64 = 1.15;

fn check_against_mitsuba(name: &str) {
    let m = measure(name, None);
    for k in 0..3 {
        assert!(
            (m.ratio[k] - 1.0).abs() < 0.01,
            "{name}: per-channel mean / Mitsuba's = {}, not within 1 %",
            m.ratio
        );
    }
    assert!(
        m.mae <= m.mitsuba_mae * NOISE_BOUND,
        "{name}: MAE/mean {:.5} is more than {NOISE_BOUND} × Mitsuba's {:.5}",
        m.mae,
        m.mitsuba_mae
    );
}

#[test]
fn mitsuba_reference_fog_with_a_spot_light() {
    check_against_mitsuba("media_fog");
}

#[test]
fn mitsuba_reference_glass_of_scattering_liquid() {
    check_against_mitsuba("media_liquid");
}

#[test]
fn mitsuba_reference_dense_white_slab() {
    check_against_mitsuba("media_slab");
}

#[test]
fn mitsuba_reference_atmosphere_with_a_sun() {
    check_against_mitsuba("media_atmosphere");
}

/// Compiles `scene` (errors fail the test).
fn compiled(scene: &str) -> Scene {
    let c = compile_str(Path::new("media.pts"), scene, Options::default());
    c.ir.unwrap_or_else(|| panic!("{}", c.diagnostics.render_human(&c.sources, false)))
}

fn mean(px: &[[f32; 3]]) -> [f64; 3] {
    let mut m = [0.0; 3];
    for p in px {
        for k in 0..3 {
            m[k] += p[k] as f64 / px.len() as f64;
        }
    }
    m
}

#[test]
fn white_furnace_a_medium_that_only_scatters_is_invisible() {
    // Inside a uniform white environment, a medium of albedo 1 neither
    // adds nor removes light, whatever its density, its phase function or
    // its boundary (none, or glass that refracts into it): every pixel is 1.
    for (boundary, g) in [
        ("type none", 0.0),
        ("type none", 0.8),
        ("transmission 1 ior 1.5", -0.5),
    ] {
        let scene = format!(
            "render {{ resolution <24, 24> samples 96 max_depth 1024 }}
             camera {{ position <0, 0, 4> look_at <0, 0, 0> fov 40 }}
             background rgb 1
             sphere {{ center <0, 0, 0> radius 1
                      material {{ {boundary} scattering rgb <2, 4, 6> anisotropy {g} }} }}"
        );
        let ir = compiled(&scene);
        assert!(ir.volumetric);
        let px = render_pixels(&ir);
        let m = mean(&px);
        for (k, c) in m.iter().enumerate() {
            assert!(
                (c - 1.0).abs() < 0.01,
                "{boundary}, g {g}: channel {k} mean {c}"
            );
        }
        // And no region strays: the pixels' RMS difference from 1 (measured
        // 0.02–0.03 for a grey medium, 0.04–0.07 for this chromatic one:
        // its channels' weights vary from path to path).
        let rms = (px
            .iter()
            .flatten()
            .map(|c| ((c - 1.0) as f64).powi(2))
            .sum::<f64>()
            / (3 * px.len()) as f64)
            .sqrt();
        assert!(rms < 0.12, "{boundary}, g {g}: RMS {rms}");
    }
}

#[test]
fn white_furnace_fails_when_the_medium_absorbs() {
    // The furnace above can fail: an albedo of 0.9 darkens the sphere.
    let ir = compiled(
        "render { resolution <24, 24> samples 16 max_depth 1024 }
         camera { position <0, 0, 4> look_at <0, 0, 0> fov 40 }
         background rgb 1
         sphere { center <0, 0, 0> radius 1 material { type none density 4 medium_color rgb 0.9 } }",
    );
    let m = mean(&render_pixels(&ir));
    assert!(m[0] < 0.95, "{m:?}");
}

#[test]
fn the_camera_inside_nested_media_and_an_atmosphere_sees_their_transmittance() {
    // The camera at the origin inside two absorbing spheres (radius 2, σa
    // 0.3; radius 4, σa 0.1), inside an atmosphere (σa 0.05, radius 10);
    // a lamp of radiance 1 at distance 6, between the outer sphere and the
    // atmosphere's edge: its centre shows exp(−(0.3·2 + 0.1·2 + 0.05·2)).
    let scene = |integrator: &str| {
        format!(
            "render {{ resolution <9, 9> samples 4 integrator {integrator} }}
             camera {{ position <0, 0, 0> look_at <0, 0, -1> fov 10 }}
             sphere {{ center <0, 0, 0> radius 2 material {{ type none absorption rgb 0.3 }} }}
             sphere {{ center <0, 0, 0> radius 4 material {{ type none absorption rgb <0.1, 0.1, 0.1> }} }}
             quad {{ corner <-3, -3, -6> edge1 <6, 0, 0> edge2 <0, 6, 0> material {{ diffuse rgb 0 emission rgb 1 }} }}
             atmosphere {{ absorption rgb 0.05 center <0, 0, 0> radius 10 }}"
        )
    };
    let want = (-(0.3f64 * 2.0 + 0.1 * 2.0 + 0.05 * 2.0)).exp();
    for integrator in ["path", "whitted", "hybrid"] {
        let ir = compiled(&scene(integrator));
        let px = render_pixels(&ir);
        let centre = px[4 * 9 + 4];
        for c in centre {
            assert!(
                (c as f64 - want).abs() < 1e-3 * want,
                "{integrator}: {centre:?}, want {want}"
            );
        }
    }
    // Without the atmosphere's ball around the lamp (radius 5), its last
    // unit is not attenuated.
    let ir = compiled(&scene("path").replace("radius 10", "radius 5"));
    let c = render_pixels(&ir)[4 * 9 + 4][0] as f64;
    let want = (-(0.3f64 * 2.0 + 0.1 * 2.0 + 0.05 * 1.0)).exp();
    assert!((c - want).abs() < 1e-3 * want, "{c} vs {want}");
}

#[test]
fn scenes_without_media_stay_on_the_plain_path() {
    // Glass that only absorbs is Beer's law at the exit, as before.
    let ir = compiled(
        "camera { position <0, 0, 5> look_at <0, 0, 0> }
         sphere { center <0, 0, 0> radius 1 material { transmission 1 absorption rgb 0.5 } }",
    );
    assert!(!ir.volumetric && ir.atmosphere.is_none());
    let ir = compiled(
        "camera { position <0, 0, 5> look_at <0, 0, 0> }
         sphere { center <0, 0, 0> radius 1 material { transmission 1 scattering rgb 0.5 } }",
    );
    assert!(ir.volumetric);
}

#[test]
fn hostile_media_give_finite_images() {
    let cases = [
        ("dense", "type none density 1000000 medium_color rgb 0.5"),
        (
            "dense white",
            "type none density 1000000 medium_color rgb 1",
        ),
        ("forward", "type none scattering rgb 3 anisotropy 0.999"),
        ("backward", "type none scattering rgb 3 anisotropy -0.999"),
        (
            "glass",
            "transmission 1 ior 1.5 scattering rgb 1000 absorption rgb 0.001",
        ),
        ("clear", "type none"),
    ];
    for (what, medium) in cases {
        for integrator in ["path", "whitted", "hybrid"] {
            // A light and the camera inside media, media inside media, two
            // media overlapping, an atmosphere around it all.
            let scene = format!(
                "render {{ resolution <12, 12> samples 4 max_depth 64 integrator {integrator} }}
                 camera {{ position <0, 0, 0.5> look_at <0, 0, -1> fov 70 }}
                 material m {{ {medium} }}
                 sphere {{ center <0, 0, 0> radius 2 material m }}
                 sphere {{ center <0, 0, -1> radius 0.5 material m }}
                 sphere {{ center <0.3, 0, -1> radius 0.5 material m }}
                 point_light {{ position <0, 0.5, -0.5> intensity rgb 5 }}
                 quad {{ corner <-3, -1, 3> edge1 <6, 0, 0> edge2 <0, 0, -6> material {{ diffuse rgb 0.5 }} }}
                 atmosphere {{ density 0.2 medium_color rgb 0.8 }}"
            );
            let ir = compiled(&scene);
            let px = render_pixels(&ir);
            assert!(
                px.iter().flatten().all(|c| c.is_finite() && *c >= 0.0),
                "{what}, {integrator}: a pixel is not finite"
            );
        }
    }
}

#[test]
fn media_renders_are_the_same_on_one_and_two_threads() {
    let text = std::fs::read_to_string(crate::root().join("tests/mitsuba/media_fog.pts")).unwrap();
    let ir = compiled(&text.replace("samples 64", "samples 8"));
    let integ = ptsc::integrator::make(ir.settings.integrator, &ir);
    let cancel = std::sync::atomic::AtomicBool::new(false);
    let on = |threads| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            ptsc::render::render(&ir, integ.as_ref(), &cancel, &|_| {}, &mut |_, _| {})
                .film
                .pixels()
        })
    };
    assert_eq!(on(1), on(2));
}

#[test]
fn aovs_look_through_null_boundaries() {
    // A red wall seen through a fog box: the albedo and depth AOVs are the
    // wall's (the boundary is not a surface).
    let ir = compiled(
        "render { resolution <4, 4> samples 4 }
         camera { position <0, 0, 5> look_at <0, 0, 0> fov 10 }
         point_light { position <0, 0, 4> intensity rgb 1 }
         quad { corner <-2, -2, 0> edge1 <4, 0, 0> edge2 <0, 4, 0> material { diffuse rgb <0.8, 0.1, 0.1> } }
         box { min <-1, -1, 1> max <1, 1, 3> material { type none density 0.2 } }",
    );
    let integ = ptsc::integrator::make(ir.settings.integrator, &ir);
    let cancel = std::sync::atomic::AtomicBool::new(false);
    let film = ptsc::render::render(&ir, integ.as_ref(), &cancel, &|_| {}, &mut |_, _| {}).film;
    use ptsc::render::aov::{render_aovs, Aov};
    let out = render_aovs(&ir, &[Aov::Albedo, Aov::Depth], &film, &cancel).unwrap();
    let albedo_r = &out[0].1[0];
    let depth = &out[1].1[0];
    assert!(
        albedo_r.iter().all(|a| (a - 0.8).abs() < 1e-4),
        "{albedo_r:?}"
    );
    assert!(depth.iter().all(|d| (5.0..5.05).contains(d)), "{depth:?}");
}

#[test]
fn overlapping_media_the_one_entered_last_fills_the_overlap() {
    // Along the axis: into A (σa 0.5) at x = −1, into B (σa 0.2) at 0, out
    // of A at 1, out of B at 2; a lamp of radiance 1 at x = 3. The overlap
    // is B's: exp(−(0.5 + 0.2 + 0.2)).
    let ir = compiled(
        "render { resolution <3, 3> samples 4 }
         camera { position <-3, 0, 0> look_at <0, 0, 0> fov 1 }
         sphere { center <0, 0, 0> radius 1 material { type none absorption rgb 0.5 } }
         sphere { center <1, 0, 0> radius 1 material { type none absorption rgb 0.2 } }
         quad { corner <3, -1, 1> edge1 <0, 2, 0> edge2 <0, 0, -2> material { diffuse rgb 0 emission rgb 1 two_sided true } }",
    );
    let c = render_pixels(&ir)[4][0] as f64;
    let want = (-0.9f64).exp();
    assert!((c - want).abs() < 1e-3, "{c} vs {want}");
}

#[test]
fn light_sampling_through_rough_glass_agrees_with_bsdf_sampling_alone() {
    // Inside a frosted ball of scattering liquid, light sampled through the
    // rough surface travels the air outside; sampling only the BSDF and the
    // phase function must give the same mean (both are unbiased).
    let scene = |nee: bool| {
        format!(
            "render {{ resolution <24, 24> samples 256 max_depth 64 light_sampling {nee} }}
             camera {{ position <0, 0.5, 4> look_at <0, 0.3, 0> fov 35 }}
             quad {{ corner <-3, 0, 3> edge1 <6, 0, 0> edge2 <0, 0, -6> material {{ diffuse rgb 0.5 }} }}
             quad {{ corner <-2, 3, -2> edge1 <4, 0, 0> edge2 <0, 0, 4> material {{ diffuse rgb 0 emission rgb 2 }} }}
             sphere {{ center <0, 0.8, 0> radius 0.8
                      material {{ type dielectric ior 1.3 gloss 0.5 scattering rgb <1, 2, 3> absorption rgb 0.2 }} }}"
        )
    };
    let with = mean(&render_pixels(&compiled(&scene(true))));
    let without = mean(&render_pixels(&compiled(&scene(false))));
    for k in 0..3 {
        let r = with[k] / without[k];
        assert!(
            (r - 1.0).abs() < 0.02,
            "channel {k}: {with:?} vs {without:?}"
        );
    }
}

#[test]
fn the_default_atmosphere_holds_the_camera_and_the_lights() {
    // Only an infinite plane: no bounded object to size the ball by.
    let ir = compiled(
        "camera { position <0, 5, 20> look_at <0, 0, 0> }
         point_light { position <30, 8, 0> intensity rgb 10 }
         plane { normal <0, 1, 0> material { diffuse rgb 0.5 } }
         atmosphere { density 0.01 }",
    );
    let a = ir.atmosphere.expect("an atmosphere");
    for p in [
        glam::Vec3::new(0.0, 5.0, 20.0),
        glam::Vec3::new(30.0, 8.0, 0.0),
    ] {
        assert!((p - a.center).length() < a.radius, "{p} outside {a:?}");
    }
}
