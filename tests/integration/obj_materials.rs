//! An OBJ's own materials (`mtllib`, `usemtl`): a mesh that names no
//! material takes them, mapped to `type principled` (`lower::mtl`).

use ptsc::compile::{compile_file, Options};
use ptsc::lower::mtl::roughness_of_exponent;

const MTL: &str = "newmtl Red
Kd 0.8 0.1 0.1
Ks 0.5 0.5 0.5
Ns 100
newmtl Gold
Kd 0.9 0.6 0.2
Pm 1
Pr 0.3
";

/// Two quads side by side, one per material; `header` starts the file.
fn obj(header: &str, red: bool, gold: bool) -> String {
    let mut s = format!("{header}v -1 0 0\nv 0 0 0\nv 0 1 0\nv -1 1 0\nv 1 0 0\nv 1 1 0\n");
    if red {
        s += "usemtl Red\nf 1 2 3\nf 1 3 4\n";
    }
    if gold {
        s += "usemtl Gold\nf 2 5 6\nf 2 6 3\n";
    }
    s
}

const STAGE: &str = "camera { position <0, 0.5, 2.5> look_at <0, 0.5, 0> }
render { resolution <32, 24> samples 16 }
sky { }
point_light { position <0, 2, 3> intensity rgb 20 }
";

fn compile(dir: &std::path::Path, scene: &str) -> ptsc::compile::Compiled {
    let path = dir.join("scene.pts");
    std::fs::write(&path, scene).unwrap();
    compile_file(&path, Options::default()).unwrap()
}

