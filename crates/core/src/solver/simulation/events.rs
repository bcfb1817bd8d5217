//! Events inside the step (method §4.4, "where we go beyond the paper"): the
//! `Located` scheme's step and inelastic multi-point impacts (landings are
//! located by `crossing.rs`). Compliant contact (`compliant.rs`) takes the same
//! step: its landings and releases are located alike, a landing adds the
//! point to the springs in compression with no impulse.
//!
//! The step is a loop over sub-steps, each the four stages of `stages.rs`:
//! predict, solve, locate, then commit up to the first event, which is
//! applied before the next sub-step.

use super::contact::{DenseSolver, Singular};
use super::parts::{Scratch, SimState, SimTables};
use super::stages::Located;
use super::{GA, GB, Simulation, Table};
use crate::solver::error::SolverError;

/// How far a located step has come.
struct Progress {
    /// Time reached (s).
    t_s: f64,
    /// What is left of the step (s).
    remaining_s: f64,
    events: u32,
    solves: u32,
}

impl Progress {
    /// Past a committed sub-step of `tau` (s).
    #[inline]
    fn advance(&mut self, tau: f64) {
        self.t_s += tau;
        self.remaining_s -= tau;
    }
}

impl Simulation {
    /// A step with events located inside it (method §4.4, "Events inside the
    /// step"): from the active set at the step start, sub-steps of predict,
    /// solve, locate and commit (`stages.rs`) up to the first event each,
    /// until the step end. `after_steady`: [`Simulation::steady_step`] was
    /// tried first from the same state and handed the step over; its free
    /// prediction over the whole step (`free`, road at the step end; the
    /// free end values in `uh`, `vh`, or swapped into `ue`, `ve` when no
    /// point was on the road) is this loop's first prediction, which is then
    /// not repeated.
    ///
    /// With tread springs (compliant contact, method §4.6) the step is the
    /// same but for what an event does: a landing adds the point to the
    /// active set (a massless spring takes no impulse; its force starts from
    /// zero), a free point left compressed at the step start joins it there,
    /// the Gauss-point solves are the compliant ones, and a cascade of
    /// events ends with the compliant step-end rule. Breakpoints of a
    /// measured road do not split its steps (no impulse at a kink of the
    /// road).
    pub(super) fn located_step(
        &mut self,
        t_start: f64,
        after_steady: bool,
    ) -> Result<(u32, u32), SolverError> {
        let dt = self.tables.dt_s;
        let mut at = Progress {
            t_s: t_start,
            remaining_s: dt,
            events: 0,
            solves: 0,
        };
        // the steady attempt's prediction holds while nothing changed the
        // state: no landing at the step start (the first sub-step is then the
        // whole step: the steady path runs only on roads without breakpoints
        // under active points, and a step without them has none to stop at)
        let mut predicted = self.start_active_set(&mut at, after_steady)?;
        // the span of a prediction still valid for the next trial
        let mut kept_prediction: Option<(f64, f64, Table)> = None;
        while at.remaining_s > 1e-12 * dt {
            if at.events > self.tables.max_events {
                at.solves += self.finish_cascade(at.t_s, at.remaining_s)?;
                break;
            }
            let (span, sel) = self.next_span(&mut at)?;
            // predict (unless the steady attempt did, over this very span)
            let reuse = std::mem::take(&mut predicted) && sel == Table::Full && at.t_s == t_start;
            // (or a release at once, which changes no state, left it)
            // (a road with breakpoints may resample the road between trials)
            let kept = std::mem::take(&mut kept_prediction) == Some((at.t_s, span, sel))
                && !self.road.has_kinks()
                && (self.scratch.projected_all
                    || self.fused_full_step()
                    || (sel == Table::Sub && self.iterative_sub_step()));
            if !reuse && !kept {
                self.predict(at.t_s, span, sel)?;
            }
            self.solve_contact(at.t_s + span, sel)?;
            at.solves += !self.state.active.is_empty() as u32;
            let found = self.locate(at.t_s, span);
            if let Some((k, th, _)) = found.release
                && th <= 0.0
            {
                self.release(k);
                at.events += 1;
                kept_prediction = Some((at.t_s, span, sel));
                continue;
            }
            let th_rel = found.release.map_or(f64::INFINITY, |r| r.1);
            let th_imp = found.impact.map_or(f64::INFINITY, |r| r.1);
            let th = th_rel.min(th_imp);
            if !th.is_finite() {
                self.commit(span, sel);
                at.advance(span);
                continue;
            }
            // commit up to the event
            if th >= span * (1.0 - 1e-12) {
                self.commit(span, sel);
                at.advance(span);
            } else if th > 1e-9 * span {
                // (an event within 1e-9 of the sub-step start happens at its
                // start: no degenerate sub-step is solved)
                if let Some(k) = self.pulling_before(th / span) {
                    self.release_or_hold(k, at.t_s);
                    at.events += 1;
                    continue;
                }
                self.commit_to_event(&mut at, span, th, th_imp > th_rel)?;
            }
            at.events += 1;
            self.apply_event(&mut at, found, th_imp <= th_rel)?;
        }
        Ok((at.events, at.solves))
    }

