//! Compile-time evaluation of expressions: numbers, vectors, colours,
//! strings, booleans, names and a few functions.

use crate::diag::codes;
use crate::diag::{did_you_mean, Diagnostic, Diagnostics};
use crate::span::Span;
use crate::syntax::ast::{BinOp, Expr, ExprKind};
use std::collections::HashMap;

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

/// Names in scope: a stack of frames (the file level, then one per loop iteration).
#[derive(Debug, Default)]
pub struct Env {
    frames: Vec<HashMap<String, Binding>>,
    /// Declarations that were read at least once.
    pub used: std::collections::HashSet<Span>,
    /// Declared textures (`texture name kind { … }`), with the span of
    /// each one's name.
    pub textures: HashMap<String, (super::scene::Texture, Span)>,
}

impl Env {
    /// An environment with one (global) frame.
    pub fn new() -> Self {
        Env {
            frames: vec![HashMap::new()],
            used: Default::default(),
            textures: HashMap::new(),
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

    /// Looks a name up, innermost first, marking it used.
    pub fn lookup(&mut self, name: &str) -> Option<Option<Value>> {
        for f in self.frames.iter().rev() {
            if let Some(b) = f.get(name) {
                self.used.insert(b.decl);
                return Some(b.value.clone());
            }
        }
        None
    }

    /// Every name in scope (for "did you mean").
    pub fn names(&self) -> Vec<String> {
        (self.frames.iter().flat_map(|f| f.keys()))
            .chain(self.textures.keys())
            .cloned()
            .collect()
    }
}

/// The built-in functions: name, number of arguments.
pub const FUNCTIONS: &[(&str, usize)] = &[
    ("sin", 1),
    ("cos", 1),
    ("tan", 1),
    ("sqrt", 1),
    ("pow", 2),
    ("abs", 1),
    ("min", 2),
    ("max", 2),
    ("radians", 1),
    ("degrees", 1),
    ("normalize", 1),
    ("length", 1),
    ("dot", 2),
    ("cross", 2),
];

/// Evaluates `e`; on failure the reason is in `diags` and `None` is returned.
pub fn eval(e: &Expr, env: &mut Env, diags: &mut Diagnostics) -> Option<Value> {
    let v = eval_inner(e, env, diags)?;
    finite(v, e.span, matches!(e.kind, ExprKind::Number(_)), diags)
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
                acc_span = span;
                bare_rgb = false;
            }
            acc
        }
        ExprKind::Call { func, args } => {
            let Some(&(_, arity)) = FUNCTIONS.iter().find(|(n, _)| *n == func.name) else {
                let help = match did_you_mean(&func.name, FUNCTIONS.iter().map(|(n, _)| *n)) {
                    Some(s) => format!("did you mean `{s}`?"),
                    None => format!(
                        "the functions are {}",
                        FUNCTIONS
                            .iter()
                            .map(|(n, _)| *n)
                            .collect::<Vec<_>>()
                            .join(", ")
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
            if args.len() != arity {
                diags.push(
                    Diagnostic::error(
                        codes::WRONG_ARGUMENT_COUNT,
                        format!(
                            "`{}` takes {arity} argument{}, found {}",
                            func.name,
                            if arity == 1 { "" } else { "s" },
                            args.len()
                        ),
                        e.span,
                    )
                    .with_label("wrong number of arguments")
                    .with_help(format!(
                        "call it as `{}({})`",
                        func.name,
                        vec!["x"; arity].join(", ")
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
    let f = |x: f64, y: f64| match op {
        BinOp::Add => x + y,
        BinOp::Sub => x - y,
        BinOp::Mul => x * y,
        BinOp::Div => x / y,
        BinOp::Rem => x % y,
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
