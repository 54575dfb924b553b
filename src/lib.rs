//! # ptsc: a compiler and path tracer for `.pts` scenes
//!
//! The pipeline, one public function per stage:
//!
//! ```text
//! text ──parse──▶ ast::File ──check──▶ check::Scene ──lower──▶ ir::Scene ──render──▶ Film ──write──▶ image
//!      (syntax)             (check: diagnostics)    (ir: BVH, meshes)   (integrator, render)
//! ```
#![forbid(unsafe_code)]
#![warn(missing_docs)]

/// The `.pts` names of a setting's values, one list for the checker, the
/// command line, the docs and the editors: `NAMES` (name, value), `WORDS`
/// (the names alone, in order) and `from_name`. Used by `IntegratorKind`
/// and `LightSelection`, which live on different floors.
macro_rules! named_values {
    ($ty:ident { $($name:literal => $value:ident),+ $(,)? }) => {
        impl $ty {
            /// Every value with its `.pts` name.
            pub const NAMES: [(&'static str, $ty); [$($name),+].len()] = [$(($name, $ty::$value)),+];

            /// The names alone, in the order of `NAMES`.
            pub const WORDS: [&'static str; [$($name),+].len()] = [$($name),+];

            /// Looks a value up by name.
            pub fn from_name(name: &str) -> Option<Self> {
                Self::NAMES.iter().find(|(n, _)| *n == name).map(|(_, k)| *k)
            }

            /// The value's `.pts` name.
            pub fn name(self) -> &'static str {
                Self::NAMES.iter().find(|(_, k)| *k == self).map_or("", |(n, _)| n)
            }
        }
    };
}

pub mod accel;
pub mod bench_data;
pub mod camera;
pub mod check;
pub mod cli;
pub mod compile;
pub mod diag;
pub mod format;
pub mod fuzz;
pub mod geometry;
pub mod ide;
pub mod integrator;
pub mod ir;
pub mod light;
pub mod lower;
pub mod lsp;
pub mod material;
pub mod output;
pub mod render;
pub mod sampling;
pub mod source;
pub mod span;
pub mod syntax;
pub mod texture;
