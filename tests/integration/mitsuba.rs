//! Unbiasedness against an independent renderer: the three benchmark scenes of
//! `../shared/bench` (their data made by `ptsc::bench_data`, so that no
//! `../shared` is needed) rendered by ptsc at 64×64 are compared with Mitsuba 3
//! references at 65,536 spp (`tests/mitsuba/*_ref_64_65536spp.exr`, made by
//! `bash ../shared/bench/mitsuba.sh ref SCENE 64 65536`), and so is
//! `tests/mitsuba/textures.pts` (reference and baseline by
//! `scripts/mitsuba_textures.py`, 16,384 spp).
//!
//! - Bias: the per-channel mean over all seeds' images is within 1 % of the
//!   reference's.
//! - Noise: at equal spp, ptsc's mean absolute error (compare.py's
//!   `mae_over_mean`, median over seeds) is no worse than Mitsuba's own, as
//!   measured by `scripts/mitsuba_baseline.py` into `tests/mitsuba/baseline.json`,
//!   up to `NOISE_SLACK`: the median of 8 seeds itself varies by about 1 %
//!   from one set of seeds to another (measured with 32 seeds for both
//!   renderers: ptsc/Mitsuba = 0.997 cornell, 1.008 mesh, 0.991 spheres).

use glam::Vec3;
use ptsc::compile::{compile_file, Options};
use ptsc::integrator;
use ptsc::ir::settings::LightSelection;
use ptsc::output::read_exr;
use ptsc::render::render;
use std::sync::atomic::AtomicBool;

/// Seeds per scene unless its baseline used more (as many as it used: a
/// scene with fireflies, such as a sun reflected in a mirror, needs more
/// for a stable median).
const SEEDS: u64 = 8;
/// Allowed excess of ptsc's median MAE over Mitsuba's: the spread of a
/// median of 8 seeds, not a difference in the estimators.
const NOISE_SLACK: f64 = 1.02;

/// Renders scene `name` with the seeds of its baseline and checks its mean
/// and noise against Mitsuba's; returns ptsc's image averaged over the
/// seeds and the reference.
fn check_scene(name: &str) -> Measured {
    check_scene_within(name, 0.01)
}

/// [`check_scene`] with the means within `tolerance` instead of 1 % (for a
/// scene where Mitsuba's reference is known to differ: said where used).
fn check_scene_within(name: &str, tolerance: f32) -> Measured {
    let m = measure(name, None);
    let (ratio, mae, mitsuba_mae) = (m.ratio, m.mae, m.mitsuba_mae);
    for k in 0..3 {
        assert!(
            (ratio[k] - 1.0).abs() < tolerance,
            "{name}: per-channel mean / Mitsuba's = {ratio}, not within {tolerance}"
        );
    }
    assert!(
        mae <= mitsuba_mae * NOISE_SLACK,
        "{name}: MAE/mean {mae:.5} is noisier than Mitsuba's {mitsuba_mae:.5}"
    );
    m
}

/// What [`measure`] finds.
#[derive(Clone)]
pub(crate) struct Measured {
    /// ptsc's image of each seed.
    pub(crate) images: Vec<Vec<Vec3>>,
    /// ptsc's image averaged over the seeds.
    pub(crate) average: Vec<Vec3>,
    /// Mitsuba's reference.
    pub(crate) reference: Vec<Vec3>,
    /// The per-channel ratio of the means, ptsc's over Mitsuba's.
    pub(crate) ratio: Vec3,
    /// ptsc's median MAE/mean over the seeds.
    pub(crate) mae: f64,
    /// Mitsuba's own, from the baseline.
    pub(crate) mitsuba_mae: f64,
}

/// The scene file of `name`: the benchmark scenes are examples; the
/// others live beside their references.
fn scene_path(name: &str) -> std::path::PathBuf {
    let own = crate::root().join(format!("tests/mitsuba/{name}.pts"));
    if own.exists() {
        own
    } else {
        crate::root().join(format!("examples/bench/{name}.pts"))
    }
}

