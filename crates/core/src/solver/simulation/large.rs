//! Large active sets (method §4.5, "Large active sets"), from
//! [`SolverOptions::large_set_from`](super::SolverOptions) points on the
//! road: the cost of the contact follows what changes.
//!
//! - **Full step.** The inverse of the `2|S|` full-step system is kept
//!   from step to step and, when points join or leave the set, updated by
//!   bordering (`contact/bordered.rs`, `O(|S|²)` per point) instead of a
//!   new factorisation and inverse (`O(|S|³)`). The solve of a step after
//!   an update is checked by its componentwise backward error; above
//!   [`UPDATE_BACKWARD_ERROR`] the inverse is formed from scratch.
//! - **Sub-steps** of tread springs (between events): the system at the sub-step's length
//!   is solved by GMRES (`contact/krylov.rs`) with the operator applied
//!   through the modal states (`O(|S| K)`) and a preconditioner of each
//!   point's own 2 × 2 block, instead of filling its `|S|² K` entries and
//!   factorising it. A solve that does not reach [`GMRES_TOLERANCE`] in
//!   [`GMRES_MAX_APPLICATIONS`] falls back to the direct one.

use super::{GA, GB, SQRT3, Simulation, Table};
use crate::solver::error::SolverError;

/// Largest componentwise backward error accepted from a solve by an
/// updated inverse; a backward-stable solve gives about `1e-15`.
pub const UPDATE_BACKWARD_ERROR: f64 = 1e-11;

/// Steps without an event after which a large set's full step fuses its
/// projection into its solve again ([`Simulation::fused_full_step`]). Events
/// on a rough road come in runs: a fused trial that meets an event throws
/// away the end state and the next step's rows it formed, and the event
/// step projects every point again. Counted over the shipped patches
/// (callgrind, 1 000 rolling steps): against fusing from the first quiet
/// step, 4 steps cost 7 % fewer instructions on the road texture, 5 % on
/// the wheel path and under 1 % more on the Belgian block, whose events
/// are rarer; 8 steps gain little more and cost the Belgian block 1.5 %.
pub const FUSE_AFTER_QUIET_STEPS: u32 = 4;

/// Relative residual of the preconditioned sub-step system at which GMRES
/// stops.
pub const GMRES_TOLERANCE: f64 = 1e-13;

/// Operator applications after which GMRES gives up (the direct solve
/// follows).
pub const GMRES_MAX_APPLICATIONS: usize = 90;

impl Simulation {
    /// The full-step compliant solve of a large active set (after
    /// `predict`): the kept inverse brought to the active set, the forces
    /// into `q1`, `q2` and the end values of every point into `ue`, `ve`.
    pub(super) fn solve_full_large(&mut self, t_end: f64) -> Result<(), SolverError> {
        let fused = self.fused_full_step();
        if fused {
            self.project_active_rows();
        }
        let updated = self.sync_updated_inverse(t_end)?;
        self.solve_by_updated();
        if updated && self.updated_backward_error() > UPDATE_BACKWARD_ERROR {
            self.state.stats.update_refusals += 1;
            self.form_updated_inverse(t_end)?;
            self.solve_by_updated();
        }
        let s = &mut self.scratch;
        for (a, &j) in self.factors.updated.points().iter().enumerate() {
            s.q1[j] = s.rhs[2 * a];
            s.q2[j] = s.rhs[2 * a + 1];
        }
        if fused {
            self.end_state_fused();
        } else {
            // (the prediction projected every point)
            self.end_values_by_columns();
        }
        Ok(())
    }

    /// The full-step solve of a large rigid active set (after `predict`,
    /// method §4.3 step 3): as [`Simulation::solve_full_large`], the
    /// kept inverse brought to the set by bordered updates (a cascade of
    /// releases at one instant costs `O(|S|²)` each, not a factorisation),
    /// and the active points ending exactly on the road, which is what the
    /// solve imposes.
    pub(super) fn solve_rigid_large(&mut self, t_end: f64) -> Result<(), SolverError> {
        self.solve_full_large(t_end)?;
        let s = &mut self.scratch;
        for &j in &self.state.active {
            s.ue[j] = s.re[j];
            s.ve[j] = s.rde[j];
        }
        Ok(())
    }

