//! Sampling: deterministic sample streams per (seed, pixel, sample) —
//! independent or Owen-scrambled Sobol — and the
//! warps from the unit square to the distributions the renderer samples.

#[cfg(test)]
pub mod chi2;
pub mod distribution;
pub mod sampler;
pub mod sobol;
pub mod warp;
