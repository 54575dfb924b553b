//! Groups and instances: a scene written with groups placed by instances
//! renders the image of the same scene written out flat (each object with
//! its placements' transforms appended to its own, and the placement's
//! material where it names none), within the float noise of transforming
//! rays instead of geometry.

use proptest::prelude::*;
use ptsc::compile::{compile_str, Options};
use std::path::Path;

/// The pixels of `text` rendered on one thread.
fn pixels(text: &str) -> Vec<[f32; 3]> {
    placed_pixels(text).1
}

/// Whether the scene `text` shares geometry (at least one prototype), and
/// its pixels rendered on one thread: one compile for both.
fn placed_pixels(text: &str) -> (bool, Vec<[f32; 3]>) {
    let c = compile_str(Path::new("instances.pts"), text, Options::default());
    let ir =
        c.ir.unwrap_or_else(|| panic!("{}\n{text}", c.diagnostics.render_human(&c.sources, false)));
    (!ir.instances.is_empty(), crate::render_pixels(&ir))
}

const HEAD: &str = "render { resolution <48, 36> samples 16 max_depth 4 }\n\
    camera { position <0, 4, 9> look_at <0, 0.5, 0> }\n\
    material red { diffuse rgb <0.8, 0.2, 0.2> }\n\
    material tiles { diffuse checker { even rgb 0.9 odd rgb 0.1 scale 0.27 } }\n\
    plane { point <0, -0.001, 0> normal <0, 1, 0> material { diffuse rgb 0.5 } }\n\
    quad { corner <-2, 5, -2> edge1 <4, 0, 0> edge2 <0, 0, 4> material { emission rgb 4 } }\n\
    background rgb 0.2\n";

/// The parts of the groups: (shape with its own transforms, material entry).
const PARTS: &[&str] = &[
    "sphere { center <0, 0.5, 0> radius 0.4 }",
    "box { min <-0.3, 0.01, -0.3> max <0.3, 0.6, 0.3> rotate <0, 20, 0> material tiles }",
    "cylinder { base <0, 0, 0> top <0, 1, 0> radius 0.2 translate <0.5, 0, 0> }",
    "cone { base <0, 0, 0> top <0, 0.8, 0> base_radius 0.3 top_radius 0.05 material red }",
    "torus { major_radius 0.4 minor_radius 0.1 rotate <90, 0, 0> translate <0, 0.5, 0> }",
    "triangle { v0 <-0.5, 0, 0> v1 <0.5, 0, 0> v2 <0, 0.9, 0.2> material tiles }",
    "disk { center <0, 0.8, 0> normal <0, 1, 0.3> radius 0.3 }",
];

