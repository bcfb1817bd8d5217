//! The time stepper (method §4): free prediction, the coupled Gauss-point solve
//! of the active points, the monotone complementarity rule, and (default
//! `Located` scheme, and compliant contact) impacts or landings and releases
//! located inside the step.

mod compliant;
mod contributions;
mod events;
mod factor_cache;
mod gauss;
mod options;
mod paper;
mod residual;
mod steady;

use crate::contact::DenseSolver;
use crate::convolution::{Influence, ModalBasis, ModalState, StepTable};
use crate::error::{SceneError, SolverError};
use crate::identify::PreparedModel;
use crate::road::Road;
use crate::road::{PointsRoad, RoadProfile, ramp};
use crate::scene::{ContactScheme, Scene};
pub use events::first_crossing;
pub use options::{IDENTIFIED_RANK_TOLERANCE, SolverOptions};
use residual::{add_residual, split_residual};

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

/// A running simulation of a scene.
pub struct Simulation {
    scene: Scene,
    basis: ModalBasis,
    road: PointsRoad,
    /// Added to `V t` so that the distance rolled stays continuous when the speed changes (m).
    x_offset_m: f64,
    zbuf: Vec<f64>,
    dzbuf: Vec<f64>,
    /// Heights `h_i` of the points above the road (m, `scene.points[i].h_m`).
    h_m: Vec<f64>,
    p: usize,
    dt_s: f64,
    pen_tol_m: f64,
    max_events: u32,
    full: StepTable,
    full_inf: Influence,
    /// The same influence by source column: for point `j`, the columns `j`
    /// of `gx1`, `gx2`, `gv1`, `gv2` one after the other (`4P` values), so
    /// that the end values run over contiguous memory.
    full_inf_cols: Vec<f64>,
    sub: StepTable,
    /// `|S| x |S|` blocks of the sub-step influence (4 |S|² used).
    gss: Vec<f64>,
    /// State increment of the solved sub-step forces.
    delta: ModalState,
    du: Vec<f64>,
    dv: Vec<f64>,
    jump: Vec<f64>,
    state: Box<ModalState>,
    free: Box<ModalState>,
    t_s: f64,
    steps: u64,
    // outputs at the current time
    u: Vec<f64>,
    v: Vec<f64>,
    q_mean: Vec<f64>,
    r: Vec<f64>,
    rd: Vec<f64>,
    contact: Vec<bool>,
    // scratch
    uh: Vec<f64>,
    vh: Vec<f64>,
    ue: Vec<f64>,
    ve: Vec<f64>,
    re: Vec<f64>,
    rde: Vec<f64>,
    q1: Vec<f64>,
    q2: Vec<f64>,
    /// Trial Gauss-point forces restricted to the interval before an event.
    rq1: Vec<f64>,
    rq2: Vec<f64>,
    impulse: Vec<f64>,
    /// Impulses of the impacts located in the last step (N·s).
    impact_impulse: Vec<f64>,
    rhs: Vec<f64>,
    active: Vec<usize>,
    released: Vec<bool>,
    solver: DenseSolver,
    full_solver: DenseSolver,
    full_set: Vec<usize>,
    full_factored: bool,
    /// The points outside `full_set`, in order.
    full_free: Vec<usize>,
    /// Per point of `full_free`, the full-step influence of the Gauss-point
    /// forces of `full_set` on its end displacement and velocity, packed as
    /// two rows of `2|S|` against the solved `q1 | q2` (`4|S|` values).
    full_free_rows: Vec<f64>,
    options: SolverOptions,
    stats: RunStats,
    /// Tread stiffness per point (N/m) of compliant contact; empty: rigid.
    tread_k_n_m: Vec<f64>,
    /// `scene.num_steps()` (the scene is fixed for the simulation's life).
    num_steps: u64,
    /// The last step located events or released points: `impact_impulse`
    /// and `released` need clearing.
    had_event: bool,
    /// Residual compliance of the dropped modes (m/N, P x P row-major);
    /// empty: all modes in the convolution.
    residual: Vec<f64>,
    /// Full-step factorisations of active sets left earlier (method §4).
    factor_cache: factor_cache::FactorCache,
}

/// `√3`: the slope of a linear force is `√3 (q2 - q1) / τ` from its
/// Gauss-point values.
const SQRT3: f64 = 1.732_050_807_568_877_2;

