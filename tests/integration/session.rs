//! The render session as a library (`ptsc::render::session`), without the
//! command line: the passes an observer sees, a render split into passes
//! equal to one render, a cancelled render resumable to the uninterrupted
//! image, checkpoints that change nothing, the state a session refuses to
//! replace, and a live session's files.

use ptsc::compile::{compile_str, Options};
use ptsc::ir::Scene;
use ptsc::render::film::Film;
use ptsc::render::session::{
    Cancel, Error, Mode, Observer, PassDone, Plan, PreviewDone, Report, Session, StatePolicy,
};
use ptsc::render::state::Pass;
use ptsc::render::Outcome;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;
use std::time::Duration;

/// A small scene with glossy reflection and an area light, `spp` samples
/// per pixel, 48×40 (several tiles of 16×16).
fn scene(spp: u32) -> Scene {
    scene_with(&format!("samples {spp}"))
}

/// The small scene with `render` as the rest of its render block.
pub(crate) fn scene_with(render: &str) -> Scene {
    let text = format!(
        "camera {{ position <0, 1, 4> look_at <0, 0.5, 0> }}\n\
         background rgb 0.3\n\
         plane {{ normal <0, 1, 0> material {{ diffuse rgb 0.5 }} }}\n\
         sphere {{ center <0, 0.5, 0> radius 0.5 material {{ reflection rgb 0.8 gloss 0.2 }} }}\n\
         sphere {{ center <1, 2, 1> radius 0.3 material {{ emission rgb 8 }} }}\n\
         render {{ resolution <48, 40> {render} }}\n"
    );
    let c = compile_str(Path::new("s.pts"), &text, Options::default());
    c.ir.unwrap_or_else(|| panic!("{}", c.diagnostics.render_human(&c.sources, false)))
}

/// A batch plan writing `output` by `policy`.
pub(crate) fn batch(output: &Path, policy: StatePolicy) -> Plan {
    Plan {
        output: output.to_path_buf(),
        inputs: Vec::new(),
        memory_limit: None,
        aovs: Vec::new(),
        denoise: false,
        tev: None,
        mode: Mode::Batch(policy),
    }
}

/// The state policy of a plain `ptsc render` of the test scene.
pub(crate) fn policy() -> StatePolicy {
    StatePolicy {
        scene: "s.pts".into(),
        fingerprint: 7,
        ..StatePolicy::default()
    }
}

/// Starts a session of `plan` over `scene`.
pub(crate) fn session(scene: Scene, plan: Plan) -> Result<Session, Error> {
    plan.check()
        .and_then(|checked| Session::new(scene, checked))
}

/// Runs `plan` over `scene` on one thread (tiles in order), to the end.
pub(crate) fn run(scene: Scene, plan: Plan, observer: &dyn Observer, cancel: &Cancel) -> Report {
    let session = session(scene, plan).unwrap();
    one_thread().install(|| session.run(observer, cancel).unwrap())
}

pub(crate) fn one_thread() -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap()
}

/// An observer that hears nothing.
pub(crate) struct Quiet;
impl Observer for Quiet {}

/// An observer that writes down what it hears, and cancels its token once
/// `stop_after` pixel samples are done.
#[derive(Default)]
pub(crate) struct Log {
    events: Mutex<Vec<String>>,
    last_progress: AtomicU64,
    stop_after: Option<(u64, Cancel)>,
}

impl Observer for Log {
    fn progress(&self, done: u64) {
        let before = self.last_progress.fetch_max(done, Ordering::Relaxed);
        assert!(done >= before, "progress went back from {before} to {done}");
        if let Some((after, cancel)) = &self.stop_after {
            if done >= *after {
                cancel.cancel();
            }
        }
    }
    fn preview(&self, preview: &PreviewDone) {
        let line = format!("preview {:?} {}", preview.size, preview.written.is_ok());
        // A build that denoises denoises the preview; one that does not, not.
        assert_eq!(preview.denoised, ptsc::render::denoise::AVAILABLE);
        self.events.lock().unwrap().push(line);
    }
    fn pass(&self, pass: &PassDone) {
        let written = pass.image.map(|r| r.is_ok());
        let line = format!("pass {} to {} spp {written:?}", pass.number, pass.spp);
        self.events.lock().unwrap().push(line);
    }
    fn checkpoint(&self, _state: &Path) {
        self.events.lock().unwrap().push("checkpoint".into());
    }
    fn rendered(&self) {
        self.events.lock().unwrap().push("rendered".into());
    }
}

