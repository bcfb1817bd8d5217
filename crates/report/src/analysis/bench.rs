//! Measurements: the work-precision study behind `tirecontact bench`, and the
//! baselines it compares against (method §3 α/β form, direct convolution;
//! with the feature `peers`, Newmark and Dormand-Prince with penalty
//! contact).

use tirecontact_core::base::error::BasisError;
use tirecontact_core::solver::error::RunError;
use tirecontact_io::scene::SceneError;

pub mod baselines;
#[cfg(feature = "peers")]
pub mod peers;
pub mod residual;
pub mod scaling;
pub mod scenes;
pub mod skipped;
pub mod work_precision;

/// Why a measurement could not be made: its scene (a tyre not identified,
/// a road not read, a model not set up), its run, or a method that does
/// not apply to it.
#[derive(Debug, thiserror::Error)]
pub enum BenchError {
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// A mode's residue could not be factored into rank terms.
    #[error(transparent)]
    Basis(#[from] BasisError),
    /// A run stopped: a step that cannot be solved.
    #[error(transparent)]
    Run(#[from] RunError),
    /// The α/β form of the paper holds for underdamped modes only.
    #[error(
        "mode {mode}: damping ratio {damping_ratio}: the α/β form needs every damping ratio < 1"
    )]
    AlphaBetaDamping { mode: usize, damping_ratio: f64 },
    /// The adaptive integrator of a peer baseline gave up.
    #[cfg(feature = "peers")]
    #[error("Dormand-Prince 5(4): {0}")]
    Integration(#[from] ode_solvers::dop_shared::IntegrationError),
    /// The implicit integrator of a peer baseline gave up.
    #[cfg(feature = "peers")]
    #[error("BDF: {0}")]
    Implicit(#[from] diffsol::DiffsolError),
    /// The implicit peer's contact switched back and forth without end.
    #[cfg(feature = "peers")]
    #[error("BDF: the contact switches without end at t = {t_s} s")]
    Chattering { t_s: f64 },
    /// The implicit peer's tread springs asked of a scene without them.
    #[cfg(feature = "peers")]
    #[error(
        "BDF with tread springs: the scene's contact is not `Compliant` with one stiffness or one a point"
    )]
    NoTreadSprings,
    /// No run was timed (zero repeats).
    #[error("no run was timed")]
    NoRun,
    /// A scene measured as a patch whose points are not one.
    #[error(transparent)]
    Patch(#[from] crate::output::patch::PatchError),
}
