//! The file seam: a scene compiled from files held in memory, its
//! includes, mesh and image read through them and never from the disk,
//! and the dependencies a compile reports being exactly what it asked.

use ptsc::compile::{compile_bytes, compile_file, Options};
use ptsc::source::{Files, MemoryFiles};
use std::path::{Path, PathBuf};

/// A 2 × 2 PNG, made in memory.
fn png() -> Vec<u8> {
    use image::ImageEncoder;
    let mut out = Vec::new();
    image::codecs::png::PngEncoder::new(&mut out)
        .write_image(&[200u8; 12], 2, 2, image::ExtendedColorType::Rgb8)
        .unwrap();
    out
}

const SCENE: &str = r#"
render { resolution <16, 16>  samples 1 }
camera { position <0, 1, 5>  look_at <0, 1, 0> }
include "parts/lights.pts"
material wood_look { diffuse image { file "maps/wood.png" } }
mesh { file "meshes/tri.obj"  material wood_look }
sphere { center <0, 1, 0>  radius RADIUS }
"#;

/// The scene, its include, mesh and image, in a folder that does not
/// exist on the disk: only the map can answer for them.
fn memory_scene() -> (MemoryFiles, PathBuf) {
    let root = PathBuf::from("/no such folder, surely/scene");
    let mut files = MemoryFiles::new();
    files.insert(root.join("main.pts"), SCENE);
    files.insert(
        root.join("parts/lights.pts"),
        "let RADIUS = 0.5;\npoint_light { position <0, 4, 4>  intensity rgb 30 }\n",
    );
    files.insert(
        root.join("meshes/tri.obj"),
        "v -1 0 0\nv 1 0 0\nv 0 2 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n",
    );
    files.insert(root.join("maps/wood.png"), png());
    assert!(!root.exists());
    (files, root)
}

#[test]
fn a_scene_in_memory_compiles_and_renders_without_the_disk() {
    let (files, root) = memory_scene();
    let options = Options {
        files: &files,
        ..Options::default()
    };
    let scene = root.join("main.pts");
    let compiled = compile_file(&scene, options).expect("the map holds the scene");
    assert!(
        !compiled.has_errors(),
        "{}",
        compiled.diagnostics.render_human(&compiled.sources, false)
    );
    let ir = compiled.ir.expect("lowered");
    assert_eq!(ir.settings.width, 16);
    // What was asked, in order, and nothing else: what `watch` watches.
    let asked: Vec<PathBuf> = [
        "main.pts",
        "parts/lights.pts",
        "maps/wood.png",
        "meshes/tri.obj",
    ]
    .iter()
    .map(|p| root.join(p))
    .collect();
    let mut got = compiled.dependencies.clone();
    got.sort();
    let mut want = asked.clone();
    want.sort();
    assert_eq!(got, want);
    assert_eq!(compiled.dependencies[0], scene);
}

#[test]
fn an_unsaved_buffer_wins_over_the_file_on_disk() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("s.pts");
    std::fs::write(&scene, "sphere { radius 1 }\n").unwrap();
    let mut files = MemoryFiles::over_disk();
    files.insert(&scene, "sphere { radus 1 }\n");
    let bytes = files.read(&scene, 1 << 20).unwrap();
    let compiled = compile_bytes(
        &scene,
        bytes,
        Options {
            files: &files,
            lower: false,
            ..Options::default()
        },
    );
    let report = compiled.diagnostics.render_human(&compiled.sources, false);
    assert!(report.contains("unknown parameter `radus`"), "{report}");
}

#[test]
fn missing_files_are_diagnostics_and_dependencies_still() {
    let (mut files, root) = memory_scene();
    files.remove(&root.join("parts/lights.pts"));
    files.remove(&root.join("meshes/tri.obj"));
    let compiled = compile_file(
        &root.join("main.pts"),
        Options {
            files: &files,
            ..Options::default()
        },
    )
    .unwrap();
    let report = compiled.diagnostics.render_human(&compiled.sources, false);
    assert!(
        report.contains("cannot include `parts/lights.pts`"),
        "{report}"
    );
    assert!(
        report.contains("mesh file `meshes/tri.obj` not found"),
        "{report}"
    );
    // A file that appears later is a change `watch` must see.
    let deps = &compiled.dependencies;
    assert!(deps.contains(&root.join("parts/lights.pts")), "{deps:?}");
    assert!(deps.contains(&root.join("meshes/tri.obj")), "{deps:?}");
}

#[test]
fn an_include_cycle_is_found_by_the_files_canonical_names() {
    let mut files = MemoryFiles::new();
    let root = Path::new("/mem");
    files.insert(root.join("a.pts"), "include \"sub/../b.pts\"\n");
    files.insert(root.join("b.pts"), "include \"a.pts\"\n");
    let compiled = compile_file(
        &root.join("a.pts"),
        Options {
            files: &files,
            lower: false,
            ..Options::default()
        },
    )
    .unwrap();
    let report = compiled.diagnostics.render_human(&compiled.sources, false);
    assert!(report.contains("includes itself"), "{report}");
}
