//! Semantic analysis: AST → checked [`Scene`] plus diagnostics. Runs every
//! pass to the end and reports all problems together; never stops at the
//! first error.

mod blocks;
pub mod domain;
pub mod eval;
mod finish;
mod group_lights;
mod loops;
mod material;
mod objects;
pub mod params;
mod povray;
mod reader;
pub mod scene;
pub mod schema;
mod texture;

pub use blocks::{MAX_PIXELS, MAX_SIDE, SAMPLES, SEED};
pub use reader::WholeSetting;
pub use scene::*;

pub(crate) use crate::diag::group_digits;
use crate::diag::{codes, Diagnostic, Diagnostics};
use crate::source::{Disk, FileId, FileKind, Files, ReadError, SourceMap, MAX_SCENE_BYTES};
use crate::span::Span;
use crate::syntax::ast::{BlockKind, Entry, MaterialRef, Statement};
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
    check_bytes_within(path, bytes, Budgets::default(), Animation::default(), &Disk)
}

/// What the loops and expressions of one compile may do: the statements
/// loops may run ([`MAX_LOOP_STATEMENTS`]) and the steps of work
/// expressions may take ([`eval::MAX_WORK`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Budgets {
    /// Statements loops and repeated includes may run in all.
    pub loop_statements: u64,
    /// Steps of work evaluation may take in all.
    pub work: u64,
}

impl Default for Budgets {
    /// The budgets of every compile but a fuzzer's.
    fn default() -> Self {
        Budgets {
            loop_statements: MAX_LOOP_STATEMENTS,
            work: eval::MAX_WORK,
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
}

/// An object of the scene or of a group.
#[derive(Debug, Clone, Copy)]
struct ObjectRef {
    /// The group that holds it, if any.
    group: Option<usize>,
    /// Its index there.
    index: usize,
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
    render: Option<(RenderSettings, Span)>,
    camera: Option<Camera>,
    camera_span: Option<Span>,
    background: Option<([f64; 3], Span)>,
    /// The environment block, if any.
    environment: Option<scene::Environment>,
    /// The sky block, if any.
    sky: Option<scene::Sky>,
    materials: Vec<Material>,
    material_names: HashMap<String, MaterialEntry>,
    used_materials: HashSet<usize>,
    /// The material of objects that name none, once one needs it.
    default_material: Option<usize>,
    /// Where each included file was first included (the include's path).
    included_from: HashMap<FileId, Span>,
    /// Objects whose material was named before its declaration: the
    /// object (its group, if any, and index) and the name as written.
    pending_materials: Vec<(ObjectRef, crate::syntax::ast::Ident)>,
    objects: Vec<Object>,
    /// Declared groups (the one being declared too, last).
    groups: Vec<Group>,
    /// The groups' names, once declared whole: index and name's span.
    group_names: HashMap<String, (usize, Span)>,
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
    lets: Vec<(String, Span)>,
    /// The declarations in `lets` (a loop runs one declaration many times).
    let_spans: HashSet<Span>,
    /// The declarations in `lets` that are functions.
    functions: HashSet<Span>,
    ambient_span: Option<Span>,
    /// Where `light_samples` was set, for the Whitted warning.
    light_samples_span: Option<Span>,
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
            loops: Vec::new(),
            loops_exhausted: false,
            render: None,
            camera: None,
            camera_span: None,
            background: None,
            environment: None,
            sky: None,
            materials: Vec::new(),
            material_names: HashMap::new(),
            used_materials: HashSet::new(),
            default_material: None,
            pending_materials: Vec::new(),
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
            lets: Vec::new(),
            let_spans: HashSet::new(),
            functions: HashSet::new(),
            ambient_span: None,
            light_samples_span: None,
            syntax_failed: false,
        }
    }