impl Log {
    /// A log that cancels `cancel` once `samples` pixel samples are done.
    pub(crate) fn stopping_after(samples: u64, cancel: &Cancel) -> Log {
        Log {
            stop_after: Some((samples, cancel.clone())),
            ..Log::default()
        }
    }

    pub(crate) fn events(&self) -> Vec<String> {
        self.events.lock().unwrap().clone()
    }
}

/// Whether two films hold the same samples, bit for bit (and the same
/// half films and stopped pixels, if adaptive).
pub(crate) fn same_film(a: &Film, b: &Film) -> bool {
    let bits = |v: &[glam::DVec3]| {
        v.iter()
            .map(|x| x.to_array().map(f64::to_bits))
            .collect::<Vec<_>>()
    };
    let halves = |f: &Film| f.halves.as_ref().map(|h| (bits(&h.odd), h.stopped.clone()));
    (a.width, a.height, a.first) == (b.width, b.height, b.first)
        && a.count == b.count
        && halves(a) == halves(b)
        && a.sum
            .iter()
            .zip(&b.sum)
            .all(|(x, y)| x.to_array() == y.to_array())
}

#[test]
fn an_observer_sees_the_passes_in_order_then_the_end() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("a.exr");
    let log = Log::default();
    let session = session(scene(40), batch(&out, policy())).unwrap();
    let (done, total) = (session.samples_done(), session.samples_total());
    assert_eq!((done, total), (0, 48 * 40 * 40));
    let report = one_thread().install(|| session.run(&log, &Cancel::new()).unwrap());
    // A batch render's passes: one sample per pixel, then whole runs.
    assert_eq!(
        log.events(),
        [
            "pass 1 to 1 spp None",
            "pass 2 to 16 spp None",
            "pass 3 to 32 spp None",
            "pass 4 to 40 spp None",
            "rendered"
        ]
    );
    assert_eq!(log.last_progress.load(Ordering::Relaxed), total);
    assert_eq!(report.outcome, Outcome::Complete);
    assert_eq!(report.samples, total);
    assert_eq!(report.film.sample_counts().0, 40);
    // A finished render keeps no state unless asked.
    assert!(report.image_written && report.state.is_none());
    assert!(out.is_file() && !dir.path().join("a.exr.state.exr").exists());
}

#[test]
fn a_render_in_two_passes_equals_one_render() {
    let dir = tempfile::tempdir().unwrap();
    let at = |name: &str| dir.path().join(name);
    let whole = run(
        scene(6),
        batch(&at("whole.exr"), policy()),
        &Quiet,
        &Cancel::new(),
    );
    let mut parts = Vec::new();
    for k in 1..=2 {
        let part = at(&format!("part{k}.exr"));
        let policy = StatePolicy {
            pass: Some(Pass { k, n: 2 }),
            ..policy()
        };
        let report = run(scene(6), batch(&part, policy), &Quiet, &Cancel::new());
        // A part file is its own state.
        assert_eq!(report.state.as_deref(), Some(part.as_path()));
        assert_eq!(report.film.sample_counts().0, 3);
        parts.push(part);
    }
    let merged = at("merged.exr");
    let request = ptsc::render::merge::Request {
        parts: &parts,
        output: &merged,
        partial: false,
        memory_limit: None,
        force: false,
    };
    let summary = ptsc::render::merge::merge(&request).unwrap();
    assert_eq!((summary.parts, summary.passes, summary.spp), (2, 2, (6, 6)));
    assert!(summary.warnings.is_empty());
    // The parts' sums add up to the whole's, up to f64 rounding.
    let (one, two) = (
        whole.film,
        ptsc::render::state::read_state(&parts[0]).unwrap().0,
    );
    let mut sum = two;
    sum.add(&ptsc::render::state::read_state(&parts[1]).unwrap().0);
    assert_eq!(sum.count, one.count);
    for (a, b) in one.sum.iter().zip(&sum.sum) {
        assert!((*a - *b).abs().max_element() <= 1e-9 * a.abs().max_element().max(1.0));
    }
}

