//! Cutouts (`ir::cutout`): a surface's opacity lets rays through, for
//! camera, bounce and shadow rays alike. An image's alpha on a quad renders
//! as the opaque parts modelled as geometry, shadows included; a fraction
//! passes its share; placed groups, glTF's `MASK` and an OBJ's `map_d` cut
//! the same way.

use crate::gltf::Doc;
use ptsc::compile::{compile_file, Options};
use serde_json::json;
use std::path::Path;

/// A sunlit floor seen from above at an angle, so that a cut-out wall and
/// its shadow are both in view.
const STAGE: &str = "camera { position <0.5, 2.2, 4> look_at <0, 0.5, 0> fov 45 }
render { resolution <64, 48> samples 16 }
sky { sun_elevation 35 sun_azimuth 30 }
plane { normal <0, 1, 0> material { diffuse rgb 0.6 } }
";

fn compile(dir: &Path, scene: &str) -> ptsc::compile::Compiled {
    let path = dir.join("scene.pts");
    std::fs::write(&path, scene).unwrap();
    compile_file(&path, Options::default()).unwrap()
}

fn pixels(dir: &Path, scene: &str) -> Vec<[f32; 3]> {
    let c = compile(dir, scene);
    match c.ir.as_ref() {
        Some(ir) => crate::render_pixels(ir),
        None => panic!("{}", c.diagnostics.render_human(&c.sources, false)),
    }
}

/// The scene of [`STAGE`] with another seed.
fn reseeded(scene: &str) -> String {
    let other = scene.replace("samples 16 }", "samples 16 seed 7 }");
    assert_ne!(other, scene);
    other
}

/// The mean absolute difference of two images, over every channel.
fn mean_difference(a: &[[f32; 3]], b: &[[f32; 3]]) -> f64 {
    let sum: f64 = (a.iter().zip(b))
        .flat_map(|(p, q)| (0..3).map(move |k| (p[k] - q[k]).abs() as f64))
        .sum();
    sum / (3 * a.len()) as f64
}

/// How many pixels differ by more than `by` in some channel.
fn differing(a: &[[f32; 3]], b: &[[f32; 3]], by: f32) -> usize {
    (a.iter().zip(b))
        .filter(|(p, q)| (0..3).any(|k| (p[k] - q[k]).abs() > by))
        .count()
}

/// An RGBA PNG of `width` × `height` whose alpha is `alpha(x, y)` (0 or
/// 255) and whose colour is a flat green.
fn rgba_png(width: u32, height: u32, alpha: impl Fn(u32, u32) -> u8) -> Vec<u8> {
    let mut data = Vec::new();
    for y in 0..height {
        for x in 0..width {
            data.extend_from_slice(&[60, 160, 40, alpha(x, y)]);
        }
    }
    let mut out = Vec::new();
    let mut encoder = png::Encoder::new(&mut out, width, height);
    encoder.set_color(png::ColorType::Rgba);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header().unwrap();
    writer.write_image_data(&data).unwrap();
    writer.finish().unwrap();
    out
}

/// Four texels across, opaque, clear, opaque, clear: read bilinearly, the
/// alpha crosses 0.5 exactly at the texels' edges, so the opaque parts are
/// u in [0, 1/4] and [1/2, 3/4].
fn stripes_png() -> Vec<u8> {
    rgba_png(4, 1, |x, _| if x % 2 == 0 { 255 } else { 0 })
}

