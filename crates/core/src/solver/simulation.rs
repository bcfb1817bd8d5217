//! The time stepper (method §4): free prediction, the coupled Gauss-point solve
//! of the active points, the monotone complementarity rule, and (default
//! `Located` scheme, and compliant contact) impacts or landings and releases
//! located inside the step.
//!
//! A [`Simulation`] is in three parts (`parts.rs`): the tables built once,
//! the run's state and the per-step scratch. Its step is made of four
//! stages (`stages.rs`): predict, solve, locate, commit; the schemes
//! combine them (`steady.rs`, `events.rs`, `paper.rs`, `compliant.rs`),
//! the paper's and the compliant step-end rules in one active-set loop
//! (`active_set.rs`).

mod active_set;
mod columns;
mod compliant;
pub mod contact;
mod contributions;
mod crossing;
mod events;
mod factor_cache;
mod gauss;
mod large;
mod merged;
mod options;
mod paper;
mod parts;
mod residual;
#[doc(hidden)]
pub mod stages;
mod steady;

use crate::base::threads::Threads;
use crate::model::road::{PointsRoad, RoadProfile};
use crate::solver::error::{BuildError, SolverError};
use crate::solver::problem::{ContactScheme, Point, Problem};
pub use crossing::{crosses, first_crossing};
use factor_cache::FullFactors;
pub use options::{IDENTIFIED_RANK_TOLERANCE, SolverOptions};
use parts::{Scratch, SimState, SimTables, SimTablesBuild};
use std::sync::Arc;

/// Values of a linear force at the step start and end from its Gauss-point values.
const GA: f64 = 1.366_025_403_784_438_6;
const GB: f64 = 0.366_025_403_784_438_6;

/// What happened in one step.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct StepReport {
    /// Time at the end of the step (s).
    pub t_s: f64,
    /// Impacts and releases located inside the step.
    pub events: u32,
    /// Linear solves performed (Gauss-point and impulse systems).
    pub solves: u32,
    /// Largest penetration left at the step end (m), corrected next step.
    pub penetration_m: f64,
}

/// Statistics of a run so far.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RunStats {
    pub steps: u64,
    pub events: u64,
    pub solves: u64,
    pub max_solves_per_step: u32,
    /// LU factorisations of contact systems (fewer than solves: reused while
    /// the active set is unchanged).
    pub factorisations: u64,
    /// Worst penetration left at any step end (m).
    pub worst_penetration_m: f64,
    /// Largest step-mean force per point (N).
    pub max_force_n: Vec<f64>,
    /// Steps ending in contact, per point.
    pub contact_steps: Vec<u64>,
    /// Steps taken by the steady path (same contact set, no event; see
    /// [`SolverOptions::steady_path`]).
    pub steady_steps: u64,
    /// Points that joined or left a large active set's kept inverse by a
    /// bordered update ([`SolverOptions::large_set_from`]).
    pub contact_updates: u64,
    /// Updated inverses whose solve failed the backward-error check and
    /// were formed again from a factorisation.
    pub update_refusals: u64,
    /// Operator applications of the sub-step GMRES solves.
    pub krylov_applications: u64,
    /// Sub-step GMRES solves that did not converge (solved directly).
    pub krylov_fallbacks: u64,
    /// Steps of tread springs whose events were taken in one full-step
    /// solve ([`SolverOptions::merged_events`]).
    pub merged_steps: u64,
}

impl RunStats {
    /// Fraction of steps ending in contact, per point.
    pub fn contact_fraction(&self) -> Vec<f64> {
        self.contact_steps
            .iter()
            .map(|&c| c as f64 / self.steps.max(1) as f64)
            .collect()
    }
}

#[derive(Clone, Copy, PartialEq)]
enum Table {
    Full,
    Sub,
}

/// A running simulation of a [`Problem`], in three parts: the tables built
/// once from the problem and `dt` (`SimTables`, never changed), the run's
/// state (`SimState`: what a snapshot or a restart needs) and the buffers a
/// step works in (`Scratch`); beside them the full-step factorisations kept
/// by active set (derived from the tables and the active set), and the
/// problem with its road, whose speed and road [`Simulation::set_speed`]
/// and [`Simulation::set_road`] change live. A step runs the stages of
/// `simulation/stages.rs`: predict, solve, locate, commit.
pub struct Simulation {
    tables: SimTables,
    state: SimState,
    scratch: Scratch,
    factors: FullFactors,
    problem: Problem,
    road: PointsRoad,
    /// Depth below the road that counts as on it (m): `1e-12` of the
    /// largest road or point height.
    pen_tol_m: f64,
    /// The threads of the large kernels ([`SolverOptions::threads`]).
    threads: Threads,
}

