//! The glTF reader's unit tests: materials field by field, transforms,
//! and hostile files refused with a sentence.

use super::*;
use crate::check::scene::{MaterialKind, TextureInput, TextureKind};
use crate::lower::gltf_buffers::{data_uri, relative_path};
use crate::lower::gltf_material::{material, uv_transform};
use crate::texture::image::{Channel, Wrap};
use glam::{DMat4, DQuat, DVec3};
use std::path::{Path, PathBuf};

/// The document of a JSON text.
fn doc(text: &str) -> gltf::Document {
    gltf::Gltf::from_slice(text.as_bytes())
        .expect("valid glTF")
        .document
}

/// The first material of a document whose `materials` array is `materials`
/// (with two textures over two images), and the notes.
fn first_material(materials: &str) -> (crate::check::Material, Vec<String>) {
    let text = format!(
        r#"{{"asset": {{"version": "2.0"}},
            "images": [{{"uri": "a.png"}}, {{"uri": "b.png"}}],
            "samplers": [{{"wrapS": 33071, "wrapT": 33071}}, {{"wrapS": 33648}}],
            "textures": [{{"source": 0, "sampler": 0}}, {{"source": 1, "sampler": 1}}],
            "materials": {materials}}}"#
    );
    let d = doc(&text);
    let images = vec![
        Some(PathBuf::from("m/a.png")),
        Some(PathBuf::from("m/b.png")),
    ];
    let mut notes = Vec::new();
    let m = material(&d.materials().next().unwrap(), &images, &mut notes);
    (m, notes)
}

fn principled(m: &crate::check::Material) -> crate::check::scene::PrincipledParams {
    match m.kind {
        MaterialKind::Principled(p) => p,
        _ => panic!("not principled: {:?}", m.kind),
    }
}

#[test]
fn factors_map_field_by_field() {
    let (m, notes) = first_material(
        r#"[{"name": "Car paint",
             "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.2, 0.1, 1], "metallicFactor": 0.25, "roughnessFactor": 0.4},
             "emissiveFactor": [1, 0.5, 0],
             "extensions": {
                "KHR_materials_emissive_strength": {"emissiveStrength": 4},
                "KHR_materials_ior": {"ior": 1.33},
                "KHR_materials_clearcoat": {"clearcoatFactor": 0.7, "clearcoatRoughnessFactor": 0.2},
                "KHR_materials_sheen": {"sheenColorFactor": [0.5, 0.5, 0.5], "sheenRoughnessFactor": 0.3}}}]"#,
    );
    assert!(notes.is_empty(), "{notes:?}");
    assert_eq!(m.name.as_deref(), Some("Car paint"));
    assert_eq!(m.diffuse, [0.8f32 as f64, 0.2f32 as f64, 0.1f32 as f64]);
    assert!((m.gloss - 0.4).abs() < 1e-6);
    assert!((m.ior - 1.33).abs() < 1e-6);
    assert_eq!(m.emission, [4.0, 2.0, 0.0]);
    assert_eq!(m.transmission, 0.0);
    let p = principled(&m);
    assert!((p.metallic - 0.25).abs() < 1e-6);
    assert_eq!(p.specular, None, "the index decides the reflection");
    assert!((p.clearcoat - 0.7).abs() < 1e-6);
    assert!((p.clearcoat_roughness - 0.2).abs() < 1e-6);
    assert!((p.sheen - 0.5).abs() < 1e-6);
    assert_eq!(p.sheen_tint, 0.0, "a grey sheen is untinted");
    assert!(m.textures.is_empty());
}

#[test]
fn defaults_are_the_specifications() {
    let (m, notes) = first_material(r#"[{}]"#);
    assert!(notes.is_empty(), "{notes:?}");
    assert_eq!(m.diffuse, [1.0; 3]);
    assert_eq!(m.gloss, 1.0);
    assert_eq!(principled(&m).metallic, 1.0);
    assert_eq!(m.ior, 1.5);
    assert_eq!(m.emission, [0.0; 3]);
}

#[test]
fn transmission_and_specular() {
    let (m, _) = first_material(
        r#"[{"extensions": {"KHR_materials_transmission": {"transmissionFactor": 0.9},
                             "KHR_materials_specular": {"specularFactor": 0.5}}}]"#,
    );
    assert!((m.transmission - 0.9).abs() < 1e-6);
    assert_eq!(
        principled(&m).specular,
        None,
        "a refracting surface keeps its index"
    );
    let (m, notes) = first_material(
        r#"[{"extensions": {"KHR_materials_specular": {"specularFactor": 0.5, "specularColorFactor": [1, 0.5, 0.5]}}}]"#,
    );
    // F0 = 0.5 × 0.04 at index 1.5, and principled's F0 is 0.08·specular.
    assert!((principled(&m).specular.unwrap() - 0.25).abs() < 1e-6);
    assert!(
        notes.iter().any(|n| n.contains("specular colour")),
        "{notes:?}"
    );
}

