//! glTF 2.0 scenes (`lower::gltf`): the same scene written as glTF and in
//! `.pts` renders the same image; a node hierarchy's transforms; a mesh
//! placed by several nodes shared; GLB with embedded images; what is not
//! followed warned about; hostile files refused.

use base64::Engine;
use ptsc::compile::{compile_file, Options};
use serde_json::{json, Value};

/// A glTF document under construction: one buffer, accessors of f32 and
/// u32, meshes of one primitive.
#[derive(Default)]
pub struct Doc {
    pub bin: Vec<u8>,
    pub views: Vec<Value>,
    pub accessors: Vec<Value>,
    pub meshes: Vec<Value>,
    pub nodes: Vec<Value>,
    pub materials: Vec<Value>,
    pub images: Vec<Value>,
    pub textures: Vec<Value>,
    pub roots: Vec<usize>,
}

impl Doc {
    /// A buffer view of `bytes` (4-byte aligned).
    pub fn view(&mut self, bytes: &[u8]) -> usize {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        let view = json!({"buffer": 0, "byteOffset": self.bin.len(), "byteLength": bytes.len()});
        self.bin.extend_from_slice(bytes);
        self.views.push(view);
        self.views.len() - 1
    }

    /// An accessor of f32 `values`, `kind` ("VEC3", …) of `n` numbers.
    pub fn floats(&mut self, values: &[f32], kind: &str, n: usize) -> usize {
        let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
        let view = self.view(&bytes);
        self.accessors
            .push(json!({"bufferView": view, "componentType": 5126,
            "count": values.len() / n, "type": kind}));
        self.accessors.len() - 1
    }

    /// An accessor of u32 indices.
    pub fn indices(&mut self, values: &[u32]) -> usize {
        let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
        let view = self.view(&bytes);
        self.accessors
            .push(json!({"bufferView": view, "componentType": 5125,
            "count": values.len(), "type": "SCALAR"}));
        self.accessors.len() - 1
    }

    /// A mesh of one triangle primitive.
    pub fn mesh(
        &mut self,
        positions: &[f32],
        uvs: Option<&[f32]>,
        indices: &[u32],
        material: Option<usize>,
    ) -> usize {
        let mut attributes = json!({"POSITION": self.floats(positions, "VEC3", 3)});
        if let Some(uvs) = uvs {
            attributes["TEXCOORD_0"] = json!(self.floats(uvs, "VEC2", 2));
        }
        let mut primitive = json!({"attributes": attributes, "indices": self.indices(indices)});
        if let Some(m) = material {
            primitive["material"] = json!(m);
        }
        self.meshes.push(json!({"primitives": [primitive]}));
        self.meshes.len() - 1
    }

    /// A node (`node` holds its properties).
    pub fn node(&mut self, node: Value) -> usize {
        self.nodes.push(node);
        self.nodes.len() - 1
    }

    /// The JSON, its buffer `buffer`.
    fn json(&self, buffer: Value) -> Value {
        let mut doc = json!({
            "asset": {"version": "2.0"},
            "scene": 0,
            "scenes": [{"nodes": self.roots}],
            "nodes": self.nodes,
            "meshes": self.meshes,
            "accessors": self.accessors,
            "bufferViews": self.views,
            "buffers": [buffer],
        });
        for (key, list) in [
            ("materials", &self.materials),
            ("images", &self.images),
            ("textures", &self.textures),
        ] {
            if !list.is_empty() {
                doc[key] = json!(list);
            }
        }
        if !self.textures.is_empty() {
            doc["samplers"] = json!([{}]);
        }
        doc
    }

    /// A `.gltf` with its buffer as a data URI.
    pub fn gltf(&self) -> String {
        let data = base64::engine::general_purpose::STANDARD.encode(&self.bin);
        let buffer = json!({"byteLength": self.bin.len(),
            "uri": format!("data:application/octet-stream;base64,{data}")});
        self.json(buffer).to_string()
    }

