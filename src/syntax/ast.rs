//! The abstract syntax tree: plain data, every node with its span, no
//! semantic information. Built by `syntax::build`, read by `check`.

use crate::span::Span;

/// A parsed file.
#[derive(Debug, Clone, PartialEq)]
pub struct File {
    /// Top-level statements in source order.
    pub statements: Vec<Statement>,
}

/// A name as written, with its span.
#[derive(Debug, Clone, PartialEq)]
pub struct Ident {
    /// The text of the name.
    pub name: String,
    /// Where it is.
    pub span: Span,
}

/// A top-level (or loop-body) statement.
#[derive(Debug, Clone, PartialEq)]
pub enum Statement {
    /// `let name = value;`
    Let {
        /// The constant's name.
        name: Ident,
        /// Its value.
        value: Expr,
        /// The whole statement.
        span: Span,
    },
    /// `include "path"`
    Include {
        /// The path, unescaped.
        path: String,
        /// The string literal.
        path_span: Span,
        /// The whole statement.
        span: Span,
    },
    /// `for var in start..end { body }`, or `for var in list { body }`
    /// (then `end` is `None` and `start` is the list).
    For {
        /// The loop variable.
        var: Ident,
        /// Inclusive start, or the list.
        start: Expr,
        /// Exclusive end of a range.
        end: Option<Expr>,
        /// Statements repeated per iteration.
        body: Vec<Statement>,
        /// The whole loop.
        span: Span,
    },
    /// `if c { … } else if d { … } else { … }`
    If {
        /// Each condition with its statements, in order.
        arms: Vec<(Expr, Vec<Statement>)>,
        /// The statements of the final `else`, if any.
        otherwise: Option<Vec<Statement>>,
        /// The whole statement.
        span: Span,
    },
    /// `fn name(params) = body;`
    Function {
        /// The function's name.
        name: Ident,
        /// Its parameters.
        params: Vec<Ident>,
        /// Its value.
        body: std::sync::Arc<Expr>,
        /// The whole declaration.
        span: Span,
    },
    /// `group name { statements }`
    Group {
        /// The group's name.
        name: Ident,
        /// The objects (and placements of other groups) it holds.
        body: Vec<Statement>,
        /// The whole declaration.
        span: Span,
    },
    /// `instance name { transforms, material, velocity }`
    Instance {
        /// The group placed.
        group: Ident,
        /// Its placement.
        block: Block,
        /// The whole statement.
        span: Span,
    },
    /// `background value`
    Background {
        /// The radiance.
        value: Expr,
        /// The whole statement.
        span: Span,
    },
    /// `material name { ... }`
    Material {
        /// The material's name.
        name: Ident,
        /// Its parameters.
        block: Block,
        /// The whole declaration.
        span: Span,
    },
    /// `texture name kind { ... }`
    Texture {
        /// The texture's name.
        name: Ident,
        /// Its kind (`wood`).
        kind: Ident,
        /// Its parameters.
        block: Block,
        /// The whole declaration.
        span: Span,
    },
    /// `render { }`, `camera { }`, a light or an object: `kind { … }`.
    Block {
        /// The name of its kind (`sphere`), looked up in the checker's
        /// kind table.
        kind: Ident,
        /// Its entries.
        block: Block,
        /// The whole statement.
        span: Span,
    },
    /// `#word …`: a POV-Ray directive and the rest of its line, not read;
    /// `#declare NAME = value;` keeps its name and value.
    Directive {
        /// The directive's word, without the `#`.
        name: Ident,
        /// The name a `#declare` or `#local` binds, with its value where
        /// the line reads as one (`#declare R = 1;`), or a `#for`'s variable
        /// (no value).
        binding: Option<(Ident, Option<Expr>)>,
        /// A `#macro`'s parameters, bound (without values) for the lines
        /// of its body that ptsc reads.
        parameters: Vec<Ident>,
        /// The whole line.
        span: Span,
    },
    /// `name { … }`: a statement ptsc does not have (POV-Ray's
    /// `light_source { … }`), its content not read.
    Foreign {
        /// The statement's word.
        name: Ident,
        /// The whole statement.
        span: Span,
    },
}

impl Statement {
    /// The whole statement.
    pub fn span(&self) -> Span {
        match self {
            Statement::Let { span, .. }
            | Statement::Include { span, .. }
            | Statement::For { span, .. }
            | Statement::If { span, .. }
            | Statement::Function { span, .. }
            | Statement::Group { span, .. }
            | Statement::Instance { span, .. }
            | Statement::Background { span, .. }
            | Statement::Material { span, .. }
            | Statement::Texture { span, .. }
            | Statement::Block { span, .. }
            | Statement::Foreign { span, .. }
            | Statement::Directive { span, .. } => *span,
        }
    }
}

