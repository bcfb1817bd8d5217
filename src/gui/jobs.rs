//! Work off the UI thread: the one background-job shape ([`Job`]) that the
//! identification, the exports and the researcher tools share.

pub mod export;
pub mod frames;
mod job;
pub mod prepare;
#[cfg(not(target_arch = "wasm32"))]
pub mod run_ahead;

pub use job::{Job, Progress, SLICE_S, SliceWork};
