//! Events of tread springs in one full-step solve (method §4.6, "Events
//! in one solve").
//!
//! With a tread spring the force is continuous at a landing and at a
//! release: only the event point's own force has a kink there. The other
//! points feel that kink through Green functions that start linearly
//! (`g(0) = 0`), so their responses to it are of third order in the time
//! since the event, and their forces stay linear over the whole step to the
//! scheme's own order. The step is then one solve over `[0, dt]` in which
//!
//! - a point that **lands** at `θ` carries a linear force on `[θ, dt]`
//!   only, given by its two Gauss values on that interval (the exact
//!   weights of a step of `τ = dt − θ`: the response at `dt` of a force
//!   that ends at `dt` is a step's of `τ` from rest), with the spring law in
//!   value and rate at `dt` as every active point;
//! - a point that is **released** at `θ` keeps the trial's linear force up
//!   to `θ` as a known load (`Φ(dt − θ)` of its response at `θ`), and no
//!   force after;
//! - every other active point keeps its two Gauss values over the step.
//!
//! Several events in one step: the solve is repeated with each new event
//! (the earliest of the solution) until none is found, up to
//! [`MERGED_EVENTS`]. A step this cannot take (a landing point that would
//! pull, a spring left compressed at the step start, more than
//! [`MERGED_SET_MAX`] points on the road, residual flexibility, a singular
//! system) goes to the sub-steps of `events.rs`, which it leaves
//! untouched: nothing is committed before the end.
//!
//! Cost: a landing's and a release's short-step weights and their
//! responses at every point come from an interpolant in `τ` built at
//! set-up ([`TauInterp`](crate::model::convolution::TauInterp), `O(M P)`
//! each; exact tables and projections where there is none); each solve
//! is `O(|S|²)` per new border unknown and a Schur complement of at most
//! `4 MERGED_EVENTS` unknowns through the trial's factorisation, or one
//! dense factorisation where the trial had none (a large set's trial is
//! solved through its kept inverse); the sub-steps instead predict, fill,
//! solve and project twice per event.

use super::contact::DenseSolver;
use super::parts::SimTables;
use super::{GA, GB, SQRT3, Simulation, first_crossing};
use crate::model::convolution::{ModalState, StepTable};
use crate::solver::error::SolverError;

mod bordered;

/// Events (landings and releases) one merged step takes; a step with more
/// is taken by the sub-steps.
pub(super) const MERGED_EVENTS: usize = 8;

/// The most points on the road a merged step solves (its dense system is
/// `2n × 2n`); a step with more is taken by the sub-steps.
pub(super) const MERGED_SET_MAX: usize = 64;

/// A point released inside the step: its trial force up to `θ`.
#[derive(Debug, Clone, Copy)]
struct Early {
    point: usize,
    theta_s: f64,
    /// The trial's force restricted to `[0, θ]`, at that interval's Gauss
    /// points (N).
    rq1: f64,
    rq2: f64,
}

