//! The built-in functions (`sin`, `pow`, `normalize`, `str`, …): their
//! table, their domains and their results at the edges of 64-bit floats.
//!
//! A result is either right or an error that says what is wrong: a vector
//! is scaled by its largest component before it is squared (so `<1e200, 0,
//! 0>` has a length and `<1e-200, 0, 0>` a direction), a power of a
//! negative number to a fraction is a domain error, not a NaN, and a
//! result past ±1.8e308 is reported as too large by the evaluator.

use super::env::{too_large, Env};
use super::limits::MAX_STRING;
use super::value::{text, TextError, Value};
use crate::check::domain;
use crate::diag::{codes, Diagnostic, Diagnostics};
use crate::span::Span;
use crate::syntax::ast::Expr;

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
    ("int", (1, 1)),
    ("mod", (2, 2)),
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

/// Each built-in function's signature and meaning, in the order of
/// [`FUNCTIONS`] (tested): what hover and completion show.
pub const FUNCTION_DOCS: &[(&str, &str, &str)] = &[
    ("sin", "sin(x)", "sine of `x` in radians"),
    ("cos", "cos(x)", "cosine of `x` in radians"),
    ("tan", "tan(x)", "tangent of `x` in radians"),
    ("asin", "asin(x)", "arc sine in radians, `x` in [-1, 1]"),
    ("acos", "acos(x)", "arc cosine in radians, `x` in [-1, 1]"),
    ("atan2", "atan2(y, x)", "the angle of the point `<x, y>` in radians, in (-π, π]"),
    ("sqrt", "sqrt(x)", "square root, `x` ≥ 0"),
    ("pow", "pow(x, y)", "`x` to the power `y` (a negative `x` only to a whole power)"),
    ("exp", "exp(x)", "e to the power `x`"),
    ("log", "log(x)", "natural logarithm, `x` > 0"),
    ("abs", "abs(x)", "absolute value"),
    ("min", "min(a, b)", "the smaller of two numbers"),
    ("max", "max(a, b)", "the larger of two numbers"),
    ("clamp", "clamp(x, lo, hi)", "`x` limited to [lo, hi]"),
    ("floor", "floor(x)", "the largest whole number ≤ `x`"),
    ("ceil", "ceil(x)", "the smallest whole number ≥ `x`"),
    ("round", "round(x)", "the nearest whole number (halves away from zero)"),
    ("int", "int(x)", "`x` with its fraction dropped (toward zero)"),
    ("mod", "mod(a, b)", "the remainder of `a / b`, with the sign of `a`"),
    ("radians", "radians(degrees)", "degrees to radians"),
    ("degrees", "degrees(radians)", "radians to degrees"),
    ("normalize", "normalize(v)", "the vector `v` scaled to length 1"),
    ("length", "length(v)", "the length of vector `v`"),
    ("dot", "dot(a, b)", "the dot product of two vectors"),
    ("cross", "cross(a, b)", "the cross product of two vectors of 3"),
    ("len", "len(list)", "the number of items of a list (or components of a vector)"),
    ("str", "str(x[, width])", "a value as text; a whole number zero-padded to `width` digits (0 to 32), as frame numbers in file names"),
    ("rand", "rand(seed, i)", "a uniform random number in [0, 1), the same for the same seed and index"),
];

/// The evaluated arguments of a call of a built-in function, and where
/// each is written.
struct Args<'a> {
    name: &'a str,
    vals: &'a [Value],
    args: &'a [Expr],
}

impl Args<'_> {
    /// Argument `i` as a number, or a type error.
    fn num(&self, i: usize, diags: &mut Diagnostics) -> Option<f64> {
        match &self.vals[i] {
            Value::Num(x) => Some(*x),
            other => {
                diags.push(
                    Diagnostic::error(
                        codes::TYPE_MISMATCH,
                        format!(
                            "`{}` needs a number, found {}",
                            self.name,
                            other.type_name()
                        ),
                        self.args[i].span,
                    )
                    .with_label("expected a number")
                    .with_help(format!("pass a number to `{}`", self.name)),
                );
                None
            }
        }
    }

    /// Argument `i` as a vector of 3, or a type error.
    fn vec3(&self, i: usize, diags: &mut Diagnostics) -> Option<[f64; 3]> {
        match &self.vals[i] {
            Value::Vector(v) if v.len() == 3 => Some([v[0], v[1], v[2]]),
            other => {
                diags.push(
                    Diagnostic::error(
                        codes::TYPE_MISMATCH,
                        format!(
                            "`{}` needs a vector of 3, found {}",
                            self.name,
                            other.type_name()
                        ),
                        self.args[i].span,
                    )
                    .with_label("expected a vector <x, y, z>")
                    .with_help(format!(
                        "pass a vector such as `<0, 1, 0>` to `{}`",
                        self.name
                    )),
                );
                None
            }
        }
    }

    /// A domain error at argument `i`.
    fn domain(&self, i: usize, message: &str, label: String, help: &str) -> Diagnostic {
        Diagnostic::error(codes::DOMAIN, message, self.args[i].span)
            .with_label(label)
            .with_help(help)
    }
}

