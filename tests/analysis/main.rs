//! What is computed from runs: spectra, sweeps, A/B comparisons, the
//! work-precision study, and the point colours of the figures.

#[allow(dead_code)] // each test binary uses a part of the shared helpers
#[path = "../support/mod.rs"]
mod support;

mod compare;
mod metrics_converge;
mod palette;
mod spectrum;
mod sweep;
mod work_precision;
