//! Compile-time evaluation of expressions: numbers, vectors, colours,
//! strings, booleans, lists, functions, names and conditionals.
//!
//! Evaluation is bounded: expressions nest at most
//! [`crate::syntax::MAX_NESTING`] deep as written; calls of user
//! functions at most [`MAX_CALL_DEPTH`] deep (a recursion without an end
//! is a diagnostic, not a stack overflow) and [`MAX_CALLS`] in all; lists
//! and strings hold at most [`MAX_ITEMS`] items and [`MAX_STRING`] bytes.

use crate::diag::codes;
use crate::diag::{did_you_mean, Diagnostic, Diagnostics};
use crate::span::Span;
use crate::syntax::ast::{BinOp, Expr, ExprKind};
use std::collections::HashMap;
use std::sync::Arc;

/// Deepest nesting of calls of user functions (a function calling
/// itself counts each time): deep enough for any loop a recursion writes
/// by halves, shallow enough for the stack of the checker's thread.
pub const MAX_CALL_DEPTH: usize = 64;
/// Most calls of user functions in one compile (a recursion that branches
/// would otherwise take exponential time).
pub const MAX_CALLS: u64 = 1_000_000;
/// Most items one list may hold (and items all lists built may hold
/// together, so that doubling a list in a loop stays bounded).
pub const MAX_ITEMS: usize = 1_000_000;
/// Longest string (file names are built of strings).
pub const MAX_STRING: usize = 4096;

/// A user function: `fn name(params) = body;`.
#[derive(Debug, PartialEq)]
pub struct Function {
    /// Its name as declared.
    pub name: String,
    /// Its parameters' names.
    pub params: Vec<String>,
    /// Its value.
    pub body: Arc<Expr>,
}

/// A value computed from an expression.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// A number.
    Num(f64),
    /// A vector of 2 or more numbers.
    Vector(Vec<f64>),
    /// An RGB colour.
    Color([f64; 3]),
    /// A string.
    Str(String),
    /// A boolean.
    Bool(bool),
    /// A list of values (shared: copying a name copies a pointer).
    List(Arc<Vec<Value>>),
    /// A user function.
    Function(Arc<Function>),
}

impl Value {
    /// The type's name in messages ("a number", "a vector of 3", …).
    pub fn type_name(&self) -> String {
        match self {
            Value::Num(_) => "a number".into(),
            Value::Vector(v) => format!("a vector of {}", v.len()),
            Value::Color(_) => "a colour".into(),
            Value::Str(_) => "a string".into(),
            Value::Bool(_) => "a boolean".into(),
            Value::List(l) => format!("a list of {}", l.len()),
            Value::Function(f) => format!("the function `{}`", f.name),
        }
    }
}

/// One bound name: a constant or a loop variable.
#[derive(Debug, Clone)]
pub struct Binding {
    /// Its value (`None` when its definition had an error: uses stay silent).
    pub value: Option<Value>,
    /// Where it is declared (identifies it for the unused-constant warning).
    pub decl: Span,
}

/// Names in scope: a stack of frames (the file level, then one per loop
/// iteration or function call).
#[derive(Debug, Default)]
pub struct Env {
    frames: Vec<HashMap<String, Binding>>,
    /// The innermost frame a name may be looked up in besides the file
    /// level: a function's body sees its parameters and the file's names,
    /// not the caller's loop variables.
    base: usize,
    /// Calls of user functions under way.
    call_depth: usize,
    /// Calls of user functions made so far.
    calls: u64,
    /// List items built so far (of [`MAX_ITEMS`] × 16 in all).
    items: u64,
    /// A limit was reached: further calls fail silently (reported once).
    exhausted: bool,
    /// Evaluations under way, nested.
    depth: usize,
    /// Declarations that were read at least once.
    pub used: std::collections::HashSet<Span>,
    /// Declared textures (`texture name kind { … }`), with the span of
    /// each one's name.
    pub textures: HashMap<String, (super::scene::Texture, Span)>,
    /// Names every scene sees unless it binds them itself (`frame`,
    /// `clock`).
    pub predefined: Vec<(&'static str, Value)>,
}

impl Env {
    /// An environment with one (global) frame.
    pub fn new() -> Self {
        Env {
            frames: vec![HashMap::new()],
            used: Default::default(),
            textures: HashMap::new(),
            ..Default::default()
        }
    }

    /// Opens a nested frame.
    pub fn push(&mut self) {
        self.frames.push(HashMap::new());
    }

    /// Closes the innermost frame.
    pub fn pop(&mut self) {
        self.frames.pop();
    }

    /// A binding in the innermost frame with this name, if any.
    pub fn in_current_frame(&self, name: &str) -> Option<&Binding> {
        self.frames.last().and_then(|f| f.get(name))
    }

    /// Binds a name in the innermost frame.
    pub fn bind(&mut self, name: &str, b: Binding) {
        self.frames
            .last_mut()
            .expect("at least one frame")
            .insert(name.to_string(), b);
    }

    /// Whether a constant or loop variable has this name.
    pub fn is_bound(&self, name: &str) -> bool {
        self.frames.iter().any(|f| f.contains_key(name))
    }

    /// The frames a name is looked up in, innermost first.
    fn visible(&self) -> impl Iterator<Item = &HashMap<String, Binding>> {
        let inner = self.frames[self.base.max(1).min(self.frames.len())..].iter();
        inner.rev().chain(self.frames.first())
    }

    /// Looks a name up, innermost first, marking it used.
    pub fn lookup(&mut self, name: &str) -> Option<Option<Value>> {
        let Some(b) = self.visible().find_map(|f| f.get(name)) else {
            let predefined = self.predefined.iter().find(|(n, _)| *n == name);
            return predefined.map(|(_, v)| Some(v.clone()));
        };
        let (decl, value) = (b.decl, b.value.clone());
        self.used.insert(decl);
        Some(value)
    }

