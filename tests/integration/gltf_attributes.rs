//! A glTF mesh's vertex attributes beyond positions: normal maps take
//! their frame from tangents (`lower::tangents`: the file's `TANGENT` with
//! its handedness, else MikkTSpace's, smooth across the triangles of a
//! curved mesh as the maps are baked), and `COLOR_0` multiplies the base
//! colour.

use crate::gltf::Doc;
use glam::Vec3;
use ptsc::compile::{compile_file, Options};
use ptsc::geometry::Ray;
use serde_json::json;
use std::f32::consts::TAU;

/// The side of an open cylinder of `SEGMENTS` flat faces (radius 1, y from
/// 0 to 1) with smooth normals and u around it, its material a normal map
/// of one texel; `tangents`: the file's, each vertex's `w` given.
const SEGMENTS: usize = 8;

/// Material 0 of `d`: a normal map of one `texel`, held in the file.
fn normal_mapped(d: &mut Doc, texel: [u8; 3]) {
    let png = crate::gltf::flat_png(texel);
    let view = d.view(&png);
    d.images
        .push(json!({"bufferView": view, "mimeType": "image/png"}));
    d.textures.push(json!({"source": 0}));
    d.materials.push(json!({"normalTexture": {"index": 0}}));
}

fn cylinder(texel: [u8; 3], tangents: Option<f32>) -> Doc {
    let mut d = Doc::default();
    let (mut p, mut n, mut uv, mut t) = (vec![], vec![], vec![], vec![]);
    for i in 0..=SEGMENTS {
        let a = TAU * i as f32 / SEGMENTS as f32;
        for y in [0.0, 1.0] {
            p.extend([a.sin(), y, a.cos()]);
            n.extend([a.sin(), 0.0, a.cos()]);
            // glTF's v runs down the image: ptsc's v (up) is y.
            uv.extend([i as f32 / SEGMENTS as f32, 1.0 - y]);
            t.extend([a.cos(), 0.0, -a.sin(), tangents.unwrap_or(1.0)]);
        }
    }
    let mut indices = vec![];
    for i in 0..SEGMENTS as u32 {
        let (a, b) = (2 * i, 2 * i + 2);
        indices.extend([a, b, b + 1, a, b + 1, a + 1]);
    }
    normal_mapped(&mut d, texel);
    let mut attributes = json!({
        "POSITION": d.floats(&p, "VEC3", 3),
        "NORMAL": d.floats(&n, "VEC3", 3),
        "TEXCOORD_0": d.floats(&uv, "VEC2", 2),
    });
    if tangents.is_some() {
        attributes["TANGENT"] = json!(d.floats(&t, "VEC4", 4));
    }
    let indices = d.indices(&indices);
    d.meshes.push(
        json!({"primitives": [{"attributes": attributes, "indices": indices, "material": 0}]}),
    );
    let node = d.node(json!({"mesh": 0}));
    d.roots.push(node);
    d
}

/// The shading normal a normal map gives where a ray from outside meets
/// the cylinder of `scene` at angle `a` around it, half way up.
fn bent_normal(scene: &str, doc: &Doc, a: f32) -> Vec3 {
    let dir = crate::temp_dir_with(&[]);
    std::fs::write(dir.path().join("c.glb"), doc.glb()).unwrap();
    let path = dir.path().join("s.pts");
    std::fs::write(&path, scene).unwrap();
    let c = compile_file(&path, Options::default()).unwrap();
    let ir =
        c.ir.as_ref()
            .unwrap_or_else(|| panic!("{}", c.diagnostics.render_human(&c.sources, false)));
    let outward = Vec3::new(a.sin(), 0.0, a.cos());
    let ray = Ray::new(outward * 3.0 + Vec3::Y * 0.5, -outward, 0.0);
    let mut hit = ir.intersect(&ray, 0.0, f32::INFINITY).expect("a hit");
    ir.material_at(&mut hit, outward, 0.0, &mut None);
    hit.n_shading
}

