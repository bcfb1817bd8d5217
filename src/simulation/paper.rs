//! The paper's contact rule (method §4 steps 1-5): active set from the free
//! prediction, monotone releases, at most `2P` solves.

use super::{Simulation, Table};
use crate::error::SolverError;

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
        if self.active.iter().any(|&j| self.q1[j] + self.q2[j] < 0.0) {
            let (q1, q2) = (&mut self.q1, &mut self.q2);
            self.active.retain(|&j| {
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
