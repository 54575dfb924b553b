//! Compile-time evaluation of expressions: numbers, vectors, colours,
//! strings, booleans, lists, functions, names and conditionals.
//!
//! Evaluation is bounded: expressions nest at most
//! [`crate::syntax::MAX_NESTING`] deep as written; calls of user
//! functions at most [`MAX_CALL_DEPTH`] deep (a recursion without an end
//! is a diagnostic, not a stack overflow) and [`MAX_CALLS`] in all; lists
//! and strings hold at most [`MAX_ITEMS`] items and [`MAX_STRING`] bytes,
//! lists nest at most [`MAX_LIST_DEPTH`] deep; and the work of all
//! evaluation together is bounded by a budget of steps
//! ([`budget::MAX_WORK`]), so that no expression, however small its text,
//! costs more than its share of it.

mod budget;
mod builtins;
mod value;

pub use budget::{MAX_SUGGESTIONS, MAX_WORK};
pub use builtins::{random, FUNCTIONS};
pub use value::{shown, Function, List, Value, MAX_LIST_DEPTH};

use crate::diag::codes;
use crate::diag::{did_you_mean, Diagnostic, Diagnostics};
use crate::span::Span;
use crate::syntax::ast::{BinOp, Expr, ExprKind};
use budget::Work;
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
    /// The steps of work evaluation may still take ([`MAX_WORK`] but for
    /// fuzzers).
    work: Work,
    /// The budget `work` started with, for the message.
    work_limit: u64,
    /// The work ran out (reported once).
    work_reported: bool,
    /// Names did-you-mean suggestions may still weigh.
    suggestions: Work,
    /// Loops and repeated includes running now: an expression they
    /// evaluate costs a step (one the text bounds does not).
    pub repeating: usize,
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
        Env::with_work(MAX_WORK)
    }

    /// An environment whose evaluation may take `steps` of work (a fuzzer
    /// keeps its inputs fast with a small budget; the rules are the same).
    pub fn with_work(steps: u64) -> Self {
        Env {
            frames: vec![HashMap::new()],
            work: Work::new(steps),
            work_limit: steps,
            suggestions: Work::new(MAX_SUGGESTIONS),
            ..Default::default()
        }
    }

    /// Takes `steps` of the work budget for work done at `span`: `false`,
    /// after the error (reported once), when the budget is spent.
    pub fn charge(&mut self, steps: u64, span: Span, diags: &mut Diagnostics) -> bool {
        if self.work.take(steps) {
            return true;
        }
        self.out_of_work(span, diags);
        false
    }

    /// Reports the work budget spent at `span` (once).
    fn out_of_work(&mut self, span: Span, diags: &mut Diagnostics) {
        if !self.work_reported {
            self.work_reported = true;
            diags.push(budget::out_of_work(self.work_limit, span));
        }
    }

    /// The closest of `candidates` to `word` for a "did you mean" help,
    /// while the suggestions' budget lasts (`count` is how many there are):
    /// an error with a suggestion costs the names it weighs.
    pub fn suggest<'a>(
        &mut self,
        word: &str,
        count: usize,
        candidates: impl IntoIterator<Item = &'a str>,
    ) -> Option<&'a str> {
        if !self.suggestions.take(count as u64) {
            return None;
        }
        did_you_mean(word, candidates)
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

    /// The name in scope (or of `also`) closest to `word`, while the
    /// suggestions' budget lasts ([`Env::suggest`]).
    fn suggest_name(&mut self, word: &str, also: &[&str]) -> Option<String> {
        let count = self.name_count() + also.len();
        if !self.suggestions.take(count as u64) {
            return None;
        }
        let names = self.names();
        let candidates = (also.iter().copied()).chain(names.iter().map(String::as_str));
        did_you_mean(word, candidates).map(str::to_string)
    }

    /// How many names [`Env::names`] gives.
    fn name_count(&self) -> usize {
        let frames: usize = self.visible().map(HashMap::len).sum();
        frames + self.textures.len() + self.predefined.len()
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
    // An expression that a loop or a function runs again costs a step
    // (once, at the top level, its text bounds it); what an operation
    // makes costs by its size besides (`Env::made`).
    if (env.repeating > 0 || env.call_depth > 0) && !env.charge(1, e.span, diags) {
        return None;
    }
    env.depth += 1;
    let v = eval_inner(e, env, diags);
    env.depth -= 1;
    match e.kind {
        // What an operation computes is checked where it is computed (a
        // chain's every step, a built-in's result, a literal); a name, an
        // item or a function's result is a value checked before, and a
        // long vector is not walked again each time it is passed on.
        ExprKind::Number(_) => finite(v?, e.span, true, diags),
        _ => v,
    }
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
    let overflow = match &v {
        Value::Num(x) => x.is_infinite(),
        Value::Vector(v) => v.iter().any(|x| x.is_infinite()),
        Value::Color(c) => c.iter().any(|x| x.is_infinite()),
        _ => false,
    };
    let (msg, label, help) = match (literal, overflow) {
        (true, _) => (
            "number too large",
            "this is not finite",
            "numbers must fit a 64-bit float (about 1.8e308)",
        ),
        (false, true) => (
            "the result is too large: beyond the ±1.8e308 of a 64-bit float",
            "this overflows",
            "scale the values down, or divide by a larger number; `pow`, `exp` and products of large numbers grow fast",
        ),
        (false, false) => (
            "the result is not a number (NaN)",
            "this is NaN",
            "an intermediate value overflowed (∞ − ∞, 0 × ∞); scale the values down",
        ),
    };
    diags.push(
        Diagnostic::error(codes::NOT_FINITE, msg, span)
            .with_label(label)
            .with_help(help),
    );
    None
}

