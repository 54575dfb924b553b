//! Tests of the MTL → principled mapping, key by key.

use super::*;

fn parse(text: &str) -> Vec<tobj::Material> {
    let (materials, _) = tobj::load_mtl_buf(&mut std::io::Cursor::new(text)).expect("parses");
    materials
}

fn mapped(text: &str) -> Mapped {
    let m = parse(text);
    material(&m[0], Path::new("models/a.mtl"), Span::default())
}

fn principled(m: &Material) -> PrincipledParams {
    match m.kind {
        MaterialKind::Principled(p) => p,
        other => panic!("{other:?}"),
    }
}

fn textures(m: &Material) -> Vec<(TextureInput, String, Wrap)> {
    (m.textures.iter())
        .map(|(input, t)| match &t.kind {
            TextureKind::Image { path, wrap, .. } => {
                (*input, path.to_string_lossy().replace('\\', "/"), *wrap)
            }
            other => panic!("{other:?}"),
        })
        .collect()
}

#[test]
fn every_key_maps_to_its_parameter() {
    let m = mapped(
        "newmtl Painted
         Kd 0.8 0.4 0.2
         Ks 0.6 0.3 0.3
         Ns 250
         Ke 0.5 0.25 0
         Pm 0.7
         Ps 0.3
         Pc 0.9
         Pcr 0.2
         aniso 0.4
         illum 2",
    );
    let material = &m.material;
    assert_eq!(material.name.as_deref(), Some("Painted"));
    assert_eq!(
        material.diffuse,
        [0.8f32 as f64, 0.4f32 as f64, 0.2f32 as f64]
    );
    assert!((material.gloss - roughness_of_exponent(250.0)).abs() < 1e-12);
    assert_eq!(material.emission, [0.5, 0.25, 0.0]);
    let p = principled(material);
    assert!((p.specular.unwrap() - 0.4).abs() < 1e-6, "{p:?}");
    assert!((p.metallic - 0.7).abs() < 1e-6);
    assert!((p.sheen - 0.3).abs() < 1e-6);
    assert!((p.clearcoat - 0.9).abs() < 1e-6);
    assert!((p.clearcoat_roughness - 0.2).abs() < 1e-6);
    assert!((p.anisotropic - 0.4).abs() < 1e-6);
    assert_eq!((p.specular_tint, p.sheen_tint), (0.0, 0.0));
    assert!(material.textures.is_empty());
    assert!(m.left_out.is_empty(), "{:?}", m.left_out);
}

#[test]
fn the_index_comes_from_ni_unless_it_is_one() {
    let glass = mapped("newmtl G\nKs 0.5 0.5 0.5\nNi 1.45\n");
    assert!((glass.material.ior - 1.45).abs() < 1e-6);
    assert_eq!(principled(&glass.material).specular, None);
    let none = mapped("newmtl N\nKs 0.2 0.2 0.2\nNi 1.0\n");
    assert_eq!(none.material.ior, 1.5);
    assert!((principled(&none.material).specular.unwrap() - 0.2).abs() < 1e-6);
    // Nothing said: Mitsuba's defaults (grey, roughness 0.5, specular 0.5).
    let bare = mapped("newmtl B\n");
    assert_eq!(bare.material.diffuse, [0.5; 3]);
    assert_eq!(bare.material.gloss, 0.5);
    assert_eq!(principled(&bare.material).specular, None);
}

#[test]
fn roughness_from_the_phong_exponent_or_pr() {
    // Ns 0 is the widest lobe (α 1), Ns 1000 a narrow one (α 0.0447).
    assert_eq!(roughness_of_exponent(0.0), 1.0);
    assert!((roughness_of_exponent(1000.0) - (2.0f64 / 1002.0).sqrt().sqrt()).abs() < 1e-12);
    assert!(roughness_of_exponent(10.0) > roughness_of_exponent(100.0));
    let pr = mapped("newmtl R\nNs 900\nPr 0.35\n");
    assert!((pr.material.gloss - 0.35).abs() < 1e-6);
}

#[test]
fn texture_keys_become_textures_with_their_options() {
    let m = mapped(
        "newmtl T
         map_Kd -s 2 2 1 wood grain.png
         map_Pr rough.png
         map_Pm -clamp on metal.png
         map_Ke glow.png
         map_Bump -bm 0.5 bumps.png
         norm normals.png",
    );
    let material = &m.material;
    assert_eq!(
        textures(material),
        vec![
            (
                TextureInput::BaseColor,
                "models/wood grain.png".into(),
                Wrap::Repeat
            ),
            (TextureInput::Gloss, "models/rough.png".into(), Wrap::Repeat),
            (
                TextureInput::Metallic,
                "models/metal.png".into(),
                Wrap::Clamp
            ),
            (
                TextureInput::Emission,
                "models/glow.png".into(),
                Wrap::Repeat
            ),
            (
                TextureInput::NormalMap,
                "models/normals.png".into(),
                Wrap::Repeat
            ),
            (TextureInput::Bump, "models/bumps.png".into(), Wrap::Repeat),
        ]
    );
    assert!(material
        .textures
        .iter()
        .all(|(_, t)| t.space == TextureSpace::Uv));
    assert!((material.bump_height - 0.005).abs() < 1e-12);
    // Textured values stand for their brightest (an image's: 1).
    assert_eq!(
        (material.diffuse, material.emission, material.gloss),
        ([1.0; 3], [1.0; 3], 1.0)
    );
    assert_eq!(principled(material).metallic, 1.0);
    assert!(m.left_out.is_empty(), "{:?}", m.left_out);
    // `-s 2 2 1` is ptsc's `scale <0.5, 0.5, 1>` (the image repeats twice).
    let scaled = &material.textures[0].1.transform;
    assert!(scaled.abs_diff_eq(DMat4::from_scale(glam::DVec3::new(0.5, 0.5, 1.0)), 1e-12));
}