    /// A `.glb` with its buffer in the binary chunk.
    pub fn glb(&self) -> Vec<u8> {
        let mut text = self
            .json(json!({"byteLength": self.bin.len()}))
            .to_string()
            .into_bytes();
        while !text.len().is_multiple_of(4) {
            text.push(b' ');
        }
        let mut bin = self.bin.clone();
        while !bin.len().is_multiple_of(4) {
            bin.push(0);
        }
        let mut out = Vec::new();
        out.extend_from_slice(b"glTF");
        out.extend_from_slice(&2u32.to_le_bytes());
        out.extend_from_slice(&((12 + 8 + text.len() + 8 + bin.len()) as u32).to_le_bytes());
        out.extend_from_slice(&(text.len() as u32).to_le_bytes());
        out.extend_from_slice(b"JSON");
        out.extend_from_slice(&text);
        out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
        out.extend_from_slice(b"BIN\0");
        out.extend_from_slice(&bin);
        out
    }
}

/// The unit cube centred on the origin as 12 outward triangles.
pub const CUBE: ([f32; 24], [u32; 36]) = (
    [
        -0.5, -0.5, -0.5, 0.5, -0.5, -0.5, 0.5, 0.5, -0.5, -0.5, 0.5, -0.5, -0.5, -0.5, 0.5, 0.5,
        -0.5, 0.5, 0.5, 0.5, 0.5, -0.5, 0.5, 0.5,
    ],
    [
        0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4, 3, 7, 6, 3, 6, 2, 0, 4, 7, 0, 7, 3,
        1, 2, 6, 1, 6, 5,
    ],
);

const STAGE: &str = "camera { position <0, 1.2, 4> look_at <0, 0.4, 0> fov 45 }
render { resolution <48, 36> samples 16 }
sky { sun_elevation 50 }
plane { normal <0, 1, 0> material { diffuse rgb 0.5 } }
";

fn compile(dir: &std::path::Path, scene: &str) -> ptsc::compile::Compiled {
    let path = dir.join("scene.pts");
    std::fs::write(&path, scene).unwrap();
    compile_file(&path, Options::default()).unwrap()
}

fn ir_of(c: &ptsc::compile::Compiled) -> &ptsc::ir::Scene {
    match c.ir.as_ref() {
        Some(ir) => ir,
        None => panic!("{}", c.diagnostics.render_human(&c.sources, false)),
    }
}

/// The largest difference of two images' channels.
fn worst(a: &[[f32; 3]], b: &[[f32; 3]]) -> f32 {
    (a.iter().zip(b))
        .flat_map(|(p, q)| (0..3).map(move |k| (p[k] - q[k]).abs()))
        .fold(0.0, f32::max)
}

/// Two cubes under a parent node (TRS), one child by TRS and one by a
/// matrix, each of its own material.
fn two_cubes() -> Doc {
    let mut d = Doc::default();
    d.materials
        .push(json!({"name": "Red", "pbrMetallicRoughness": {
        "baseColorFactor": [0.8, 0.1, 0.1, 1], "metallicFactor": 0.0, "roughnessFactor": 0.5}}));
    d.materials
        .push(json!({"name": "Gold", "pbrMetallicRoughness": {
        "baseColorFactor": [0.9, 0.6, 0.2, 1], "metallicFactor": 1.0, "roughnessFactor": 0.3}}));
    let red = d.mesh(&CUBE.0, None, &CUBE.1, Some(0));
    let gold = d.mesh(&CUBE.0, None, &CUBE.1, Some(1));
    let (s, c) = (22.5f64.to_radians().sin(), 22.5f64.to_radians().cos());
    let a = d.node(
        json!({"name": "A", "mesh": red, "translation": [-0.8, 0, 0], "scale": [0.6, 0.6, 0.6]}),
    );
    // 0.5 × (rotation of 45° about x), then a move of (0.8, 0, 0), column-major.
    let (s45, c45) = (
        45f64.to_radians().sin() * 0.5,
        45f64.to_radians().cos() * 0.5,
    );
    let b = d.node(json!({"name": "B", "mesh": gold, "matrix": [
        0.5, 0, 0, 0,  0, c45, s45, 0,  0, -s45, c45, 0,  0.8, 0, 0, 1]}));
    let parent = d.node(
        json!({"name": "Parent", "children": [a, b], "translation": [0, 0.5, 0],
        "rotation": [0, s, 0, c]}),
    );
    d.roots.push(parent);
    d
}

