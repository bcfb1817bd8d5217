//! # tirecontact
//!
//! Dynamic tyre/road contact by fast modal convolution (see `docs/method.md`, from
//! Meftah & Duhamel, CFM 2011): the application over the workspace's crates.
//!
//! | crate | modules (re-exported here) | what |
//! |---|---|---|
//! | `tirecontact-core` | [`base`], [`model`], [`solver`] | modes, tyres, roads as height functions, the convolution, the time stepper and its run driver |
//! | `tirecontact-io` | [`fsio`], [`readers`], [`scene`], [`identify`] | the scene format, the file readers, identification; a scene made into the solver's [`Problem`] |
//! | `tirecontact-report` | [`output`], [`analysis`], [`studies`] | the run sampler, CSV, figures, analysis, sweeps and studies |
//! | `tirecontact` (this crate) | `gui`, and the binary's command line | the visualiser (feature `gui`) and the `tirecontact` program (feature `cli`) |
//!
//! Each crate depends only on those above it in this table: Cargo keeps the
//! layers. Inside a crate the folders keep an order of their own, checked
//! by the test `layers` below (ARCHITECTURE.md).

pub use tirecontact_core::{base, model, solver};
pub use tirecontact_io::{fsio, identify, readers, scene};
pub use tirecontact_report::{analysis, output, studies};

#[cfg(feature = "gui")]
pub mod gui;

pub use tirecontact_core::{
    IDENTIFIED_RANK_TOLERANCE, Problem, RunError, Simulation, SolverError, SolverOptions,
    StepReport,
};
pub use tirecontact_io::{
    IdentifyError, ModeCache, PreparedModel, Scene, SceneError, SceneSimulation,
};

/// The preset opened when no file is given (embedded in the binary).
pub const DEFAULT_PRESET: &str =
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/presets/paper.ron"));
/// File name of the embedded default preset, for messages.
pub const DEFAULT_PRESET_NAME: &str = "presets/paper.ron";

#[cfg(test)]
mod layers;
