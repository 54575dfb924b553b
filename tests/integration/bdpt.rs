//! Bidirectional path tracing: the same image as the path integrator
//! (every light kind it starts paths from, and those it leaves to the
//! camera's side), and the same image on any thread count.

use ptsc::compile::{compile_str, Options};
use ptsc::diag::codes::INTEGRATOR_SETTING;
use ptsc::render::{film::Film, render};
use std::path::Path;
use std::sync::atomic::AtomicBool;

/// `text` rendered with `integrator` on `threads` threads.
fn film(text: &str, integrator: &str, threads: usize) -> Film {
    let text = text.replace("INTEGRATOR", integrator);
    let c = compile_str(Path::new("test.pts"), &text, Options::default());
    let ir =
        c.ir.unwrap_or_else(|| panic!("{}", c.diagnostics.render_human(&c.sources, false)));
    let integ = ptsc::integrator::make(ir.settings.integrator, &ir);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    let cancel = AtomicBool::new(false);
    pool.install(|| render(&ir, integ.as_ref(), &cancel, &|_| {}, &mut |_, _| {}))
        .film
}

/// Mean of each channel over the four quarters of the image.
fn quarters(f: &Film) -> Vec<[f64; 3]> {
    let (w, h) = (f.width as usize, f.height as usize);
    let px = f.pixels();
    let mut q = vec![[0.0f64; 3]; 4];
    for y in 0..h {
        for x in 0..w {
            let p = px[y * w + x];
            let k = (y * 2 / h) * 2 + x * 2 / w;
            for c in 0..3 {
                q[k][c] += p[c] as f64 / (w * h / 4) as f64;
            }
        }
    }
    q
}

/// The box of the Cornell scene without its lights, with `extra` inside.
fn cornell(extra: &str, spp: u32) -> String {
    format!(
        r#"
render {{ resolution <16, 16>  samples {spp}  max_depth 6  integrator INTEGRATOR }}
camera {{ position <0, 0, 3.9>  look_at <0, 0, 0>  fov 39.3 }}
material white {{ diffuse rgb 0.7 }}
material red {{ diffuse rgb <0.6, 0.05, 0.05> }}
material green {{ diffuse rgb <0.1, 0.4, 0.1> }}
quad {{ corner <-1, -1, -1> edge1 <0, 0, 2> edge2 <2, 0, 0> material white }}
quad {{ corner <-1, 1, -1>  edge1 <2, 0, 0> edge2 <0, 0, 2> material white }}
quad {{ corner <-1, -1, -1> edge1 <2, 0, 0> edge2 <0, 2, 0> material white }}
quad {{ corner <-1, -1, -1> edge1 <0, 2, 0> edge2 <0, 0, 2> material red }}
quad {{ corner <1, -1, -1>  edge1 <0, 0, 2> edge2 <0, 2, 0> material green }}
{extra}
"#
    )
}

/// A lamp under the ceiling and a glass ball: caustics for light paths.
const LAMP_AND_GLASS: &str = r#"
material lamp { diffuse rgb 0 emission rgb 12 }
quad { corner <-0.25, 0.99, -0.25> edge1 <0.5, 0, 0> edge2 <0, 0, 0.5> material lamp }
material glass { transmission 1 ior 1.5 }
sphere { center <0.4, -0.65, 0.3> radius 0.33 material glass }
"#;

/// Asserts that bdpt and ptlt give the quarter means path gives within `tol`
/// (relative, on the sum of channels' means).
fn agree(name: &str, scene: &str, tol: f64) {
    let path = quarters(&film(scene, "path", 2));
    for integrator in ["bdpt", "ptlt"] {
        let other = quarters(&film(scene, integrator, 2));
        for (k, (p, b)) in path.iter().zip(&other).enumerate() {
            let (sp, sb): (f64, f64) = (p.iter().sum(), b.iter().sum());
            assert!(sp > 1e-3, "{name}: quarter {k} is black");
            let rel = (sb - sp).abs() / sp;
            let why = format!("{name}: quarter {k}: path {p:?}, {integrator} {b:?} ({rel:.4})");
            assert!(rel < tol, "{why}");
        }
    }
}

