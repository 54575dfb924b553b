//! The `budget` fuzz target: scenes made of the constructs that cost the
//! evaluator most (long lists compared and printed, long vectors and
//! strings, long and branching functions, nested loops, a warning in
//! every iteration), generated from the fuzzer's bytes, checked under
//! small budgets. Whatever the bytes, a check must end quickly, report each
//! budget once and fold repeated diagnostics: work that no budget counts
//! shows as time.

use crate::compile::{compile_bytes, Options};
use crate::diag::codes;
use std::collections::HashSet;
use std::fmt::Write;
use std::path::Path;
use std::time::{Duration, Instant};

/// The statements a generated scene's loops may run (the checker's rule,
/// a smaller budget).
const LOOP_STATEMENTS: u64 = 20_000;
/// The steps of work a generated scene's expressions may take.
const WORK: u64 = 200_000;
/// The longest a check of a generated scene may take. Within the budgets
/// above one takes milliseconds (the most a scene can ask for without them
/// is minutes): this is hundreds of times that, so that a loaded machine
/// does not fail it, and work no budget counts does.
const MAX_CHECK: Duration = Duration::from_secs(5);
/// The most statements a generated scene has at its top level.
const MAX_STATEMENTS: usize = 16;
/// The deepest loops nest in a generated scene.
const MAX_LOOP_DEPTH: usize = 3;

/// Checks the scene [`budget_scene`] makes of `bytes` under small budgets:
/// no panic, done within [`MAX_CHECK`], the evaluation budget reported at
/// most once, no two diagnostics of one code at one place (a loop's
/// repeats are folded). Returns whether the scene met a budget (an input
/// worth mutating further).
pub fn budget(bytes: &[u8]) -> bool {
    let text = budget_scene(bytes);
    let start = Instant::now();
    let compiled = compile_bytes(
        Path::new("budget.pts"),
        text.clone().into_bytes(),
        Options {
            lower: false,
            loop_statements: LOOP_STATEMENTS,
            work: WORK,
            output_elsewhere: true,
            ..Options::default()
        },
    );
    let took = start.elapsed();
    assert!(
        took < MAX_CHECK,
        "checking took {took:?}: work that no budget counts\n{text}"
    );
    let items = &compiled.diagnostics.items;
    let spent = |code: &str| items.iter().filter(|d| d.code == code).count();
    assert!(
        spent(codes::EVALUATION_TOO_LONG) <= 1,
        "the evaluation budget reported twice\n{text}"
    );
    let mut places = HashSet::new();
    for d in items {
        assert!(
            places.insert((d.code, d.span)),
            "{} reported twice at one place: {}\n{text}",
            d.code,
            d.message
        );
    }
    spent(codes::EVALUATION_TOO_LONG) + spent(codes::LOOP_TOO_LONG) > 0
}

/// Reads choices from a fuzzer's bytes (zeros once they run out).
struct Choices<'a> {
    bytes: &'a [u8],
    at: usize,
    /// Names made so far (each statement binds its own).
    names: usize,
}

impl Choices<'_> {
    /// A number below `n`.
    fn below(&mut self, n: usize) -> usize {
        let b = self.bytes.get(self.at).copied().unwrap_or(0);
        self.at += 1;
        b as usize % n.max(1)
    }

    /// One of `options`.
    fn one<'s>(&mut self, options: &[&'s str]) -> &'s str {
        options[self.below(options.len())]
    }

    /// A fresh name starting with `_` (unused on purpose).
    fn name(&mut self) -> String {
        self.names += 1;
        format!("_n{}", self.names)
    }
}

