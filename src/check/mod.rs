//! Semantic analysis: AST → checked [`Scene`] plus diagnostics. Runs every
//! pass to the end and reports all problems together; never stops at the
//! first error.

mod block_statement;
mod blocks;
mod defined_elsewhere;
pub mod domain;
pub mod eval;
mod finish;
mod foreign_file;
mod group_lights;
mod groups;
pub mod image_files;
mod include;
pub mod kinds;
mod loops;
mod material;
pub mod medium;
mod objects;
mod param_errors;
pub mod params;
mod povray;
pub mod principled;
mod reader;
pub mod scene;
pub mod schema;
mod statements;
mod swaps;
pub mod symbols;
pub mod texture;
pub mod texture_input;
mod typed_value;
pub mod unbuilt;
mod undeclared;
mod unrun;

pub use blocks::{MAX_NOISE, MAX_PIXELS, MAX_SIDE, MIN_SAMPLES, SAMPLES, SEED};
pub use foreign_file::{not_a_scene, not_a_scene_error};
pub use objects::non_uniform;
pub use reader::WholeSetting;
pub use scene::*;
pub use symbols::{DefId, Definition, ParamUse, SymbolKind, Symbols};

pub(crate) use crate::diag::group_digits;
use crate::diag::{codes, Diagnostic, Diagnostics};
use crate::source::{Disk, FileId, FileKind, Files, ReadError, SourceMap, MAX_SCENE_BYTES};
use crate::span::Span;
use crate::syntax::ast::{Entry, Ident, MaterialRef, Statement};
use eval::{eval, Binding, Env, Value};
use glam::DMat4;
use params::Params;
use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};

/// The material index of an object whose named material is not declared
/// yet (resolved by `finish`, which reports the names never declared).
const PENDING_MATERIAL: usize = usize::MAX;

/// Most statements loops may run in one compile, all loops together: every
/// statement of a loop body (a nested `for` and the statements of an
/// included file too) counts each time it runs, one per 64 bytes of its
/// text (at least one), and an iteration of an empty body counts one.
/// Nested loops of 1,000 × 1,000 around a short statement run 1,001,000.
/// A file included again (in a loop, or twice) counts as its statements
/// plus its parse (32 and one per 64 bytes). Evaluation stays bounded (no loop or
/// tree of includes runs forever) and so does the memory of the objects
/// loops make (about 250 bytes each when checked).
pub const MAX_LOOP_STATEMENTS: u64 = 4_000_000;
/// A statement counts one against [`MAX_LOOP_STATEMENTS`] per this many
/// bytes of its text (at least one): a long expression takes longer.
const STATEMENT_BYTES: u64 = 64;
/// What running an included file again costs against
/// [`MAX_LOOP_STATEMENTS`] besides its size: a parse's set-up takes about
/// as long as checking 30 statements.
const INCLUDE_RUN_COST: u64 = 32;
/// Most objects the instances of a scene may place in all (a mesh counts
/// one), through every level of groups placing groups.
pub const MAX_PLACED_OBJECTS: u64 = 4_000_000;
/// Deepest chain of includes.
pub const MAX_INCLUDE_DEPTH: usize = 32;

/// Where in an animation a scene is compiled: the values of the predefined
/// names `frame` (the frame's number) and `clock` (0 at the animation's
/// first frame to 1 at its last, as POV-Ray's). A still image is frame 0 at
/// clock 0.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Animation {
    /// The frame's number.
    pub frame: u32,
    /// Where the frame lies in the animation, 0 to 1.
    pub clock: f64,
    /// The clock's step from one frame to the next (0 for a still image),
    /// POV-Ray's `clock_delta`.
    pub clock_delta: f64,
}

/// The names every scene sees unless it binds them itself, with the values
/// of [`Animation`] (for the editors and docs too).
pub const PREDEFINED: [&str; 7] = ["frame", "clock", "clock_delta", "pi", "x", "y", "z"];