/// [`measure_once`], each scene and light selection measured once per
/// run: a scene's own test and the test of the rules ask for the same
/// `auto` renders (seconds each), and the second waits for the first's.
pub(crate) fn measure(name: &str, rule: Option<LightSelection>) -> Measured {
    use std::collections::HashMap;
    use std::sync::{Arc, Mutex, OnceLock};
    type Cells = Mutex<HashMap<String, Arc<OnceLock<Measured>>>>;
    static DONE: OnceLock<Cells> = OnceLock::new();
    // A scene that names no rule renders with `auto`, as `Some(Auto)` does.
    let text = std::fs::read_to_string(scene_path(name)).unwrap();
    let rule = match rule {
        None if !text.contains("light_selection") => Some(LightSelection::Auto),
        r => r,
    };
    let key = format!("{name} {rule:?}");
    let cell = DONE
        .get_or_init(Cells::default)
        .lock()
        .unwrap()
        .entry(key)
        .or_default()
        .clone();
    cell.get_or_init(|| measure_once(name, rule)).clone()
}

/// Scene `name` rendered with the seeds of its baseline (with the light
/// selection `rule` instead of the scene's, if given).
fn measure_once(name: &str, rule: Option<LightSelection>) -> Measured {
    let dir = crate::root().join("tests/mitsuba");
    let baseline: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("baseline.json")).unwrap()).unwrap();
    let res = baseline["res"].as_u64().unwrap() as u32;
    let spp = baseline["spp"].as_u64().unwrap() as u32;
    let entry = &baseline["scenes"][name];
    let mitsuba_mae = entry["median_mae_over_mean"].as_f64().unwrap();
    let seeds = (entry["mae_over_mean"].as_array().map_or(0, |a| a.len()) as u64).max(SEEDS);
    let (w, h, reference) = read_exr(&dir.join(entry["reference"].as_str().unwrap())).unwrap();
    assert_eq!((w, h), (res, res));

    ptsc::bench_data::ensure_mesh_blob(&crate::root()).unwrap();
    let path = scene_path(name);
    let options = Options {
        adjust: &|s| {
            (s.width, s.height, s.samples) = (res, res, spp);
            if let Some(rule) = rule {
                s.light_selection = rule;
            }
        },
        ..Options::default()
    };
    let c = compile_file(&path, options).unwrap();
    let mut ir =
        c.ir.unwrap_or_else(|| panic!("{}", c.diagnostics.render_human(&c.sources, false)));
    let integ = integrator::make(ir.settings.integrator, &ir);
    let cancel = AtomicBool::new(false);

    let ref_sum = sum(&reference);
    let ref_mean = (ref_sum.x + ref_sum.y + ref_sum.z) as f64 / (3 * reference.len()) as f64;
    let mut total = Vec3::ZERO;
    let mut average = vec![Vec3::ZERO; reference.len()];
    let mut maes = Vec::new();
    let mut images = Vec::new();
    for seed in 0..seeds {
        ir.settings.seed = 1000 + seed;
        let px = render(&ir, integ.as_ref(), &cancel, &|_| {}, &mut |_, _| {})
            .film
            .pixels();
        total += sum(&px);
        for (a, p) in average.iter_mut().zip(&px) {
            *a += *p / seeds as f32;
        }
        let abs: f64 = px
            .iter()
            .zip(&reference)
            .map(|(a, b)| {
                let d = (*a - *b).abs();
                (d.x + d.y + d.z) as f64
            })
            .sum();
        maes.push(abs / (3 * px.len()) as f64 / ref_mean);
        images.push(px);
    }
    let ratio = total / (ref_sum * seeds as f32);
    maes.sort_by(f64::total_cmp);
    let mae = 0.5 * (maes[maes.len() / 2 - 1] + maes[maes.len() / 2]);
    eprintln!(
        "{name}: mean ratio {ratio:.4} ({seeds} x {spp} spp), MAE/mean {mae:.5} vs Mitsuba {mitsuba_mae:.5}"
    );
    Measured {
        images,
        average,
        reference,
        ratio,
        mae,
        mitsuba_mae,
    }
}

fn sum(px: &[Vec3]) -> Vec3 {
    px.iter().fold(Vec3::ZERO, |a, b| a + *b)
}

