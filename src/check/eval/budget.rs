//! The evaluation budget: the work the expressions of one compile may do,
//! counted in steps of roughly equal cost, whatever construct does it.
//!
//! A step is:
//! - an expression evaluated in a loop, in a file included again or in a
//!   function's body (an expression run once, at the top level of a file,
//!   is bounded by the text and costs nothing);
//! - a list item visited by `==` or `!=`;
//! - a byte of text `str` writes;
//! - 16 bytes of a string or 16 components of a vector made, copied,
//!   compared or scanned (`len`, indexing).
//!
//! Building lists is counted apart, by their items
//! ([`super::limits::MAX_ITEMS`]); loops by their statements
//! ([`crate::check::MAX_LOOP_STATEMENTS`]). Did-you-mean suggestions have
//! a budget of their own ([`MAX_SUGGESTIONS`]): an error is reported
//! without one once it is spent.

use crate::diag::{codes, group_digits, Diagnostic};
use crate::span::Span;

/// Most steps the expressions of one compile may take: 1.5 s of CPU at the
/// slowest step (an expression evaluated in a function's body, about
/// 60 ns; 3 s on a machine as loaded as 2026-12-03's), a scene at the
/// budget checking in a few seconds whatever spends it; about six steps a
/// statement of the loops' budget (a `sphere` in a loop takes five), and
/// forty times what the most demanding example takes (`many_lights.pts`,
/// 590,000).
pub const MAX_WORK: u64 = 25_000_000;

/// Most names did-you-mean suggestions may weigh in one compile, all
/// errors together: 20,000 unknown names among 20,000 constants would
/// otherwise weigh 400 million pairs (minutes).
pub const MAX_SUGGESTIONS: u64 = 2_000_000;

/// Steps of work left.
#[derive(Debug, Clone, Copy)]
pub struct Work {
    left: u64,
}

impl Work {
    /// A budget of `steps`.
    pub fn new(steps: u64) -> Work {
        Work { left: steps }
    }

    /// Takes `steps`: `false`, leaving none, when fewer are left.
    pub fn take(&mut self, steps: u64) -> bool {
        match self.left.checked_sub(steps) {
            Some(left) => {
                self.left = left;
                true
            }
            None => {
                self.left = 0;
                false
            }
        }
    }
}

impl Default for Work {
    /// The budget of a compile ([`MAX_WORK`]).
    fn default() -> Work {
        Work::new(MAX_WORK)
    }
}

/// The error of a budget of `limit` steps spent at `span`.
pub fn out_of_work(limit: u64, span: Span) -> Diagnostic {
    Diagnostic::error(
        codes::EVALUATION_TOO_LONG,
        format!(
            "the expressions of this scene take more than {} steps of work in all",
            group_digits(limit)
        ),
        span,
    )
    .with_label("evaluation stops here")
    .with_help(
        "a step is an expression a loop or a function evaluates, a list item `==` compares or a byte `str` writes; compare and print large lists outside loops, call long functions less often, and put large generated data in a mesh file",
    )
}
