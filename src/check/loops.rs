//! `for` loops and the statement budget they (and repeated includes) run
//! under: each statement a loop runs is charged by its text
//! ([`MAX_LOOP_STATEMENTS`]); the expressions it evaluates are charged to
//! the evaluation budget besides (`eval::budget`).

use super::*;
use crate::check::eval::List;
use crate::syntax::ast::{Expr, Ident};
use std::sync::Arc;

/// The largest loop bound: from 2^53 on, whole numbers are no longer all
/// exact in a 64-bit float (`i + 1` would be `i`).
const MAX_BOUND: f64 = 9_007_199_254_740_992.0;

impl Checker<'_> {
    /// Starts charging statements to the loop (or repeated include) at
    /// `span`: its statements, and the expressions they evaluate, cost.
    pub(super) fn enter_loop(&mut self, span: Span) {
        self.loops.push(span);
        self.env.repeating += 1;
    }

    /// Ends what [`Checker::enter_loop`] started.
    pub(super) fn leave_loop(&mut self) {
        self.loops.pop();
        self.env.repeating -= 1;
    }

    /// Charges one statement run by a loop; `false` once the loops have
    /// run out of statements (the first time, with the diagnostic).
    pub(super) fn charge_loop_statement(&mut self) -> bool {
        self.charge_loop(1)
    }

    /// Charges `units` statements to the loops running now (none outside
    /// loops); `false` once they have run out (the first time, with the
    /// diagnostic).
    pub(super) fn charge_loop(&mut self, units: u64) -> bool {
        if self.loops.is_empty() {
            return true;
        }
        if self.loops_exhausted {
            return false;
        }
        if self.loop_budget < units {
            self.loop_budget = 0;
            self.loops_exhausted = true;
            let outermost = self.loops[0];
            self.diags.push(
                Diagnostic::error(
                    codes::LOOP_TOO_LONG,
                    format!(
                        "the loops (and repeated includes) of this scene run more than {} statements in all",
                        group_digits(self.loop_statements)
                    ),
                    outermost,
                )
                .with_label("these loops stop here")
                .with_help("nested loops multiply: a loop of 1,000 around one of 10,000 runs 10,000,000 statements; shrink the ranges, or put generated geometry in a mesh file"),
            );
            return false;
        }
        self.loop_budget -= units;
        true
    }

    /// `for var in list { body }`.
    pub(super) fn for_list(
        &mut self,
        var: (&Ident, Span),
        list: &Expr,
        body: &[Statement],
        file: FileId,
    ) {
        let Some(value) = eval(list, &mut self.env, &mut self.diags) else {
            return;
        };
        let items: Arc<List> = match value {
            Value::List(items) => items,
            other => {
                self.diags.push(
                    Diagnostic::error(
                        codes::TYPE_MISMATCH,
                        format!(
                            "`for … in` needs a range `a..b` or a list, found {}",
                            other.type_name()
                        ),
                        list.span,
                    )
                    .with_label(format!("this is {}", other.type_name()))
                    .with_help("write `for i in 0..10 { … }` or `for x in [1, 2, 3] { … }`"),
                );
                return;
            }
        };
        // The items are shared, not copied: a loop that stops early costs
        // its iterations, not the list's length.
        let each = (0..items.items.len()).map(|i| items.items[i].clone());
        self.run_loop(var, each, list.span, body, file);
    }

    /// `for var in start..end { body }`.
    pub(super) fn for_range(
        &mut self,
        var: (&Ident, Span),
        (start, end): (&Expr, &Expr),
        body: &[Statement],
        file: FileId,
    ) {
        let a = eval(start, &mut self.env, &mut self.diags);
        let b = eval(end, &mut self.env, &mut self.diags);
        let a = whole_bound(a, start.span, &mut self.diags);
        let b = whole_bound(b, end.span, &mut self.diags);
        let (Some(a), Some(b)) = (a, b) else { return };
        let range = start.span.join(end.span);
        // Every iteration runs at least one statement (or counts one). The
        // count is taken in floats: the bounds may be far apart.
        let n = (b - a).max(0.0);
        if n > self.loop_budget as f64 {
            self.too_many_iterations(n, range);
            return;
        }
        for (x, s) in [(a, start.span), (b, end.span)] {
            if x.abs() > MAX_BOUND {
                self.diags.push(
                    Diagnostic::error(
                        codes::OUT_OF_RANGE,
                        format!(
                            "a loop bound must be within ±{} (2^53), found {}",
                            group_digits(MAX_BOUND as u64),
                            eval::shown(x)
                        ),
                        s,
                    )
                    .with_label("too large")
                    .with_help("past 2^53 a 64-bit float cannot count by ones; loop over a smaller range and add an offset: `for i in 0..10 { let x = 1e16 + i * 2; … }`"),
                );
                return;
            }
        }
        let (a, b) = (a as i64, b as i64);
        self.run_loop(var, (a..b).map(|i| Value::Num(i as f64)), range, body, file);
    }

    /// Reports a loop of `n` iterations, more than the loops may still run.
    fn too_many_iterations(&mut self, n: f64, range: Span) {
        let before = self.loop_statements - self.loop_budget;
        let count = match n {
            n if n < 1e15 => group_digits(n as u64),
            n if n.is_finite() => crate::check::domain::number(n),
            _ => format!("more than {}", crate::check::domain::number(f64::MAX)),
        };
        let (message, help) = if before == 0 {
            (
                format!(
                    "this loop runs {count} times, more than the {} statements loops may run in all",
                    group_digits(self.loop_statements)
                ),
                "shrink the range; large generated scenes belong in a mesh file".to_string(),
            )
        } else {
            (
                format!(
                    "this loop runs {count} times, more than the {} statements loops may still run ({} in all)",
                    group_digits(self.loop_budget),
                    group_digits(self.loop_statements)
                ),
                format!(
                    "the loops before it (and around it) ran {} statements already; nested loops multiply; shrink the ranges, or put generated geometry in a mesh file",
                    group_digits(before)
                ),
            )
        };
        self.diags.push(
            Diagnostic::error(codes::LOOP_TOO_LONG, message, range)
                .with_label(format!("{count} iterations"))
                .with_help(help),
        );
        self.loops_exhausted = true;
    }

    /// Runs `body` once per item of `items` with `var` bound to it, each
    /// statement charged to the loop budget (`range` is the loop's range
    /// or list, where a runaway is reported; `var` comes with the loop's
    /// span).
    fn run_loop(
        &mut self,
        (var, span): (&Ident, Span),
        items: impl Iterator<Item = Value>,
        range: Span,
        body: &[Statement],
        file: FileId,
    ) {
        // One definition, however many iterations bind it.
        let symbols = &mut self.env.symbols;
        let def = symbols.define(SymbolKind::LoopVariable, &var.name, var.span, span);
        self.enter_loop(range);
        let mut ran = false;
        for item in items {
            ran = true;
            // A spent work budget fails every expression silently: the
            // iterations left would do nothing but count statements.
            if self.loops_exhausted || self.env.spent() {
                break;
            }
            if body.is_empty() && !self.charge_loop_statement() {
                break;
            }
            // Counted, not looked for: a scan of the diagnostics here made
            // a loop with a warning per iteration quadratic.
            let errors_before = self.diags.errors_pushed();
            self.env.push();
            let value = Some(item);
            self.env.bind(&var.name, Binding { value, def });
            self.statements(body, file);
            self.env.pop();
            // One broken iteration is enough to report; the others repeat it.
            if self.diags.errors_pushed() > errors_before {
                break;
            }
        }
        match ran {
            true => self.env.ran.extend(super::statements::body_span(body)),
            false => self.not_run(body),
        }
        self.leave_loop();
    }
}

/// A loop bound: a whole number (of any size: the caller bounds it), or
/// `None` after the error.
fn whole_bound(v: Option<Value>, span: Span, diags: &mut Diagnostics) -> Option<f64> {
    match v? {
        Value::Num(x) if x.fract() == 0.0 => Some(x),
        other => {
            diags.push(
                Diagnostic::error(
                    codes::TYPE_MISMATCH,
                    format!(
                        "a loop bound must be a whole number, found {}",
                        match other {
                            Value::Num(x) => eval::shown(x),
                            o => o.type_name(),
                        }
                    ),
                    span,
                )
                .with_label("not a whole number")
                .with_help("write the range as `0..10`"),
            );
            None
        }
    }
}