#[test]
fn mitsuba_reference_materials() {
    // Each ball on its own: the pixels within 70 % of its radius on screen
    // (centres and radii from the camera), mean per channel against
    // Mitsuba's. Each ball gets 1,024 spp in about 80 to 130 pixels here;
    // Mitsuba's own 4,096-spp image is within 2 % of its reference on
    // every ball (the gold mirror, which shows the sun, the furthest).
    check_balls(
        &check_scene("materials"),
        [
            "gold (conductor)",
            "rough copper (roughconductor α 0.1)",
            "frosted glass (roughdielectric α 0.2)",
            "red plastic (plastic)",
            "blue rough plastic (roughplastic α 0.2)",
            "bubble (thindielectric)",
        ],
        BALL_TOLERANCE,
    );
}

/// What users tried to say (issue 34), ball by ball as the materials: a
/// metal's roughness from a texture, a metal rough unevenly (`alpha_u`,
/// `alpha_v`), glass and a bubble in water (`ext_ior`), a metal in water,
/// an 8-bit image read linearly (`raw`). The balls here show the sun
/// through smooth and rough glass and in smooth metal cells: the 16,384-spp
/// reference itself carries up to 2 % of noise on some, and 4,096 of
/// Mitsuba's own samples are within 5 % of it on every ball.
#[test]
fn mitsuba_reference_material_options() {
    check_balls(
        &check_scene("material_options"),
        [
            "gold rough by a checker (roughconductor, alpha a checkerboard)",
            "copper rough unevenly (roughconductor, alpha_u 0.05, alpha_v 0.4)",
            "frosted glass in water (roughdielectric, ext_ior 1.33)",
            "an air bubble in water (dielectric, int_ior 1, ext_ior 1.33)",
            "aluminium in water (conductor, eta and k over 1.33)",
            "an 8-bit image read linearly (bitmap, raw)",
        ],
        0.05,
    );
}

/// The principled material against Mitsuba 3's `principled`, three scenes
/// of six balls (`scripts/mitsuba_principled_scenes.py`): each ball's mean
/// within 1 % of the reference's (plus three standard errors of ptsc's
/// mean over the seeds), the whole image's mean within 1 % and its error
/// no worse than Mitsuba's own at equal spp.
fn check_principled(name: &str, balls: [&str; 6]) {
    check_balls(&check_scene(name), balls, 0.01);
}

#[test]
fn mitsuba_reference_principled_dielectrics() {
    check_principled(
        "principled_a",
        [
            "red, roughness 0.1",
            "green, roughness 0.5",
            "blue, roughness 0.9",
            "half metal with clearcoat",
            "grey, specular 0.1",
            "pink, tinted specular 0.8, metallic 0.3",
        ],
    );
}

#[test]
fn mitsuba_reference_principled_metals() {
    check_principled(
        "principled_b",
        [
            "gold-coloured metal, roughness 0.1",
            "white metal, roughness 0.5",
            "red metal, roughness 0.9",
            "half metal, roughness 0.1",
            "half metal, roughness 0.5",
            "half metal, roughness 0.9",
        ],
    );
}

#[test]
fn mitsuba_reference_principled_lobes() {
    check_principled(
        "principled_c",
        [
            "tinted specular 0.9",
            "clearcoat",
            "sheen",
            "glass (transmission 1)",
            "part glass (transmission 0.6, metallic 0.2)",
            "anisotropic metal",
        ],
    );
}

