//! Scenes: what is simulated, as written in RON preset files, and their
//! validation. Every validation error names the field, the value and what was
//! expected; syntax errors give file, line and column, and so do validation
//! errors of a preset's text (where it writes the field, `locate`).

use serde::{Deserialize, Serialize};
use std::path::PathBuf;
use tirecontact_core::model::road::Road;

mod edits;
mod error;
pub mod fields;
mod load;
pub mod locate;
pub mod points;
pub mod share;
mod tyre;
mod validate;
pub use edits::{described_with_edits, edits_since, edits_since_identified};
pub use error::SceneError;
pub use load::load_road;
pub use points::{PointGrid, Points, Preload};
pub use tyre::Tyre;

pub use tirecontact_core::solver::problem::{Contact, ContactScheme, Point, RunShape};

/// Largest tread stiffness accepted (N/m).
pub const MAX_TREAD_STIFFNESS_N_M: f64 = 1e16;

pub use tirecontact_core::base::modal::Mode;

/// A complete scene: tyre, contact points, road, speed and time stepping.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// Display name.
    pub name: String,
    /// Free text shown with the scene (optional).
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub description: String,
    /// The tyre model. Changing it restarts the run.
    pub tyre: Tyre,
    /// Contact points: a list of `Point(...)`, or `Grid(...)` (see
    /// [`PointGrid`]). Changing them restarts the run.
    pub points: Points,
    /// Road profile. Applied live.
    pub road: Road,
    /// Rolling speed `V` (m/s), >= 0. Applied live.
    pub speed_mps: f64,
    /// Ramp time `T_ramp` (s) of preload and road, >= 0; default 0.
    #[serde(default)]
    pub ramp_s: f64,
    /// Time step (s), > 0. Changing it restarts the run.
    pub dt_s: f64,
    /// Duration of a run (s), >= dt_s.
    pub duration_s: f64,
    /// Contact scheme; default `Located`.
    #[serde(default)]
    pub contact_scheme: ContactScheme,
    /// Contact law; default `Rigid` (the paper's kinematic contact).
    #[serde(default, skip_serializing_if = "Contact::is_rigid")]
    pub contact: Contact,
    /// Folder the scene was loaded from (for relative road files). Not saved.
    #[serde(skip)]
    pub base_dir: Option<PathBuf>,
}

/// Largest number of steps a run may have (bounds memory and time).
pub const MAX_STEPS: f64 = 1e10;

/// Largest scene file read (bytes): 64 MiB, far above any preset (mode
/// shapes take 20 bytes per point and mode).
pub const MAX_SCENE_BYTES: u64 = 64 << 20;

/// Largest number of contact points: the contact solver keeps about 16 P²
/// numbers (operators and their factorisations), 0.5 GB at 2000 points.
pub const MAX_POINTS: usize = 2000;

/// Largest number of sampled response values (pairs of points times
/// samples) a ring tyre's identification may need: 5e7 values, 400 MB; the
/// paper preset needs 1.5e4, 300 points at its 1000 samples 4.5e7.
pub const MAX_RING_RESPONSE_VALUES: f64 = 5e7;

impl Scene {
    /// Number of contact points `P`.
    pub fn num_points(&self) -> usize {
        self.points.len()
    }

    /// Whether the tyre's modes are identified from responses (a ring or
    /// measured tyre) rather than given or computed exactly.
    pub fn modes_identified(&self) -> bool {
        matches!(self.tyre, Tyre::Ring { .. } | Tyre::Measured { .. })
    }

    /// Steps of the whole run ([`RunShape::num_steps`]).
    pub fn num_steps(&self) -> u64 {
        RunShape::num_steps(self)
    }
}

impl RunShape for Scene {
    fn points(&self) -> &[Point] {
        &self.points
    }
    fn dt_s(&self) -> f64 {
        self.dt_s
    }
    fn duration_s(&self) -> f64 {
        self.duration_s
    }
    fn ramp_s(&self) -> f64 {
        self.ramp_s
    }
    fn grid_spacing_m(&self) -> Option<(f64, f64)> {
        self.points.grid().map(|g| g.spacing_m)
    }
}
