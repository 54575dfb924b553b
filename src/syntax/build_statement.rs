//! Statements, blocks and their entries from pest pairs (see `build.rs`).

use super::ast::*;
use super::build::Builder;
use super::build_expr::unescape;
use super::parser::Rule;
use crate::span::Span;
use pest::iterators::{Pair, Pairs};

impl Builder<'_> {
    /// `file`, parsed whole.
    pub fn build_file(&self, pair: Pair<Rule>) -> File {
        let statements = pair
            .into_inner()
            .filter(|p| p.as_rule() != Rule::EOI)
            .map(|p| self.build_statement(p))
            .collect();
        File { statements }
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
            Rule::for_stmt => self.build_for(inner, span),
            Rule::if_stmt => self.build_if(inner, span),
            Rule::fn_stmt | Rule::fn_head => self.build_fn(inner, span),
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
            Rule::texture_decl => self.build_texture_decl(inner, span),
            Rule::block_stmt => {
                let kind = self.build_ident(inner.next().unwrap());
                let block = self.build_block(inner.next().unwrap());
                Statement::Block { kind, block, span }
            }
            Rule::directive_stmt => self.build_directive(inner, span, pair_text),
            Rule::declare_stmt => self.build_declare(inner, span),
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

    /// `for NAME in a..b { … }` (or `in LIST`).
    fn build_for(&self, mut inner: Pairs<Rule>, span: Span) -> Statement {
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

    /// `if c { … } else if d { … } else { … }`.
    fn build_if(&self, inner: Pairs<Rule>, span: Span) -> Statement {
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

    /// `fn NAME(a, b) = …;`.
    fn build_fn(&self, mut inner: Pairs<Rule>, span: Span) -> Statement {
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

    /// `texture NAME KIND { … }`.
    fn build_texture_decl(&self, mut inner: Pairs<Rule>, span: Span) -> Statement {
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

    /// A POV-Ray directive, read whole: the name it binds (`#macro NAME(…)`) and a macro's parameters, so that their uses raise nothing more.
    fn build_directive(&self, mut inner: Pairs<Rule>, span: Span, pair_text: &str) -> Statement {
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

    /// POV-Ray's `#declare NAME = …;`, bound as `let` would.
    fn build_declare(&self, mut inner: Pairs<Rule>, span: Span) -> Statement {
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
            *slot = Some(super::hints::convert_error(
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
}
