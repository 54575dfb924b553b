//! Expressions from pest pairs, operators applied by precedence (see
//! `build.rs`).

use super::ast::*;
use super::build::Builder;
use super::parser::Rule;
use crate::span::Span;
use pest::iterators::{Pair, Pairs};

impl Builder<'_> {
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
    pub(super) fn build_expr(&self, pair: Pair<Rule>) -> Expr {
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