#[test]
fn textures_carry_factors_channels_and_wraps() {
    let (m, notes) = first_material(
        r#"[{"pbrMetallicRoughness": {
                "baseColorFactor": [0.5, 0.5, 1, 1], "baseColorTexture": {"index": 0},
                "metallicFactor": 0.8, "roughnessFactor": 0.6, "metallicRoughnessTexture": {"index": 1}},
             "normalTexture": {"index": 1, "scale": 2},
             "emissiveFactor": [1, 1, 1], "emissiveTexture": {"index": 0},
             "occlusionTexture": {"index": 1}}]"#,
    );
    let find = |input: TextureInput| {
        let (_, t) = m
            .textures
            .iter()
            .find(|(i, _)| *i == input)
            .expect("a texture");
        match &t.kind {
            TextureKind::Image {
                path,
                wrap,
                factor,
                channel,
                ..
            } => (path.clone(), *wrap, *factor, *channel),
            _ => panic!("not an image"),
        }
    };
    let base = find(TextureInput::BaseColor);
    assert_eq!(
        base,
        (PathBuf::from("m/a.png"), Wrap::Clamp, [0.5, 0.5, 1.0], None)
    );
    let rough = find(TextureInput::Gloss);
    assert_eq!(rough.0, PathBuf::from("m/b.png"));
    assert_eq!(rough.1, Wrap::Mirror);
    assert!((rough.2[0] - 0.6).abs() < 1e-6 && rough.3 == Some(Channel::Green));
    let metal = find(TextureInput::Metallic);
    assert!((metal.2[0] - 0.8).abs() < 1e-6 && metal.3 == Some(Channel::Blue));
    assert_eq!(find(TextureInput::NormalMap).0, PathBuf::from("m/b.png"));
    assert_eq!(find(TextureInput::Emission).2, [1.0; 3]);
    assert_eq!(m.textures.len(), 5, "occlusion is not read");
    assert_eq!(m.normal_scale, 2.0, "the normal map's scale");
    assert!(notes.is_empty(), "{notes:?}");
}

#[test]
fn alpha_modes_are_cutouts_and_unknown_extensions_are_noted() {
    let mask = r#"[{"name": "Leaf", "alphaMode": "MASK", "alphaCutoff": 0.3,
        "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 0.8]}}]"#;
    let (m, notes) = first_material(mask);
    assert!(notes.is_empty(), "{notes:?}");
    assert!((m.opacity - 0.8).abs() < 1e-6 && m.opacity_cutoff == Some(0.30000001192092896));
    let blend =
        r#"[{"alphaMode": "BLEND", "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 0.25]}}]"#;
    let (m, _) = first_material(blend);
    assert_eq!((m.opacity, m.opacity_cutoff), (0.25, None));
    // MASK's cutoff defaults to 0.5; OPAQUE ignores alpha, with a note.
    let (m, _) = first_material(r#"[{"alphaMode": "MASK"}]"#);
    assert_eq!((m.opacity, m.opacity_cutoff), (1.0, Some(0.5)));
    // A base colour texture's alpha channel, times the factor's alpha.
    let textured = r#"[{"alphaMode": "MASK", "pbrMetallicRoughness": {
        "baseColorFactor": [1, 1, 1, 0.5], "baseColorTexture": {"index": 0}}}]"#;
    let (m, _) = first_material(textured);
    let image = |input: TextureInput| match m.textures.iter().find(|(i, _)| *i == input) {
        Some((_, t)) => match &t.kind {
            TextureKind::Image {
                path,
                factor,
                channel,
                ..
            } => (path.clone(), *factor, *channel),
            k => panic!("{k:?}"),
        },
        None => panic!("no {input:?} texture"),
    };
    let (path, factor, channel) = image(TextureInput::Opacity);
    assert_eq!((factor, channel), ([0.5; 3], Some(Channel::Alpha)));
    assert_eq!(path, image(TextureInput::BaseColor).0);
    let opaque =
        r#"[{"name": "Glass", "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 0.5]}}]"#;
    let (m, notes) = first_material(opaque);
    assert!(!m.is_cut_out());
    assert!(
        notes
            .iter()
            .any(|n| n.contains("OPAQUE") && n.contains("Glass")),
        "{notes:?}"
    );
    // An emitting surface stays whole.
    let lit = r#"[{"name": "Lamp", "alphaMode": "BLEND", "emissiveFactor": [1, 1, 1],
        "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 0.5]}}]"#;
    let (m, notes) = first_material(lit);
    assert!(!m.is_cut_out());
    assert!(
        notes
            .iter()
            .any(|n| n.contains("Lamp") && n.contains("whole")),
        "{notes:?}"
    );
    let (_, notes) = first_material(r#"[{"extensions": {"KHR_materials_volume": {}}}]"#);
    assert!(
        notes.iter().any(|n| n.contains("KHR_materials_volume")),
        "{notes:?}"
    );
}