/// The buffers of the merged event step, sized once.
pub(super) struct MergedScratch {
    /// The table of a landing's remaining interval or of a release's two.
    tab: StepTable,
    /// A landing's responses at the step end to unit Gauss values on its
    /// interval (slot `2 l + c` for late point `l`, value `c`): end
    /// displacements (m/N) and velocities (m/(N·s)) at every point,
    /// `(2 l + c) P + i`.
    unit_x: Vec<f64>,
    unit_v: Vec<f64>,
    /// The released points' known loads: their state at the step end and
    /// its end values at every point (m, m/s).
    known: ModalState,
    known_x: Vec<f64>,
    known_v: Vec<f64>,
    /// `known`, `known_x` and `known_v` hold zeros (no release wrote
    /// them since they were cleared): a step without one clears nothing.
    known_clear: bool,
    /// A released point's load, or a landing's unit response, as a state
    /// at the step end.
    load: ModalState,
    /// Point-indexed Gauss values of one source (zero but at that point).
    g1: Vec<f64>,
    g2: Vec<f64>,
    /// The set: the points with a force over the whole step, then the late
    /// ones (`late_tau_s` by slot).
    set: Vec<usize>,
    full: usize,
    late_tau_s: Vec<f64>,
    early: Vec<Early>,
    solver: DenseSolver,
    rhs: Vec<f64>,
    /// The trial's set (whose full-step factorisation the bordered solve
    /// reuses), and per border unknown its column through that
    /// factorisation's inverse (`A⁻¹ B`, `2|S|` each).
    trial_set: Vec<usize>,
    /// The trial was solved through the kept inverse of a large set (in
    /// its slot order, `trial_set`), not a factorisation; `slots`: a
    /// right-hand side and solution in that inverse's slot order.
    trial_kept: bool,
    slots: Vec<f64>,
    z: Vec<f64>,
    z0: Vec<f64>,
    /// The kept inverse's trial solution in `z0`'s layout: `z0` itself
    /// while no release has added a known load (the same right-hand side).
    trial_x: Vec<f64>,
    /// The bordered system's Schur complement and its solver.
    schur: DenseSolver,
    /// The borders in the order of the step's events, and how many of
    /// them have their columns in `z`.
    border: Vec<Border>,
    z_done: usize,
    y: Vec<f64>,
    /// The steady trial of this step (prediction over the whole step, the
    /// carried set solved, every point's end values) is in the scratch.
    pub trial_ready: bool,
}

impl MergedScratch {
    /// Buffers for the tables' points and states; empty unless the
    /// contact is compliant. The systems solved hold at most
    /// [`MERGED_SET_MAX`] points.
    pub fn new(tables: &SimTables) -> Self {
        let compliant = tables.compliant();
        let (n, states) = if compliant {
            (tables.p, tables.basis.stored_states())
        } else {
            (0, 0)
        };
        let cap = n.min(MERGED_SET_MAX);
        let zero = || ModalState {
            x: vec![0.0; states],
            v: vec![0.0; states],
        };
        MergedScratch {
            // (sized as the full step's; refilled for each event)
            tab: if compliant {
                tables.full.clone()
            } else {
                StepTable::default()
            },
            unit_x: vec![0.0; 2 * MERGED_EVENTS * n],
            unit_v: vec![0.0; 2 * MERGED_EVENTS * n],
            known: zero(),
            known_x: vec![0.0; n],
            known_v: vec![0.0; n],
            known_clear: true,
            load: zero(),
            g1: vec![0.0; n],
            g2: vec![0.0; n],
            set: Vec::with_capacity(n),
            full: 0,
            late_tau_s: Vec::with_capacity(MERGED_EVENTS),
            early: Vec::with_capacity(MERGED_EVENTS),
            solver: DenseSolver::new(2 * cap),
            rhs: vec![0.0; 2 * cap],
            trial_set: Vec::with_capacity(n),
            trial_kept: false,
            slots: vec![0.0; 4 * cap],
            // (two borders per event at most: a spring that lets go and lands)
            z: vec![0.0; 8 * MERGED_EVENTS * cap],
            z0: vec![0.0; 2 * cap],
            trial_x: vec![0.0; 2 * cap],
            schur: DenseSolver::new(4 * MERGED_EVENTS),
            border: Vec::with_capacity(2 * MERGED_EVENTS),
            z_done: 0,
            y: vec![0.0; 4 * MERGED_EVENTS],
            trial_ready: false,
        }
    }
}

/// Two unknowns bordering the trial's factorised system (method §4.6,
/// "Events in one solve").
#[derive(Debug, Clone, Copy)]
enum Border {
    /// A trial point left (entry `k` of the trial set): its two unknowns
    /// held at zero, its two equations freed by two multipliers.
    Left(usize),
    /// A late point (slot `l`, point `i`): its two Gauss values on its
    /// interval and its two equations.
    Late(usize, usize),
}

