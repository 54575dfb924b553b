//! Typed getters with range checks over a block's checked [`Params`]:
//! what every block's conversion reads its values with.

use super::params::{Params, Val};
use super::scene::*;
use crate::diag::codes;
use crate::diag::{Diagnostic, Diagnostics};
use crate::span::Span;
use glam::DVec3;

pub fn range_error(what: &str, name: &str, span: Span, needs: &str, help: String) -> Diagnostic {
    Diagnostic::error(
        codes::OUT_OF_RANGE,
        format!("`{name}` of `{what}` must be {needs}"),
        span,
    )
    .with_label(format!("must be {needs}"))
    .with_help(help)
}

/// A whole-number setting and its range: the scene's `render { }` block
/// and the command line's overrides check it by the same rule.
#[derive(Debug, Clone, Copy)]
pub struct WholeSetting {
    /// Its name in `render { }`.
    pub name: &'static str,
    /// The least value.
    pub min: u64,
    /// The largest value.
    pub max: u64,
}

impl WholeSetting {
    /// `x` if it is a whole number in range, else what it must be.
    pub fn check(&self, x: f64) -> Result<u64, String> {
        if x.fract() == 0.0 && x >= self.min as f64 && x <= self.max as f64 {
            Ok(x as u64)
        } else {
            Err(self.needs())
        }
    }

    /// `text` (a command-line value) read as this setting.
    pub fn parse(&self, text: &str) -> Result<u64, String> {
        let x: f64 = text
            .trim()
            .parse()
            .map_err(|_| format!("`{text}` is not a number; {}", self.needs()))?;
        let why = match x.fract() {
            0.0 => "is out of range",
            _ => "is not a whole number",
        };
        self.check(x)
            .map_err(|needs| format!("{text} {why}: {needs}"))
    }

    /// "a whole number from 1 to 1000000".
    pub fn needs(&self) -> String {
        format!("a whole number from {} to {}", self.min, self.max)
    }
}

/// Typed getters with range checks over [`Params`].
pub struct Reader<'a> {
    /// The checked parameters.
    pub p: &'a Params,
    /// Where problems go.
    pub diags: &'a mut Diagnostics,
}

impl Reader<'_> {
    /// A number, if given.
    pub fn num(&mut self, name: &str) -> Option<(f64, Span)> {
        match self.p.get(name) {
            Some((Val::Num(x), s)) => Some((*x, *s)),
            _ => None,
        }
    }

    /// A number in `[lo, hi]` (with `open_lo`, `lo` excluded), or the default.
    pub fn num_in(&mut self, name: &str, lo: f64, hi: f64, open_lo: bool, default: f64) -> f64 {
        match self.num(name) {
            Some((x, s)) => {
                let ok = (if open_lo { x > lo } else { x >= lo }) && x <= hi;
                if ok {
                    x
                } else {
                    let needs = match (open_lo, hi.is_finite()) {
                        (true, false) => format!("greater than {lo}"),
                        (false, false) => format!("at least {lo}"),
                        (true, true) => format!("greater than {lo} and at most {hi}"),
                        (false, true) => format!("between {lo} and {hi}"),
                    };
                    let what = self.p.what.clone();
                    self.diags.push(range_error(
                        &what,
                        name,
                        s,
                        &needs,
                        format!("`{name}` is {x} here"),
                    ));
                    default
                }
            }
            None => default,
        }
    }

    /// A whole-number setting checked by its rule, or the default.
    pub fn whole(&mut self, setting: WholeSetting, default: u64) -> u64 {
        match self.num(setting.name) {
            Some((x, s)) => setting.check(x).unwrap_or_else(|needs| {
                let what = self.p.what.clone();
                self.diags.push(range_error(
                    &what,
                    setting.name,
                    s,
                    &needs,
                    format!("`{}` is {x} here", setting.name),
                ));
                default
            }),
            None => default,
        }
    }

    /// A vector of 3, if given.
    pub fn vec3(&mut self, name: &str) -> Option<(DVec3, Span)> {
        match self.p.get(name) {
            Some((Val::Vector(v), s)) if v.len() == 3 => Some((DVec3::new(v[0], v[1], v[2]), *s)),
            _ => None,
        }
    }

    /// A required vector of 3.
    pub fn vec3_req(
        &mut self,
        name: &'static str,
        schema: &[super::schema::ParamSpec],
    ) -> Option<(DVec3, Span)> {
        self.p.require(name, schema, self.diags)?;
        self.vec3(name)
    }

    /// A required number.
    pub fn num_req(
        &mut self,
        name: &'static str,
        schema: &[super::schema::ParamSpec],
    ) -> Option<(f64, Span)> {
        self.p.require(name, schema, self.diags)?;
        self.num(name)
    }

    /// A non-zero vector of 3 (a direction).
    pub fn direction(
        &mut self,
        name: &'static str,
        schema: &[super::schema::ParamSpec],
    ) -> Option<DVec3> {
        let (v, s) = self.vec3_req(name, schema)?;
        let Some(unit) = super::domain::unit(v) else {
            let what = self.p.what.clone();
            self.diags.push(range_error(
                &what,
                name,
                s,
                "a non-zero vector",
                "a direction needs a length; e.g. `<0, 1, 0>`".into(),
            ));
            return None;
        };
        Some(unit)
    }

    /// A colour with non-negative components, or the default.
    pub fn color(&mut self, name: &str, default: Rgb) -> Rgb {
        match self.p.get(name) {
            Some((Val::Color(c), s)) => {
                if c.iter().any(|x| *x < 0.0) {
                    let what = self.p.what.clone();
                    self.diags.push(range_error(
                        &what,
                        name,
                        *s,
                        "non-negative",
                        "colour components are ≥ 0".into(),
                    ));
                    default
                } else {
                    *c
                }
            }
            _ => default,
        }
    }

    /// A boolean, or the default.
    pub fn boolean(&mut self, name: &str, default: bool) -> bool {
        match self.p.get(name) {
            Some((Val::Bool(b), _)) => *b,
            _ => default,
        }
    }
}

/// The textures given to a material's parameters.
pub fn textures(p: &Params) -> Vec<(TextureInput, Texture)> {
    (TextureInput::ALL.iter())
        .filter_map(|&(name, input)| match p.get(name) {
            Some((Val::Texture(t), _)) => Some((input, (**t).clone())),
            _ => None,
        })
        .collect()
}