/// The result of compiling a scene file up to the checked scene.
#[derive(Debug)]
pub struct Checked {
    /// Every file read (the scene and its includes).
    pub sources: SourceMap,
    /// The scene, when there were no errors.
    pub scene: Option<Scene>,
    /// Errors and warnings, sorted by position.
    pub diagnostics: Diagnostics,
    /// Every name the scene defines and where each is used, as far as the
    /// check went (a scene with errors has them too).
    pub symbols: Symbols,
    /// When there were errors: the files the scene names, which lowering
    /// would read.
    pub unbuilt: Option<unbuilt::Unbuilt>,
}

/// Reads, parses and checks the scene at `path` and everything it includes.
/// An unreadable root file is an I/O error (exit code 2), not a diagnostic.
pub fn check_file(path: &Path) -> std::io::Result<Checked> {
    Ok(check_bytes(path, read_scene_file(&Disk, path)?))
}

/// The bytes of the scene file at `path`, read up to [`MAX_SCENE_BYTES`]
/// like every file of a scene. It must be a regular file: a FIFO (or
/// `<(generate)`) would wait for its writer and a device could be endless
/// (the message says what the path is).
pub fn read_scene_file(files: &dyn Files, path: &Path) -> std::io::Result<Vec<u8>> {
    files.read(path, MAX_SCENE_BYTES).map_err(|e| match e {
        ReadError::Io(e) => e,
        ReadError::NotFound => std::io::Error::new(std::io::ErrorKind::NotFound, "no such file"),
        other => std::io::Error::other(other.to_string()),
    })
}

/// Checks a scene given as bytes, as if read from `path` (includes are
/// resolved relative to it).
pub fn check_bytes(path: &Path, bytes: Vec<u8>) -> Checked {
    check_bytes_within(
        path,
        bytes,
        Budgets::standard(),
        Animation::default(),
        &Disk,
    )
}

/// What the loops and expressions of one compile may do: the statements
/// loops may run ([`MAX_LOOP_STATEMENTS`]) and the steps of work
/// expressions may take ([`eval::MAX_WORK`]).
#[derive(Debug, Clone)]
pub struct Budgets {
    /// Statements loops and repeated includes may run in all.
    pub loop_statements: u64,
    /// Steps of work evaluation may take in all.
    pub work: u64,
    /// Set by another thread when the result is no longer wanted (an
    /// editor's newer text): checking stops at the next statement, and
    /// the result is incomplete.
    pub cancel: Option<std::sync::Arc<std::sync::atomic::AtomicBool>>,
}

impl Budgets {
    /// The budgets of every compile but a fuzzer's.
    pub fn standard() -> Self {
        Budgets {
            loop_statements: MAX_LOOP_STATEMENTS,
            work: eval::MAX_WORK,
            cancel: None,
        }
    }
}

/// [`check_bytes`] with other budgets (a fuzzer keeps its inputs fast
/// with small ones; the rules are the same), at a frame of an animation,
/// its includes (and mesh files) read from `files`.
pub fn check_bytes_within(
    path: &Path,
    bytes: Vec<u8>,
    budgets: Budgets,
    animation: Animation,
    files: &dyn Files,
) -> Checked {
    let mut c = Checker::new(budgets, files);
    let [frame, clock, clock_delta, pi, x, y, z] = PREDEFINED;
    let axis = |v: [f64; 3]| Value::Vector(v.into());
    c.env.predefined = vec![
        (frame, Value::Num(animation.frame as f64)),
        (clock, Value::Num(animation.clock)),
        (clock_delta, Value::Num(animation.clock_delta)),
        (pi, Value::Num(std::f64::consts::PI)),
        (x, axis([1.0, 0.0, 0.0])),
        (y, axis([0.0, 1.0, 0.0])),
        (z, axis([0.0, 0.0, 1.0])),
    ];
    if let Some(kind) = foreign_file::not_a_scene(path, &bytes) {
        let id = c.sources.add(path, String::new());
        c.diags.push(foreign_file::not_a_scene_error(
            path,
            kind,
            Span::new(id, 0, 0),
        ));
        // No statement was read: the whole-scene checks would be noise.
        c.syntax_failed = true;
        return c.finish();
    }
    let (text, bad_utf8) = decode(bytes);
    let id = c.sources.add(path, text);
    if let Some(at) = bad_utf8 {
        c.diags.push(invalid_utf8(id, at));
    }
    // The root file opens the include stack, so that including it is a cycle too.
    let root = files.canonical(path);
    c.include_stack.push((root, Span::new(id, 0, 0)));
    c.run_file(id);
    c.finish()
}