    /// Whether the full step is solved through the kept inverse of a
    /// large set ([`Simulation::solve_full_large`]).
    #[inline]
    pub(super) fn large_full_step(&self) -> bool {
        self.tables.large_sets()
            && self.tables.options.reuse_factorisation
            && self.state.active.len() >= self.tables.large_set_from()
    }

    /// Whether a full step's prediction leaves the projection to the solve
    /// (a large set's [`Simulation::solve_full_large`]). Not with tread
    /// springs whose events are merged, within [`FUSE_AFTER_QUIET_STEPS`]
    /// steps of an event (events come in runs on a rough road): a step with
    /// events reads every point's free values (method §4.6, "Events in one
    /// solve"), and the end state a fused trial forms for the next step
    /// would be thrown away. Quiet stretches keep the fused projection,
    /// which costs less.
    #[inline]
    pub(super) fn fused_full_step(&self) -> bool {
        self.large_full_step()
            && !(self.scratch.quiet_steps < FUSE_AFTER_QUIET_STEPS
                && self.tables.compliant()
                && self.tables.options.merged_events)
    }

    /// Whether a sub-step's prediction leaves the projection to the solve
    /// (a compliant set solved by GMRES: [`Simulation::solve_sub_iterative`]).
    #[inline]
    pub(super) fn iterative_sub_step(&self) -> bool {
        self.state.active.len() >= self.tables.iterative_sub_from()
    }

    /// The free end values `uh`, `vh` of every point, where the last
    /// prediction left them to the solve (before a solve that reads them
    /// all: the direct ones).
    pub(super) fn ensure_projected_all(&mut self) {
        let s = &mut self.scratch;
        if !s.projected_all {
            s.free
                .project_on(&self.tables.basis, &mut s.uh, &mut s.vh, &self.threads);
            s.projected_all = true;
        }
    }

    /// The free end values `uh`, `vh` of the active points only, from the
    /// predicted states (the same sums as the full projection's rows; `du`,
    /// `dv` hold the rows' values in the set's order on the way).
    ///
    /// After a fused full step the rows projected ahead from its end state
    /// are this prediction's (`ahead.in_use`, once): only the active points
    /// without one are projected here.
    fn project_active_rows(&mut self) {
        let (tb, s) = (&self.tables, &mut self.scratch);
        let rows = if std::mem::take(&mut s.ahead.in_use) {
            s.ahead.others.clear();
            for &i in &self.state.active {
                if s.ahead.row[i] {
                    (s.uh[i], s.vh[i]) = (s.ahead.uh[i], s.ahead.vh[i]);
                } else {
                    s.ahead.others.push(i);
                }
            }
            &s.ahead.others[..]
        } else {
            &self.state.active[..]
        };
        s.free.project_rows_on(
            &tb.basis,
            rows,
            &mut s.uh,
            &mut s.vh,
            [&mut s.du, &mut s.dv],
            &self.threads,
        );
    }

