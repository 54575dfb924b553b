//! `ptsc watch FILE`: re-render on every save, progressively, keeping the last
//! good image while the scene is broken.
//!
//! The loop: compile (check + lower, reusing unchanged meshes and geometry
//! through [`LowerCache`]); on errors print the diagnostics and leave the image
//! alone; on success cancel the render in flight (it stops between tiles) and
//! start a new one in the background: a quarter-resolution 1-spp preview, then
//! full-resolution passes of 1, 2, 4, … spp, the image replaced atomically after
//! each. The preview goes to its own file beside the image, at its own
//! resolution (`render::session::preview_path`: `NAME.preview.png` for `NAME.png`), so the image only
//! ever holds full-resolution results: a viewer showing it never drops to
//! the thumbnail, and one showing the preview file sees each save at once. File events come from `notify` on the folders of the scene, its
//! includes and its meshes, batched (100 ms of quiet, at most 500 ms), so an
//! editor's atomic save (write a temporary file, rename it over) counts as one
//! change and the output file's own writes are ignored.

use super::render::{compile, output_path, RenderArgs};
use crate::lower::cache::LowerCache;
use crate::render::session::{
    Cancel, Error, Mode, Observer, PassDone, Plan, PreviewDone, Report, Session,
};
use notify::{RecursiveMode, Watcher};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::sync::{mpsc, Arc};
use std::thread::JoinHandle;
use std::time::{Duration, Instant, SystemTime};

/// Quiet time that ends a batch of file events.
const QUIET: Duration = Duration::from_millis(100);
/// Longest a batch may wait after its first event.
const MAX_BATCH: Duration = Duration::from_millis(500);

/// Runs `watch`; returns the exit code (after Ctrl-C).
pub fn run(args: &RenderArgs) -> u8 {
    if super::render::reads_stdin(args) {
        eprintln!("error: watch needs a scene file to watch; stdin (`-`) is read once (`ptsc render -` renders it)");
        return super::EXIT_USAGE;
    }
    // A regular file only (a FIFO would wait for a writer at every compile).
    if let Err(e) = crate::source::open_regular(&args.file) {
        eprintln!("error: cannot watch {}: {e}", args.file.display());
        return super::EXIT_USAGE;
    }
    // Flags of a batch render's end that a live render does not honour
    // (yet): said, not silently ignored.
    // Each with why a live render has no use for it.
    let batch_only = [
        (
            "--denoise",
            args.denoise,
            "its passes are written as they come, not denoised",
        ),
        (
            "--aov",
            args.aov.is_some(),
            "it writes the image and its preview only, no other layers",
        ),
        (
            "--time",
            args.time.is_some(),
            "it renders passes until the samples asked, not for a time",
        ),
        (
            "--tev",
            args.tev.is_some(),
            "it writes its passes to the image file, which a viewer can watch",
        ),
    ];
    if let Some((flag, _, why)) = batch_only.iter().find(|(_, given, _)| *given) {
        eprintln!("error: {flag} is for `ptsc render`: `ptsc watch` does not take it ({why})");
        return super::EXIT_USAGE;
    }
    // One frame: --frame's, else the first of --frames.
    let animation = match args.animations() {
        Ok(a) => a[0],
        Err(why) => {
            eprintln!("error: {why}");
            return super::EXIT_USAGE;
        }
    };
    // --frames alone named more than the one frame rendered: said, not
    // silently narrowed.
    if let (Some((a, b)), None) = (args.frames, args.frame) {
        if a < b && !args.quiet {
            eprintln!("warning: watch renders one frame: frame {a} of --frames {a}..{b} (add --frame F for another; `ptsc render` renders them all)");
        }
    }
    // An image named on the command line is checked once, as `render`
    // does: a folder that does not exist is refused before watching.
    if args.output.is_some() {
        let output = output_path(args, None, animation.frame);
        if let Err(why) = crate::output::check_output(&output, &[]) {
            eprintln!("error: cannot write {}: {why}", output.display());
            return super::EXIT_USAGE;
        }
    }
    let pool = match rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads.unwrap_or(0))
        .build()
    {
        Ok(p) => Arc::new(p),
        Err(e) => {
            eprintln!("error: cannot start threads: {e}");
            return super::EXIT_USAGE;
        }
    };
    // Ctrl-C (or SIGTERM) ends a watch: its normal end, exit code 0.
    let signals = super::signals::Signals::install();
    let (tx, rx) = mpsc::channel();
    let mut watcher = match notify::recommended_watcher(move |e: notify::Result<notify::Event>| {
        // Only changes count: our own reads of the scene are access events.
        if let Ok(e) = e {
            if matches!(
                e.kind,
                notify::EventKind::Create(_)
                    | notify::EventKind::Modify(_)
                    | notify::EventKind::Remove(_)
            ) {
                let _ = tx.send(e.paths);
            }
        }
    }) {
        Ok(w) => w,
        Err(e) => {
            eprintln!("error: cannot watch files: {e}");
            return super::EXIT_USAGE;
        }
    };

    let mut state = State {
        args: args.clone(),
        animation,
        cache: LowerCache::default(),
        files: BTreeSet::new(),
        watched_dirs: BTreeSet::new(),
        render: None,
        renders: 0,
        pool,
    };
    state.files.insert(absolute(&args.file));
    status(&format!(
        "watching {} (Ctrl-C to stop)",
        args.file.display()
    ));
    // The first compile follows the start, the others a save.
    let mut changed_at = (Instant::now(), "starting");
    loop {
        state.compile(changed_at);
        state.update_watches(&mut watcher);
        // Wait for the next relevant change (or Ctrl-C).
        let first = loop {
            if signals.stopped() {
                state.stop_render();
                status("stopped");
                return super::EXIT_OK;
            }
            match rx.recv_timeout(Duration::from_millis(50)) {
                Ok(paths) if state.is_relevant(&paths) => break Instant::now(),
                Ok(_) | Err(mpsc::RecvTimeoutError::Timeout) => {}
                Err(mpsc::RecvTimeoutError::Disconnected) => return super::EXIT_USAGE,
            }
        };
        // Batch: until QUIET passes without a relevant event, or MAX_BATCH.
        let mut last = first;
        while first.elapsed() < MAX_BATCH {
            let wait = QUIET.saturating_sub(last.elapsed());
            if wait.is_zero() {
                break;
            }
            match rx.recv_timeout(wait) {
                Ok(paths) if state.is_relevant(&paths) => last = Instant::now(),
                Ok(_) => {}
                Err(_) => {}
            }
        }
        changed_at = (first, "the save");
    }
}