/// [`Simulation::full_inf_cols`] of an influence.
fn influence_columns(g: &Influence, p: usize) -> Vec<f64> {
    let mut cols = Vec::with_capacity(4 * p * p);
    for j in 0..p {
        for m in [&g.gx1, &g.gx2, &g.gv1, &g.gv2] {
            cols.extend((0..p).map(|i| m[i * p + j]));
        }
    }
    cols
}

impl Simulation {
    /// Builds the simulation of a prepared scene (validated, modes known,
    /// road loaded: [`PreparedModel`]); no I/O and no identification here.
    /// Fails only if a mode's residue cannot be split into rank terms
    /// (method §3) or the residual compliance does not apply.
    pub fn new(model: &PreparedModel, options: SolverOptions) -> Result<Self, SceneError> {
        let scene = model.scene();
        let p = scene.num_points();
        let (modes, residual) =
            split_residual(scene, model.modes().to_vec(), options.residual_above_hz)?;
        let basis = if options.rank_reduction {
            ModalBasis::with_rank_tolerance(&modes, p, options.rank_tolerance_for(scene)).map_err(
                |source| SceneError::Basis {
                    scene: scene.name.clone(),
                    source,
                },
            )?
        } else {
            ModalBasis::per_source(&modes, p)
        };
        let road = model.road().clone();
        let full = StepTable::new(&basis, scene.dt_s);
        let mut full_inf = Influence::new(&basis, &full);
        if !residual.is_empty() {
            add_residual(&mut full_inf, &residual, scene.dt_s);
        }
        let jump = basis.velocity_jump();
        let state = ModalState::zeros(&basis);
        let scale = scene
            .points
            .iter()
            .map(|pt| pt.h_m.abs())
            .fold(road.scale_m(), f64::max)
            .max(1e-6);
        let xs: Vec<f64> = scene.points.iter().map(|pt| pt.x_m).collect();
        let road = PointsRoad::new(road, &xs);
        let mut sim = Simulation {
            x_offset_m: 0.0,
            zbuf: vec![0.0; p],
            dzbuf: vec![0.0; p],
            h_m: scene.points.iter().map(|pt| pt.h_m).collect(),
            scene: scene.clone(),
            p,
            dt_s: scene.dt_s,
            pen_tol_m: 1e-12 * scale,
            max_events: 4 * p as u32 + 16,
            sub: full.clone(),
            gss: vec![0.0; 4 * p * p],
            delta: state.clone(),
            du: vec![0.0; p],
            dv: vec![0.0; p],
            full,
            full_inf_cols: influence_columns(&full_inf, p),
            full_inf,
            jump,
            free: Box::new(state.clone()),
            state: Box::new(state),
            basis,
            road,
            t_s: 0.0,
            steps: 0,
            u: vec![0.0; p],
            v: vec![0.0; p],
            q_mean: vec![0.0; p],
            r: vec![0.0; p],
            rd: vec![0.0; p],
            contact: vec![false; p],
            uh: vec![0.0; p],
            vh: vec![0.0; p],
            ue: vec![0.0; p],
            ve: vec![0.0; p],
            re: vec![0.0; p],
            rde: vec![0.0; p],
            q1: vec![0.0; p],
            q2: vec![0.0; p],
            rq1: vec![0.0; p],
            rq2: vec![0.0; p],
            impulse: vec![0.0; p],
            impact_impulse: vec![0.0; p],
            rhs: vec![0.0; 2 * p],
            active: Vec::with_capacity(p),
            released: vec![false; p],
            solver: DenseSolver::new(2 * p),
            full_solver: DenseSolver::new(2 * p),
            full_set: Vec::with_capacity(p),
            full_factored: false,
            full_free: Vec::with_capacity(p),
            full_free_rows: Vec::with_capacity(4 * p * p),
            options,
            stats: RunStats::default(),
            tread_k_n_m: scene.contact.stiffness_per_point(p),
            factor_cache: factor_cache::FactorCache::new(
                p,
                options.reuse_factorisation && scene.contact.stiffness_per_point(p).is_empty(),
            ),
            residual,
            had_event: true,
            num_steps: scene.num_steps(),
        };
        sim.reset();
        Ok(sim)
    }

