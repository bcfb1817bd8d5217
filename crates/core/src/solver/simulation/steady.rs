//! The steady step of the `Located` scheme (method §4): most steps of a
//! rolling tyre keep the same points on the road and locate no event. Such
//! a step is the first trial of [`Simulation::located_step`] accepted as it
//! is: one free prediction, one solve with the reused factorisation, the
//! release and landing checks, the commit. This path takes it without the
//! event loop's bookkeeping and hands any step with an event, before it has
//! changed anything but scratch values, to the event loop, which then runs
//! the same trial again. Both give bit-identical results (tested).

use super::{GA, GB, Simulation, Table, crosses};
use crate::solver::error::SolverError;
use crate::solver::problem::ContactScheme;

impl Simulation {
    /// Whether the next step may take [`Simulation::steady_step`]: the
    /// located scheme with rigid contact, the last step had no event (so the
    /// active set is the contact set, `released` and the impact impulses are
    /// clear), and the active set is the one whose full-step factorisation
    /// is kept, on a road without breakpoints under it.
    #[inline]
    pub(super) fn steady_ready(&self) -> bool {
        let n = self.state.active.len();
        !self.state.had_event
            && self.tables.options.steady_path
            && self.tables.options.reuse_factorisation
            && self.problem.contact_scheme == ContactScheme::Located
            && self.tables.tread_k_n_m.is_empty()
            && (n == 0 || (!self.road.has_kinks() && self.factors.holds(&self.state.active)))
    }

    /// The step from `t0` when it has no event: the stages of `stages.rs`
    /// over the full step (predict; solve by the kept inverse; the release
    /// and landing checks; commit). `Some(solves)` once committed; `None`,
    /// with only scratch values changed, when a point starts below the road,
    /// a force would end pulling, or a free point lands inside the step.
    pub(super) fn steady_step(&mut self, t0: f64) -> Result<Option<u32>, SolverError> {
        let p = self.tables.p;
        let dt = self.tables.dt_s;
        self.predict(t0, dt, Table::Full)?;
        let n = self.state.active.len();
        if n > 0 {
            // solve (the factorisation of the set is kept: a product)
            let (active, s) = (&self.state.active, &mut self.scratch);
            let (re, rde) = (&s.re[..p], &s.rde[..p]);
            let (uh, vh) = (&s.uh[..p], &s.vh[..p]);
            let (rx, rv) = s.rhs[..2 * n].split_at_mut(n);
            for (k, &i) in active.iter().enumerate() {
                rx[k] = re[i] - uh[i];
                rv[k] = rde[i] - vh[i];
            }
            let solver = &mut self.factors.current.solver;
            solver.solve_by_inverse(&mut s.rhs[..2 * n]);
            let (q1, q2) = (&mut s.q1[..p], &mut s.q2[..p]);
            for (k, &j) in active.iter().enumerate() {
                q1[j] = s.rhs[k];
                q2[j] = s.rhs[n + k];
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
            std::mem::swap(&mut self.scratch.ue, &mut self.scratch.uh);
            std::mem::swap(&mut self.scratch.ve, &mut self.scratch.vh);
        }
        // locate, landings only: a free point left below the road (a live
        // road or speed change) lands at the step start, one that would cross it inside the step
        // lands there: both are events
        let (st, s) = (&self.state, &self.scratch);
        let (u, v, r, rd) = (&st.u[..p], &st.v[..p], &st.r[..p], &st.rd[..p]);
        let (ue, ve, re, rde) = (&s.ue[..p], &s.ve[..p], &s.re[..p], &s.rde[..p]);
        let tol = self.pen_tol_m;
        // Most steps: every free point clearly stays above the road. Checked
        // branch-free over all of them first; only when one is not clear do
        // the exact checks run (`clear` implies `!lands`, so both give the
        // same answer). Two plain loops each: as closures the checks were
        // not inlined (+10 % instructions per step).
        let mut all_clear = true;
        if n > 0 {
            for &i in &self.factors.current.free {
                all_clear &= clear(
                    u[i] - r[i],
                    v[i] - rd[i],
                    ue[i] - re[i],
                    ve[i] - rde[i],
                    dt,
                    tol,
                );
            }
        } else {
            // (every point free: indices the compiler sees in range)
            for i in 0..p {
                all_clear &= clear(
                    u[i] - r[i],
                    v[i] - rd[i],
                    ue[i] - re[i],
                    ve[i] - rde[i],
                    dt,
                    tol,
                );
            }
        }
        if !all_clear {
            let lands_at = |i: usize| {
                lands(
                    u[i] - r[i],
                    v[i] - rd[i],
                    ue[i] - re[i],
                    ve[i] - rde[i],
                    dt,
                    tol,
                )
            };
            let landing = if n > 0 {
                self.factors.current.free.iter().any(|&i| lands_at(i))
            } else {
                (0..p).any(lands_at)
            };
            if landing {
                return Ok(None);
            }
        }
        self.commit(dt, Table::Full);
        Ok(Some((n > 0) as u32))
    }
}

/// Whether a free point with gap `g0`, gap rate `d0` at the step start and
/// `g1`, `d1` at its end certainly neither starts below the road nor lands
/// inside the step, without branches: both end gaps stay above `-tol` by
/// more than the cubic can dip between them (|H10|, |H11| <= 4/27 < 1/4 of
/// the scaled slopes), a stricter form of [`first_crossing`]'s cheap
/// rejection that also covers the start check. `true` implies
/// `!lands(..)`; a NaN gives `false`.
#[inline(always)]
fn clear(g0: f64, d0: f64, g1: f64, d1: f64, dt: f64, tol: f64) -> bool {
    // (the very operations of the cheap rejection: rounding is monotone, so
    // `g - dip >= -tol` implies that rejection's inequalities exactly)
    let dip = 0.25 * ((d0 * dt).abs() + (d1 * dt).abs());
    (g0 - dip >= -tol) & (g1 - dip >= -tol)
}

/// Whether a free point with gap `g0`, gap rate `d0` at the step start and
/// `g1`, `d1` at its end is below the road at the start or lands inside the
/// step ([`first_crossing`] of the Hermite cubic).
#[inline(always)]
fn lands(g0: f64, d0: f64, g1: f64, d1: f64, dt: f64, tol: f64) -> bool {
    g0 < -tol || crosses(g0, d0 * dt, g1, d1 * dt, tol, false)
}

#[cfg(test)]
mod tests {
    use super::{clear, lands};
    use proptest::prelude::*;

