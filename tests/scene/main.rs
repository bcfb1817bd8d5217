//! Scenes as files: the shipped presets, bad presets and the errors they
//! give, and property tests with arbitrary, hostile and corrupted scenes.
//! Failing seeds of the property tests are kept in
//! `tests/proptest-regressions/<module>.txt` (where proptest looks for them).

#[allow(dead_code)] // each test binary uses a part of the shared helpers
#[path = "../support/mod.rs"]
mod support;

mod bad_presets;
mod crg;
mod fuzz;
mod hostile;
mod presets;
