//! Layer 6, analysis of runs: spectra and bands, run metrics, A/B compare,
//! the fidelity of a modal model, the work-precision and scaling benchmarks.

pub mod bench;
pub mod compare;
pub mod fidelity;
pub mod metrics;
pub mod spectrum;
