//! Sampling: deterministic random streams per (seed, pixel, sample) and the
//! warps from the unit square to the distributions the renderer samples.

pub mod sampler;
pub mod warp;