/// [`Simulation::new`] a stage at a time: the tables' basis, then their
/// `P × P` parts a block of rows (about a millisecond of work) at a time,
/// then the simulation. The tables are [`Simulation::new`]'s to the bit, so
/// the run is the same.
pub struct SimulationBuild {
    problem: Problem,
    options: SolverOptions,
    tables: SimTablesBuild,
    stages_done: usize,
}

impl std::fmt::Debug for SimulationBuild {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SimulationBuild")
            .field("problem", &self.problem.name)
            .field("stages_done", &self.stages_done)
            .finish()
    }
}

impl SimulationBuild {
    /// Runs the next stage; the simulation once the last one ran.
    pub fn stage(&mut self) -> Result<Option<Simulation>, BuildError> {
        self.stages_done += 1;
        Ok(self.tables.stage(&self.problem)?.map(|tables| {
            let threads = Threads::new(self.options.threads)
                .with_parallel_from(self.options.parallel_from_madds);
            Simulation::with_tables(&self.problem, tables, threads)
        }))
    }

    /// Stages done so far.
    pub fn stages_done(&self) -> usize {
        self.stages_done
    }

    /// Stages of the whole build (exact once the basis is built, the
    /// first stage; an estimate before).
    pub fn num_stages(&self) -> usize {
        self.stages_done + self.tables.stages_left(&self.problem)
    }

    /// The problem the simulation is built from.
    pub fn problem(&self) -> &Problem {
        &self.problem
    }

    /// Runs every stage left.
    pub fn finish(mut self) -> Result<Simulation, BuildError> {
        loop {
            if let Some(sim) = self.stage()? {
                return Ok(sim);
            }
        }
    }
}

/// `√3`: the slope of a linear force is `√3 (q2 - q1) / τ` from its
/// Gauss-point values.
const SQRT3: f64 = 1.732_050_807_568_877_2;

/// The penetration tolerance of `road` under `points` (m): `1e-12` of the
/// largest road or point height, at least `1e-18`.
fn penetration_tolerance_m(road: &RoadProfile, points: &[Point]) -> f64 {
    let scale = points
        .iter()
        .map(|pt| pt.h_m.abs())
        .fold(road.scale_m(), f64::max)
        .max(1e-6);
    1e-12 * scale
}

impl Simulation {
    /// Builds the simulation of a problem (its modes known, its road
    /// loaded); no I/O and no identification here. Fails only if a mode's
    /// residue cannot be split into rank terms (method §3.4) or the
    /// residual compliance does not apply (§4.7).
    pub fn new(problem: &Problem, options: SolverOptions) -> Result<Self, BuildError> {
        let threads = Threads::new(options.threads).with_parallel_from(options.parallel_from_madds);
        let tables = SimTables::new(problem, options, &threads)?;
        Ok(Self::with_tables(problem, tables, threads))
    }

    /// [`Simulation::new`] a stage at a time ([`SimulationBuild`]), for a
    /// caller that must return between stages (a page in the browser).
    pub fn build_in_stages(problem: Problem, options: SolverOptions) -> SimulationBuild {
        SimulationBuild {
            tables: SimTablesBuild::new(options),
            problem,
            options,
            stages_done: 0,
        }
    }

    /// The simulation of `problem` on its tables, at rest.
    fn with_tables(problem: &Problem, tables: SimTables, threads: Threads) -> Self {
        let options = tables.options;
        let p = tables.p;
        let pen_tol_m = penetration_tolerance_m(&problem.road, &problem.points);
        let xs: Vec<f64> = problem.points.iter().map(|pt| pt.x_m).collect();
        let ys: Vec<f64> = problem.points.iter().map(|pt| pt.y_m).collect();
        let keep = options.reuse_factorisation && !tables.compliant();
        let mut sim = Simulation {
            state: SimState::new(&tables.basis, p),
            scratch: Scratch::new(&tables),
            factors: FullFactors::new(p, keep, tables.large_sets()),
            road: PointsRoad::new(problem.road.clone(), &xs, &ys),
            problem: problem.clone(),
            pen_tol_m,
            tables,
            threads,
        };
        sim.reset();
        sim
    }

    /// Back to `t = 0`, at rest, zero gap.
    pub fn reset(&mut self) {
        let st = &mut self.state;
        st.modal.reset();
        self.scratch.ahead.ready = false;
        st.t_s = 0.0;
        st.x_offset_m = 0.0;
        st.steps = 0;
        for x in [&mut st.u, &mut st.v, &mut st.q_mean, &mut st.impact_impulse] {
            x.fill(0.0);
        }
        st.contact.fill(false);
        // the next step rebuilds its active set from `contact`
        st.had_event = true;
        // road at t = 0 (zero while ramping; a validated scene samples in range)
        if self.road_at(0.0, true).is_err() {
            self.scratch.re.fill(0.0);
            self.scratch.rde.fill(0.0);
        }
        let (st, s) = (&mut self.state, &self.scratch);
        st.r.copy_from_slice(&s.re);
        st.rd.copy_from_slice(&s.rde);
        st.stats = RunStats {
            max_force_n: vec![0.0; self.tables.p],
            contact_steps: vec![0; self.tables.p],
            ..RunStats::default()
        };
    }

