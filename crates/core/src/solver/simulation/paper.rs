//! The paper's contact rule (method §4 steps 1-5): active set from the free
//! prediction, monotone releases, at most `2P` solves.

use super::{Simulation, Table};
use crate::solver::error::SolverError;

impl Simulation {
    /// The paper's step (method §4 steps 1-5) over `[t, t + tau]`: candidates from
    /// the free prediction, release of the most negative mean force, points
    /// pushed below the road by a neighbour added, a released point never
    /// re-added, at most `2P` solves.
    pub(super) fn paper_substep(
        &mut self,
        t: f64,
        tau: f64,
        sel: Table,
    ) -> Result<u32, SolverError> {
        self.predict(t, tau, sel)?;
        self.state.active.clear();
        for i in 0..self.tables.p {
            if self.scratch.uh[i] - self.scratch.re[i] < 0.0 && !self.state.released[i] {
                self.state.active.push(i);
            }
        }
        let mut solves = 0u32;
        loop {
            self.solve_active(t + tau, sel)?;
            solves += !self.state.active.is_empty() as u32;
            if solves as usize >= 2 * self.tables.p {
                break;
            }
            // most negative step-mean force
            let worst = self
                .state
                .active
                .iter()
                .enumerate()
                .map(|(k, &j)| (k, self.scratch.q1[j] + self.scratch.q2[j]))
                .filter(|&(_, m)| m < 0.0)
                .min_by(|a, b| a.1.total_cmp(&b.1));
            if let Some((k, _)) = worst {
                let j = self.state.active.remove(k);
                self.state.released[j] = true;
                continue;
            }
            // a neighbour's force pushed a free point below the road
            let deepest = (0..self.tables.p)
                .filter(|&i| !self.state.released[i] && !self.state.active.contains(&i))
                .map(|i| (i, self.scratch.ue[i] - self.scratch.re[i]))
                .filter(|&(_, g)| g < -self.pen_tol_m)
                .min_by(|a, b| a.1.total_cmp(&b.1));
            match deepest {
                Some((i, _)) => self.state.active.push(i),
                None => break,
            }
        }
        // At the solve bound, a point still pulling is let go (its force
        // zeroed): the forces stay non-negative, any penetration is reported.
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
