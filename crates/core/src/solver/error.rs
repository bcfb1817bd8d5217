//! Errors of the solver: building a simulation from a problem
//! ([`BuildError`]), a step ([`SolverError`]) and a run ([`RunError`]).

use crate::base::error::{BasisError, FieldError};
use thiserror::Error;

/// A problem the solver cannot build its tables for.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum BuildError {
    /// A mode's residue could not be factored into rank terms that rebuild
    /// it (checked at set-up, method §3.4).
    #[error("problem \"{problem}\": {source}")]
    Basis {
        /// The problem's name.
        problem: String,
        #[source]
        source: BasisError,
    },
    /// An option of the solver does not apply to the problem's modes (the
    /// residual cut-off, method §4.7).
    #[error("problem \"{problem}\": {error}")]
    Option {
        problem: String,
        /// The option's field (`solver_options.…`), its value and what was
        /// expected.
        error: FieldError,
    },
}

/// Why a run driven by [`crate::solver::drive::run`] stopped early.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    /// A step could not be solved.
    #[error(transparent)]
    Solver(#[from] SolverError),
    /// What the run's observer writes failed (a CSV file, a frame).
    #[error("writing the run's output: {0}")]
    Output(#[from] std::io::Error),
    /// The run's cancel flag was set.
    #[error("cancelled after {steps} steps")]
    Cancelled { steps: u64 },
}

/// Errors of the time stepper. A step that fails leaves the simulation at the
/// start of that step.
#[derive(Debug, Clone, Error, PartialEq)]
pub enum SolverError {
    /// The contact system of the active points could not be solved.
    #[error(
        "singular contact system at t = {t_s:.6e} s for points {points:?} (pivot {pivot:.3e} after scaling): the modal model cannot hold these points on the road independently (too few modes for the points in contact?)"
    )]
    SingularContactSystem {
        t_s: f64,
        points: Vec<usize>,
        pivot: f64,
    },
    /// A displacement, velocity or force became NaN or infinite.
    #[error(
        "non-finite {quantity} at t = {t_s:.6e} s, point {point}: the step cannot be solved in floating point (a road, slope or preload far beyond a tyre's deflection, e.g. huge values in a measured road file?)"
    )]
    NonFinite {
        t_s: f64,
        point: usize,
        quantity: &'static str,
    },
    /// A measured road profile was sampled outside its extent.
    #[error(
        "road profile sampled at x = {x_m} m (t = {t_s:.6e} s, point {point}) outside its extent [{min_m}, {max_m}] m: set `looped: true`, shorten `duration_s`, or extend the file"
    )]
    RoadOutOfRange {
        t_s: f64,
        point: usize,
        x_m: f64,
        min_m: f64,
        max_m: f64,
    },
}