/// A braced list of entries.
#[derive(Debug, Clone, PartialEq)]
pub struct Block {
    /// Entries in source order.
    pub entries: Vec<Entry>,
    /// From `{` to `}`.
    pub span: Span,
}

/// One entry of a block.
#[derive(Debug, Clone, PartialEq)]
pub enum Entry {
    /// `name` alone before the block's `}` (POV-Ray's `no_shadow`).
    Flag {
        /// The name.
        name: Ident,
    },
    /// `name value`
    Param {
        /// Parameter name.
        name: Ident,
        /// Its value.
        value: Expr,
        /// The whole entry.
        span: Span,
    },
    /// `name kind { ... }`: a parameter given a texture.
    Texture {
        /// Parameter name.
        name: Ident,
        /// The texture's kind (`checker`).
        kind: Ident,
        /// Its parameters.
        block: Block,
        /// The whole entry.
        span: Span,
    },
    /// `stop position colour`: a stop of a texture's colour map.
    Stop {
        /// The word `stop`.
        word: Ident,
        /// Where the stop is, in [0, 1].
        position: Expr,
        /// Its colour.
        color: Expr,
        /// The whole entry.
        span: Span,
    },
    /// `name { … }`: a block ptsc does not have (POV-Ray's `pigment
    /// { … }`), its content not read.
    Foreign {
        /// The block's name.
        name: Ident,
        /// The whole entry.
        span: Span,
    },
    /// `value, value, …` without a parameter name (POV-Ray's
    /// `sphere { <0, 1, 0>, 1 }`).
    Positional {
        /// The values, in order.
        values: Vec<Expr>,
        /// The whole entry.
        span: Span,
    },
    /// `material name` or `material { ... }`
    Material {
        /// The referenced or inline material.
        material: MaterialRef,
        /// The whole entry.
        span: Span,
    },
    /// `materials { "Name" material … }`: a mesh file's materials
    /// replaced by name.
    Materials {
        /// The word `materials`.
        word: Ident,
        /// The replacements, in order.
        swaps: Vec<MaterialSwap>,
        /// From `{` to `}`.
        braces: Span,
        /// The whole entry.
        span: Span,
    },
}

/// `"Name" material`: one of a mesh file's materials replaced.
#[derive(Debug, Clone, PartialEq)]
pub struct MaterialSwap {
    /// The material's name in the file.
    pub name: String,
    /// Where the name is written (its quotes included).
    pub name_span: Span,
    /// The scene's material that replaces it.
    pub material: MaterialRef,
    /// The whole pair.
    pub span: Span,
}

/// How an object names its material.
#[derive(Debug, Clone, PartialEq)]
pub enum MaterialRef {
    /// By name.
    Named(Ident),
    /// Inline.
    Inline(Block),
}

/// An expression with its span.
#[derive(Debug, Clone, PartialEq)]
pub struct Expr {
    /// What it is.
    pub kind: ExprKind,
    /// Where it is.
    pub span: Span,
}

impl Expr {
    /// Calls `f` with every name the expression reads and where, and
    /// whether it is a called function's (an explicit stack: an expression
    /// may nest deeply). Expressions bind no names, so each is looked up
    /// in the scope around the expression.
    pub fn each_name(&self, f: &mut dyn FnMut(&str, Span, bool)) {
        let mut stack = vec![self];
        while let Some(e) = stack.pop() {
            match &e.kind {
                ExprKind::Name(name) => f(name, e.span, false),
                ExprKind::Call { func, args } => {
                    f(&func.name, func.span, true);
                    stack.extend(args);
                }
                ExprKind::Number(_) | ExprKind::Str(_) | ExprKind::Bool(_) => {}
                ExprKind::Vector(items) | ExprKind::List(items) => stack.extend(items),
                ExprKind::Color(inner) | ExprKind::Neg(inner) | ExprKind::Not(inner) => {
                    stack.push(inner)
                }
                ExprKind::FilterColor { value, .. } => stack.push(value),
                ExprKind::Member { base, .. } => stack.push(base),
                ExprKind::Index { base, indexes } => {
                    stack.push(base);
                    stack.extend(indexes);
                }
                ExprKind::If { arms, otherwise } => {
                    stack.extend(arms.iter().flat_map(|(c, v)| [c, v]));
                    stack.push(otherwise);
                }
                ExprKind::Chain { first, rest } => {
                    stack.push(first);
                    stack.extend(rest.iter().map(|r| &r.2));
                }
            }
        }
    }
}