    /// The end state of the full step, the prediction plus the response to
    /// the solved Gauss-point forces (method §3.3), into `delta` (taken by
    /// `commit` as it is), and its projection, the end values of every
    /// point, into `ue`, `ve` (one pass over the output vectors, where the
    /// free prediction and the forces' response would take two), with the
    /// residual compliance's share where there is one.
    ///
    /// With tread springs, the active points' end values are instead what
    /// the solve imposes (the road less the springs' compression and its
    /// rate, method §4.6), and their rows project the next step's free
    /// prediction from this end state (`ahead.free`, read by that step's
    /// [`Self::project_active_rows`] once `commit` took this state): every
    /// row is read once a step, as in a step off the road.
    fn end_state_fused(&mut self) {
        if !self.tables.compliant() {
            return self.end_state_projected(Table::Full);
        }
        self.form_end_state(Table::Full);
        let (tb, st, s) = (&self.tables, &self.state, &mut self.scratch);
        let threads = &self.threads;
        let dt_s = tb.dt_s;
        // the rows ahead: the active points'
        for &j in &s.ahead.points {
            s.ahead.row[j] = false;
        }
        s.ahead.points.clear();
        s.ahead.points.extend_from_slice(&st.active);
        for &j in &st.active {
            s.ahead.row[j] = true;
        }
        // the next step's prediction and its active rows (first: with a
        // symmetric basis the forces just read these rows)
        s.delta
            .predict_into_on(&tb.full, &mut s.ahead.free, threads);
        let pk = [&mut s.du[..], &mut s.dv[..]];
        let (uh, vh) = (&mut s.ahead.uh, &mut s.ahead.vh);
        s.ahead
            .free
            .project_rows_on(&tb.basis, &st.active, uh, vh, pk, threads);
        // the points off the set: their end values from the end state
        s.ahead.others.clear();
        s.ahead
            .others
            .extend((0..tb.p).filter(|&i| !s.ahead.row[i]));
        let pk = [&mut s.du[..], &mut s.dv[..]];
        s.delta.project_rows_on(
            &tb.basis,
            &s.ahead.others,
            &mut s.ue,
            &mut s.ve,
            pk,
            threads,
        );
        s.ahead.pending = true;
        self.add_residual_ends(dt_s);
        // the active points: the road less the compression (the residual
        // compliance is in the solved system)
        let (tb, st, s) = (&self.tables, &self.state, &mut self.scratch);
        let rate = SQRT3 / dt_s;
        for &j in &st.active {
            let (q1, q2) = (s.q1[j], s.q2[j]);
            let kt = 1.0 / tb.tread_k_n_m[j];
            s.ue[j] = s.re[j] - kt * (-GB * q1 + GA * q2);
            s.ve[j] = s.rde[j] - kt * rate * (q2 - q1);
        }
    }

    /// The end state over `sel`, the prediction plus the response to the
    /// solved Gauss-point forces (method §3.3), into `delta`, which
    /// `commit` takes as it is.
    fn form_end_state(&mut self, sel: Table) {
        let (tb, st, s) = (&self.tables, &self.state, &mut self.scratch);
        let table = match sel {
            Table::Full => &tb.full,
            Table::Sub => &s.sub,
        };
        s.delta.copy_from(&s.free);
        s.delta
            .add_gauss_forces_on(&tb.basis, table, &st.active, &s.q1, &s.q2, &self.threads);
        s.fused_end = true;
    }

    /// [`Self::form_end_state`] and its projection, the end values of
    /// every point, into `ue`, `ve`, with the residual compliance's share
    /// where there is one.
    pub(super) fn end_state_projected(&mut self, sel: Table) {
        self.form_end_state(sel);
        let (tb, s) = (&self.tables, &mut self.scratch);
        s.delta
            .project_on(&tb.basis, &mut s.ue, &mut s.ve, &self.threads);
        let tau_s = match sel {
            Table::Full => tb.dt_s,
            Table::Sub => s.sub.tau_s,
        };
        self.add_residual_ends(tau_s);
    }

    /// Brings the kept inverse to the active set: the points that left
    /// removed, those that joined bordered in; formed from scratch when
    /// there is none, when more than a quarter of the set changed, or when
    /// an update meets a singular block. `true` if it was updated (its
    /// solve is then to be checked).
    fn sync_updated_inverse(&mut self, t_end: f64) -> Result<bool, SolverError> {
        let (st, s) = (&self.state, &mut self.scratch);
        let inv = &mut self.factors.updated;
        if !self.factors.updated_valid {
            return self.form_updated_inverse(t_end).map(|()| false);
        }
        // marks: the active points
        for &j in &st.active {
            s.large.mark[j] = true;
        }
        let leaving = inv.points().iter().filter(|&&j| !s.large.mark[j]).count();
        let staying = inv.points().len() - leaving;
        let joining = st.active.len() - staying;
        for &j in &st.active {
            s.large.mark[j] = false;
        }
        if leaving + joining == 0 {
            return Ok(false);
        }
        if 4 * (leaving + joining) > st.active.len() + 4 {
            return self.form_updated_inverse(t_end).map(|()| false);
        }
        let mut ok = true;
        // leaving, from the last slot down (the slots after one move down)
        for &j in &st.active {
            s.large.mark[j] = true;
        }
        let mut k = inv.points().len();
        while k > 0 && ok {
            k -= 1;
            if !s.large.mark[inv.points()[k]] {
                ok = inv.leave(k);
            }
        }
        for &j in &st.active {
            s.large.mark[j] = false;
        }
        // joining: the active points not in a slot
        for &j in inv.points() {
            s.large.mark[j] = true;
        }
        {
            let entry = full_entry(&self.tables);
            for &j in &st.active {
                if ok && !s.large.mark[j] {
                    ok = inv.join(j, &entry);
                }
            }
        }
        for &j in inv.points() {
            s.large.mark[j] = false;
        }
        self.state.stats.contact_updates += (leaving + joining) as u64;
        if !ok {
            return self.form_updated_inverse(t_end).map(|()| false);
        }
        Ok(true)
    }