    /// Replaces the road live (no restart) by `profile`.
    pub fn set_road(&mut self, profile: impl Into<Arc<RoadProfile>>) {
        let profile: Arc<RoadProfile> = profile.into();
        let xs: Vec<f64> = self.problem.points.iter().map(|p| p.x_m).collect();
        let ys: Vec<f64> = self.problem.points.iter().map(|p| p.y_m).collect();
        self.road = PointsRoad::new(profile.clone(), &xs, &ys);
        self.pen_tol_m = penetration_tolerance_m(&profile, &self.problem.points);
        self.problem.road = profile;
    }

    /// Changes the rolling speed live (m/s, no restart).
    /// The distance rolled stays continuous: the road does not jump.
    pub fn set_speed(&mut self, speed_mps: f64) {
        self.state.x_offset_m += (self.problem.speed_mps - speed_mps) * self.state.t_s;
        self.problem.speed_mps = speed_mps;
    }

    /// The problem being run (its speed and road as last set).
    pub fn problem(&self) -> &Problem {
        &self.problem
    }
    /// The road profile being sampled (for drawing it).
    pub fn road_profile(&self) -> &RoadProfile {
        &self.road.profile
    }
    /// Distance rolled so far (m): point `i` sees the road at `x_i + rolled_m()`.
    pub fn rolled_m(&self) -> f64 {
        self.problem.speed_mps * self.state.t_s + self.state.x_offset_m
    }
    pub fn time_s(&self) -> f64 {
        self.state.t_s
    }
    pub fn steps(&self) -> u64 {
        self.state.steps
    }
    pub fn num_points(&self) -> usize {
        self.tables.p
    }
    /// States of the convolution (rank terms of all modes).
    pub fn num_states(&self) -> usize {
        self.tables.basis.num_states()
    }
    pub fn dt_s(&self) -> f64 {
        self.tables.dt_s
    }
    /// Displacements `u_i` (m, up) at the current time.
    pub fn displacement_m(&self) -> &[f64] {
        &self.state.u
    }
    /// Velocities `v_i` (m/s) at the current time.
    pub fn velocity_mps(&self) -> &[f64] {
        &self.state.v
    }
    /// Impulses of the impacts located inside the last step (N·s), included
    /// in [`Self::force_n`] as impulse / dt; zero without impacts and for the
    /// paper's scheme and compliant contact, which have none.
    pub fn impact_impulse_ns(&self) -> &[f64] {
        &self.state.impact_impulse
    }
    /// Step-mean contact forces of the last step (N): impulse / dt.
    pub fn force_n(&self) -> &[f64] {
        &self.state.q_mean
    }
    /// Road heights `r_i` seen by the points at the current time (m).
    pub fn road_m(&self) -> &[f64] {
        &self.state.r
    }
    /// Gaps `u_i - r_i` (m) at the current time.
    pub fn gap_m(&self, i: usize) -> f64 {
        self.state.u[i] - self.state.r[i]
    }
    /// Contact state at the current time.
    pub fn in_contact(&self) -> &[bool] {
        &self.state.contact
    }
    pub fn stats(&self) -> &RunStats {
        &self.state.stats
    }
    /// Threads of the kernels ([`SolverOptions::threads`]; fewer if the
    /// system refused to start some).
    pub fn threads(&self) -> usize {
        self.threads.count()
    }
    /// Kernel calls split over the threads since the simulation was
    /// built, set-up included (0 on one thread, and for scenes below
    /// [`SolverOptions::parallel_from_madds`]).
    pub fn threaded_kernel_calls(&self) -> u64 {
        self.threads.split_calls()
    }
    /// Whether the run reached `duration_s`.
    pub fn finished(&self) -> bool {
        self.state.steps >= self.tables.num_steps
    }

    /// The sub-step table for a sub-step of `tau` (s, method §3.3).
    fn prepare_sub(&mut self, tau: f64) {
        self.scratch.sub.fill(&self.tables.basis, tau);
    }

