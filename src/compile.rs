//! The compile driver: read → check → lower, and the files the scene
//! depends on. The one sequence every front door uses: `render`, `watch`,
//! `check`, the tests, the benches, the fuzzers (and later the language
//! server and the render farm).
//!
//! ```text
//! path ──read──▶ bytes ──check──▶ check::Scene ──lower──▶ ir::Scene
//!                  │ (syntax + check diagnostics)  │ (lowering diagnostics)
//!                  ▼                               ▼
//!        Compiled { sources, diagnostics (one list), symbols, ir, dependencies, output }
//! ```

use crate::check::{self, Animation, Budgets, MAX_LOOP_STATEMENTS};
use crate::diag::{codes, Diagnostic, Diagnostics};
use crate::ir::settings::Settings;
use crate::lower::cache::LowerCache;
use crate::source::{Asked, Disk, FileId, Files, SourceMap};
use crate::span::Span;
use std::path::{Path, PathBuf};
use std::sync::atomic::Ordering;
use std::time::Instant;

/// How far to compile, and what to change on the way.
pub struct Options<'a> {
    /// Whether to lower the checked scene into the IR (`false`: check
    /// only, as `ptsc check` and an editor do; everything lowering would
    /// refuse is still found, images and meshes read, nothing built).
    pub lower: bool,
    /// Edits the settings before lowering uses them (the command line's
    /// `--spp`, `--resolution`, `--seed`, `--integrator`).
    pub adjust: &'a dyn Fn(&mut Settings),
    /// Meshes and geometry kept between compiles (`watch`); `None` keeps
    /// nothing.
    pub cache: Option<&'a mut LowerCache>,
    /// The statements loops may run in all (a fuzzer keeps its inputs fast
    /// with a small budget; the rules are the same).
    pub loop_statements: u64,
    /// The steps of work expressions may take in all
    /// ([`check::eval::MAX_WORK`]; a fuzzer's is smaller).
    pub work: u64,
    /// The frame of an animation to compile (`frame` and `clock` in the
    /// scene).
    pub animation: Animation,
    /// Whether to compute the scene's fingerprint (render states need it).
    pub fingerprint: bool,
    /// Whether the image goes elsewhere than the scene's `render { output
    /// … }` (the command line's `-o`): then that is not checked.
    pub output_elsewhere: bool,
    /// Where the scene, its includes, meshes and images are read: the
    /// disk, or files in memory (tests, an editor's unsaved buffers).
    pub files: &'a dyn Files,
    /// Set by another thread when the result is no longer wanted (an
    /// editor's newer text): checking stops early, the result is
    /// incomplete and is to be dropped.
    pub cancel: Option<std::sync::Arc<std::sync::atomic::AtomicBool>>,
    /// The memory the process may hold in all (`--memory-limit`); `None`:
    /// what the machine leaves free. A scene whose objects would need more
    /// to load is refused before lowering starts ([`load_memory`]).
    pub memory_limit: Option<u64>,
}

impl Default for Options<'_> {
    /// Check and lower, nothing adjusted, nothing cached.
    fn default() -> Self {
        Options {
            lower: true,
            adjust: &|_| {},
            cache: None,
            loop_statements: MAX_LOOP_STATEMENTS,
            work: check::eval::MAX_WORK,
            animation: Animation::default(),
            fingerprint: false,
            output_elsewhere: false,
            files: &Disk,
            cancel: None,
            memory_limit: None,
        }
    }
}

/// What a compile gives.
#[derive(Debug)]
pub struct Compiled {
    /// Every scene file read (the scene and its includes), for diagnostics.
    pub sources: SourceMap,
    /// Every diagnostic, syntax, check and lowering in one list.
    pub diagnostics: Diagnostics,
    /// Every name the scene defines and where each is used, across its
    /// files: what editors read (hover, go to definition, references,
    /// rename, outline). A scene with errors has them as far as it was
    /// checked.
    pub symbols: check::Symbols,
    /// The scene ready to render, when there were no errors and lowering
    /// was asked for.
    pub ir: Option<crate::ir::Scene>,
    /// Every file the compile asked of its [`Files`], in the order first
    /// asked, found or not: the scene, its includes, its meshes and images
    /// (those of a scene with errors only as far as it was read). `watch`
    /// watches exactly these.
    pub dependencies: Vec<PathBuf>,
    /// The image the scene's `render { output … }` names, if it does.
    pub output: Option<PathBuf>,
    /// The scene's fingerprint ([`crate::lower::fingerprint`]), when asked
    /// for and the scene checked.
    pub fingerprint: Option<u64>,
    /// Seconds spent reading and checking.
    pub check_seconds: f64,
    /// Seconds spent lowering (mesh reading, BVH build).
    pub lower_seconds: f64,
}

