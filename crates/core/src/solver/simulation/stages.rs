//! The four stages of a step (method §4.3-4.4), each over a step or a
//! sub-step `[t, t + τ]`:
//!
//! 1. **predict**: the free prediction of the modal states and the road at
//!    the end (`Simulation::predict`);
//! 2. **solve**: the Gauss-point contact solve of the active set and the end
//!    values of every point (`Simulation::solve_contact`);
//! 3. **locate**: the first release and the first impact inside the trial
//!    (`Simulation::locate`);
//! 4. **commit**: the solved forces into the modal states, the end values
//!    into the current ones (`Simulation::commit`).
//!
//! Every scheme's step is built from them (`events.rs`, `steady.rs`,
//! `active_set.rs` with `paper.rs` and `compliant.rs`). [`Stages`] runs
//! them one at a time, for the benchmarks.

use super::{GA, GB, Simulation, Table, first_crossing};
use crate::model::road::ramp;
use crate::solver::error::SolverError;

/// The first release and the first impact of a solved trial over a
/// sub-step (method §4.4), times from the sub-step start (s).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Located {
    /// `(k, θ, q_e)`: entry `k` of the active set released at `θ`, its
    /// linear force ending at `q_e` (N).
    pub(super) release: Option<(usize, f64, f64)>,
    /// `(i, θ)`: point `i` lands at `θ`.
    pub(super) impact: Option<(usize, f64)>,
}

impl Located {
    /// Time of the first release from the sub-step start (s), if any.
    pub fn release_s(&self) -> Option<f64> {
        self.release.map(|r| r.1)
    }
    /// Time of the first impact from the sub-step start (s), if any.
    pub fn impact_s(&self) -> Option<f64> {
        self.impact.map(|r| r.1)
    }
}

impl Simulation {
    /// **Predict** (method §3.3 with no new force, §4.3 step 1; the road of
    /// §4.1): the modal states advanced over `tau` from `t` by `Φ(τ)` alone
    /// into `free`, projected to the free end values `uh`, `vh`, and the
    /// road at `t + tau` into `re`, `rde`.
    #[inline(always)]
    pub(super) fn predict(&mut self, t: f64, tau: f64, sel: Table) -> Result<(), SolverError> {
        let table = match sel {
            Table::Full => &self.tables.full,
            Table::Sub => &self.scratch.sub,
        };
        self.scratch.fused_end = false;
        let threads = &self.threads;
        self.state
            .modal
            .predict_into_on(table, &mut self.scratch.free, threads);
        // (a large compliant set's full step, and a sub-step solved by
        // GMRES, project only their active points, in their solve, and the
        // end values in one pass: `large.rs`)
        let fused = match sel {
            Table::Full => self.fused_full_step(),
            Table::Sub => self.iterative_sub_step(),
        };
        if !fused {
            let (uh, vh) = (&mut self.scratch.uh, &mut self.scratch.vh);
            self.scratch
                .free
                .project_on(&self.tables.basis, uh, vh, threads);
        }
        self.scratch.projected_all = !fused;
        // (the rows projected ahead by the last step, for this very prediction)
        let ahead = std::mem::take(&mut self.scratch.ahead.ready);
        self.scratch.ahead.in_use =
            ahead && fused && sel == Table::Full && t == self.state.t_s && tau == self.tables.dt_s;
        // a full step from the current time ends at step `steps + 1`
        let step_end = (sel == Table::Full && t == self.state.t_s).then_some(self.state.steps + 1);
        self.sample_road(t + tau, false, step_end)
    }

    /// Road heights and rates at `t` into `re`, `rde` (method §4.1); at a
    /// breakpoint of a measured road, the rate after it (`after`) or before
    /// it.
    pub(super) fn road_at(&mut self, t: f64, after: bool) -> Result<(), SolverError> {
        self.sample_road(t, after, None)
    }

