//! Layer 7, many runs: parameter sweeps over scene paths and studies of
//! several factors.

pub mod study;
pub mod sweep;