/// The same two cubes written in `.pts`.
const TWO_CUBES_PTS: &str = "
box { min <-0.5, -0.5, -0.5> max <0.5, 0.5, 0.5> scale 0.6 translate <-0.8, 0, 0> rotate <0, 45, 0> translate <0, 0.5, 0>
      material { type principled base_color rgb <0.8, 0.1, 0.1> roughness 0.5 } }
box { min <-0.5, -0.5, -0.5> max <0.5, 0.5, 0.5> scale 0.5 rotate <45, 0, 0> translate <0.8, 0, 0> rotate <0, 45, 0> translate <0, 0.5, 0>
      material { type principled base_color rgb <0.9, 0.6, 0.2> metallic 1 roughness 0.3 } }
";

#[test]
fn a_scene_written_as_gltf_renders_as_written_in_pts() {
    let d = two_cubes();
    let dir = crate::temp_dir_with(&[("cubes.gltf", &d.gltf())]);
    std::fs::write(dir.path().join("cubes.glb"), d.glb()).unwrap();
    let written = compile(dir.path(), &format!("{STAGE}{TWO_CUBES_PTS}"));
    let reference = crate::render_pixels(ir_of(&written));
    for file in ["cubes.gltf", "cubes.glb"] {
        let from_file = compile(dir.path(), &format!("{STAGE}mesh {{ file \"{file}\" }}"));
        let pixels = crate::render_pixels(ir_of(&from_file));
        // The same surfaces as triangles instead of quads: equal up to f32
        // rounding at the cubes' edges.
        let differing = (pixels.iter().zip(&reference))
            .filter(|(p, q)| worst(&[**p], &[**q]) > 1e-3)
            .count();
        assert!(differing <= 6, "{file}: {differing} pixels differ");
    }
    // The cubes are in view: without them, many pixels change.
    let stage = crate::render_pixels(ir_of(&compile(dir.path(), STAGE)));
    let covered = (stage.iter().zip(&reference))
        .filter(|(p, q)| worst(&[**p], &[**q]) > 0.02)
        .count();
    assert!(covered > 150, "the cubes cover {covered} pixels");
    // The test can fail: the parent turned the other way is another image.
    let turned = TWO_CUBES_PTS.replace("rotate <0, 45, 0>", "rotate <0, -45, 0>");
    let turned = compile(dir.path(), &format!("{STAGE}{turned}"));
    let other = crate::render_pixels(ir_of(&turned));
    assert!(worst(&other, &reference) > 0.05);
}

#[test]
fn materials_replaces_a_files_material_by_name() {
    let d = two_cubes();
    let dir = crate::temp_dir_with(&[("cubes.gltf", &d.gltf())]);
    std::fs::write(dir.path().join("cubes.glb"), d.glb()).unwrap();
    let blue = "material { diffuse rgb <0.2, 0.3, 0.9> }";
    let written = TWO_CUBES_PTS.replace(
        "material { type principled base_color rgb <0.9, 0.6, 0.2> metallic 1 roughness 0.3 }",
        blue,
    );
    assert_ne!(written, TWO_CUBES_PTS);
    let reference = crate::render_pixels(ir_of(&compile(dir.path(), &format!("{STAGE}{written}"))));
    for file in ["cubes.gltf", "cubes.glb"] {
        let scene = format!(
            "{STAGE}mesh {{ file \"{file}\" materials {{ \"Gold\" {blue} \"Gould\" {blue} }} }}"
        );
        let c = compile(dir.path(), &scene);
        let pixels = crate::render_pixels(ir_of(&c));
        let differing = (pixels.iter().zip(&reference))
            .filter(|(p, q)| worst(&[**p], &[**q]) > 1e-3)
            .count();
        assert!(differing <= 6, "{file}: {differing} pixels differ");
        let text = c.diagnostics.render_human(&c.sources, false);
        assert!(
            text.contains("has no material `Gould`") && text.contains("did you mean `Gold`?"),
            "{text}"
        );
    }
}