#[test]
fn texture_transform_maps_as_the_extension_says() {
    // glTF reads its image at T·R·S·uv (v down); ptsc's (u, v) has v up.
    let (offset, rotation, scale) = ([0.25, 0.5], 0.3f64, [2.0, 3.0]);
    let to_image = uv_transform((offset, rotation, scale)).unwrap().inverse();
    for (u, v) in [(0.0, 0.0), (0.3, 0.8), (1.0, 0.25)] {
        let gltf_uv = (u, 1.0 - v);
        let (su, sv) = (scale[0] * gltf_uv.0, scale[1] * gltf_uv.1);
        let (s, c) = rotation.sin_cos();
        let (ru, rv) = (c * su - s * sv, s * su + c * sv);
        let expect = (ru + offset[0], 1.0 - (rv + offset[1]));
        let got = to_image.transform_point3(DVec3::new(u, v, 0.0));
        assert!(
            (got.x - expect.0).abs() < 1e-12 && (got.y - expect.1).abs() < 1e-12,
            "{got} {expect:?}"
        );
    }
    assert!(
        uv_transform(([0.0; 2], 0.0, [0.0, 1.0])).is_none(),
        "a zero scale"
    );
}

#[test]
fn node_transforms_compose_parent_first() {
    let q = DQuat::from_rotation_z(0.7);
    let t = gltf::scene::Transform::Decomposed {
        translation: [1.0, 2.0, 3.0],
        rotation: q.as_quat().to_array(),
        scale: [2.0, 2.0, 0.5],
    };
    let m = local_transform(&t, "n").unwrap();
    let expect = DMat4::from_translation(DVec3::new(1.0, 2.0, 3.0))
        * DMat4::from_quat(q)
        * DMat4::from_scale(DVec3::new(2.0, 2.0, 0.5));
    assert!(m.abs_diff_eq(expect, 1e-6), "{m} {expect}");
    let bad = gltf::scene::Transform::Decomposed {
        translation: [0.0; 3],
        rotation: [0.0; 4],
        scale: [1.0; 3],
    };
    assert!(local_transform(&bad, "n").unwrap_err().contains("length 0"));
}

/// A scene of one triangle: `nodes` and `scenes` as given, the rest fixed;
/// `accessor` replaces the positions' accessor.
fn triangle_file(nodes: &str, accessor: &str) -> String {
    let floats: [f32; 9] = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0];
    let bytes: Vec<u8> = floats.iter().flat_map(|f| f.to_le_bytes()).collect();
    let data = base64::Engine::encode(&base64::engine::general_purpose::STANDARD, &bytes);
    format!(
        r#"{{"asset": {{"version": "2.0"}}, "scene": 0, {nodes},
            "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}}}]}}],
            "accessors": [{accessor}],
            "bufferViews": [{{"buffer": 0, "byteLength": 36}}],
            "buffers": [{{"byteLength": 36, "uri": "data:application/octet-stream;base64,{data}"}}]}}"#
    )
}

const GOOD_ACCESSOR: &str =
    r#"{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}"#;

/// The file read, and what a statement without `node` places of it.
fn parse(text: &str) -> Result<MeshData, String> {
    let m = crate::lower::mesh::parse(Path::new("t.gltf"), text.as_bytes())?;
    m.scene.as_ref().expect("a scene").placements(None)?;
    Ok(m)
}