/// The mean of each ball of the materials' layout (`materials.pts`, six
/// balls in two rows) within `tolerance` of the reference's, plus three
/// standard errors of ptsc's mean (from the spread of the seeds' own
/// means): a ball that shows the sun in a rough metal has a few bright
/// samples, and the mean of 16 seeds of 64 spp varies by 5 % or more
/// from one set of seeds to the next with either sampler.
fn check_balls(m: &Measured, names: [&str; 6], tolerance: f32) {
    let balls = [
        (14.53, 28.25, 4.99),
        (32.0, 28.25, 5.09),
        (49.47, 28.25, 4.99),
        (9.61, 35.6, 6.32),
        (32.0, 35.6, 6.52),
        (54.39, 35.6, 6.32),
    ];
    for (name, (cx, cy, r)) in names.into_iter().zip(balls) {
        let inside = |i: usize| {
            let (dx, dy) = ((i % 64) as f32 + 0.5 - cx, (i / 64) as f32 + 0.5 - cy);
            dx * dx + dy * dy < r * r
        };
        let ball = |image: &[Vec3]| -> Vec3 {
            let pixels = image.iter().enumerate().filter(|(i, _)| inside(*i));
            pixels.fold(Vec3::ZERO, |a, (_, p)| a + *p)
        };
        let b = ball(&m.reference);
        let ratio = ball(&m.average) / b;
        let seeds: Vec<Vec3> = m.images.iter().map(|image| ball(image) / b).collect();
        let n = seeds.len() as f32;
        let variance = seeds
            .iter()
            .fold(Vec3::ZERO, |a, s| a + (*s - ratio) * (*s - ratio))
            / (n - 1.0);
        let error = (variance / n).powf(0.5);
        eprintln!("{name}: mean ratio {ratio:.4} ± {error:.4}");
        let allowed = Vec3::splat(tolerance) + 3.0 * error;
        assert!(
            (ratio - Vec3::ONE).abs().cmplt(allowed).all(),
            "{name}: mean / Mitsuba's = {ratio}, more than {allowed} from 1"
        );
    }
}

/// How far one ball's mean in `materials.pts` may be from Mitsuba's: the
/// noise of its few pixels, plus the 1.5 % by which Mitsuba's rough
/// plastic is darker (its R_int is a 64-point mean, see
/// `ptsc::material::plastic`).
const BALL_TOLERANCE: f32 = 0.035;

#[test]
fn mitsuba_reference_cornell() {
    check_scene("cornell");
}

#[test]
fn mitsuba_reference_mesh() {
    check_scene("mesh");
}

#[test]
fn mitsuba_reference_spheres() {
    check_scene("spheres");
}

/// Checker and image textures on quads and spheres, an HDR image as a
/// lamp's emission and a normal-mapped quad (Mitsuba's `checkerboard`,
/// `bitmap`, textured `area` emitter and `normalmap`; conventions mapped
/// onto ptsc's in `scripts/mitsuba_textures.py`).
#[test]
fn mitsuba_reference_textures() {
    check_scene("textures");
}

/// An environment map with a sun-like hot spot lighting a diffuse floor,
/// a diffuse ball and a mirror ball (Mitsuba's `envmap`; the same lookup,
/// its bilinear importance sampling against ptsc's piecewise-constant one).
#[test]
fn mitsuba_reference_envmap() {
    check_scene("envmap");
}

/// A daylight sky and its sun (Mitsuba's `sunsky`: the same Hošek–Wilkie
/// sky, the same solar table) over a diffuse floor, a white ball and a
/// glossy ball that shows the sun's highlight.
#[test]
fn mitsuba_reference_sky() {
    check_scene("sky");
}