/// Calls the built-in `name` (its argument count checked) with `vals`,
/// evaluated from `args`; `span` is the whole call.
pub(super) fn call(
    name: &str,
    vals: &[Value],
    args: &[Expr],
    span: Span,
    env: &mut Env,
    diags: &mut Diagnostics,
) -> Option<Value> {
    let a = Args { name, vals, args };
    match name {
        "len" => len(&a, span, env, diags),
        "str" => str(&a, span, env, diags),
        "normalize" | "length" | "dot" | "cross" => vector(&a, diags),
        _ => numeric(&a, diags).map(Value::Num),
    }
}

/// The functions of numbers to a number.
fn numeric(a: &Args, diags: &mut Diagnostics) -> Option<f64> {
    let x = a.num(0, diags)?;
    Some(match a.name {
        "sin" => x.sin(),
        "cos" => x.cos(),
        "tan" => x.tan(),
        "exp" => x.exp(),
        "abs" => x.abs(),
        "floor" => x.floor(),
        "ceil" => x.ceil(),
        "round" => x.round(),
        // POV-Ray's `int`: the whole part, towards zero.
        "int" => x.trunc(),
        "mod" => return remainder(a, x, a.num(1, diags)?, diags),
        "radians" => x.to_radians(),
        "degrees" => x.to_degrees(),
        "sqrt" if x < 0.0 => {
            let label = format!("this is {}", domain::number(x));
            diags.push(a.domain(
                0,
                "square root of a negative number",
                label,
                "sqrt needs a value ≥ 0",
            ));
            return None;
        }
        "sqrt" => x.sqrt(),
        "log" if x <= 0.0 => {
            let label = format!("this is {}", domain::number(x));
            let message = "logarithm of a number that is not positive";
            diags.push(a.domain(0, message, label, "log needs a value > 0"));
            return None;
        }
        "log" => x.ln(),
        "asin" | "acos" if !(-1.0..=1.0).contains(&x) => {
            let message = format!("`{}` of a number outside [-1, 1]", a.name);
            let help = format!("`{}` takes a sine or cosine, between -1 and 1", a.name);
            let label = format!("this is {}", domain::number(x));
            diags.push(a.domain(0, &message, label, &help));
            return None;
        }
        "asin" => x.asin(),
        "acos" => x.acos(),
        "pow" => return pow(a, x, a.num(1, diags)?, diags),
        "atan2" => x.atan2(a.num(1, diags)?),
        "min" => x.min(a.num(1, diags)?),
        "max" => x.max(a.num(1, diags)?),
        "rand" => random(x, a.num(1, diags)?),
        "clamp" => {
            let (lo, hi) = (a.num(1, diags)?, a.num(2, diags)?);
            if lo > hi {
                diags.push(
                    Diagnostic::error(
                        codes::DOMAIN,
                        "`clamp` with its low bound above its high bound",
                        a.args[1].span.join(a.args[2].span),
                    )
                    .with_label(format!("{} > {}", domain::number(lo), domain::number(hi)))
                    .with_help("call it as `clamp(x, low, high)`"),
                );
                return None;
            }
            x.clamp(lo, hi)
        }
        other => unreachable!("function table and evaluator disagree on `{other}`"),
    })
}

/// `mod(a, b)`: POV-Ray's remainder, `a - int(a / b) * b` (the sign of
/// `a`, as `%`), or a division-by-zero error.
fn remainder(a: &Args, x: f64, y: f64, diags: &mut Diagnostics) -> Option<f64> {
    if y == 0.0 {
        diags.push(
            Diagnostic::error(codes::DIVISION_BY_ZERO, "`mod` by zero", a.args[1].span)
                .with_label("this is 0")
                .with_help("`mod(a, b)` needs b ≠ 0"),
        );
        return None;
    }
    Some(x % y)
}

/// `pow(x, y)`: a real number, or a domain error (a negative number to a
/// fraction has none; zero to a negative power is a division by zero). A
/// result too large is the evaluator's to report.
fn pow(a: &Args, x: f64, y: f64, diags: &mut Diagnostics) -> Option<f64> {
    // Both arguments make the mistake: the error spans them.
    let both = |d: Diagnostic| Diagnostic {
        span: Some(a.args[0].span.join(a.args[1].span)),
        ..d
    };
    if x < 0.0 && y.fract() != 0.0 {
        let label = format!("{} to the power {}", domain::number(x), domain::number(y));
        let help = "only whole powers of a negative number are real; use `pow(abs(x), y)` or a whole exponent";
        let message = "a negative number to a fractional power";
        diags.push(both(a.domain(0, message, label, help)));
        return None;
    }
    if x == 0.0 && y < 0.0 {
        let label = format!("0 to the power {}", domain::number(y));
        let help = "a negative power divides by the base; give a base other than 0";
        diags.push(both(a.domain(0, "zero to a negative power", label, help)));
        return None;
    }
    Some(x.powf(y))
}