#[test]
fn a_tree_of_nodes_places_its_meshes() {
    let nodes = r#""scenes": [{"nodes": [0]}],
        "nodes": [{"children": [1, 2], "translation": [0, 1, 0]},
                  {"mesh": 0, "translation": [1, 0, 0]},
                  {"mesh": 0, "name": "Second", "scale": [2, 2, 2]}]"#;
    let m = parse(&triangle_file(nodes, GOOD_ACCESSOR)).unwrap();
    let scene = m.scene.unwrap();
    assert_eq!(scene.parts.len(), 1, "the mesh is read once");
    let (placed, _) = scene.placements(None).unwrap();
    assert_eq!(placed.len(), 2);
    assert_eq!(placed[0].node, "#1");
    assert_eq!(placed[1].node, "Second");
    let p = placed[0].transform.transform_point3(DVec3::ZERO);
    assert_eq!(p, DVec3::new(1.0, 1.0, 0.0));
    let p = placed[1].transform.transform_point3(DVec3::X);
    assert_eq!(p, DVec3::new(2.0, 1.0, 0.0));
}

#[test]
fn hostile_files_are_refused_with_a_sentence() {
    let one = r#""scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}]"#;
    let cases = [
        // A cycle: 0 → 1 → 0.
        (
            triangle_file(
                r#""scenes": [{"nodes": [0]}], "nodes": [{"children": [1]}, {"children": [0], "mesh": 0}]"#,
                GOOD_ACCESSOR,
            ),
            "the node hierarchy has a cycle: nodes[",
        ),
        // A cycle no scene reaches (every node a child: no root), named
        // rather than "places no triangles".
        (
            triangle_file(
                r#""scenes": [{"nodes": [2]}], "nodes": [{"name": "A", "children": [1]}, {"name": "B", "children": [0], "mesh": 0}, {}]"#,
                GOOD_ACCESSOR,
            ),
            "cycle: `A` (nodes[0]) → `B` (nodes[1]) → `A` (nodes[0])",
        ),
        // A node under two parents.
        (
            triangle_file(
                r#""scenes": [{"nodes": [0, 1]}], "nodes": [{"children": [2]}, {"children": [2]}, {"mesh": 0}]"#,
                GOOD_ACCESSOR,
            ),
            "nodes[2] is a child of both nodes[0] and nodes[1]",
        ),
        // A scene that lists a node and its parent.
        (
            triangle_file(
                r#""scenes": [{"nodes": [0, 1]}], "nodes": [{"children": [1]}, {"mesh": 0}]"#,
                GOOD_ACCESSOR,
            ),
            "is placed twice: the scene lists it twice, or lists it and a node above it",
        ),
        (
            triangle_file(
                one,
                r#"{"bufferView": 0, "componentType": 5126, "count": 4000000000, "type": "VEC3"}"#,
            ),
            // Refused from the claim, before a byte is read or allocated.
            "more than 100,000,000 vertices",
        ),
        (
            // One past the most vertices a file may have.
            triangle_file(
                one,
                r#"{"bufferView": 0, "componentType": 5126, "count": 100000001, "type": "VEC3"}"#,
            ),
            "more than 100,000,000 vertices",
        ),
        (
            // At the most: refused by its buffer view, which holds three.
            triangle_file(
                one,
                r#"{"bufferView": 0, "componentType": 5126, "count": 100000000, "type": "VEC3"}"#,
            ),
            "more than its buffer view holds",
        ),
        (
            triangle_file(
                one,
                r#"{"bufferView": 0, "byteOffset": 30, "componentType": 5126, "count": 3, "type": "VEC3"}"#,
            ),
            "more than its buffer view holds",
        ),
        (
            triangle_file(
                one,
                r#"{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC2"}"#,
            ),
            "not 3",
        ),
        (
            triangle_file(
                one,
                r#"{"componentType": 5126, "count": 3, "type": "VEC3"}"#,
            ),
            "bufferView: Missing",
        ),
        (
            triangle_file(
                r#""scenes": [{"nodes": [0]}], "nodes": [{}]"#,
                GOOD_ACCESSOR,
            ),
            "place no triangles",
        ),
        (
            triangle_file(one, GOOD_ACCESSOR)
                .replace(r#""byteLength": 36, "uri""#, r#""byteLength": 360, "uri""#),
            "declares 360",
        ),
        (
            triangle_file(one, GOOD_ACCESSOR).replace(
                "data:application/octet-stream;base64,",
                "https://example.com/x.bin?",
            ),
            "not a relative path",
        ),
        (
            "{\"asset\": {\"version\": \"2.0\"}, \"nodes\": [{\"mesh\": 7}]}".to_string(),
            "not valid",
        ),
        (
            "glTF\u{2}\0\0\0\u{ff}\u{ff}\u{ff}\u{7f}".to_string(),
            "cannot read the glTF file",
        ),
    ];
    for (text, says) in cases {
        let e = parse(&text).unwrap_err();
        assert!(e.contains(says), "{e} (expected `{says}`)");
    }
    let m = parse(&triangle_file(one, GOOD_ACCESSOR)).unwrap();
    assert_eq!(m.triangles, [[0, 1, 2]]);
}

#[test]
fn data_uris_are_bounded_before_decoding() {
    let e = data_uri("data:application/octet-stream;base64,AAAAAAAA", 5).unwrap_err();
    assert!(e.contains("more than"), "{e}");
    assert_eq!(
        data_uri("data:x;base64,AAAA", 5).unwrap(),
        Some(vec![0, 0, 0])
    );
    assert!(data_uri("data:x,plain", 5).is_err());
    assert_eq!(data_uri("file.bin", 5).unwrap(), None);
    assert_eq!(
        relative_path("a%20b/c.bin").unwrap(),
        PathBuf::from("a b/c.bin")
    );
}

#[test]
fn a_material_reads_one_set_of_texture_coordinates() {
    // Base colour and emission on set 1: both kept; a normal map on set 0
    // is left out with a note.
    let (m, notes) = first_material(
        r#"[{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "texCoord": 1}},
             "emissiveFactor": [1, 1, 1], "emissiveTexture": {"index": 1, "texCoord": 1},
             "normalTexture": {"index": 1}}]"#,
    );
    let inputs: Vec<TextureInput> = m.textures.iter().map(|(i, _)| *i).collect();
    assert_eq!(inputs, [TextureInput::BaseColor, TextureInput::Emission]);
    assert!(
        notes
            .iter()
            .any(|n| n.contains("reads texture coordinates 0") && n.contains("set 1")),
        "{notes:?}"
    );
    let d = doc(
        r#"{"asset": {"version": "2.0"}, "images": [{"uri": "a.png"}], "textures": [{"source": 0}],
            "materials": [{"normalTexture": {"index": 0, "texCoord": 1}}, {}]}"#,
    );
    let sets: Vec<u32> = d
        .materials()
        .map(|m| crate::lower::gltf_material::uv_set(&m))
        .collect();
    assert_eq!(sets, [1, 0]);
}

