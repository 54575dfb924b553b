//! Golden images: tiny renders compared with committed references
//! (`tests/golden/NAME.INTEGRATOR.exr`) within a tolerance, never byte for byte.
//!
//! `PTSC_BLESS=1 cargo test --release golden` rewrites the references. A failing
//! comparison writes the actual image, the expected one and a difference image
//! (as EXR and PNG) to `target/tmp/golden/` and names them in the message.

use glam::Vec3;
use ptsc::compile::{compile_file, Options};
use ptsc::integrator;
use ptsc::ir::settings::IntegratorKind;
use ptsc::output::read_exr;
use ptsc::render::film::Film;
use ptsc::render::render;
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

/// Renders a scene file with an integrator, optionally at another size and
/// sample count.
fn render_file(path: &Path, kind: IntegratorKind, size: Option<(u32, u32, u32)>) -> Film {
    let adjust = |s: &mut ptsc::ir::settings::Settings| {
        s.integrator = kind;
        if let Some((w, h, spp)) = size {
            (s.width, s.height, s.samples) = (w, h, spp);
        }
    };
    let options = Options {
        adjust: &adjust,
        ..Options::default()
    };
    let c = compile_file(path, options).unwrap();
    let ir =
        c.ir.unwrap_or_else(|| panic!("{}", c.diagnostics.render_human(&c.sources, false)));
    let integ = integrator::make(kind, &ir);
    let cancel = AtomicBool::new(false);
    render(&ir, integ.as_ref(), &cancel, &|_| {}, &mut |_, _| {}).film
}

/// Relative mean absolute error: Σ|a − b| / Σ|b| over every channel.
fn relative_mae(actual: &[Vec3], expected: &[Vec3]) -> f64 {
    let (mut diff, mut sum) = (0.0f64, 0.0f64);
    for (a, b) in actual.iter().zip(expected) {
        diff += (*a - *b)
            .abs()
            .to_array()
            .iter()
            .map(|&v| v as f64)
            .sum::<f64>();
        sum += b.abs().to_array().iter().map(|&v| v as f64).sum::<f64>();
    }
    diff / sum.max(1e-12)
}

fn failure_dir() -> PathBuf {
    Path::new(env!("CARGO_TARGET_TMPDIR")).join("golden")
}

/// Compares a render with its reference, or rewrites the reference when blessing.
fn golden(scene: &str, kind: IntegratorKind, size: Option<(u32, u32, u32)>, tolerance: f64) {
    let root = crate::root().join("tests/golden");
    let name = format!("{}.{}", scene, kind.name());
    let reference = root.join(format!("{name}.exr"));
    let film = render_file(
        &root.join("scenes").join(format!("{scene}.pts")),
        kind,
        size,
    );
    if std::env::var_os("PTSC_BLESS").is_some() {
        film.write(&reference, 0.0).unwrap();
        return;
    }
    if let Err(e) = compare(&name, &film, &reference, tolerance) {
        panic!("{e}");
    }
}

/// Checks `film` against the reference image; on failure writes the actual,
/// expected and difference images and says where.
fn compare(name: &str, film: &Film, reference: &Path, tolerance: f64) -> Result<(), String> {
    let (w, h, expected) = read_exr(reference).map_err(|e| {
        format!("no reference for {name} ({e}); run `PTSC_BLESS=1 cargo test --release golden`")
    })?;
    let actual = film.pixels();
    let same_size = (w, h) == (film.width, film.height);
    let error = if same_size {
        relative_mae(&actual, &expected)
    } else {
        f64::INFINITY
    };
    if error <= tolerance {
        return Ok(());
    }
    let dir = failure_dir();
    std::fs::create_dir_all(&dir).unwrap();
    let diff: Vec<Vec3> = if same_size {
        actual
            .iter()
            .zip(&expected)
            .map(|(a, b)| (*a - *b).abs())
            .collect()
    } else {
        vec![Vec3::ZERO; actual.len()]
    };
    let expected_film = Film::from_pixels(w, h, expected);
    let diff_film = Film::from_pixels(film.width, film.height, diff);
    for ext in ["exr", "png"] {
        film.write(&dir.join(format!("{name}.actual.{ext}")), 0.0)
            .unwrap();
        expected_film
            .write(&dir.join(format!("{name}.expected.{ext}")), 0.0)
            .unwrap();
        // The difference image is brightened 8× (3 stops) in the PNG.
        diff_film
            .write(&dir.join(format!("{name}.diff.{ext}")), 3.0)
            .unwrap();
    }
    Err(format!(
        "{name}: relative mean absolute error {error:.5} above {tolerance} \
         (image {}x{} vs reference {w}x{h}); actual, expected and diff images in {}",
        film.width,
        film.height,
        dir.display()
    ))
}

/// The debug views are noise-free up to antialiasing jitter: the tolerance
/// only absorbs floating-point differences between machines.
const DEBUG_TOLERANCE: f64 = 2e-3;
/// Whitted and hybrid images carry sampling noise; a changed random stream or
/// estimator shows as a few per cent.
const NOISY_TOLERANCE: f64 = 1e-2;

fn debug_views(scene: &str) {
    for kind in [
        IntegratorKind::Normals,
        IntegratorKind::Albedo,
        IntegratorKind::Depth,
    ] {
        golden(scene, kind, None, DEBUG_TOLERANCE);
    }
}

#[test]
fn golden_sphere() {
    debug_views("sphere");
}

#[test]
fn golden_plane() {
    debug_views("plane");
}

#[test]
fn golden_quad() {
    debug_views("quad");
}

#[test]
fn golden_disk() {
    debug_views("disk");
}

#[test]
fn golden_triangle() {
    debug_views("triangle");
}

#[test]
fn golden_box() {
    debug_views("box");
}

#[test]
fn golden_mesh() {
    debug_views("mesh");
}

#[test]
fn golden_depth_of_field_and_motion_blur() {
    debug_views("dof");
}

#[test]
fn golden_whitted_and_hybrid() {
    for kind in [IntegratorKind::Whitted, IntegratorKind::Hybrid] {
        golden("glass_mirror", kind, None, NOISY_TOLERANCE);
        golden("cornell", kind, Some((48, 48, 16)), NOISY_TOLERANCE);
    }
}

#[test]
fn a_changed_image_fails_and_leaves_a_diff() {
    // The comparison must be able to fail: a sphere's normals against the
    // reference of the quad scene.
    let root = crate::root().join("tests/golden");
    let film = render_file(
        &root.join("scenes/sphere.pts"),
        IntegratorKind::Normals,
        None,
    );
    let name = "self-test.sphere-vs-quad";
    let err = compare(name, &film, &root.join("quad.normals.exr"), DEBUG_TOLERANCE).unwrap_err();
    assert!(err.contains("relative mean absolute error"), "{err}");
    for kind in ["actual", "expected", "diff"] {
        assert!(failure_dir().join(format!("{name}.{kind}.png")).is_file());
    }
    assert!(compare(
        name,
        &film,
        &root.join("sphere.normals.exr"),
        DEBUG_TOLERANCE
    )
    .is_ok());
}
