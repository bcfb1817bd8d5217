//! The ring tyre model (method §5), its LSCE identification (method §6), the
//! paper's preset built on them (method §7) and the fidelity error of a modal
//! model against a reference.

#[allow(dead_code)] // each test binary uses a part of the shared helpers
#[path = "../support/mod.rs"]
mod support;

mod fe_modes;
mod fidelity;
mod frf_fit;
mod measured;
mod paper_preset;
mod ring_green;
mod ring_lsce;