    /// Forms the kept inverse of the active set from a new factorisation
    /// (slot order: the active set's).
    fn form_updated_inverse(&mut self, t_end: f64) -> Result<(), SolverError> {
        self.state.stats.factorisations += 1;
        let act = &self.state.active;
        let entry = full_entry(&self.tables);
        let solver = &mut self.factors.current.solver;
        let res = solver.factor(2 * act.len(), |e, u| {
            entry(act[e / 2], e % 2, act[u / 2], u % 2)
        });
        self.factors.updated_valid = res.is_ok();
        // the dense solver's factorisation is not that of `current.set`
        self.factors.factored = false;
        if let Err(e) = res {
            self.factors.updated.clear();
            return Err(SolverError::SingularContactSystem {
                t_s: t_end,
                points: act.clone(),
                pivot: e.pivot,
            });
        }
        solver.form_inverse();
        self.factors.updated.set(act, solver.inverse(), &entry);
        Ok(())
    }

    /// The right-hand side of the kept inverse's points (slot order) into
    /// `rhs_slots` and its solution into `rhs`.
    fn solve_by_updated(&mut self) {
        let s = &mut self.scratch;
        let inv = &self.factors.updated;
        for (a, &i) in inv.points().iter().enumerate() {
            s.large.rhs_slots[2 * a] = s.re[i] - s.uh[i];
            s.large.rhs_slots[2 * a + 1] = s.rde[i] - s.vh[i];
        }
        inv.solve_on(&s.large.rhs_slots, &mut s.rhs, &self.threads);
    }

    /// The componentwise backward error of the last [`Self::solve_by_updated`].
    fn updated_backward_error(&self) -> f64 {
        let (s, inv) = (&self.scratch, &self.factors.updated);
        inv.backward_error_on(&s.large.rhs_slots, &s.rhs, &self.threads)
    }