/// The next event of a merged solve.
enum Next {
    None,
    /// Entry of the set (a full-step point) released at `θ`.
    Release(usize, f64),
    /// A free point landing at `θ`.
    Landing(usize, f64),
    /// Entry of the set (a full-step point) whose force is negative only
    /// near the step start: free up to `θ`, on the road after it.
    Reland(usize, f64),
    /// An event this step cannot take.
    Unsupported,
}

impl Simulation {
    /// Whether a step of tread springs may be taken by
    /// [`Simulation::merged_event_step`] after its steady trial failed.
    #[inline]
    pub(super) fn merged_events_apply(&self) -> bool {
        self.tables.options.merged_events
            && self.tables.residual.is_empty()
            && self.scratch.merged.trial_ready
    }

    /// The current step with its events in one solve (module doc), after
    /// [`Simulation::compliant_steady_step`]'s trial. `Some((events,
    /// solves))` once committed; `None`, with only scratch values changed,
    /// when the step is the sub-steps'.
    pub(super) fn merged_event_step(&mut self) -> Result<Option<(u32, u32)>, SolverError> {
        if !self.merged_events_apply() {
            return Ok(None);
        }
        // (a large set's trial projected only its own rows)
        self.free_values_after_trial();
        let dt = self.tables.dt_s;
        let kept = self.trial_by_kept_inverse();
        {
            let m = &mut self.scratch.merged;
            m.set.clear();
            m.set.extend_from_slice(&self.state.active);
            m.full = m.set.len();
            // (the landing search skips the starting set by `contact`)
            debug_assert!(
                m.set.iter().all(|&j| self.state.contact[j])
                    && self.state.contact.iter().filter(|&&c| c).count() == m.full
            );
            m.trial_set.clear();
            m.trial_kept = kept;
            if m.trial_kept {
                // (the kept inverse's slot order, and the trial's solution
                // in it: `A⁻¹ b` of the bordered solve before any release)
                m.trial_set.extend_from_slice(self.factors.updated.points());
                let n0 = m.trial_set.len();
                for (r, &a) in m.trial_set.iter().enumerate() {
                    (m.trial_x[r], m.trial_x[n0 + r]) = (self.scratch.q1[a], self.scratch.q2[a]);
                }
            } else {
                m.trial_set.extend_from_slice(&self.state.active);
            }
            m.border.clear();
            m.z_done = 0;
            m.late_tau_s.clear();
            m.early.clear();
            if !m.known_clear {
                m.known.reset();
                m.known_x.fill(0.0);
                m.known_v.fill(0.0);
                m.known_clear = true;
            }
        }
        let mut solves = 0u32;
        loop {
            match self.next_merged_event() {
                Next::None => break,
                Next::Unsupported => return Ok(None),
                _ if self.scratch.merged.late_tau_s.len() + self.scratch.merged.early.len()
                    >= MERGED_EVENTS =>
                {
                    return Ok(None);
                }
                Next::Release(k, theta) => self.merged_release(k, theta),
                Next::Landing(i, theta) => {
                    if dt - theta <= 1e-9 * dt {
                        return Ok(None);
                    }
                    self.merged_landing(i, dt - theta);
                }
                Next::Reland(k, theta) => {
                    let m = &mut self.scratch.merged;
                    let j = m.set.remove(k);
                    m.full -= 1;
                    if let Some(k0) = m.trial_set.iter().position(|&x| x == j) {
                        m.border.push(Border::Left(k0));
                    }
                    self.merged_landing(j, dt - theta);
                }
            }
            let n = self.scratch.merged.set.len();
            if n > MERGED_SET_MAX {
                return Ok(None);
            }
            let bordered = self.tables.options.reuse_factorisation
                && (self.scratch.merged.trial_kept
                    || self.factors.factored
                        && self.factors.current.set == self.scratch.merged.trial_set);
            let solved = if bordered {
                self.merged_solve_bordered()
            } else if n == 0 {
                // (no force left but the known loads)
                self.merged_end_values();
                true
            } else {
                self.merged_solve()
            };
            if !solved {
                return Ok(None);
            }
            solves += (n > 0) as u32;
        }
        // commit: the free prediction plus the full-step forces, the late
        // points' and the known loads' responses
        let events = self.scratch.merged.late_tau_s.len() + self.scratch.merged.early.len();
        let (tb, st, s) = (&self.tables, &mut self.state, &mut self.scratch);
        let m = &mut s.merged;
        // (a large set's trial formed its end state and the next step's
        // rows from it: neither is this step's)
        s.fused_end = false;
        s.ahead.pending = false;
        std::mem::swap(&mut st.modal, &mut s.free);
        let full = &m.set[..m.full];
        st.modal
            .add_gauss_forces_on(&tb.basis, &tb.full, full, &s.q1, &s.q2, &self.threads);
        for &j in full {
            s.impulse[j] += 0.5 * dt * (s.q1[j] + s.q2[j]);
        }
        for (l, &i) in m.set[m.full..].iter().enumerate() {
            let (q1, q2) = (s.q1[i], s.q2[i]);
            let tau = m.late_tau_s[l];
            tb.short_table(tau, &mut m.tab);
            (m.g1[i], m.g2[i]) = (q1, q2);
            st.modal
                .add_gauss_forces(&tb.basis, &m.tab, &[i], &m.g1, &m.g2);
            (m.g1[i], m.g2[i]) = (0.0, 0.0);
            s.impulse[i] += 0.5 * tau * (q1 + q2);
        }
        if !m.early.is_empty() {
            st.modal.add(&m.known);
        }
        for e in &m.early {
            s.impulse[e.point] += 0.5 * e.theta_s * (e.rq1 + e.rq2);
            st.released[e.point] = true;
        }
        st.active.clone_from(&m.set);
        std::mem::swap(&mut st.u, &mut s.ue);
        std::mem::swap(&mut st.v, &mut s.ve);
        std::mem::swap(&mut st.r, &mut s.re);
        std::mem::swap(&mut st.rd, &mut s.rde);
        Ok(Some((events as u32, solves)))
    }