    /// Every name in scope (for "did you mean").
    pub fn names(&self) -> Vec<String> {
        (self.visible().flat_map(|f| f.keys()))
            .chain(self.textures.keys())
            .cloned()
            .chain(self.predefined.iter().map(|(n, _)| n.to_string()))
            .collect()
    }
}

/// The built-in functions: name, least and most number of arguments.
pub const FUNCTIONS: &[(&str, (usize, usize))] = &[
    ("sin", (1, 1)),
    ("cos", (1, 1)),
    ("tan", (1, 1)),
    ("asin", (1, 1)),
    ("acos", (1, 1)),
    ("atan2", (2, 2)),
    ("sqrt", (1, 1)),
    ("pow", (2, 2)),
    ("exp", (1, 1)),
    ("log", (1, 1)),
    ("abs", (1, 1)),
    ("min", (2, 2)),
    ("max", (2, 2)),
    ("clamp", (3, 3)),
    ("floor", (1, 1)),
    ("ceil", (1, 1)),
    ("round", (1, 1)),
    ("radians", (1, 1)),
    ("degrees", (1, 1)),
    ("normalize", (1, 1)),
    ("length", (1, 1)),
    ("dot", (2, 2)),
    ("cross", (2, 2)),
    ("len", (1, 1)),
    ("str", (1, 2)),
    ("rand", (2, 2)),
];

/// Deepest nesting of evaluation in all (expressions within expressions,
/// through calls): what the brackets of one expression allow
/// ([`crate::syntax::MAX_NESTING`], each bracket a few levels) a few
/// times over, within the stack of a 2 MiB thread.
pub const MAX_EVAL_DEPTH: usize = 1024;

/// Evaluates `e`; on failure the reason is in `diags` and `None` is returned.
pub fn eval(e: &Expr, env: &mut Env, diags: &mut Diagnostics) -> Option<Value> {
    if env.depth >= MAX_EVAL_DEPTH {
        if !env.exhausted {
            env.exhausted = true;
            diags.push(
                Diagnostic::error(
                    codes::RECURSION_LIMIT,
                    format!("evaluation nests deeper than {MAX_EVAL_DEPTH} levels"),
                    e.span,
                )
                .with_label("too deep here")
                .with_help("functions that call functions multiply the depth of their expressions; use `let` for parts of them"),
            );
        }
        return None;
    }
    env.depth += 1;
    let v = eval_inner(e, env, diags);
    env.depth -= 1;
    finite(v?, e.span, matches!(e.kind, ExprKind::Number(_)), diags)
}

/// Evaluates a condition: `Some(true or false)`, or `None` after a
/// diagnostic (not a boolean, or broken).
pub fn condition(e: &Expr, env: &mut Env, diags: &mut Diagnostics) -> Option<bool> {
    match eval(e, env, diags)? {
        Value::Bool(b) => Some(b),
        other => {
            diags.push(
                Diagnostic::error(
                    codes::TYPE_MISMATCH,
                    format!(
                        "a condition must be `true` or `false`, found {}",
                        other.type_name()
                    ),
                    e.span,
                )
                .with_label(format!("this is {}", other.type_name()))
                .with_help("compare values to make a condition: `x > 0`, `name == \"final\"`"),
            );
            None
        }
    }
}

/// `v` if every number in it is finite; else reports it at `span` (the
/// smallest expression that produced it) and returns `None`.
fn finite(v: Value, span: Span, literal: bool, diags: &mut Diagnostics) -> Option<Value> {
    let ok = match &v {
        Value::Num(x) => x.is_finite(),
        Value::Vector(v) => v.iter().all(|x| x.is_finite()),
        Value::Color(c) => c.iter().all(|x| x.is_finite()),
        _ => true,
    };
    if ok {
        return Some(v);
    }
    let (msg, help) = if literal {
        (
            "number too large",
            "numbers must fit a 64-bit float (about 1.8e308)",
        )
    } else {
        (
            "expression is not a finite number",
            "the result is infinite or NaN; check for overflow, sqrt of a negative or a zero denominator",
        )
    };
    diags.push(
        Diagnostic::error(codes::NOT_FINITE, msg, span)
            .with_label("this is not finite")
            .with_help(help),
    );
    None
}

fn eval_inner(e: &Expr, env: &mut Env, diags: &mut Diagnostics) -> Option<Value> {
    match &e.kind {
        ExprKind::Number(x) => Some(Value::Num(*x)),
        ExprKind::Str(s) => Some(Value::Str(s.clone())),
        ExprKind::Bool(b) => Some(Value::Bool(*b)),
        ExprKind::Vector(items) => {
            let mut out = Vec::with_capacity(items.len());
            let mut ok = true;
            for it in items {
                match eval(it, env, diags) {
                    Some(Value::Num(x)) => out.push(x),
                    Some(other) => {
                        diags.push(
                            Diagnostic::error(
                                codes::TYPE_MISMATCH,
                                format!(
                                    "a vector component must be a number, found {}",
                                    other.type_name()
                                ),
                                it.span,
                            )
                            .with_label("not a number")
                            .with_help("vectors hold numbers: `<1, 2, 3>`"),
                        );
                        ok = false;
                    }
                    None => ok = false,
                }
            }
            ok.then_some(Value::Vector(out))
        }
        ExprKind::Color(inner) => match eval(inner, env, diags)? {
            Value::Num(x) => Some(Value::Color([x; 3])),
            Value::Vector(v) if v.len() == 3 => Some(Value::Color([v[0], v[1], v[2]])),
            Value::Color(c) => Some(Value::Color(c)),
            other => {
                diags.push(
                    Diagnostic::error(
                        codes::TYPE_MISMATCH,
                        format!(
                            "`rgb` needs a number or a vector of 3, found {}",
                            other.type_name()
                        ),
                        inner.span,
                    )
                    .with_label("not a grey level or an <r, g, b> triple")
                    .with_help("write `rgb <0.8, 0.2, 0.1>` or `rgb 0.5`"),
                );
                None
            }
        },
        ExprKind::Name(name) => {
            if let Some(v) = env.lookup(name) {
                return v;
            }
            let names = env.names();
            let mut d = Diagnostic::error(
                codes::UNKNOWN_NAME,
                format!("unknown name `{name}`"),
                e.span,
            )
            .with_label("not defined");
            d = match did_you_mean(name, names.iter().map(String::as_str)) {
                Some(s) => d.with_help(format!("did you mean `{s}`?")),
                None => d.with_help(format!("define it first with `let {name} = …;`")),
            };
            diags.push(d);
            None
        }
        ExprKind::Neg(inner) => match eval(inner, env, diags)? {
            Value::Num(x) => Some(Value::Num(-x)),
            Value::Vector(v) => Some(Value::Vector(v.iter().map(|x| -x).collect())),
            Value::Color(c) => Some(Value::Color(c.map(|x| -x))),
            other => {
                diags.push(
                    Diagnostic::error(
                        codes::TYPE_MISMATCH,
                        format!("cannot negate {}", other.type_name()),
                        e.span,
                    )
                    .with_label("`-` needs a number, vector or colour")
                    .with_help("remove the minus sign"),
                );
                None
            }
        },
        ExprKind::Not(inner) => match eval(inner, env, diags)? {
            Value::Bool(b) => Some(Value::Bool(!b)),
            other => {
                diags.push(
                    Diagnostic::error(
                        codes::TYPE_MISMATCH,
                        format!("`!` needs `true` or `false`, found {}", other.type_name()),
                        e.span,
                    )
                    .with_label(format!("this is {}", other.type_name()))
                    .with_help("`!` turns a condition around: `!(x > 0)`"),
                );
                None
            }
        },
        ExprKind::List(items) => {
            let mut out = Vec::with_capacity(items.len());
            let mut ok = true;
            for it in items {
                match eval(it, env, diags) {
                    Some(v) => out.push(v),
                    None => ok = false,
                }
            }
            if !ok {
                return None;
            }
            env.new_list(out, e.span, diags)
        }
        ExprKind::Index { base, indexes } => {
            let mut v = eval(base, env, diags)?;
            let mut at = base.span;
            for ix in indexes {
                let i = eval(ix, env, diags)?;
                v = index(v, i, at, ix.span, diags)?;
                at = at.join(ix.span);
            }
            Some(v)
        }
        ExprKind::If { arms, otherwise } => {
            // Only the chosen arm is evaluated: a recursion ends in the arm
            // that does not call again.
            for (cond, value) in arms {
                if condition(cond, env, diags)? {
                    return eval(value, env, diags);
                }
            }
            eval(otherwise, env, diags)
        }
        ExprKind::Chain { first, rest } if matches!(rest[0].0, BinOp::And | BinOp::Or) => {
            // `a && b && c` (or `||`): stops at the first operand that
            // decides, as in C and Rust, so `i < len(xs) && xs[i] > 0`
            // never indexes out of range.
            let and = rest[0].0 == BinOp::And;
            let operands = std::iter::once(&**first).chain(rest.iter().map(|r| &r.2));
            for operand in operands {
                if condition(operand, env, diags)? != and {
                    return Some(Value::Bool(!and));
                }
            }
            Some(Value::Bool(and))
        }
        ExprKind::Chain { first, rest } => {
            // Left to right, as `((a op b) op c) …`: every operand is
            // evaluated (all their mistakes reported), the fold stops at the
            // first failure.
            let mut acc = eval(first, env, diags);
            let mut acc_span = first.span;
            // `rgb 0.5 + 0.1` is `(rgb 0.5) + 0.1`: worth a hint when it fails.
            let mut bare_rgb = matches!(first.kind, ExprKind::Color(_));
            for (op, op_span, operand) in rest {
                let b = eval(operand, env, diags);
                let span = acc_span.join(operand.span);
                let at = Operands {
                    lhs: acc_span,
                    op: *op_span,
                    rhs: operand.span,
                    bare_rgb,
                };
                acc = match (acc, b) {
                    (Some(a), Some(b)) => {
                        binary(*op, a, b, at, diags).and_then(|v| finite(v, span, false, diags))
                    }
                    _ => None,
                };
                if acc
                    .as_ref()
                    .is_some_and(|v| !env.charge_items(v, span, diags))
                {
                    return None;
                }
                acc_span = span;
                bare_rgb = false;
            }
            acc
        }
        ExprKind::Call { func, args } => {
            let builtin = FUNCTIONS.iter().find(|(n, _)| *n == func.name);
            match env.lookup(&func.name) {
                Some(Some(Value::Function(f))) => return call_user(&f, args, e.span, env, diags),
                // Its declaration failed and said why.
                Some(None) if builtin.is_none() => return None,
                Some(Some(v)) if builtin.is_none() => {
                    diags.push(
                        Diagnostic::error(
                            codes::TYPE_MISMATCH,
                            format!("`{}` is not a function", func.name),
                            func.span,
                        )
                        .with_label(format!("this is {}", v.type_name()))
                        .with_help("declare a function with `fn name(x) = …;`"),
                    );
                    return None;
                }
                _ => {}
            }
            let Some(&(_, (least, most))) = builtin else {
                let user: Vec<String> = env.names();
                let names = FUNCTIONS
                    .iter()
                    .map(|(n, _)| *n)
                    .chain(user.iter().map(String::as_str));
                let help = match did_you_mean(&func.name, names) {
                    Some(s) => format!("did you mean `{s}`?"),
                    None => format!(
                        "the built-in functions are {}; declare your own with `fn {}(x) = …;`",
                        FUNCTIONS
                            .iter()
                            .map(|(n, _)| *n)
                            .collect::<Vec<_>>()
                            .join(", "),
                        func.name
                    ),
                };
                diags.push(
                    Diagnostic::error(
                        codes::UNKNOWN_FUNCTION,
                        format!("unknown function `{}`", func.name),
                        func.span,
                    )
                    .with_label("no such function")
                    .with_help(help),
                );
                return None;
            };
            if !(least..=most).contains(&args.len()) {
                let takes = if least == most {
                    format!("{least} argument{}", if least == 1 { "" } else { "s" })
                } else {
                    format!("{least} or {most} arguments")
                };
                diags.push(
                    Diagnostic::error(
                        codes::WRONG_ARGUMENT_COUNT,
                        format!("`{}` takes {takes}, found {}", func.name, args.len()),
                        e.span,
                    )
                    .with_label("wrong number of arguments")
                    .with_help(format!(
                        "call it as `{}({})`",
                        func.name,
                        vec!["x"; least].join(", ")
                    )),
                );
                return None;
            }
            let mut vals = Vec::new();
            for a in args {
                vals.push(eval(a, env, diags));
            }
            let vals: Option<Vec<Value>> = vals.into_iter().collect();
            call(&func.name, &vals?, args, e.span, diags)
        }
    }
}

impl Env {
    /// A list of `items`, counted against the items all lists may hold.
    fn new_list(
        &mut self,
        items: Vec<Value>,
        span: Span,
        diags: &mut Diagnostics,
    ) -> Option<Value> {
        let v = Value::List(Arc::new(items));
        self.charge_items(&v, span, diags).then_some(v)
    }