const WALL: &str = "material { diffuse rgb <0.7, 0.3, 0.2>
    opacity image { file \"stripes.png\" channel a wrap clamp } opacity_cutoff 0.5 }";

#[test]
fn an_alpha_masked_quad_renders_as_its_opaque_parts_modelled_shadows_included() {
    let dir = crate::temp_dir_with(&[]);
    std::fs::write(dir.path().join("stripes.png"), stripes_png()).unwrap();
    let cut =
        format!("{STAGE}quad {{ corner <-1, 0, 0> edge1 <2, 0, 0> edge2 <0, 1.2, 0> {WALL} }}");
    let modelled = format!(
        "{STAGE}quad {{ corner <-1, 0, 0> edge1 <0.5, 0, 0> edge2 <0, 1.2, 0> material {{ diffuse rgb <0.7, 0.3, 0.2> }} }}
         quad {{ corner <0, 0, 0> edge1 <0.5, 0, 0> edge2 <0, 1.2, 0> material {{ diffuse rgb <0.7, 0.3, 0.2> }} }}"
    );
    let a = pixels(dir.path(), &cut);
    let b = pixels(dir.path(), &modelled);
    // The same paths meet the same surfaces: equal but for f32 rounding at
    // the stripes' edges.
    assert!(
        differing(&a, &b, 1e-3) <= 6,
        "{} pixels differ",
        differing(&a, &b, 1e-3)
    );
    // The test can fail: the wall whole, or the other stripes, are other images.
    let whole = format!(
        "{STAGE}quad {{ corner <-1, 0, 0> edge1 <2, 0, 0> edge2 <0, 1.2, 0> material {{ diffuse rgb <0.7, 0.3, 0.2> }} }}"
    );
    assert!(differing(&pixels(dir.path(), &whole), &b, 0.02) > 100);
    let shifted = cut.replace("corner <-1, 0, 0>", "corner <-0.5, 0, 0>");
    assert!(differing(&pixels(dir.path(), &shifted), &b, 0.02) > 100);
}

#[test]
fn a_leaf_shaped_mask_renders_as_the_leaf_modelled_within_noise() {
    // A rhombus leaf in a 256² image's alpha; the same rhombus as two
    // triangles. The image's edges are a texel off at most: far below noise.
    let n = 256u32;
    let inside = |x: u32, y: u32| {
        let (u, v) = ((x as f64 + 0.5) / n as f64, (y as f64 + 0.5) / n as f64);
        (u - 0.5).abs() / 0.3 + (v - 0.5).abs() / 0.5 <= 1.0
    };
    let dir = crate::temp_dir_with(&[]);
    std::fs::write(
        dir.path().join("leaf.png"),
        rgba_png(n, n, |x, y| if inside(x, y) { 255 } else { 0 }),
    )
    .unwrap();
    let leaf_material = "material { diffuse rgb <0.2, 0.6, 0.1> }";
    let cut = format!(
        "{STAGE}quad {{ corner <-0.5, 0.1, 0> edge1 <1, 0, 0> edge2 <0, 1, 0>
           material {{ diffuse rgb <0.2, 0.6, 0.1> opacity image {{ file \"leaf.png\" channel a }} opacity_cutoff 0.5 }} }}"
    );
    // Image row 0 is the top (v = 1): the rhombus is symmetric anyway.
    let modelled = format!(
        "{STAGE}triangle {{ v0 <-0.3, 0.6, 0> v1 <0.3, 0.6, 0> v2 <0, 1.1, 0> {leaf_material} }}
         triangle {{ v0 <-0.3, 0.6, 0> v1 <0, 0.1, 0> v2 <0.3, 0.6, 0> {leaf_material} }}"
    );
    let a = pixels(dir.path(), &cut);
    let b = pixels(dir.path(), &modelled);
    let other_seed = pixels(dir.path(), &reseeded(&modelled));
    let noise = mean_difference(&b, &other_seed);
    let difference = mean_difference(&a, &b);
    assert!(
        difference < 0.25 * noise,
        "cut vs modelled {difference:.5}, noise {noise:.5}"
    );
    // The leaf is in view, with its shadow.
    let bare = pixels(dir.path(), STAGE);
    assert!(differing(&bare, &b, 0.05) > 60);
}

#[test]
fn a_fraction_of_opacity_passes_its_share_of_camera_and_shadow_rays() {
    let dir = crate::temp_dir_with(&[]);
    // A black quad filling the view in front of a white background.
    let view = |material: &str| {
        format!(
            "camera {{ position <0, 0, 2> look_at <0, 0, 0> fov 30 }}
             render {{ resolution <32, 32> samples 64 }}
             background rgb 1
             quad {{ corner <-2, -2, 0> edge1 <4, 0, 0> edge2 <0, 4, 0> material {{ diffuse rgb 0 {material} }} }}"
        )
    };
    let mean = |p: &[[f32; 3]]| p.iter().map(|c| c[1] as f64).sum::<f64>() / p.len() as f64;
    let blend = mean(&pixels(dir.path(), &view("opacity 0.3")));
    // 65536 Bernoulli samples: a standard deviation of 0.0018.
    assert!((blend - 0.7).abs() < 0.01, "{blend}");
    let clear = pixels(dir.path(), &view("opacity 0.3 opacity_cutoff 0.5"));
    assert!(clear.iter().all(|c| (c[1] - 1.0).abs() < 1e-6));
    let solid = pixels(dir.path(), &view("opacity 0.6 opacity_cutoff 0.5"));
    assert!(solid.iter().all(|c| c[1] == 0.0));
    // A roof of opacity 0.3 between the sun and the floor lets 0.7 of the
    // sunlight through (a black roof reflects nothing).
    let floor = |roof: &str| {
        format!(
            "camera {{ position <0, 1, 3> look_at <0, 0, 0> fov 30 }}
             render {{ resolution <32, 32> samples 64 }}
             directional_light {{ direction <0, -1, 0> irradiance rgb 3 }}
             plane {{ normal <0, 1, 0> material {{ diffuse rgb 0.5 }} }}
             {roof}"
        )
    };
    let lit = mean(&pixels(dir.path(), &floor("")));
    let roof = "quad { corner <-50, 5, -50> edge1 <100, 0, 0> edge2 <0, 0, 100> material { diffuse rgb 0 opacity 0.3 } }";
    let shaded = mean(&pixels(dir.path(), &floor(roof)));
    assert!(lit > 0.1);
    assert!((shaded / lit - 0.7).abs() < 0.02, "{shaded} / {lit}");
}

#[test]
fn placed_groups_glb_masks_and_obj_map_d_cut_as_the_scene_does() {
    let dir = crate::temp_dir_with(&[]);
    std::fs::write(dir.path().join("stripes.png"), stripes_png()).unwrap();
    let quad = |at: f32| {
        format!("quad {{ corner <{at}, 0, 0> edge1 <1, 0, 0> edge2 <0, 1.2, 0> {WALL} }}\n")
    };
    let reference = pixels(dir.path(), &format!("{STAGE}{}{}", quad(-1.2), quad(0.2)));
    // A group placed twice: its prototype's primitives are cut out too.
    let grouped = format!(
        "{STAGE}group wall {{ quad {{ corner <0, 0, 0> edge1 <1, 0, 0> edge2 <0, 1.2, 0> {WALL} }} }}
         instance wall {{ translate <-1.2, 0, 0> }}
         instance wall {{ translate <0.2, 0, 0> }}"
    );
    let placed = compile(dir.path(), &grouped);
    assert_eq!(placed.ir.as_ref().unwrap().instances.placements.len(), 2);
    let p = crate::render_pixels(placed.ir.as_ref().unwrap());
    assert!(
        differing(&p, &reference, 1e-3) <= 6,
        "{}",
        differing(&p, &reference, 1e-3)
    );
    // The same walls from a GLB whose material is MASK over the image's alpha.
    let mut d = Doc::default();
    let image = d.view(&stripes_png());
    d.images
        .push(json!({"bufferView": image, "mimeType": "image/png"}));
    d.textures.push(json!({"source": 0, "sampler": 0}));
    d.materials
        .push(json!({"alphaMode": "MASK", "pbrMetallicRoughness": {
        "baseColorFactor": [1, 1, 1, 1], "baseColorTexture": {"index": 0},
        "metallicFactor": 0.0}}));
    let positions = [
        0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.2, 0.0, 0.0, 1.2, 0.0,
    ];
    // glTF's v runs down the image: v = 1 − ptsc's.
    let uvs = [0.0f32, 1.0, 1.0, 1.0, 1.0, 0.0, 0.0, 0.0];
    let mesh = d.mesh(&positions, Some(&uvs), &[0, 1, 2, 0, 2, 3], Some(0));
    let node = d.node(json!({"mesh": mesh}));
    d.roots.push(node);
    let mut text: serde_json::Value = serde_json::from_str(&d.gltf()).unwrap();
    text["samplers"] = json!([{"wrapS": 33071, "wrapT": 33071}]);
    std::fs::write(dir.path().join("wall.gltf"), text.to_string()).unwrap();
    let file_wall = |at: f32| format!("mesh {{ file \"wall.gltf\" translate <{at}, 0, 0> }}\n");
    let c = compile(
        dir.path(),
        &format!("{STAGE}{}{}", file_wall(-1.2), file_wall(0.2)),
    );
    let warnings = c.diagnostics.render_human(&c.sources, false);
    assert!(!warnings.contains("alphaMode"), "{warnings}");
    let from_file = crate::render_pixels(c.ir.as_ref().unwrap());
    // Written in .pts: the file's principled material, its base colour and
    // its opacity read from the image.
    let principled = |at: f32| {
        format!(
            "quad {{ corner <{at}, 0, 0> edge1 <1, 0, 0> edge2 <0, 1.2, 0>
               material {{ type principled base_color image {{ file \"stripes.png\" wrap clamp }} roughness 1 metallic 0
                 opacity image {{ file \"stripes.png\" channel a wrap clamp }} opacity_cutoff 0.5 }} }}\n"
        )
    };
    let written = pixels(
        dir.path(),
        &format!("{STAGE}{}{}", principled(-1.2), principled(0.2)),
    );
    let n = differing(&from_file, &written, 2e-3);
    assert!(n <= 6, "{n} pixels differ");
    // A scene material replaces the file's, cutout included: the wall is whole.
    let replaced =
        format!("{STAGE}mesh {{ file \"wall.gltf\" material {{ diffuse rgb <0.7, 0.3, 0.2> }} }}");
    assert!(compile(dir.path(), &replaced).ir.unwrap().cutouts.is_none());
}

#[test]
fn an_obj_materials_map_d_is_its_images_alpha() {
    let dir = crate::temp_dir_with(&[]);
    std::fs::write(dir.path().join("stripes.png"), stripes_png()).unwrap();
    std::fs::write(
        dir.path().join("wall.obj"),
        "mtllib wall.mtl\nv 0 0 0\nv 1 0 0\nv 1 1.2 0\nv 0 1.2 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl W\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n",
    )
    .unwrap();
    std::fs::write(
        dir.path().join("wall.mtl"),
        "newmtl W\nKd 0.7 0.3 0.2\nmap_d -clamp on stripes.png\n",
    )
    .unwrap();
    let obj = format!(
        "{STAGE}mesh {{ file \"wall.obj\" translate <-1.2, 0, 0> }}\nmesh {{ file \"wall.obj\" translate <0.2, 0, 0> }}"
    );
    let o = pixels(dir.path(), &obj);
    // Written in .pts: `map_d` has no cutoff, so the bilinear alpha's
    // fractions pass at random: the same image within noise (the random
    // choices hash other primitive numbers).
    let written = |extra: &str| {
        let wall = |at: f32| {
            format!(
                "quad {{ corner <{at}, 0, 0> edge1 <1, 0, 0> edge2 <0, 1.2, 0>
                   material {{ type principled base_color rgb <0.7, 0.3, 0.2> roughness 0.5 {extra} }} }}\n"
            )
        };
        format!("{STAGE}{}{}", wall(-1.2), wall(0.2))
    };
    let cut = written("opacity image { file \"stripes.png\" channel a wrap clamp }");
    let reference = pixels(dir.path(), &cut);
    let noise = mean_difference(&reference, &pixels(dir.path(), &reseeded(&cut)));
    let difference = mean_difference(&o, &reference);
    // Measured: 0.3 of another seed's difference.
    assert!(
        difference < 0.6 * noise,
        "{difference:.5} vs noise {noise:.5}"
    );
    // The test can fail: whole walls are another image.
    let whole = pixels(dir.path(), &written(""));
    let far = mean_difference(&whole, &reference);
    assert!(far > 1.5 * noise, "whole walls {far:.5}, noise {noise:.5}");
}