    /// The active set at the step start (method §4.4, "Landing at the step
    /// start" and "Trial"): the points in contact carry over; the point
    /// deepest below the road, left there by the last step, lands now (an
    /// impact); with tread springs, every free spring left compressed joins
    /// the set. Returns whether the steady attempt's prediction still holds
    /// (`after_steady` and no landing).
    fn start_active_set(
        &mut self,
        at: &mut Progress,
        after_steady: bool,
    ) -> Result<bool, SolverError> {
        let compliant = self.tables.compliant();
        let p = self.tables.p;
        let st = &mut self.state;
        let (contact, u, r) = (&st.contact[..p], &st.u[..p], &st.r[..p]);
        st.active.clear();
        let mut deepest: Option<(usize, f64)> = None;
        for i in 0..p {
            if contact[i] {
                st.active.push(i);
            } else {
                let g = u[i] - r[i];
                if g < -self.pen_tol_m {
                    if compliant {
                        st.active.push(i);
                        at.events += 1;
                    } else if deepest.is_none_or(|(_, d)| g < d) {
                        deepest = Some((i, g));
                    }
                }
            }
        }
        let predicted = after_steady && deepest.is_none();
        if predicted && st.active.is_empty() {
            // (the steady attempt without active points swapped the free end
            // values into `ue`, `ve`)
            let s = &mut self.scratch;
            std::mem::swap(&mut s.ue, &mut s.uh);
            std::mem::swap(&mut s.ve, &mut s.vh);
        }
        if let Some((i, _)) = deepest {
            at.solves += self.impact(at.t_s, i)?;
            at.events += 1;
        }
        Ok(predicted)
    }

    /// After `4P + 16` events in the step (method §4.4, "Cascades"): the
    /// rest of it, `remaining` from `t`, by the paper's rule (method §4.3)
    /// or the compliant step-end rule. Returns the solves.
    fn finish_cascade(&mut self, t: f64, remaining: f64) -> Result<u32, SolverError> {
        self.prepare_sub(remaining);
        if self.tables.compliant() {
            self.compliant_substep(t, remaining, Table::Sub)
        } else {
            self.paper_substep(t, remaining, Table::Sub)
        }
    }

    /// The next sub-step from `at` and its table (method §4.4, "Measured
    /// roads"): an active point on a breakpoint where the road turns up
    /// takes an impact first; the sub-step ends at the step end or where an
    /// active point meets a breakpoint. The full step's table for the whole
    /// step, else the sub-step's, filled for the span.
    fn next_span(&mut self, at: &mut Progress) -> Result<(f64, Table), SolverError> {
        let compliant = self.tables.compliant();
        // An active point on a breakpoint where the road turns upward is hit
        // by it: an inelastic impulse (a downward turn releases it in the
        // trial).
        if !compliant && let Some(i) = self.kinked_up(at.t_s)? {
            at.solves += self.impact(at.t_s, i)?;
            at.events += 1;
        }
        // (a measured profile's breakpoint: the road velocity jumps there,
        // which no smooth force can follow)
        let span = if compliant {
            at.remaining_s
        } else {
            self.kink_limit(at.t_s, at.remaining_s)
        };
        if span == self.tables.dt_s {
            return Ok((span, Table::Full));
        }
        if self.scratch.sub.tau_s != span {
            self.prepare_sub(span);
        }
        Ok((span, Table::Sub))
    }

    /// Entry `k` of the active set released (not re-added in this step).
    fn release(&mut self, k: usize) {
        let j = self.state.active.remove(k);
        self.state.released[j] = true;
    }