    /// Counts a list or string just built against what all values built
    /// may hold ([`MAX_ITEMS`] items per list, twice that in all; a
    /// string's 16 bytes as one item): `false`, after a diagnostic, when
    /// it is too large.
    fn charge_items(&mut self, v: &Value, span: Span, diags: &mut Diagnostics) -> bool {
        let n = match v {
            Value::List(l) => l.len(),
            Value::Str(s) => s.len() / 16,
            _ => return true,
        };
        self.items += n as u64;
        if n <= MAX_ITEMS && self.items <= 2 * MAX_ITEMS as u64 {
            return true;
        }
        diags.push(too_large(format!("this is {}", v.type_name()), span));
        false
    }
}

/// The error for a list or string past its bound ([`MAX_ITEMS`],
/// [`MAX_STRING`], the items of all lists together), labelled `label`.
fn too_large(label: String, span: Span) -> Diagnostic {
    Diagnostic::error(
        codes::VALUE_TOO_LARGE,
        format!(
            "lists hold at most {} items, all lists and strings of a scene together {}, a string {} bytes",
            super::group_digits(MAX_ITEMS as u64),
            super::group_digits(2 * MAX_ITEMS as u64),
            super::group_digits(MAX_STRING as u64)
        ),
        span,
    )
    .with_label(label)
    .with_help("large generated data belongs in a mesh file; strings name files and words")
}

/// Calls the user function `f` with `args` (evaluated here, in the
/// caller's scope); its body sees its parameters and the file's names.
fn call_user(
    f: &Function,
    args: &[Expr],
    span: Span,
    env: &mut Env,
    diags: &mut Diagnostics,
) -> Option<Value> {
    if args.len() != f.params.len() {
        diags.push(
            Diagnostic::error(
                codes::WRONG_ARGUMENT_COUNT,
                format!(
                    "`{}` takes {} argument{}, found {}",
                    f.name,
                    f.params.len(),
                    if f.params.len() == 1 { "" } else { "s" },
                    args.len()
                ),
                span,
            )
            .with_label("wrong number of arguments")
            .with_help(format!("call it as `{}({})`", f.name, f.params.join(", "))),
        );
        return None;
    }
    let mut vals = Vec::with_capacity(args.len());
    for a in args {
        vals.push(eval(a, env, diags));
    }
    let vals: Vec<Value> = vals.into_iter().collect::<Option<_>>()?;
    if env.exhausted {
        return None;
    }
    env.calls += 1;
    if env.call_depth >= MAX_CALL_DEPTH || env.calls > MAX_CALLS {
        env.exhausted = true;
        let (message, help) = if env.call_depth >= MAX_CALL_DEPTH {
            (
                format!("calls of functions nest deeper than {MAX_CALL_DEPTH}"),
                "a function that calls itself needs an `if` whose other arm stops calling: `fn f(n) = if n <= 0 { 1 } else { n * f(n - 1) };`",
            )
        } else {
            (
                format!("functions are called more than {MAX_CALLS} times"),
                "a function that calls itself twice doubles its calls at every level; compute such values with a loop",
            )
        };
        diags.push(
            Diagnostic::error(codes::RECURSION_LIMIT, message, span)
                .with_label(format!("in this call of `{}`", f.name))
                .with_help(help),
        );
        return None;
    }
    let outer_base = env.base;
    env.push();
    env.base = env.frames.len() - 1;
    env.call_depth += 1;
    for (name, v) in f.params.iter().zip(vals) {
        env.bind(
            name,
            Binding {
                value: Some(v),
                decl: span,
            },
        );
    }
    let v = eval(&f.body, env, diags);
    env.call_depth -= 1;
    env.base = outer_base;
    env.pop();
    v
}

/// `v[i]`: an item of a list, a component of a vector or colour, a
/// character of a string.
fn index(v: Value, i: Value, at: Span, i_span: Span, diags: &mut Diagnostics) -> Option<Value> {
    let len = match &v {
        Value::List(l) => l.len(),
        Value::Vector(x) => x.len(),
        Value::Color(_) => 3,
        Value::Str(s) => s.chars().count(),
        other => {
            diags.push(
                Diagnostic::error(
                    codes::TYPE_MISMATCH,
                    format!("cannot index {}", other.type_name()),
                    at,
                )
                .with_label(format!("this is {}", other.type_name()))
                .with_help("lists, vectors, colours and strings are indexed: `xs[0]`"),
            );
            return None;
        }
    };
    let k = match i {
        Value::Num(x) if x.fract() == 0.0 => x,
        other => {
            diags.push(
                Diagnostic::error(
                    codes::TYPE_MISMATCH,
                    format!(
                        "an index must be a whole number, found {}",
                        match other {
                            Value::Num(x) => format!("{x}"),
                            o => o.type_name(),
                        }
                    ),
                    i_span,
                )
                .with_label("not a whole number")
                .with_help("index from 0: `xs[0]` is the first item; `floor` rounds down"),
            );
            return None;
        }
    };
    if k < 0.0 || k >= len as f64 {
        diags.push(
            Diagnostic::error(
                codes::INDEX_OUT_OF_RANGE,
                format!("index {k} is out of range for {}", v.type_name()),
                i_span,
            )
            .with_label(if len == 0 {
                "it is empty".to_string()
            } else {
                format!("valid indexes are 0 to {}", len - 1)
            })
            .with_secondary(at, v.type_name())
            .with_help("index from 0; `len(xs)` is one past the last index"),
        );
        return None;
    }
    let k = k as usize;
    Some(match v {
        Value::List(l) => l[k].clone(),
        Value::Vector(x) => Value::Num(x[k]),
        Value::Color(c) => Value::Num(c[k]),
        Value::Str(s) => Value::Str(s.chars().nth(k).map(String::from).unwrap_or_default()),
        _ => unreachable!("checked above"),
    })
}

/// `v` as text: whole numbers without a fraction (zero-padded to `width`
/// digits), other numbers as the shortest decimal that reads back the same,
/// strings as they are, other values as they are written in a scene.
pub fn format_value(v: &Value, width: usize) -> String {
    let number = |x: f64| {
        if x.fract() == 0.0 && x.abs() < 1e15 {
            let digits = format!("{:0width$}", (x as i64).unsigned_abs());
            if x < 0.0 {
                format!("-{digits}")
            } else {
                digits
            }
        } else {
            format!("{x}")
        }
    };
    let join = |xs: &[f64]| xs.iter().map(|&x| number(x)).collect::<Vec<_>>().join(", ");
    match v {
        Value::Num(x) => number(*x),
        Value::Str(s) => s.clone(),
        Value::Bool(b) => b.to_string(),
        Value::Vector(xs) => format!("<{}>", join(xs)),
        Value::Color(c) => format!("rgb <{}>", join(c)),
        Value::List(l) => {
            let items: Vec<String> = l.iter().map(|x| format_value(x, 0)).collect();
            format!("[{}]", items.join(", "))
        }
        Value::Function(f) => format!("fn {}", f.name),
    }
}

/// A random number in [0, 1) that depends only on `seed` and `index`: the
/// same scene always makes the same forest. The two numbers' bits are
/// mixed by SplitMix64's finaliser (Steele, Lea and Flood 2014, "Fast
/// splittable pseudorandom number generators"), applied twice; the top 53
/// bits are the fraction.
pub fn random(seed: f64, index: f64) -> f64 {
    fn mix(mut z: u64) -> u64 {
        z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    // +0.0 for -0.0: the two are equal, so they give the same number.
    let bits = |x: f64| (x + 0.0).to_bits();
    let h = mix(mix(bits(seed)) ^ bits(index));
    (h >> 11) as f64 / (1u64 << 53) as f64
}

/// Where the parts of one operation are written.
#[derive(Debug, Clone, Copy)]
struct Operands {
    /// The left operand (everything folded so far).
    lhs: Span,
    /// The operator.
    op: Span,
    /// The right operand.
    rhs: Span,
    /// Whether the left operand is a bare `rgb x`, which takes only `x`.
    bare_rgb: bool,
}

/// A type mismatch labelled at the operator (so that the operands' labels
/// fall under the operands, not all at the end of the expression).
fn mismatch(at: Operands, msg: String, help: &str) -> Diagnostic {
    let help = if at.bare_rgb {
        "`rgb` takes only the value right after it (`rgb 0.5 + 0.1` is `(rgb 0.5) + 0.1`): to make a colour of the whole expression, put it in brackets, `rgb (0.5 + 0.1)`"
    } else {
        help
    };
    Diagnostic::error(codes::TYPE_MISMATCH, msg, at.op)
        .with_label("incompatible operands")
        .with_help(help.to_string())
}

fn binary(op: BinOp, a: Value, b: Value, at: Operands, diags: &mut Diagnostics) -> Option<Value> {
    let (a_span, b_span) = (at.lhs, at.rhs);
    use Value::*;
    match (op, &a, &b) {
        (BinOp::Eq, _, _) => return Some(Bool(a == b)),
        (BinOp::Ne, _, _) => return Some(Bool(a != b)),
        (BinOp::Lt | BinOp::Le | BinOp::Gt | BinOp::Ge, Num(x), Num(y)) => {
            return Some(Bool(match op {
                BinOp::Lt => x < y,
                BinOp::Le => x <= y,
                BinOp::Gt => x > y,
                _ => x >= y,
            }))
        }
        (BinOp::Lt | BinOp::Le | BinOp::Gt | BinOp::Ge, _, _) => {
            diags.push(
                mismatch(
                    at,
                    format!(
                        "cannot order {} and {} with `{}`",
                        a.type_name(),
                        b.type_name(),
                        op.symbol()
                    ),
                    "`<`, `<=`, `>` and `>=` compare numbers; `==` and `!=` compare any two values",
                )
                .with_secondary(a_span, a.type_name())
                .with_secondary(b_span, b.type_name()),
            );
            return None;
        }
        (BinOp::Add, Str(x), Str(y)) => {
            if x.len() + y.len() > MAX_STRING {
                let n = x.len() + y.len();
                diags.push(too_large(format!("{n} bytes"), a_span.join(b_span)));
                return None;
            }
            return Some(Str(format!("{x}{y}")));
        }
        (BinOp::Add, Str(_), _) | (BinOp::Add, _, Str(_)) => {
            diags.push(
                mismatch(
                    at,
                    format!("cannot add {} and {}", a.type_name(), b.type_name()),
                    "strings join with strings: turn a number into one with `str(x)`, as in `\"tree\" + str(i) + \".obj\"`",
                )
                .with_secondary(a_span, a.type_name())
                .with_secondary(b_span, b.type_name()),
            );
            return None;
        }
        (BinOp::Add, List(x), List(y)) => {
            // Counted against the items of all lists by the caller's
            // `new_list`; here only the length of one list is bounded.
            if x.len() + y.len() > MAX_ITEMS {
                let n = x.len() + y.len();
                diags.push(too_large(format!("a list of {n}"), a_span.join(b_span)));
                return None;
            }
            return Some(List(Arc::new(x.iter().chain(y.iter()).cloned().collect())));
        }
        (BinOp::And | BinOp::Or, _, _) => unreachable!("`&&` and `||` are evaluated lazily"),
        _ => {}
    }
    let f = |x: f64, y: f64| match op {
        BinOp::Add => x + y,
        BinOp::Sub => x - y,
        BinOp::Mul => x * y,
        BinOp::Div => x / y,
        BinOp::Rem => x % y,
        _ => unreachable!("comparisons are handled above"),
    };
    if matches!(op, BinOp::Div | BinOp::Rem) {
        let zero = match &b {
            Num(y) => *y == 0.0,
            Vector(v) => v.contains(&0.0),
            Color(c) => c.contains(&0.0),
            _ => false,
        };
        if zero {
            diags.push(
                Diagnostic::error(codes::DIVISION_BY_ZERO, "division by zero", b_span)
                    .with_label("this is zero")
                    .with_help("divide by a non-zero value"),
            );
            return None;
        }
    }
    let additive = matches!(op, BinOp::Add | BinOp::Sub);
    let r = match (a, b) {
        (Num(x), Num(y)) => Num(f(x, y)),
        (Vector(u), Vector(v)) if u.len() == v.len() => {
            Vector(u.iter().zip(&v).map(|(x, y)| f(*x, *y)).collect())
        }
        (Color(u), Color(v)) => Color([f(u[0], v[0]), f(u[1], v[1]), f(u[2], v[2])]),
        (Vector(u), Num(y)) if !additive => Vector(u.iter().map(|x| f(*x, y)).collect()),
        (Num(x), Vector(v)) if op == BinOp::Mul => Vector(v.iter().map(|y| f(x, *y)).collect()),
        (Color(u), Num(y)) if !additive => Color(u.map(|x| f(x, y))),
        (Num(x), Color(v)) if op == BinOp::Mul => Color(v.map(|y| f(x, y))),
        (Vector(u), Vector(v)) => {
            diags.push(
                mismatch(
                    at,
                    format!(
                        "cannot apply `{}` to vectors of {} and {} components",
                        op.symbol(),
                        u.len(),
                        v.len()
                    ),
                    "both vectors must have the same number of components",
                )
                .with_secondary(a_span, format!("{} components", u.len()))
                .with_secondary(b_span, format!("{} components", v.len())),
            );
            return None;
        }
        (x, y) => {
            diags.push(
                mismatch(
                    at,
                    format!(
                        "cannot apply `{}` to {} and {}",
                        op.symbol(),
                        x.type_name(),
                        y.type_name()
                    ),
                    "numbers, vectors and colours combine with themselves; vectors and colours can be scaled by a number",
                )
                .with_secondary(a_span, x.type_name())
                .with_secondary(b_span, y.type_name()),
            );
            return None;
        }
    };
    Some(r)
}

fn call(
    name: &str,
    vals: &[Value],
    args: &[Expr],
    span: Span,
    diags: &mut Diagnostics,
) -> Option<Value> {
    use Value::*;
    let num = |i: usize, diags: &mut Diagnostics| -> Option<f64> {
        match &vals[i] {
            Num(x) => Some(*x),
            other => {
                diags.push(
                    Diagnostic::error(
                        codes::TYPE_MISMATCH,
                        format!("`{name}` needs a number, found {}", other.type_name()),
                        args[i].span,
                    )
                    .with_label("expected a number")
                    .with_help(format!("pass a number to `{name}`")),
                );
                None
            }
        }
    };
    let vec3 = |i: usize, diags: &mut Diagnostics| -> Option<[f64; 3]> {
        match &vals[i] {
            Vector(v) if v.len() == 3 => Some([v[0], v[1], v[2]]),
            other => {
                diags.push(
                    Diagnostic::error(
                        codes::TYPE_MISMATCH,
                        format!("`{name}` needs a vector of 3, found {}", other.type_name()),
                        args[i].span,
                    )
                    .with_label("expected a vector <x, y, z>")
                    .with_help(format!("pass a vector such as `<0, 1, 0>` to `{name}`")),
                );
                None
            }
        }
    };
    let dot3 = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    Some(match name {
        "sin" => Num(num(0, diags)?.sin()),
        "cos" => Num(num(0, diags)?.cos()),
        "tan" => Num(num(0, diags)?.tan()),
        "sqrt" => {
            let x = num(0, diags)?;
            if x < 0.0 {
                diags.push(
                    Diagnostic::error(
                        codes::DOMAIN,
                        "square root of a negative number",
                        args[0].span,
                    )
                    .with_label(format!("this is {x}"))
                    .with_help("sqrt needs a value ≥ 0"),
                );
                return None;
            }
            Num(x.sqrt())
        }
        "pow" => Num(num(0, diags)?.powf(num(1, diags)?)),
        "asin" | "acos" => {
            let x = num(0, diags)?;
            if !(-1.0..=1.0).contains(&x) {
                diags.push(
                    Diagnostic::error(
                        codes::DOMAIN,
                        format!("`{name}` of a number outside [-1, 1]"),
                        args[0].span,
                    )
                    .with_label(format!("this is {x}"))
                    .with_help(format!("`{name}` takes a sine or cosine, between -1 and 1")),
                );
                return None;
            }
            Num(if name == "asin" { x.asin() } else { x.acos() })
        }
        "atan2" => Num(num(0, diags)?.atan2(num(1, diags)?)),
        "exp" => Num(num(0, diags)?.exp()),
        "log" => {
            let x = num(0, diags)?;
            if x <= 0.0 {
                diags.push(
                    Diagnostic::error(
                        codes::DOMAIN,
                        "logarithm of a number that is not positive",
                        args[0].span,
                    )
                    .with_label(format!("this is {x}"))
                    .with_help("log needs a value > 0"),
                );
                return None;
            }
            Num(x.ln())
        }
        "clamp" => {
            let (x, lo, hi) = (num(0, diags)?, num(1, diags)?, num(2, diags)?);
            if lo > hi {
                diags.push(
                    Diagnostic::error(
                        codes::DOMAIN,
                        "`clamp` with its low bound above its high bound",
                        args[1].span.join(args[2].span),
                    )
                    .with_label(format!("{lo} > {hi}"))
                    .with_help("call it as `clamp(x, low, high)`"),
                );
                return None;
            }
            Num(x.clamp(lo, hi))
        }
        "floor" => Num(num(0, diags)?.floor()),
        "ceil" => Num(num(0, diags)?.ceil()),
        "round" => Num(num(0, diags)?.round()),
        "len" => match &vals[0] {
            List(l) => Num(l.len() as f64),
            Vector(v) => Num(v.len() as f64),
            Str(t) => Num(t.chars().count() as f64),
            Color(_) => Num(3.0),
            other => {
                diags.push(
                    Diagnostic::error(
                        codes::TYPE_MISMATCH,
                        format!(
                            "`len` needs a list, vector or string, found {}",
                            other.type_name()
                        ),
                        args[0].span,
                    )
                    .with_label(format!("this is {}", other.type_name()))
                    .with_help("`len(xs)` counts the items of a list"),
                );
                return None;
            }
        },
        "str" => {
            let width = match vals.get(1) {
                None => 0,
                Some(_) => {
                    let w = num(1, diags)?;
                    if !(w.fract() == 0.0 && (0.0..=32.0).contains(&w)) {
                        diags.push(
                            Diagnostic::error(
                                codes::DOMAIN,
                                "a width must be a whole number from 0 to 32",
                                args[1].span,
                            )
                            .with_label(format!("this is {w}"))
                            .with_help("`str(7, 4)` is \"0007\""),
                        );
                        return None;
                    }
                    w as usize
                }
            };
            Str(format_value(&vals[0], width))
        }
        "rand" => Num(random(num(0, diags)?, num(1, diags)?)),
        "abs" => Num(num(0, diags)?.abs()),
        "min" => Num(num(0, diags)?.min(num(1, diags)?)),
        "max" => Num(num(0, diags)?.max(num(1, diags)?)),
        "radians" => Num(num(0, diags)?.to_radians()),
        "degrees" => Num(num(0, diags)?.to_degrees()),
        "length" => Num(dot3(vec3(0, diags)?, vec3(0, diags)?).sqrt()),
        "normalize" => {
            let v = vec3(0, diags)?;
            let l = dot3(v, v).sqrt();
            if l == 0.0 {
                diags.push(
                    Diagnostic::error(
                        codes::DOMAIN,
                        "cannot normalize a zero vector",
                        args[0].span,
                    )
                    .with_label("this vector has length 0")
                    .with_help("pass a non-zero vector"),
                );
                return None;
            }
            Vector(v.iter().map(|x| x / l).collect())
        }
        "dot" => Num(dot3(vec3(0, diags)?, vec3(1, diags)?)),
        "cross" => {
            let a = vec3(0, diags)?;
            let b = vec3(1, diags)?;
            Vector(vec![
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ])
        }
        other => unreachable!("function table and evaluator disagree on `{other}` at {span:?}"),
    })
}

#[cfg(test)]
mod tests {
    use crate::check::{check_str, Shape};
    use crate::diag::codes;
    use std::path::Path;

    /// The value of `expr` used as a sphere's radius.
    fn radius(expr: &str) -> f64 {
        let src = format!(
            "camera {{ position <0, 0, 5> look_at <0, 0, 0> }}\n\
             sphere {{ center <0, 0, 0> radius {expr} }}\n"
        );
        let c = check_str(Path::new("t.pts"), &src);
        let scene = c
            .scene
            .unwrap_or_else(|| panic!("{}", c.diagnostics.render_human(&c.sources, false)));
        match scene.objects[0].shape {
            Shape::Sphere { radius, .. } => radius,
            ref s => panic!("not a sphere: {s:?}"),
        }
    }

    /// The value of `expr` after the statements `before`, or the first
    /// diagnostic's code.
    fn value(before: &str, expr: &str) -> Result<super::Value, String> {
        use crate::syntax::ast::Statement;
        let src = format!("{before}\nlet v__ = {expr};");
        let file =
            crate::syntax::parse(crate::source::FileId(0), &src).map_err(|d| d.code.to_string())?;
        let mut env = super::Env::new();
        let mut diags = crate::diag::Diagnostics::new();
        let mut out = None;
        for st in &file.statements {
            match st {
                Statement::Let { name, value, .. } => {
                    let v = super::eval(value, &mut env, &mut diags);
                    if name.name == "v__" {
                        out = v.clone();
                    }
                    let decl = name.span;
                    env.bind(&name.name, super::Binding { value: v, decl });
                }
                Statement::Function {
                    name, params, body, ..
                } => {
                    let f = super::Function {
                        name: name.name.clone(),
                        params: params.iter().map(|p| p.name.clone()).collect(),
                        body: body.clone(),
                    };
                    let value = Some(super::Value::Function(std::sync::Arc::new(f)));
                    env.bind(
                        &name.name,
                        super::Binding {
                            value,
                            decl: name.span,
                        },
                    );
                }
                _ => {}
            }
        }
        match diags.items.first() {
            Some(d) => Err(d.code.to_string()),
            None => Ok(out.expect("a value")),
        }
    }

    fn num(before: &str, expr: &str) -> f64 {
        match value(before, expr) {
            Ok(super::Value::Num(x)) => x,
            other => panic!("{expr}: {other:?}"),
        }
    }

    fn boolean(expr: &str) -> bool {
        match value("", expr) {
            Ok(super::Value::Bool(b)) => b,
            other => panic!("{expr}: {other:?}"),
        }
    }

    #[test]
    fn comparisons_and_logic_bind_below_arithmetic() {
        for (expr, want) in [
            ("1 + 1 == 2", true),
            ("2 * 3 < 5", false),
            ("1 < 2 && 2 < 3", true),
            ("1 > 2 || 2 < 3 && 3 < 4", true),
            ("(1 > 2 || 2 < 3) && 3 > 4", false),
            ("!(1 < 2)", false),
            ("!!true", true),
            ("1 <= 1 && 1 >= 1 && 1 != 2", true),
            ("<1, 2, 3> == <1, 2, 3>", true),
            ("[1, \"a\"] != [1, \"a\"]", false),
            ("\"ab\" == \"a\" + \"b\"", true),
            ("rgb 1 == rgb <1, 1, 1>", true),
        ] {
            assert_eq!(boolean(expr), want, "{expr}");
        }
        // `&&` and `||` stop at the first operand that decides: the right
        // side would fail (index out of range, division by zero).
        assert!(!boolean("[1][0] > 1 && [1][5] > 0"));
        assert!(boolean("true || 1 / 0 > 0"));
        assert_eq!(value("", "1 < true").unwrap_err(), codes::TYPE_MISMATCH);
        assert_eq!(value("", "1 && true").unwrap_err(), codes::TYPE_MISMATCH);
    }

    #[test]
    fn lists_index_and_measure() {
        let before = "let xs = [10, <1, 2, 3>, \"abc\", [4, 5]];";
        assert_eq!(num(before, "xs[0]"), 10.0);
        assert_eq!(num(before, "xs[1][2]"), 3.0);
        assert_eq!(num(before, "xs[3][1]"), 5.0);
        assert_eq!(num(before, "len(xs) + len(xs[2]) + len([])"), 7.0);
        assert_eq!(num(before, "len(xs + [1, 2])"), 6.0);
        assert_eq!(value(before, "xs[2][1]"), Ok(super::Value::Str("b".into())));
        assert_eq!(
            value(before, "xs[4]").unwrap_err(),
            codes::INDEX_OUT_OF_RANGE
        );
        assert_eq!(
            value(before, "xs[-1]").unwrap_err(),
            codes::INDEX_OUT_OF_RANGE
        );
        assert_eq!(value(before, "xs[0.5]").unwrap_err(), codes::TYPE_MISMATCH);
        assert_eq!(value(before, "xs[0][0]").unwrap_err(), codes::TYPE_MISMATCH);
    }

    #[test]
    fn conditionals_evaluate_only_the_chosen_arm() {
        assert_eq!(
            num(
                "let a = 2;",
                "if a < 1 { 10 } else if a < 3 { 20 } else { 30 }"
            ),
            20.0
        );
        assert_eq!(
            num(
                "let a = 5;",
                "if a < 1 { 10 } else if a < 3 { 20 } else { 30 }"
            ),
            30.0
        );
        // The arm not taken would divide by zero.
        assert_eq!(num("", "if true { 1 } else { 1 / 0 }"), 1.0);
        assert_eq!(
            value("", "if 1 { 1 } else { 2 }").unwrap_err(),
            codes::TYPE_MISMATCH
        );
    }

    #[test]
    fn functions_see_their_parameters_and_the_file_and_recurse_within_bounds() {
        let before = "let k = 3;\nfn scale(x) = x * k;\nfn fact(n) = if n <= 1 { 1 } else { n * fact(n - 1) };";
        assert_eq!(num(before, "scale(2)"), 6.0);
        assert_eq!(num(before, "fact(10)"), 3_628_800.0);
        assert_eq!(
            value(before, "fact(100)").unwrap_err(),
            codes::RECURSION_LIMIT
        );
        assert_eq!(
            value(before, "scale(1, 2)").unwrap_err(),
            codes::WRONG_ARGUMENT_COUNT
        );
        assert_eq!(value(before, "k(1)").unwrap_err(), codes::TYPE_MISMATCH);
        assert_eq!(
            value(before, "scal(1)").unwrap_err(),
            codes::UNKNOWN_FUNCTION
        );
        // A constant named like a built-in leaves the built-in callable.
        assert_eq!(num("let max = 1;", "max(max, 2)"), 2.0);
        // A function's body does not see its caller's names.
        assert_eq!(
            value("fn f(x) = x + y;\nfn g(y) = f(1);", "g(2)").unwrap_err(),
            codes::UNKNOWN_NAME
        );
    }

    #[test]
    fn strings_and_numbers_format() {
        let s = |expr: &str| match value("", expr) {
            Ok(super::Value::Str(s)) => s,
            other => panic!("{expr}: {other:?}"),
        };
        assert_eq!(s("\"frame_\" + str(7, 4) + \".png\""), "frame_0007.png");
        assert_eq!(s("str(-3, 3)"), "-003");
        assert_eq!(s("str(0.25)"), "0.25");
        assert_eq!(s("str(<1, 2.5, 3>)"), "<1, 2.5, 3>");
        assert_eq!(s("str([1, \"a\"])"), "[1, a]");
        assert_eq!(value("", "str(1, 40)").unwrap_err(), codes::DOMAIN);
        assert_eq!(value("", "\"a\" + 1").unwrap_err(), codes::TYPE_MISMATCH);
    }

    #[test]
    fn random_numbers_are_a_pure_function_of_seed_and_index() {
        let a: Vec<f64> = (0..1000).map(|i| super::random(7.0, i as f64)).collect();
        let b: Vec<f64> = (0..1000).map(|i| super::random(7.0, i as f64)).collect();
        assert_eq!(a, b);
        assert!(a.iter().all(|x| (0.0..1.0).contains(x)));
        // Another seed, another sequence; uniform enough to fill ten bins.
        assert_ne!(super::random(8.0, 0.0), a[0]);
        assert_eq!(super::random(-0.0, 3.0), super::random(0.0, 3.0));
        let mut bins = [0; 10];
        for x in &a {
            bins[(x * 10.0) as usize] += 1;
        }
        assert!(bins.iter().all(|&n| (70..130).contains(&n)), "{bins:?}");
        let mean = a.iter().sum::<f64>() / a.len() as f64;
        assert!((mean - 0.5).abs() < 0.03, "{mean}");
    }

    #[test]
    fn new_built_in_functions() {
        assert_eq!(num("", "floor(-1.5) + ceil(1.2) + round(2.5)"), 3.0);
        assert_eq!(num("", "clamp(5, 0, 1) + clamp(-1, 0, 1)"), 1.0);
        assert!((num("", "atan2(1, 1)") - std::f64::consts::FRAC_PI_4).abs() < 1e-12);
        assert!((num("", "exp(log(3))") - 3.0).abs() < 1e-12);
        assert!((num("", "asin(1) + acos(1)") - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
        assert_eq!(value("", "asin(2)").unwrap_err(), codes::DOMAIN);
        assert_eq!(value("", "log(0)").unwrap_err(), codes::DOMAIN);
        assert_eq!(value("", "clamp(0, 1, -1)").unwrap_err(), codes::DOMAIN);
    }

    #[test]
    fn operators_bind_and_associate_as_in_arithmetic() {
        // Each wrong precedence or associativity gives another (or a
        // negative, rejected) value.
        for (expr, want) in [
            ("10 - 2 * 3 - 1", 3.0),
            ("2 * 3 + 4 * 5", 26.0),
            ("1 - 2 + 3", 2.0),
            ("12 / 3 * 2", 8.0),
            ("8 / 2 / 2", 2.0),
            ("2 - -3", 5.0),
            ("-2 * -3", 6.0),
            ("- - 3", 3.0),
            ("-(1 - 3) * 2", 4.0),
            ("2 * (1 + 2) - 1", 5.0),
            ("1 + 2 * 3 * 2 - 4 / 2", 11.0),
            // `%` binds as `*` and `/`, with the sign of the dividend.
            ("7 % 4", 3.0),
            ("1 + 7 % 4 * 2", 7.0),
            ("7.5 % 2", 1.5),
            ("10 - -7 % 4", 13.0),
        ] {
            assert_eq!(radius(expr), want, "{expr}");
        }
    }
}
