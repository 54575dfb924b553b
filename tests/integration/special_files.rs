//! Issue 35, class 7: a scene's inputs that are not regular files (a link
//! to `/dev/zero` or `/dev/urandom`, a FIFO, a folder) or that are absurdly
//! large (a sparse terabyte) are refused at once, with the path and what
//! it is, by `check` and `render` alike: in every role a file plays (image
//! texture, environment map, OBJ and PLY mesh, include, the scene itself).
//! Before, `render` hashed every data file to its end for the scene's
//! fingerprint: it waited forever on a device or a FIFO (and ignored
//! SIGTERM meanwhile) and read a sparse file in full, while `check` said
//! the scene was wrong, or `check FIFO` itself waited for a writer. Run
//! through the binary under the hostile suite's time and memory limits,
//! then compared: `check` and `render` print the same diagnostics.

use crate::hostile::{check_case, generated, CAMERA};
use std::path::Path;
use std::process::Command;

/// The special files of a kind, made in `dir` under the name `NAME.EXT`
/// for each extension; returns the text `stderr` must hold (what the file
/// is), or `None` where the platform cannot make it.
fn make(dir: &Path, name: &str, ext: &str) -> Option<&'static str> {
    let path = dir.join(format!("{name}.{ext}"));
    match name {
        "zero" | "random" => {
            let device = if name == "zero" {
                "/dev/zero"
            } else {
                "/dev/urandom"
            };
            std::os::unix::fs::symlink(device, &path).ok()?;
            Some("a character device")
        }
        "fifo" => {
            let made = Command::new("mkfifo").arg(&path).status().ok()?;
            made.success().then_some("a FIFO")
        }
        "folder" => {
            std::fs::create_dir(&path).ok()?;
            Some("folder")
        }
        // A terabyte without a byte on disk.
        "sparse" => {
            let f = std::fs::File::create(&path).ok()?;
            f.set_len(1 << 40).ok()?;
            Some("larger than")
        }
        _ => unreachable!(),
    }
}

/// A scene in which `file` plays `role`.
fn scene(role: &str, file: &str) -> String {
    let lamp = "point_light { position <0, 5, 0> intensity rgb 10 }\n";
    let body = match role {
        "texture" => format!(
            "sphere {{ center <0, 0, 0> radius 1 material {{ diffuse image {{ file \"{file}\" }} }} }}\n"
        ),
        "bump" => format!(
            "sphere {{ center <0, 0, 0> radius 1 material {{ bump image {{ file \"{file}\" }} }} }}\n"
        ),
        "environment" => format!("environment {{ file \"{file}\" }}\n"),
        "mesh" => format!("mesh {{ file \"{file}\" }}\n"),
        "include" => format!("include \"{file}\"\n"),
        _ => unreachable!(),
    };
    format!("{CAMERA}{lamp}{body}")
}

#[test]
fn special_and_huge_files_are_refused_at_once_by_check_and_render() {
    let dir = tempfile::tempdir().unwrap();
    let roles = [
        ("texture", "png"),
        ("bump", "jpg"),
        ("environment", "hdr"),
        ("environment", "exr"),
        ("mesh", "obj"),
        ("mesh", "ply"),
        ("include", "ptsi"),
    ];
    let mut tried = 0;
    for name in ["zero", "random", "fifo", "folder", "sparse"] {
        for (role, ext) in roles {
            let Some(what) = make(dir.path(), name, ext) else {
                continue;
            };
            let file = format!("{name}.{ext}");
            let path = dir.path().join(format!("{role}_{name}_{ext}.pts"));
            std::fs::write(&path, scene(role, &file)).unwrap();
            for command in ["check {scene}", "render {scene} -o {out}.png"] {
                // One verdict: the same refusal, naming the file and what
                // it is, within seconds.
                let case = generated(
                    &format!("{role} {file}: {command}"),
                    &format!(
                        "// run: {command}\n// exit: 1\n// stderr: {file}\n// stderr: {what}\n// timeout: 10\n// memory: 1024"
                    ),
                );
                check_case(&case, &path, dir.path());
                tried += 1;
            }
            // Both ended at once: their diagnostics are the same, spans too.
            let out = dir.path().join("out.png");
            if let Some(why) = crate::verdict::disagreement(&path, &out) {
                panic!("{why}");
            }
        }
    }
    assert!(tried >= 40, "only {tried} cases could be made");
}

#[test]
fn a_scene_that_is_no_regular_file_is_refused_at_once() {
    let dir = tempfile::tempdir().unwrap();
    for name in ["zero", "fifo", "folder", "sparse"] {
        let Some(what) = make(dir.path(), name, "pts") else {
            continue;
        };
        let scene = dir.path().join(format!("{name}.pts"));
        // `fmt` takes a folder for its scenes; the others it reads as
        // `check` does (it read `/dev/zero` until memory ran out).
        let fmt = ["fmt {scene}", "fmt --check {scene}"];
        let fmt = if name == "folder" { &[][..] } else { &fmt[..] };
        let commands = ["check {scene}", "render {scene} -o {out}.png"];
        for command in commands.iter().chain(fmt) {
            let case = generated(
                &format!("{name}.pts: {command}"),
                &format!(
                    "// run: {command}\n// exit: 2\n// stderr: {name}.pts\n// stderr: {what}\n// timeout: 10\n// memory: 1024"
                ),
            );
            check_case(&case, &scene, dir.path());
        }
    }
}