    /// Frees active entry `k`, whose trial force would pull before an
    /// event, from time `t` (s) to that event. A point on the road is
    /// released (it lands again in this step only after it rose clear of
    /// the road). A tread spring is held free instead: a spring that
    /// landed a moment ago holds almost no force, and the linear force
    /// through its Gauss points, positive there, extrapolates below zero
    /// at the sub-step start; the spring lands again, located as any
    /// landing, once time has moved on from `t` (method §4.6, "A spring
    /// freed before an event").
    fn release_or_hold(&mut self, k: usize, t: f64) {
        if self.tables.compliant() {
            let j = self.state.active.remove(k);
            self.state.held_at_s[j] = t;
        } else {
            self.release(k);
        }
    }

    /// The active point (its entry) whose force dips below zero at the
    /// sub-step start and would pull on average over the fraction `f` of
    /// the sub-step before an event: it is released at once instead.
    fn pulling_before(&self, f: f64) -> Option<usize> {
        let s = &self.scratch;
        self.state.active.iter().position(|&j| {
            let (qs, qe) = (GA * s.q1[j] - GB * s.q2[j], -GB * s.q1[j] + GA * s.q2[j]);
            let mean = qs + 0.5 * (qe - qs) * f;
            mean < -1e-9 * (qs.abs() + qe.abs())
        })
    }

    /// Predict, solve and commit over `[0, θ]` of the sub-step of `span`
    /// before an event (method §4.4, "Split"). Up to a release
    /// (`up_to_release`), the trial forces restricted to `[0, θ]` (they
    /// stay >= 0 up to the crossing; active points stay on the road to
    /// O(θ⁴)). Up to an impact, solved again so that the active points are
    /// exactly on the road at the impact, unless that solve would pull
    /// somewhere: then restricted as well.
    fn commit_to_event(
        &mut self,
        at: &mut Progress,
        span: f64,
        th: f64,
        up_to_release: bool,
    ) -> Result<(), SolverError> {
        let f = th / span;
        let (ya, yb) = (0.5 - 0.5 / 3f64.sqrt(), 0.5 + 0.5 / 3f64.sqrt());
        let s = &mut self.scratch;
        for &j in &self.state.active {
            let (q1, q2) = (s.q1[j], s.q2[j]);
            let (qs, qe) = (GA * q1 - GB * q2, -GB * q1 + GA * q2);
            s.events.rq1[j] = qs + (qe - qs) * f * ya;
            s.events.rq2[j] = qs + (qe - qs) * f * yb;
        }
        self.prepare_sub(th);
        self.predict(at.t_s, th, Table::Sub)?;
        let mut restricted = up_to_release;
        if !restricted {
            self.solve_contact(at.t_s + th, Table::Sub)?;
            at.solves += !self.state.active.is_empty() as u32;
            // a re-solve that would pull somewhere keeps the trial's forces
            let s = &self.scratch;
            restricted = self.state.active.iter().any(|&j| {
                let (q1, q2) = (s.q1[j], s.q2[j]);
                q1 + q2 < -1e-9 * (q1.abs() + q2.abs())
            });
        }
        if restricted {
            let s = &mut self.scratch;
            for &j in &self.state.active {
                (s.q1[j], s.q2[j]) = (s.events.rq1[j], s.events.rq2[j]);
            }
            self.end_values_sub();
        }
        self.commit(th, Table::Sub);
        at.advance(th);
        Ok(())
    }

    /// The located event at the time reached (method §4.4, "Impact"): an
    /// impact (`impact_first`) is an inelastic impulse, or with tread
    /// springs the point joins the set with none; else the release.
    fn apply_event(
        &mut self,
        at: &mut Progress,
        found: Located,
        impact_first: bool,
    ) -> Result<(), SolverError> {
        if impact_first {
            let (i, _) = found.impact.unwrap_or((0, 0.0));
            if !self.tables.compliant() {
                at.solves += self.impact(at.t_s, i)?;
            } else if !self.state.active.contains(&i) {
                // a spring lands with zero force: no impulse
                self.state.active.push(i);
            }
        } else if let Some((k, _, _)) = found.release {
            self.release(k);
        }
        Ok(())
    }