#[test]
fn bdpt_and_ptlt_match_path_tracing_under_an_area_light() {
    let light = r#"
material lamp { diffuse rgb 0 emission rgb 12 }
quad { corner <-0.25, 0.99, -0.25> edge1 <0.5, 0, 0> edge2 <0, 0, 0.5> material lamp }
material gloss { type conductor preset gold gloss 0.3 }
sphere { center <-0.4, -0.6, -0.3> radius 0.35 material gloss }
sphere { center <0.45, -0.6, 0.2> radius 0.3 material white }
"#;
    agree("area light", &cornell(light, 2048), 0.02);
}

#[test]
fn bdpt_and_ptlt_match_path_tracing_under_point_spot_and_two_sided_lights() {
    let lights = r#"
point_light { position <0.5, 0.6, 0.3> intensity rgb 2 }
spot_light { position <-0.5, 0.9, 0.5> look_at <-0.3, -1, -0.2> intensity rgb 6 angle 40 hotspot 25 }
material panel { diffuse rgb 0 emission rgb 3 two_sided true }
quad { corner <-0.3, 0.2, -0.6> edge1 <0.4, 0, 0> edge2 <0, 0.3, 0.2> material panel }
"#;
    agree("point, spot, two-sided", &cornell(lights, 2048), 0.02);
}

#[test]
fn bdpt_and_ptlt_match_path_tracing_with_glass_and_a_mirror() {
    let scene = r#"
material lamp { diffuse rgb 0 emission rgb 12 }
quad { corner <-0.25, 0.99, -0.25> edge1 <0.5, 0, 0> edge2 <0, 0, 0.5> material lamp }
material glass { transmission 1 ior 1.5 }
material mirror { reflection rgb 1 }
sphere { center <0.4, -0.65, 0.3> radius 0.33 material glass }
sphere { center <-0.4, -0.65, -0.35> radius 0.33 material mirror }
"#;
    // Caustics make the path tracer's own estimate noisy: a wider margin.
    agree("glass and mirror", &cornell(scene, 4096), 0.04);
}

#[test]
fn bdpt_and_ptlt_match_path_tracing_under_the_sky_and_a_sphere_lamp() {
    let scene = r#"
render { resolution <16, 16>  samples 2048  max_depth 5  integrator INTEGRATOR }
camera { position <0, 1, 4>  look_at <0, 0, 0>  fov 45 }
background rgb <0.3, 0.4, 0.6>
material ground { diffuse rgb 0.6 }
material lamp { diffuse rgb 0 emission rgb 8 }
material ball { diffuse rgb <0.7, 0.5, 0.3> }
plane { point <0, -1, 0> normal <0, 1, 0> material ground }
sphere { center <0.8, 0.2, 0> radius 0.2 material lamp }
sphere { center <-0.3, -0.4, 0> radius 0.6 material ball }
"#;
    agree("background and sphere lamp", scene, 0.02);
}

#[test]
fn bdpt_and_ptlt_give_the_same_image_on_one_and_two_threads() {
    let scene = cornell(LAMP_AND_GLASS, 24);
    for integrator in ["bdpt", "ptlt"] {
        let (a, b) = (film(&scene, integrator, 1), film(&scene, integrator, 2));
        assert_eq!(a.pixels(), b.pixels(), "{integrator}");
        let light = a.light.as_ref().expect("a light film");
        assert_eq!(light.paths, 16 * 16 * 24, "one light path per sample");
        let reached = light.sum.iter().any(|s| s.max_element() > 0.0);
        assert!(reached, "{integrator}: light paths reach the camera");
    }
}

/// Renders `scene` to `out` with `args`, expecting success.
fn run(scene: &str, out: &str, args: &[&str]) {
    let mut all = vec!["render", scene, "-o", out];
    all.extend_from_slice(args);
    let (code, _, err) = crate::ptsc(&all);
    assert_eq!(code, 0, "{err}");
}