fn eval_inner(e: &Expr, env: &mut Env, diags: &mut Diagnostics) -> Option<Value> {
    match &e.kind {
        ExprKind::Number(x) => Some(Value::Num(*x)),
        ExprKind::Str(s) => {
            // A literal run again is copied again: a long one costs by its size.
            let v = Value::Str(s.as_str().into());
            let repeated = env.repeating > 0 || env.call_depth > 0;
            (!repeated || env.charge(v.weight(), e.span, diags)).then_some(v)
        }
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
            ok.then_some(Value::Vector(out.into()))
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
            let mut d = Diagnostic::error(
                codes::UNKNOWN_NAME,
                format!("unknown name `{name}`"),
                e.span,
            )
            .with_label("not defined");
            d = match env.suggest_name(name, &[]) {
                Some(s) => d.with_help(format!("did you mean `{s}`?")),
                None => d.with_help(format!("define it first with `let {name} = …;`")),
            };
            diags.push(d);
            None
        }
        ExprKind::Neg(inner) => match eval(inner, env, diags)? {
            Value::Num(x) => Some(Value::Num(-x)),
            Value::Vector(v) => {
                // Counted before it is made: a budget spent stops the work.
                let weight = Value::Vector(v.clone()).weight();
                if !env.charge(weight, e.span, diags) {
                    return None;
                }
                Some(Value::Vector(v.iter().map(|x| -x).collect()))
            }
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
                // A string is indexed by its characters, counted from its start.
                if matches!(v, Value::Str(_)) && !env.charge(v.weight(), at, diags) {
                    return None;
                }
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
                    (Some(a), Some(b)) => binary(*op, a, b, at, env, diags)
                        .and_then(|v| finite(v, span, false, diags)),
                    _ => None,
                };
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
                let built_in: Vec<&str> = FUNCTIONS.iter().map(|(n, _)| *n).collect();
                let help = match env.suggest_name(&func.name, &built_in) {
                    Some(s) => format!("did you mean `{s}`?"),
                    None => format!(
                        "the built-in functions are {}; declare your own with `fn {}(x) = …;`",
                        built_in.join(", "),
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
            builtins::call(&func.name, &vals?, args, e.span, env, diags)
                .and_then(|v| finite(v, e.span, false, diags))
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
        let list = List::new(items);
        if list.depth > MAX_LIST_DEPTH {
            diags.push(
                Diagnostic::error(
                    codes::VALUE_TOO_LARGE,
                    format!("lists nest at most {MAX_LIST_DEPTH} levels deep"),
                    span,
                )
                .with_label(format!("this list nests {} levels", list.depth))
                .with_help("a list of lists of lists… is walked level by level; keep the data flat (a list of vectors), or put it in a mesh file"),
            );
            return None;
        }
        let n = list.items.len();
        let v = Value::List(Arc::new(list));
        self.charge_items(n, span, diags).then_some(v)
    }

    /// Counts `n` items of a list (or 16 bytes of a string) about to be
    /// built at `span` against what all values built may hold
    /// ([`MAX_ITEMS`] items per list, twice that in all): `false`, after
    /// a diagnostic, when they are too many. Counted before the value is
    /// built, so that a refused one costs nothing.
    fn charge_items(&mut self, n: usize, span: Span, diags: &mut Diagnostics) -> bool {
        self.charge_items_as(n, || format!("this is a list of {n}"), span, diags)
    }

    /// [`Env::charge_items`], with the label of the error made by `label`.
    fn charge_items_as(
        &mut self,
        n: usize,
        label: impl FnOnce() -> String,
        span: Span,
        diags: &mut Diagnostics,
    ) -> bool {
        self.items += n as u64;
        if n <= MAX_ITEMS && self.items <= 2 * MAX_ITEMS as u64 {
            return true;
        }
        diags.push(too_large(label(), span));
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
        Value::List(l) => l.items.len(),
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
                            Value::Num(x) => value::shown(x),
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
                format!(
                    "index {} is out of range for {}",
                    value::shown(k),
                    v.type_name()
                ),
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
        Value::List(l) => l.items[k].clone(),
        Value::Vector(x) => Value::Num(x[k]),
        Value::Color(c) => Value::Num(c[k]),
        Value::Str(s) => {
            let c = s.chars().nth(k).map(String::from).unwrap_or_default();
            Value::Str(c.into())
        }
        _ => unreachable!("checked above"),
    })
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

fn binary(
    op: BinOp,
    a: Value,
    b: Value,
    at: Operands,
    env: &mut Env,
    diags: &mut Diagnostics,
) -> Option<Value> {
    let (a_span, b_span) = (at.lhs, at.rhs);
    use Value::*;
    match (op, &a, &b) {
        (BinOp::Eq | BinOp::Ne, _, _) => {
            // Two lists of a million items are compared item by item, each
            // a step of the budget: a loop of such comparisons stops.
            let Some(same) = value::equal(&a, &b, &mut env.work) else {
                env.out_of_work(a_span.join(b_span), diags);
                return None;
            };
            return Some(Bool(same == (op == BinOp::Eq)));
        }
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
            let (n, span) = (x.len() + y.len(), a_span.join(b_span));
            if n > MAX_STRING {
                diags.push(too_large(format!("{n} bytes"), span));
                return None;
            }
            let label = || "this is a string".to_string();
            if !(env.charge(n as u64 / 16, span, diags)
                && env.charge_items_as(n / 16, label, span, diags))
            {
                return None;
            }
            return Some(Str(format!("{x}{y}").into()));
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
            let (n, span) = (x.items.len() + y.items.len(), a_span.join(b_span));
            if n > MAX_ITEMS {
                diags.push(too_large(format!("a list of {n}"), span));
                return None;
            }
            // Counted before the copy: a refused one costs nothing.
            if !env.charge_items(n, span, diags) {
                return None;
            }
            return Some(Value::list(
                x.items.iter().chain(&y.items).cloned().collect(),
            ));
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
    // Each component of a vector is computed: counted before, so that a
    // budget spent stops the work.
    if !env.charge(a.weight().max(b.weight()), a_span.join(b_span), diags) {
        return None;
    }
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
            Vector(u.iter().zip(v.iter()).map(|(x, y)| f(*x, *y)).collect())
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

#[cfg(test)]
mod tests;