#[test]
fn an_obj_with_its_mtl_renders_as_the_same_materials_written_out() {
    let dir = crate::temp_dir_with(&[
        ("two.mtl", MTL),
        ("red.obj", &obj("", true, false)),
        ("gold.obj", &obj("", false, true)),
    ]);
    std::fs::write(
        dir.path().join("two.obj"),
        obj("mtllib two.mtl\n", true, true),
    )
    .unwrap();
    let from_file = compile(dir.path(), &format!("{STAGE}mesh {{ file \"two.obj\" }}"));
    let written = compile(
        dir.path(),
        &format!(
            "{STAGE}mesh {{ file \"red.obj\" material {{ type principled base_color rgb <0.8, 0.1, 0.1> specular 0.5 roughness {:.17} }} }}
             mesh {{ file \"gold.obj\" material {{ type principled base_color rgb <0.9, 0.6, 0.2> metallic 1 roughness 0.3 }} }}",
            roughness_of_exponent(100.0)
        ),
    );
    let sources = &from_file.sources;
    let (a, b) = (from_file.ir.as_ref(), written.ir.as_ref());
    let (Some(a), Some(b)) = (a, b) else {
        panic!(
            "{}{}",
            from_file.diagnostics.render_human(sources, false),
            written.diagnostics.render_human(&written.sources, false)
        );
    };
    // The file's two groups are two objects of their own materials (the
    // default grey stays in the list, unused).
    let used = |ir: &ptsc::ir::Scene| -> Vec<ptsc::material::Material> {
        (ir.object_material.iter())
            .map(|&m| ir.materials[m as usize].clone())
            .collect()
    };
    let (ma, mb) = (used(a), used(b));
    assert_eq!(ma.len(), 2);
    for (x, y) in ma.iter().zip(&mb) {
        assert_eq!(x.kind, y.kind);
        assert!((x.diffuse - y.diffuse).abs().max_element() < 1e-6);
    }
    let (pa, pb) = (crate::render_pixels(a), crate::render_pixels(b));
    let worst = (pa.iter().zip(&pb))
        .flat_map(|(p, q)| (0..3).map(move |k| (p[k] - q[k]).abs()))
        .fold(0.0f32, f32::max);
    assert!(worst < 1e-4, "largest difference {worst}");
    let lit = pa.iter().filter(|p| p[0] > p[2] * 2.0).count();
    assert!(lit > 20, "the red quad shows in {lit} pixels");
}

#[test]
fn a_scene_material_overrides_the_files() {
    let dir = crate::temp_dir_with(&[("two.mtl", MTL)]);
    std::fs::write(
        dir.path().join("two.obj"),
        obj("mtllib two.mtl\n", true, true),
    )
    .unwrap();
    let c = compile(
        dir.path(),
        &format!("{STAGE}mesh {{ file \"two.obj\" material {{ diffuse rgb 0.5 }} }}"),
    );
    let ir = c.ir.expect("compiles");
    assert_eq!(ir.materials.len(), 1);
    assert_eq!(ir.materials[0].kind, ptsc::material::Kind::Lobes);
}

#[test]
fn a_missing_library_or_texture_is_reported_at_the_mesh() {
    let dir = crate::temp_dir_with(&[("textured.mtl", "newmtl T\nmap_Kd nowhere.png\n")]);
    std::fs::write(
        dir.path().join("lost.obj"),
        obj("mtllib lost.mtl\n", true, false),
    )
    .unwrap();
    std::fs::write(
        dir.path().join("textured.obj"),
        obj("mtllib textured.mtl\nvt 0 0\n", true, false).replace("Red", "T"),
    )
    .unwrap();
    let lost = compile(dir.path(), &format!("{STAGE}mesh {{ file \"lost.obj\" }}"));
    let text = lost.diagnostics.render_human(&lost.sources, false);
    assert!(lost.ir.is_some(), "{text}");
    assert!(
        text.contains("a material library of") && text.contains("lost.mtl"),
        "{text}"
    );
    assert!(
        text.contains("mesh { file \"lost.obj\" }"),
        "the mesh statement is shown: {text}"
    );
    let textured = compile(
        dir.path(),
        &format!("{STAGE}mesh {{ file \"textured.obj\" }}"),
    );
    let text = textured.diagnostics.render_human(&textured.sources, false);
    assert!(textured.ir.is_none(), "a missing texture is an error");
    assert!(text.contains("nowhere.png"), "{text}");
}

#[test]
fn a_library_changed_alone_is_read_again_by_a_kept_cache() {
    use ptsc::compile::compile_str;
    use ptsc::lower::cache::LowerCache;
    let dir = crate::temp_dir_with(&[("two.mtl", MTL)]);
    std::fs::write(
        dir.path().join("two.obj"),
        obj("mtllib two.mtl\n", true, true),
    )
    .unwrap();
    let path = dir.path().join("scene.pts");
    let text = format!("{STAGE}mesh {{ file \"two.obj\" }}");
    let mut cache = LowerCache::default();
    let mut red = || {
        let options = Options {
            cache: Some(&mut cache),
            ..Options::default()
        };
        let ir = compile_str(&path, &text, options).ir.expect("compiles");
        ir.materials[ir.object_material[0] as usize].diffuse.x
    };
    assert!((red() - 0.8).abs() < 1e-6);
    // The library changes size (its stamp with it); the OBJ does not.
    std::fs::write(
        dir.path().join("two.mtl"),
        MTL.replace("Kd 0.8 0.1 0.1", "Kd 0.25 0.1 0.1 "),
    )
    .unwrap();
    assert!(
        (red() - 0.25).abs() < 1e-6,
        "the kept mesh still had the old library"
    );
}

#[test]
fn copies_of_one_file_share_its_materials_and_warn_once() {
    let dir = crate::temp_dir_with(&[("two.mtl", &format!("{MTL}map_Kd -t 0.1 0.1 x.png\n"))]);
    std::fs::write(
        dir.path().join("x.png"),
        include_bytes!("../../examples/models/leaf.png"),
    )
    .unwrap();
    std::fs::write(
        dir.path().join("two.obj"),
        obj("mtllib two.mtl\n", true, true),
    )
    .unwrap();
    let c = compile(
        dir.path(),
        &format!(
            "{STAGE}for i in 0 .. 2 {{ mesh {{ file \"two.obj\" translate <i * 3, 0, 0> }} }}"
        ),
    );
    let text = c.diagnostics.render_human(&c.sources, false);
    let ir = c.ir.expect("compiles");
    // Two copies (`0 .. 2` leaves 2 out), two groups each, the two
    // materials once.
    assert_eq!(ir.object_material.len(), 4);
    let distinct: std::collections::BTreeSet<u32> = ir.object_material.iter().copied().collect();
    assert_eq!(distinct.len(), 2, "{:?}", ir.object_material);
    assert_eq!(text.matches("`map_Kd`'s options -t").count(), 1, "{text}");
}

#[test]
fn a_render_reads_each_mesh_file_once() {
    use ptsc::compile::compile_str;
    use ptsc::lower::cache::LowerCache;
    let dir = crate::temp_dir_with(&[("two.mtl", MTL)]);
    std::fs::write(
        dir.path().join("two.obj"),
        obj("mtllib two.mtl\n", true, true),
    )
    .unwrap();
    std::fs::write(dir.path().join("plain.obj"), obj("", true, false)).unwrap();
    let path = dir.path().join("scene.pts");
    // A mesh split by its materials, and one that brings none: the split
    // reads both, and the gathering takes what it read.
    let text = format!("{STAGE}mesh {{ file \"two.obj\" }}\nmesh {{ file \"plain.obj\" }}");
    let mut cache = LowerCache::one_off();
    let options = Options {
        cache: Some(&mut cache),
        ..Options::default()
    };
    assert!(compile_str(&path, &text, options).ir.is_some());
    assert_eq!(cache.mesh_loads, 2);
}

#[test]
fn materials_replaces_the_files_by_name_and_warns_of_names_it_lacks() {
    let dir = crate::temp_dir_with(&[
        ("two.mtl", MTL),
        ("red.obj", &obj("", true, false)),
        ("gold.obj", &obj("", false, true)),
    ]);
    std::fs::write(
        dir.path().join("two.obj"),
        obj("mtllib two.mtl\n", true, true),
    )
    .unwrap();
    // The replacing material is declared after the mesh that names it.
    let swapped = compile(
        dir.path(),
        &format!(
            "{STAGE}mesh {{ file \"two.obj\" materials {{ \"Gold\" blue  \"Silver\" blue }} }}
             material blue {{ diffuse rgb <0.2, 0.3, 0.9> }}"
        ),
    );
    let written = compile(
        dir.path(),
        &format!(
            "{STAGE}mesh {{ file \"red.obj\" material {{ type principled base_color rgb <0.8, 0.1, 0.1> specular 0.5 roughness {:.17} }} }}
             mesh {{ file \"gold.obj\" material {{ diffuse rgb <0.2, 0.3, 0.9> }} }}",
            roughness_of_exponent(100.0)
        ),
    );
    let text = swapped.diagnostics.render_human(&swapped.sources, false);
    let (Some(a), Some(b)) = (swapped.ir.as_ref(), written.ir.as_ref()) else {
        panic!("{text}");
    };
    assert!(
        text.contains("has no material `Silver`") && text.contains("\"Silver\""),
        "the name the file lacks is a warning at it: {text}"
    );
    assert_eq!(swapped.diagnostics.items.len(), 1, "{text}");
    let (pa, pb) = (crate::render_pixels(a), crate::render_pixels(b));
    let worst = (pa.iter().zip(&pb))
        .flat_map(|(p, q)| (0..3).map(move |k| (p[k] - q[k]).abs()))
        .fold(0.0f32, f32::max);
    assert!(worst < 1e-4, "largest difference {worst}");
    let blue = pa.iter().filter(|p| p[2] > p[0] * 2.0).count();
    let red = pa.iter().filter(|p| p[0] > p[2] * 2.0).count();
    assert!(blue > 20 && red > 20, "{blue} blue and {red} red pixels");
}

#[test]
fn a_group_placed_twice_keeps_its_objs_materials() {
    let dir = crate::temp_dir_with(&[("two.mtl", MTL)]);
    std::fs::write(
        dir.path().join("two.obj"),
        obj("mtllib two.mtl\n", true, true),
    )
    .unwrap();
    let placed = compile(
        dir.path(),
        &format!(
            "{STAGE}group g {{ mesh {{ file \"two.obj\" scale 0.5 materials {{ \"Gold\" blue }} }} }}
             instance g {{ translate <-0.5, 0, 0> }}
             instance g {{ translate <0.5, 0.2, 0> material {{ diffuse rgb <0, 1, 0> }} }}
             material blue {{ diffuse rgb <0.2, 0.3, 0.9> }}"
        ),
    );
    let flat = compile(
        dir.path(),
        &format!(
            "{STAGE}mesh {{ file \"two.obj\" scale 0.5 translate <-0.5, 0, 0> materials {{ \"Gold\" blue }} }}
             mesh {{ file \"two.obj\" scale 0.5 translate <0.5, 0.2, 0> materials {{ \"Gold\" blue }} }}
             material blue {{ diffuse rgb <0.2, 0.3, 0.9> }}"
        ),
    );
    let text = placed.diagnostics.render_human(&placed.sources, false);
    let (Some(a), Some(b)) = (placed.ir.as_ref(), flat.ir.as_ref()) else {
        panic!("{text}");
    };
    assert_eq!(a.instances.placements.len(), 2, "the group is shared");
    let (pa, pb) = (crate::render_pixels(a), crate::render_pixels(b));
    let worst = (pa.iter().zip(&pb))
        .flat_map(|(p, q)| (0..3).map(move |k| (p[k] - q[k]).abs()))
        .fold(0.0f32, f32::max);
    assert!(worst < 1e-3, "largest difference {worst}");
    let blue = pa.iter().filter(|p| p[2] > p[0] * 2.0).count();
    let red = pa.iter().filter(|p| p[0] > p[2] * 2.0).count();
    assert!(blue > 10 && red > 10, "{blue} blue and {red} red pixels");
}
