//! Rendering: determinism across thread counts, white furnace, a closed-form
//! case, and the command line's exit codes.

use ptsc::accel::ray_count::RayCounts;
use ptsc::compile::{compile_str, Options};
use ptsc::integrator;
use ptsc::render::{film::Film, render, Rendered};
use std::path::Path;
use std::sync::atomic::AtomicBool;

fn film_of(text: &str, threads: usize) -> Film {
    film_at(Path::new("test.pts"), text, threads)
}

/// Renders `text` as if it were the scene file `path` (for relative mesh files).
fn film_at(path: &Path, text: &str, threads: usize) -> Film {
    rendered_at(path, text, threads).film
}

fn rendered_at(path: &Path, text: &str, threads: usize) -> Rendered {
    let c = compile_str(path, text, Options::default());
    let ir =
        c.ir.unwrap_or_else(|| panic!("{}", c.diagnostics.render_human(&c.sources, false)));
    let integ = integrator::make(ir.settings.integrator, &ir);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    let cancel = AtomicBool::new(false);
    pool.install(|| render(&ir, integ.as_ref(), &cancel, &|_| {}, &mut |_, _| {}))
}

fn mean(f: &Film) -> [f64; 3] {
    let px = f.pixels();
    let mut m = [0.0; 3];
    for p in &px {
        m[0] += p.x as f64;
        m[1] += p.y as f64;
        m[2] += p.z as f64;
    }
    m.map(|v| v / px.len() as f64)
}

#[test]
fn same_image_for_one_and_two_threads() {
    let text = std::fs::read_to_string(crate::root().join("examples/bench/cornell.pts")).unwrap();
    let text = text
        .replace("resolution <512, 512>", "resolution <40, 40>")
        .replace("samples 64", "samples 4");
    let a = film_of(&text, 1);
    let b = film_of(&text, 2);
    let dir = tempfile::tempdir().unwrap();
    a.write(&dir.path().join("a.exr"), 0.0).unwrap();
    b.write(&dir.path().join("b.exr"), 0.0).unwrap();
    assert_eq!(
        std::fs::read(dir.path().join("a.exr")).unwrap(),
        std::fs::read(dir.path().join("b.exr")).unwrap()
    );
    assert!(mean(&a)[0] > 0.01, "the cornell box is not black");
}

#[test]
fn a_render_counts_the_rays_it_traced() {
    // Looking straight down at a plane that fills the view, a point light
    // above it, two segments: every path is a camera ray, one shadow ray and
    // one BSDF ray (traced to see whether it meets an emitter; then the path
    // ends). Counted per thread and summed per tile: the same for any
    // thread count.
    let text = "render { resolution <8, 8> samples 4 max_depth 2 }
camera { position <0, 1, 0> look_at <0, 0, 0> up <0, 0, -1> fov 10 }
plane { normal <0, 1, 0> material { diffuse rgb 0.6 } }
point_light { position <0, 2, 0> intensity rgb 10 }
";
    let paths = 8 * 8 * 4;
    for threads in [1, 2] {
        let r = rendered_at(Path::new("test.pts"), text, threads);
        assert_eq!(
            r.rays,
            RayCounts {
                closest: 2 * paths,
                shadow: paths
            },
            "{threads} threads"
        );
    }
}

const FURNACE: &str = "render { resolution <16, 16> samples 256 max_depth 64 rr_depth 5 }
camera { position <0, 0, 4> look_at <0, 0, 0> fov 30 }
background rgb 0.5
";

#[test]
fn white_furnace_diffuse_glossy_and_glass() {
    for m in [
        "diffuse rgb 1",
        "reflection rgb 1 gloss 0.4",
        "reflection rgb 1 gloss 1",
        "transmission 1 ior 1.5",
    ] {
        let text = format!("{FURNACE}sphere {{ center <0, 0, 0> radius 1 material {{ {m} }} }}\n");
        let got = mean(&film_of(&text, 2));
        for c in got {
            assert!(
                (c - 0.5).abs() < 0.5 * 0.005,
                "{m}: mean {got:?}, expected 0.5 within 0.5 %"
            );
        }
    }
}

#[test]
fn point_light_on_a_diffuse_plane_is_exact() {
    // Camera straight down at the plane; light 2 above the centre: the central
    // pixel sees albedo/π · I · cos θ / r² with cos θ ≈ 1, r = 2.
    let text = "render { resolution <33, 33> samples 16 integrator whitted max_depth 2 }
camera { position <0, 1, 0.0001> look_at <0, 0, 0> up <0, 0, -1> fov 1 }
plane { normal <0, 1, 0> material { diffuse rgb 0.6 } }
point_light { position <0, 2, 0> intensity rgb 10 }
";
    let f = film_of(text, 2);
    let centre = f.pixels()[(16 * 33 + 16) as usize];
    let expect = 0.6 / std::f32::consts::PI * 10.0 / 4.0;
    assert!(
        (centre.x - expect).abs() < expect * 1e-3,
        "{} vs {expect}",
        centre.x
    );
}

