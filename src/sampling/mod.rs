//! Sampling: deterministic random streams per (seed, pixel, sample) and the
//! warps from the unit square to the distributions the renderer samples.

#[cfg(test)]
pub mod chi2;
pub mod distribution;
pub mod sampler;
pub mod warp;
