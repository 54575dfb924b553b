//! Denoising (`--denoise`, `ptsc denoise`): refused up front by a build
//! without the `denoise` feature; with it, a denoised 4-spp Cornell box is
//! closer to the converged image than a 64-spp one without denoising.

use super::{ptsc_stderr, root, temp_dir_with};

/// A build without the feature says how to get it, before any sample.
#[cfg(not(feature = "denoise"))]
#[test]
fn without_the_feature_denoising_is_refused_before_the_render() {
    let dir = temp_dir_with(&[]);
    let out = dir.path().join("c.png");
    let scene = root().join("examples/bench/cornell.pts");
    let (code, err) = ptsc_stderr(&[
        "render",
        scene.to_str().unwrap(),
        "--denoise",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 2);
    assert!(
        err.contains("setup-oidn.sh") && err.contains("--features denoise"),
        "{err}"
    );
    assert!(!out.exists());
    let (code, err) = ptsc_stderr(&["denoise", "in.exr", "-o", out.to_str().unwrap()]);
    assert_ne!(code, 0, "{err}");
}

/// relMSE of `a` against `reference` as pbrt-v4 and the denoising
/// literature measure it: the mean over pixels and channels of
/// (a − r)² / (r² + 0.01). (Summed squared error over summed squares would
/// be decided by the lamp's few pixels, radiance 17 beside walls of 0.3.)
#[cfg(feature = "denoise")]
fn rel_mse(a: &[glam::Vec3], reference: &[glam::Vec3]) -> f64 {
    let mut e = 0.0f64;
    for (p, r) in a.iter().zip(reference) {
        for c in 0..3 {
            let (x, y) = (p[c] as f64, r[c] as f64);
            e += (x - y) * (x - y) / (y * y + 0.01);
        }
    }
    e / (3 * a.len()) as f64
}

#[cfg(feature = "denoise")]
#[test]
fn a_denoised_4_spp_cornell_box_beats_64_spp_without() {
    use ptsc::output::read_exr;
    let dir = temp_dir_with(&[]);
    let scene = root().join("examples/bench/cornell.pts");
    let render = |spp: &str, name: &str, extra: &[&str]| {
        let out = dir.path().join(name);
        let mut args = vec!["render", scene.to_str().unwrap(), "--resolution", "128x128"];
        args.extend(["--spp", spp, "-q", "-o", out.to_str().unwrap()]);
        args.extend(extra);
        let (code, err) = ptsc_stderr(&args);
        assert_eq!(code, 0, "{err}");
        read_exr(&out).unwrap().2
    };
    let reference = render("2048", "ref.exr", &[]);
    let noisy = render("64", "noisy.exr", &["--seed", "3"]);
    let denoised = render(
        "4",
        "denoised.exr",
        &["--seed", "5", "--denoise", "--aov", "albedo,normal"],
    );
    let (e_noisy, e_denoised) = (rel_mse(&noisy, &reference), rel_mse(&denoised, &reference));
    eprintln!("relMSE: 64 spp {e_noisy:.5}, 4 spp denoised {e_denoised:.5}");
    assert!(e_denoised < e_noisy, "denoised {e_denoised} vs {e_noisy}");
    // `ptsc denoise` of the saved 4-spp render (its AOVs inside) agrees.
    let raw = dir.path().join("raw.exr");
    let mut args = vec!["render", scene.to_str().unwrap(), "--resolution", "128x128"];
    args.extend([
        "--spp",
        "4",
        "--seed",
        "5",
        "--aov",
        "albedo,normal",
        "-q",
        "-o",
        raw.to_str().unwrap(),
    ]);
    assert_eq!(ptsc_stderr(&args).0, 0);
    let again = dir.path().join("again.exr");
    let (code, err) = ptsc_stderr(&[
        "denoise",
        raw.to_str().unwrap(),
        "-o",
        again.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let e_again = rel_mse(&read_exr(&again).unwrap().2, &reference);
    assert!(
        (e_again - e_denoised).abs() <= 0.05 * e_denoised,
        "{e_again} vs {e_denoised}"
    );
}