    /// Gap-like values: zero, tolerance-sized, millimetres, and NaN.
    fn gap() -> impl Strategy<Value = f64> {
        prop_oneof![Just(0.0), Just(f64::NAN), -1e-9..1e-9f64, -1e-3..1e-3f64,]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(20_000))]
        /// The branch-free pre-check never clears a point the exact check
        /// would land (the steady step relies on it).
        #[test]
        fn clear_implies_no_landing(
            g0 in gap(), g1 in gap(),
            d0 in prop_oneof![Just(0.0), -1.0..1.0f64],
            d1 in prop_oneof![Just(0.0), -1.0..1.0f64],
            dt in prop_oneof![Just(1e-5), 1e-7..1e-3f64],
        ) {
            let tol = 1e-12;
            if clear(g0, d0, g1, d1, dt, tol) {
                prop_assert!(!lands(g0, d0, g1, d1, dt, tol));
            }
        }
    }

    #[test]
    fn clear_is_the_common_case_and_rejects_what_it_must() {
        // clearly above the road, moving apart slowly: clear
        assert!(clear(1e-3, 0.0, 1e-3, 0.0, 1e-5, 1e-12));
        // below the road at the start, or at the end: not clear
        assert!(!clear(-1e-6, 0.0, 1e-3, 0.0, 1e-5, 1e-12));
        assert!(!clear(1e-3, 0.0, -1e-6, 0.0, 1e-5, 1e-12));
        assert!(lands(1e-3, 0.0, -1e-6, 0.0, 1e-5, 1e-12));
        // NaN: left to the exact check
        assert!(!clear(f64::NAN, 0.0, 1e-3, 0.0, 1e-5, 1e-12));
    }
}