/// Checks a scene given as text (for tests and benchmarks).
pub fn check_str(path: &Path, text: &str) -> Checked {
    check_bytes(path, text.as_bytes().to_vec())
}

/// The text of a file and the offset of its first invalid UTF-8 byte, if
/// any. Each invalid byte becomes one `?`, so that every offset in the text
/// is the same byte offset in the file (spans, line and column numbers
/// match what an editor shows after the bad byte too).
fn decode(bytes: Vec<u8>) -> (String, Option<usize>) {
    match String::from_utf8(bytes) {
        Ok(s) => (s, None),
        Err(e) => {
            let at = e.utf8_error().valid_up_to();
            let bytes = e.into_bytes();
            let mut text = String::with_capacity(bytes.len());
            for chunk in bytes.utf8_chunks() {
                text.push_str(chunk.valid());
                text.extend(std::iter::repeat_n('?', chunk.invalid().len()));
            }
            (text, Some(at))
        }
    }
}

fn invalid_utf8(file: FileId, at: usize) -> Diagnostic {
    Diagnostic::error(
        codes::INVALID_UTF8,
        format!("the file is not valid UTF-8 (byte {at})"),
        Span::new(file, at, at + 1),
    )
    .with_label("this byte does not start a UTF-8 character")
    .with_help("save the file as UTF-8 text")
}

/// The folder relative paths in `file` (output, mesh and include files) start from.
fn folder_of(sources: &SourceMap, file: FileId) -> &Path {
    sources.get(file).path.parent().unwrap_or(Path::new(""))
}

struct MaterialEntry {
    index: usize,
    span: Span,
    /// Its definition in the symbols, which uses are recorded against.
    def: DefId,
}

/// An object of the scene or of a group.
#[derive(Debug, Clone, Copy)]
struct ObjectRef {
    /// The group that holds it, if any.
    group: Option<usize>,
    /// Its index there.
    index: usize,
    /// Which of a mesh's replaced materials (`materials { … }`) is meant,
    /// if not the object's own.
    swap: Option<usize>,
}