#[test]
fn a_mesh_placed_by_several_nodes_is_stored_once() {
    let mut d = Doc::default();
    let cube = d.mesh(&CUBE.0, None, &CUBE.1, None);
    for x in [-1.0, 0.0, 1.0] {
        let node =
            d.node(json!({"mesh": cube, "translation": [x, 0.5, 0], "scale": [0.5, 0.5, 0.5]}));
        d.roots.push(node);
    }
    let dir = crate::temp_dir_with(&[("three.gltf", &d.gltf())]);
    let from_file = compile(
        dir.path(),
        &format!("{STAGE}mesh {{ file \"three.gltf\" }}"),
    );
    let ir = ir_of(&from_file);
    assert_eq!(ir.instances.prototypes.len(), 1, "one cube stored");
    assert_eq!(ir.instances.placements.len(), 3, "placed three times");
    let written: String = [-1.0, 0.0, 1.0]
        .map(|x| format!("box {{ min <-0.5, -0.5, -0.5> max <0.5, 0.5, 0.5> scale 0.5 translate <{x}, 0.5, 0> }}\n"))
        .concat();
    let reference = crate::render_pixels(ir_of(&compile(dir.path(), &format!("{STAGE}{written}"))));
    let pixels = crate::render_pixels(ir);
    let differing = (pixels.iter().zip(&reference))
        .filter(|(p, q)| worst(&[**p], &[**q]) > 1e-3)
        .count();
    assert!(differing <= 6, "{differing} pixels differ");
}

/// A PNG of one colour, 4 × 4.
pub fn flat_png(rgb: [u8; 3]) -> Vec<u8> {
    let mut out = Vec::new();
    let mut encoder = png::Encoder::new(&mut out, 4, 4);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header().unwrap();
    writer.write_image_data(&rgb.repeat(16)).unwrap();
    writer.finish().unwrap();
    out
}