#[test]
fn whitted_direct_light_matches_path_with_two_segments() {
    let base = "camera { position <0, 1, 4> look_at <0, 0.5, 0> fov 40 }
plane { normal <0, 1, 0> material { diffuse rgb 0.7 } }
sphere { center <0, 0.5, 0> radius 0.5 material { diffuse rgb <0.3, 0.6, 0.9> } }
quad { corner <-0.5, 2, -0.5> edge1 <1, 0, 0> edge2 <0, 0, 1> material { emission rgb 5 } }
";
    let w = mean(&film_of(&format!("render {{ resolution <24, 24> samples 256 integrator whitted max_depth 2 light_samples 4 }}\n{base}"), 2));
    let p = mean(&film_of(
        &format!(
            "render {{ resolution <24, 24> samples 1024 integrator path max_depth 2 }}\n{base}"
        ),
        2,
    ));
    for k in 0..3 {
        assert!(
            (w[k] - p[k]).abs() < 0.02 * p[k].max(1e-3),
            "whitted {w:?} vs path {p:?}"
        );
    }
}

#[test]
fn whitted_with_many_lights_samples_them_and_matches_path() {
    // 40 lamps (more than Whitted visits one by one) of very different
    // brightness and a point light: Whitted's chosen-light estimate of
    // direct light equals the path tracer's with two segments, and so does
    // every selection rule's.
    let mut base = String::from(
        "camera { position <0, 1, 4> look_at <0, 0.5, 0> fov 40 }
plane { normal <0, 1, 0> material { diffuse rgb 0.7 } }
sphere { center <0, 0.5, 0> radius 0.5 material { diffuse rgb <0.3, 0.6, 0.9> } }
point_light { position <1, 1.5, 1> intensity rgb 2 }
",
    );
    for i in 0..40 {
        let (x, z) = ((i % 8) as f64 * 0.5 - 2.0, (i / 8) as f64 * 0.5 - 1.5);
        let e = 2.0 + (i * 7 % 11) as f64;
        base.push_str(&format!(
            "quad {{ corner <{x}, 1.8, {z}> edge1 <0.2, 0, 0> edge2 <0, 0, 0.2> material {{ diffuse rgb 0 emission rgb {e} }} }}\n"
        ));
    }
    let w = mean(&film_of(&format!("render {{ resolution <24, 24> samples 256 integrator whitted max_depth 2 light_samples 4 }}\n{base}"), 2));
    for rule in ["auto", "bvh", "power", "uniform"] {
        let p = mean(&film_of(
            &format!(
                "render {{ resolution <24, 24> samples 1024 integrator path max_depth 2 light_selection {rule} }}\n{base}"
            ),
            2,
        ));
        for k in 0..3 {
            assert!(
                (w[k] - p[k]).abs() < 0.02 * p[k].max(1e-3),
                "whitted {w:?} vs path ({rule}) {p:?}"
            );
        }
    }
}

use crate::ptsc_stderr as ptsc;