/// A placement: translate, rotate about y, uniform scale, material.
type Place = ([f64; 2], f64, f64, Option<&'static str>);

/// The grouped and the flat text of two groups (the second placing the
/// first at `inner`) placed at `outer` and `places`.
fn scenes(
    parts_a: &[usize],
    parts_b: &[usize],
    inner: Place,
    places: &[Place],
) -> (String, String) {
    let transforms = |(t, r, s, _): Place| {
        format!(
            "scale {s} rotate <0, {r}, 0> translate <{}, 0, {}>",
            t[0], t[1]
        )
    };
    let material = |m: Option<&str>| m.map_or(String::new(), |m| format!(" material {m}"));
    let mut grouped = HEAD.to_string();
    grouped += "group a {\n";
    for &k in parts_a {
        grouped += &format!("    {}\n", PARTS[k]);
    }
    grouped += "}\ngroup b {\n";
    for &k in parts_b {
        grouped += &format!("    {}\n", PARTS[k]);
    }
    grouped += &format!(
        "    instance a {{ {}{} }}\n}}\n",
        transforms(inner),
        material(inner.3)
    );
    for &p in places {
        grouped += &format!("instance b {{ {}{} }}\n", transforms(p), material(p.3));
        grouped += &format!("instance a {{ {}{} }}\n", transforms(p), material(p.3));
    }
    // Flat: each part with the transforms of its placements after its own
    // (innermost first), and the nearest placement's material if it has none.
    let mut flat = HEAD.to_string();
    let write = |flat: &mut String, part: &str, chain: &[Place]| {
        let body = part.trim_end_matches('}').trim_end();
        let has_material = part.contains("material");
        let mut extra = String::new();
        for &p in chain {
            extra += &format!(" {}", transforms(p));
        }
        let inherited = chain.iter().find_map(|p| p.3).filter(|_| !has_material);
        *flat += &format!("{body}{extra}{} }}\n", material(inherited));
    };
    for &p in places {
        for &k in parts_b {
            write(&mut flat, PARTS[k], &[p]);
        }
        for &k in parts_a {
            write(&mut flat, PARTS[k], &[inner, p]);
        }
        for &k in parts_a {
            write(&mut flat, PARTS[k], &[p]);
        }
    }
    (grouped, flat)
}

/// Compares two renders of the same scene: the same image up to the paths
/// that float rounding sends another way (a bounce that grazes a torus in
/// one and misses it in the other changes its pixel by a sample's worth).
fn assert_same_image(a: &[[f32; 3]], b: &[[f32; 3]], what: &str) {
    let (d, diff) = image_difference(a, b);
    eprintln!("relative MAE {d:.5}, {diff} of {} pixels differ", a.len());
    assert_images(a, b, what);
}

/// The mean absolute difference of two images over the first's mean, and
/// how many pixels differ at all.
fn image_difference(a: &[[f32; 3]], b: &[[f32; 3]]) -> (f64, usize) {
    let total: f64 = a.iter().flatten().map(|&x| x.abs() as f64).sum();
    let abs: f64 = (a.iter().flatten())
        .zip(b.iter().flatten())
        .map(|(x, y)| (x - y).abs() as f64)
        .sum();
    let differing = a
        .iter()
        .zip(b)
        .filter(|(x, y)| {
            x.iter()
                .zip(y.iter())
                .any(|(u, v)| (u - v).abs() > 1e-3 * (1.0 + u.abs()))
        })
        .count();
    (abs / total.max(1e-9), differing)
}

fn assert_images(a: &[[f32; 3]], b: &[[f32; 3]], what: &str) {
    let mean =
        |p: &[[f32; 3]]| p.iter().flatten().map(|&x| x as f64).sum::<f64>() / (3 * p.len()) as f64;
    let (ma, mb) = (mean(a), mean(b));
    assert!(
        (ma - mb).abs() <= 0.01 * ma.max(1e-3),
        "{what}: means {ma} vs {mb}"
    );
    // Most cases are identical to the last bit; surfaces that meet exactly
    // cost a few tenths of a percent (0.24 % in the worst case found, see
    // below). Normals left in the group's frame cost 0.6 % to 5.6 %
    // (checked by breaking them).
    let (mae, differing) = image_difference(a, b);
    assert!(
        mae <= 0.004,
        "{what}: relative MAE {mae:.5} ({differing} of {} pixels differ)",
        a.len()
    );
}

fn place() -> impl Strategy<Value = Place> {
    (
        (-2.5f64..2.5, -2.0f64..1.5),
        -180f64..180.0,
        0.5f64..1.5,
        prop::option::of(prop::sample::select(vec!["red", "tiles"])),
    )
        .prop_map(|((x, z), r, s, m)| {
            (
                [(x * 100.0).round() / 100.0, (z * 100.0).round() / 100.0],
                r.round(),
                (s * 100.0).round() / 100.0,
                m,
            )
        })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 6, ..ProptestConfig::default() })]
    #[test]
    fn grouped_and_flat_scenes_render_the_same_image(
        parts_a in prop::sample::subsequence((0..PARTS.len()).collect::<Vec<_>>(), 1..4),
        parts_b in prop::sample::subsequence((0..PARTS.len()).collect::<Vec<_>>(), 1..3),
        inner in place(),
        places in prop::collection::vec(place(), 2..4),
    ) {
        let (grouped, flat) = scenes(&parts_a, &parts_b, inner, &places);
        let (shared, grouped_pixels) = placed_pixels(&grouped);
        prop_assert!(shared, "the groups are placed several times: shared");
        assert_same_image(&grouped_pixels, &pixels(&flat), &grouped);
    }
}