struct State {
    args: RenderArgs,
    /// The frame watched.
    animation: crate::check::Animation,
    cache: LowerCache,
    /// Absolute paths of the scene, its includes and its meshes.
    files: BTreeSet<PathBuf>,
    watched_dirs: BTreeSet<PathBuf>,
    render: Option<(Cancel, JoinHandle<()>)>,
    /// Renders started so far: each one's status lines carry its number.
    renders: u32,
    pool: Arc<rayon::ThreadPool>,
}

impl State {
    /// Checks, lowers and (on success) starts rendering the scene.
    /// `changed_at` is when the change happened and what it was.
    fn compile(&mut self, changed_at: (Instant, &'static str)) {
        let t0 = Instant::now();
        // Not on `self.pool`: the previous render keeps its threads busy
        // until this compile succeeds, and a job queued behind its tiles
        // would wait for them. Large files parse on rayon's global pool.
        let (loads, builds) = (self.cache.mesh_loads, self.cache.bvh_builds);
        let compiled = match compile(
            &self.args,
            None,
            Some(&mut self.cache),
            self.animation,
            false,
        ) {
            Ok(c) => c,
            Err(e) => {
                status(&format!(
                    "cannot read {}: {e}; keeping the last image",
                    self.args.file.display()
                ));
                return;
            }
        };
        // Exactly what the scene read or names (the scene itself always).
        self.files = std::iter::once(&self.args.file)
            .chain(&compiled.dependencies)
            .map(|f| absolute(f))
            .collect();
        if !compiled.diagnostics.items.is_empty() {
            eprint!(
                "{}",
                compiled
                    .diagnostics
                    .render_human(&compiled.sources, super::stderr_is_terminal())
            );
        }
        let Some(ir) = compiled.ir else {
            status(&self.keeping());
            return;
        };
        for warning in super::args::flag_warnings(&self.args, &ir) {
            eprintln!("{warning}");
        }
        let output = output_path(&self.args, compiled.output.as_deref(), self.animation.frame);
        let plan = Plan {
            output,
            inputs: compiled.dependencies,
            memory_limit: self.args.memory_limit,
            aovs: Vec::new(),
            denoise: false,
            tev: None,
            mode: Mode::Live,
        };
        let checked = match plan.check() {
            Ok(checked) => checked,
            Err(Error::Output { path, why }) => {
                status(&format!(
                    "cannot write {}: {why}; keeping the last image",
                    path.display()
                ));
                return;
            }
            Err(why) => {
                status(&format!("{why}; keeping the last image"));
                return;
            }
        };
        // A preview that cannot be written is left out: the passes still are.
        if let Some((preview, why)) = &checked.no_preview {
            status(&format!(
                "no preview: cannot write {}: {why}",
                preview.display()
            ));
        }
        // The image watch replaces must not be a render's state, and the
        // film must fit (the last render's is released first).
        self.stop_render();
        let session = match Session::new(ir, checked) {
            Ok(session) => session,
            Err(why) => {
                status(&format!("{why}; keeping the last image"));
                return;
            }
        };
        status(&format!(
            "compiled in {} ms: {} mesh file(s) loaded, geometry {}",
            t0.elapsed().as_millis(),
            self.cache.mesh_loads - loads,
            if self.cache.bvh_builds > builds {
                "rebuilt"
            } else {
                "reused"
            }
        ));
        self.stop_render();
        let cancel = Cancel::new();
        let c = cancel.clone();
        let pool = self.pool.clone();
        self.renders += 1;
        let number = self.renders;
        let handle = std::thread::spawn(move || {
            let lines = Lines {
                number,
                changed_at,
                output: session.output().to_path_buf(),
            };
            let samples = session.scene().settings.samples;
            if let Ok(report) = pool.install(|| session.run(&lines, &c)) {
                lines.finished(&report, samples);
            }
        });
        self.render = Some((cancel, handle));
    }

    /// What a broken save says: the image stays, and which render (of the
    /// last good scene) is still running, if one is.
    fn keeping(&self) -> String {
        match &self.render {
            Some((_, handle)) if !handle.is_finished() => format!(
                "the scene has errors; keeping the last image (render {} of the last good version goes on)",
                self.renders
            ),
            _ => "the scene has errors; keeping the last image".to_string(),
        }
    }

    /// Cancels the render in flight and waits for it (it stops within a
    /// few samples).
    fn stop_render(&mut self) {
        if let Some((cancel, handle)) = self.render.take() {
            cancel.cancel();
            let _ = handle.join();
        }
    }

    /// Watches the folder of every file of the scene (folders, not files:
    /// an atomic save replaces the file, which would end a watch on it).
    fn update_watches(&mut self, watcher: &mut impl Watcher) {
        let dirs: BTreeSet<PathBuf> = self
            .files
            .iter()
            .filter_map(|f| f.parent().map(Path::to_path_buf))
            .collect();
        for d in dirs.difference(&self.watched_dirs.clone()) {
            match watcher.watch(d, RecursiveMode::NonRecursive) {
                Ok(()) => {
                    self.watched_dirs.insert(d.clone());
                }
                Err(e) => status(&format!("cannot watch {}: {e}", d.display())),
            }
        }
    }

    /// Whether an event touches a file of the scene.
    fn is_relevant(&self, paths: &[PathBuf]) -> bool {
        paths.iter().any(|p| self.files.contains(&absolute(p)))
    }
}

/// The status lines of one render, from its session's events; each starts
/// with `render N:`.
struct Lines {
    /// The render's number.
    number: u32,
    /// When the change it renders happened, and what it was.
    changed_at: (Instant, &'static str),
    /// The image it writes.
    output: PathBuf,
}

impl Lines {
    /// A status line of this render.
    fn status(&self, msg: &str) {
        status(&format!("render {}: {msg}", self.number));
    }