    /// At a breakpoint of a measured road under an active point: the road
    /// rates become those after it, and the point whose road now rises
    /// faster than it moves (the road turns up into it) is returned.
    fn kinked_up(&mut self, t: f64) -> Result<Option<usize>, SolverError> {
        let vel = self.problem.speed_mps;
        if vel <= 0.0 || !self.road.has_kinks() {
            return Ok(None);
        }
        let s = vel * t + self.state.x_offset_m;
        let eps = 1e-9 * vel * self.tables.dt_s;
        let Some(&i) = self
            .state
            .active
            .iter()
            .find(|&&i| self.road.at_kink(i, s, eps))
        else {
            return Ok(None);
        };
        // from here on the road's rate is the one after the breakpoint
        self.road_at(t, true)?;
        let (st, sc) = (&mut self.state, &self.scratch);
        st.r.copy_from_slice(&sc.re);
        st.rd.copy_from_slice(&sc.rde);
        let scale = sc.rde.iter().fold(1e-6, |m: f64, x| m.max(x.abs()));
        let up = st
            .active
            .iter()
            .any(|&j| sc.rde[j] > st.v[j] + 1e-9 * scale);
        Ok(up.then_some(i))
    }

    /// Length of the next sub-step from `t`: `remaining`, or less where an
    /// active point reaches a breakpoint of a measured road first.
    fn kink_limit(&self, t: f64, remaining: f64) -> f64 {
        let vel = self.problem.speed_mps;
        if vel <= 0.0 || self.state.active.is_empty() || !self.road.has_kinks() {
            return remaining;
        }
        let s0 = vel * t + self.state.x_offset_m;
        let s1 = s0 + vel * remaining;
        let mut span = remaining;
        for &i in &self.state.active {
            if let Some(sk) = self.road.next_kink(i, s0, s1) {
                span = span.min((sk - s0) / vel);
            }
        }
        span
    }

    /// Perfectly inelastic impact of point `i` at `t` (method §4.4,
    /// "Impact"): impulses on all points on the road together so that their
    /// velocities equal the road's; a point whose impulse would pull is
    /// thrown off ([`joint_impact`], or [`one_by_one_impact`] without
    /// `SolverOptions::joint_impacts`).
    fn impact(&mut self, t: f64, i: usize) -> Result<u32, SolverError> {
        self.road_at(t, true)?;
        let pen_tol_m = self.pen_tol_m;
        let (tb, st, s) = (&self.tables, &mut self.state, &mut self.scratch);
        st.r.copy_from_slice(&s.re);
        st.rd.copy_from_slice(&s.rde);
        if !st.active.contains(&i) {
            st.active.push(i);
        }
        let p = tb.p;
        // With residual flexibility every point on the road meets it through
        // the dropped modes' static compliance `C`, which has no mass: an
        // inelastic landing takes no impulse (method §4.7). The velocity
        // mismatch becomes the force rate of the next sub-step
        // (`v = v_kept + C q'`), whose solve puts the points on the road in
        // position and velocity at its end. A kept-mode impulse instead
        // treats the points as rigid: it throws neighbours off whose force
        // was holding them on the road through `C q`; that deflection
        // vanishes at once, they are below the road again and land, and so
        // on to the event limit in every step. Only where `C` is singular on
        // the points on the road (fewer dropped modes than such points) is a
        // rigid impact left.
        if !tb.residual.is_empty()
            && super::residual::compliant_on(&tb.residual, p, &st.active, &mut s.dense.gss)
        {
            return Ok(0);
        }
        let solves = if tb.options.joint_impacts {
            joint_impact(tb, st, s, t, i, pen_tol_m)?
        } else {
            one_by_one_impact(tb, st, s, t, i)?
        };
        let n = st.active.len();
        s.q1.fill(0.0);
        for k in 0..n {
            s.q1[st.active[k]] = s.rhs[k];
        }
        st.modal.add_impulses(&tb.basis, &st.active, &s.q1);
        for &j in &st.active {
            s.impulse[j] += s.q1[j];
            st.impact_impulse[j] += s.q1[j];
        }
        for a in 0..p {
            st.v[a] += st
                .active
                .iter()
                .map(|&j| tb.jump_t[j * p + a] * s.q1[j])
                .sum::<f64>();
        }
        Ok(solves)
    }
}

