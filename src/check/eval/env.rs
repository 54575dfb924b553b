//! The environment of evaluation: the names in scope (a stack of frames),
//! and what evaluation has spent of its limits and budgets (calls, list
//! items, steps of work, suggestions).

use super::budget::{self, Work};
use super::budget::{MAX_SUGGESTIONS, MAX_WORK};
use super::limits::{MAX_ITEMS, MAX_STRING};
use super::value::{List, Value, MAX_LIST_DEPTH};
use crate::check::symbols::{DefId, SymbolKind, Symbols};
use crate::diag::{codes, did_you_mean, Diagnostic, Diagnostics};
use crate::span::Span;
use std::collections::HashMap;
use std::sync::Arc;

/// One bound name: a constant, a function, a parameter or a loop variable.
#[derive(Debug, Clone)]
pub struct Binding {
    /// Its value (`None` when its definition had an error: uses stay silent).
    pub value: Option<Value>,
    /// Its definition in [`Env::symbols`], which a use is recorded against.
    pub def: DefId,
}

/// Names in scope: a stack of frames (the file level, then one per loop
/// iteration or function call).
#[derive(Debug, Default)]
pub struct Env {
    pub(super) frames: Vec<HashMap<String, Binding>>,
    /// The innermost frame a name may be looked up in besides the file
    /// level: a function's body sees its parameters and the file's names,
    /// not the caller's loop variables.
    pub(super) base: usize,
    /// Calls of user functions under way.
    pub(super) call_depth: usize,
    /// Calls of user functions made so far.
    pub(super) calls: u64,
    /// List items built so far (of [`MAX_ITEMS`] × 16 in all).
    pub(super) items: u64,
    /// A limit was reached: further calls fail silently (reported once).
    pub(super) exhausted: bool,
    /// Evaluations under way, nested.
    pub(super) depth: usize,
    /// The steps of work evaluation may still take ([`MAX_WORK`] but for
    /// fuzzers).
    pub(super) work: Work,
    /// The budget `work` started with, for the message.
    pub(super) work_limit: u64,
    /// The work ran out (reported once).
    pub(super) work_reported: bool,
    /// Names did-you-mean suggestions may still weigh.
    pub(super) suggestions: Work,
    /// Loops and repeated includes running now: an expression they
    /// evaluate costs a step (one the text bounds does not).
    pub repeating: usize,
    /// Every definition met so far and the uses resolved to each: where
    /// a name resolves is where its use is recorded.
    pub symbols: Symbols,
    /// Declared textures (`texture name kind { … }`), with each one's
    /// definition.
    pub textures: HashMap<String, (crate::check::scene::Texture, DefId)>,
    /// Names every scene sees unless it binds them itself (`frame`,
    /// `clock`).
    pub predefined: Vec<(&'static str, Value)>,
    /// Code that did not run: an `if`'s arms not taken, a loop's body run
    /// no time. A name written there is not reported as never used
    /// (`if final { … final_spp … }` uses it in the final build).
    pub untaken: crate::span::SpanSet,
    /// The code of `untaken`, each piece once (when first not run), for
    /// the checks that need no values (`check::unrun`).
    pub unrun: Vec<Unrun>,
    /// The bodies and arms that ran at least once: a piece of `unrun` that
    /// ran in another pass (a loop's iteration, a call) was checked there.
    pub ran: crate::span::SpanSet,
    /// The `fn` statements whose bodies `unrun` holds: one run again (in
    /// a loop, a file included twice) is kept once.
    pub functions_kept: crate::span::SpanSet,
    /// Names reported unknown, where (the first [`MAX_UNKNOWN_KEPT`]): one
    /// defined elsewhere in the scene, later or in another block, is told
    /// where at the end.
    pub unknown_names: Vec<(String, Span)>,
}

/// Most unknown names kept in [`Env::unknown_names`] (a loop repeats its
/// error; a scene with more has other problems first).
pub const MAX_UNKNOWN_KEPT: usize = 1000;

/// A piece of code that did not run, kept for the checks that need no
/// values: its words, kinds and parameter names.
#[derive(Debug, Clone)]
pub enum Unrun {
    /// Statements (an `if`'s arm, a loop's body) and the text they cover.
    Statements(Span, Vec<crate::syntax::ast::Statement>),
    /// The value of an `if` expression's arm.
    Value(crate::syntax::ast::Expr),
    /// A function's body, with its declaration's span: checked when the
    /// function is never called.
    Function(Span, Arc<crate::syntax::ast::Expr>),
}

impl Unrun {
    /// The text the piece covers.
    pub fn span(&self) -> Span {
        match self {
            Unrun::Statements(span, _) | Unrun::Function(span, _) => *span,
            Unrun::Value(e) => e.span,
        }
    }
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

