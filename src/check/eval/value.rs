//! The values expressions compute, and the two operations that walk a whole
//! value: equality and text. Both are bounded by the work they may do
//! ([`Work`]), not by the size of their operands: a list of a million items
//! compared in a loop stops the loop at the budget, not after hours.

use super::budget::Work;
use crate::check::symbols::DefId;
use crate::syntax::ast::Expr;
use std::fmt::Write;
use std::sync::Arc;

/// Deepest nesting of lists in one value (`[[1]]` nests 2 deep). Walking a
/// value (comparing, printing, dropping it) recurses once per level, so
/// this bounds the stack it takes; a chain of `let`s could otherwise nest a
/// list a million deep.
pub const MAX_LIST_DEPTH: u32 = 256;

/// A user function: `fn name(params) = body;`.
#[derive(Debug)]
pub struct Function {
    /// Its name as declared.
    pub name: String,
    /// Its parameters' names, with the definition of each (the body's
    /// uses of a parameter are recorded against it).
    pub params: Vec<(String, DefId)>,
    /// Its value.
    pub body: Arc<Expr>,
}

impl PartialEq for Function {
    /// The same declaration: the body is the declaration's own (shared with
    /// the syntax tree), so that comparing two functions never walks them.
    fn eq(&self, other: &Function) -> bool {
        Arc::ptr_eq(&self.body, &other.body) && self.name == other.name
    }
}

/// The items of a list value, and how deeply lists nest in it.
#[derive(Debug, PartialEq)]
pub struct List {
    /// The items.
    pub items: Vec<Value>,
    /// 1 for a list without lists in it, one more per level of lists.
    pub depth: u32,
}

impl List {
    /// A list of `items` (its depth from theirs).
    pub fn new(items: Vec<Value>) -> List {
        let inner = items.iter().map(Value::depth).max().unwrap_or(0);
        List {
            items,
            depth: inner + 1,
        }
    }
}

/// A value computed from an expression.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// A number.
    Num(f64),
    /// A vector of 2 or more numbers (shared, as a list: a name copies a
    /// pointer, whatever the vector's length).
    Vector(Arc<[f64]>),
    /// An RGB colour.
    Color([f64; 3]),
    /// A string (shared).
    Str(Arc<str>),
    /// A boolean.
    Bool(bool),
    /// A list of values (shared: copying a name copies a pointer).
    List(Arc<List>),
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
            Value::List(l) => format!("a list of {}", l.items.len()),
            Value::Function(f) => format!("the function `{}`", f.name),
        }
    }

    /// A list of `items`.
    pub fn list(items: Vec<Value>) -> Value {
        Value::List(Arc::new(List::new(items)))
    }

    /// How deeply lists nest in this value (0 for anything but a list).
    pub fn depth(&self) -> u32 {
        match self {
            Value::List(l) => l.depth,
            _ => 0,
        }
    }

    /// What making or walking this value costs beyond a step: a step per
    /// 16 bytes of a string or of a vector's components (8 bytes each).
    /// Copying any value costs nothing (it is shared); building a list is
    /// counted by its items.
    pub fn weight(&self) -> u64 {
        let bytes = match self {
            Value::Str(s) => s.len(),
            Value::Vector(v) => 8 * v.len(),
            _ => 0,
        };
        bytes as u64 / 16
    }
}

/// Whether `a` equals `b`, taking one step of `work` per list item
/// visited (and strings and vectors by their [`Value::weight`]); `None`
/// when the work runs out first. Lists shared by both sides are equal
/// without a look (every number in a value is finite, so a value equals
/// itself).
pub fn equal(a: &Value, b: &Value, work: &mut Work) -> Option<bool> {
    match (a, b) {
        (Value::List(x), Value::List(y)) => {
            if Arc::ptr_eq(x, y) {
                return Some(true);
            }
            if x.items.len() != y.items.len() {
                return Some(false);
            }
            for (p, q) in x.items.iter().zip(&y.items) {
                if !work.take(1) {
                    return None;
                }
                if !equal(p, q, work)? {
                    return Some(false);
                }
            }
            Some(true)
        }
        (Value::Str(_) | Value::Vector(_), _) => {
            if !work.take(a.weight().min(b.weight())) {
                return None;
            }
            Some(a == b)
        }
        // Numbers, colours, booleans, functions, and values of two types:
        // one look.
        _ => Some(a == b),
    }
}

/// Why [`text`] made no string.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TextError {
    /// The text would be longer than its limit.
    TooLong,
    /// The work ran out.
    OutOfWork,
}

/// `v` as text (what `str(v, width)` gives), at most `max` bytes, taking a
/// step of `work` per byte written: whole numbers without a fraction
/// (zero-padded to `width` digits), other numbers as the shortest decimal
/// that reads back the same, strings as they are, other values as they are
/// written in a scene. It stops as soon as the text passes `max`, so a
/// list of a million items costs no more than a short one.
pub fn text(v: &Value, width: usize, max: usize, work: &mut Work) -> Result<String, TextError> {
    let mut out = String::new();
    write_value(&mut out, v, width, max)?;
    if !work.take(out.len() as u64) {
        return Err(TextError::OutOfWork);
    }
    Ok(out)
}

/// Appends `v` to `out` ([`text`]); `Err` once `out` passes `max` bytes.
fn write_value(out: &mut String, v: &Value, width: usize, max: usize) -> Result<(), TextError> {
    // A vector may be long too: stop within it.
    let numbers = |out: &mut String, xs: &[f64]| {
        for (i, &x) in xs.iter().enumerate() {
            if out.len() > max {
                return Err(TextError::TooLong);
            }
            if i > 0 {
                out.push_str(", ");
            }
            write_number(out, x, 0);
        }
        Ok(())
    };
    match v {
        Value::Num(x) => write_number(out, *x, width),
        Value::Str(s) => out.push_str(s),
        Value::Bool(b) => out.push_str(if *b { "true" } else { "false" }),
        Value::Vector(xs) => {
            out.push('<');
            numbers(out, xs)?;
            out.push('>');
        }
        Value::Color(c) => {
            out.push_str("rgb <");
            numbers(out, c)?;
            out.push('>');
        }
        Value::List(l) => {
            out.push('[');
            for (i, item) in l.items.iter().enumerate() {
                if i > 0 {
                    out.push_str(", ");
                }
                write_value(out, item, 0, max)?;
            }
            out.push(']');
        }
        Value::Function(f) => {
            out.push_str("fn ");
            out.push_str(&f.name);
        }
    }
    if out.len() > max {
        return Err(TextError::TooLong);
    }
    Ok(())
}

/// `x` as a message shows it: a whole number below 1e15 in digits (`12`,
/// `1000000`), any other as a person writes it (`0.5`, `1e300`).
pub fn shown(x: f64) -> String {
    if x.fract() == 0.0 && x.abs() < 1e15 {
        let mut out = String::new();
        write_number(&mut out, x, 0);
        out
    } else {
        crate::check::domain::number(x)
    }
}

/// Appends a number: whole numbers below 1e15 as integers zero-padded to
/// `width` digits, others as the shortest decimal that reads back the same.
fn write_number(out: &mut String, x: f64, width: usize) {
    if x.fract() == 0.0 && x.abs() < 1e15 {
        if x < 0.0 {
            out.push('-');
        }
        let _ = write!(out, "{:0width$}", (x as i64).unsigned_abs());
    } else {
        let _ = write!(out, "{x}");
    }
}