/// The normal-mapped quad of `textures.pts` on its own: its pixels match
/// Mitsuba's `normalmap` (mean within 1 %, error at the level of the
/// noise), and the same quad without its normal map is measurably further
/// from the reference, so that the comparison above could fail on a wrong
/// frame or decoding.
#[test]
fn mitsuba_reference_normal_map_region() {
    let dir = crate::root().join("tests/mitsuba");
    let (w, _, reference) = read_exr(&dir.join("textures_ref_64_16384spp.exr")).unwrap();
    // The quad's pixels (rows 10 to 26, columns 37 to 57 of the 64 × 64
    // image: where its normal map changes the image).
    let region: Vec<usize> = (10..=26)
        .flat_map(|y| (37..=57).map(move |x| y * w as usize + x))
        .collect();
    let path = dir.join("textures.pts");
    let text = std::fs::read_to_string(&path).unwrap();
    let flat_text: String = text
        .lines()
        .map(|l| match l.find("normal_map") {
            Some(i) => format!("{}}} }}", &l[..i]),
            None => l.to_string(),
        })
        .collect::<Vec<_>>()
        .join("\n");
    assert_ne!(text, flat_text);
    let error = |scene: &str| {
        let options = Options {
            adjust: &|s| (s.width, s.height, s.samples, s.seed) = (64, 64, 1024, 7),
            ..Options::default()
        };
        let c = ptsc::compile::compile_str(&path, scene, options);
        let ir =
            c.ir.unwrap_or_else(|| panic!("{}", c.diagnostics.render_human(&c.sources, false)));
        let integ = integrator::make(ir.settings.integrator, &ir);
        let px = render(
            &ir,
            integ.as_ref(),
            &AtomicBool::new(false),
            &|_| {},
            &mut |_, _| {},
        )
        .film
        .pixels();
        let (mut abs, mut mean, mut ours) = (0.0f64, 0.0f64, 0.0f64);
        for &i in &region {
            let d = (px[i] - reference[i]).abs();
            abs += (d.x + d.y + d.z) as f64;
            mean += (reference[i].x + reference[i].y + reference[i].z) as f64;
            ours += (px[i].x + px[i].y + px[i].z) as f64;
        }
        (abs / mean, ours / mean)
    };
    let (mapped, ratio) = error(&text);
    let (flat, _) = error(&flat_text);
    eprintln!("normal-mapped quad: MAE/mean {mapped:.4} (without the map {flat:.4}), mean ratio {ratio:.4}");
    assert!((ratio - 1.0).abs() < 0.01, "mean ratio {ratio}");
    assert!(
        mapped < 0.03,
        "MAE/mean {mapped} in the normal-mapped region"
    );
    assert!(
        flat > 2.0 * mapped,
        "without its normal map: {flat} vs {mapped}"
    );
}

/// Normal maps (Mitsuba's `normalmap`) and bump maps (`bumpmap`) on quads
/// turned to four orientations in their plane, with edges 0.5, 1 and 8
/// long (`scripts/mitsuba_bumps.py`): the maps follow each quad's `edge1`
/// and `edge2` and a bump's slope their lengths, whether or not the BVH
/// packs the quad into a block.
#[test]
fn mitsuba_reference_bumps_on_quads() {
    for name in ["bumps_05", "bumps_1", "bumps_8"] {
        check_scene(name);
    }
}

/// Both maps on a curved, smooth-shaded mesh whose texture coordinates run
/// at 30° to its edges, turned and scaled unevenly.
#[test]
fn mitsuba_reference_bumps_on_a_mesh() {
    check_scene("bump_mesh");
}

/// Light selection with a point, a spot and a directional light in an
/// open room (Mitsuba 3 picks lights uniformly: its noise is the bar).
#[test]
fn mitsuba_reference_lights_mixed() {
    check_scene("lights_mixed");
}

/// Light selection with a dim sky (its sun low) and a small lamp under a roof.
#[test]
fn mitsuba_reference_lamp_and_sky() {
    check_scene("lamp_and_sky");
}

/// Light selection among area lights of very different sizes (a large
/// dim panel to a tiny bright ball) beside a constant background.
#[test]
fn mitsuba_reference_area_sizes() {
    check_scene("area_sizes");
}

/// The light selection rules side by side on the scenes with several
/// lights (run with `--ignored --nocapture`; the figures are in
/// docs/performance.md, "Light selection").
#[test]
// Open cylinders (Mitsuba's `cylinder` has no caps) and a group placed three
// times, turned and scaled (`shapegroup` + `instance`): shared geometry in
// ptsc too. scripts/mitsuba_composition.py writes the same scene for Mitsuba.
fn mitsuba_reference_composition() {
    check_scene("composition");
}

/// Capsules (issue 37): a diffuse one and a tube lamp, which Mitsuba makes
/// of an open `cylinder` and two `sphere`s. scripts/mitsuba_capsule.py
/// writes the same scene for Mitsuba.
#[test]
fn mitsuba_reference_capsule() {
    check_scene("capsule");
}