/// The functions of vectors: `length`, `normalize`, `dot`, `cross`.
fn vector(a: &Args, diags: &mut Diagnostics) -> Option<Value> {
    let u = a.vec3(0, diags)?;
    Some(match a.name {
        "length" => Value::Num(length(u)),
        "normalize" => {
            let Some(n) = domain::unit(glam::DVec3::from_array(u)) else {
                let help = "pass a non-zero vector";
                let message = "cannot normalize a zero vector";
                diags.push(a.domain(0, message, "this vector has length 0".into(), help));
                return None;
            };
            Value::Vector(n.to_array().into())
        }
        "dot" => {
            let v = a.vec3(1, diags)?;
            let (p, q, su, sv) = (scaled(u), scaled(v), largest(u), largest(v));
            Value::Num(unscale(p[0] * q[0] + p[1] * q[1] + p[2] * q[2], su, sv))
        }
        "cross" => {
            let v = a.vec3(1, diags)?;
            let (p, q, su, sv) = (scaled(u), scaled(v), largest(u), largest(v));
            let c = [
                p[1] * q[2] - p[2] * q[1],
                p[2] * q[0] - p[0] * q[2],
                p[0] * q[1] - p[1] * q[0],
            ];
            Value::Vector(c.iter().map(|&x| unscale(x, su, sv)).collect())
        }
        other => unreachable!("`{other}` is not a function of vectors"),
    })
}

/// The largest magnitude of a component of `v`.
fn largest(v: [f64; 3]) -> f64 {
    v.iter().fold(0.0, |m: f64, x| m.max(x.abs()))
}

/// `v` divided by its largest magnitude (components within ±1, one of
/// them ±1), or `v` itself when it is zero: its squares neither overflow
/// nor underflow.
fn scaled(v: [f64; 3]) -> [f64; 3] {
    let m = largest(v);
    if m == 0.0 {
        v
    } else {
        v.map(|x| x / m)
    }
}

/// `x` (a product of two scaled vectors) times the scales `s` and `t` it
/// was divided by: in one product when that stays a normal number, else
/// one after the other, so that a zero stays zero and a product of a huge
/// and a tiny scale is not lost to overflow or underflow.
fn unscale(x: f64, s: f64, t: f64) -> f64 {
    if s == 0.0 || t == 0.0 {
        return x;
    }
    let st = s * t;
    if st.is_normal() {
        x * st
    } else {
        x * s * t
    }
}

/// The length of `v` without overflow or underflow of its squares: the
/// largest component times the length of the scaled vector.
fn length(v: [f64; 3]) -> f64 {
    let (p, m) = (scaled(v), largest(v));
    m * (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt()
}

/// `len(x)`: the items of a list, the components of a vector or colour,
/// the characters of a string (counted: a step per 16 bytes).
fn len(a: &Args, span: Span, env: &mut Env, diags: &mut Diagnostics) -> Option<Value> {
    let n = match &a.vals[0] {
        Value::List(l) => l.items.len(),
        Value::Vector(v) => v.len(),
        Value::Str(t) => {
            if !env.charge(a.vals[0].weight(), span, diags) {
                return None;
            }
            t.chars().count()
        }
        Value::Color(_) => 3,
        other => {
            diags.push(
                Diagnostic::error(
                    codes::TYPE_MISMATCH,
                    format!(
                        "`len` needs a list, vector or string, found {}",
                        other.type_name()
                    ),
                    a.args[0].span,
                )
                .with_label(format!("this is {}", other.type_name()))
                .with_help("`len(xs)` counts the items of a list"),
            );
            return None;
        }
    };
    Some(Value::Num(n as f64))
}

/// `str(x)` and `str(x, width)`: text of at most [`MAX_STRING`] bytes.
fn str(a: &Args, span: Span, env: &mut Env, diags: &mut Diagnostics) -> Option<Value> {
    let width = match a.vals.get(1) {
        None => 0,
        Some(_) => {
            let w = a.num(1, diags)?;
            if !(w.fract() == 0.0 && (0.0..=32.0).contains(&w)) {
                let label = format!("this is {}", domain::number(w));
                let message = "a width must be a whole number from 0 to 32";
                diags.push(a.domain(1, message, label, "`str(7, 4)` is \"0007\""));
                return None;
            }
            w as usize
        }
    };
    match text(&a.vals[0], width, MAX_STRING, &mut env.work) {
        Ok(s) => Some(Value::Str(s.into())),
        Err(TextError::TooLong) => {
            diags.push(too_large(
                format!("{} as text is longer", a.vals[0].type_name()),
                span,
            ));
            None
        }
        Err(TextError::OutOfWork) => {
            env.out_of_work(span, diags);
            None
        }
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

#[cfg(test)]
mod doc_tests {
    #[test]
    fn every_function_has_its_doc_line_in_order() {
        let names: Vec<_> = super::FUNCTIONS.iter().map(|f| f.0).collect();
        let documented: Vec<_> = super::FUNCTION_DOCS.iter().map(|f| f.0).collect();
        assert_eq!(names, documented);
    }
}