#[test]
fn images_inside_a_glb_are_read_with_factors_and_channels() {
    // A base colour image times a factor, and a metallic-roughness image
    // whose green (roughness) and blue (metallic) channels differ.
    let mut d = Doc::default();
    let colour = d.view(&flat_png([200, 100, 50]));
    let mr = d.view(&flat_png([0, 128, 255]));
    d.images
        .push(json!({"bufferView": colour, "mimeType": "image/png"}));
    d.images
        .push(json!({"bufferView": mr, "mimeType": "image/png"}));
    d.textures.push(json!({"source": 0, "sampler": 0}));
    d.textures.push(json!({"source": 1, "sampler": 0}));
    d.materials.push(json!({"pbrMetallicRoughness": {
        "baseColorFactor": [0.5, 1, 1, 1], "baseColorTexture": {"index": 0},
        "metallicFactor": 0.8, "roughnessFactor": 1.0, "metallicRoughnessTexture": {"index": 1}}}));
    let uvs = [0.0f32; 16];
    let cube = d.mesh(&CUBE.0, Some(&uvs), &CUBE.1, Some(0));
    let node = d.node(
        json!({"mesh": cube, "translation": [0, 0.5, 0], "rotation": [0, 0.3826834, 0, 0.9238795]}),
    );
    d.roots.push(node);
    let dir = crate::temp_dir_with(&[]);
    std::fs::write(dir.path().join("textured.glb"), d.glb()).unwrap();
    let from_file = compile(
        dir.path(),
        &format!("{STAGE}mesh {{ file \"textured.glb\" }}"),
    );
    let srgb = |c: f64| {
        let c = c / 255.0;
        if c <= 0.04045 {
            c / 12.92
        } else {
            ((c + 0.055) / 1.055).powf(2.4)
        }
    };
    let base = [0.5 * srgb(200.0), srgb(100.0), srgb(50.0)];
    let written = format!(
        "box {{ min <-0.5, -0.5, -0.5> max <0.5, 0.5, 0.5> rotate <0, 45, 0> translate <0, 0.5, 0>
           material {{ type principled base_color rgb <{:.9}, {:.9}, {:.9}> metallic 0.8 roughness {:.9} }} }}",
        base[0], base[1], base[2], 128.0 / 255.0
    );
    let reference = crate::render_pixels(ir_of(&compile(dir.path(), &format!("{STAGE}{written}"))));
    let pixels = crate::render_pixels(ir_of(&from_file));
    let differing = (pixels.iter().zip(&reference))
        .filter(|(p, q)| worst(&[**p], &[**q]) > 2e-3)
        .count();
    assert!(differing <= 6, "{differing} pixels differ");
    // Reading the channels the other way round is another image.
    let swapped = written.replace(
        &format!("metallic 0.8 roughness {:.9}", 128.0 / 255.0),
        &format!("metallic {:.9} roughness 1", 0.8 * 128.0 / 255.0),
    );
    assert_ne!(swapped, written);
    let other = crate::render_pixels(ir_of(&compile(dir.path(), &format!("{STAGE}{swapped}"))));
    assert!(worst(&other, &reference) > 0.02);
}

#[test]
fn what_the_file_asks_beyond_ptsc_is_a_warning_at_the_statement() {
    let mut d = two_cubes();
    d.nodes[0]["skin"] = json!(0);
    d.materials[0]["pbrMetallicRoughness"]["baseColorFactor"][3] = json!(0.5);
    let mut text: Value = serde_json::from_str(&d.gltf()).unwrap();
    text["skins"] = json!([{"joints": [2]}]);
    text["extensionsRequired"] = json!(["KHR_draco_mesh_compression"]);
    text["extensionsUsed"] = json!(["KHR_draco_mesh_compression"]);
    let dir = crate::temp_dir_with(&[("odd.gltf", &text.to_string())]);
    let c = compile(dir.path(), &format!("{STAGE}mesh {{ file \"odd.gltf\" }}"));
    let report = c.diagnostics.render_human(&c.sources, false);
    assert!(c.ir.is_some(), "{report}");
    for says in [
        "skinned",
        "OPAQUE",
        "KHR_draco_mesh_compression",
        "mesh { file \"odd.gltf\" }",
    ] {
        assert!(report.contains(says), "`{says}` missing: {report}");
    }
    // `check` says the same.
    let path = dir.path().join("scene.pts");
    let (_, _, err) = crate::ptsc(&["check", path.to_str().unwrap()]);
    assert!(err.contains("skinned") && err.contains("OPAQUE"), "{err}");
    // A statement that gives its material hears nothing of the file's.
    let given = compile(
        dir.path(),
        &format!("{STAGE}mesh {{ file \"odd.gltf\" material {{ diffuse rgb 0.5 }} }}"),
    );
    let report = given.diagnostics.render_human(&given.sources, false);
    assert!(
        report.contains("skinned") && !report.contains("BLEND"),
        "{report}"
    );
}