    /// The last line of a render that finished (one that was stopped says
    /// nothing: a newer render follows).
    fn finished(&self, report: &Report, samples: u32) {
        let output = &self.output;
        if report.outcome != crate::render::Outcome::Complete {
            return;
        }
        let total = report.render_time.as_secs_f64();
        if report.image_written {
            self.status(&format!(
                "done: {samples} spp in {total:.2} s → {}",
                output.display()
            ));
        } else {
            self.status(&format!(
                "finished {samples} spp in {total:.2} s, but {} could not be written (see above); save the scene to try again",
                output.display()
            ));
        }
    }
}

impl Observer for Lines {
    fn preview(&self, preview: &PreviewDone) {
        let (changed_at, change) = self.changed_at;
        match preview.written {
            Ok(()) => self.status(&format!(
                "preview {}×{} at 1 spp{} in {} ms ({} ms after {change}) → {}",
                preview.size.0,
                preview.size.1,
                if preview.denoised { ", denoised" } else { "" },
                preview.elapsed.as_millis(),
                changed_at.elapsed().as_millis(),
                preview.path.display()
            )),
            Err(e) => self.status(&format!("cannot write {}: {e}", preview.path.display())),
        }
    }

    fn pass(&self, pass: &PassDone) {
        match pass.image {
            Some(Ok(())) => self.status(&format!(
                "pass {}: {} spp in {:.2} s (total {:.2} s){}",
                pass.number,
                pass.spp,
                pass.elapsed.as_secs_f64(),
                pass.total.as_secs_f64(),
                (pass.converged)
                    .map(|share| format!(", {:.0} % of pixels converged", share * 100.0))
                    .unwrap_or_default()
            )),
            Some(Err(e)) => self.status(&format!("cannot write {}: {e}", self.output.display())),
            None => {}
        }
    }
}

/// The path made absolute and its folder canonical (the file itself may not
/// exist between an editor's remove and create).
fn absolute(p: &Path) -> PathBuf {
    let p = std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf());
    match (p.parent(), p.file_name()) {
        (Some(d), Some(n)) => d.canonicalize().map_or(p.clone(), |d| d.join(n)),
        _ => p,
    }
}

/// A status line with the time of day (UTC).
fn status(msg: &str) {
    let secs = SystemTime::now()
        .duration_since(SystemTime::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    let (h, m, s) = ((secs / 3600) % 24, (secs / 60) % 60, secs % 60);
    eprintln!("[{h:02}:{m:02}:{s:02}] {msg}");
}
