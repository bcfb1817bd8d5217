//! # tirecontact-io
//!
//! What a simulation is given, read and checked: the RON scene format
//! ([`scene`]: parse, validate with file:line:column, edits by path, share
//! links), the file readers ([`readers`]: measured responses, FE modes, road
//! files), atomic writes ([`fsio`]) and [`identify`], which turns a scene
//! into a [`PreparedModel`]: its modes known, its road loaded, and the
//! solver's [`tirecontact_core::Problem`] built from it.

pub mod fsio;
pub mod identify;
pub mod readers;
pub mod scene;

pub use identify::{IdentifyError, ModeCache, PreparedModel, SceneSimulation};
pub use scene::{Scene, SceneError};
