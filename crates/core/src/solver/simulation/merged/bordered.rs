//! The merged solve through the trial's factorisation or kept inverse,
//! bordered by the step's events (method §4.6, "Events in one solve"):
//! `O(|S|²)` per border unknown instead of a new factorisation.

use super::super::contact::DenseSolver;
use super::super::contact::bordered::BorderedInverse;
use super::super::{GA, GB, SQRT3, Simulation};
use super::Border;

/// What solves the trial's full-step system in the bordered merged solve:
/// its factorisation (`2n` unknowns, the `q1` then the `q2`) or the kept
/// inverse of a large set (slot `a`: `q1`, `q2` of its point `a`).
enum TrialSolver<'a> {
    Factored(&'a DenseSolver),
    Kept(&'a BorderedInverse, &'a mut Vec<f64>),
}

impl TrialSolver<'_> {
    /// `z ← A⁻¹ e_u` (`u`: unknown `c n + k` in the factorisation's
    /// layout, `c` of trial entry `k`): through the kept inverse the
    /// column itself (`O(n)`, the entries a solve would sum with zeros),
    /// through a factorisation a solve.
    fn unit(&mut self, c: usize, k: usize, z: &mut [f64]) {
        let n = z.len() / 2;
        match self {
            TrialSolver::Factored(solver) => {
                z.fill(0.0);
                z[c * n + k] = 1.0;
                solver.solve(z);
            }
            TrialSolver::Kept(inv, _) => {
                let col = 2 * k + c;
                for a in 0..n {
                    (z[a], z[n + a]) = (
                        inv.inverse_entry(2 * a, col),
                        inv.inverse_entry(2 * a + 1, col),
                    );
                }
            }
        }
    }

    /// `z ← A⁻¹ z` with `z` in the factorisation's layout (`2n` values).
    fn solve(&mut self, z: &mut [f64]) {
        match self {
            TrialSolver::Factored(solver) => solver.solve(z),
            TrialSolver::Kept(inv, slots) => {
                let n = z.len() / 2;
                let (b, x) = slots.split_at_mut(2 * n);
                for a in 0..n {
                    (b[2 * a], b[2 * a + 1]) = (z[a], z[n + a]);
                }
                inv.solve(b, &mut x[..2 * n]);
                for a in 0..n {
                    (z[a], z[n + a]) = (x[2 * a], x[2 * a + 1]);
                }
            }
        }
    }
}