    fn run_file(&mut self, id: FileId) {
        let text = self.sources.get(id).text.clone();
        // Statements are checked while later parts of the file are parsed.
        // Parsing goes on past a syntax error: the statements before and
        // after it are checked, and their mistakes reported with it.
        let errors = crate::syntax::parse_each(id, &text, &mut |statements| {
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
        (self.env.in_current_frame(name).map(|b| b.decl))
            .or_else(|| self.env.textures.get(name).map(|t| t.1))
    }

    /// Checks `body` in order.
    fn statements(&mut self, body: &[Statement], file: FileId) {
        for st in body {
            self.statement(st, file);
        }
    }

    /// `group name { body }`: runs the body with objects and instances
    /// going to the new group, which is named once it is whole (so that
    /// placing itself is a cycle, not a placement).
    fn group(
        &mut self,
        name: &crate::syntax::ast::Ident,
        body: &[Statement],
        span: Span,
        file: FileId,
    ) {
        if let Some(outer) = self.open_group {
            self.diags.push(not_in_group(
                "a group declaration",
                span,
                self.groups[outer].span,
                "declare groups at the top level and place one in another with `instance`",
            ));
            return;
        }
        if let Some(&(_, first)) = self.group_names.get(&name.name) {
            // A loop or a second include runs one declaration again: it
            // declares the same group again, once.
            if first != name.span {
                self.diags
                    .push(defined_again(name, first, "give each group its own name"));
            }
            return;
        }
        self.groups.push(Group {
            name: name.name.clone(),
            objects: Vec::new(),
            unmaterialled: Vec::new(),
            instances: Vec::new(),
            lights: Vec::new(),
            placed_objects: 0,
            placed_lights: 0,
            span: name.span,
        });
        let index = self.groups.len() - 1;
        self.open_group = Some(index);
        // The body's constants and functions are its own.
        self.env.push();
        self.statements(body, file);
        self.env.pop();
        self.open_group = None;
        self.count_placements(index);
        self.group_names
            .insert(name.name.clone(), (index, name.span));
    }

    /// `instance name { … }`: a placement of a declared group.
    fn instance(
        &mut self,
        name: &crate::syntax::ast::Ident,
        block: &crate::syntax::ast::Block,
        span: Span,
    ) {
        let p = Params::collect(
            "instance",
            name.span,
            block,
            &[schema::SHAPE_COMMON],
            &mut self.env,
            &mut self.diags,
        );
        let material_entries = material_entries(block);
        let transform = objects::transform(&p, &mut self.diags);
        let velocity = objects::velocity(&p);
        let material = if material_entries.is_empty() {
            None
        } else {
            self.object_material(&material_entries, span)
        };
        let group = match self.group_names.get(&name.name) {
            Some(&(g, _)) => g,
            None => {
                let open = self.open_group.map(|g| &self.groups[g]);
                if let Some(open) = open.filter(|g| g.name == name.name) {
                    self.diags.push(
                        Diagnostic::error(
                            codes::GROUP_CYCLE,
                            format!("group `{}` contains itself", name.name),
                            name.span,
                        )
                        .with_label("placed inside its own declaration")
                        .with_secondary(open.span, "declared here")
                        .with_help("a group cannot hold copies of itself; repeat parts with a `for` loop, or place another group"),
                    );
                    return;
                }
                let mut d = Diagnostic::error(
                    codes::UNKNOWN_GROUP,
                    format!("unknown group `{}`", name.name),
                    name.span,
                )
                .with_label("no group of this name");
                let names = self.group_names.keys().map(String::as_str);
                d = match (self.env).suggest(&name.name, self.group_names.len(), names) {
                    Some(s) => d.with_help(format!("did you mean `{s}`?")),
                    None => d.with_help(format!(
                        "declare it before placing it: `group {} {{ sphere {{ … }} }}`",
                        name.name
                    )),
                };
                self.diags.push(d);
                return;
            }
        };
        self.placed_groups.insert(group);
        if self.groups[group].is_empty() {
            self.diags.push(
                Diagnostic::warning(
                    codes::EMPTY_GROUP,
                    format!("group `{}` holds nothing", name.name),
                    name.span,
                )
                .with_label("this instance adds nothing to the image")
                .with_secondary(self.groups[group].span, "declared here")
                .with_help("put objects in the group, or remove the instance"),
            );
        }
        if let Some((MaterialRef::Named(m), _)) = material_entries.first() {
            if material == Some(PENDING_MATERIAL) {
                // Resolved at the end like an object's; instances name
                // materials declared before them (reported otherwise).
                self.diags.push(unknown_material_here(
                    m,
                    &self.material_names,
                    &mut self.env,
                ));
                return;
            }
        }
        let instance = Instance {
            group,
            transform,
            material,
            velocity,
            span,
        };
        match self.open_group {
            Some(g) => self.groups[g].instances.push(instance),
            None => {
                // Groups placing groups multiply: the objects all placements
                // make are bounded like the statements loops run.
                let more = self.groups[group].placed_objects;
                self.placed_objects = self.placed_objects.saturating_add(more);
                if self.placed_objects > MAX_PLACED_OBJECTS {
                    if !self.placements_exhausted {
                        self.placements_exhausted = true;
                        self.diags.push(
                            Diagnostic::error(
                                codes::LOOP_TOO_LONG,
                                format!(
                                    "the instances of this scene place more than {} objects in all",
                                    group_digits(MAX_PLACED_OBJECTS)
                                ),
                                span,
                            )
                            .with_label(format!(
                                "this one places {}",
                                group_digits(more)
                            ))
                            .with_help("groups that place groups multiply; place fewer, or make a large part a mesh"),
                        );
                    }
                    return;
                }
                self.place_lights(&instance);
                self.instances.push(instance)
            }
        }
    }

    fn statement(&mut self, st: &Statement, file: FileId) {
        // Checking a statement takes time in proportion to its text.
        if !self.charge_loop(1 + st.span().len() as u64 / STATEMENT_BYTES) {
            return;
        }
        match st {
            Statement::Let { name, value, .. } => {
                // A texture's name is taken too (both are read as names).
                if let Some(first) = self.name_taken(&name.name) {
                    self.diags.push(defined_again(
                        name,
                        first,
                        "constants cannot be redefined; pick another name",
                    ));
                    return;
                }
                let v = eval(value, &mut self.env, &mut self.diags);
                if v.is_none() {
                    // Uses of a broken constant stay silent; don't call it unused either.
                    self.env.used.insert(name.span);
                }
                self.env.bind(
                    &name.name,
                    Binding {
                        value: v,
                        decl: name.span,
                    },
                );
                if self.let_spans.insert(name.span) {
                    self.lets.push((name.name.clone(), name.span));
                }
            }
            Statement::Texture {
                name,
                kind,
                block,
                span,
            } => {
                let clash = (self.env.textures.get(&name.name).map(|t| t.1))
                    .or_else(|| self.env.in_current_frame(&name.name).map(|b| b.decl));
                if let Some(first) = clash.filter(|&first| first != name.span) {
                    self.diags.push(defined_again(
                        name,
                        first,
                        "give each texture and constant its own name",
                    ));
                    return;
                }
                let texture =
                    texture::check_texture(kind, block, *span, &mut self.env, &mut self.diags);
                if let Some(mut texture) = texture {
                    texture.resolve_path(folder_of(&self.sources, span.file));
                    self.env
                        .textures
                        .insert(name.name.clone(), (texture, name.span));
                    if self.let_spans.insert(name.span) {
                        self.lets.push((name.name.clone(), name.span));
                    }
                }
            }
            Statement::Include {
                path, path_span, ..
            } => self.include(path, *path_span, file),
            Statement::For {
                var,
                start,
                end: None,
                body,
                ..
            } => self.for_list(var, start, body, file),
            Statement::For {
                var,
                start,
                end: Some(end),
                body,
                ..
            } => self.for_range(var, (start, end), body, file),
            Statement::If {
                arms, otherwise, ..
            } => {
                // A branch's statements run in the enclosing scope, as
                // POV-Ray's `#if`: `if final { let spp = 1024; } else { let
                // spp = 16; }` defines `spp` for what follows.
                for (cond, body) in arms {
                    match eval::condition(cond, &mut self.env, &mut self.diags) {
                        Some(true) => return self.statements(body, file),
                        Some(false) => {}
                        None => return,
                    }
                }
                if let Some(body) = otherwise {
                    self.statements(body, file);
                }
            }
            Statement::Function {
                name, params, body, ..
            } => {
                if let Some(first) = self.name_taken(&name.name) {
                    if first != name.span {
                        self.diags.push(defined_again(
                            name,
                            first,
                            "give each function, constant and texture its own name",
                        ));
                        return;
                    }
                }
                if eval::FUNCTIONS.iter().any(|(f, _)| *f == name.name) {
                    self.diags.push(
                        Diagnostic::error(
                            codes::DUPLICATE_NAME,
                            format!("`{}` is a built-in function", name.name),
                            name.span,
                        )
                        .with_label("defined again here")
                        .with_help(format!("pick another name, e.g. `my_{}`", name.name)),
                    );
                    return;
                }
                let mut seen: HashMap<&str, Span> = HashMap::new();
                for p in params {
                    if let Some(first) = seen.insert(&p.name, p.span) {
                        self.diags.push(defined_again(
                            p,
                            first,
                            "give each parameter its own name",
                        ));
                        return;
                    }
                }
                let f = eval::Function {
                    name: name.name.clone(),
                    params: params.iter().map(|p| p.name.clone()).collect(),
                    body: body.clone(),
                };
                self.env.bind(
                    &name.name,
                    Binding {
                        value: Some(Value::Function(std::sync::Arc::new(f))),
                        decl: name.span,
                    },
                );
                if self.let_spans.insert(name.span) {
                    self.lets.push((name.name.clone(), name.span));
                    self.functions.insert(name.span);
                }
            }
            Statement::Group { name, body, span } => self.group(name, body, *span, file),
            Statement::Instance { group, block, span } => self.instance(group, block, *span),
            Statement::Background { value, span } => {
                if let Some(g) = self.open_group {
                    self.diags.push(not_in_group(
                        "`background`",
                        *span,
                        self.groups[g].span,
                        "settings and the sky belong at the top level of the scene",
                    ));
                    return;
                }
                let v = eval(value, &mut self.env, &mut self.diags);
                if let Some(first) = self.background.map(|b| b.1) {
                    self.diags.push(duplicate_block("background", *span, first));
                    return;
                }
                if let Some(first) = self.infinite_light() {
                    self.diags.push(two_skies(*span, first));
                    return;
                }
                match v {
                    Some(Value::Color(c)) if c.iter().all(|x| *x >= 0.0) => {
                        match domain::Quantity::Radiance.check_all(&c, "background", "", value.span)
                        {
                            Ok(()) => self.background = Some((c, *span)),
                            Err(d) => self.diags.push(d),
                        }
                    }
                    Some(Value::Color(_)) => self.diags.push(
                        Diagnostic::error(
                            codes::OUT_OF_RANGE,
                            "the background must be non-negative",
                            value.span,
                        )
                        .with_label("negative radiance")
                        .with_help("colour components are ≥ 0"),
                    ),
                    Some(other) => self.diags.push(
                        Diagnostic::error(
                            codes::TYPE_MISMATCH,
                            format!("`background` expects a colour, found {}", other.type_name()),
                            value.span,
                        )
                        .with_label(format!("this is {}", other.type_name()))
                        .with_help("write e.g. `background rgb <0.7, 0.8, 1.0>`"),
                    ),
                    None => {}
                }
            }
            Statement::Material { name, block, span } => {
                let what = format!("material {}", name.name);
                let checking = (&mut self.env, &mut self.diags);
                let p = material::collect(what, name.span, block, checking);
                for e in &block.entries {
                    if let Entry::Material { span, .. } = e {
                        self.diags.push(
                            Diagnostic::error(
                                codes::UNKNOWN_PARAM,
                                "a material cannot contain a material",
                                *span,
                            )
                            .with_label("not allowed inside `material`")
                            .with_help("put the material's parameters directly in its block"),
                        );
                    }
                }
                let mut m = material::material(&p, Some(name.name.clone()), *span, &mut self.diags);
                m.resolve_paths(folder_of(&self.sources, span.file));
                if let Some(prev) = self.material_names.get(&name.name) {
                    // Loops may redeclare the same declaration; only distinct declarations clash.
                    if prev.span != name.span {
                        self.diags.push(
                            Diagnostic::error(
                                codes::DUPLICATE_NAME,
                                format!("material `{}` is already defined", name.name),
                                name.span,
                            )
                            .with_label("defined again here")
                            .with_secondary(prev.span, "first defined here")
                            .with_help("give each material its own name"),
                        );
                        return;
                    }
                }
                self.materials.push(m);
                self.material_names.insert(
                    name.name.clone(),
                    MaterialEntry {
                        index: self.materials.len() - 1,
                        span: name.span,
                    },
                );
            }
            Statement::Block {
                kind,
                kind_span,
                block,
                span,
            } => self.block(*kind, *kind_span, block, *span, file),
            Statement::Foreign { name, span } => {
                self.diags.push(povray::foreign_statement(name, *span));
            }
            Statement::Directive {
                name,
                binding,
                span,
            } => {
                self.diags.push(povray::directive(name));
                // `#declare R = 1;` binds `R` as `let` would: its uses are fine.
                if let Some((bound, value)) = binding {
                    let name = bound.clone();
                    let value = value.clone();
                    let span = *span;
                    self.statement(&Statement::Let { name, value, span }, file);
                }
            }
        }
    }

    fn include(&mut self, path: &str, path_span: Span, file: FileId) {
        let target = folder_of(&self.sources, file).join(path);
        let canonical = self.files.canonical(&target);
        if let Some(pos) = self.include_stack.iter().position(|(p, _)| *p == canonical) {
            let mut d = Diagnostic::error(
                codes::INCLUDE_CYCLE,
                format!("`{path}` includes itself"),
                path_span,
            )
            .with_label("this include closes a cycle")
            .with_help("remove one of the includes in the cycle");
            for (_, s) in self.include_stack[pos + 1..].iter() {
                d = d.with_secondary(*s, "included from");
            }
            self.diags.push(d);
            return;
        }
        if self.include_stack.len() >= MAX_INCLUDE_DEPTH {
            self.diags.push(
                Diagnostic::error(
                    codes::INCLUDE_CYCLE,
                    "includes nested too deeply",
                    path_span,
                )
                .with_label(format!("more than {MAX_INCLUDE_DEPTH} levels"))
                .with_help("flatten the chain of includes"),
            );
            return;
        }
        // A file already read (an include in a loop, or included twice) is
        // not read again; but it is parsed again, which costs as many
        // statements as a parse's set-up plus one per 64 bytes (a typical
        // statement's size).
        if let Some(id) = self.sources.find(&target) {
            let bytes = self.sources.get(id).text.len() as u64;
            self.enter_loop(path_span);
            if self.charge_loop(INCLUDE_RUN_COST + bytes / STATEMENT_BYTES) {
                self.include_stack.push((canonical, path_span));
                self.run_file(id);
                self.include_stack.pop();
            }
            self.leave_loop();
            return;
        }
        let room = MAX_SCENE_BYTES.saturating_sub(self.sources.total_bytes() as u64);
        let bytes = match self.files.read(&target, room) {
            Ok(b) => b,
            Err(e) => {
                let (reason, help) = match &e {
                    ReadError::NotFound => (
                        "not found".to_string(),
                        "include paths are relative to the file that contains the `include`"
                            .to_string(),
                    ),
                    ReadError::NotRegular(FileKind::Folder) => (
                        "it is a folder, not a file".to_string(),
                        "include a `.pts` or `.ptsi` file".to_string(),
                    ),
                    ReadError::NotRegular(kind) => (
                        format!("not a regular file: it is {kind}"),
                        "devices, pipes and sockets are never read: include a file".to_string(),
                    ),
                    ReadError::TooLarge { size, .. } if *size <= MAX_SCENE_BYTES => (
                        format!(
                            "the scene's files would hold more than {} of text together",
                            crate::source::human_bytes(MAX_SCENE_BYTES)
                        ),
                        "large generated geometry belongs in a mesh file (`mesh { file \"…\" }`)"
                            .to_string(),
                    ),
                    other => (
                        other.to_string(),
                        "large generated geometry belongs in a mesh file (`mesh { file \"…\" }`)"
                            .to_string(),
                    ),
                };
                self.diags.push(
                    Diagnostic::error(
                        codes::INCLUDE_NOT_FOUND,
                        format!("cannot include `{path}`: {reason}"),
                        path_span,
                    )
                    .with_label(format!("looked for {}", target.display()))
                    .with_help(help),
                );
                return;
            }
        };
        let (text, bad) = decode(bytes);
        let id = self.sources.add(target.clone(), text);
        self.included_from.insert(id, path_span);
        if let Some(at) = bad {
            self.diags.push(invalid_utf8(id, at));
        }
        self.include_stack.push((canonical, path_span));
        self.run_file(id);
        self.include_stack.pop();
    }

    fn block(
        &mut self,
        kind: BlockKind,
        kind_span: Span,
        block: &crate::syntax::ast::Block,
        span: Span,
        file: FileId,
    ) {
        if let Some(g) = self
            .open_group
            .filter(|_| !kind.is_shape() && !kind.is_light())
        {
            self.diags.push(not_in_group(
                &format!("`{}`", kind.keyword()),
                kind_span,
                self.groups[g].span,
                "settings and the sky belong at the top level of the scene",
            ));
            return;
        }
        let p = Params::collect(
            kind.keyword(),
            kind_span,
            block,
            &objects::shape_schemas(kind),
            &mut self.env,
            &mut self.diags,
        );
        let material_entries = material_entries(block);
        if !kind.is_shape() {
            for (_, s) in &material_entries {
                self.diags.push(
                    Diagnostic::error(
                        codes::UNKNOWN_PARAM,
                        format!("`{}` does not take a material", kind.keyword()),
                        *s,
                    )
                    .with_label("not allowed here")
                    .with_help("materials belong to objects such as `sphere { … }`"),
                );
            }
        }
        match kind {
            BlockKind::Render => {
                let base = folder_of(&self.sources, file);
                let settings = blocks::render_settings(&p, base, &mut self.diags);
                if let Some((_, first)) = &self.render {
                    self.diags
                        .push(duplicate_block("render", kind_span, *first));
                    return;
                }
                self.ambient_span = p.get("ambient").map(|v| v.1);
                self.light_samples_span = p.get("light_samples").map(|v| v.1);
                self.render = Some((settings, kind_span));
            }
            BlockKind::Camera => {
                let cam = blocks::camera(&p, span, &mut self.diags);
                if let Some(first) = self.camera_span {
                    self.diags.push(duplicate_block("camera", kind_span, first));
                    return;
                }
                self.camera_span = Some(kind_span);
                self.camera = cam;
            }
            BlockKind::Environment => {
                let base = folder_of(&self.sources, file);
                let environment = blocks::environment(&p, base, span, &mut self.diags);
                if let Some(e) = &self.environment {
                    self.diags
                        .push(duplicate_block("environment", kind_span, e.span));
                    return;
                }
                if let Some(first) = self.infinite_light() {
                    self.diags.push(two_skies(kind_span, first));
                    return;
                }
                self.environment = environment;
            }
            BlockKind::Sky => {
                let sky = blocks::sky(&p, span, &mut self.diags);
                if let Some(s) = &self.sky {
                    self.diags.push(duplicate_block("sky", kind_span, s.span));
                    return;
                }
                if let Some(first) = self.infinite_light() {
                    self.diags.push(two_skies(kind_span, first));
                    return;
                }
                self.sky = sky;
            }
            BlockKind::PointLight | BlockKind::SpotLight | BlockKind::DirectionalLight => {
                if let Some(l) = blocks::light(kind, &p, &mut self.diags) {
                    // A group's lights are the scene's once placed.
                    match self.open_group {
                        Some(g) => self.groups[g].lights.push((l, span)),
                        None => self.lights.push((l, span)),
                    }
                }
            }
            _ => {
                let material = self.object_material(&material_entries, span);
                // Only a mesh has a path to resolve (Path::parent is not free).
                let base = match kind {
                    BlockKind::Mesh => folder_of(&self.sources, file),
                    _ => Path::new(""),
                };
                let shape = objects::shape(kind, &p, (base, self.files), &mut self.diags);
                let transform: DMat4 = objects::transform(&p, &mut self.diags);
                let velocity = objects::velocity(&p);
                if let (Some(shape), Some(material)) = (shape, material) {
                    if matches!(shape, Shape::Plane { .. })
                        && material != PENDING_MATERIAL
                        && self.materials[material].is_emissive()
                    {
                        self.diags.push(emissive_plane(kind_span));
                        return;
                    }
                    let object = Object {
                        shape,
                        material,
                        transform,
                        velocity,
                        span,
                    };
                    let at = match self.open_group {
                        Some(g) => {
                            let group = &mut self.groups[g];
                            group.objects.push(object);
                            group.unmaterialled.push(material_entries.is_empty());
                            ObjectRef {
                                group: Some(g),
                                index: group.objects.len() - 1,
                            }
                        }
                        None => {
                            self.objects.push(object);
                            ObjectRef {
                                group: None,
                                index: self.objects.len() - 1,
                            }
                        }
                    };
                    if material == PENDING_MATERIAL {
                        if let Some((MaterialRef::Named(name), _)) = material_entries.first() {
                            self.pending_materials.push((at, (*name).clone()));
                        }
                    }
                }
            }
        }
    }

    /// Resolves the material entries of an object to an index (a default one when absent).
    fn object_material(&mut self, entries: &[(&MaterialRef, Span)], span: Span) -> Option<usize> {
        for (_, s) in entries.iter().skip(1) {
            self.diags.push(
                Diagnostic::error(codes::DUPLICATE_PARAM, "an object has one material", *s)
                    .with_label("second material")
                    .with_secondary(entries[0].1, "first material")
                    .with_help("remove one of them"),
            );
        }
        match entries.first() {
            // One grey material serves every object without one (a loop of
            // a million spheres made a million copies of it).
            None => Some(*self.default_material.get_or_insert_with(|| {
                self.materials.push(Material::default_at(span));
                self.materials.len() - 1
            })),
            Some((MaterialRef::Named(name), _)) => match self.material_names.get(&name.name) {
                Some(m) => {
                    self.used_materials.insert(m.index);
                    Some(m.index)
                }
                // Declared further on, perhaps: names of materials are
                // resolved when the whole scene has been read.
                None => Some(PENDING_MATERIAL),
            },
            Some((MaterialRef::Inline(block), s)) => {
                let p = material::collect("material", *s, block, (&mut self.env, &mut self.diags));
                let mut m = material::material(&p, None, *s, &mut self.diags);
                m.resolve_paths(folder_of(&self.sources, s.file));
                self.materials.push(m);
                let i = self.materials.len() - 1;
                self.used_materials.insert(i);
                Some(i)
            }
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