struct Checker<'f> {
    /// Where files are read: the front end asks nothing of the disk itself.
    files: &'f dyn Files,
    sources: SourceMap,
    diags: Diagnostics,
    env: Env,
    include_stack: Vec<(PathBuf, Span)>,
    /// Statements loops may still run (of `loop_statements`).
    loop_budget: u64,
    /// Statements loops may run in all ([`MAX_LOOP_STATEMENTS`] but for fuzzers).
    loop_statements: u64,
    /// The loops and repeated includes running now, outermost first (a
    /// loop's range, an include's path): their statements are charged.
    loops: Vec<Span>,
    /// The budget ran out: every loop stops (reported once).
    loops_exhausted: bool,
    /// Set when the result is no longer wanted ([`Budgets::cancel`]).
    cancel: Option<std::sync::Arc<std::sync::atomic::AtomicBool>>,
    render: Option<(RenderSettings, Span)>,
    camera: Option<Camera>,
    camera_span: Option<Span>,
    background: Option<([f64; 3], Span)>,
    /// The environment block, if any.
    environment: Option<scene::Environment>,
    /// The sky block, if any.
    sky: Option<scene::Sky>,
    atmosphere: Option<scene::Atmosphere>,
    materials: Vec<Material>,
    material_names: HashMap<String, MaterialEntry>,
    /// The material of objects that name none, once one needs it.
    default_material: Option<usize>,
    /// Where each included file was first included (the include's path).
    included_from: HashMap<FileId, Span>,
    /// Objects whose material was named before its declaration: the
    /// object (its group, if any, and index) and the name as written.
    pending_materials: Vec<(ObjectRef, crate::syntax::ast::Ident)>,
    /// Material names of objects not kept (their shape had an error) that
    /// were not declared before them: looked up at the end all the same.
    unplaced_materials: Vec<crate::syntax::ast::Ident>,
    /// The names of instances' groups not declared before them (each
    /// reported at once; taken back at the end where a statement that did
    /// not parse may declare it).
    unknown_groups: Vec<crate::syntax::ast::Ident>,
    /// The `let`s in loops that hide an outer name, looked at for
    /// [`codes::SHADOWED_IN_LOOP`] (each once, however many passes run it).
    shadow_examined: std::collections::HashSet<Span>,
    /// Names given to a misspelt `material` (`materal red`, reported
    /// there): the materials they name are not reported unused too.
    meant_materials: Vec<crate::syntax::ast::Ident>,
    /// A light block had errors: the scene's "no light" would be their
    /// echo.
    light_with_errors: bool,
    objects: Vec<Object>,
    /// Declared groups (the one being declared too, last).
    groups: Vec<Group>,
    /// The groups' names, once declared whole: index, name's span and
    /// definition.
    group_names: HashMap<String, (usize, Span, DefId)>,
    /// The group whose body runs now: objects and instances go there.
    open_group: Option<usize>,
    /// Placements of groups at the top level.
    instances: Vec<Instance>,
    /// Groups placed at least once.
    placed_groups: HashSet<usize>,
    /// Objects the top-level instances place, all together.
    placed_objects: u64,
    /// [`MAX_PLACED_OBJECTS`] was passed (reported once).
    placements_exhausted: bool,
    lights: Vec<(Light, Span)>,
    ambient_span: Option<Span>,
    /// Where `render { clamp }` is set, if it is.
    clamp_span: Option<Span>,
    /// Where `light_samples` was set, for the Whitted warning.
    light_samples_span: Option<Span>,
    /// Where `integrator` was set, for the bidirectional ones' warning.
    integrator_span: Option<Span>,
    /// A file did not parse: whole-scene checks would only echo that.
    syntax_failed: bool,
}

impl<'f> Checker<'f> {
    /// Where the scene's light at infinity (background, environment or
    /// sky) was given, if it has one yet.
    fn infinite_light(&self) -> Option<Span> {
        (self.background.map(|b| b.1))
            .or(self.environment.as_ref().map(|e| e.span))
            .or(self.sky.as_ref().map(|s| s.span))
    }

    fn new(budgets: Budgets, files: &'f dyn Files) -> Self {
        Checker {
            files,
            sources: SourceMap::new(),
            // A loop meets its body's problems once per iteration: one each.
            diags: Diagnostics::folding(),
            env: Env::with_work(budgets.work),
            include_stack: Vec::new(),
            loop_budget: budgets.loop_statements,
            loop_statements: budgets.loop_statements,
            cancel: budgets.cancel,
            loops: Vec::new(),
            loops_exhausted: false,
            render: None,
            camera: None,
            camera_span: None,
            background: None,
            environment: None,
            sky: None,
            atmosphere: None,
            materials: Vec::new(),
            material_names: HashMap::new(),
            default_material: None,
            pending_materials: Vec::new(),
            unplaced_materials: Vec::new(),
            unknown_groups: Vec::new(),
            shadow_examined: Default::default(),
            meant_materials: Vec::new(),
            light_with_errors: false,
            included_from: HashMap::new(),
            objects: Vec::new(),
            groups: Vec::new(),
            group_names: HashMap::new(),
            open_group: None,
            instances: Vec::new(),
            placed_groups: HashSet::new(),
            placed_objects: 0,
            placements_exhausted: false,
            lights: Vec::new(),
            ambient_span: None,
            clamp_span: None,
            light_samples_span: None,
            integrator_span: None,
            syntax_failed: false,
        }
    }