#[test]
fn a_cancelled_render_leaves_a_state_that_resumes_to_the_uninterrupted_image() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("a.exr");
    let reference = run(
        scene(40),
        batch(&dir.path().join("b.exr"), policy()),
        &Quiet,
        &Cancel::new(),
    );
    // Stopped in the middle of its third pass (16 to 32 spp), between
    // tiles: the resumed render skips the two passes done.
    let cancel = Cancel::new();
    let log = Log {
        stop_after: Some((48 * 40 * 16 + 16 * 16 * 16 * 3, cancel.clone())),
        ..Log::default()
    };
    let stopped = run(scene(40), batch(&out, policy()), &log, &cancel);
    assert_eq!(stopped.outcome, Outcome::Cancelled);
    let (least, most, _) = stopped.film.sample_counts();
    assert_eq!(
        (least, most),
        (16, 32),
        "the pass in flight stops where it is"
    );
    assert_eq!(log.events().last().map(String::as_str), Some("rendered"));
    assert!(log.events().iter().any(|e| e.contains("to 16 spp")));
    assert!(!log.events().iter().any(|e| e.contains("to 32 spp")));
    let state = dir.path().join("a.exr.state.exr");
    assert_eq!(stopped.state.as_deref(), Some(state.as_path()));
    assert!(stopped.image_written && out.is_file());
    // The state is not replaced without a word.
    let refused = session(scene(40), batch(&out, policy())).err().unwrap();
    assert!(refused.to_string().contains("--resume"), "{refused}");
    let resume = StatePolicy {
        resume: true,
        ..policy()
    };
    let resumed = session(scene(40), batch(&out, resume)).unwrap();
    assert!(
        resumed
            .note()
            .unwrap()
            .starts_with("resuming a render of 40 spp"),
        "{:?}",
        resumed.note()
    );
    assert_eq!(resumed.samples_done(), stopped.samples);
    let resumed = one_thread().install(|| resumed.run(&Quiet, &Cancel::new()).unwrap());
    assert_eq!(resumed.outcome, Outcome::Complete);
    assert_eq!(resumed.samples + stopped.samples, 48 * 40 * 40);
    assert!(same_film(&resumed.film, &reference.film));
}

#[test]
fn checkpoints_save_the_state_and_change_no_sample() {
    let dir = tempfile::tempdir().unwrap();
    let reference = run(
        scene(4),
        batch(&dir.path().join("b.exr"), policy()),
        &Quiet,
        &Cancel::new(),
    );
    let out = dir.path().join("a.exr");
    // Every tile a checkpoint: the render pauses, saves, and goes on.
    let policy = StatePolicy {
        checkpoint: Some(Duration::ZERO),
        ..policy()
    };
    let log = Log::default();
    let report = run(scene(4), batch(&out, policy), &log, &Cancel::new());
    assert_eq!(report.outcome, Outcome::Complete);
    assert!(log.events().iter().filter(|e| *e == "checkpoint").count() > 3);
    let passes: Vec<String> = (log.events().into_iter())
        .filter(|e| e.starts_with("pass"))
        .collect();
    assert_eq!(passes, ["pass 1 to 1 spp None", "pass 2 to 4 spp None"]);
    assert!(same_film(&report.film, &reference.film));
    // A checkpoint made a state: the finished render keeps it current.
    let state = dir.path().join("a.exr.state.exr");
    assert_eq!(report.state.as_deref(), Some(state.as_path()));
    let (saved, _) = ptsc::render::state::read_state(&state).unwrap();
    assert!(same_film(&saved, &reference.film));
}

