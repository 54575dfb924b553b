//! pest pairs → AST. One `build_*` function per rule; rules that the grammar
//! makes impossible at a place are `unreachable!`.

use super::ast::*;
use super::parser::Rule;
use crate::source::FileId;
use crate::span::Span;
use pest::iterators::{Pair, Pairs};

/// Builds AST nodes from the pairs of one file.
pub struct Builder<'t> {
    /// The file the pairs come from.
    pub file: FileId,
    /// The whole text of the file.
    pub text: &'t str,
    /// The names of the kinds of block statement (see [`super::parse_each`]).
    pub kinds: &'t [&'t str],
    /// The first statement refused while building: a declaration that uses
    /// a reserved word as its name, or a kind's block that does not parse.
    pub reserved: std::cell::RefCell<Option<crate::diag::Diagnostic>>,
    /// Where in the file the parsed text starts (pairs count from there).
    pub base: std::cell::Cell<usize>,
}

impl<'t> Builder<'t> {
    /// A builder of `file`'s pairs, parsed from byte `base` of its `text`.
    pub fn new(file: FileId, text: &'t str, kinds: &'t [&'t str], base: usize) -> Self {
        Builder {
            file,
            text,
            kinds,
            reserved: Default::default(),
            base: std::cell::Cell::new(base),
        }
    }

    fn span(&self, pair: &Pair<Rule>) -> Span {
        let s = pair.as_span();
        let base = self.base.get();
        Span::new(self.file, base + s.start(), base + s.end())
    }

    /// `file`, parsed whole.
    pub fn build_file(&self, pair: Pair<Rule>) -> File {
        let statements = pair
            .into_inner()
            .filter(|p| p.as_rule() != Rule::EOI)
            .map(|p| self.build_statement(p))
            .collect();
        File { statements }
    }

    fn build_ident(&self, pair: Pair<Rule>) -> Ident {
        Ident {
            name: pair.as_str().to_string(),
            span: self.span(&pair),
        }
    }

    /// A name being declared: reserved words are refused.
    fn build_decl_name(&self, pair: Pair<Rule>) -> Ident {
        let id = self.build_ident(pair);
        if super::words::KEYWORDS.contains(&id.name.as_str()) {
            let mut slot = self.reserved.borrow_mut();
            if slot.is_none() {
                *slot = Some(
                    crate::diag::Diagnostic::error(
                        crate::diag::codes::RESERVED_WORD,
                        format!("`{}` is a reserved word", id.name),
                        id.span,
                    )
                    .with_label("cannot be used as a name")
                    .with_help(format!("pick another name, e.g. `my_{}`", id.name)),
                );
            }
        }
        id
    }

    /// A statement pair.
    pub fn build_statement(&self, pair: Pair<Rule>) -> Statement {
        let span = self.span(&pair);
        let rule = pair.as_rule();
        let pair_text = pair.as_str();
        let mut inner = pair.into_inner();
        match rule {
            // A `let` or `fn` without its `;` (after a syntax error) is
            // built as if it had one.
            Rule::let_stmt | Rule::let_head => {
                inner.next(); // kw_let
                let name = self.build_decl_name(inner.next().unwrap());
                inner.next(); // =
                let value = self.build_expr(inner.next().unwrap());
                Statement::Let { name, value, span }
            }
            Rule::include_stmt => {
                inner.next(); // kw_include
                let s = inner.next().unwrap();
                let path_span = self.span(&s);
                Statement::Include {
                    path: unescape(s.into_inner().next().unwrap().as_str()),
                    path_span,
                    span,
                }
            }
            Rule::for_stmt => {
                inner.next(); // kw_for
                let var = self.build_decl_name(inner.next().unwrap());
                inner.next(); // kw_in
                let start = self.build_expr(inner.next().unwrap());
                let mut end = None;
                let mut next = inner.next().unwrap();
                if next.as_rule() == Rule::range_dots {
                    end = Some(self.build_expr(inner.next().unwrap()));
                    next = inner.next().unwrap();
                }
                Statement::For {
                    var,
                    start,
                    end,
                    body: self.build_body(next),
                    span,
                }
            }
            Rule::if_stmt => {
                let mut arms = Vec::new();
                let mut otherwise = None;
                let mut cond = None;
                // The statement ends with its last brace: pest's span would
                // take in the blanks its search for one more `else` skipped.
                let end = inner.clone().last().map_or(span, |p| self.span(&p));
                let span = Span {
                    end: end.end,
                    ..span
                };
                for p in inner {
                    match p.as_rule() {
                        Rule::kw_if | Rule::kw_else => {}
                        Rule::expr => cond = Some(self.build_expr(p)),
                        Rule::body => match cond.take() {
                            Some(c) => arms.push((c, self.build_body(p))),
                            None => otherwise = Some(self.build_body(p)),
                        },
                        r => unreachable!("not part of an if: {r:?}"),
                    }
                }
                Statement::If {
                    arms,
                    otherwise,
                    span,
                }
            }
            Rule::fn_stmt | Rule::fn_head => {
                inner.next(); // kw_fn
                let name = self.build_decl_name(inner.next().unwrap());
                let mut params = Vec::new();
                let mut body = None;
                for p in inner {
                    match p.as_rule() {
                        Rule::ident => params.push(self.build_decl_name(p)),
                        Rule::expr => body = Some(self.build_expr(p)),
                        _ => {}
                    }
                }
                Statement::Function {
                    name,
                    params,
                    body: std::sync::Arc::new(body.expect("the grammar gives a body")),
                    span,
                }
            }
            Rule::group_stmt => {
                inner.next(); // kw_group
                let name = self.build_decl_name(inner.next().unwrap());
                let body = self.build_body(inner.next().unwrap());
                Statement::Group { name, body, span }
            }
            Rule::instance_stmt => {
                inner.next(); // kw_instance
                let group = self.build_ident(inner.next().unwrap());
                let block = self.build_block(inner.next().unwrap());
                Statement::Instance { group, block, span }
            }
            Rule::background_stmt => {
                inner.next(); // kw_background
                let value = self.build_expr(inner.next().unwrap());
                Statement::Background { value, span }
            }
            Rule::material_decl => {
                inner.next(); // kw_material
                let name = self.build_decl_name(inner.next().unwrap());
                let block = self.build_block(inner.next().unwrap());
                Statement::Material { name, block, span }
            }
            Rule::texture_decl => {
                inner.next(); // kw_texture
                let name = self.build_decl_name(inner.next().unwrap());
                let kind = self.build_ident(inner.next().unwrap());
                let block = self.build_block(inner.next().unwrap());
                Statement::Texture {
                    name,
                    kind,
                    block,
                    span,
                }
            }
            Rule::block_stmt => {
                let kind = self.build_ident(inner.next().unwrap());
                let block = self.build_block(inner.next().unwrap());
                Statement::Block { kind, block, span }
            }
            Rule::directive_stmt => {
                let name = self.build_ident(inner.next().unwrap());
                let rest = &pair_text[(name.span.end - span.start) as usize..];
                let ident = |(at, bound): (usize, &str)| {
                    let start = name.span.end as usize + at;
                    let span = Span::new(self.file, start, start + bound.len());
                    Ident {
                        name: bound.to_string(),
                        span,
                    }
                };
                let binding = super::povray::bound_name(&name.name, rest).map(|b| (ident(b), None));
                let parameters = match name.name.as_str() {
                    "macro" => super::povray::macro_parameters(rest)
                        .into_iter()
                        .map(ident)
                        .collect(),
                    _ => Vec::new(),
                };
                Statement::Directive {
                    name,
                    binding,
                    parameters,
                    span,
                }
            }
            Rule::declare_stmt => {
                let word = inner.next().unwrap();
                let mut name = self.build_ident(word);
                // The word without its `#`.
                name.name.remove(0);
                name.span = Span::new(
                    name.span.file,
                    name.span.start as usize + 1,
                    name.span.end as usize,
                );
                let bound = self.build_ident(inner.next().unwrap());
                inner.next(); // =
                let value = self.build_expr(inner.next().unwrap());
                Statement::Directive {
                    name,
                    binding: Some((bound, Some(value))),
                    parameters: Vec::new(),
                    span,
                }
            }
            Rule::foreign_stmt => {
                let name = self.build_ident(inner.next().unwrap());
                if self.kinds.contains(&name.name.as_str()) {
                    self.refuse_broken_block(span);
                }
                Statement::Foreign { name, span }
            }
            r => unreachable!("not a statement: {r:?}"),
        }
    }

    /// A kind's block at `span` that did not parse as one, and so was read
    /// whole as a statement ptsc does not have: its syntax error, as a parse
    /// of the statement as a block finds it.
    fn refuse_broken_block(&self, span: Span) {
        use pest::Parser;
        let (start, end) = (span.start as usize, span.end as usize);
        let Err(e) = super::parser::PtsParser::parse(Rule::block_stmt, &self.text[start..end])
        else {
            return;
        };
        let mut slot = self.reserved.borrow_mut();
        if slot.is_none() {
            *slot = Some(super::parser::convert_error(
                e,
                self.file,
                (self.text, self.kinds),
                start,
            ));
        }
    }

    /// The statements of a `body` pair.
    fn build_body(&self, pair: Pair<Rule>) -> Vec<Statement> {
        pair.into_inner()
            .filter(|p| !matches!(p.as_rule(), Rule::lbrace | Rule::rbrace))
            .map(|p| self.build_statement(p))
            .collect()
    }

    fn build_block(&self, pair: Pair<Rule>) -> Block {
        let span = self.span(&pair);
        let entries = pair
            .into_inner()
            .filter(|p| !matches!(p.as_rule(), Rule::lbrace | Rule::rbrace))
            .map(|p| self.build_entry(p))
            .collect();
        Block { entries, span }
    }

    fn build_entry(&self, pair: Pair<Rule>) -> Entry {
        let span = self.span(&pair);
        let rule = pair.as_rule();
        let mut inner = pair.into_inner();
        match rule {
            Rule::param => {
                let name = self.build_ident(inner.next().unwrap());
                let value = self.build_expr(inner.next().unwrap());
                Entry::Param { name, value, span }
            }
            Rule::texture_param => {
                let name = self.build_ident(inner.next().unwrap());
                let kind = self.build_ident(inner.next().unwrap());
                let block = self.build_block(inner.next().unwrap());
                Entry::Texture {
                    name,
                    kind,
                    block,
                    span,
                }
            }
            Rule::color_stop => {
                let word = self.build_ident(inner.next().unwrap());
                let position = self.build_expr(inner.next().unwrap());
                let color = self.build_expr(inner.next().unwrap());
                Entry::Stop {
                    word,
                    position,
                    color,
                    span,
                }
            }
            Rule::foreign_block => {
                let name = self.build_ident(inner.next().unwrap());
                Entry::Foreign { name, span }
            }
            Rule::flag => Entry::Flag {
                name: self.build_ident(inner.next().unwrap()),
            },
            Rule::positional => {
                let values: Vec<Expr> = inner
                    .filter(|p| p.as_rule() == Rule::component)
                    .map(|p| self.build_expr(p))
                    .collect();
                // The values alone: pest's pair also holds the blanks after
                // them (to the next line's entry).
                let end = values.last().map_or(span.end, |v| v.span.end);
                let span = Span::new(self.file, span.start as usize, end as usize);
                Entry::Positional { values, span }
            }
            Rule::material_entry => {
                inner.next(); // kw_material
                let m = inner.next().unwrap();
                let material = match m.as_rule() {
                    Rule::block => MaterialRef::Inline(self.build_block(m)),
                    Rule::ident => MaterialRef::Named(self.build_ident(m)),
                    r => unreachable!("material entry holds a block or a name, got {r:?}"),
                };
                Entry::Material { material, span }
            }
            Rule::materials_entry => {
                let word = self.build_ident(inner.next().unwrap());
                let open = self.span(&inner.next().unwrap());
                let swaps = inner
                    .filter(|p| p.as_rule() == Rule::material_swap)
                    .map(|p| self.build_swap(p))
                    .collect();
                let braces = Span::new(self.file, open.start as usize, span.end as usize);
                Entry::Materials {
                    word,
                    swaps,
                    braces,
                    span,
                }
            }
            r => unreachable!("not an entry: {r:?}"),
        }
    }

    /// `"Name" material`: a name in quotes, then a material's name or
    /// `material { … }`.
    fn build_swap(&self, pair: Pair<Rule>) -> MaterialSwap {
        let span = self.span(&pair);
        let mut inner = pair.into_inner();
        let name = inner.next().unwrap();
        let name_span = self.span(&name);
        let name = unescape(name.into_inner().next().unwrap().as_str());
        let m = inner.next().unwrap();
        let material = match m.as_rule() {
            Rule::ident => MaterialRef::Named(self.build_ident(m)),
            Rule::material_entry => match self.build_entry(m) {
                Entry::Material { material, .. } => material,
                _ => unreachable!("a material entry builds a material"),
            },
            r => unreachable!("a replaced material is a name or a material entry, got {r:?}"),
        };
        MaterialSwap {
            name,
            name_span,
            material,
            span,
        }
    }

    /// The next operand of `inner`: unary minus and not signs, a primary
    /// and its indexes.
    fn build_operand(&self, inner: &mut Pairs<Rule>) -> Expr {
        let mut signs: Vec<(Rule, Span)> = Vec::new();
        for pair in inner.by_ref() {
            let rule = pair.as_rule();
            if matches!(rule, Rule::neg | Rule::not) {
                // `--x` and `!!x` are `x`: a sign cancels the same sign
                // right before it, so that long runs cannot nest deeply.
                if signs.last().is_some_and(|(r, _)| *r == rule) {
                    signs.pop();
                } else {
                    signs.push((rule, self.span(&pair)));
                }
                continue;
            }
            let mut e = self.build_expr(pair);
            let mut indexes = Vec::new();
            while inner.peek().is_some_and(|p| p.as_rule() == Rule::index) {
                let index = inner.next().unwrap();
                indexes.push(self.build_expr(index.into_inner().nth(1).unwrap()));
            }
            if let Some(last) = indexes.last() {
                e = Expr {
                    span: e.span.join(last.span),
                    kind: ExprKind::Index {
                        base: Box::new(e),
                        indexes,
                    },
                };
            }
            if inner.peek().is_some_and(|p| p.as_rule() == Rule::member) {
                let member = self.build_ident(inner.next().unwrap().into_inner().next().unwrap());
                e = Expr {
                    span: e.span.join(member.span),
                    kind: ExprKind::Member {
                        base: Box::new(e),
                        member,
                    },
                };
            }
            // What is left alternates (`-!-x`): any two of them are a type
            // error whatever `x` is, found by the innermost two, so at
            // most those two are kept.
            let keep = signs.len().saturating_sub(2);
            for (rule, at) in signs.drain(keep..).rev() {
                let inner = Box::new(e);
                e = Expr {
                    span: at.join(inner.span),
                    kind: if rule == Rule::neg {
                        ExprKind::Neg(inner)
                    } else {
                        ExprKind::Not(inner)
                    },
                };
            }
            return e;
        }
        unreachable!("the grammar puts a primary after the signs")
    }

    /// An expression pair or a primary.
    fn build_expr(&self, pair: Pair<Rule>) -> Expr {
        let span = self.span(&pair);
        match pair.as_rule() {
            Rule::expr | Rule::component => {
                // The grammar keeps `a + b * -c < d` flat: operands and
                // operators alternate. Precedence is applied here, one
                // `Chain` node per run of one level, however long.
                let mut inner = pair.into_inner();
                let first = self.build_operand(&mut inner);
                // Most expressions are one operand (a vector's components):
                // no allocation for them.
                if inner.peek().is_none() {
                    return first;
                }
                let mut operands = vec![first];
                let mut ops = Vec::new();
                while let Some(op) = inner.next() {
                    let op_span = self.span(&op);
                    let op = BinOp::from_symbol(op.as_str()).expect("a binary operator");
                    ops.push((op, op_span));
                    operands.push(self.build_operand(&mut inner));
                }
                by_precedence(operands, ops, 0)
            }
            Rule::list => Expr {
                kind: ExprKind::List(
                    pair.into_inner()
                        .filter(|p| p.as_rule() == Rule::expr)
                        .map(|p| self.build_expr(p))
                        .collect(),
                ),
                span,
            },
            Rule::if_expr => {
                let mut exprs: Vec<Expr> = pair
                    .into_inner()
                    .filter(|p| p.as_rule() == Rule::expr)
                    .map(|p| self.build_expr(p))
                    .collect();
                let otherwise = Box::new(exprs.pop().expect("an else arm"));
                let mut arms = Vec::new();
                let mut it = exprs.into_iter();
                while let (Some(c), Some(v)) = (it.next(), it.next()) {
                    arms.push((c, v));
                }
                Expr {
                    kind: ExprKind::If { arms, otherwise },
                    span,
                }
            }
            Rule::number => Expr {
                kind: ExprKind::Number(pair.as_str().parse().unwrap_or(f64::INFINITY)),
                span,
            },
            Rule::string => Expr {
                kind: ExprKind::Str(unescape(pair.into_inner().next().unwrap().as_str())),
                span,
            },
            Rule::boolean => Expr {
                kind: ExprKind::Bool(pair.as_str() == "true"),
                span,
            },
            Rule::vector => Expr {
                kind: ExprKind::Vector(
                    pair.into_inner()
                        .filter(|p| p.as_rule() == Rule::component)
                        .map(|p| self.build_expr(p))
                        .collect(),
                ),
                span,
            },
            Rule::color => {
                let mut inner = pair.into_inner();
                inner.next(); // `rgb`
                Expr {
                    kind: ExprKind::Color(Box::new(self.build_operand(&mut inner))),
                    span,
                }
            }
            Rule::filter_color => {
                let mut inner = pair.into_inner();
                let word = self.build_ident(inner.next().unwrap());
                Expr {
                    kind: ExprKind::FilterColor {
                        word,
                        value: Box::new(self.build_operand(&mut inner)),
                    },
                    span,
                }
            }
            Rule::call => {
                let mut inner = pair.into_inner();
                let func = self.build_ident(inner.next().unwrap());
                let args = inner
                    .filter(|p| p.as_rule() == Rule::expr)
                    .map(|p| self.build_expr(p))
                    .collect();
                Expr {
                    kind: ExprKind::Call { func, args },
                    span,
                }
            }
            Rule::ident => Expr {
                kind: ExprKind::Name(pair.as_str().to_string()),
                span,
            },
            Rule::paren => {
                let inner = pair.into_inner().nth(1).unwrap();
                let mut e = self.build_expr(inner);
                e.span = span;
                e
            }
            r => unreachable!("not an expression: {r:?}"),
        }
    }
}

/// Resolves `\"`, `\\`, `\n` and `\t` escapes; other escaped characters stand for themselves.
pub fn unescape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    let mut chars = s.chars();
    while let Some(c) = chars.next() {
        if c == '\\' {
            match chars.next() {
                Some('n') => out.push('\n'),
                Some('t') => out.push('\t'),
                Some(other) => out.push(other),
                None => {}
            }
        } else {
            out.push(c);
        }
    }
    out
}

