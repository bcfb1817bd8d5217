//! The A/B compare view: its clipping of impact spikes, its plots kept
//! current without input, and its axis titles.

mod clip;
mod current;
mod fit;
mod rms;
mod titles;
mod unlike;