#[test]
fn an_image_is_never_written_over_a_state_without_force() {
    let dir = tempfile::tempdir().unwrap();
    let part = dir.path().join("p.exr");
    let pass = StatePolicy {
        pass: Some(Pass { k: 1, n: 2 }),
        ..policy()
    };
    run(scene(2), batch(&part, pass), &Quiet, &Cancel::new());
    match session(scene(2), batch(&part, policy())) {
        Err(Error::Refused(why)) => assert!(why.contains("--force"), "{why}"),
        other => panic!("{:?}", other.err()),
    }
    let live = Plan {
        mode: Mode::Live,
        ..batch(&part, policy())
    };
    assert!(matches!(session(scene(2), live), Err(Error::Refused(_))));
    let force = StatePolicy {
        force: true,
        ..policy()
    };
    assert!(session(scene(2), batch(&part, force)).is_ok());
    // An image that would replace a file of the scene is refused first.
    let plan = Plan {
        inputs: vec![part.clone()],
        ..batch(&part, policy())
    };
    assert!(matches!(session(scene(2), plan), Err(Error::Output { .. })));
}

#[test]
fn a_live_session_writes_its_preview_then_every_pass() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("a.png");
    let plan = Plan {
        mode: Mode::Live,
        ..batch(&out, policy())
    };
    let log = Log::default();
    let report = run(scene(4), plan, &log, &Cancel::new());
    assert_eq!(
        log.events(),
        [
            "preview (12, 10) true",
            "pass 1 to 1 spp Some(true)",
            "pass 2 to 2 spp Some(true)",
            "pass 3 to 4 spp Some(true)",
            "rendered"
        ]
    );
    assert!(report.image_written && report.state.is_none());
    let preview: PathBuf = dir.path().join("a.preview.png");
    assert!(out.is_file() && preview.is_file());
    // Cancelled before it starts: nothing is written, no state is left.
    let later = dir.path().join("b.png");
    let plan = Plan {
        mode: Mode::Live,
        ..batch(&later, policy())
    };
    let cancel = Cancel::new();
    cancel.cancel();
    let report = run(scene(4), plan, &Quiet, &cancel);
    assert_eq!(report.outcome, Outcome::Cancelled);
    assert!(!report.image_written);
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 2);
}

/// The path integrator, its first sample slowed down when `slow` is set:
/// a render whose first pass takes seconds.
struct SlowStart {
    slow: std::sync::atomic::AtomicBool,
    path: Box<dyn ptsc::integrator::Integrator>,
}

impl ptsc::integrator::Integrator for SlowStart {
    fn li(
        &self,
        scene: &Scene,
        ray: ptsc::geometry::Ray,
        sampler: &mut ptsc::sampling::sampler::Sampler,
    ) -> glam::Vec3 {
        if self.slow.swap(false, Ordering::Relaxed) {
            std::thread::sleep(Duration::from_millis(2200));
        }
        self.path.li(scene, ray, sampler)
    }
}

#[test]
fn a_slow_render_doubles_its_passes_from_the_first_sample() {
    let mut ir = scene(8);
    (ir.settings.width, ir.settings.height) = (2, 2);
    let ends = |slow: bool| {
        let integrator = SlowStart {
            slow: std::sync::atomic::AtomicBool::new(slow),
            path: ptsc::integrator::make(ir.settings.integrator, &ir),
        };
        let mut ends = Vec::new();
        let film = Film::for_settings(&ir.settings, 0);
        let to = (8, ptsc::render::Progression::Runs);
        let cancel = std::sync::atomic::AtomicBool::new(false);
        let r = ptsc::render::render_from(
            &ir,
            &integrator,
            film,
            to,
            &cancel,
            &|_| {},
            &mut |_, spp| ends.push(spp),
        );
        (ends, r.film)
    };
    let (fast, fast_film) = ends(false);
    assert_eq!(fast, [1, 8]);
    // The first pass took more than 2 s: the runs' 15 more samples per
    // pixel would keep the next image waiting half a minute; the passes
    // double instead, and the samples are the same.
    let (slow, slow_film) = ends(true);
    assert_eq!(slow, [1, 2, 4, 8]);
    assert!(same_film(&fast_film, &slow_film));
}