impl Simulation {
    /// [`Simulation::merged_solve`] through the trial's factorisation
    /// `A` of the trial set, bordered by the points that left it and the
    /// late ones (`O(|S|²)` per border unknown instead of a new
    /// factorisation): `x = A⁻¹(b − B y)` with `(D − R A⁻¹ B) y = d − R A⁻¹ b`.
    pub(super) fn merged_solve_bordered(&mut self) -> bool {
        let p = self.tables.p;
        let (tb, st, s) = (&self.tables, &mut self.state, &mut self.scratch);
        let m = &mut s.merged;
        let trial_solver = if m.trial_kept {
            TrialSolver::Kept(&self.factors.updated, &mut m.slots)
        } else {
            TrialSolver::Factored(&self.factors.current.solver)
        };
        let mut solver = trial_solver;
        let trial = &m.trial_set;
        let n0 = trial.len();
        let big_n = 2 * n0;
        let nb = 2 * m.border.len();
        let g = &tb.full_inf;
        let blocks = [&g.gx1, &g.gx2, &g.gv1, &g.gv2];
        let units = [&m.unit_x, &m.unit_v];
        // the border columns B and their A⁻¹ B (those of earlier solves
        // of the step kept)
        for (b, border) in m.border.iter().enumerate().skip(m.z_done) {
            for c in 0..2 {
                let z = &mut m.z[(2 * b + c) * big_n..(2 * b + c + 1) * big_n];
                match *border {
                    Border::Left(k) => {
                        solver.unit(c, k, z);
                        // (debug builds: the column is what a solve gives)
                        #[cfg(debug_assertions)]
                        {
                            let e = &mut m.rhs[..big_n];
                            e.fill(0.0);
                            e[c * n0 + k] = 1.0;
                            solver.solve(e);
                            // (a zero's sign aside; a solve would spread a
                            // NaN or an infinity of the inverse's row)
                            debug_assert!(
                                e.iter().zip(z.iter()).all(|(a, b)| a == b && a.is_finite())
                            );
                        }
                    }
                    Border::Late(l, _) => {
                        let slot = 2 * l + c;
                        for (r, &a) in trial.iter().enumerate() {
                            z[r] = units[0][slot * p + a];
                            z[n0 + r] = units[1][slot * p + a];
                        }
                        if big_n > 0 {
                            solver.solve(z);
                        }
                    }
                }
            }
        }
        m.z_done = m.border.len();
        // A⁻¹ b: the kept inverse's trial solution while the known loads
        // are zero (`b` is then the trial's right-hand side, `re - uh`)
        if m.trial_kept && m.known_clear {
            m.z0[..big_n].copy_from_slice(&m.trial_x[..big_n]);
            // (debug builds: the same numbers as the solve)
            #[cfg(debug_assertions)]
            {
                let b = &mut m.rhs[..big_n];
                for (r, &a) in trial.iter().enumerate() {
                    b[r] = s.re[a] - s.uh[a] - m.known_x[a];
                    b[n0 + r] = s.rde[a] - s.vh[a] - m.known_v[a];
                }
                solver.solve(b);
                debug_assert!(
                    b.iter()
                        .zip(&m.z0[..big_n])
                        .all(|(x, y)| x.to_bits() == y.to_bits())
                );
            }
        } else {
            for (r, &a) in trial.iter().enumerate() {
                m.z0[r] = s.re[a] - s.uh[a] - m.known_x[a];
                m.z0[n0 + r] = s.rde[a] - s.vh[a] - m.known_v[a];
            }
            if big_n > 0 {
                solver.solve(&mut m.z0[..big_n]);
            }
        }
        // the border rows R against x (`R z` for a column `z`), D, and d
        let row_dot = |border: Border, rho: usize, z: &[f64]| -> f64 {
            match border {
                Border::Left(k) => z[rho * n0 + k],
                Border::Late(_, i) => {
                    let mut sum = 0.0;
                    for (c, &b) in trial.iter().enumerate() {
                        sum += blocks[2 * rho][i * p + b] * z[c]
                            + blocks[2 * rho + 1][i * p + b] * z[n0 + c];
                    }
                    sum
                }
            }
        };
        let (border, z, z0, kk) = (&m.border, &m.z, &m.z0, &tb.tread_k_n_m);
        let late_tau = &m.late_tau_s;
        let entry = |r: usize, c: usize| -> f64 {
            let (rb, rho) = (border[r / 2], r % 2);
            let (cb, cc) = (border[c / 2], c % 2);
            let d = match (rb, cb) {
                (Border::Late(_, i), Border::Late(l2, j)) => {
                    let mut x = units[rho][(2 * l2 + cc) * p + i];
                    if i == j {
                        let rate = SQRT3 / late_tau[l2];
                        let diag = [[-GB, GA], [-rate, rate]];
                        x += diag[rho][cc] / kk[i];
                    }
                    x
                }
                _ => 0.0,
            };
            d - row_dot(rb, rho, &z[c * big_n..(c + 1) * big_n])
        };
        st.stats.factorisations += 1;
        if m.schur.factor(nb, entry).is_err() {
            return false;
        }
        for (b, &br) in border.iter().enumerate() {
            for rho in 0..2 {
                let d = match br {
                    Border::Left(_) => 0.0,
                    Border::Late(_, i) => {
                        if rho == 0 {
                            s.re[i] - s.uh[i] - m.known_x[i]
                        } else {
                            s.rde[i] - s.vh[i] - m.known_v[i]
                        }
                    }
                };
                m.y[2 * b + rho] = d - row_dot(br, rho, &z0[..big_n]);
            }
        }
        m.schur.solve(&mut m.y[..nb]);
        // x = A⁻¹ b − A⁻¹ B y
        for (k, &a) in trial.iter().enumerate() {
            let (mut x1, mut x2) = (z0[k], z0[n0 + k]);
            for (c, y) in m.y[..nb].iter().enumerate() {
                x1 -= z[c * big_n + k] * y;
                x2 -= z[c * big_n + n0 + k] * y;
            }
            (s.q1[a], s.q2[a]) = (x1, x2);
        }
        for (b, &br) in border.iter().enumerate() {
            if let Border::Late(_, i) = br {
                (s.q1[i], s.q2[i]) = (m.y[2 * b], m.y[2 * b + 1]);
            }
        }
        self.merged_end_values();
        true
    }
}