/// A scene of the constructs that cost the evaluator most, chosen by
/// `bytes`: data (a list doubled up to a million items, a copy of it,
/// lists of lists, a long vector and string), functions (long, branching,
/// calling each other) and statements using them, in loops nested up to
/// [`MAX_LOOP_DEPTH`] deep over ranges up to 1e300 and over the lists.
pub fn budget_scene(bytes: &[u8]) -> String {
    let mut c = Choices {
        bytes,
        at: 0,
        names: 0,
    };
    let mut s = String::from(
        "camera { position <0, 0, 5> look_at <0, 0, 0> }\n\
         point_light { position <0, 5, 0> intensity rgb 10 }\n\
         sphere { center <0, 0, 0> radius 1 }\n\
         let l0 = [1, 2.5, \"a\", <1, 2>];\n",
    );
    let doublings = c.below(19);
    for k in 1..=doublings {
        let _ = writeln!(s, "let l{k} = l{} + l{};", k - 1, k - 1);
    }
    let last = doublings;
    let _ = writeln!(s, "let m = l{last} + [];");
    let _ = writeln!(
        s,
        "let n = [{}];",
        vec![format!("l{last}"); 1 + c.below(8)].join(", ")
    );
    let _ = writeln!(s, "let o = [{}];", vec!["m"; 1 + c.below(8)].join(", "));
    let components = 3 + c.below(4) * 500;
    let _ = writeln!(s, "let v = <{}>;", vec!["1.5"; components].join(", "));
    let _ = writeln!(s, "let t = \"{}\";", "ab".repeat(c.below(2049)));
    let terms: Vec<String> = (0..1 + c.below(8) * 400)
        .map(|k| format!("x * {k}"))
        .collect();
    let _ = writeln!(s, "fn f(x) = {};", terms.join(" + "));
    s.push_str("fn r(k) = if k <= 0 { 1 } else { r(k - 1) + r(k - 1) };\n");
    s.push_str("fn g(x) = f(x) + f(x + 1) + len(str(x));\n");
    for _ in 0..1 + c.below(MAX_STATEMENTS) {
        statement(&mut c, &mut s, 0, "1");
    }
    s
}

/// Appends one statement at loop depth `depth`, `var` a number in scope.
fn statement(c: &mut Choices, s: &mut String, depth: usize, var: &str) {
    let name = c.name();
    let lists = ["l0", "m", "n", "o", "[m, n]"];
    match c.below(if depth < MAX_LOOP_DEPTH { 14 } else { 11 }) {
        0 => {
            let (a, b) = (c.one(&lists), c.one(&lists));
            let _ = writeln!(s, "let {name} = {a} == {b} || {a} != [{b}];");
        }
        1 => {
            let _ = writeln!(s, "let {name} = str({}, {});", c.one(&lists), c.below(33));
        }
        2 => {
            let _ = writeln!(s, "let {name} = f({var}) + g({var});");
        }
        3 => {
            let _ = writeln!(s, "let {name} = r({});", c.below(40));
        }
        4 => {
            // A warning (albedo above 1) at every iteration.
            let _ = writeln!(
                s,
                "sphere {{ center <{var}, 0, 0> radius 1 material {{ diffuse rgb 2 }} }}"
            );
        }
        5 => {
            let _ = writeln!(s, "let {name} = -v + v * {var} - v / 2;");
        }
        6 => {
            let _ = writeln!(s, "let {name} = len(t + t) + len(t[len(t) - 1]);");
        }
        7 => {
            let _ = writeln!(s, "let {name} = str(v) + str(t);");
        }
        8 => {
            let _ = writeln!(s, "let {name} = [n, o, v, t] == [n, o, v, t + \"\"];");
        }
        9 => {
            let _ = writeln!(
                s,
                "let {name} = length(v[0] * <1e200, 1e-200, 0>) + pow({var}, 0.5);"
            );
        }
        10 => {
            // A mistake in a loop: the loop stops at its first iteration.
            let _ = writeln!(s, "let {name} = m[{var} + 1e300];");
        }
        _ => {
            let range = c.one(&[
                "0..1",
                "0..7",
                "0..100",
                "0..1000",
                "0..100000",
                "0..1e300",
                "-3..3",
            ]);
            let over = match c.below(3) {
                0 => range.to_string(),
                1 => c.one(&lists).to_string(),
                _ => "[1, 2, 3]".to_string(),
            };
            let loop_var = format!("i{depth}");
            let _ = writeln!(s, "for {loop_var} in {over} {{");
            for _ in 0..1 + c.below(3) {
                statement(c, s, depth + 1, &loop_var);
            }
            s.push_str("}\n");
        }
    }
}