    /// Whether the trial was solved through the kept inverse of a large
    /// set ([`Simulation::solve_full_large`]), which holds exactly the
    /// active points.
    fn trial_by_kept_inverse(&self) -> bool {
        let inv = &self.factors.updated;
        self.large_full_step()
            && self.factors.updated_valid
            && inv.points().len() == self.state.active.len()
            && inv.points().len() <= MERGED_SET_MAX
            && self.state.active.iter().all(|j| inv.points().contains(j))
    }

    /// The earliest event of the current solution: a full-step point whose
    /// linear force crosses zero (as [`Simulation::locate`] finds it), a
    /// free point whose gap's Hermite cubic crosses the road; a late point
    /// whose force would pull is not this step's.
    fn next_merged_event(&self) -> Next {
        let (p, dt) = (self.tables.p, self.tables.dt_s);
        let (st, s, m) = (&self.state, &self.scratch, &self.scratch.merged);
        let mut next = Next::None;
        let mut first = f64::INFINITY;
        for (k, &j) in m.set[..m.full].iter().enumerate() {
            let (qs, qe) = (GA * s.q1[j] - GB * s.q2[j], -GB * s.q1[j] + GA * s.q2[j]);
            if qe < 0.0 || qs + qe < 0.0 {
                let unresolved = self.spring_unresolved(j, dt);
                if unresolved && qs + qe >= 0.0 {
                    continue;
                }
                if qe >= 0.0 && !unresolved {
                    // negative at the start only: the spring lets go at
                    // once and takes the road again where the linear
                    // force turns positive (`qs < -qe <= 0`)
                    if 0.0 < first {
                        (first, next) = (0.0, Next::Reland(k, dt * qs / (qs - qe)));
                    }
                    continue;
                }
                let th = if qs > 0.0 && !unresolved {
                    dt * qs / (qs - qe)
                } else {
                    0.0
                };
                if th < first {
                    (first, next) = (th, Next::Release(k, th));
                }
            }
        }
        for (l, &j) in m.set[m.full..].iter().enumerate() {
            let (qs, qe) = (GA * s.q1[j] - GB * s.q2[j], -GB * s.q1[j] + GA * s.q2[j]);
            let pulls = qe < 0.0 || qs + qe < 0.0;
            if pulls && !(self.spring_unresolved(j, m.late_tau_s[l]) && qs + qe >= 0.0) {
                return Next::Unsupported;
            }
        }
        let (u, v, r, rd) = (&st.u[..p], &st.v[..p], &st.r[..p], &st.rd[..p]);
        let (ue, ve, re, rde) = (&s.ue[..p], &s.ve[..p], &s.re[..p], &s.rde[..p]);
        // a released point back below the road by the step end is the
        // sub-steps' (they locate its landing once it rose clear)
        if m.early
            .iter()
            .any(|e| ue[e.point] - re[e.point] < -self.pen_tol_m)
        {
            return Next::Unsupported;
        }
        for i in 0..p {
            // (the step's starting set, `contact`, holds every full-step
            // and early point: their compressed springs are far below the
            // road, where locating a crossing would only be thrown away)
            if st.contact[i] {
                continue;
            }
            let (g0, d0) = (u[i] - r[i], (v[i] - rd[i]) * dt);
            let (g1, d1) = (ue[i] - re[i], (ve[i] - rde[i]) * dt);
            if let Some(y) = first_crossing(g0, d0, g1, d1, self.pen_tol_m, st.released[i])
                && !m.set[m.full..].contains(&i)
            {
                let th = y * dt;
                if th < first {
                    (first, next) = (th, Next::Landing(i, th));
                }
            }
        }
        next
    }

