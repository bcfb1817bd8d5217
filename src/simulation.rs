//! The time stepper (SPEC §4): free prediction, the coupled Gauss-point solve
//! of the active points, the monotone complementarity rule, and (default
//! `Located` scheme) impacts and releases located inside the step.

use crate::contact::DenseSolver;
use crate::convolution::{Influence, ModalBasis, ModalState, StepTable};
use crate::error::{SceneError, SolverError};
use crate::road::Road;
use crate::road::{RoadProfile, ramp};
use crate::scene::{ContactScheme, Scene};

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
    /// Worst penetration left at any step end (m).
    pub worst_penetration_m: f64,
    /// Largest step-mean force per point (N).
    pub max_force_n: Vec<f64>,
    /// Steps ending in contact, per point.
    pub contact_steps: Vec<u64>,
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
    road: RoadProfile,
    p: usize,
    dt_s: f64,
    pen_tol_m: f64,
    max_events: u32,
    full: StepTable,
    full_inf: Influence,
    sub: StepTable,
    sub_inf: Influence,
    jump: Vec<f64>,
    state: ModalState,
    free: ModalState,
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
    impulse: Vec<f64>,
    rhs: Vec<f64>,
    active: Vec<usize>,
    released: Vec<bool>,
    solver: DenseSolver,
    stats: RunStats,
}

impl Simulation {
    /// Builds the simulation of a validated scene; reads a measured road file.
    pub fn new(scene: &Scene) -> Result<Self, SceneError> {
        scene.validate().map_err(|errors| SceneError::Invalid {
            file: scene.name.clone(),
            errors,
        })?;
        let p = scene.num_points();
        let basis = ModalBasis::new(scene.modes(), p);
        let road = RoadProfile::new(&scene.road, scene.base_dir.as_deref())?;
        let full = StepTable::new(&basis, scene.dt_s);
        let full_inf = Influence::new(&basis, &full);
        let jump = basis.velocity_jump();
        let state = ModalState::zeros(&basis);
        let scale = scene
            .points
            .iter()
            .map(|pt| pt.h_m.abs())
            .fold(road.scale_m(), f64::max)
            .max(1e-6);
        let mut sim = Simulation {
            scene: scene.clone(),
            p,
            dt_s: scene.dt_s,
            pen_tol_m: 1e-12 * scale,
            max_events: 4 * p as u32 + 16,
            sub: full.clone(),
            sub_inf: full_inf.clone(),
            full,
            full_inf,
            jump,
            free: state.clone(),
            state,
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
            impulse: vec![0.0; p],
            rhs: vec![0.0; 2 * p],
            active: Vec::with_capacity(p),
            released: vec![false; p],
            solver: DenseSolver::new(2 * p),
            stats: RunStats::default(),
        };
        sim.reset();
        Ok(sim)
    }