    /// Back to `t = 0`, at rest, zero gap.
    pub fn reset(&mut self) {
        self.state.reset();
        self.t_s = 0.0;
        self.x_offset_m = 0.0;
        self.steps = 0;
        for x in [
            &mut self.u,
            &mut self.v,
            &mut self.q_mean,
            &mut self.impact_impulse,
        ] {
            x.fill(0.0);
        }
        self.contact.fill(false);
        // the next step rebuilds its active set from `contact`
        self.had_event = true;
        // road at t = 0 (zero while ramping; a validated scene samples in range)
        if self.road_at(0.0, true).is_err() {
            self.re.fill(0.0);
            self.rde.fill(0.0);
        }
        self.r.copy_from_slice(&self.re);
        self.rd.copy_from_slice(&self.rde);
        self.stats = RunStats {
            max_force_n: vec![0.0; self.p],
            contact_steps: vec![0; self.p],
            ..RunStats::default()
        };
    }

    /// Prepares a scene with a cache of its own and builds its simulation
    /// with default options: for a scene run once. Runs of one ring tyre
    /// share a [`crate::identify::ModeCache`] and call [`Simulation::new`].
    pub fn from_scene(scene: &Scene) -> Result<Self, SceneError> {
        Self::new(&PreparedModel::of(scene)?, SolverOptions::default())
    }

    /// As [`Simulation::from_scene`], with explicit [`SolverOptions`].
    pub fn from_scene_with(scene: &Scene, options: SolverOptions) -> Result<Self, SceneError> {
        Self::new(&PreparedModel::of(scene)?, options)
    }

    /// Replaces the road live (no restart) by `road`, whose profile
    /// `profile` the caller has loaded ([`RoadProfile::new`]).
    pub fn set_road(&mut self, road: &Road, profile: RoadProfile) {
        let xs: Vec<f64> = self.scene.points.iter().map(|p| p.x_m).collect();
        self.road = PointsRoad::new(profile, &xs);
        self.scene.road = road.clone();
        let scale = self
            .scene
            .points
            .iter()
            .map(|pt| pt.h_m.abs())
            .fold(self.road.profile.scale_m(), f64::max)
            .max(1e-6);
        self.pen_tol_m = 1e-12 * scale;
    }

    /// Changes the rolling speed live (m/s, no restart).
    /// The distance rolled stays continuous: the road does not jump.
    pub fn set_speed(&mut self, speed_mps: f64) {
        self.x_offset_m += (self.scene.speed_mps - speed_mps) * self.t_s;
        self.scene.speed_mps = speed_mps;
    }

    pub fn scene(&self) -> &Scene {
        &self.scene
    }
    /// The road profile being sampled (for drawing it).
    pub fn road_profile(&self) -> &RoadProfile {
        &self.road.profile
    }
    /// Distance rolled so far (m): point `i` sees the road at `x_i + rolled_m()`.
    pub fn rolled_m(&self) -> f64 {
        self.scene.speed_mps * self.t_s + self.x_offset_m
    }
    pub fn time_s(&self) -> f64 {
        self.t_s
    }
    pub fn steps(&self) -> u64 {
        self.steps
    }
    pub fn num_points(&self) -> usize {
        self.p
    }
    /// States of the convolution (rank terms of all modes).
    pub fn num_states(&self) -> usize {
        self.basis.num_states()
    }
    pub fn dt_s(&self) -> f64 {
        self.dt_s
    }
    /// Displacements `u_i` (m, up) at the current time.
    pub fn displacement_m(&self) -> &[f64] {
        &self.u
    }
    /// Velocities `v_i` (m/s) at the current time.
    pub fn velocity_mps(&self) -> &[f64] {
        &self.v
    }
    /// Impulses of the impacts located inside the last step (N·s), included
    /// in [`Self::force_n`] as impulse / dt; zero without impacts and for the
    /// paper's scheme and compliant contact, which have none.
    pub fn impact_impulse_ns(&self) -> &[f64] {
        &self.impact_impulse
    }
    /// Step-mean contact forces of the last step (N): impulse / dt.
    pub fn force_n(&self) -> &[f64] {
        &self.q_mean
    }
    /// Road heights `r_i` seen by the points at the current time (m).
    pub fn road_m(&self) -> &[f64] {
        &self.r
    }
    /// Gaps `u_i - r_i` (m) at the current time.
    pub fn gap_m(&self, i: usize) -> f64 {
        self.u[i] - self.r[i]
    }
    /// Contact state at the current time.
    pub fn in_contact(&self) -> &[bool] {
        &self.contact
    }
    pub fn stats(&self) -> &RunStats {
        &self.stats
    }
    /// Whether the run reached `duration_s`.
    pub fn finished(&self) -> bool {
        self.steps >= self.num_steps
    }