/// Light selection with a textured lamp whose image has a hot spot, a dim
/// environment map, a sun and two small lamps (issue 34).
/// Its mean is 1.2 % below Mitsuba's (over 256 seeds, with either
/// sampler): Mitsuba's environment map gives more direct light by emitter
/// sampling than by BSDF sampling (see the next test), and ptsc agrees with
/// the latter; 2 % allowed.
#[test]
fn mitsuba_reference_lights_textured() {
    check_scene_within("lights_textured", 0.02);
}

/// The difference kept on purpose: direct light from lights_textured's
/// environment map alone (`env_direct.pts`). Mitsuba 3's two estimates of
/// the same integral differ by 7 % (emitter sampling 0.1297, BSDF sampling
/// 0.1208, mean radiance); ptsc's, which samples the map and evaluates it
/// with the same lookup (checked direction by direction against Mitsuba's
/// `eval`), is within 1 % of the BSDF-sampled one, which needs nothing of
/// the map but its lookup.
#[test]
fn mitsuba_envmap_emitter_sampling_is_brighter_than_its_own_bsdf_sampling() {
    let dir = crate::root().join("tests/mitsuba");
    let mean = |name: &str| {
        let (_, _, px) = read_exr(&dir.join(name)).unwrap();
        let s = sum(&px);
        (s.x + s.y + s.z) as f64 / (3 * px.len()) as f64
    };
    let by_emitter = mean("env_direct_emitter_64_4096spp.exr");
    let by_bsdf = mean("env_direct_bsdf_64_16384spp.exr");
    let c = compile_file(&dir.join("env_direct.pts"), Options::default()).unwrap();
    let mut ir = c.ir.unwrap();
    ir.settings.samples = 1024;
    let integ = integrator::make(ir.settings.integrator, &ir);
    let cancel = AtomicBool::new(false);
    let px = render(&ir, integ.as_ref(), &cancel, &|_| {}, &mut |_, _| {})
        .film
        .pixels();
    let s = sum(&px);
    let ours = (s.x + s.y + s.z) as f64 / (3 * px.len()) as f64;
    eprintln!(
        "env_direct: ptsc {ours:.5}, Mitsuba by BSDF {by_bsdf:.5}, by emitter {by_emitter:.5}"
    );
    assert!(
        (ours / by_bsdf - 1.0).abs() < 0.01,
        "ptsc {ours} vs {by_bsdf}"
    );
    assert!(
        by_emitter / by_bsdf > 1.05,
        "Mitsuba's two estimates agree now: {by_emitter} vs {by_bsdf}"
    );
}

/// `auto` is at least as good as `uniform` (Mitsuba's rule) and `power` on
/// every scene of the references with more than one light (the others
/// have one: every rule picks it); the median error of the same seeds, up
/// to the spread of a median.
#[test]
fn auto_light_selection_is_never_worse_than_uniform_or_power() {
    for name in [
        "lights_mixed",
        "lamp_and_sky",
        "area_sizes",
        "lights_textured",
    ] {
        let auto = measure(name, Some(LightSelection::Auto)).mae;
        for rule in [LightSelection::Uniform, LightSelection::Power] {
            let other = measure(name, Some(rule)).mae;
            assert!(
                auto <= other * NOISE_SLACK,
                "{name}: auto's MAE/mean {auto:.5} against {rule:?}'s {other:.5}"
            );
        }
    }
}

#[test]
#[ignore]
fn light_selection_rules_against_mitsuba() {
    for name in [
        "lights_mixed",
        "lamp_and_sky",
        "area_sizes",
        "lights_textured",
        "textures",
        "materials",
    ] {
        for rule in [
            LightSelection::Auto,
            LightSelection::Uniform,
            LightSelection::Power,
            LightSelection::Exhaustive,
            LightSelection::Bvh,
        ] {
            let m = measure(name, Some(rule));
            let (ratio, mae, mitsuba) = (m.ratio, m.mae, m.mitsuba_mae);
            eprintln!(
                "RULES {name} {rule:?}: mean ratio {ratio:.4}, MAE/mean {mae:.5} = {:.3} × Mitsuba's",
                mae / mitsuba
            );
        }
    }
}
