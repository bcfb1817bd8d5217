//! The paper's contact rule (method §4.3 steps 1-5): the active set from
//! the free prediction, monotone releases, at most `2P` solves, in the loop
//! of `active_set.rs`.

use super::active_set::ActiveSetRule;
use super::{Simulation, Table};
use crate::solver::error::SolverError;

/// The paper's rule for rigid contact (method §4.3): a point enters where
/// its free prediction ends below the road, unless released in this step;
/// a point pulling on average may leave; the rigid Gauss-point solve.
pub(super) struct PaperRule;

impl ActiveSetRule for PaperRule {
    const FIRST_OF_EQUALLY_DEEP: bool = true;

    fn start_set(sim: &mut Simulation) {
        // every point's free prediction: a large set's fused prediction
        // projected the active rows only
        sim.ensure_projected_all();
        let (st, s) = (&mut sim.state, &sim.scratch);
        st.active.clear();
        for i in 0..sim.tables.p {
            if s.uh[i] - s.re[i] < 0.0 && !st.released[i] {
                st.active.push(i);
            }
        }
    }

    #[inline]
    fn may_release(_q1: f64, _q2: f64) -> bool {
        true
    }

    fn solve(sim: &mut Simulation, t_end: f64, sel: Table) -> Result<(), SolverError> {
        // (through `solve_contact`: a large set's solve forms the end
        // state, and a later solve of a smaller set in the same step must
        // not leave `commit` that stale one)
        sim.solve_contact(t_end, sel)
    }
}

impl Simulation {
    /// The paper's step (method §4.3 steps 1-5) over `[t, t + tau]`:
    /// candidates from the free prediction, release of the most negative
    /// mean force, points pushed below the road by a neighbour added, a
    /// released point never re-added, at most `2P` solves; at that bound a
    /// point still pulling is let go (its force zeroed), so the forces stay
    /// non-negative and any penetration is reported. Returns the solves.
    pub(super) fn paper_substep(
        &mut self,
        t: f64,
        tau: f64,
        sel: Table,
    ) -> Result<u32, SolverError> {
        self.step_end_rule::<PaperRule>(t, tau, sel)
    }
}
