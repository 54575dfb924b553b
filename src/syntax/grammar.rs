//! The parser pest generates from `grammar/pts.pest`, and its rules.
#![allow(missing_docs)]

use pest_derive::Parser;

/// The parser generated from `grammar/pts.pest`.
#[derive(Parser)]
#[grammar = "../grammar/pts.pest"]
pub struct PtsParser;