    /// Every point's free end values `uh`, `vh` for the merged solve. A
    /// trial that fused its projection into its solve (a large set's,
    /// [`Simulation::fused_full_step`]) projected only the set's rows of
    /// its prediction, and the other points' end values from its end state:
    /// theirs are those end values less the response to the trial's forces,
    /// summed down the influence columns (`O(P |S|)`, against `O(P K)` to
    /// project every point again). Round-off apart, the same values.
    fn free_values_after_trial(&mut self) {
        if self.scratch.projected_all {
            return;
        }
        if !self.scratch.fused_end {
            return self.ensure_projected_all();
        }
        self.forces_response_by_columns();
        let p = self.tables.p;
        let (st, s) = (&self.state, &mut self.scratch);
        // (the trial's set is the contact set: its rows are projected)
        for i in 0..p {
            if !st.contact[i] {
                s.uh[i] = s.ue[i] - s.du[i];
                s.vh[i] = s.ve[i] - s.dv[i];
            }
        }
        s.projected_all = true;
        // (checked against the projection itself in debug builds: every
        // solver test that merges events after a fused trial runs it; the
        // known loads' buffers, cleared by the merged step next, hold it)
        #[cfg(debug_assertions)]
        {
            s.merged.known_clear = false;
            let (u, v) = (&mut s.merged.known_x, &mut s.merged.known_v);
            s.free.project_on(&self.tables.basis, u, v, &self.threads);
            let scale = |w: &[f64]| w.iter().fold(f64::MIN_POSITIVE, |m, x| m.max(x.abs()));
            let (su, sv) = (scale(u), scale(v));
            for i in (0..p).filter(|&i| !st.contact[i]) {
                debug_assert!(
                    (s.uh[i] - u[i]).abs() <= 1e-10 * su && (s.vh[i] - v[i]).abs() <= 1e-10 * sv,
                    "point {i}: free values {} m, {} m/s from the trial, {} m, {} m/s projected",
                    s.uh[i],
                    s.vh[i],
                    u[i],
                    v[i]
                );
            }
        }
    }