    /// Whether the work budget is spent (and reported): nothing that costs
    /// a step can run any more.
    pub fn spent(&self) -> bool {
        self.work_reported
    }

    /// Reports the work budget spent at `span` (once).
    pub(super) fn out_of_work(&mut self, span: Span, diags: &mut Diagnostics) {
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

    /// Records the definition of `name`, written at `name_span` in the
    /// statement `span`, and binds it to `value` in the innermost frame.
    pub fn define(
        &mut self,
        kind: SymbolKind,
        (name, name_span): (&str, Span),
        span: Span,
        value: Option<Value>,
    ) -> DefId {
        let def = self.symbols.define(kind, name, name_span, span);
        self.bind(name, Binding { value, def });
        def
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
    pub(super) fn visible(&self) -> impl Iterator<Item = &HashMap<String, Binding>> {
        let inner = self.frames[self.base.max(1).min(self.frames.len())..].iter();
        inner.rev().chain(self.frames.first())
    }

    /// The binding `name` resolves to, innermost first, without recording
    /// a use.
    pub fn visible_binding(&self, name: &str) -> Option<&Binding> {
        self.visible().find_map(|f| f.get(name))
    }

    /// Looks up the name written at `at`, innermost first, recording the
    /// use against the definition it resolves to.
    pub fn lookup(&mut self, name: &str, at: Span) -> Option<Option<Value>> {
        let Some(b) = self.visible().find_map(|f| f.get(name)) else {
            let predefined = self.predefined.iter().find(|(n, _)| *n == name);
            return predefined.map(|(_, v)| Some(v.clone()));
        };
        let (def, value) = (b.def, b.value.clone());
        self.record_use(def, at);
        Some(value)
    }

    /// Records that the parameter named at `name_span` is the schema row
    /// `spec` (once per place).
    pub fn record_param(
        &mut self,
        name_span: Span,
        spec: &'static crate::check::schema::ParamSpec,
    ) {
        let repeating = self.repeating > 0 || self.call_depth > 0;
        self.symbols.record_param(name_span, spec, repeating);
    }

    /// Records a use at `at` of the definition `def` (a texture, a
    /// material or a group, named where evaluation does not look names up).
    pub fn record_use(&mut self, def: DefId, at: Span) {
        let repeating = self.repeating > 0 || self.call_depth > 0;
        self.symbols.record_use(def, at, repeating);
    }

    /// The name in scope (or of `also`) closest to `word`, while the
    /// suggestions' budget lasts ([`Env::suggest`]).
    pub(super) fn suggest_name(&mut self, word: &str, also: &[&str]) -> Option<String> {
        let count = self.name_count() + also.len();
        if !self.suggestions.take(count as u64) {
            return None;
        }
        let names = self.names();
        let candidates = (also.iter().copied()).chain(names.iter().map(String::as_str));
        did_you_mean(word, candidates).map(str::to_string)
    }

    /// How many names [`Env::names`] gives.
    pub(super) fn name_count(&self) -> usize {
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

impl Env {
    /// A list of `items`, counted against the items all lists may hold.
    pub(super) fn new_list(
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
    pub(super) fn charge_items(&mut self, n: usize, span: Span, diags: &mut Diagnostics) -> bool {
        self.charge_items_as(n, || format!("this is a list of {n}"), span, diags)
    }

    /// [`Env::charge_items`], with the label of the error made by `label`.
    pub(super) fn charge_items_as(
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
pub(super) fn too_large(label: String, span: Span) -> Diagnostic {
    Diagnostic::error(
        codes::VALUE_TOO_LARGE,
        format!(
            "lists hold at most {} items, all lists and strings of a scene together {}, a string {} bytes",
            crate::diag::group_digits(MAX_ITEMS as u64),
            crate::diag::group_digits(2 * MAX_ITEMS as u64),
            crate::diag::group_digits(MAX_STRING as u64)
        ),
        span,
    )
    .with_label(label)
    .with_help("large generated data belongs in a mesh file; strings name files and words")
}
