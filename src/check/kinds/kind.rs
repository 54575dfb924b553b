//! The row of the kind table: what a kind of block statement is, and what a
//! shape's conversion is given.

use super::super::params::Params;
use super::super::reader::{range_error, Reader};
use super::super::scene::{Light, Shape};
use super::super::schema::{ParamSpec, SHAPE_COMMON};
use crate::diag::{codes, Diagnostic, Diagnostics};
use crate::source::Files;
use crate::span::Span;
use glam::DVec3;
use std::path::Path;

/// One kind of block statement.
#[derive(Debug)]
pub struct Kind {
    /// The name that opens the block (`sphere`).
    pub name: &'static str,
    /// What it is, in a line (hover, docs).
    pub summary: &'static str,
    /// Its own parameters (a shape's common ones are in [`SHAPE_COMMON`]).
    pub params: &'static [ParamSpec],
    /// What it becomes in the scene.
    pub role: Role,
    /// POV-Ray's positional values of the kind (`sphere { <0, 1, 0>, 1 }`):
    /// the parameters they stand for in POV-Ray's order, and a note on what
    /// ptsc means otherwise (empty if none).
    pub positional: Option<(&'static [&'static str], &'static str)>,
    /// POV-Ray statement words that this kind stands for in ptsc, each
    /// with the help line that says how ptsc writes it.
    pub povray: &'static [(&'static str, &'static str)],
}

/// What a block statement becomes.
#[derive(Debug, Clone, Copy)]
pub enum Role {
    /// One of the scene's settings, kept by the checker.
    Setting(Setting),
    /// A light that is not a shape, from its checked parameters.
    Light(fn(&Params, &mut Diagnostics) -> Option<Light>),
    /// An object's shape before transforms, from its checked parameters.
    Shape(fn(&mut ShapeInput) -> Option<Shape>),
}

/// The settings blocks, each given at most once.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Setting {
    /// `render { }`
    Render,
    /// `camera { }`
    Camera,
    /// `environment { }`
    Environment,
    /// `sky { }`
    Sky,
    /// `atmosphere { }`
    Atmosphere,
}

impl Kind {
    /// Whether it is an object's shape.
    pub fn is_shape(&self) -> bool {
        matches!(self.role, Role::Shape(_))
    }

    /// Whether it is a light that is not a shape.
    pub fn is_light(&self) -> bool {
        matches!(self.role, Role::Light(_))
    }

    /// The schemas its block is checked against: its own parameters, and
    /// a shape's common ones (transforms, motion).
    pub fn schemas(&self) -> [&'static [ParamSpec]; 2] {
        let common: &[_] = if self.is_shape() { SHAPE_COMMON } else { &[] };
        [self.params, common]
    }

    /// Whether its block takes a `material` (an object's shape), read by
    /// the checker beside the rows.
    pub fn takes_material(&self) -> bool {
        self.is_shape()
    }

    /// Every name its block accepts, in order: its rows' parameters (not
    /// the refused POV-Ray words), then `material` where it takes one. The
    /// list check's help gives for a misspelt name, and hover's.
    pub fn accepted(&self) -> Vec<&'static str> {
        super::super::schema::accepted_names(&self.schemas(), self.takes_material())
    }

    /// Its parameter `name`, if it has one (common ones included).
    pub fn param(&self, name: &str) -> Option<&'static ParamSpec> {
        self.schemas()
            .into_iter()
            .flatten()
            .find(|p| p.name == name && p.povray.is_none())
    }
}

/// What a shape's conversion reads: its checked parameters, where problems
/// go, and where the files it names are found.
pub struct ShapeInput<'a> {
    /// The parameters, with typed getters.
    pub r: Reader<'a>,
    /// The shape's row.
    pub kind: &'static Kind,
    /// The folder of the scene file that holds the block.
    pub base_dir: &'a Path,
    /// Where files are read.
    pub files: &'a dyn Files,
}

impl ShapeInput<'_> {
    /// The checked parameters.
    pub fn params(&self) -> &Params {
        self.r.p
    }

    /// A required vector of 3 and where it is written.
    pub fn vec3(&mut self, name: &'static str) -> Option<(DVec3, Span)> {
        self.r.vec3_req(name, self.kind.params)
    }

    /// A required number and where it is written.
    pub fn num(&mut self, name: &'static str) -> Option<(f64, Span)> {
        self.r.num_req(name, self.kind.params)
    }

    /// A required non-zero vector, normalised.
    pub fn direction(&mut self, name: &'static str) -> Option<DVec3> {
        self.r.direction(name, self.kind.params)
    }

    /// A vector of 3, or `default` when not given.
    pub fn vec3_or(&mut self, name: &str, default: DVec3) -> DVec3 {
        self.r.vec3(name).map_or(default, |v| v.0)
    }

    /// A required number above 0 (a size).
    pub fn positive(&mut self, name: &'static str) -> Option<f64> {
        let (x, s) = self.num(name)?;
        if x > 0.0 {
            return Some(x);
        }
        self.r.diags.push(range_error(
            self.kind.name,
            name,
            s,
            "greater than 0",
            format!("`{name}` is {x} here; give a positive size"),
        ));
        None
    }

    /// A boolean, or `default`.
    pub fn boolean(&mut self, name: &str, default: bool) -> bool {
        self.r.boolean(name, default)
    }

    /// Reports a shape without area or volume (`message` at `span`, with
    /// its `label` and `help`); always `None`.
    pub fn degenerate(
        &mut self,
        message: impl Into<String>,
        span: Span,
        label: &str,
        help: &str,
    ) -> Option<Shape> {
        self.r.diags.push(
            Diagnostic::error(codes::DEGENERATE, message, span)
                .with_label(label)
                .with_help(help),
        );
        None
    }

    /// Where problems go.
    pub fn diags(&mut self) -> &mut Diagnostics {
        self.r.diags
    }
}
