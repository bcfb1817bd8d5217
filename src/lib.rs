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
//!
//! A preset read, prepared (validated, modes known, road loaded) and run to
//! its end by the one run driver with one probe:
//!
//! ```
//! use tirecontact::solver::drive::{Watch, run_to_end};
//! use tirecontact::output::record::Recording;
//! use tirecontact::{ModeCache, PreparedModel, Scene, SolverOptions};
//!
//! let mut scene = Scene::load(std::path::Path::new("presets/three_points.ron"))?;
//! scene.duration_s = 0.01;
//! // validation, a ring tyre's identification, a measured road's file: here
//! let model = PreparedModel::new(&scene, &ModeCache::new())?;
//! let mut sim = model.simulation(SolverOptions::default())?;
//! let mut rec = Recording::new(scene.num_points(), scene.num_steps(), 100);
//! run_to_end(&mut sim, &mut rec, Watch::none())?;
//! assert!(sim.finished());
//! assert_eq!(rec.t_s.last(), Some(&sim.time_s()));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

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
