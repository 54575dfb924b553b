//! The single integration-test binary (one link step for all of them).

mod adaptive;
mod bdpt;
mod catalogue;
mod cli;
mod cutouts;
mod denoise;
mod diagnostics;
mod editors;
mod environment;
mod examples;
mod farm;
mod files;
mod fmt;
mod folders;
mod frames;
mod gltf;
mod gltf_attributes;
mod golden;
mod group_lights;
mod hostile;
mod image_limits;
mod instances;
mod kinds;
mod layering;
mod lighting;
mod lsp;
mod materials;
mod media;
mod mitsuba;
mod nasty;
mod noise_params;
mod obj_materials;
mod outputs;
mod packets;
mod principled;
mod render;
mod session;
mod shapes;
#[cfg(unix)]
mod special_files;
mod symbols;
mod texture_inputs;
mod textures;
mod unclosed_blocks;
mod verdict;
mod watch;

use std::path::{Path, PathBuf};

/// Runs the ptsc binary in `dir` with `input` written to its stdin from
/// another thread (a command that stops reading early breaks the pipe,
/// which is not an error here); returns its exit code, stdout and stderr.
pub fn ptsc_fed(
    dir: &std::path::Path,
    args: &[&str],
    input: impl std::io::Read + Send + 'static,
) -> (i32, String, String) {
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_ptsc"))
        .args(args)
        .current_dir(dir)
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let mut stdin = child.stdin.take().unwrap();
    let mut input = input;
    let writer = std::thread::spawn(move || {
        let _ = std::io::copy(&mut input, &mut stdin);
    });
    let out = child.wait_with_output().unwrap();
    writer.join().unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// Runs the ptsc binary; returns its exit code, stdout and stderr.
pub fn ptsc(args: &[&str]) -> (i32, String, String) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_ptsc"))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// Runs the ptsc binary; returns its exit code and stderr.
pub fn ptsc_stderr(args: &[&str]) -> (i32, String) {
    let (code, _, err) = ptsc(args);
    (code, err)
}

/// The package root.
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A temporary folder holding `files` (name, text): the meshes and scenes
/// a test reads.
pub fn temp_dir_with(files: &[(&str, &str)]) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    for (name, text) in files {
        std::fs::write(dir.path().join(name), text).unwrap();
    }
    dir
}

/// Every file below `dir` whose name ends in `.{extension}`, in no
/// particular order.
pub fn files_below(dir: &Path, extension: &str) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut pending = vec![dir.to_path_buf()];
    while let Some(dir) = pending.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                pending.push(path);
            } else if path.extension().is_some_and(|e| e == extension) {
                out.push(path);
            }
        }
    }
    out
}

/// `path` relative to the package root, with `/` separators (stable in snapshots).
pub fn relative(path: &Path) -> PathBuf {
    path.strip_prefix(root()).unwrap_or(path).to_path_buf()
}

/// The pixels of a compiled scene rendered on one thread.
pub fn render_pixels(ir: &ptsc::ir::Scene) -> Vec<[f32; 3]> {
    let integ = ptsc::integrator::make(ir.settings.integrator, ir);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let cancel = std::sync::atomic::AtomicBool::new(false);
    let r =
        pool.install(|| ptsc::render::render(ir, integ.as_ref(), &cancel, &|_| {}, &mut |_, _| {}));
    r.film.pixels().iter().map(|p| p.to_array()).collect()
}
