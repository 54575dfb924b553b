//! The limits evaluation runs within: calls, list and string sizes, depth.

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

/// Deepest nesting of evaluation in all (expressions within expressions,
/// through calls): what the brackets of one expression allow
/// ([`crate::syntax::MAX_NESTING`], each bracket a few levels) a few
/// times over, within the stack of a 2 MiB thread.
pub const MAX_EVAL_DEPTH: usize = 1024;