const SCENE: &str = "camera { position <0, 0.5, 4> look_at <0, 0.5, 0> }
background rgb 1
mesh { file \"c.glb\" }
";

#[test]
fn tangents_read_or_generated_follow_u_around_a_cylinder() {
    // A texel (0.78, ½, 0.78) tilts the normal 45° towards the tangent.
    let along_tangent = [200, 128, 200];
    let step = TAU / SEGMENTS as f32;
    for tangents in [None, Some(1.0)] {
        let doc = cylinder(along_tangent, tangents);
        // Just before, on and just after an edge between two faces, and
        // in the middle of a face: the tangent around the cylinder there.
        for a in [step - 0.02, step + 0.02, 1.5 * step, 3.0 * step + 0.01] {
            let got = bent_normal(SCENE, &doc, a);
            let (tangent, normal) = (
                Vec3::new(a.cos(), 0.0, -a.sin()),
                Vec3::new(a.sin(), 0.0, a.cos()),
            );
            let want = (tangent + normal).normalize();
            // Corners' tangents interpolated linearly on a face 45° wide.
            assert!(
                (got - want).length() < 0.03,
                "{tangents:?} at {a}: {got} vs {want}"
            );
        }
    }
}

#[test]
fn the_files_tangents_keep_their_handedness() {
    // Green tilts the normal towards the bitangent: up along the cylinder
    // for w = 1, down where the file says the coordinates are mirrored.
    let up_a_little = [128, 200, 200];
    for (w, up) in [(1.0, true), (-1.0, false)] {
        let got = bent_normal(SCENE, &cylinder(up_a_little, Some(w)), 0.3);
        assert!((got.y > 0.3) == up && got.y.abs() > 0.3, "w {w}: {got}");
    }
    // A mirroring transform of the statement keeps the map's look.
    let mirrored = SCENE.replace("\"c.glb\" }", "\"c.glb\" scale <-1, 1, 1> }");
    let got = bent_normal(&mirrored, &cylinder(up_a_little, Some(1.0)), 0.3);
    assert!(got.y > 0.3, "mirrored: {got}");
}

/// A flat square (normal +z) of two triangles split along its diagonal,
/// its texture coordinates not a parallelogram, so that ∂p/∂u turns by 34°
/// from one triangle to the other; its material a normal map of one texel.
fn skewed_square(texel: [u8; 3]) -> Doc {
    let mut d = Doc::default();
    normal_mapped(&mut d, texel);
    let p = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0, 0.0];
    // glTF's v runs down: ptsc's are (0, 0), (1, 0.4), (1, 1), (0, 1).
    let uv = [0.0, 1.0, 1.0, 0.6, 1.0, 0.0, 0.0, 0.0];
    let attributes = json!({
        "POSITION": d.floats(&p, "VEC3", 3),
        "NORMAL": d.floats(&[0.0, 0.0, 1.0].repeat(4), "VEC3", 3),
        "TEXCOORD_0": d.floats(&uv, "VEC2", 2),
    });
    let indices = d.indices(&[0, 1, 2, 0, 2, 3]);
    d.meshes.push(
        json!({"primitives": [{"attributes": attributes, "indices": indices, "material": 0}]}),
    );
    let node = d.node(json!({"mesh": 0}));
    d.roots.push(node);
    d
}

#[test]
fn generated_tangents_do_not_jump_where_the_triangles_meet() {
    let doc = skewed_square([200, 128, 200]);
    let dir = crate::temp_dir_with(&[]);
    std::fs::write(dir.path().join("c.glb"), doc.glb()).unwrap();
    let path = dir.path().join("s.pts");
    std::fs::write(&path, SCENE).unwrap();
    let c = compile_file(&path, Options::default()).unwrap();
    let ir = c.ir.as_ref().expect("compiles");
    let at = |x: f32, y: f32| {
        let ray = Ray::new(Vec3::new(x, y, 2.0), -Vec3::Z, 0.0);
        let mut hit = ir.intersect(&ray, 0.0, f32::INFINITY).expect("a hit");
        ir.material_at(&mut hit, Vec3::Z, 0.0, &mut None);
        hit.n_shading
    };
    // Either side of the diagonal, a hundredth apart: one frame (a
    // triangle's own ∂p/∂u would turn the tilted normal by 0.4).
    let (below, above) = (at(0.505, 0.495), at(0.495, 0.505));
    assert!((below - above).length() < 0.03, "{below} vs {above}");
    // Tilted 45° off the normal, towards +x on the whole.
    assert!((below.z - 0.707).abs() < 0.05 && below.x > 0.5, "{below}");
}

/// A square facing +z whose vertices are coloured `rgb` (as floats, or as
/// normalised bytes with an alpha), its material white.
fn coloured_square(rgb: [f32; 3], bytes: bool) -> Doc {
    let mut d = Doc::default();
    d.materials.push(json!({"pbrMetallicRoughness": {
        "baseColorFactor": [1, 1, 1, 1], "metallicFactor": 0.0, "roughnessFactor": 0.5}}));
    let p = [-0.5, 0.0, 0.0, 0.5, 0.0, 0.0, 0.5, 1.0, 0.0, -0.5, 1.0, 0.0];
    let position = d.floats(&p, "VEC3", 3);
    let color = match bytes {
        false => json!(d.floats(&rgb.repeat(4), "VEC3", 3)),
        true => {
            let rgba: Vec<u8> = [rgb.map(|c| (c * 255.0).round() as u8).to_vec(), vec![255]]
                .concat()
                .repeat(4);
            let view = d.view(&rgba);
            d.accessors
                .push(json!({"bufferView": view, "componentType": 5121,
                "normalized": true, "count": 4, "type": "VEC4"}));
            json!(d.accessors.len() - 1)
        }
    };
    let indices = d.indices(&[0, 1, 2, 0, 2, 3]);
    d.meshes.push(
        json!({"primitives": [{"attributes": {"POSITION": position, "COLOR_0": color},
        "indices": indices, "material": 0}]}),
    );
    let node = d.node(json!({"mesh": 0}));
    d.roots.push(node);
    d
}

