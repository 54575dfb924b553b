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
    /// `for var in start..end { body }`
    For {
        /// The loop variable.
        var: Ident,
        /// Inclusive start.
        start: Expr,
        /// Exclusive end.
        end: Expr,
        /// Statements repeated per iteration.
        body: Vec<Statement>,
        /// The whole loop.
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
    /// `render { }`, `camera { }`, a light or an object.
    Block {
        /// What the block declares.
        kind: BlockKind,
        /// The keyword.
        kind_span: Span,
        /// Its entries.
        block: Block,
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
            | Statement::Background { span, .. }
            | Statement::Material { span, .. }
            | Statement::Texture { span, .. }
            | Statement::Block { span, .. } => *span,
        }
    }
}

/// The kinds of block statement.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum BlockKind {
    /// `render { }` settings.
    Render,
    /// `camera { }`.
    Camera,
    /// `environment { }`: light from an image all around.
    Environment,
    /// `sky { }`: a daylight sky and its sun.
    Sky,
    /// `sphere { }`.
    Sphere,
    /// `plane { }` (infinite).
    Plane,
    /// `quad { }` (parallelogram).
    Quad,
    /// `disk { }`.
    Disk,
    /// `triangle { }`.
    Triangle,
    /// `box { }` (axis-aligned before transforms).
    Box,
    /// `mesh { }` (OBJ or PLY file).
    Mesh,
    /// `point_light { }`.
    PointLight,
    /// `spot_light { }`.
    SpotLight,
    /// `directional_light { }`.
    DirectionalLight,
}

impl BlockKind {
    /// Every block kind.
    pub const ALL: [BlockKind; 14] = [
        BlockKind::Render,
        BlockKind::Camera,
        BlockKind::Environment,
        BlockKind::Sky,
        BlockKind::Sphere,
        BlockKind::Plane,
        BlockKind::Quad,
        BlockKind::Disk,
        BlockKind::Triangle,
        BlockKind::Box,
        BlockKind::Mesh,
        BlockKind::PointLight,
        BlockKind::SpotLight,
        BlockKind::DirectionalLight,
    ];

    /// The keyword that opens the block.
    pub fn keyword(self) -> &'static str {
        match self {
            BlockKind::Render => "render",
            BlockKind::Camera => "camera",
            BlockKind::Environment => "environment",
            BlockKind::Sky => "sky",
            BlockKind::Sphere => "sphere",
            BlockKind::Plane => "plane",
            BlockKind::Quad => "quad",
            BlockKind::Disk => "disk",
            BlockKind::Triangle => "triangle",
            BlockKind::Box => "box",
            BlockKind::Mesh => "mesh",
            BlockKind::PointLight => "point_light",
            BlockKind::SpotLight => "spot_light",
            BlockKind::DirectionalLight => "directional_light",
        }
    }

    /// Whether the block is a geometric object (takes a material and transforms).
    pub fn is_shape(self) -> bool {
        !matches!(
            self,
            BlockKind::Render
                | BlockKind::Camera
                | BlockKind::Environment
                | BlockKind::Sky
                | BlockKind::PointLight
                | BlockKind::SpotLight
                | BlockKind::DirectionalLight
        )
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
    /// `material name` or `material { ... }`
    Material {
        /// The referenced or inline material.
        material: MaterialRef,
        /// The whole entry.
        span: Span,
    },
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