    /// Back to `t = 0`, at rest, zero gap.
    pub fn reset(&mut self) {
        self.state.reset();
        self.t_s = 0.0;
        self.steps = 0;
        for x in [&mut self.u, &mut self.v, &mut self.q_mean] {
            x.fill(0.0);
        }
        self.contact.fill(false);
        // road at t = 0 (zero while ramping; a validated scene samples in range)
        if self.road_at(0.0, Table::Full).is_err() {
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

    /// Replaces the road profile live (no restart).
    pub fn set_road(&mut self, road: &Road) -> Result<(), SceneError> {
        self.road = RoadProfile::new(road, self.scene.base_dir.as_deref())?;
        self.scene.road = road.clone();
        let scale = self
            .scene
            .points
            .iter()
            .map(|pt| pt.h_m.abs())
            .fold(self.road.scale_m(), f64::max)
            .max(1e-6);
        self.pen_tol_m = 1e-12 * scale;
        Ok(())
    }

    /// Changes the rolling speed live (m/s, no restart).
    pub fn set_speed(&mut self, speed_mps: f64) {
        self.scene.speed_mps = speed_mps;
    }

    pub fn scene(&self) -> &Scene {
        &self.scene
    }
    /// The road profile being sampled (for drawing it).
    pub fn road_profile(&self) -> &RoadProfile {
        &self.road
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
        self.steps >= self.scene.num_steps()
    }

    /// Road heights and rates at `t` into `re`, `rde`.
    fn road_at(&mut self, t: f64, _sel: Table) -> Result<(), SolverError> {
        let (w, dw) = ramp(t, self.scene.ramp_s);
        let vel = self.scene.speed_mps;
        for (i, pt) in self.scene.points.iter().enumerate() {
            let x = pt.x_m + vel * t;
            let (z, dz) = self
                .road
                .sample(x)
                .map_err(|e| SolverError::RoadOutOfRange {
                    t_s: t,
                    point: i,
                    x_m: e.x_m,
                    min_m: e.min_m,
                    max_m: e.max_m,
                })?;
            self.re[i] = w * (z - pt.h_m);
            self.rde[i] = dw * (z - pt.h_m) + w * dz * vel;
        }
        Ok(())
    }

    fn prepare_sub(&mut self, tau: f64) {
        self.sub.fill(&self.basis, tau);
        self.sub_inf.fill(&self.basis, &self.sub);
    }

    /// Free prediction over `tau` from `t`: `free`, `uh`, `vh`, road at `t + tau`.
    fn predict(&mut self, t: f64, tau: f64, sel: Table) -> Result<(), SolverError> {
        let table = match sel {
            Table::Full => &self.full,
            Table::Sub => &self.sub,
        };
        self.state.predict_into(table, &mut self.free);
        self.free.project(&self.basis, &mut self.uh, &mut self.vh);
        self.road_at(t + tau, sel)
    }

    /// Solves the Gauss-point system of `active` (after `predict`) and the end
    /// displacement/velocity of every point into `ue`, `ve`.
    fn solve_active(&mut self, t_end: f64, sel: Table) -> Result<(), SolverError> {
        let n = self.active.len();
        let p = self.p;
        self.ue.copy_from_slice(&self.uh);
        self.ve.copy_from_slice(&self.vh);
        if n == 0 {
            return Ok(());
        }
        let (_, g) = match sel {
            Table::Full => (&self.full, &self.full_inf),
            Table::Sub => (&self.sub, &self.sub_inf),
        };
        let act = &self.active;
        let res = self.solver.factor(2 * n, |r, c| {
            let (i, j) = (act[r % n], act[c % n]);
            let m = match (r < n, c < n) {
                (true, true) => &g.gx1,
                (true, false) => &g.gx2,
                (false, true) => &g.gv1,
                (false, false) => &g.gv2,
            };
            m[i * p + j]
        });
        if let Err(s) = res {
            return Err(SolverError::SingularContactSystem {
                t_s: t_end,
                points: self.active.clone(),
                pivot: s.pivot,
            });
        }
        for (k, &i) in act.iter().enumerate() {
            self.rhs[k] = self.re[i] - self.uh[i];
            self.rhs[n + k] = self.rde[i] - self.vh[i];
        }
        self.solver.solve(&mut self.rhs[..2 * n]);
        self.q1.fill(0.0);
        self.q2.fill(0.0);
        for (k, &j) in act.iter().enumerate() {
            self.q1[j] = self.rhs[k];
            self.q2[j] = self.rhs[n + k];
        }
        for i in 0..p {
            let (mut du, mut dv) = (0.0, 0.0);
            for &j in act {
                du += g.gx1[i * p + j] * self.q1[j] + g.gx2[i * p + j] * self.q2[j];
                dv += g.gv1[i * p + j] * self.q1[j] + g.gv2[i * p + j] * self.q2[j];
            }
            self.ue[i] += du;
            self.ve[i] += dv;
        }
        Ok(())
    }

    /// Accepts the solved sub-step of length `tau`: state, impulses, outputs.
    fn commit(&mut self, tau: f64, sel: Table) {
        let (table, _) = match sel {
            Table::Full => (&self.full, &self.full_inf),
            Table::Sub => (&self.sub, &self.sub_inf),
        };
        self.state.copy_from(&self.free);
        self.state
            .add_gauss_forces(&self.basis, table, &self.active, &self.q1, &self.q2);
        for &j in &self.active {
            self.impulse[j] += 0.5 * tau * (self.q1[j] + self.q2[j]);
        }
        self.u.copy_from_slice(&self.ue);
        self.v.copy_from_slice(&self.ve);
        self.r.copy_from_slice(&self.re);
        self.rd.copy_from_slice(&self.rde);
    }

    /// Advances one step of `dt_s`. On error the state is that of the step start
    /// only as far as modal states go; call `reset` to restart.
    pub fn step(&mut self) -> Result<StepReport, SolverError> {
        let t0 = self.t_s;
        self.impulse.fill(0.0);
        self.released.fill(false);
        let (events, solves) = match self.scene.contact_scheme {
            ContactScheme::Paper => {
                let s = self.paper_substep(t0, self.dt_s, Table::Full)?;
                (0, s)
            }
            ContactScheme::Located => self.located_step(t0)?,
        };
        self.steps += 1;
        self.t_s = self.steps as f64 * self.dt_s;
        let mut pen = 0.0f64;
        for i in 0..self.p {
            self.q_mean[i] = self.impulse[i] / self.dt_s;
            let checks = [
                (self.u[i], "displacement"),
                (self.v[i], "velocity"),
                (self.q_mean[i], "force"),
            ];
            for (x, quantity) in checks {
                if !x.is_finite() {
                    return Err(SolverError::NonFinite {
                        t_s: self.t_s,
                        point: i,
                        quantity,
                    });
                }
            }
            self.contact[i] = self.active.contains(&i);
            pen = pen.max(self.r[i] - self.u[i]);
            self.stats.max_force_n[i] = self.stats.max_force_n[i].max(self.q_mean[i]);
            self.stats.contact_steps[i] += self.contact[i] as u64;
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

    /// The paper's step (SPEC §4 steps 1-5) over `[t, t + tau]`: candidates from
    /// the free prediction, release of the most negative mean force, points
    /// pushed below the road by a neighbour added, a released point never
    /// re-added, at most `2P` solves.
    fn paper_substep(&mut self, t: f64, tau: f64, sel: Table) -> Result<u32, SolverError> {
        self.predict(t, tau, sel)?;
        self.active.clear();
        for i in 0..self.p {
            if self.uh[i] - self.re[i] < 0.0 && !self.released[i] {
                self.active.push(i);
            }
        }
        let mut solves = 0u32;
        loop {
            self.solve_active(t + tau, sel)?;
            solves += !self.active.is_empty() as u32;
            if solves as usize >= 2 * self.p {
                break;
            }
            // most negative step-mean force
            let worst = self
                .active
                .iter()
                .enumerate()
                .map(|(k, &j)| (k, self.q1[j] + self.q2[j]))
                .filter(|&(_, m)| m < 0.0)
                .min_by(|a, b| a.1.total_cmp(&b.1));
            if let Some((k, _)) = worst {
                let j = self.active.remove(k);
                self.released[j] = true;
                continue;
            }
            // a neighbour's force pushed a free point below the road
            let deepest = (0..self.p)
                .filter(|&i| !self.released[i] && !self.active.contains(&i))
                .map(|i| (i, self.ue[i] - self.re[i]))
                .filter(|&(_, g)| g < -self.pen_tol_m)
                .min_by(|a, b| a.1.total_cmp(&b.1));
            match deepest {
                Some((i, _)) => self.active.push(i),
                None => break,
            }
        }
        self.commit(tau, sel);
        Ok(solves)
    }

    /// A step with events located inside it (SPEC §4, "Events inside the step").
    fn located_step(&mut self, t_start: f64) -> Result<(u32, u32), SolverError> {
        let dt = self.dt_s;
        let mut t = t_start;
        let mut remaining = dt;
        let (mut events, mut solves) = (0u32, 0u32);
        // the active set carries over: points in contact at the step start
        self.active.clear();
        for i in 0..self.p {
            if self.contact[i] {
                self.active.push(i);
            }
        }
        // a point left below the road by the last step lands now
        let deepest = (0..self.p)
            .filter(|&i| !self.contact[i])
            .map(|i| (i, self.u[i] - self.r[i]))
            .filter(|&(_, g)| g < -self.pen_tol_m)
            .min_by(|a, b| a.1.total_cmp(&b.1));
        if let Some((i, _)) = deepest {
            solves += self.impact(t, i)?;
            events += 1;
        }
        let mut sel = Table::Full;
        while remaining > 1e-12 * dt {
            if events > self.max_events {
                // Zeno-like cascade: finish the step with the paper's rule.
                if sel == Table::Full {
                    self.prepare_sub(remaining);
                }
                solves += self.paper_substep(t, remaining, Table::Sub)?;
                break;
            }
            self.predict(t, remaining, sel)?;
            self.solve_active(t + remaining, sel)?;
            solves += !self.active.is_empty() as u32;
            // releases: the linear force's end value is negative
            let mut release: Option<(usize, f64, f64)> = None; // (k, θ, end value)
            for (k, &j) in self.active.iter().enumerate() {
                let (q1, q2) = (self.q1[j], self.q2[j]);
                let (qs, qe) = (GA * q1 - GB * q2, -GB * q1 + GA * q2);
                if qe < 0.0 {
                    let th = if qs > 0.0 {
                        remaining * qs / (qs - qe)
                    } else {
                        0.0
                    };
                    let better = match release {
                        None => true,
                        Some((_, t2, e2)) => th < t2 || (th == t2 && qe < e2),
                    };
                    if better {
                        release = Some((k, th, qe));
                    }
                }
            }
            if let Some((k, th, _)) = release
                && th <= 0.0
            {
                let j = self.active.remove(k);
                self.released[j] = true;
                events += 1;
                continue;
            }
            // impacts: first root of the Hermite cubic of the gap of a free point
            let mut impact: Option<(usize, f64)> = None;
            for i in 0..self.p {
                if self.released[i] || self.active.contains(&i) {
                    continue;
                }
                let (g0, d0) = (self.u[i] - self.r[i], self.v[i] - self.rd[i]);
                let (g1, d1) = (self.ue[i] - self.re[i], self.ve[i] - self.rde[i]);
                if let Some(y) =
                    first_crossing(g0, d0 * remaining, g1, d1 * remaining, self.pen_tol_m)
                {
                    let th = y * remaining;
                    if impact.is_none_or(|(_, t2)| th < t2) {
                        impact = Some((i, th));
                    }
                }
            }
            let th_rel = release.map_or(f64::INFINITY, |r| r.1);
            let th_imp = impact.map_or(f64::INFINITY, |r| r.1);
            let th = th_rel.min(th_imp);
            if !th.is_finite() {
                self.commit(remaining, sel);
                break;
            }
            // advance to the event
            if th >= remaining * (1.0 - 1e-12) {
                self.commit(remaining, sel);
                t += remaining;
                remaining = 0.0;
            } else if th > 0.0 {
                self.prepare_sub(th);
                sel = Table::Sub;
                self.predict(t, th, sel)?;
                self.solve_active(t + th, sel)?;
                solves += !self.active.is_empty() as u32;
                self.commit(th, sel);
                t += th;
                remaining -= th;
            }
            events += 1;
            if th_imp <= th_rel {
                let (i, _) = impact.unwrap_or((0, 0.0));
                solves += self.impact(t, i)?;
            } else if let Some((k, _, _)) = release {
                let j = self.active.remove(k);
                self.released[j] = true;
            }
            if remaining > 1e-12 * dt {
                self.prepare_sub(remaining);
                sel = Table::Sub;
            }
        }
        Ok((events, solves))
    }

    /// Perfectly inelastic impact of point `i` at `t`: impulses on all points on
    /// the road together so that their velocities equal the road's; a point
    /// whose impulse would pull is thrown off (monotone, most negative first).
    fn impact(&mut self, t: f64, i: usize) -> Result<u32, SolverError> {
        self.road_at(t, Table::Sub)?;
        self.r.copy_from_slice(&self.re);
        self.rd.copy_from_slice(&self.rde);
        if !self.active.contains(&i) {
            self.active.push(i);
        }
        let p = self.p;
        let mut solves = 0;
        while !self.active.is_empty() {
            let n = self.active.len();
            let act = &self.active;
            let jump = &self.jump;
            if let Err(s) = self.solver.factor(n, |r, c| jump[act[r] * p + act[c]]) {
                return Err(SolverError::SingularContactSystem {
                    t_s: t,
                    points: self.active.clone(),
                    pivot: s.pivot,
                });
            }
            for (k, &j) in act.iter().enumerate() {
                self.rhs[k] = self.rd[j] - self.v[j];
            }
            self.solver.solve(&mut self.rhs[..n]);
            solves += 1;
            let worst = (0..n)
                .map(|k| (k, self.rhs[k]))
                .filter(|&(_, x)| x < 0.0)
                .min_by(|a, b| a.1.total_cmp(&b.1));
            match worst {
                Some((k, _)) => {
                    let j = self.active.remove(k);
                    self.released[j] = true;
                }
                None => break,
            }
        }
        let n = self.active.len();
        self.q1.fill(0.0);
        for k in 0..n {
            self.q1[self.active[k]] = self.rhs[k];
        }
        self.state.add_impulses(&self.basis, &self.active, &self.q1);
        for &j in &self.active {
            self.impulse[j] += self.q1[j];
        }
        for a in 0..p {
            self.v[a] += self
                .active
                .iter()
                .map(|&j| self.jump[a * p + j] * self.q1[j])
                .sum::<f64>();
        }
        Ok(solves)
    }
}

/// First `y ∈ (0, 1]` where the cubic Hermite interpolant with values `g0`,
/// `g1` and scaled slopes `d0`, `d1` (slope × interval) goes below `-tol`,
/// starting from `g0 >= -tol`; returns the zero crossing before it.
pub fn first_crossing(g0: f64, d0: f64, g1: f64, d1: f64, tol: f64) -> Option<f64> {
    if g0 < -tol {
        return None;
    }
    let c = [
        g0,
        d0,
        -3.0 * g0 - 2.0 * d0 + 3.0 * g1 - d1,
        2.0 * g0 + d0 - 2.0 * g1 + d1,
    ];
    let p = |y: f64| ((c[3] * y + c[2]) * y + c[1]) * y + c[0];
    // cheap rejection: all of the cubic is above -tol
    if g1 >= -tol && (d0 >= 0.0 && d1 <= 0.0 || g0.min(g1) - 0.25 * (d0.abs() + d1.abs()) >= -tol) {
        return None;
    }
    // breakpoints: critical points of the cubic in (0, 1)
    let (qa, qb, qc) = (3.0 * c[3], 2.0 * c[2], c[1]);
    let mut bp = [1.0f64; 3];
    let mut nb = 0;
    if qa.abs() > 1e-300 {
        let disc = qb * qb - 4.0 * qa * qc;
        if disc >= 0.0 {
            let sq = disc.sqrt();
            let qq = -0.5 * (qb + qb.signum() * sq);
            for y in [qq / qa, if qq != 0.0 { qc / qq } else { f64::NAN }] {
                if y > 0.0 && y < 1.0 {
                    bp[nb] = y;
                    nb += 1;
                }
            }
        }
    } else if qb.abs() > 1e-300 {
        let y = -qc / qb;
        if y > 0.0 && y < 1.0 {
            bp[nb] = y;
            nb += 1;
        }
    }
    bp[nb] = 1.0;
    let bps = &mut bp[..nb + 1];
    bps.sort_by(f64::total_cmp);
    let mut ya = 0.0;
    for &yb in bps.iter() {
        if p(yb) < -tol {
            // monotone decreasing on [ya, yb]: bisect for p = 0
            if p(ya) < 0.0 {
                return Some(ya);
            }
            let (mut lo, mut hi) = (ya, yb);
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if p(mid) >= 0.0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            return Some(0.5 * (lo + hi));
        }
        ya = yb;
    }
    None
}