impl Compiled {
    /// Whether the scene has errors (no image can be made).
    pub fn has_errors(&self) -> bool {
        self.diagnostics.has_errors()
    }
}

/// Compiles the scene at `path` and everything it includes. An unreadable
/// root file is an I/O error (a usage problem), not a diagnostic.
pub fn compile_file(path: &Path, options: Options) -> std::io::Result<Compiled> {
    let start = Instant::now();
    let bytes = check::read_scene_file(options.files, path)?;
    Ok(compile_from(path, bytes, options, start))
}

/// Compiles a scene given as bytes, as if read from `path` (includes and
/// meshes are found relative to it).
pub fn compile_bytes(path: &Path, bytes: Vec<u8>, options: Options) -> Compiled {
    compile_from(path, bytes, options, Instant::now())
}

/// Compiles a scene given as text (tests, benches).
pub fn compile_str(path: &Path, text: &str, options: Options) -> Compiled {
    compile_bytes(path, text.as_bytes().to_vec(), options)
}

fn compile_from(path: &Path, bytes: Vec<u8>, options: Options, start: Instant) -> Compiled {
    let budgets = Budgets {
        loop_statements: options.loop_statements,
        work: options.work,
        cancel: options.cancel.clone(),
    };
    // The root was read already (or given): it is asked first all the same.
    let asked = Asked::new(options.files);
    asked.note(path);
    let files: &dyn Files = &asked;
    let checked = check::check_bytes_within(path, bytes, budgets, options.animation, files);
    let check_seconds = start.elapsed().as_secs_f64();
    let mut compiled = Compiled {
        sources: checked.sources,
        diagnostics: checked.diagnostics,
        symbols: checked.symbols,
        ir: None,
        dependencies: Vec::new(),
        output: None,
        fingerprint: None,
        check_seconds,
        lower_seconds: 0.0,
    };
    if let Some(scene) = checked.scene {
        compiled.output = scene.render.output.clone();
        let mut one_off = LowerCache::one_off();
        let cache = options.cache.unwrap_or(&mut one_off);
        let mut warnings = crate::diag::Diagnostics::new();
        if let Some(refused) = load_memory(&scene, options.memory_limit) {
            compiled.diagnostics.push(refused);
        } else if options.lower {
            match crate::lower::lower(&scene, options.adjust, (cache, files), &mut warnings) {
                Ok(ir) => compiled.ir = Some(ir),
                Err(d) => compiled.diagnostics.extend(d),
            }
        } else {
            compiled.diagnostics.extend(crate::lower::validate(
                &scene,
                (cache, files),
                &mut warnings,
            ));
        }
        compiled.diagnostics.extend(warnings);
        if options.fingerprint {
            // After lowering: the files its meshes name (an OBJ's
            // libraries, a glTF's buffers) were asked of `files` then.
            compiled.fingerprint = Some(crate::lower::fingerprint(
                files,
                (&compiled.sources, &asked.paths()),
                &scene,
                options.animation,
            ));
        }
        if !options.output_elsewhere {
            let inputs = asked.paths();
            let output = match scene.render.output {
                Some(_) => check_scene_output(&scene.render, options.animation.frame, &inputs),
                None => check_default_output(path, &scene, &inputs),
            };
            if let Some(d) = output {
                compiled.diagnostics.push(d);
                // No image without the place to write it.
                compiled.ir = None;
            }
        }
        // Lowering reads images before meshes: its errors join the
        // checker's in source order.
        compiled.diagnostics.sort();
        // A group placed several times, or a mesh named in a loop, meets
        // the same problem more than once: it is one mistake.
        compiled.diagnostics.dedup();
        compiled.lower_seconds = start.elapsed().as_secs_f64() - check_seconds;
    } else if let Some(unbuilt) = &checked.unbuilt {
        // A check cancelled (an editor's, overtaken by an edit) reads no
        // files: its result is thrown away.
        let cancelled = (options.cancel.as_ref()).is_some_and(|c| c.load(Ordering::Relaxed));
        if !cancelled {
            files_of_unbuilt(&mut compiled, unbuilt, (options.cache, files));
        }
    }
    compiled.dependencies = asked.paths();
    compiled
}

/// Adds the errors of the image and mesh files that a scene with errors
/// names ([`crate::lower::validate_files`]; the check reads none of them)
/// and keeps the diagnostics in source order, each once.
fn files_of_unbuilt(
    compiled: &mut Compiled,
    unbuilt: &check::unbuilt::Unbuilt,
    (cache, files): (Option<&mut LowerCache>, &dyn Files),
) {
    let mut one_off = LowerCache::one_off();
    let cache = cache.unwrap_or(&mut one_off);
    let found = crate::lower::validate_files(unbuilt, (cache, files));
    if !found.items.is_empty() {
        compiled.diagnostics.extend(found);
        compiled.diagnostics.sort();
        compiled.diagnostics.dedup();
    }
}