#[test]
fn a_broken_file_is_an_error_at_the_statement_in_check_and_render() {
    let d = two_cubes();
    let broken = d
        .gltf()
        .replace("\"byteLength\":", "\"byteLength\": 99999 , \"x\":");
    let dir = crate::temp_dir_with(&[
        ("broken.gltf", &broken),
        ("lost.gltf", &d.gltf().replace("data:", "lost.bin#")),
    ]);
    for file in ["broken.gltf", "lost.gltf", "absent.glb"] {
        let c = compile(dir.path(), &format!("{STAGE}mesh {{ file \"{file}\" }}"));
        let report = c.diagnostics.render_human(&c.sources, false);
        assert!(c.ir.is_none(), "{file}: {report}");
        assert!(
            report.contains(&format!("mesh {{ file \"{file}\" }}")),
            "{report}"
        );
    }
}

#[test]
fn node_places_one_subtree_without_its_own_place() {
    let d = two_cubes();
    let dir = crate::temp_dir_with(&[("cubes.gltf", &d.gltf())]);
    let picked = compile(
        dir.path(),
        &format!("{STAGE}mesh {{ file \"cubes.gltf\" node \"A\" translate <0, 0.5, 0> }}"),
    );
    let written = "box { min <-0.5, -0.5, -0.5> max <0.5, 0.5, 0.5> translate <0, 0.5, 0>
        material { type principled base_color rgb <0.8, 0.1, 0.1> roughness 0.5 } }";
    let reference = crate::render_pixels(ir_of(&compile(dir.path(), &format!("{STAGE}{written}"))));
    let pixels = crate::render_pixels(ir_of(&picked));
    let differing = (pixels.iter().zip(&reference))
        .filter(|(p, q)| worst(&[**p], &[**q]) > 1e-3)
        .count();
    assert!(differing <= 6, "{differing} pixels differ");
    // The parent's subtree is both cubes, in the parent's frame.
    let parent = compile(
        dir.path(),
        &format!("{STAGE}mesh {{ file \"cubes.gltf\" node \"Parent\" }}"),
    );
    assert_eq!(
        ir_of(&parent).object_material.len(),
        3,
        "the plane and two cubes"
    );
    // A node the file does not have: an error at `node`, in check too.
    let scene = format!("{STAGE}mesh {{ file \"cubes.gltf\" node \"Parnet\" }}");
    let c = compile(dir.path(), &scene);
    let report = c.diagnostics.render_human(&c.sources, false);
    assert!(
        c.ir.is_none() && report.contains("no node `Parnet`") && report.contains("Parent"),
        "{report}"
    );
    let (code, _, err) = crate::ptsc(&["check", dir.path().join("scene.pts").to_str().unwrap()]);
    assert!(code != 0 && err.contains("no node `Parnet`"), "{err}");
}

#[test]
fn the_fingerprint_sees_the_files_a_mesh_names() {
    // A render state resumes only the same scene: a glTF's buffer or an
    // OBJ's library changed is another scene.
    let d = two_cubes();
    let text = d.gltf();
    let data = text.find("data:").unwrap();
    let end = data + text[data..].find('"').unwrap();
    let external = format!("{}cubes.bin{}", &text[..data], &text[end..]);
    let dir = crate::temp_dir_with(&[("cubes.gltf", &external), ("m.mtl", "newmtl A\nKd 1 0 0\n")]);
    std::fs::write(dir.path().join("cubes.bin"), &d.bin).unwrap();
    std::fs::write(
        dir.path().join("q.obj"),
        "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl A\nf 1 2 3\n",
    )
    .unwrap();
    let scene = format!("{STAGE}mesh {{ file \"cubes.gltf\" }}\nmesh {{ file \"q.obj\" }}");
    let path = dir.path().join("scene.pts");
    std::fs::write(&path, &scene).unwrap();
    let fingerprint = || {
        let options = Options {
            fingerprint: true,
            ..Options::default()
        };
        let c = compile_file(&path, options).unwrap();
        ir_of(&c);
        c.fingerprint.expect("asked for")
    };
    let before = fingerprint();
    assert_eq!(before, fingerprint(), "stable");
    let mut bin = d.bin.clone();
    bin[0] ^= 1;
    std::fs::write(dir.path().join("cubes.bin"), &bin).unwrap();
    let after_bin = fingerprint();
    assert_ne!(before, after_bin, "the buffer changed");
    std::fs::write(dir.path().join("m.mtl"), "newmtl A\nKd 0 1 0\n").unwrap();
    assert_ne!(after_bin, fingerprint(), "the library changed");
}