    /// [`Simulation::road_at`] `t`; at the end of step `step_end` (`Some`),
    /// with the road advanced from the previous step end (one rotation per
    /// harmonic instead of a `sin_cos`, see
    /// [`crate::model::road::PointsRoad::sample_step`]).
    fn sample_road(
        &mut self,
        t: f64,
        after: bool,
        step_end: Option<u64>,
    ) -> Result<(), SolverError> {
        let (w, dw) = ramp(t, self.problem.ramp_s);
        let vel = self.problem.speed_mps;
        let scratch = &mut self.scratch;
        // past the ramp, a sine road at consecutive step ends: fused
        if let Some(n) = step_end
            && w == 1.0
            && dw == 0.0
            && self.road.step_end_offset(
                n,
                vel * self.tables.dt_s,
                &self.tables.h_m,
                vel,
                &mut scratch.re,
                &mut scratch.rde,
            )
        {
            return Ok(());
        }
        let rolled_m = vel * t + self.state.x_offset_m;
        let (z, dz) = (&mut scratch.zbuf, &mut scratch.dzbuf);
        match step_end {
            Some(n) => self
                .road
                .sample_step(n, rolled_m, vel * self.tables.dt_s, z, dz),
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

    /// `re`, `rde` from the road samples in `zbuf`, `dzbuf` and the ramp
    /// `w`, `dw/dt` (method §4.1): `r = w (z - h)`, `r' = w' (z - h) + w z' V`.
    fn apply_ramp(&mut self, w: f64, dw: f64) {
        let (vel, p) = (self.problem.speed_mps, self.tables.p);
        let s = &mut self.scratch;
        let (z, dz, h) = (&s.zbuf[..p], &s.dzbuf[..p], &self.tables.h_m[..p]);
        let (re, rde) = (&mut s.re[..p], &mut s.rde[..p]);
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

    /// **Solve** (method §4.3 step 3, §4.5; compliant contact §4.6): the
    /// Gauss-point system of the active set over `sel` (after
    /// [`Simulation::predict`]), the forces into `q1`, `q2` and the end
    /// values of every point into `ue`, `ve`; rigid
    /// ([`Simulation::solve_active`]) or tread springs
    /// ([`Simulation::solve_compliant`]).
    #[inline]
    pub(super) fn solve_contact(&mut self, t_end: f64, sel: Table) -> Result<(), SolverError> {
        self.scratch.fused_end = false;
        if self.tables.tread_k_n_m.is_empty() {
            self.solve_active(t_end, sel)
        } else {
            self.solve_compliant(t_end, sel)
        }
    }

    /// **Locate** (method §4.4, "Release location" and "Impact location"):
    /// in the trial solved over a sub-step of `span`, the first release of
    /// an active point and, unless that release is at once, the first
    /// landing of a free point. Reads the trial; changes nothing.
    pub(super) fn locate(&self, t_s: f64, span: f64) -> Located {
        let release = self.first_release(span);
        if let Some((_, th, _)) = release
            && th <= 0.0
        {
            return Located {
                release,
                impact: None,
            };
        }
        Located {
            release,
            impact: self.first_impact(t_s, span),
        }
    }

    /// The first release of the trial (method §4.4, "Release location"):
    /// a linear force that ends negative is released where it crosses zero,
    /// `θ = τ q_s / (q_s - q_e)`; one negative on average from the start,
    /// at once (`θ = 0`). The earliest wins, the most negative end on a tie.
    fn first_release(&self, span: f64) -> Option<(usize, f64, f64)> {
        let compliant = self.tables.compliant();
        let s = &self.scratch;
        let mut release: Option<(usize, f64, f64)> = None; // (k, θ, end value)
        for (k, &j) in self.state.active.iter().enumerate() {
            let (q1, q2) = (s.q1[j], s.q2[j]);
            let (qs, qe) = (GA * q1 - GB * q2, -GB * q1 + GA * q2);
            if qe < 0.0 || qs + qe < 0.0 {
                // (a tread spring the sub-step does not resolve: released
                // only if it pulls on average, and at once)
                let unresolved = compliant && self.spring_unresolved(j, span);
                if unresolved && qs + qe >= 0.0 {
                    continue;
                }
                let th = if qs > 0.0 && !unresolved {
                    span * qs / (qs - qe)
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
        release
    }

    /// The first landing of a free point in the trial (method §4.4, "Impact
    /// location"): the first root of the Hermite cubic of its gap.
    fn first_impact(&self, t_s: f64, span: f64) -> Option<(usize, f64)> {
        let compliant = self.tables.compliant();
        let mut impact: Option<(usize, f64)> = None;
        let p = self.tables.p;
        let (st, s) = (&self.state, &self.scratch);
        let (u, v, r, rd) = (&st.u[..p], &st.v[..p], &st.r[..p], &st.rd[..p]);
        let (ue, ve, re, rde) = (&s.ue[..p], &s.ve[..p], &s.re[..p], &s.rde[..p]);
        let (released, active) = (&st.released[..p], &st.active);
        for i in 0..p {
            // (a compressed spring is not on the road: its gap is far
            // from the cheap rejection, so active points are skipped first)
            if compliant && (active.contains(&i) || st.held_at_s[i] == t_s) {
                continue;
            }
            let (g0, d0) = (u[i] - r[i], v[i] - rd[i]);
            let (g1, d1) = (ue[i] - re[i], ve[i] - rde[i]);
            // a point released in this step lands again only after it rose
            // clear of the road (no cycling at the release instant)
            let rise = released[i];
            // (active points are skipped only past the cheap rejection,
            // which most points of most steps take)
            if let Some(y) = first_crossing(g0, d0 * span, g1, d1 * span, self.pen_tol_m, rise)
                && !active.contains(&i)
            {
                let th = y * span;
                if impact.is_none_or(|(_, t2)| th < t2) {
                    impact = Some((i, th));
                }
            }
        }
        impact
    }

    /// **Commit** (method §4.3 step 5, §3.3): the solved sub-step of length
    /// `tau` accepted. The modal states become the free prediction plus the
    /// response to the Gauss-point forces (`x ← Φ x + W1 β(q1) + W2 β(q2)`),
    /// the impulses `τ (q1 + q2) / 2` add to the step's, and the end values
    /// become the current ones.
    #[inline(always)]
    pub(super) fn commit(&mut self, tau: f64, sel: Table) {
        let (st, s) = (&mut self.state, &mut self.scratch);
        // (the end state formed by the last solve, over this very span:
        // `predict` and `solve_contact` clear the mark)
        let fused = std::mem::take(&mut s.fused_end);
        let ahead = std::mem::take(&mut s.ahead.pending);
        s.ahead.ready = ahead && fused && sel == Table::Full;
        if fused {
            // the end state is formed already (`large.rs`)
            std::mem::swap(&mut st.modal, &mut s.delta);
        } else {
            // `free` is rewritten by the next prediction before it is read again
            std::mem::swap(&mut st.modal, &mut s.free);
        }
        if !st.active.is_empty() && !fused {
            match sel {
                Table::Full => st.modal.add_gauss_forces_on(
                    &self.tables.basis,
                    &self.tables.full,
                    &st.active,
                    &s.q1,
                    &s.q2,
                    &self.threads,
                ),
                Table::Sub => st.modal.add(&s.delta),
            }
        }
        for &j in &st.active {
            s.impulse[j] += 0.5 * tau * (s.q1[j] + s.q2[j]);
        }
        // the end values become the current ones; `ue`, `ve`, `re`, `rde`
        // are rewritten in full before they are read again
        std::mem::swap(&mut st.u, &mut s.ue);
        std::mem::swap(&mut st.v, &mut s.ve);
        std::mem::swap(&mut st.r, &mut s.re);
        std::mem::swap(&mut st.rd, &mut s.rde);
    }

    /// The stages of a full step from the current time, one at a time (for
    /// the benchmarks: `benches/solver.rs`).
    #[doc(hidden)]
    pub fn stages(&mut self) -> Stages<'_> {
        Stages { sim: self }
    }
}

/// The stages of a step one at a time, each over the full step from the
/// simulation's current time, as the first trial of a step runs them:
/// [`Stages::predict`], then [`Stages::solve`] of the active set the last
/// step left, [`Stages::locate`], [`Stages::commit`]. Predict, solve and
/// locate change only scratch values and may be repeated. Commit changes
/// the modal states but not the time: a step then starts from a state no
/// run reaches, so call [`Simulation::reset`] before stepping again.
#[doc(hidden)]
pub struct Stages<'a> {
    sim: &'a mut Simulation,
}

impl Stages<'_> {
    /// The points on the road that [`Stages::solve`] holds there.
    pub fn active(&self) -> &[usize] {
        &self.sim.state.active
    }

    /// `Simulation::predict` over the full step from the current time.
    pub fn predict(&mut self) -> Result<(), SolverError> {
        let (t, dt) = (self.sim.state.t_s, self.sim.tables.dt_s);
        self.sim.predict(t, dt, Table::Full)
    }

    /// `Simulation::solve_contact` of the active set over the full step,
    /// after [`Stages::predict`] (the factorisation is reused while the set
    /// holds, as in a step).
    pub fn solve(&mut self) -> Result<(), SolverError> {
        let t_end = self.sim.state.t_s + self.sim.tables.dt_s;
        self.sim.solve_contact(t_end, Table::Full)
    }

    /// `Simulation::locate` in the trial, after [`Stages::solve`].
    pub fn locate(&self) -> Located {
        self.sim.locate(self.sim.state.t_s, self.sim.tables.dt_s)
    }

    /// `Simulation::commit` of the trial over the full step.
    pub fn commit(&mut self) {
        let dt = self.sim.tables.dt_s;
        self.sim.commit(dt, Table::Full)
    }

    /// Whether the next step will read the active rows the last step
    /// projected ahead (`large.rs`), for the tests of that reuse.
    pub fn rows_ahead_ready(&self) -> bool {
        self.sim.scratch.ahead.ready
    }

    /// Makes the next step project its active rows afresh, as a step with
    /// an event does.
    pub fn forget_rows_ahead(&mut self) {
        self.sim.scratch.ahead.ready = false;
    }

    /// The modal states: displacements and velocities (method §3.3).
    pub fn modal_states(&self) -> (&[f64], &[f64]) {
        (&self.sim.state.modal.x, &self.sim.state.modal.v)
    }
}
