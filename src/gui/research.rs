//! Researcher tools of the visualiser: spectra of the current
//! run, parameter sweeps on a background thread, A/B comparison with a
//! pinned run, and the fidelity of the modal model against the ring's
//! Green functions. The logic lives in egui-free submodules; `state` holds
//! what the app keeps; the app runs their commands (`app/research_tools.rs`).

pub mod compare;
pub mod fidelity;
pub mod fidelity_job;
pub mod spectra;
pub mod spectra_job;
pub mod state;
pub mod sweep_job;
pub mod workbench_job;

pub use state::ResearchState;