/// Binary operators.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BinOp {
    /// `+`
    Add,
    /// `-`
    Sub,
    /// `*`
    Mul,
    /// `/`
    Div,
    /// `%`: the remainder of a division, with the sign of the dividend
    /// (C's `fmod`, POV-Ray's `mod`).
    Rem,
    /// `==`
    Eq,
    /// `!=`
    Ne,
    /// `<`
    Lt,
    /// `<=`
    Le,
    /// `>`
    Gt,
    /// `>=`
    Ge,
    /// `&&`: true when both are (the right side is evaluated only when
    /// the left is true).
    And,
    /// `||`: true when either is (the right side is evaluated only when
    /// the left is false).
    Or,
}

impl BinOp {
    /// The operator as written.
    pub fn symbol(self) -> &'static str {
        match self {
            BinOp::Add => "+",
            BinOp::Sub => "-",
            BinOp::Mul => "*",
            BinOp::Div => "/",
            BinOp::Rem => "%",
            BinOp::Eq => "==",
            BinOp::Ne => "!=",
            BinOp::Lt => "<",
            BinOp::Le => "<=",
            BinOp::Gt => ">",
            BinOp::Ge => ">=",
            BinOp::And => "&&",
            BinOp::Or => "||",
        }
    }

    /// The operator written `s`.
    pub fn from_symbol(s: &str) -> Option<BinOp> {
        Some(match s {
            "+" => BinOp::Add,
            "-" => BinOp::Sub,
            "*" => BinOp::Mul,
            "/" => BinOp::Div,
            "%" => BinOp::Rem,
            "==" => BinOp::Eq,
            "!=" => BinOp::Ne,
            "<" => BinOp::Lt,
            "<=" => BinOp::Le,
            ">" => BinOp::Gt,
            ">=" => BinOp::Ge,
            "&&" => BinOp::And,
            "||" => BinOp::Or,
            _ => return None,
        })
    }

    /// How tightly the operator binds: `||` 0, `&&` 1, comparisons 2,
    /// `+ -` 3, `* / %` 4 (as in C, Rust and POV-Ray).
    pub fn precedence(self) -> u8 {
        match self {
            BinOp::Or => 0,
            BinOp::And => 1,
            BinOp::Eq | BinOp::Ne | BinOp::Lt | BinOp::Le | BinOp::Gt | BinOp::Ge => 2,
            BinOp::Add | BinOp::Sub => 3,
            BinOp::Mul | BinOp::Div | BinOp::Rem => 4,
        }
    }
}

/// The kinds of expression.
#[derive(Debug, Clone, PartialEq)]
pub enum ExprKind {
    /// A number literal (may be infinite if written too large; the checker reports it).
    Number(f64),
    /// A string literal, unescaped.
    Str(String),
    /// `true` / `false`.
    Bool(bool),
    /// `<a, b, ...>`
    Vector(Vec<Expr>),
    /// `rgb x`
    Color(Box<Expr>),
    /// A name: a constant, a loop variable or a word such as `path`.
    Name(String),
    /// `f(args)`
    Call {
        /// The function.
        func: Ident,
        /// Its arguments.
        args: Vec<Expr>,
    },
    /// `-x`
    Neg(Box<Expr>),
    /// `!x`
    Not(Box<Expr>),
    /// `[a, b, c]`
    List(Vec<Expr>),
    /// `list[i][j]…`: one node for a run of indexes.
    Index {
        /// The list indexed.
        base: Box<Expr>,
        /// Each index, outermost first.
        indexes: Vec<Expr>,
    },
    /// `v.x`: a component of a vector or colour by name.
    Member {
        /// The vector or colour.
        base: Box<Expr>,
        /// The component's name (`x`, `red`, …).
        member: Ident,
    },
    /// POV-Ray's `rgbf x`, `rgbt x` or `rgbft x`: a colour with filter or
    /// transmit channels, which ptsc does not have (the checker says what
    /// to write instead).
    FilterColor {
        /// The word (`rgbf`, `rgbt`, `rgbft`).
        word: Ident,
        /// Its value.
        value: Box<Expr>,
    },
    /// `if c { a } else if d { b } else { e }`
    If {
        /// Each condition with its value, in order.
        arms: Vec<(Expr, Expr)>,
        /// The value when no condition holds.
        otherwise: Box<Expr>,
    },
    /// Operands of one precedence level, `a op b op c …`, folded from the
    /// left: a sum of terms or a product of factors. One node per chain, not
    /// one per operator, so a long chain adds no depth (the evaluator loops).
    Chain {
        /// The first operand.
        first: Box<Expr>,
        /// Each further operator (with where it is written) and its
        /// operand, in source order.
        rest: Vec<(BinOp, Span, Expr)>,
    },
}