    /// Full-step entry `k` released at `θ`: its trial force on `[0, θ]`
    /// becomes a known load, `Φ(dt − θ)` of its response at `θ`.
    fn merged_release(&mut self, k: usize, theta: f64) {
        let dt = self.tables.dt_s;
        let (tb, s) = (&self.tables, &mut self.scratch);
        let m = &mut s.merged;
        let j = m.set.remove(k);
        m.full -= 1;
        let (q1, q2) = (s.q1[j], s.q2[j]);
        let (qs, qe) = (GA * q1 - GB * q2, -GB * q1 + GA * q2);
        let f = theta / dt;
        let (ya, yb) = (0.5 - 0.5 / SQRT3, 0.5 + 0.5 / SQRT3);
        let e = Early {
            point: j,
            theta_s: theta,
            rq1: qs + (qe - qs) * f * ya,
            rq2: qs + (qe - qs) * f * yb,
        };
        m.early.push(e);
        if let Some(k0) = m.trial_set.iter().position(|&x| x == j) {
            m.border.push(Border::Left(k0));
        }
        if theta <= 1e-9 * dt {
            return;
        }
        // the linear force over the whole step less its part on
        // `[θ, dt]` (the Gauss values of that interval, a step of
        // `dt − θ`): one table instead of `Φ(dt − θ)` of a step of `θ`
        let tau = dt - theta;
        let at = |y: f64| qs + (qe - qs) * (theta + tau * y) / dt;
        let columns = tb.tau_interp.as_ref().filter(|ti| ti.has_columns());
        // (the step's first release, where its load is not projected: the
        // load formed in the clear known state itself, the same sums)
        let direct = columns.is_some() && m.known_clear;
        let load = if direct {
            &mut m.known
        } else {
            m.load.reset();
            &mut m.load
        };
        (m.g1[j], m.g2[j]) = (q1, q2);
        load.add_gauss_forces(&tb.basis, &tb.full, &[j], &m.g1, &m.g2);
        tb.short_table(tau, &mut m.tab);
        let (r1, r2) = (-at(ya), -at(yb));
        (m.g1[j], m.g2[j]) = (r1, r2);
        load.add_gauss_forces(&tb.basis, &m.tab, &[j], &m.g1, &m.g2);
        (m.g1[j], m.g2[j]) = (0.0, 0.0);
        if !direct {
            m.known.add(&m.load);
        }
        m.known_clear = false;
        match columns {
            Some(ti) => {
                tb.add_full_step_response(j, q1, q2, &mut m.known_x, &mut m.known_v);
                ti.add_column(tau, j, r1, r2, &mut m.known_x, &mut m.known_v);
            }
            None => {
                let (du, dv) = (&mut s.du, &mut s.dv);
                m.load.project(&tb.basis, du, dv);
                for (a, b) in m.known_x.iter_mut().zip(du.iter()) {
                    *a += b;
                }
                for (a, b) in m.known_v.iter_mut().zip(dv.iter()) {
                    *a += b;
                }
            }
        }
    }

    /// Free point `i` landing `tau` before the step end: its unit
    /// responses at the step end (a step of `tau` from rest).
    fn merged_landing(&mut self, i: usize, tau: f64) {
        let p = self.tables.p;
        let (tb, m) = (&self.tables, &mut self.scratch.merged);
        let l = m.late_tau_s.len();
        m.late_tau_s.push(tau);
        m.set.push(i);
        m.border.push(Border::Late(l, i));
        let columns = tb.tau_interp.as_ref().filter(|ti| ti.has_columns());
        if let Some(ti) = columns {
            // (both units in one pass over the point's columns)
            let (x1, x2) = m.unit_x[2 * l * p..(2 * l + 2) * p].split_at_mut(p);
            let (v1, v2) = m.unit_v[2 * l * p..(2 * l + 2) * p].split_at_mut(p);
            ti.unit_columns(tau, i, [x1, v1, x2, v2]);
            return;
        }
        tb.short_table(tau, &mut m.tab);
        for c in 0..2 {
            let slot = 2 * l + c;
            let (ux, uv) = (
                &mut m.unit_x[slot * p..(slot + 1) * p],
                &mut m.unit_v[slot * p..(slot + 1) * p],
            );
            let (g1, g2) = if c == 0 { (1.0, 0.0) } else { (0.0, 1.0) };
            let u = &mut m.load;
            u.reset();
            (m.g1[i], m.g2[i]) = (g1, g2);
            u.add_gauss_forces(&tb.basis, &m.tab, &[i], &m.g1, &m.g2);
            u.project(&tb.basis, ux, uv);
        }
        (m.g1[i], m.g2[i]) = (0.0, 0.0);
    }

