//! pest pairs → AST. One `build_*` function per rule; rules that the grammar
//! makes impossible at a place are `unreachable!`.

use super::ast::*;
use super::parser::Rule;
use crate::source::FileId;
use crate::span::Span;
use pest::iterators::{Pair, Pairs};

/// Builds AST nodes from the pairs of one file.
pub struct Builder {
    /// The file the pairs come from.
    pub file: FileId,
    /// The first declaration that uses a reserved word as its name.
    pub reserved: std::cell::RefCell<Option<crate::diag::Diagnostic>>,
    /// Where in the file the parsed text starts (pairs count from there).
    pub base: std::cell::Cell<usize>,
}

impl Builder {
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
        if super::parser::KEYWORDS.contains(&id.name.as_str()) {
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
        let mut inner = pair.into_inner();
        match rule {
            Rule::let_stmt => {
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
                inner.next(); // ..
                let end = self.build_expr(inner.next().unwrap());
                inner.next(); // {
                let body = inner
                    .filter(|p| p.as_rule() != Rule::rbrace)
                    .map(|p| self.build_statement(p))
                    .collect();
                Statement::For {
                    var,
                    start,
                    end,
                    body,
                    span,
                }
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
                let kind_pair = inner.next().unwrap();
                let kind_span = self.span(&kind_pair);
                let kw = kind_pair.into_inner().next().unwrap();
                let kind = match kw.as_rule() {
                    Rule::kw_render => BlockKind::Render,
                    Rule::kw_camera => BlockKind::Camera,
                    Rule::kw_environment => BlockKind::Environment,
                    Rule::kw_sky => BlockKind::Sky,
                    Rule::kw_sphere => BlockKind::Sphere,
                    Rule::kw_plane => BlockKind::Plane,
                    Rule::kw_quad => BlockKind::Quad,
                    Rule::kw_disk => BlockKind::Disk,
                    Rule::kw_triangle => BlockKind::Triangle,
                    Rule::kw_box => BlockKind::Box,
                    Rule::kw_mesh => BlockKind::Mesh,
                    Rule::kw_point_light => BlockKind::PointLight,
                    Rule::kw_spot_light => BlockKind::SpotLight,
                    Rule::kw_directional_light => BlockKind::DirectionalLight,
                    r => unreachable!("block_kind holds only keywords, got {r:?}"),
                };
                let block = self.build_block(inner.next().unwrap());
                Statement::Block {
                    kind,
                    kind_span,
                    block,
                    span,
                }
            }
            r => unreachable!("not a statement: {r:?}"),
        }
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
            r => unreachable!("not an entry: {r:?}"),
        }
    }

    /// The next operand of `inner`: unary minus signs and a primary.
    fn build_operand(&self, inner: &mut Pairs<Rule>) -> Expr {
        let mut signs: Option<(Span, usize)> = None;
        for pair in inner.by_ref() {
            if pair.as_rule() == Rule::neg {
                let (first, n) = signs.unwrap_or((self.span(&pair), 0));
                signs = Some((first, n + 1));
                continue;
            }
            let e = self.build_expr(pair);
            // `--x` is `x`: runs of signs fold, so that long runs cannot nest deeply.
            return match signs {
                Some((first, n)) if n % 2 == 1 => Expr {
                    span: first.join(e.span),
                    kind: ExprKind::Neg(Box::new(e)),
                },
                _ => e,
            };
        }
        unreachable!("the grammar puts a primary after the signs")
    }

    /// An expression pair or a primary.
    fn build_expr(&self, pair: Pair<Rule>) -> Expr {
        let span = self.span(&pair);
        match pair.as_rule() {
            Rule::expr => {
                // The grammar keeps `a + b * -c` flat: operands and operators
                // alternate. Precedence in one pass: factors gather into the
                // current term; a `+` or `-` closes it into the sum. Each
                // level is one `Chain` node, however long.
                let mut inner = pair.into_inner();
                let first = self.build_operand(&mut inner);
                // Most expressions are one operand (a vector's components):
                // no allocation for them.
                let Some(op) = inner.next() else {
                    return first;
                };
                // Each term: its first factor and the further ones; the
                // operator before each term after the first.
                type Links = Vec<(BinOp, Span, Expr)>;
                let mut terms: Vec<(Expr, Links)> = vec![(first, Vec::new())];
                let mut sum_ops: Vec<(BinOp, Span)> = Vec::new();
                let mut next_op = Some(op);
                while let Some(op) = next_op.take().or_else(|| inner.next()) {
                    let op_span = self.span(&op);
                    let op = match op.as_str() {
                        "+" => BinOp::Add,
                        "-" => BinOp::Sub,
                        "*" => BinOp::Mul,
                        "/" => BinOp::Div,
                        "%" => BinOp::Rem,
                        o => unreachable!("operator {o}"),
                    };
                    let rhs = self.build_operand(&mut inner);
                    if matches!(op, BinOp::Mul | BinOp::Div | BinOp::Rem) {
                        terms
                            .last_mut()
                            .expect("one term")
                            .1
                            .push((op, op_span, rhs));
                    } else {
                        sum_ops.push((op, op_span));
                        terms.push((rhs, Vec::new()));
                    }
                }
                let mut terms = terms.into_iter().map(chain);
                let first = terms.next().expect("one term");
                let rest = sum_ops
                    .into_iter()
                    .zip(terms)
                    .map(|((op, s), e)| (op, s, e));
                chain((first, rest.collect()))
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
                        .filter(|p| p.as_rule() == Rule::expr)
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
