//! # tirecontact-core
//!
//! Dynamic tyre/road contact by fast modal convolution (see `docs/method.md`, from
//! Meftah & Duhamel, CFM 2011).
//!
//! ## Conventions (method §1)
//!
//! * `P` contact points on the contact line, indices `i, j = 0..P-1`; point `i`
//!   sits at `x_i` (m) with undeformed height `h_i` (m) above the mean road
//!   plane (`h_i < 0` means preload).
//! * `u_i` is the vertical displacement of point `i`, positive **up**, from the
//!   undeformed tyre; `v_i = du_i/dt`.
//! * `q_i >= 0` is the contact force of the road on the tyre, positive up.
//! * SI units everywhere; names carry their unit (`dt_s`, `freq_hz`, ...).
//!
//! ## Module map
//!
//! ## What this crate holds
//!
//! The solver and what it is made of, with no file format, figure or
//! front end (ARCHITECTURE.md):
//!
//! | module | what | method |
//! |---|---|---|
//! | [`base`] | errors of the solver and of model parameters; checked dense decompositions (faer); modes, poles for every damping ratio, `g(t)`, `G(ω)`; the kernels' worker threads | §2, §3, §6 |
//! | [`model`] | ring and plate tyres; LSCE and LSCF identification numerics; roads as height functions and the ramp; the bounded recursive convolution with exact step weights | §3, §5, §6 |
//! | [`solver`] | the [`Problem`] a simulation is built from; the time stepper (tables, state and scratch; the stages of a step: predict, solve, locate, commit); the run driver and its `Probe`; contact phases | §4 |
//!
//! The scene format, the file readers and identification live in
//! `tirecontact-io`, which builds a [`Problem`] from a scene.

pub mod base;
pub mod model;
pub mod solver;

pub use solver::error::{BuildError, RunError, SolverError};
pub use solver::problem::Problem;
pub use solver::simulation::{IDENTIFIED_RANK_TOLERANCE, Simulation, SolverOptions, StepReport};
