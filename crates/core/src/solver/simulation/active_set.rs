//! The step-end rule over `[t, t + τ]` (method §4.3 steps 2-4, and its
//! compliant form, method §4.6): the active set from the free prediction,
//! the most negative step-mean force released and not re-added in the
//! step, the free point deepest into the road under its neighbours' forces
//! added, at most `2P` solves, and at that bound a point still pulling let
//! go. The paper's scheme (`paper.rs`) and the compliant rule that ends a
//! cascade of events (`compliant.rs`) run this one loop; they differ in
//! their entry tests and their solve ([`ActiveSetRule`]).

use super::{Simulation, Table};
use crate::solver::error::SolverError;

/// What a contact scheme's step-end rule sets in the loop of
/// [`Simulation::step_end_rule`]: which points enter the active set, which
/// may leave it, and the solve of the set.
pub(super) trait ActiveSetRule {
    /// Among free points equally deep into the road, the first in point
    /// order joins (`true`) or the last (`false`).
    const FIRST_OF_EQUALLY_DEEP: bool;

    /// The active set the loop starts from, into `state.active` (in point
    /// order), from the free prediction over the (sub-)step.
    fn start_set(sim: &mut Simulation);

    /// Whether an active point with Gauss-point forces `q1`, `q2` (N) may
    /// be released when its step-mean force pulls.
    fn may_release(q1: f64, q2: f64) -> bool;

    /// The Gauss-point solve of the active set over `sel` ending at
    /// `t_end` (s): the forces into `q1`, `q2`, the end values of every
    /// point into `ue`, `ve`.
    fn solve(sim: &mut Simulation, t_end: f64, sel: Table) -> Result<(), SolverError>;
}

impl Simulation {
    /// The step-end rule of `R` over `[t, t + tau]` (method §4.3 steps
    /// 1-5): predict, start from `R`'s active set, then solve and, while
    /// fewer than `2P` solves ran, release the point with the most negative
    /// step-mean force `(q1 + q2)/2` among those `R` lets go, or else add
    /// the free point (not released in this step) deepest into the road,
    /// `r_e - u_e` beyond the penetration tolerance; stop when neither
    /// applies. A point still pulling then is let go and the (sub-)step
    /// committed. Returns the number of solves.
    pub(super) fn step_end_rule<R: ActiveSetRule>(
        &mut self,
        t: f64,
        tau: f64,
        sel: Table,
    ) -> Result<u32, SolverError> {
        self.predict(t, tau, sel)?;
        R::start_set(self);
        let mut solves = 0u32;
        loop {
            R::solve(self, t + tau, sel)?;
            solves += !self.state.active.is_empty() as u32;
            if solves as usize >= 2 * self.tables.p {
                break;
            }
            // released: the most negative step-mean force
            let (q1, q2) = (&self.scratch.q1, &self.scratch.q2);
            let worst = self
                .state
                .active
                .iter()
                .enumerate()
                .filter(|&(_, &j)| R::may_release(q1[j], q2[j]))
                .map(|(k, &j)| (k, q1[j] + q2[j]))
                .filter(|&(_, q)| q < 0.0)
                .min_by(|a, b| a.1.total_cmp(&b.1));
            if let Some((k, _)) = worst {
                let j = self.state.active.remove(k);
                self.state.released[j] = true;
                continue;
            }
            // added: a free point its neighbours' forces pushed into the road
            let (st, s) = (&self.state, &self.scratch);
            let depths = (0..self.tables.p)
                .filter(|&i| !st.released[i] && !st.active.contains(&i))
                .map(|i| (i, s.re[i] - s.ue[i]))
                .filter(|&(_, d)| d > self.pen_tol_m);
            let deepest = if R::FIRST_OF_EQUALLY_DEEP {
                depths.min_by(|a, b| b.1.total_cmp(&a.1))
            } else {
                depths.max_by(|a, b| a.1.total_cmp(&b.1))
            };
            match deepest {
                Some((i, _)) => self.state.active.push(i),
                None => break,
            }
        }
        self.let_go_pulling(sel);
        self.commit(tau, sel);
        Ok(solves)
    }

    /// At the solve bound, a point still pulling on average is let go (its
    /// force zeroed) and the end values are solved again: the forces stay
    /// non-negative, any penetration is reported.
    pub(super) fn let_go_pulling(&mut self, sel: Table) {
        if self
            .state
            .active
            .iter()
            .any(|&j| self.scratch.q1[j] + self.scratch.q2[j] < 0.0)
        {
            let (q1, q2) = (&mut self.scratch.q1, &mut self.scratch.q2);
            self.state.active.retain(|&j| {
                let keep = q1[j] + q2[j] >= 0.0;
                if !keep {
                    (q1[j], q2[j]) = (0.0, 0.0);
                }
                keep
            });
            self.end_values_sub_or_full(sel);
        }
    }
}