/// The impulses of an inelastic impact at `t` (method §4.4, "Impact"),
/// one point thrown off at a time: the set on the road (`st.active`, with
/// the landing point `i`) solved together, the point whose impulse would
/// pull the most thrown off, and solved again. The impulses are left in
/// `s.rhs`, by entry of the remaining set. Returns the solves.
fn one_by_one_impact(
    tb: &SimTables,
    st: &mut SimState,
    s: &mut Scratch,
    t: f64,
    i: usize,
) -> Result<u32, SolverError> {
    let p = tb.p;
    let mut solves = 0;
    while !st.active.is_empty() {
        let n = st.active.len();
        let act = &st.active;
        let jump = &tb.jump;
        if let Err(e) = solve_impulses(tb, st, &mut s.dense.solver, &mut s.rhs) {
            return Err(SolverError::SingularContactSystem {
                t_s: t,
                points: st.active.clone(),
                pivot: e.pivot,
            });
        }
        solves += 1;
        let v_tol = impact_v_tol(st);
        let worst = (0..n)
            .map(|k| (k, s.rhs[k] * jump[act[k] * p + act[k]]))
            .filter(|&(_, dv)| dv < -v_tol)
            .min_by(|a, b| a.1.total_cmp(&b.1));
        match worst {
            Some((k, _)) => {
                // Thrown off with a positive relative velocity: it may land
                // again later in this step (a located event). Only the landing
                // point itself, if it cannot land, is kept off until the next step.
                let j = st.active.remove(k);
                if j == i {
                    st.released[j] = true;
                }
            }
            None => break,
        }
    }
    Ok(solves)
}

/// The impact's impulses of the set on the road `st.active` (method §4.4,
/// "Impact"): `(Σ_k A_k)_S J = r'_S − v_S` factored and solved, `J` into
/// `rhs` by entry of the set.
fn solve_impulses(
    tb: &SimTables,
    st: &SimState,
    solver: &mut DenseSolver,
    rhs: &mut [f64],
) -> Result<(), Singular> {
    let (p, jump, act) = (tb.p, &tb.jump, &st.active);
    let n = act.len();
    solver.factor(n, |r, c| jump[act[r] * p + act[c]])?;
    for (k, &j) in act.iter().enumerate() {
        rhs[k] = st.rd[j] - st.v[j];
    }
    solver.solve(&mut rhs[..n]);
    Ok(())
}

/// Velocity (m/s) a pulling impulse of the set on the road stands for:
/// below it a violation is round-off or the tail of a converged impact
/// cascade, and the point stays on.
fn impact_v_tol(st: &SimState) -> f64 {
    1e-9 * st
        .active
        .iter()
        .map(|&j| st.rd[j].abs().max(st.v[j].abs()))
        .fold(1e-6, f64::max)
}

/// Throw-offs of a point in one step after which a slow one is a Zeno
/// sequence (method §4.4, "Zeno sequences").
const ZENO_THROW_OFFS: u32 = 2;

/// Velocity away from the road, relative to the largest `|v|`, `|r'|` of
/// an impact's candidates, below which a point of a Zeno sequence stays on
/// the road (method §4.4, "Zeno sequences").
const ZENO_VELOCITY: f64 = 1e-3;