#[test]
fn lights_of_the_file_are_placed_as_written_in_pts() {
    // KHR_lights_punctual: a point light under a moved parent, a spot
    // turned down by its node, a directional light; the scene has no sky.
    let mut d = two_cubes();
    let (s, c) = (45f64.to_radians().sin(), 45f64.to_radians().cos());
    let point = d.node(json!({"name": "Lamp", "translation": [0, 1.5, 0],
        "extensions": {"KHR_lights_punctual": {"light": 0}}}));
    let holder = d.node(json!({"translation": [0.5, 0.5, 1], "children": [point]}));
    // −z turned 90° about x points down.
    let spot = d.node(
        json!({"translation": [-0.5, 2.5, 0.5], "rotation": [-s, 0, 0, c],
        "extensions": {"KHR_lights_punctual": {"light": 1}}}),
    );
    let sun = d.node(
        json!({"rotation": [-s, 0, 0, c], "extensions": {"KHR_lights_punctual": {"light": 2}}}),
    );
    d.roots.extend([holder, spot, sun]);
    let mut text: Value = serde_json::from_str(&d.gltf()).unwrap();
    text["extensionsUsed"] = json!(["KHR_lights_punctual"]);
    text["extensions"] = json!({"KHR_lights_punctual": {"lights": [
        {"type": "point", "color": [1, 0.8, 0.6], "intensity": 20},
        {"type": "spot", "intensity": 30, "spot": {"innerConeAngle": 0.3, "outerConeAngle": 0.5}},
        {"type": "directional", "color": [0.5, 0.5, 1], "intensity": 2}]}});
    let dir = crate::temp_dir_with(&[("lit.gltf", &text.to_string())]);
    let stage = STAGE.replace("sky { sun_elevation 50 }\n", "");
    let from_file = compile(dir.path(), &format!("{stage}mesh {{ file \"lit.gltf\" }}"));
    let written = format!(
        "{stage}{TWO_CUBES_PTS}
        point_light {{ position <0.5, 2, 1> intensity rgb <20, 16, 12> }}
        spot_light {{ position <-0.5, 2.5, 0.5> look_at <-0.5, 0, 0.5> intensity rgb 30 angle {} hotspot {} }}
        directional_light {{ direction <0, -1, 0> irradiance rgb <1, 1, 2> }}",
        0.5f64.to_degrees(),
        0.3f64.to_degrees()
    );
    let written_c = compile(dir.path(), &written);
    let reference = crate::render_pixels(ir_of(&written_c));
    let pixels = crate::render_pixels(ir_of(&from_file));
    // Within noise: the light paths part at the cubes' edges (triangles
    // for quads) and differ there as two seeds do; the mean difference is
    // below another seed's.
    let reseeded = written.replace("samples 16", "samples 16 seed 9");
    let other_seed = crate::render_pixels(ir_of(&compile(dir.path(), &reseeded)));
    let mean_difference = |a: &[[f32; 3]], b: &[[f32; 3]]| {
        let sum: f32 = a
            .iter()
            .zip(b)
            .map(|(p, q)| (0..3).map(|k| (p[k] - q[k]).abs()).sum::<f32>())
            .sum();
        sum / (3 * a.len()) as f32
    };
    let (ours, noise) = (
        mean_difference(&pixels, &reference),
        mean_difference(&other_seed, &reference),
    );
    assert!(
        ours < 0.5 * noise,
        "difference {ours}, another seed's {noise}"
    );
    let lit = pixels.iter().filter(|p| p[0] > 0.05).count();
    assert!(lit > 200, "the lights light {lit} pixels");
}