#[test]
fn opacity_maps_to_cutouts_and_bad_texture_statements_are_named() {
    let opacity = |text: &str| {
        let m = mapped(&format!("newmtl O\n{text}\n"));
        assert!(m.left_out.is_empty(), "{text}: {:?}", m.left_out);
        m.material
    };
    let d = opacity("d 0.5");
    assert_eq!((d.opacity, d.opacity_cutoff), (0.5, None));
    assert!(d.is_cut_out());
    assert!((opacity("Tr 0.3").opacity - 0.7).abs() < 1e-6);
    assert!(!opacity("d 1\nTr 0").is_cut_out());
    // `map_d` reads its image's alpha, times `d`.
    let map = opacity("d 0.8\nmap_d leaf.png");
    let (input, t) = &map.textures[0];
    assert_eq!(*input, TextureInput::Opacity);
    match &t.kind {
        TextureKind::Image {
            path,
            factor,
            channel,
            ..
        } => {
            assert!(path.ends_with("leaf.png"));
            assert!((factor[0] - 0.8).abs() < 1e-6);
            assert_eq!(*channel, Some(crate::texture::image::Channel::Alpha));
        }
        k => panic!("{k:?}"),
    }
    // A light is not cut out: named.
    let lit = mapped("newmtl L\nKe 1 1 1\nd 0.5\n");
    assert!(!lit.material.is_cut_out());
    assert!(
        lit.left_out.iter().any(|l| l.contains("opacity")),
        "{:?}",
        lit.left_out
    );
    let bad = mapped("newmtl B\nmap_Kd -bm\n");
    assert!(bad.material.textures.is_empty());
    assert_eq!(bad.left_out.len(), 1, "{:?}", bad.left_out);
}

#[test]
fn texture_statements_parse_their_options() {
    let r = texture_ref("-bm 0.3 -s 2 2 1 -t 1 dir/my file.png").unwrap();
    assert_eq!(r.file, "dir/my file.png");
    assert_eq!(r.bump_multiplier, Some(0.3));
    assert_eq!(r.scale, Some([2.0, 2.0, 1.0]));
    assert_eq!(r.ignored, vec!["-t".to_string()]);
    let one = texture_ref("-o 0.5 tex.png").unwrap();
    assert_eq!(
        (one.file.as_str(), one.offset),
        ("tex.png", Some([0.5, 0.0, 0.0]))
    );
    // Shifted, then scaled: the pattern reads 3·uv + 0.25.
    let both = image(
        &texture_ref("-o 0.25 0.25 -s 3 3 t.png").unwrap(),
        ("map_Kd", "A", Path::new("a.mtl")),
        Span::default(),
    );
    let uv = glam::DVec3::new(0.1, 0.2, 0.0);
    let read = both.transform.inverse().transform_point3(uv);
    assert!(
        (read - glam::DVec3::new(0.55, 0.85, 0.0)).length() < 1e-12,
        "{read}"
    );
    assert_eq!(texture_ref("-s 0 1 1 t.png"), None);
    assert!(texture_ref("-clamp on t.png").unwrap().clamp);
    assert_eq!(texture_ref("-bm"), None);
    assert_eq!(texture_ref("-unknown 3 t.png"), None);
    assert_eq!(texture_ref("   "), None);
}

#[test]
fn colours_of_one_value_are_greys_and_others_are_left_out() {
    let (text, dropped) =
        readable(b"newmtl A\nKd 0.5\nKs 1 2 3 4\nKe spectral lamp.spd\nKa 1 2\nNs 10\n");
    assert_eq!(text, "newmtl A\nKd 0.5 0.5 0.5\nKs 1 2 3\nNs 10\n");
    assert_eq!(
        dropped,
        vec!["Ke spectral lamp.spd".to_string(), "Ka 1 2".to_string()]
    );
    let m = parse(&text);
    assert_eq!(m[0].diffuse, Some([0.5; 3]));
}

#[test]
fn an_obj_names_a_bounded_number_of_libraries() {
    use crate::lower::mesh::{parse_with, MAX_LIBRARIES};
    let mut obj = String::new();
    for k in 0..1000 {
        obj += &format!("mtllib lib{k}.mtl\n");
    }
    obj += "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl A\nf 1 2 3\n";
    let mut reads = 0;
    let m = parse_with(Path::new("m.obj"), obj.as_bytes(), &mut |_, _| {
        reads += 1;
        Ok(b"newmtl A\nKd 1 0 0\n".to_vec())
    })
    .unwrap();
    assert_eq!(reads, MAX_LIBRARIES);
    assert_eq!(m.libraries.len(), MAX_LIBRARIES);
    assert_eq!(m.library_errors.len(), 1, "{:?}", m.library_errors);
}

#[test]
fn a_map_is_read_beside_its_library_and_says_where_it_is_named() {
    let m = parse("newmtl Wood\nmap_Kd tex/grain.png\n");
    let mapped = material(&m[0], Path::new("models/mats/wood.mtl"), Span::default());
    let TextureKind::Image { path, origin, .. } = &mapped.material.textures[0].1.kind else {
        panic!("not an image")
    };
    // Relative to the MTL file, as Blender reads it, not to the OBJ.
    assert_eq!(path, Path::new("models/mats/tex/grain.png"));
    let origin = origin.as_ref().expect("named by the library");
    assert_eq!(
        origin.named,
        "`tex/grain.png` of `map_Kd` of material `Wood` in `wood.mtl`"
    );
    assert!(
        origin.help.starts_with("an MTL file's maps are read relative to the MTL file: put `tex/grain.png` beside `wood.mtl`"),
        "{}",
        origin.help
    );
}