    /// The sub-step solve of a large compliant active set by GMRES (after
    /// `predict` over the sub-step table): the forces into `q1`, `q2` and
    /// the end values into `ue`, `ve`. `false`, with only scratch values
    /// changed, when GMRES did not converge or a point's own block is
    /// singular: the direct solve follows.
    pub(super) fn solve_sub_iterative(&mut self) -> bool {
        if !self.scratch.projected_all {
            self.project_active_rows();
        }
        let (tb, act, s) = (&self.tables, &self.state.active, &mut self.scratch);
        let (n, p, ns) = (act.len(), tb.p, tb.basis.stored_states());
        let rate = SQRT3 / s.sub.tau_s;
        // the sub-step's four weights, each contiguous over the states
        let wq = s.sub.weight_columns(ns);
        // each point's own 2 x 2 block (end value, slope) x (q1, q2), inverted
        for (a, &i) in act.iter().enumerate() {
            let mut g = own_block(&tb.own_terms[i * ns..(i + 1) * ns], wq);
            let c = if tb.residual.is_empty() {
                0.0
            } else {
                tb.residual[i * p + i]
            };
            let kc = 1.0 / tb.tread_k_n_m[i] + c;
            g[0] += -GB * kc;
            g[1] += GA * kc;
            g[2] += -rate * kc;
            g[3] += rate * kc;
            let det = g[0] * g[3] - g[1] * g[2];
            if !(det.is_finite() && det != 0.0) {
                return false;
            }
            s.large.jacobi[a] = [g[3] / det, -g[1] / det, -g[2] / det, g[0] / det];
        }
        // the preconditioned right-hand side; unknowns and equations
        // interleaved per point: (q1, q2) and (end value, slope)
        for (a, &i) in act.iter().enumerate() {
            let (bx, bv) = (s.re[i] - s.uh[i], s.rde[i] - s.vh[i]);
            let z = s.large.jacobi[a];
            s.large.rhs_slots[2 * a] = z[0] * bx + z[1] * bv;
            s.large.rhs_slots[2 * a + 1] = z[2] * bx + z[3] * bv;
        }
        let jacobi = &s.large.jacobi[..n];
        let residual = &tb.residual;
        let tread = &tb.tread_k_n_m;
        let (state, sub, basis) = (&mut *s.delta, &s.sub, &tb.basis);
        let (gq1, gq2) = (&mut s.large.gq1, &mut s.large.gq2);
        let (ex, ev) = (&mut s.du[..n], &mut s.dv[..n]);
        let apply = |z: &[f64], y: &mut [f64]| {
            // the forces into the states over the sub-step (their response
            // at its end, method §3.3), then out to the active points: the
            // step's own kernels
            for (a, &j) in act.iter().enumerate() {
                (gq1[j], gq2[j]) = (z[2 * a], z[2 * a + 1]);
            }
            state.x.fill(0.0);
            state.v.fill(0.0);
            state.add_gauss_forces(basis, sub, act, gq1, gq2);
            state.project_rows_packed(basis, act, ex, ev);
            for (a, &i) in act.iter().enumerate() {
                let (mut ex, mut ev) = (ex[a], ev[a]);
                let (q1, q2) = (z[2 * a], z[2 * a + 1]);
                // the tread's compliance on the point's own forces, the
                // residual compliance on every active point's
                let kt = 1.0 / tread[i];
                ex += kt * (-GB * q1 + GA * q2);
                ev += kt * rate * (q2 - q1);
                if !residual.is_empty() {
                    for (b, &j) in act.iter().enumerate() {
                        let (c, r1, r2) = (residual[i * p + j], z[2 * b], z[2 * b + 1]);
                        ex += c * (-GB * r1 + GA * r2);
                        ev += c * rate * (r2 - r1);
                    }
                }
                let m = jacobi[a];
                y[2 * a] = m[0] * ex + m[1] * ev;
                y[2 * a + 1] = m[2] * ex + m[3] * ev;
            }
        };
        // from the block-diagonal solution
        let x = &mut s.rhs[..2 * n];
        x.copy_from_slice(&s.large.rhs_slots[..2 * n]);
        let outcome = s.large.gmres.solve(
            2 * n,
            apply,
            &s.large.rhs_slots[..2 * n],
            x,
            GMRES_TOLERANCE,
            GMRES_MAX_APPLICATIONS,
        );
        self.state.stats.krylov_applications += outcome.applications as u64;
        if !outcome.converged {
            self.state.stats.krylov_fallbacks += 1;
            return false;
        }
        let s = &mut self.scratch;
        for (a, &j) in self.state.active.iter().enumerate() {
            s.q1[j] = s.rhs[2 * a];
            s.q2[j] = s.rhs[2 * a + 1];
        }
        self.end_values_sub();
        true
    }
}

/// A point's own 2 × 2 block of the sub-step system without the tread,
/// `g_m = Σ_s a_s[i] b_s[i] w_m(s)` for the weights `w_m` (end value by
/// `q1`, by `q2`, slope by `q1`, by `q2`), over the point's terms
/// `ab = a_s[i] b_s[i]` ([`SimTables::own_terms`](super::parts::SimTables),
/// a whole number of 4-wide lanes): four lanes per sum, run in AVX2 lanes
/// where the CPU has them (the same operations in the same order: the same
/// bits).
fn own_block(ab: &[f64], w: [&[f64]; 4]) -> [f64; 4] {
    #[cfg(target_arch = "x86_64")]
    {
        if std::arch::is_x86_feature_detected!("avx2") {
            #[target_feature(enable = "avx2")]
            fn wide(ab: &[f64], w: [&[f64]; 4]) -> [f64; 4] {
                own_block_body(ab, w)
            }
            // SAFETY: the CPU supports AVX2 (checked just above).
            return unsafe { wide(ab, w) };
        }
    }
    own_block_body(ab, w)
}