    /// Solves the merged system of the set and writes every point's end
    /// values into `ue`, `ve`; `false` if it is singular.
    fn merged_solve(&mut self) -> bool {
        let p = self.tables.p;
        let dt = self.tables.dt_s;
        let (tb, st, s) = (&self.tables, &mut self.state, &mut self.scratch);
        let m = &mut s.merged;
        let n = m.set.len();
        let (set, full, late_tau) = (&m.set, m.full, &m.late_tau_s);
        let g = &tb.full_inf;
        let kk = &tb.tread_k_n_m;
        let blocks = [&g.gx1, &g.gx2, &g.gv1, &g.gv2];
        let units = [&m.unit_x, &m.unit_v];
        let entry = |r: usize, c: usize| {
            let (rb, cb) = ((r >= n) as usize, (c >= n) as usize);
            let (a, mc) = (set[r % n], c % n);
            let b = set[mc];
            let (mut x, tau) = if mc < full {
                (blocks[2 * rb + cb][a * p + b], dt)
            } else {
                let slot = 2 * (mc - full) + cb;
                (units[rb][slot * p + a], late_tau[mc - full])
            };
            if a == b {
                let rate = SQRT3 / tau;
                let diag = [[-GB, GA], [-rate, rate]];
                x += diag[rb][cb] / kk[a];
            }
            x
        };
        st.stats.factorisations += 1;
        if m.solver.factor(2 * n, entry).is_err() {
            return false;
        }
        for (k, &a) in set.iter().enumerate() {
            m.rhs[k] = s.re[a] - s.uh[a] - m.known_x[a];
            m.rhs[n + k] = s.rde[a] - s.vh[a] - m.known_v[a];
        }
        m.solver.solve(&mut m.rhs[..2 * n]);
        for (k, &b) in set.iter().enumerate() {
            s.q1[b] = m.rhs[k];
            s.q2[b] = m.rhs[n + k];
        }
        self.merged_end_values();
        true
    }

    /// Every point's end values under the known loads and the solved
    /// forces of the set, into `ue`, `ve`.
    fn merged_end_values(&mut self) {
        let p = self.tables.p;
        let (tb, s) = (&self.tables, &mut self.scratch);
        let m = &s.merged;
        let (set, full) = (&m.set, m.full);
        let (ue, ve) = (&mut s.ue[..p], &mut s.ve[..p]);
        for i in 0..p {
            ue[i] = s.uh[i] + m.known_x[i];
            ve[i] = s.vh[i] + m.known_v[i];
        }
        tb.add_set_full_step_response(&set[..full], &s.q1, &s.q2, ue, ve);
        for (l, &j) in set[full..].iter().enumerate() {
            for (c, q) in [s.q1[j], s.q2[j]].into_iter().enumerate() {
                let slot = 2 * l + c;
                let (ux, uv) = (
                    &m.unit_x[slot * p..(slot + 1) * p],
                    &m.unit_v[slot * p..(slot + 1) * p],
                );
                for i in 0..p {
                    ue[i] += ux[i] * q;
                    ve[i] += uv[i] * q;
                }
            }
        }
    }
}