    /// Advances one step of `dt_s`. On error the state is that of the step start
    /// only as far as modal states go; call `reset` to restart.
    pub fn step(&mut self) -> Result<StepReport, SolverError> {
        let t0 = self.state.t_s;
        // (cleared as the last step read it, unless that step failed)
        if !std::mem::replace(&mut self.scratch.impulse_clear, false) {
            self.scratch.impulse.fill(0.0);
        }
        if self.state.had_event {
            self.state.impact_impulse.fill(0.0);
            self.state.released.fill(false);
            self.state.thrown_off.fill(0);
        }
        // (read before `had_event` is set below)
        let steady = self.steady_ready();
        self.scratch.quiet_steps = if self.state.had_event {
            0
        } else {
            self.scratch.quiet_steps.saturating_add(1)
        };
        // until the step succeeds (an error mid-step may leave either set)
        self.state.had_event = true;
        let compliant = self.tables.compliant();
        let (events, solves) = match self.problem.contact_scheme {
            // tread springs: a step with a landing or a release goes to the
            // event loop, which locates them as for rigid contact
            _ if compliant => {
                let taken = if self.tables.options.steady_path {
                    self.compliant_steady_step(t0)?
                } else {
                    None
                };
                match taken {
                    Some(solves) => {
                        self.state.stats.steady_steps += 1;
                        (0, solves)
                    }
                    None => match self.merged_event_step()? {
                        Some(taken) => {
                            self.state.stats.merged_steps += 1;
                            taken
                        }
                        None => self.located_step(t0, false)?,
                    },
                }
            }
            ContactScheme::Paper => {
                let s = self.paper_substep(t0, self.tables.dt_s, Table::Full)?;
                (0, s)
            }
            ContactScheme::Located => {
                // a step with an event goes to the event loop
                let taken = if steady { self.steady_step(t0)? } else { None };
                match taken {
                    Some(solves) => {
                        self.state.stats.steady_steps += 1;
                        (0, solves)
                    }
                    None => self.located_step(t0, steady)?,
                }
            }
        };
        // every impact is a located event, and so is every release of the
        // located scheme; the other schemes' releases set `released`
        let located = !compliant && self.problem.contact_scheme == ContactScheme::Located;
        let (tb, st) = (&self.tables, &mut self.state);
        st.had_event = events > 0 || (!located && st.released.iter().any(|&r| r));
        st.steps += 1;
        st.t_s = st.steps as f64 * tb.dt_s;
        let p = tb.p;
        let contact = &mut st.contact[..p];
        // The located scheme changes its active set (built from `contact` in
        // point order at the step start) only at an event.
        if events > 0 || !located {
            contact.fill(false);
            for &j in &st.active {
                contact[j] = true;
            }
        }
        let mut pen = 0.0f64;
        // one test of the sum: a NaN or an infinity anywhere makes it non-finite
        // (after the loop: the statistics of a failed step do not matter, a
        // failed simulation is reset)
        let mut sum = 0.0;
        let inv_dt = 1.0 / tb.dt_s;
        let (q, imp) = (&mut st.q_mean[..p], &mut self.scratch.impulse[..p]);
        let (u, v, r) = (&st.u[..p], &st.v[..p], &st.r[..p]);
        let max_force = &mut st.stats.max_force_n[..p];
        let contact_steps = &mut st.stats.contact_steps[..p];
        for i in 0..p {
            let qi = imp[i] * inv_dt;
            imp[i] = 0.0;
            q[i] = qi;
            sum += u[i] + v[i] + qi;
            // a compliant contact's compression is its spring's, not a penetration
            let gap_counts = !(compliant && contact[i]);
            let pen_i = if gap_counts { r[i] - u[i] } else { 0.0 };
            // (plain comparisons: a NaN fails them, and fails the sum below)
            if pen_i > pen {
                pen = pen_i;
            }
            if qi > max_force[i] {
                max_force[i] = qi;
            }
            contact_steps[i] += contact[i] as u64;
        }
        self.scratch.impulse_clear = true;
        if !sum.is_finite() {
            return Err(self.non_finite());
        }
        let stats = &mut self.state.stats;
        stats.steps += 1;
        stats.events += events as u64;
        stats.solves += solves as u64;
        stats.max_solves_per_step = stats.max_solves_per_step.max(solves);
        stats.worst_penetration_m = stats.worst_penetration_m.max(pen);
        Ok(StepReport {
            t_s: self.state.t_s,
            events,
            solves,
            penetration_m: pen.max(0.0),
        })
    }

    /// The first non-finite output of the step just taken (the sum of all
    /// of them was not finite).
    #[cold]
    fn non_finite(&self) -> SolverError {
        let st = &self.state;
        let quantities = [
            (&st.u, "displacement"),
            (&st.v, "velocity"),
            (&st.q_mean, "force"),
        ];
        for i in 0..self.tables.p {
            for (x, quantity) in quantities {
                if !x[i].is_finite() {
                    return SolverError::NonFinite {
                        t_s: st.t_s,
                        point: i,
                        quantity,
                    };
                }
            }
        }
        // finite values whose sum overflowed
        SolverError::NonFinite {
            t_s: st.t_s,
            point: 0,
            quantity: "displacement, velocity and force sum",
        }
    }
}