/// [`own_block`]'s sums: lane `k` adds the states `s ≡ k (mod 4)` in
/// order, then `(l0 + l1) + (l2 + l3)`.
#[inline(always)]
fn own_block_body(ab: &[f64], w: [&[f64]; 4]) -> [f64; 4] {
    const L: usize = 4;
    let mut acc = [[0.0f64; L]; 4];
    let lanes = ab.chunks_exact(L);
    let tail = lanes.remainder();
    for (c, t) in lanes.enumerate() {
        for (a, wm) in acc.iter_mut().zip(w) {
            let wm = &wm[c * L..c * L + L];
            for k in 0..L {
                a[k] += t[k] * wm[k];
            }
        }
    }
    // (stored states come in whole lanes: no tail, but a short one is summed)
    let start = ab.len() - tail.len();
    std::array::from_fn(|m| {
        let a = acc[m];
        let mut g = (a[0] + a[1]) + (a[2] + a[3]);
        for (c, t) in tail.iter().enumerate() {
            g += t * w[m][start + c];
        }
        g
    })
}

/// The full-step compliant system's entry of equation `r` (0: end value,
/// 1: slope) of point `i` and unknown `c` (0: `q1`, 1: `q2`) of point `j`
/// (method §4.6): the influence blocks plus, on a point's own block, the
/// tread compliance.
fn full_entry(tb: &super::parts::SimTables) -> impl Fn(usize, usize, usize, usize) -> f64 + '_ {
    let g = &tb.full_inf;
    let blocks = [&g.gx1, &g.gx2, &g.gv1, &g.gv2];
    let rate = SQRT3 / tb.dt_s;
    let diag = [[-GB, GA], [-rate, rate]];
    let (p, kk) = (tb.p, &tb.tread_k_n_m);
    move |i, r, j, c| {
        let a = blocks[2 * r + c][i * p + j];
        if i == j && !kk.is_empty() {
            a + diag[r][c] / kk[i]
        } else {
            a
        }
    }
}

#[cfg(test)]
mod tests {
    use super::full_entry;
    use crate::Simulation;
    use crate::solver::simulation::contact::DenseSolver;
    use crate::solver::simulation::contact::bordered::BorderedInverse;
    use rand_chacha::ChaCha8Rng;
    use rand_chacha::rand_core::{RngCore, SeedableRng};

    /// The entry-wise backward error of `M x = b` for `points` (slot
    /// order): each equation's sum over [`full_entry`], term by term.
    fn entry_wise(sim: &Simulation, points: &[usize], b: &[f64], x: &[f64]) -> f64 {
        let entry = full_entry(&sim.tables);
        let mut worst = 0.0f64;
        for (a, &i) in points.iter().enumerate() {
            for r in 0..2 {
                let (mut s, mut mag) = (0.0, b[2 * a + r].abs());
                for (c, &j) in points.iter().enumerate() {
                    for u in 0..2 {
                        let t = entry(i, r, j, u) * x[2 * c + u];
                        s += t;
                        mag += t.abs();
                    }
                }
                let res = (b[2 * a + r] - s).abs();
                worst = worst.max(if res > 0.0 { res / mag } else { 0.0 });
            }
        }
        worst
    }

