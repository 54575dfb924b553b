//! Semantic analysis: AST → checked [`Scene`] plus diagnostics. Runs every
//! pass to the end and reports all problems together; never stops at the
//! first error.

mod blocks;
pub mod codes;
pub mod eval;
mod finish;
mod objects;
pub mod params;
pub mod scene;

pub use scene::*;

use crate::diag::{did_you_mean, Diagnostic, Diagnostics};
use crate::source::{FileId, SourceMap};
use crate::span::Span;
use crate::syntax::ast::{BlockKind, Entry, MaterialRef, Statement};
use eval::{eval, Binding, Env, Value};
use glam::DMat4;
use params::Params;
use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};

/// Most loop iterations in one compile (all loops together).
pub const MAX_LOOP_ITERATIONS: u64 = 1_000_000;
/// Deepest chain of includes.
pub const MAX_INCLUDE_DEPTH: usize = 32;

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
    let bytes = std::fs::read(path)?;
    Ok(check_bytes(path, bytes))
}

/// Checks a scene given as bytes, as if read from `path` (includes are
/// resolved relative to it).
pub fn check_bytes(path: &Path, bytes: Vec<u8>) -> Checked {
    let mut c = Checker::new();
    let (text, bad_utf8) = decode(bytes);
    let id = c.sources.add(path, text);
    if let Some(at) = bad_utf8 {
        c.diags.push(invalid_utf8(id, at));
    }
    // The root file opens the include stack, so that including it is a cycle too.
    let root = std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf());
    c.include_stack.push((root, Span::new(id, 0, 0)));
    c.run_file(id);
    c.finish()
}

/// Checks a scene given as text (for tests and benchmarks).
pub fn check_str(path: &Path, text: &str) -> Checked {
    check_bytes(path, text.as_bytes().to_vec())
}

