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

pub mod accel;
pub mod bench_data;
pub mod camera;
pub mod check;
pub mod cli;
pub mod compile;
pub mod diag;
pub mod fuzz;
pub mod geometry;
pub mod integrator;
pub mod ir;
pub mod light;
pub mod lower;
pub mod material;
pub mod output;
pub mod render;
pub mod sampling;
pub mod source;
pub mod span;
pub mod syntax;
pub mod texture;
