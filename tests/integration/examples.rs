//! Every scene in `examples/` checks without errors.

use ptsc::check::check_file;
use std::path::Path;

fn scenes(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            scenes(&p, out);
        } else if p.extension().is_some_and(|x| x == "pts") {
            out.push(p);
        }
    }
}

#[test]
fn every_example_checks_clean() {
    let mut files = Vec::new();
    scenes(&crate::root().join("examples"), &mut files);
    assert!(files.len() >= 10, "found only {} examples", files.len());
    for f in files {
        let c = check_file(&f).unwrap();
        assert!(
            !c.diagnostics.has_errors(),
            "{}:\n{}",
            f.display(),
            c.diagnostics.render_human(&c.sources, false)
        );
        assert!(c.scene.is_some());
    }
}