fn decode(bytes: Vec<u8>) -> (String, Option<usize>) {
    match String::from_utf8(bytes) {
        Ok(s) => (s, None),
        Err(e) => {
            let at = e.utf8_error().valid_up_to();
            (String::from_utf8_lossy(e.as_bytes()).into_owned(), Some(at))
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

struct Checker {
    sources: SourceMap,
    diags: Diagnostics,
    env: Env,
    include_stack: Vec<(PathBuf, Span)>,
    loop_budget: u64,
    render: Option<(RenderSettings, Span)>,
    camera: Option<Camera>,
    camera_span: Option<Span>,
    background: Option<([f64; 3], Span)>,
    materials: Vec<Material>,
    material_names: HashMap<String, MaterialEntry>,
    used_materials: HashSet<usize>,
    objects: Vec<Object>,
    lights: Vec<(Light, Span)>,
    lets: Vec<(String, Span)>,
    /// The declarations in `lets` (a loop runs one declaration many times).
    let_spans: HashSet<Span>,
    ambient_span: Option<Span>,
    /// Where `light_samples` was set, for the Whitted warning.
    light_samples_span: Option<Span>,
    /// A file did not parse: whole-scene checks would only echo that.
    syntax_failed: bool,
}

impl Checker {
    fn new() -> Self {
        Checker {
            sources: SourceMap::new(),
            diags: Diagnostics::new(),
            env: Env::new(),
            include_stack: Vec::new(),
            loop_budget: MAX_LOOP_ITERATIONS,
            render: None,
            camera: None,
            camera_span: None,
            background: None,
            materials: Vec::new(),
            material_names: HashMap::new(),
            used_materials: HashSet::new(),
            objects: Vec::new(),
            lights: Vec::new(),
            lets: Vec::new(),
            let_spans: HashSet::new(),
            ambient_span: None,
            light_samples_span: None,
            syntax_failed: false,
        }
    }

    fn run_file(&mut self, id: FileId) {
        let text = self.sources.get(id).text.clone();
        // Statements are checked while later parts of the file are parsed.
        // After a syntax error the statements before it have been checked:
        // their mistakes are reported with it.
        let parsed = crate::syntax::parse_each(id, &text, &mut |statements| {
            for st in &statements {
                self.statement(st, id);
            }
        });
        if let Err(d) = parsed {
            self.syntax_failed = true;
            self.diags.push(d);
        }
    }

    fn statement(&mut self, st: &Statement, file: FileId) {
        match st {
            Statement::Let { name, value, .. } => {
                if let Some(prev) = self.env.in_current_frame(&name.name) {
                    let first = prev.decl;
                    self.diags.push(
                        Diagnostic::error(
                            codes::DUPLICATE_NAME,
                            format!("`{}` is already defined", name.name),
                            name.span,
                        )
                        .with_label("defined again here")
                        .with_secondary(first, "first defined here")
                        .with_help("constants cannot be redefined; pick another name"),
                    );
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
            Statement::Include {
                path, path_span, ..
            } => self.include(path, *path_span, file),
            Statement::For {
                var,
                start,
                end,
                body,
                ..
            } => {
                let a = eval(start, &mut self.env, &mut self.diags);
                let b = eval(end, &mut self.env, &mut self.diags);
                let bound = |v: Option<Value>, s: Span, diags: &mut Diagnostics| -> Option<i64> {
                    match v? {
                        Value::Num(x) if x.fract() == 0.0 && x.abs() < 1e15 => Some(x as i64),
                        other => {
                            diags.push(
                                Diagnostic::error(
                                    codes::TYPE_MISMATCH,
                                    format!(
                                        "a loop bound must be a whole number, found {}",
                                        match other {
                                            Value::Num(x) => format!("{x}"),
                                            o => o.type_name(),
                                        }
                                    ),
                                    s,
                                )
                                .with_label("not a whole number")
                                .with_help("write the range as `0..10`"),
                            );
                            None
                        }
                    }
                };
                let a = bound(a, start.span, &mut self.diags);
                let b = bound(b, end.span, &mut self.diags);
                let (Some(a), Some(b)) = (a, b) else { return };
                let n = (b - a).max(0) as u64;
                if n > self.loop_budget {
                    self.diags.push(
                        Diagnostic::error(
                            codes::LOOP_TOO_LONG,
                            format!("this loop runs {n} times, more than the {MAX_LOOP_ITERATIONS} iterations a scene may run in all"),
                            start.span.join(end.span),
                        )
                        .with_label(format!("{n} iterations"))
                        .with_help("shrink the range; large generated scenes belong in a mesh file"),
                    );
                    self.loop_budget = 0;
                    return;
                }
                self.loop_budget -= n;
                self.env.used.insert(var.span);
                for i in a..b {
                    let errors_before = self.diags.error_count();
                    self.env.push();
                    self.env.bind(
                        &var.name,
                        Binding {
                            value: Some(Value::Num(i as f64)),
                            decl: var.span,
                        },
                    );
                    for s in body {
                        self.statement(s, file);
                    }
                    self.env.pop();
                    // One broken iteration is enough to report; the others repeat it.
                    if self.diags.error_count() > errors_before {
                        break;
                    }
                }
            }
            Statement::Background { value, span } => {
                let v = eval(value, &mut self.env, &mut self.diags);
                if let Some((_, first)) = self.background {
                    self.diags.push(duplicate_block("background", *span, first));
                    return;
                }
                match v {
                    Some(Value::Color(c)) if c.iter().all(|x| *x >= 0.0) => {
                        self.background = Some((c, *span))
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
                let p = Params::collect(
                    format!("material {}", name.name),
                    name.span,
                    block,
                    &blocks::material_schema(),
                    &mut self.env,
                    &mut self.diags,
                );
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
                let m = blocks::material(&p, Some(name.name.clone()), *span, &mut self.diags);
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
        }
    }

    fn include(&mut self, path: &str, path_span: Span, file: FileId) {
        let target = folder_of(&self.sources, file).join(path);
        let canonical = std::fs::canonicalize(&target).unwrap_or_else(|_| target.clone());
        if let Some(pos) = self.include_stack.iter().position(|(p, _)| *p == canonical) {
            let mut d = Diagnostic::error(
                codes::INCLUDE_CYCLE,
                format!("`{path}` includes itself"),
                path_span,
            )
            .with_label("this include closes a cycle")
            .with_help("remove one of the includes in the cycle");
            for (_, s) in self.include_stack[pos + 1..].iter() {
                d = d.with_secondary(*s, "included from here");
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
        if target.is_dir() {
            self.diags.push(
                Diagnostic::error(
                    codes::INCLUDE_NOT_FOUND,
                    format!("`{path}` is a folder, not a file"),
                    path_span,
                )
                .with_label("a folder")
                .with_help("include a `.pts` file"),
            );
            return;
        }
        let bytes = match std::fs::read(&target) {
            Ok(b) => b,
            Err(e) => {
                let reason = if e.kind() == std::io::ErrorKind::NotFound {
                    "not found".to_string()
                } else {
                    e.to_string()
                };
                self.diags.push(
                    Diagnostic::error(
                        codes::INCLUDE_NOT_FOUND,
                        format!("cannot include `{path}`: {reason}"),
                        path_span,
                    )
                    .with_label(format!("looked for {}", target.display()))
                    .with_help(
                        "include paths are relative to the file that contains the `include`",
                    ),
                );
                return;
            }
        };
        let (text, bad) = decode(bytes);
        let id = match self.sources.find(&target) {
            Some(id) => id,
            None => self.sources.add(target.clone(), text),
        };
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
        let p = Params::collect(
            kind.keyword(),
            kind_span,
            block,
            &objects::shape_schemas(kind),
            &mut self.env,
            &mut self.diags,
        );
        let material_entries: Vec<(&MaterialRef, Span)> = block
            .entries
            .iter()
            .filter_map(|e| match e {
                Entry::Material { material, span } => Some((material, *span)),
                _ => None,
            })
            .collect();
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
            BlockKind::PointLight | BlockKind::SpotLight | BlockKind::DirectionalLight => {
                if let Some(l) = blocks::light(kind, &p, &mut self.diags) {
                    self.lights.push((l, span));
                }
            }
            _ => {
                let material = self.object_material(&material_entries, span);
                // Only a mesh has a path to resolve (Path::parent is not free).
                let base = match kind {
                    BlockKind::Mesh => folder_of(&self.sources, file),
                    _ => Path::new(""),
                };
                let shape = objects::shape(kind, &p, base, &mut self.diags);
                let transform: DMat4 = objects::transform(&p, &mut self.diags);
                let velocity = objects::velocity(&p);
                if let (Some(shape), Some(material)) = (shape, material) {
                    if matches!(shape, Shape::Plane { .. })
                        && self.materials[material].is_emissive()
                    {
                        self.diags.push(
                            Diagnostic::error(codes::DEGENERATE, "an infinite plane cannot emit light", kind_span)
                                .with_label("this plane has an emissive material")
                                .with_help("use a `quad` or a `disk` as an area light, or `background` for light from everywhere"),
                        );
                        return;
                    }
                    self.objects.push(Object {
                        shape,
                        material,
                        transform,
                        velocity,
                        span,
                    });
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
            None => {
                self.materials.push(Material::default_at(span));
                Some(self.materials.len() - 1)
            }
            Some((MaterialRef::Named(name), _)) => {
                match self.material_names.get(&name.name) {
                    Some(m) => {
                        self.used_materials.insert(m.index);
                        Some(m.index)
                    }
                    None => {
                        let help = match did_you_mean(&name.name, self.material_names.keys().map(String::as_str)) {
                        Some(s) => format!("did you mean `{s}`?"),
                        None => format!("declare it before this object: `material {} {{ diffuse rgb 0.8 }}`", name.name),
                    };
                        self.diags.push(
                            Diagnostic::error(
                                codes::UNKNOWN_MATERIAL,
                                format!("unknown material `{}`", name.name),
                                name.span,
                            )
                            .with_label("no material with this name")
                            .with_help(help),
                        );
                        None
                    }
                }
            }
            Some((MaterialRef::Inline(block), s)) => {
                let p = Params::collect(
                    "material",
                    *s,
                    block,
                    &blocks::material_schema(),
                    &mut self.env,
                    &mut self.diags,
                );
                let m = blocks::material(&p, None, *s, &mut self.diags);
                self.materials.push(m);
                let i = self.materials.len() - 1;
                self.used_materials.insert(i);
                Some(i)
            }
        }
    }
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
