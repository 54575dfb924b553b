//! `ptsc watch FILE`: re-render on every save, progressively, keeping the last
//! good image while the scene is broken.
//!
//! The loop: compile (check + lower, reusing unchanged meshes and geometry
//! through [`LowerCache`]); on errors print the diagnostics and leave the image
//! alone; on success cancel the render in flight (it stops between tiles) and
//! start a new one in the background: a quarter-resolution 1-spp preview, then
//! full-resolution passes of 1, 2, 4, … spp, the image replaced atomically after
//! each. The preview goes to its own file beside the image, at its own
//! resolution ([`preview_path`]: `NAME.preview.png` for `NAME.png`), so the image only
//! ever holds full-resolution results: a viewer showing it never drops to
//! the thumbnail, and one showing the preview file sees each save at once. File events come from `notify` on the folders of the scene, its
//! includes and its meshes, batched (100 ms of quiet, at most 500 ms), so an
//! editor's atomic save (write a temporary file, rename it over) counts as one
//! change and the output file's own writes are ignored.

use super::render::{compile, output_path, RenderArgs};
use crate::ir::Scene;
use crate::lower::cache::LowerCache;
use crate::render::memory::Need;
use notify::{RecursiveMode, Watcher};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{mpsc, Arc};
use std::thread::JoinHandle;
use std::time::{Duration, Instant, SystemTime};

/// Quiet time that ends a batch of file events.
const QUIET: Duration = Duration::from_millis(100);
/// Longest a batch may wait after its first event.
const MAX_BATCH: Duration = Duration::from_millis(500);
/// The preview renders at 1 / PREVIEW_DIVISOR of the resolution on each side.
const PREVIEW_DIVISOR: u32 = 4;

/// Runs `watch`; returns the exit code (after Ctrl-C).
pub fn run(args: &RenderArgs) -> u8 {
    // A regular file only (a FIFO would wait for a writer at every compile).
    if let Err(e) = crate::source::open_regular(&args.file) {
        eprintln!("error: cannot watch {}: {e}", args.file.display());
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
    render: Option<(Arc<AtomicBool>, JoinHandle<()>)>,
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
        let compiled = match compile(&self.args, Some(&mut self.cache), self.animation, false) {
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
        let output = output_path(&self.args, compiled.output.as_deref(), self.animation.frame);
        if let Err(why) = crate::output::check_output(&output, &compiled.dependencies) {
            status(&format!(
                "cannot write {}: {why}; keeping the last image",
                output.display()
            ));
            return;
        }
        // A preview that cannot be written is left out: the passes still are.
        let preview = preview_path(&output);
        let preview = match crate::output::check_output(&preview, &compiled.dependencies)
            .and_then(|()| crate::cli::farm::refuse_to_replace_state(&preview, false))
        {
            Ok(()) => Some(preview),
            Err(why) => {
                status(&format!(
                    "no preview: cannot write {}: {why}",
                    preview.display()
                ));
                None
            }
        };
        // The image watch replaces must not be a render's state, and the
        // film must fit (the last render's is released first).
        self.stop_render();
        let need = Need::film((ir.settings.width, ir.settings.height));
        let fits = crate::cli::farm::refuse_to_replace_state(&output, false)
            .and_then(|()| crate::render::memory::check(&need, self.args.memory_limit));
        if let Err(why) = fits {
            status(&format!("{why}; keeping the last image"));
            return;
        }
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
        let cancel = Arc::new(AtomicBool::new(false));
        let c = cancel.clone();
        let pool = self.pool.clone();
        self.renders += 1;
        let number = self.renders;
        let handle = std::thread::spawn(move || {
            let files = (output.as_path(), preview.as_deref());
            pool.install(|| render_progressively(&ir, files, &c, changed_at, number));
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

    /// Cancels the render in flight and waits for it (it stops between tiles).
    fn stop_render(&mut self) {
        if let Some((cancel, handle)) = self.render.take() {
            cancel.store(true, Ordering::Relaxed);
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

/// Where `watch` writes the quick preview of the image `output`: beside it,
/// `.preview` before the extension (`shot.png` → `shot.preview.png`).
pub fn preview_path(output: &Path) -> PathBuf {
    let stem = output.file_stem().unwrap_or_default().to_string_lossy();
    let name = match output.extension() {
        Some(ext) => format!("{stem}.preview.{}", ext.to_string_lossy()),
        None => format!("{stem}.preview"),
    };
    output.with_file_name(name)
}

/// A quick low-resolution preview (to `preview`, when there is one), then
/// the progressive passes (to `output`); its status lines start with
/// `render N:`.
fn render_progressively(
    ir: &Scene,
    (output, preview): (&Path, Option<&Path>),
    cancel: &AtomicBool,
    (changed_at, change): (Instant, &str),
    number: u32,
) {
    let status = |msg: &str| status(&format!("render {number}: {msg}"));
    let integrator = crate::integrator::make(ir.settings.integrator);
    let exposure = ir.settings.exposure;
    let (w, h) = (ir.settings.width, ir.settings.height);
    let t0 = Instant::now();
    let wants_preview = w >= 4 * PREVIEW_DIVISOR && h >= 4 * PREVIEW_DIVISOR;
    if let Some(preview) = preview.filter(|_| wants_preview && ir.settings.samples > 1) {
        let Some(film) =
            crate::render::render_preview(ir, integrator.as_ref(), cancel, PREVIEW_DIVISOR)
        else {
            return;
        };
        // At its own size: encoding it enlarged to the image's took as long
        // as rendering it (cornell: 171 M instructions of 348 M, mostly
        // sRGB conversion and deflate), and its own file needs no match.
        match film.write(preview, exposure) {
            Ok(()) => status(&format!(
                "preview {}×{} at 1 spp in {} ms ({} ms after {change}) → {}",
                film.width,
                film.height,
                t0.elapsed().as_millis(),
                changed_at.elapsed().as_millis(),
                preview.display()
            )),
            Err(e) => status(&format!("cannot write {}: {e}", preview.display())),
        }
    }
    let mut pass = 0;
    let mut last = Instant::now();
    // Whether the last pass's image reached the disk.
    let mut written = false;
    let outcome = crate::render::render(
        ir,
        integrator.as_ref(),
        cancel,
        &|_| {},
        &mut |film, spp| {
            pass += 1;
            written = match film.write(output, exposure) {
                Ok(()) => {
                    status(&format!(
                        "pass {pass}: {spp} spp in {:.2} s (total {:.2} s)",
                        last.elapsed().as_secs_f64(),
                        t0.elapsed().as_secs_f64()
                    ));
                    true
                }
                Err(e) => {
                    status(&format!("cannot write {}: {e}", output.display()));
                    false
                }
            };
            last = Instant::now();
        },
    )
    .outcome;
    if outcome == crate::render::Outcome::Complete {
        if written {
            status(&format!(
                "done: {} spp in {:.2} s → {}",
                ir.settings.samples,
                t0.elapsed().as_secs_f64(),
                output.display()
            ));
        } else {
            status(&format!(
                "finished {} spp in {:.2} s, but {} could not be written (see above); save the scene to try again",
                ir.settings.samples,
                t0.elapsed().as_secs_f64(),
                output.display()
            ));
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_preview_goes_beside_the_image_in_its_format() {
        let p = |s: &str| preview_path(Path::new(s));
        assert_eq!(p("out/shot.png"), Path::new("out/shot.preview.png"));
        assert_eq!(p("frame_0012.exr"), Path::new("frame_0012.preview.exr"));
        assert_eq!(p("a.b.pfm"), Path::new("a.b.preview.pfm"));
    }
}
