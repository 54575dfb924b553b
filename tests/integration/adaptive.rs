//! Adaptive sampling (`noise_threshold`, `min_samples`) through the render
//! session: converged pixels stop and keep their mean, the film is the same
//! on any thread count, a stopped render resumes to the uninterrupted
//! film, and what cannot be exact (passes, merge, another threshold) is
//! refused.

use super::session::{batch, one_thread, policy, run, same_film, scene_with, session, Log, Quiet};
use ptsc::ir::Scene;
use ptsc::render::session::{Cancel, StatePolicy};
use ptsc::render::state::Pass;
use ptsc::render::Outcome;

/// The session tests' 48×40 scene (several tiles): a constant sky above
/// (noiseless: it converges at once) and a floor and glossy sphere lit by a
/// small light below (noisy); `render` is the rest of the render block.
fn scene(render: &str) -> Scene {
    scene_with(render)
}

/// The adaptive scene at `spp`.
fn adaptive(spp: u32) -> Scene {
    scene(&format!("samples {spp} noise_threshold 0.02 min_samples 8"))
}

/// A plain batch render of `scene` to `name` in `dir`, on one thread.
fn render(dir: &tempfile::TempDir, name: &str, scene: Scene) -> ptsc::render::session::Report {
    run(
        scene,
        batch(&dir.path().join(name), policy()),
        &Quiet,
        &Cancel::new(),
    )
}

fn two_threads() -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap()
}

#[test]
fn converged_pixels_stop_and_keep_the_mean_of_their_samples() {
    let dir = tempfile::tempdir().unwrap();
    let report = render(&dir, "a.exr", adaptive(64));
    assert_eq!(report.outcome, Outcome::Complete);
    let film = &report.film;
    let (least, most, _) = film.sample_counts();
    assert_eq!(
        (least, most),
        (8, 64),
        "stopped at the first decision; noisy to the end"
    );
    let share = film.stopped_share().unwrap();
    assert!((0.2..0.95).contains(&share), "{share}");
    assert!(
        report.samples < 48 * 40 * 64 * 8 / 10,
        "{} samples",
        report.samples
    );
    // The sky's top row: no noise, stopped at 8 samples, with its colour.
    for x in 0..48 {
        assert_eq!(film.count[x], 8);
        assert!((film.pixel(x) - glam::Vec3::splat(0.3)).abs().max_element() < 1e-6);
    }
    // A pixel that sampled to the end is the uniform render's pixel: the
    // same samples in the same order.
    let uniform = render(&dir, "u.exr", scene("samples 64"));
    let full = (0..film.count.len()).filter(|&i| film.count[i] == 64);
    let mut n = 0;
    for i in full {
        assert_eq!(film.sum[i], uniform.film.sum[i]);
        n += 1;
    }
    assert!(n > 0);
}

#[test]
fn an_adaptive_film_is_the_same_on_one_and_two_threads() {
    let dir = tempfile::tempdir().unwrap();
    let one = render(&dir, "a.exr", adaptive(48));
    let s = session(adaptive(48), batch(&dir.path().join("b.exr"), policy())).unwrap();
    let two = two_threads().install(|| s.run(&Quiet, &Cancel::new()).unwrap());
    assert!(same_film(&one.film, &two.film));
    assert!(one.film.stopped_share().unwrap() > 0.0);
}

#[test]
fn a_stopped_adaptive_render_resumes_to_the_uninterrupted_film() {
    let dir = tempfile::tempdir().unwrap();
    let reference = render(&dir, "b.exr", adaptive(64));
    // Stopped in a pass after several decisions, mid-way through the tiles.
    let out = dir.path().join("a.exr");
    let cancel = Cancel::new();
    let log = Log::stopping_after(reference.samples * 2 / 3, &cancel);
    let stopped = run(adaptive(64), batch(&out, policy()), &log, &cancel);
    assert_eq!(stopped.outcome, Outcome::Cancelled);
    assert!(stopped.film.stopped_share().unwrap() > 0.0);
    let state = dir.path().join("a.exr.state.exr");
    let (saved, info) = ptsc::render::state::read_state(&state).unwrap();
    assert!(info.adaptive());
    assert!(
        same_film(&saved, &stopped.film),
        "the state keeps the halves"
    );
    let resume = StatePolicy {
        resume: true,
        ..policy()
    };
    let resumed = session(adaptive(64), batch(&out, resume.clone())).unwrap();
    let resumed = two_threads().install(|| resumed.run(&Quiet, &Cancel::new()).unwrap());
    assert_eq!(resumed.outcome, Outcome::Complete);
    assert!(same_film(&resumed.film, &reference.film));
    assert_eq!(resumed.samples + stopped.samples, reference.samples);
    // Checkpoints at every tile change no sample either.
    let every_tile = StatePolicy {
        checkpoint: Some(std::time::Duration::ZERO),
        ..policy()
    };
    let checked = run(
        adaptive(64),
        batch(&dir.path().join("c.exr"), every_tile),
        &Quiet,
        &Cancel::new(),
    );
    assert!(same_film(&checked.film, &reference.film));
    // More samples continue it as a render of that many would have.
    let more = session(adaptive(96), batch(&out, resume)).unwrap();
    let more = one_thread().install(|| more.run(&Quiet, &Cancel::new()).unwrap());
    let direct = render(&dir, "d.exr", adaptive(96));
    assert!(same_film(&more.film, &direct.film));
}

#[test]
fn what_adaptive_sampling_cannot_make_exact_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    // A share of the samples for `ptsc merge`.
    let pass = StatePolicy {
        pass: Some(Pass { k: 1, n: 2 }),
        ..policy()
    };
    let why = session(adaptive(16), batch(&dir.path().join("p.exr"), pass))
        .err()
        .unwrap()
        .to_string();
    assert!(why.contains("adaptive") && why.contains("--noise"), "{why}");
    // Its state is not a part to merge.
    let out = dir.path().join("a.exr");
    let keep = StatePolicy {
        keep_state: true,
        ..policy()
    };
    let report = run(adaptive(16), batch(&out, keep), &Quiet, &Cancel::new());
    let state = report.state.unwrap();
    let merged = dir.path().join("m.exr");
    let request = ptsc::render::merge::Request {
        parts: std::slice::from_ref(&state),
        output: &merged,
        partial: true,
        memory_limit: None,
        force: false,
    };
    let why = ptsc::render::merge::merge(&request).unwrap_err();
    assert!(why.contains("adaptive render"), "{why}");
    assert!(!merged.exists());
    // Resuming with another threshold, or none, is refused by name.
    let resume = StatePolicy {
        resume: true,
        ..policy()
    };
    let other = scene("samples 32 noise_threshold 0.1 min_samples 8");
    let why = session(other, batch(&out, resume.clone()))
        .err()
        .unwrap()
        .to_string();
    assert!(
        why.contains("with adaptive sampling (--noise 0.02)"),
        "{why}"
    );
    let why = session(scene("samples 32"), batch(&out, resume))
        .err()
        .unwrap()
        .to_string();
    assert!(
        why.contains("this render without adaptive sampling (--noise)"),
        "{why}"
    );
}