/// The expression `operands[0] ops[0] operands[1] …` with operators of
/// precedence `level` and above: split at the operators of `level`, each
/// part built one level up. Recursion depth is the number of levels (5).
fn by_precedence(operands: Vec<Expr>, ops: Vec<(BinOp, Span)>, level: u8) -> Expr {
    if ops.is_empty() {
        return operands.into_iter().next().expect("one operand");
    }
    let mut parts: Vec<Expr> = Vec::new();
    let mut links: Vec<(BinOp, Span)> = Vec::new();
    let mut part_operands = Vec::new();
    let mut part_ops = Vec::new();
    let mut operands = operands.into_iter();
    part_operands.push(operands.next().expect("one operand"));
    for ((op, at), rhs) in ops.into_iter().zip(operands) {
        if op.precedence() == level {
            parts.push(by_precedence(
                std::mem::take(&mut part_operands),
                std::mem::take(&mut part_ops),
                level + 1,
            ));
            links.push((op, at));
        } else {
            part_ops.push((op, at));
        }
        part_operands.push(rhs);
    }
    parts.push(by_precedence(part_operands, part_ops, level + 1));
    let mut parts = parts.into_iter();
    let first = parts.next().expect("one part");
    let rest = links
        .into_iter()
        .zip(parts)
        .map(|((op, s), e)| (op, s, e))
        .collect();
    chain((first, rest))
}

/// `first op x op y …` as one node spanning all operands (the operand
/// itself when there is no operator).
fn chain((first, rest): (Expr, Vec<(BinOp, Span, Expr)>)) -> Expr {
    match rest.last() {
        None => first,
        Some((_, _, last)) => Expr {
            span: first.span.join(last.span),
            kind: ExprKind::Chain {
                first: Box::new(first),
                rest,
            },
        },
    }
}