#[test]
fn exit_codes() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("s.pts");
    std::fs::write(&scene, "camera { position <0,0,5> look_at <0,0,0> }\nbackground rgb 1\nsphere { center <0,0,0> radius 1 }\n").unwrap();
    let s = scene.to_str().unwrap();
    let out = dir.path().join("out.png");
    assert_eq!(
        ptsc(&[
            "render",
            s,
            "-o",
            out.to_str().unwrap(),
            "--resolution",
            "8x8",
            "--spp",
            "2"
        ])
        .0,
        0
    );
    assert!(out.is_file());
    let (code, err) = ptsc(&[
        "render",
        s,
        "-o",
        dir.path().join("missing/out.png").to_str().unwrap(),
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("does not exist"));
    assert_eq!(
        ptsc(&["check", dir.path().join("nope.pts").to_str().unwrap()]).0,
        2
    );
    assert_eq!(ptsc(&["check", "--bogus"]).0, 2);
    let bad = dir.path().join("bad.pts");
    std::fs::write(&bad, "mesh { file \"missing.ply\" }").unwrap();
    assert_eq!(ptsc(&["render", bad.to_str().unwrap()]).0, 1);
    let broken_ply = dir.path().join("broken.ply");
    std::fs::write(
        &broken_ply,
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_header\n1 2",
    )
    .unwrap();
    let m = dir.path().join("m.pts");
    std::fs::write(&m, "camera { position <0,0,5> look_at <0,0,0> }\nbackground rgb 1\nmesh { file \"broken.ply\" }\n").unwrap();
    let (code, err) = ptsc(&["render", m.to_str().unwrap(), "--resolution", "8x8"]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("cannot load mesh"), "{err}");
    // The previous image survives a failed render.
    let before = std::fs::read(&out).unwrap();
    let _ = ptsc(&["render", m.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert_eq!(std::fs::read(&out).unwrap(), before);
}

#[test]
fn moving_emitters_are_sampled_where_they_are() {
    // A light moving at <3, 0, 0> per unit time, seen at time 1 only, must
    // light the floor exactly as the same light placed at time 1's position.
    let scene = |light: &str, shutter: &str| {
        format!(
            "render {{ resolution <24, 24> samples 64 max_depth 3 }}
camera {{ position <0.5, 4, 0.01> look_at <0.5, 0, 0> fov 60 shutter {shutter} }}
plane {{ normal <0, 1, 0> material {{ diffuse rgb 0.8 }} }}
{light}
"
        )
    };
    let moving = mean(&film_of(
        &scene(
            "sphere { center <-2, 1, 0> radius 0.3 velocity <3, 0, 0> material { emission rgb 5 } }",
            "<1, 1>",
        ),
        2,
    ));
    let fixed = mean(&film_of(
        &scene(
            "sphere { center <1, 1, 0> radius 0.3 material { emission rgb 5 } }",
            "<0, 0>",
        ),
        2,
    ));
    // The same random numbers drive both renders: only float rounding differs.
    for k in 0..3 {
        assert!(
            (moving[k] - fixed[k]).abs() < 1e-3 * fixed[k],
            "moving {moving:?} vs fixed {fixed:?}"
        );
    }
}

#[test]
fn plain_mesh_triangles_light_the_scene_as_records_do() {
    // A flat mesh's triangles have no 64-byte record (their blocks in the
    // BVH hold them); an emissive one must still be sampled as a light, as
    // the same triangle with vertex normals (which keeps its record) is. The
    // floor is a plain mesh too, so that blocks also hold triangles that
    // are not lights.
    let dir = crate::temp_dir_with(&[
        (
            "light.obj",
            "v -1 2 -1\nv 1 2 -1\nv 0 2 1\nvn 0 -1 0\nf 1//1 2//1 3//1\n",
        ),
        (
            "floor.obj",
            "v -5 0 -5\nv -5 0 5\nv 5 0 5\nv 5 0 -5\nf 1 2 3\nf 1 3 4\n",
        ),
    ]);
    let scene = |smooth: bool| {
        format!(
            "render {{ resolution <24, 24> samples 16 max_depth 3 }}
camera {{ position <0, 6, 4> look_at <0, 0, 0> fov 50 }}
mesh {{ file \"floor.obj\" material {{ diffuse rgb 0.8 }} }}
mesh {{ file \"light.obj\" smooth {smooth} material {{ diffuse rgb 0 emission rgb 5 }} }}
"
        )
    };
    let path = dir.path().join("s.pts");
    let plain = mean(&film_at(&path, &scene(false), 2));
    let record = mean(&film_at(&path, &scene(true), 2));
    // The same random numbers drive both renders: only float rounding differs.
    assert!(plain[0] > 0.05, "the floor is lit: {plain:?}");
    for k in 0..3 {
        assert!(
            (plain[k] - record[k]).abs() < 1e-3 * record[k],
            "plain {plain:?} vs record {record:?}"
        );
    }
}

#[test]
fn a_pinhole_with_an_open_shutter_stratifies_its_samples_times() {
    // The lens slot a pinhole does not use is skipped, not drawn: the time
    // keeps its own Sobol slot, so a pixel's 16 samples take one time in
    // each sixteenth of the shutter (a time drawn from the lens slot would
    // fall to the independent stream and leave strata empty).
    let text = "render { resolution <8, 8> samples 16 }\n\
        camera { position <0, 0, -5> look_at <0, 0, 0> shutter <0, 2> }\n\
        sphere { center <0, 0, 0> radius 1 material { diffuse rgb 0.5 } velocity <1, 0, 0> }\n";
    let c = compile_str(Path::new("shutter.pts"), text, Options::default());
    let scene =
        c.ir.unwrap_or_else(|| panic!("{}", c.diagnostics.render_human(&c.sources, false)));
    for (x, y) in [(0, 0), (3, 5), (7, 7)] {
        let pixel = ptsc::render::pixel_sampler(&scene, x, y);
        let mut strata = [false; 16];
        for i in 0..16 {
            let ray = ptsc::render::camera_ray(&scene, &mut pixel.sample(i), (x, y), 1.0);
            let cell = (ray.time / 2.0 * 16.0) as usize;
            assert!(
                !strata[cell],
                "pixel ({x}, {y}), sample {i}: stratum {cell} twice"
            );
            strata[cell] = true;
        }
    }
}