#[test]
fn vertex_colours_multiply_the_base_colour() {
    let stage = "camera { position <0, 0.5, 2> look_at <0, 0.5, 0> fov 50 }
render { resolution <32, 24> samples 8 }
sky { sun_elevation 50 }
";
    let written = format!(
        "{stage}quad {{ corner <-0.5, 0, 0> edge1 <1, 0, 0> edge2 <0, 1, 0>
            material {{ type principled base_color rgb <0.8, 0.2, 0.2> roughness 0.5 }} }}"
    );
    let dir = crate::temp_dir_with(&[("written.pts", &written)]);
    let render = |name: &str| render_scene(&dir.path().join(name));
    let reference = render("written.pts");
    for bytes in [false, true] {
        std::fs::write(
            dir.path().join("c.glb"),
            coloured_square([0.8, 0.2, 0.2], bytes).glb(),
        )
        .unwrap();
        std::fs::write(
            dir.path().join("s.pts"),
            format!("{stage}mesh {{ file \"c.glb\" }}"),
        )
        .unwrap();
        let pixels = render("s.pts");
        let differing = (pixels.iter().zip(&reference))
            .filter(|(p, q)| (0..3).any(|k| (p[k] - q[k]).abs() > 1e-3))
            .count();
        assert!(differing <= 6, "bytes {bytes}: {differing} pixels differ");
        let red = pixels.iter().filter(|p| p[0] > 2.0 * p[1]).count();
        assert!(red > 100, "the square is red in {red} pixels");
    }
}

/// An OBJ's `v x y z r g b` and a PLY's `red green blue` are read as the
/// sRGB a viewer shows (decoded: 0.5 is 0.214 linear, `uchar` 128 is
/// 0.216) where the material asks for vertex colours, and left out where
/// it does not.
#[test]
fn obj_and_ply_vertex_colours_multiply_the_diffuse_colour() {
    let stage = "camera { position <0, 0.5, 2> look_at <0, 0.5, 0> fov 50 }
render { resolution <32, 24> samples 8 integrator albedo }
background rgb 1
";
    let quad = |rgb: f32| {
        format!("{stage}quad {{ corner <-0.5, 0, 0> edge1 <1, 0, 0> edge2 <0, 1, 0> material {{ diffuse rgb {rgb} }} }}")
    };
    let obj = "v -0.5 0 0 0.5 0.5 0.5\nv 0.5 0 0 0.5 0.5 0.5\nv 0.5 1 0 0.5 0.5 0.5\nv -0.5 1 0 0.5 0.5 0.5\nf 1 2 3 4\n";
    let ply = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n-0.5 0 0 128 128 128\n0.5 0 0 128 128 128\n0.5 1 0 128 128 128\n-0.5 1 0 128 128 128\n4 0 1 2 3\n";
    let dir = crate::temp_dir_with(&[
        ("c.obj", obj),
        ("c.ply", ply),
        ("dark_obj.pts", &quad(0.214_041_14)),
        ("dark_ply.pts", &quad(0.215_860_53)),
        ("white.pts", &quad(1.0)),
    ]);
    let render = |name: &str| render_scene(&dir.path().join(name));
    for (file, reference) in [("c.obj", "dark_obj.pts"), ("c.ply", "dark_ply.pts")] {
        for (flag, reference) in [("true", reference), ("false", "white.pts")] {
            let scene = format!(
                "{stage}mesh {{ file \"{file}\" material {{ diffuse rgb 1 vertex_color {flag} }} }}"
            );
            std::fs::write(dir.path().join("s.pts"), scene).unwrap();
            let (pixels, reference) = (render("s.pts"), render(reference));
            let differing = (pixels.iter().zip(&reference))
                .filter(|(p, q)| (0..3).any(|k| (p[k] - q[k]).abs() > 1e-3))
                .count();
            assert!(
                differing <= 6,
                "{file}, vertex_color {flag}: {differing} pixels differ"
            );
        }
    }
}

/// The pixels of the scene at `path`, compiled as `ptsc render` would.
fn render_scene(path: &std::path::Path) -> Vec<[f32; 3]> {
    let c = compile_file(path, Options::default()).unwrap();
    let ir =
        c.ir.as_ref()
            .unwrap_or_else(|| panic!("{}", c.diagnostics.render_human(&c.sources, false)));
    crate::render_pixels(ir)
}