/// Four placements of a mesh against the mesh written out four times; a
/// moving placement against a moving object.
#[test]
fn placed_meshes_and_moving_placements_match_their_flat_scenes() {
    let dir = crate::temp_dir_with(&[(
        "tet.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 -1\nvn 0 -1 0\nvn -1 0 0\nvn 1 1 1\n\
         f 1/1/1 3/3/1 2/2/1\nf 1/1/2 2/2/2 4/3/2\nf 1/1/3 4/3/3 3/2/3\nf 2/1/4 3/2/4 4/3/4\n",
    )]);
    let path = dir.path().join("s.pts");
    let head = "render { resolution <40, 30> samples 16 }\ncamera { position <0, 2, 6> look_at <0, 0.5, 0> shutter <0, 1> }\n\
                background rgb 1\nplane { normal <0, 1, 0> }\n";
    let placements = [
        "translate <-1.5, 0, 0>",
        "rotate <0, 45, 0> translate <0, 0, -1>",
        "scale 0.5 translate <1.5, 0, 0>",
        "translate <0, 1, 1> velocity <0.3, 0, 0>",
    ];
    let mut grouped = format!("{head}group t {{ mesh {{ file \"tet.obj\" smooth true material {{ diffuse image {{ file \"none\" }} }} }} }}\n");
    grouped = grouped.replace(" material { diffuse image { file \"none\" } }", "");
    let mut flat = head.to_string();
    for p in placements {
        let (transform, velocity) = match p.split_once(" velocity ") {
            Some((t, v)) => (t, format!(" velocity {v}")),
            None => (p, String::new()),
        };
        grouped += &format!("instance t {{ {p} }}\n");
        flat += &format!("mesh {{ file \"tet.obj\" smooth true {transform}{velocity} }}\n");
    }
    let render_at = |text: &str| {
        std::fs::write(&path, text).unwrap();
        let c = ptsc::compile::compile_file(&path, Options::default()).unwrap();
        let ir =
            c.ir.unwrap_or_else(|| panic!("{}", c.diagnostics.render_human(&c.sources, false)));
        (!ir.instances.is_empty(), crate::render_pixels(&ir))
    };
    let (shared, a) = render_at(&grouped);
    assert!(shared);
    let (flat_shared, b) = render_at(&flat);
    assert!(!flat_shared);
    assert_same_image(&a, &b, "meshes");
}