/// The impulses of an inelastic impact at `t` as one complementarity
/// problem (method §4.4, "Several events at one instant"): over the
/// candidates `C` (the set on the road, the landing point `i`, and every
/// free point at the road, `u - r <= pen_tol`, moving into it, not
/// released in this step), impulses `J >= 0` and velocities after the
/// impact relative to the road `w = v + (Σ_k A_k) J - r' >= 0` with
/// `J_j w_j = 0`. Solved by principal pivoting from `S` = the set on the
/// road and `i` (the free points join by flips; one whose joining makes
/// the system singular stays off and lands later): `J_S` from the impulse
/// system with `w_S = 0`; the worst violation (a pulling
/// impulse `J_j (Σ_k A_k)_jj < -v_tol`, or a point off the set moving into
/// the road, `w_j < -v_tol`) flips its point in or out, the most negative
/// first, then the first in `C`'s order (Murty's least-index rule, finite
/// for a P-matrix: `Σ_k A_k` of symmetric mode shapes is positive
/// definite on independent points); past `8|C| + 32` flips only pulling
/// points leave, so the set shrinks to an end. A point of the set on the
/// road thrown off for the third time in the step and moving away slower
/// than [`ZENO_VELOCITY`] of the velocity scale stays in `S` with no
/// impulse (method §4.4, "Zeno sequences"). Sets `st.active` to `S` and
/// leaves `J_S` in `s.rhs` by entry. Returns the solves.
fn joint_impact(
    tb: &SimTables,
    st: &mut SimState,
    s: &mut Scratch,
    t: f64,
    i: usize,
    pen_tol_m: f64,
) -> Result<u32, SolverError> {
    let (p, jump) = (tb.p, &tb.jump);
    let (cand, in_set) = (&mut s.events.impact_candidates, &mut s.events.impact_in_set);
    cand.clear();
    cand.extend_from_slice(&st.active);
    let mut n_on = cand.len();
    for &j in cand.iter() {
        in_set[j] = true;
    }
    // (the free points at the road join `S` by the flips below, if they
    // would move into it: `in_set` marks the candidates until then)
    for j in 0..p {
        let w = st.v[j] - st.rd[j];
        if !in_set[j]
            && !st.released[j]
            && st.u[j] - st.r[j] <= pen_tol_m
            && w < -1e-9 * st.rd[j].abs().max(st.v[j].abs()).max(1e-6)
        {
            cand.push(j);
            in_set[j] = true;
        }
    }
    for &j in &cand[n_on..] {
        in_set[j] = false;
    }
    let mut joined: Option<usize> = None;
    let (most_negative_flips, all_flips) = (4 * cand.len() + 16, 8 * cand.len() + 32);
    let (mut solves, mut flips) = (0, 0);
    loop {
        st.active.clear();
        st.active
            .extend(cand.iter().copied().filter(|&j| in_set[j]));
        let (act, n) = (&st.active, st.active.len());
        if n > 0 {
            if let Err(e) = solve_impulses(tb, st, &mut s.dense.solver, &mut s.rhs) {
                if let Some(j) = joined.take() {
                    // a point whose joining makes the system singular stays
                    // off: it lands later as an event of its own
                    in_set[j] = false;
                    if let Some(c) = cand.iter().position(|&x| x == j) {
                        cand.remove(c);
                        n_on -= usize::from(c < n_on);
                    }
                    continue;
                }
                for &j in cand.iter() {
                    in_set[j] = false;
                }
                return Err(SolverError::SingularContactSystem {
                    t_s: t,
                    points: st.active.clone(),
                    pivot: e.pivot,
                });
            }
            solves += 1;
        }
        let v_tol = impact_v_tol(st);
        let pulling = (0..n)
            .map(|k| (act[k], s.rhs[k] * jump[act[k] * p + act[k]]))
            .filter(|&(_, dv)| dv < -v_tol);
        let mut worst: Option<(usize, f64)> = None;
        let mut first: Option<usize> = None;
        for (j, dv) in pulling {
            if worst.is_none_or(|(_, d)| dv < d) {
                worst = Some((j, dv));
            }
        }
        if flips < all_flips {
            for (c, &j) in cand.iter().enumerate() {
                if in_set[j] {
                    continue;
                }
                let w = st.v[j] - st.rd[j]
                    + (0..n).map(|k| jump[j * p + act[k]] * s.rhs[k]).sum::<f64>();
                if w < -v_tol && worst.is_none_or(|(_, d)| w < d) {
                    worst = Some((j, w));
                }
                if w < -v_tol && first.is_none() {
                    first = Some(c);
                }
            }
        }
        let Some((mut j, _)) = worst else { break };
        if flips >= most_negative_flips && flips < all_flips {
            // Murty's least-index rule: the first violation in `C`'s order
            let pulls = |c: usize| {
                act.iter()
                    .position(|&a| a == cand[c])
                    .is_some_and(|k| s.rhs[k] * jump[act[k] * p + act[k]] < -v_tol)
            };
            let first_pull = (0..cand.len()).find(|&c| pulls(c));
            j = cand[match (first_pull, first) {
                (Some(a), Some(b)) => a.min(b),
                (Some(a), None) | (None, Some(a)) => a,
                (None, None) => break,
            }];
        } else if flips >= all_flips && !in_set[j] {
            break;
        }
        in_set[j] = !in_set[j];
        joined = in_set[j].then_some(j);
        flips += 1;
    }
    // a point on the road thrown off a third time in the step, moving away
    // slowly, stays on with no impulse (method §4.4, "Zeno sequences")
    let n = st.active.len();
    let vscale = cand
        .iter()
        .map(|&j| st.rd[j].abs().max(st.v[j].abs()))
        .fold(1e-6, f64::max);
    for c in 0..n_on {
        let j = cand[c];
        if j == i || in_set[j] {
            continue;
        }
        let w = st.v[j] - st.rd[j]
            + (0..n)
                .map(|k| jump[j * p + st.active[k]] * s.rhs[k])
                .sum::<f64>();
        if st.thrown_off[j] >= ZENO_THROW_OFFS && w <= ZENO_VELOCITY * vscale {
            st.active.push(j);
            s.rhs[st.active.len() - 1] = 0.0;
        } else {
            st.thrown_off[j] += 1;
        }
    }
    for &j in cand.iter() {
        in_set[j] = false;
    }
    // the landing point thrown off is kept off until the next step
    if !st.active.contains(&i) {
        st.released[i] = true;
    }
    Ok(solves)
}
