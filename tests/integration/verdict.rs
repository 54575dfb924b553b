//! One verdict: `ptsc check` and `ptsc render` agree on every scene the
//! project keeps (tests, examples, the diagnostic and hostile cases): both
//! accept it, or both refuse it before the first sample with the same
//! diagnostics. Everything `render` can refuse comes from the compile path
//! `check` runs (`compile::compile_file`, `lower::validate`).

use std::path::{Path, PathBuf};

/// The diagnostics a command printed: its stderr up to its summary line
/// ("N errors, M warnings", or `check`'s "scene.pts: ok, M warnings"), with
/// the counts (nothing when it printed none).
fn diagnostics(stderr: &str) -> String {
    let lines: Vec<&str> = stderr.lines().collect();
    let summary = lines.iter().position(|l| {
        let words: Vec<&str> = l.split_whitespace().collect();
        matches!(words.as_slice(), [_, e, _, w] if e.starts_with("error") && w.starts_with("warning"))
            || matches!(words.as_slice(), [_, "ok,", _, w] if w.starts_with("warning"))
    });
    let Some(end) = summary else {
        return String::new();
    };
    let mut shown = lines[..end].join("\n");
    let errors = lines[..end]
        .iter()
        .filter(|l| l.trim_start().starts_with('×'))
        .count();
    let warnings = lines[..end]
        .iter()
        .filter(|l| l.trim_start().starts_with('⚠'))
        .count();
    shown.push_str(&format!("\n{errors} errors, {warnings} warnings"));
    shown
}

/// Every scene below the tests and the examples.
fn scenes() -> Vec<PathBuf> {
    let root = crate::root();
    let mut all = crate::files_below(&root.join("tests"), "pts");
    all.extend(crate::files_below(&root.join("examples"), "pts"));
    all.sort();
    all
}

/// A scene naming the image it renders to (`render { output … }`).
fn names_an_output(scene: &Path) -> bool {
    std::fs::read_to_string(scene).is_ok_and(|t| t.contains("output \""))
}

/// Runs `check` and a tiny `render` of `scene` from the package root;
/// `None` when they agree, else what differs.
pub fn disagreement(scene: &Path, out: &Path) -> Option<String> {
    let rel = crate::relative(scene);
    let rel = rel.to_str().unwrap();
    let (check_code, _, check_err) = crate::ptsc(&["check", rel]);
    let check = diagnostics(&check_err);
    // The image goes to a temporary file, unless the scene's own output is
    // what `check` refused: then `render` must refuse it too (it writes
    // nothing).
    let out = out.to_str().unwrap();
    let mut args = vec!["render", rel, "--spp", "1", "--resolution", "4x4"];
    let refused_output = check.contains("pts::check::output_file");
    if !(names_an_output(scene) && refused_output) {
        args.extend(["-o", out]);
    }
    let (render_code, _, render_err) = crate::ptsc(&args);
    let render = diagnostics(&render_err);
    let verdicts = (check_code, render_code);
    if !matches!(verdicts, (0, 0) | (1, 1)) || check != render {
        return Some(format!(
            "{rel}: check exit {check_code}, render exit {render_code}\n--- check:\n{check_err}\n--- render:\n{render_err}"
        ));
    }
    None
}

#[test]
fn check_and_render_give_one_verdict_on_every_scene() {
    let root = crate::root();
    std::env::set_current_dir(&root).unwrap();
    let all = scenes();
    assert!(all.len() > 150, "only {} scenes", all.len());
    let dir = tempfile::tempdir().unwrap();
    let next = std::sync::atomic::AtomicUsize::new(0);
    let failures = std::sync::Mutex::new(Vec::new());
    std::thread::scope(|s| {
        for worker in 0..2 {
            let (all, next, failures, dir) = (&all, &next, &failures, dir.path());
            s.spawn(move || loop {
                let i = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                let Some(scene) = all.get(i) else { break };
                // One image per scene: a scene with a time budget keeps
                // its state beside its image, which another render into
                // the same file would refuse to replace.
                let out = dir.join(format!("out{worker}_{i}.png"));
                if let Some(why) = disagreement(scene, &out) {
                    failures.lock().unwrap().push(why);
                }
            });
        }
    });
    let failures = failures.into_inner().unwrap();
    assert!(
        failures.is_empty(),
        "{} of {} scenes:\n{}",
        failures.len(),
        all.len(),
        failures.join("\n\n")
    );
}

#[test]
fn a_group_placed_twice_reports_its_broken_mesh_once() {
    let scene = crate::root().join("tests/diagnostics/lower_broken_mesh_placed_twice.pts");
    let (code, _, err) = crate::ptsc(&["check", scene.to_str().unwrap()]);
    assert_eq!(code, 1);
    assert_eq!(err.matches("cannot load mesh").count(), 1, "{err}");
}

/// A corrupt image or mesh is reported beside the scene's other errors
/// (a typo, a syntax error), with the words lowering uses once the rest is
/// fixed: not found only after every other mistake is.
#[test]
fn broken_files_are_reported_beside_the_other_errors() {
    let data = crate::root().join("tests/diagnostics/data");
    let tmp = crate::temp_dir_with(&[]);
    let dir = tmp.path();
    for name in ["truncated.ply", "not_an_image.png", "cyclic.gltf"] {
        std::fs::copy(data.join(name), dir.join(name)).unwrap();
    }
    let clean = "camera { position <0, 1, 5> look_at <0, 0, 0> }\n\
         point_light { position <0, 5, 5> intensity rgb 10 }\n\
         material m { diffuse image { file \"not_an_image.png\" } }\n\
         mesh { file \"truncated.ply\" material m }\n\
         group g { mesh { file \"cyclic.gltf\" } }\n\
         instance g { }\n";
    let run = |text: &str| {
        let scene = dir.join("s.pts");
        std::fs::write(&scene, text).unwrap();
        let (code, _, err) = crate::ptsc(&["check", scene.to_str().unwrap()]);
        assert_eq!(code, 1, "{err}");
        err
    };
    let files_only = run(clean);
    for mistake in [
        "sphere { center <0, 0, 0> radius 1 radus 2 }\n",
        "sphere { center <0, 0, 0> radius 1\n",
        "let x = ;\n",
    ] {
        let err = run(&format!("{clean}{mistake}"));
        for line in files_only
            .lines()
            .filter(|l| l.contains('×') || l.contains("╰──"))
        {
            assert!(err.contains(line), "{mistake}: {line} missing from\n{err}");
        }
    }
    for said in [
        "cannot load image `not_an_image.png`",
        "cannot load mesh `truncated.ply`",
    ] {
        assert_eq!(files_only.matches(said).count(), 1, "{files_only}");
    }
}