    /// Road heights and rates at `t` into `re`, `rde`.
    /// Road heights and rates at `t` into `re`, `rde`; at a breakpoint of a
    /// measured road, the rate after it (`after`) or before it.
    fn road_at(&mut self, t: f64, after: bool) -> Result<(), SolverError> {
        self.sample_road(t, after, None)
    }

    /// [`Simulation::road_at`] `t`; at the end of step `step_end` (`Some`),
    /// with the road advanced from the previous step end (one rotation per
    /// harmonic instead of a `sin_cos`, see [`PointsRoad::sample_step`]).
    fn sample_road(
        &mut self,
        t: f64,
        after: bool,
        step_end: Option<u64>,
    ) -> Result<(), SolverError> {
        let (w, dw) = ramp(t, self.scene.ramp_s);
        let vel = self.scene.speed_mps;
        // past the ramp, a sine road at consecutive step ends: fused
        if let Some(n) = step_end
            && w == 1.0
            && dw == 0.0
            && self.road.step_end_offset(
                n,
                vel * self.dt_s,
                &self.h_m,
                vel,
                &mut self.re,
                &mut self.rde,
            )
        {
            return Ok(());
        }
        let rolled_m = vel * t + self.x_offset_m;
        let (z, dz) = (&mut self.zbuf, &mut self.dzbuf);
        match step_end {
            Some(n) => self.road.sample_step(n, rolled_m, vel * self.dt_s, z, dz),
            None => self.road.sample_all(rolled_m, after, z, dz),
        }
        .map_err(|(i, e)| SolverError::RoadOutOfRange {
            t_s: t,
            point: i,
            x_m: e.x_m,
            min_m: e.min_m,
            max_m: e.max_m,
        })?;
        self.apply_ramp(w, dw);
        Ok(())
    }

    fn prepare_sub(&mut self, tau: f64) {
        self.sub.fill(&self.basis, tau);
    }

    /// Free prediction over `tau` from `t`: `free`, `uh`, `vh`, road at `t + tau`.
    #[inline(always)]
    fn predict(&mut self, t: f64, tau: f64, sel: Table) -> Result<(), SolverError> {
        let table = match sel {
            Table::Full => &self.full,
            Table::Sub => &self.sub,
        };
        self.state.predict_into(table, &mut self.free);
        self.free.project(&self.basis, &mut self.uh, &mut self.vh);
        // a full step from the current time ends at step `steps + 1`
        let step_end = (sel == Table::Full && t == self.t_s).then_some(self.steps + 1);
        self.sample_road(t + tau, false, step_end)
    }

    /// `re`, `rde` from the road samples in `zbuf`, `dzbuf` and the ramp
    /// `w`, `dw/dt` (method §4): `r = w (z - h)`, `r' = w' (z - h) + w z' V`.
    fn apply_ramp(&mut self, w: f64, dw: f64) {
        let (vel, p) = (self.scene.speed_mps, self.p);
        let (z, dz, h) = (&self.zbuf[..p], &self.dzbuf[..p], &self.h_m[..p]);
        let (re, rde) = (&mut self.re[..p], &mut self.rde[..p]);
        if w == 1.0 && dw == 0.0 {
            // past the ramp (the same values: 1 x and 0 x + y are exact)
            for i in 0..p {
                re[i] = z[i] - h[i];
                rde[i] = dz[i] * vel;
            }
            return;
        }
        for i in 0..p {
            re[i] = w * (z[i] - h[i]);
            rde[i] = dw * (z[i] - h[i]) + w * dz[i] * vel;
        }
    }

    /// Accepts the solved sub-step of length `tau`: state, impulses, outputs.
    #[inline(always)]
    fn commit(&mut self, tau: f64, sel: Table) {
        // `free` is rewritten by the next prediction before it is read again
        std::mem::swap(&mut self.state, &mut self.free);
        if !self.active.is_empty() {
            match sel {
                Table::Full => self.state.add_gauss_forces(
                    &self.basis,
                    &self.full,
                    &self.active,
                    &self.q1,
                    &self.q2,
                ),
                Table::Sub => self.state.add(&self.delta),
            }
        }
        for &j in &self.active {
            self.impulse[j] += 0.5 * tau * (self.q1[j] + self.q2[j]);
        }
        // the end values become the current ones; `ue`, `ve`, `re`, `rde`
        // are rewritten in full before they are read again
        std::mem::swap(&mut self.u, &mut self.ue);
        std::mem::swap(&mut self.v, &mut self.ve);
        std::mem::swap(&mut self.r, &mut self.re);
        std::mem::swap(&mut self.rd, &mut self.rde);
    }