#[test]
fn a_primitive_reads_the_coordinates_its_material_reads() {
    let floats: [f32; 21] = [
        0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, // positions
        0.5, 0.5, 0.5, 0.5, 0.5, 0.5, // TEXCOORD_0
        0.0, 0.0, 1.0, 0.0, 0.0, 1.0, // TEXCOORD_1
    ];
    let bytes: Vec<u8> = floats.iter().flat_map(|f| f.to_le_bytes()).collect();
    let data = base64::Engine::encode(&base64::engine::general_purpose::STANDARD, &bytes);
    let file = |set: u32| {
        format!(
            r#"{{"asset": {{"version": "2.0"}}, "scene": 0, "scenes": [{{"nodes": [0]}}], "nodes": [{{"mesh": 0}}],
                "images": [{{"uri": "a.png"}}], "textures": [{{"source": 0}}],
                "materials": [{{"pbrMetallicRoughness": {{"baseColorTexture": {{"index": 0, "texCoord": {set}}}}}}}],
                "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0, "TEXCOORD_0": 1, "TEXCOORD_1": 2}}, "material": 0}}]}}],
                "accessors": [{{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}},
                              {{"bufferView": 0, "byteOffset": 36, "componentType": 5126, "count": 3, "type": "VEC2"}},
                              {{"bufferView": 0, "byteOffset": 60, "componentType": 5126, "count": 3, "type": "VEC2"}}],
                "bufferViews": [{{"buffer": 0, "byteLength": 84}}],
                "buffers": [{{"byteLength": 84, "uri": "data:application/octet-stream;base64,{data}"}}]}}"#
        )
    };
    let uvs = |set| parse(&file(set)).unwrap().uvs;
    // v is flipped (glTF's origin is the image's top left).
    assert_eq!(uvs(0), vec![glam::Vec2::new(0.5, 0.5); 3]);
    assert_eq!(
        uvs(1),
        vec![
            glam::Vec2::new(0.0, 1.0),
            glam::Vec2::new(1.0, 1.0),
            glam::Vec2::new(0.0, 0.0)
        ]
    );
}