/// The peak memory `ptsc render` reports for `scene` (at 16 × 16, 1 spp).
fn peak_memory_mb(scene: &Path) -> f64 {
    let out = tempfile::tempdir().unwrap();
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_ptsc"))
        .args([
            "render",
            &scene.display().to_string(),
            "--spp",
            "1",
            "--resolution",
            "16x16",
            "-o",
        ])
        .arg(out.path().join("o.exr"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stderr}");
    let mb = stderr
        .split("peak memory ")
        .nth(1)
        .and_then(|r| r.split(" MB").next())
        .unwrap_or_else(|| panic!("no peak memory in {stderr}"));
    mb.parse().unwrap()
}

/// 1,000 placements of the 1,003,520-triangle bench blob take little more
/// memory than the blob once (the bound: 1.3 times).
#[test]
fn a_thousand_placed_blobs_take_the_memory_of_one() {
    ptsc::bench_data::ensure_mesh_blob(&crate::root()).unwrap();
    let one = peak_memory_mb(&crate::root().join("examples/bench/mesh.pts"));
    let thousand = peak_memory_mb(&crate::root().join("examples/bench/mesh_instances.pts"));
    assert!(
        thousand <= 1.3 * one,
        "1,000 placements: {thousand} MB; one blob: {one} MB"
    );
}

/// Four placements of the bench blob against the blob written out four
/// times: the same image.
#[test]
fn four_placed_blobs_match_four_blobs() {
    let blob = ptsc::bench_data::ensure_mesh_blob(&crate::root()).unwrap();
    let head = format!(
        "render {{ resolution <32, 24> samples 4 }}\ncamera {{ position <0, 3, 7> look_at <0, 0.8, 0> }}\n\
         background rgb 1\nplane {{ normal <0, 1, 0> }}\nlet blob = \"{}\";\n",
        blob.display()
    );
    let places = [
        "translate <-1.5, 0, 0>",
        "rotate <0, 90, 0> translate <1.5, 0, 0>",
        "scale 0.5 translate <0, 0, 1.5>",
        "rotate <0, 200, 0> translate <0, 0, -1.5>",
    ];
    let mut grouped = format!("{head}group b {{ mesh {{ file blob }} }}\n");
    let mut flat = head.clone();
    for p in places {
        grouped += &format!("instance b {{ {p} }}\n");
        flat += &format!("mesh {{ file blob {p} }}\n");
    }
    let (shared, grouped_pixels) = placed_pixels(&grouped);
    assert!(shared);
    assert_same_image(&grouped_pixels, &pixels(&flat), "blobs");
}

/// A case the property test found while the box stood on y = 0, where the
/// triangle's edge and the torus's lowest point also lie: where surfaces
/// of a group meet exactly, float rounding decides which is hit,
/// differently for a transformed ray and for transformed geometry (71
/// pixels of 1,728, relative MAE 0.24 %; with the box 0.01 higher, none).
#[test]
fn grazing_placements_match_their_flat_scene() {
    let (grouped, flat) = scenes(
        &[1, 4, 5],
        &[3],
        ([2.25, 1.5], 147.0, 1.27, None),
        &[
            ([-1.1, 1.36], -77.0, 1.2, None),
            ([1.35, 0.21], 119.0, 1.43, None),
            ([-0.27, 0.02], 32.0, 1.36, None),
        ],
    );
    assert_same_image(&pixels(&grouped), &pixels(&flat), &grouped);
}

/// An emissive shape in a group is a light at every placement: the
/// placements with it become the scene's own primitives (two lights), and
/// the image is the flat scene's.
#[test]
fn emissive_parts_of_groups_are_lights_at_every_placement() {
    let head = "render { resolution <32, 24> samples 8 }\ncamera { position <0, 2, 6> look_at <0, 0.5, 0> }\n\
                plane { normal <0, 1, 0> }\n";
    let lamp = "sphere { center <0, 1.5, 0> radius 0.1 material { emission rgb 40 } } box { min <-0.2, 0, -0.2> max <0.2, 1.3, 0.2> }";
    let grouped = format!(
        "{head}group lamp {{ {lamp} }}\ninstance lamp {{ translate <-1, 0, 0> }}\ninstance lamp {{ translate <1, 0, 0> }}\n"
    );
    let flat = format!(
        "{head}sphere {{ center <-1, 1.5, 0> radius 0.1 material {{ emission rgb 40 }} }} box {{ min <-1.2, 0, -0.2> max <-0.8, 1.3, 0.2> }}\n\
         sphere {{ center <1, 1.5, 0> radius 0.1 material {{ emission rgb 40 }} }} box {{ min <0.8, 0, -0.2> max <1.2, 1.3, 0.2> }}\n"
    );
    let c = compile_str(Path::new("lamps.pts"), &grouped, Options::default());
    let ir = c.ir.expect("compiles");
    assert_eq!(ir.area_lights.len(), 2, "one light per placement");
    assert_same_image(&pixels(&grouped), &pixels(&flat), "lamps");
}

/// A group holding the bench blob and a plane (which cannot be shared),
/// placed 1,000 times: the plane is copied at each placement, the blob
/// still shared (it used to be copied too: a billion triangles).
#[test]
fn a_plane_beside_a_placed_mesh_is_copied_alone() {
    let blob = ptsc::bench_data::ensure_mesh_blob(&crate::root()).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("s.pts");
    let text = format!(
        "camera {{ position <0, 3, 40> look_at <0, 0, 0> }}\nbackground rgb 1\n\
         group g {{ mesh {{ file \"{}\" }} plane {{ normal <0, 1, 0> }} }}\n\
         for i in 0..1000 {{ instance g {{ translate <i % 40 - 20, 0, -(i / 40)> }} }}\n",
        blob.display()
    );
    std::fs::write(&scene, text).unwrap();
    let one = peak_memory_mb(&crate::root().join("examples/bench/mesh.pts"));
    let placed = peak_memory_mb(&scene);
    assert!(
        placed <= 1.3 * one,
        "1,000 placements: {placed} MB; one blob: {one} MB"
    );
}

/// An emissive blob placed 100 times must be copied (lights are the
/// scene's primitives): 100 million triangles, refused before anything is
/// built, by check as by render.
#[test]
fn copies_past_the_primitive_limit_are_refused_by_check_and_render() {
    let blob = ptsc::bench_data::ensure_mesh_blob(&crate::root()).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("s.pts");
    let text = format!(
        "camera {{ position <0, 3, 40> look_at <0, 0, 0> }}\n\
         group lamp {{ mesh {{ file \"{}\" material {{ emission rgb 1 }} }} }}\n\
         for i in 0..100 {{ instance lamp {{ translate <i * 3, 0, 0> }} }}\n",
        blob.display()
    );
    std::fs::write(&scene, text).unwrap();
    let scene = scene.to_str().unwrap();
    let out = dir.path().join("o.png");
    for args in [
        vec!["check", scene],
        vec!["render", scene, "-o", out.to_str().unwrap()],
    ] {
        let started = std::time::Instant::now();
        let (code, err) = crate::ptsc_stderr(&args);
        assert_eq!(code, 1, "{args:?}: {err}");
        assert!(
            err.contains("too_many_primitives") && err.contains("100,352,000"),
            "{err}"
        );
        // One read of the blob, nothing built (a copy per placement took
        // minutes and tens of GB).
        assert!(started.elapsed().as_secs() < 60, "{args:?}");
    }
    assert!(!out.exists());
}