    /// Advances one step of `dt_s`. On error the state is that of the step start
    /// only as far as modal states go; call `reset` to restart.
    pub fn step(&mut self) -> Result<StepReport, SolverError> {
        let t0 = self.t_s;
        self.impulse.fill(0.0);
        if self.had_event {
            self.impact_impulse.fill(0.0);
            self.released.fill(false);
        }
        // (read before `had_event` is set below)
        let steady = self.steady_ready();
        // until the step succeeds (an error mid-step may leave either set)
        self.had_event = true;
        let compliant = !self.tread_k_n_m.is_empty();
        let (events, solves) = match self.scene.contact_scheme {
            // tread springs: a step with a landing or a release goes to the
            // event loop, which locates them as for rigid contact
            _ if compliant => {
                let taken = if self.options.steady_path {
                    self.compliant_steady_step(t0)?
                } else {
                    None
                };
                match taken {
                    Some(solves) => {
                        self.stats.steady_steps += 1;
                        (0, solves)
                    }
                    None => self.located_step(t0, false)?,
                }
            }
            ContactScheme::Paper => {
                let s = self.paper_substep(t0, self.dt_s, Table::Full)?;
                (0, s)
            }
            ContactScheme::Located => {
                // a step with an event goes to the event loop
                let taken = if steady { self.steady_step(t0)? } else { None };
                match taken {
                    Some(solves) => {
                        self.stats.steady_steps += 1;
                        (0, solves)
                    }
                    None => self.located_step(t0, steady)?,
                }
            }
        };
        // every impact is a located event, and so is every release of the
        // located scheme; the other schemes' releases set `released`
        let located = !compliant && self.scene.contact_scheme == ContactScheme::Located;
        self.had_event = events > 0 || (!located && self.released.iter().any(|&r| r));
        self.steps += 1;
        self.t_s = self.steps as f64 * self.dt_s;
        let p = self.p;
        let contact = &mut self.contact[..p];
        // The located scheme changes its active set (built from `contact` in
        // point order at the step start) only at an event.
        if events > 0 || !located {
            contact.fill(false);
            for &j in &self.active {
                contact[j] = true;
            }
        }
        let mut pen = 0.0f64;
        // one test of the sum: a NaN or an infinity anywhere makes it non-finite
        // (after the loop: the statistics of a failed step do not matter, a
        // failed simulation is reset)
        let mut sum = 0.0;
        let inv_dt = 1.0 / self.dt_s;
        let (q, imp) = (&mut self.q_mean[..p], &self.impulse[..p]);
        let (u, v, r) = (&self.u[..p], &self.v[..p], &self.r[..p]);
        let max_force = &mut self.stats.max_force_n[..p];
        let contact_steps = &mut self.stats.contact_steps[..p];
        for i in 0..p {
            let qi = imp[i] * inv_dt;
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
        if !sum.is_finite() {
            return Err(self.non_finite());
        }
        let st = &mut self.stats;
        st.steps += 1;
        st.events += events as u64;
        st.solves += solves as u64;
        st.max_solves_per_step = st.max_solves_per_step.max(solves);
        st.worst_penetration_m = st.worst_penetration_m.max(pen);
        Ok(StepReport {
            t_s: self.t_s,
            events,
            solves,
            penetration_m: pen.max(0.0),
        })
    }

    /// The first non-finite output of the step just taken (the sum of all
    /// of them was not finite).
    #[cold]
    fn non_finite(&self) -> SolverError {
        let quantities = [
            (&self.u, "displacement"),
            (&self.v, "velocity"),
            (&self.q_mean, "force"),
        ];
        for i in 0..self.p {
            for (x, quantity) in quantities {
                if !x[i].is_finite() {
                    return SolverError::NonFinite {
                        t_s: self.t_s,
                        point: i,
                        quantity,
                    };
                }
            }
        }
        // finite values whose sum overflowed
        SolverError::NonFinite {
            t_s: self.t_s,
            point: 0,
            quantity: "displacement, velocity and force sum",
        }
    }
}
