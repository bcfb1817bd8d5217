//! The steady step of the `Located` scheme (SPEC §4): most steps of a
//! rolling tyre keep the same points on the road and locate no event. Such
//! a step is the first trial of [`Simulation::located_step`] accepted as it
//! is: one free prediction, one solve with the reused factorisation, the
//! release and landing checks, the commit. This path takes it without the
//! event loop's bookkeeping and hands any step with an event, before it has
//! changed anything but scratch values, to the event loop, which then runs
//! the same trial again. Both give bit-identical results (tested).

use super::{GA, GB, Simulation, Table, first_crossing};
use crate::error::SolverError;
use crate::scene::ContactScheme;

impl Simulation {
    /// Whether the next step may take [`Simulation::steady_step`]: the
    /// located scheme with rigid contact, the last step had no event (so the
    /// active set is the contact set, `released` and the impact impulses are
    /// clear), and the active set is the one whose full-step factorisation
    /// is kept, on a road without breakpoints under it.
    #[inline]
    pub(super) fn steady_ready(&self) -> bool {
        let n = self.active.len();
        !self.had_event
            && self.options.steady_path
            && self.options.reuse_factorisation
            && self.scene.contact_scheme == ContactScheme::Located
            && self.tread_k_n_m.is_empty()
            && (n == 0
                || (self.full_factored
                    && !self.road.has_kinks()
                    && self.full_set.len() == n
                    && self.full_set.iter().zip(&self.active).all(|(a, b)| a == b)))
    }

    /// The step from `t0` when it has no event: `Some(solves)` once
    /// committed; `None`, with only scratch values changed, when a point
    /// starts below the road, a force would end pulling, or a free point
    /// lands inside the step.
    pub(super) fn steady_step(&mut self, t0: f64) -> Result<Option<u32>, SolverError> {
        let p = self.p;
        let dt = self.dt_s;
        self.predict(t0, dt, Table::Full)?;
        let n = self.active.len();
        if n > 0 {
            let (re, rde) = (&self.re[..p], &self.rde[..p]);
            let (uh, vh) = (&self.uh[..p], &self.vh[..p]);
            let (rx, rv) = self.rhs[..2 * n].split_at_mut(n);
            for (k, &i) in self.active.iter().enumerate() {
                rx[k] = re[i] - uh[i];
                rv[k] = rde[i] - vh[i];
            }
            self.full_solver.solve_by_inverse(&mut self.rhs[..2 * n]);
            let (q1, q2) = (&mut self.q1[..p], &mut self.q2[..p]);
            for (k, &j) in self.active.iter().enumerate() {
                q1[j] = self.rhs[k];
                q2[j] = self.rhs[n + k];
                // a force ending negative or pulling on average: a release
                let (qs, qe) = (GA * q1[j] - GB * q2[j], -GB * q1[j] + GA * q2[j]);
                if qe < 0.0 || qs + qe < 0.0 {
                    return Ok(None);
                }
            }
        }
        if n > 0 {
            self.end_values_solved();
        } else {
            // no force: the end values are the free ones, which nothing reads
            // again before the next prediction rewrites them
            std::mem::swap(&mut self.ue, &mut self.uh);
            std::mem::swap(&mut self.ve, &mut self.vh);
        }
        // a free point left below the road (a live road or speed change)
        // lands at the step start, one that would cross it inside the step
        // lands there: both are events
        let (u, v, r, rd) = (&self.u[..p], &self.v[..p], &self.r[..p], &self.rd[..p]);
        let (ue, ve, re, rde) = (&self.ue[..p], &self.ve[..p], &self.re[..p], &self.rde[..p]);
        let tol = self.pen_tol_m;
        // (two plain loops: as a closure the check was not inlined, +10 %
        // instructions per step)
        if n > 0 {
            for &i in &self.full_free {
                if lands(
                    u[i] - r[i],
                    v[i] - rd[i],
                    ue[i] - re[i],
                    ve[i] - rde[i],
                    dt,
                    tol,
                ) {
                    return Ok(None);
                }
            }
        } else {
            // (every point free: indices the compiler sees in range)
            for i in 0..p {
                if lands(
                    u[i] - r[i],
                    v[i] - rd[i],
                    ue[i] - re[i],
                    ve[i] - rde[i],
                    dt,
                    tol,
                ) {
                    return Ok(None);
                }
            }
        }
        self.commit(dt, Table::Full);
        Ok(Some((n > 0) as u32))
    }
}

/// Whether a free point with gap `g0`, gap rate `d0` at the step start and
/// `g1`, `d1` at its end is below the road at the start or lands inside the
/// step ([`first_crossing`] of the Hermite cubic).
#[inline(always)]
fn lands(g0: f64, d0: f64, g1: f64, d1: f64, dt: f64, tol: f64) -> bool {
    g0 < -tol || first_crossing(g0, d0 * dt, g1, d1 * dt, tol, false).is_some()
}