#[test]
fn a_render_resumed_from_its_state_equals_one_rendered_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("box.pts");
    let text = cornell(LAMP_AND_GLASS, 8);
    for (integrator, adaptive) in [
        ("bdpt", &[][..]),
        ("ptlt", &["--noise", "0.1", "--min-samples", "4"][..]),
    ] {
        std::fs::write(&scene, text.replace("INTEGRATOR", integrator)).unwrap();
        let scene = scene.to_str().unwrap();
        let resumed = dir.path().join(format!("{integrator}_resumed.pfm"));
        let once = dir.path().join(format!("{integrator}_once.pfm"));
        let (resumed, once) = (resumed.to_str().unwrap(), once.to_str().unwrap());
        let with = |more: &[&'static str]| -> Vec<&'static str> { [adaptive, more].concat() };
        run(scene, resumed, &with(&["--keep-state"]));
        run(scene, resumed, &with(&["--spp", "24", "--resume"]));
        run(scene, once, &with(&["--spp", "24", "--threads", "1"]));
        // The state keeps the light film bit for bit, in its own part.
        assert_eq!(
            std::fs::read(resumed).unwrap(),
            std::fs::read(once).unwrap(),
            "{integrator}"
        );
    }
}

#[test]
fn check_warns_of_media_exactly_where_bdpt_falls_back_to_path() {
    // One verdict: the warning `check` (and so `watch` and the language
    // server) gives at `integrator bdpt` must name exactly the scenes that
    // lowering finds volumetric and the renderer hands to `path`.
    let head = "render { integrator bdpt }
        camera { position <0, 1, 4> look_at <0, 0, 0> }
        sphere { center <0, 3, 0> radius 0.5 material { emission rgb 5 } }\n";
    let ball = |m: &str| format!("sphere {{ center <0, 0, 0> radius 1 material {{ {m} }} }}\n");
    let cases = [
        ball("diffuse rgb 0.5"),
        ball("transmission 1 absorption rgb 0.5"),
        ball("transmission 1 scattering rgb 0.5"),
        ball("transmission 1 density 2 medium_color rgb 0.5"),
        ball("transmission 1 density 2 medium_color rgb 0"),
        ball("transmission 0 scattering rgb 0.5"),
        ball("type none density 1 medium_color rgb 0.5"),
        ball("type none"),
        ball("type principled transmission 1 scattering rgb 0.5"),
        ball("type principled transmission 1"),
        ball("transmission 1 scattering rgb 0.5 diffuse rgb 0.2"),
        format!(
            "{}atmosphere {{ density 0.05 medium_color rgb 1 }}\n",
            ball("diffuse rgb 0.5")
        ),
        format!("{}atmosphere {{ density 0 }}\n", ball("diffuse rgb 0.5")),
        format!(
            "{}atmosphere {{ absorption rgb 0 scattering rgb 0 }}\n",
            ball("diffuse rgb 0.5")
        ),
        format!(
            "material fog {{ transmission 1 scattering rgb 1 }}\n{}",
            ball("diffuse rgb 0.5")
        ),
        // Below what an f32 holds: no medium once lowered.
        ball("transmission 1e-50 scattering rgb 0.5"),
        ball("transmission 1 scattering rgb 1e-50"),
        format!(
            "{}atmosphere {{ absorption rgb 1e-50 }}\n",
            ball("diffuse rgb 0.5")
        ),
    ];
    let mut wrong = Vec::new();
    for case in &cases {
        let text = format!("{head}{case}");
        let c = compile_str(Path::new("media.pts"), &text, Options::default());
        let Some(ir) = c.ir else {
            wrong.push(format!(
                "does not compile: {case}{}",
                c.diagnostics.render_human(&c.sources, false)
            ));
            continue;
        };
        let warned = c
            .diagnostics
            .render_json(&c.sources)
            .contains(INTEGRATOR_SETTING);
        if warned != ir.volumetric {
            wrong.push(format!(
                "warned {warned}, volumetric {}: {case}",
                ir.volumetric
            ));
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}
