//! The problem a [`Simulation`](super::simulation::Simulation) is given
//! (method §1, §4): the contact points, the tyre's modes, the road as a
//! height function, the contact law and scheme, the time step, the run's
//! length, the rolling speed and the ramp. The solver knows nothing of the
//! file it came from: `tirecontact-io` builds a [`Problem`] from a scene.

use crate::base::modal::Mode;
use crate::model::road::RoadProfile;
use serde::{Deserialize, Serialize};
use std::sync::Arc;

/// How contact is decided inside a time step (method §4).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum ContactScheme {
    /// Impacts and releases located inside the step (second order). Default.
    #[default]
    Located,
    /// The paper's plain scheme: contact decided at step ends (first order).
    Paper,
}

/// Contact law between a tyre point and the road.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub enum Contact {
    /// The paper's rigid kinematic contact (method §4): while in contact the
    /// point follows the road in position and velocity. Default.
    #[default]
    Rigid,
    /// A tread spring in series with the tyre at each point: force
    /// `q = k max(0, r - u)`, its landings and releases located inside the
    /// step (method §4, "Events inside the step"; see
    /// `simulation/compliant.rs`). Overrides `contact_scheme`.
    Compliant {
        /// Tread stiffness `k` (N/m), > 0: one value for every point, or one
        /// per point.
        stiffness_n_m: Vec<f64>,
    },
}

impl Contact {
    pub fn is_rigid(&self) -> bool {
        matches!(self, Contact::Rigid)
    }

    /// Stiffness per point (N/m) for `p` points; empty for rigid contact.
    pub fn stiffness_per_point(&self, p: usize) -> Vec<f64> {
        match self {
            Contact::Rigid => Vec::new(),
            Contact::Compliant { stiffness_n_m: k } if k.len() == 1 => vec![k[0]; p],
            Contact::Compliant { stiffness_n_m: k } => k.clone(),
        }
    }
}

/// A contact point of the contact patch.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Point {
    /// Longitudinal position `x_i` (m) along the contact line.
    pub x_m: f64,
    /// Lateral position `y_i` (m) across the tread, 0 on its centreline;
    /// default 0, not written when 0. The road is a profile `z(x)` and
    /// does not see it; a modal tyre's residues may depend on it.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub y_m: f64,
    /// Undeformed height `h_i` (m) above the mean road plane; < 0 is preload.
    pub h_m: f64,
}

/// `y_m` left out of a saved point: 0, the centreline (either sign).
fn is_zero(y_m: &f64) -> bool {
    *y_m == 0.0
}

/// Everything a simulation is built from, checked by whoever built it (the
/// I/O layer validates a scene before it makes one).
#[derive(Debug, Clone, PartialEq)]
pub struct Problem {
    /// Name shown in messages (the scene's name).
    pub name: String,
    /// The contact points, `P` of them (method §1).
    pub points: Vec<Point>,
    /// The tyre's modes over the points (method §2): `P × P` residues.
    pub modes: Arc<Vec<Mode>>,
    /// Whether the modes were identified from responses (a ring or
    /// measured tyre) rather than given exactly: identified residues carry
    /// noise below `1e-5` of their largest rank term
    /// ([`SolverOptions::rank_tolerance`](super::simulation::SolverOptions::rank_tolerance)).
    pub modes_identified: bool,
    /// The road, ready to be sampled (shared: a measured road may hold
    /// millions of rows).
    pub road: Arc<RoadProfile>,
    /// The contact law (rigid, or a tread spring per point, method §4.6).
    pub contact: Contact,
    /// How contact is decided inside a step (method §4).
    pub contact_scheme: ContactScheme,
    /// The time step (s).
    pub dt_s: f64,
    /// The run's length (s).
    pub duration_s: f64,
    /// Rolling speed (m/s).
    pub speed_mps: f64,
    /// The road's ramp-in time (s, method §4): the road rises from 0 over it.
    pub ramp_s: f64,
}

impl Problem {
    /// Number of contact points `P`.
    pub fn num_points(&self) -> usize {
        self.points.len()
    }

    /// Steps of the whole run ([`RunShape::num_steps`]).
    pub fn num_steps(&self) -> u64 {
        RunShape::num_steps(self)
    }
}

/// The points and the time line of a run, as a recorder sizes itself
/// before it: held by a [`Problem`] and by the scene it came from (the I/O
/// layer's), so that what records a run is sized from either.
pub trait RunShape {
    /// The contact points.
    fn points(&self) -> &[Point];
    /// The time step (s).
    fn dt_s(&self) -> f64;
    /// The run's length (s).
    fn duration_s(&self) -> f64;
    /// The road's ramp-in time (s).
    fn ramp_s(&self) -> f64;
    /// Number of contact points `P`.
    fn num_points(&self) -> usize {
        self.points().len()
    }
    /// Steps of the whole run, `round(duration / dt)`, at least 1.
    fn num_steps(&self) -> u64 {
        (self.duration_s() / self.dt_s()).round().max(1.0) as u64
    }
    /// The spacing `(Δx, Δy)` (m) of points written as a grid; `None`
    /// when they are listed one by one (a problem's are).
    fn grid_spacing_m(&self) -> Option<(f64, f64)> {
        None
    }
}

impl RunShape for Problem {
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
}
