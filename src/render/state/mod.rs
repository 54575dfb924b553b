//! A render's state file: what a stopped render continues from, and what
//! `ptsc merge` adds up. An OpenEXR file of two parts, or three (docs/farm.md):
//!
//! - `image`: R, G, B as float32, the mean so far, so any EXR viewer
//!   shows how far the render got;
//! - `ptsc.light` (a third part, for `bdpt` and `ptlt` only): the light
//!   film, per pixel the sum of the splats it received (see `light`);
//! - `ptsc.state`: per pixel the sum of its samples as the bits of three
//!   f64 (channels `sum.R.hi`, `sum.R.lo`, … as uint32, the high and low
//!   halves) and its sample count (`count`, uint32), uncompressed; its
//!   header's text attribute `ptsc.state` is a JSON object naming the
//!   scene's fingerprint, every setting that shapes a sample, the samples
//!   per pixel of the whole render and the pass (K of N) it holds.
//!
//! Sums are kept bit for bit, so a render continued from its state adds
//! the very samples, in the very order, of an uninterrupted one. Both parts
//! are written and read block by block: a state of the largest image takes
//! no memory beyond its film.

mod file;
mod info;
mod light;
mod mismatch;

pub use file::{
    add_state, held_state, read_state, read_state_bytes, read_state_header, read_state_info,
    refuse_to_replace, write_state, HeldState, STATE_PART,
};
pub use info::{sample_settings, Pass, StateInfo};
pub use mismatch::Mismatch;