/// Memory a placed object takes while a scene loads, beyond what its check
/// holds: its primitive record, its share of the BVH build and the wide
/// tree (a million spheres, placed directly or by groups of groups, peak at
/// about 470 and 650 MB in all).
const LOAD_BYTES_PER_OBJECT: u64 = 500;

/// Scenes whose objects need less than this to load are not measured
/// against the free memory (no system query for an ordinary scene).
const LOAD_BYTES_UNASKED: u64 = 64 << 20;

/// The error of a scene whose objects would need more memory to load than
/// is free (`limit`: `--memory-limit`), found before lowering allocates it
/// (where the allocation would otherwise fail and end the process).
fn load_memory(scene: &check::Scene, limit: Option<u64>) -> Option<Diagnostic> {
    let placed = (scene.instances.iter())
        .map(|i| scene.groups[i.group].placed_objects)
        .fold(scene.objects.len() as u64, u64::saturating_add);
    let need = placed.saturating_mul(LOAD_BYTES_PER_OBJECT);
    if need < LOAD_BYTES_UNASKED {
        return None;
    }
    let (free, which) = crate::render::memory::available(limit)?;
    if need <= free {
        return None;
    }
    use crate::render::memory::gigabytes;
    Some(
        Diagnostic::error(
            codes::SCENE_MEMORY,
            format!(
                "loading this scene needs about {} of memory, more than the {} free ({which})",
                gigabytes(need),
                gigabytes(free)
            ),
            Span::new(FileId(0), 0, 0),
        )
        .with_label(format!(
            "the scene places {} objects",
            crate::diag::group_digits(placed)
        ))
        .with_help("place fewer objects (a mesh holds many triangles in far less memory), or give --memory-limit if the memory is there"),
    )
}

/// The error of a scene without `output` whose image would go where it
/// reads a file: a render without `-o` writes FILE with `.png`, which
/// would replace `poster.png` read by `poster.pts` as a texture. Only that
/// clash, a property of the scene: a folder that takes no file is the
/// render's to find, where `-o` may name another.
fn check_default_output(
    root: &Path,
    scene: &check::Scene,
    inputs: &[PathBuf],
) -> Option<Diagnostic> {
    let image = root.with_extension("png");
    // Nothing there yet, nothing to replace: one `stat` for most scenes.
    // Else each input's real path once (not a pair per comparison).
    let target = std::fs::canonicalize(&image).ok()?;
    let real = |p: &Path| std::fs::canonicalize(p).ok();
    if real(root).as_ref() == Some(&target) {
        // (A scene itself named `.png` is the command line's to refuse.)
        return None;
    }
    let input = inputs.iter().find(|i| real(i).as_ref() == Some(&target))?;
    let images = check::image_files::named_images(&scene.materials, scene.environment.as_ref());
    let named = images
        .iter()
        .find(|(p, ..)| real(p).as_ref() == Some(&target));
    // Where the file is named; else (an OBJ's texture) the scene's start.
    let span = named.map_or(Span::new(FileId(0), 0, 0), |(_, _, span, _)| *span);
    Some(
        Diagnostic::error(
            codes::OUTPUT_FILE,
            format!("the image `{}` would replace a file this scene reads", image.display()),
            span,
        )
        .with_label(format!("{} is read here", input.display()))
        .with_help(format!(
            "a render without `-o` writes the scene's name with .png: give it another with `render {{ output \"{}\" }}` or `-o`",
            suggested_name(&image)
        )),
    )
}

/// Another name for the image `path` beside it: `poster_render.png`.
fn suggested_name(path: &Path) -> String {
    let stem = path
        .file_stem()
        .map_or("image".into(), |s| s.to_string_lossy());
    format!("{stem}_render.png")
}

/// The error of an output image the scene names that a render could not
/// write (`frame` numbering a `#` pattern; `inputs` the scene's files).
fn check_scene_output(
    render: &check::RenderSettings,
    frame: u32,
    inputs: &[PathBuf],
) -> Option<Diagnostic> {
    let (Some(output), Some(span)) = (&render.output, render.output_span) else {
        return None;
    };
    let path = crate::output::frame_path(output, frame);
    let why = crate::output::check_output(&path, inputs).err()?;
    Some(
        Diagnostic::error(
            codes::OUTPUT_FILE,
            format!("cannot write the image `{}`", path.display()),
            span,
        )
        .with_label(why)
        .with_help(
            "name a .png, .exr or .pfm file in a folder that exists (or give another with `-o`)",
        ),
    )
}