    fn run_file(&mut self, id: FileId) {
        let text = self.sources.get(id).text.clone();
        // Statements are checked while later parts of the file are parsed.
        // Parsing goes on past a syntax error: the statements before and
        // after it are checked, and their mistakes reported with it.
        let errors = crate::syntax::parse_each(id, &text, &kinds::NAMES, &mut |statements| {
            for st in &statements {
                self.statement(st, id);
            }
        });
        self.syntax_failed |= !errors.is_empty();
        errors.into_iter().for_each(|d| self.diags.push(d));
    }

    /// Where the constant, function or texture named `name` visible in
    /// the current frame is declared, if there is one.
    fn name_taken(&self, name: &str) -> Option<Span> {
        (self.env.in_current_frame(name).map(|b| b.def))
            .or_else(|| self.env.textures.get(name).map(|t| t.1))
            .map(|def| self.env.symbols.get(def).name_span)
    }

    /// Checks `body` in order.
    fn statements(&mut self, body: &[Statement], file: FileId) {
        for st in body {
            self.statement(st, file);
        }
    }
}

/// The `material` entries of a block, with where each is written.
fn material_entries(block: &crate::syntax::ast::Block) -> Vec<(&MaterialRef, Span)> {
    (block.entries.iter())
        .filter_map(|e| match e {
            Entry::Material { material, span } => Some((material, *span)),
            _ => None,
        })
        .collect()
}

/// The error for a statement that a group cannot hold, written at `span`
/// inside the group declared at `group`.
fn not_in_group(what: &str, span: Span, group: Span, help: &str) -> Diagnostic {
    Diagnostic::error(
        codes::NOT_IN_GROUP,
        format!("{what} cannot be part of a group"),
        span,
    )
    .with_label("inside a group")
    .with_secondary(group, "the group")
    .with_help(help.to_string())
}

/// The error for an instance naming a material not declared before it.
fn unknown_material_here(
    name: &crate::syntax::ast::Ident,
    names: &HashMap<String, MaterialEntry>,
    env: &mut Env,
) -> Diagnostic {
    let d = Diagnostic::error(
        codes::UNKNOWN_MATERIAL,
        format!("unknown material `{}`", name.name),
        name.span,
    )
    .with_label("not declared before this instance");
    match env.suggest(&name.name, names.len(), names.keys().map(String::as_str)) {
        Some(s) => d.with_help(format!("did you mean `{s}`?")),
        None => d.with_help(format!(
            "declare it before the instance: `material {} {{ diffuse rgb 0.8 }}`",
            name.name
        )),
    }
}

/// The error for an infinite plane with an emissive material.
fn emissive_plane(at: Span) -> Diagnostic {
    Diagnostic::error(codes::DEGENERATE, "an infinite plane cannot emit light", at)
        .with_label("this plane has an emissive material")
        .with_help(
            "use a `quad` or a `disk` as an area light, or `background` for light from everywhere",
        )
}

/// A name declared again (`let`, `texture`) where it was declared `first`.
fn defined_again(name: &crate::syntax::ast::Ident, first: Span, help: &str) -> Diagnostic {
    Diagnostic::error(
        codes::DUPLICATE_NAME,
        format!("`{}` is already defined", name.name),
        name.span,
    )
    .with_label("defined again here")
    .with_secondary(first, "first defined here")
    .with_help(help.to_string())
}

/// Two of `background`, `environment` and `sky` in one scene.
fn two_skies(span: Span, first: Span) -> Diagnostic {
    Diagnostic::error(
        codes::DUPLICATE_BLOCK,
        "a scene has one light at infinity: a `background`, an `environment` or a `sky`",
        span,
    )
    .with_label("the second one")
    .with_secondary(first, "the first one")
    .with_help("keep one; `environment { … intensity rgb … }` scales its image, as a background colour would")
}

fn duplicate_block(what: &str, span: Span, first: Span) -> Diagnostic {
    Diagnostic::error(
        codes::DUPLICATE_BLOCK,
        format!("a scene has one `{what}`"),
        span,
    )
    .with_label(format!("second `{what}`"))
    .with_secondary(first, "first one here")
    .with_help(format!("merge the two `{what}` statements into one"))
}