    /// The kept inverse's backward error, read from the system it keeps
    /// beside the inverse (set, then bordered and shrunk with each join and
    /// leave), is the entry-wise one of the full-step tread-spring system to
    /// round-off, `4 (2|S| + 1) ε`: over 400 random joins and leaves of 9
    /// points, solutions from 1e-6 to 1e6 and right-hand sides from exact
    /// (an error of round-off) to far off (an error near 1). A kept system
    /// that missed a move, a row or a column fails it.
    #[test]
    fn the_kept_systems_backward_error_is_the_entry_wise_one() {
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        let mut unit = move || (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        let p = 9;
        let points: Vec<String> = (0..p)
            .map(|i| format!("Point(x_m: {:.3}, h_m: -0.0005)", 0.01 * i as f64))
            .collect();
        let modes: Vec<String> = (0..5)
            .map(|m| {
                let phi: Vec<f64> = (0..p).map(|_| unit() - 0.5).collect();
                let rows: Vec<String> = (0..p)
                    .map(|i| {
                        let row: Vec<String> =
                            (0..p).map(|j| format!("{:e}", phi[i] * phi[j])).collect();
                        format!("[{}]", row.join(", "))
                    })
                    .collect();
                format!(
                    "Mode(freq_hz: {}, damping_ratio: 0.05, residue: [{}])",
                    80.0 + 130.0 * m as f64,
                    rows.join(", ")
                )
            })
            .collect();
        let text = format!(
            "Scene(name: \"b\", tyre: Modal(modes: [{}]), points: [{}],
              road: Sine(amplitude_m: 0.0001, wavelength_m: 0.3), speed_mps: 15.0,
              dt_s: 1e-5, duration_s: 0.001, contact: Compliant(stiffness_n_m: [75000.0]))",
            modes.join(", "),
            points.join(", ")
        );
        let sim = Simulation::new(
            &crate::solver::test_problem::problem(&text),
            crate::SolverOptions::default(),
        )
        .unwrap();
        let entry = full_entry(&sim.tables);
        let mut inv = BorderedInverse::new(p);
        // a start from a factorisation (as a refused update's): four points
        let first = [4usize, 1, 7, 2];
        let mut solver = DenseSolver::new(2 * p);
        solver
            .factor(8, |e, u| entry(first[e / 2], e % 2, first[u / 2], u % 2))
            .unwrap();
        solver.form_inverse();
        inv.set(&first, solver.inverse(), &entry);
        let (mut small, mut large) = (0, 0);
        for case in 0..400 {
            let set = inv.points().to_vec();
            let join = set.is_empty() || (set.len() < p && unit() < 0.55);
            if join {
                let out: Vec<usize> = (0..p).filter(|i| !set.contains(i)).collect();
                let pick = out[((unit() * out.len() as f64) as usize).min(out.len() - 1)];
                assert!(inv.join(pick, &entry), "case {case}: join {pick}");
            } else {
                let k = ((unit() * set.len() as f64) as usize).min(set.len() - 1);
                assert!(inv.leave(k), "case {case}: leave slot {k}");
            }
            let set = inv.points().to_vec();
            let n = set.len();
            if n == 0 {
                continue;
            }
            let scale = 10f64.powf(12.0 * unit() - 6.0);
            let x: Vec<f64> = (0..2 * n).map(|_| (unit() - 0.5) * scale).collect();
            let off = [0.0, 1e-12, 1e-6, 1.0][case % 4];
            let b: Vec<f64> = (0..2 * n)
                .map(|e| {
                    let (i, r) = (set[e / 2], e % 2);
                    let mx: f64 = (0..2 * n)
                        .map(|u| entry(i, r, set[u / 2], u % 2) * x[u])
                        .sum();
                    mx * (1.0 + off * (unit() - 0.5))
                })
                .collect();
            let kept = inv.backward_error(&b, &x);
            let plain = entry_wise(&sim, &set, &b, &x);
            let tol = 4.0 * (2 * n + 1) as f64 * f64::EPSILON;
            assert!(
                (kept - plain).abs() <= tol * (1.0 + plain),
                "case {case}, set {set:?}, scale {scale:e}, offset {off:e}: {kept:e} against {plain:e}"
            );
            if plain < 1e-13 {
                small += 1;
            } else if plain > 1e-8 {
                large += 1;
            }
        }
        // both regimes were met: round-off errors and far-off solutions
        assert!(small > 50 && large > 50, "{small} small, {large} large");
    }
}
