//! The Gauss-point contact solve (method §4.3 step 3, §4.5): the
//! `2|S| × 2|S|` system of the active points over a full step (factorisation
//! reused while the set holds) or a sub-step, and the end values of every
//! point under the solved forces.

use super::{GA, GB, SQRT3, Simulation, Table};
use crate::solver::error::SolverError;

impl Simulation {
    /// Solves the Gauss-point system of `active` (after `predict`) and the end
    /// displacement/velocity of every point into `ue`, `ve`.
    pub(super) fn solve_active(&mut self, t_end: f64, sel: Table) -> Result<(), SolverError> {
        if sel == Table::Sub {
            self.ensure_projected_all();
        }
        let n = self.state.active.len();
        let p = self.tables.p;
        if n == 0 {
            let s = &mut self.scratch;
            s.ue.copy_from_slice(&s.uh);
            s.ve.copy_from_slice(&s.vh);
            return Ok(());
        }
        if sel == Table::Full && self.fused_full_step() {
            return self.solve_rigid_large(t_end);
        }
        if sel == Table::Sub {
            self.fill_sub_block();
        }
        let reuse_factorisation = self.tables.options.reuse_factorisation;
        // The full-step operator depends only on the active set: its
        // factorisation is reused while the set is unchanged.
        let mut reuse =
            sel == Table::Full && reuse_factorisation && self.factors.holds(&self.state.active);
        if !reuse && sel == Table::Full && self.factors.cache.is_enabled() {
            reuse = self.swap_cached_factorisation();
        }
        if !reuse {
            self.factorise(t_end, sel)?;
        }
        let s = &mut self.scratch;
        let (re, rde, uh, vh) = (&s.re[..p], &s.rde[..p], &s.uh[..p], &s.vh[..p]);
        let (rx, rv) = s.rhs[..2 * n].split_at_mut(n);
        for (k, &i) in self.state.active.iter().enumerate() {
            rx[k] = re[i] - uh[i];
            rv[k] = rde[i] - vh[i];
        }
        match sel {
            Table::Full if reuse_factorisation => self
                .factors
                .current
                .solver
                .solve_by_inverse(&mut s.rhs[..2 * n]),
            Table::Full => self.factors.current.solver.solve(&mut s.rhs[..2 * n]),
            Table::Sub => s.dense.solver.solve(&mut s.rhs[..2 * n]),
        }
        // only the active points' entries of q1, q2 are ever read
        for (k, &j) in self.state.active.iter().enumerate() {
            s.q1[j] = s.rhs[k];
            s.q2[j] = s.rhs[n + k];
        }
        // O(P |S|) with the precomputed full influence; through the states on sub-steps
        match sel {
            // (`current.set` is the active set here: reused or just factored)
            Table::Full => self.end_values_solved(),
            Table::Sub => self.end_values_sub(),
        }
        Ok(())
    }

    /// Factorises the Gauss-point operator of `active` over `sel` (method
    /// §4.5): over the full step from the influence blocks into the current
    /// full-step factorisation (its inverse formed when it is to be reused,
    /// the free points' rows packed); over a sub-step from the blocks of
    /// [`Simulation::fill_sub_block`].
    fn factorise(&mut self, t_end: f64, sel: Table) -> Result<(), SolverError> {
        let n = self.state.active.len();
        let p = self.tables.p;
        self.state.stats.factorisations += 1;
        let act = &self.state.active;
        let res = match sel {
            Table::Full => {
                let g = &self.tables.full_inf;
                let blocks = [&g.gx1, &g.gx2, &g.gv1, &g.gv2];
                let entry = |r: usize, c: usize| {
                    let blk = 2 * (r >= n) as usize + (c >= n) as usize;
                    blocks[blk][act[r % n] * p + act[c % n]]
                };
                self.factors.current.solver.factor(2 * n, entry)
            }
            // the interleaved blocks into the 2|S| x 2|S| matrix
            Table::Sub => {
                let gss = &self.scratch.dense.gss[..4 * n * n];
                self.scratch.dense.solver.factor_filled(2 * n, |m| {
                    let (top, bottom) = m.split_at_mut(2 * n * n);
                    let rows = top
                        .chunks_exact_mut(2 * n)
                        .zip(bottom.chunks_exact_mut(2 * n));
                    for ((mx, mv), g) in rows.zip(gss.chunks_exact(4 * n)) {
                        let (mx1, mx2) = mx.split_at_mut(n);
                        let (mv1, mv2) = mv.split_at_mut(n);
                        for (b, e) in g.chunks_exact(4).enumerate() {
                            (mx1[b], mx2[b], mv1[b], mv2[b]) = (e[0], e[1], e[2], e[3]);
                        }
                    }
                })
            }
        };
        if sel == Table::Full {
            self.factors.factored = res.is_ok();
            self.factors.current.set.clone_from(&self.state.active);
            self.pack_free_rows();
            if res.is_ok() && self.tables.options.reuse_factorisation {
                // reused while the set holds: solves become products
                self.factors.current.solver.form_inverse();
            }
        }
        if let Err(e) = res {
            return Err(SolverError::SingularContactSystem {
                t_s: t_end,
                points: self.state.active.clone(),
                pivot: e.pivot,
            });
        }
        Ok(())
    }

    /// Before a full-step factorisation of a new active set (method §4.5,
    /// "Reuse"): the kept factorisation of `active`, if any, becomes the
    /// current one (`true`: nothing to factorise); the current one, if
    /// valid, is kept in its place or in the least recently used entry.
    /// Swaps of buffers sized once: no allocation, and the same values as a
    /// new factorisation, bit for bit (it depends only on the set and `dt`).
    fn swap_cached_factorisation(&mut self) -> bool {
        let factors = &mut self.factors;
        let found = factors.cache.find(&self.state.active);
        let k = match found {
            Some(k) => k,
            // nothing to keep: factorise into the current buffers
            None if !factors.factored => return false,
            None => factors.cache.victim(),
        };
        let tick = factors.cache.tick();
        let e = &mut factors.cache.entries[k];
        std::mem::swap(&mut e.factor, &mut factors.current);
        // the entry now holds the previous current factorisation
        e.used = if factors.factored { tick } else { 0 };
        // taken back: valid, inverse formed; else the factorisation follows
        factors.factored = found.is_some();
        found.is_some()
    }

    /// The current factorisation's `free` points and `free_rows` of its
    /// `set` (allocation-free: capacities `P` and `4P²`).
    fn pack_free_rows(&mut self) {
        let p = self.tables.p;
        let f = &mut self.factors.current;
        let n = f.set.len();
        f.free.clear();
        f.free_rows.clear();
        for i in 0..p {
            if !f.set.contains(&i) {
                f.free.push(i);
            }
        }
        // each source column read once, contiguous (`full_inf_cols`): a
        // new set costs 4 |S| P reads in order, not P rows of 4 strided ones
        let m = 4 * n;
        f.free_rows.resize(f.free.len() * m, 0.0);
        for (b, &j) in f.set.iter().enumerate() {
            let cols = &self.tables.full_inf_cols[4 * p * j..4 * p * (j + 1)];
            for (blk, col) in cols.chunks_exact(p).enumerate() {
                for (row, &i) in f.free_rows.chunks_exact_mut(m).zip(&f.free) {
                    row[blk * n + b] = col[i];
                }
            }
        }
    }

    /// End values of every point right after a full-step solve of the
    /// current factorisation's set, whose forces `q1 | q2` are in `rhs`
    /// (method §4.3 step 3): the active points end on the road, which is
    /// what the solve imposed (exactly, not to the solve's round-off); each
    /// free point is its free value plus its packed influence row times the
    /// forces (O((P - |S|) |S|)).
    pub(super) fn end_values_solved(&mut self) {
        let f = &self.factors.current;
        let n = f.set.len();
        let p = self.tables.p;
        let s = &mut self.scratch;
        if n == 0 {
            s.ue[..p].copy_from_slice(&s.uh[..p]);
            s.ve[..p].copy_from_slice(&s.vh[..p]);
            return;
        }
        let m = 2 * n;
        let q = &s.rhs[..m];
        let (ue, ve) = (&mut s.ue[..p], &mut s.ve[..p]);
        let (uh, vh) = (&s.uh[..p], &s.vh[..p]);
        let (free, rows) = (&f.free[..], &f.free_rows[..]);
        // (fixed lengths for up to five points on the road: unrolled sums)
        match m {
            2 => free_ends::<2>(free, rows, q, uh, vh, ue, ve),
            4 => free_ends::<4>(free, rows, q, uh, vh, ue, ve),
            6 => free_ends::<6>(free, rows, q, uh, vh, ue, ve),
            8 => free_ends::<8>(free, rows, q, uh, vh, ue, ve),
            10 => free_ends::<10>(free, rows, q, uh, vh, ue, ve),
            _ => {
                for (&i, row) in free.iter().zip(rows.chunks_exact(2 * m)) {
                    let (rx, rv) = row.split_at(m);
                    (ue[i], ve[i]) = free_end(uh[i], vh[i], rx, rv, q);
                }
            }
        }
        for &j in &f.set {
            ue[j] = s.re[j];
            ve[j] = s.rde[j];
        }
    }

    /// End displacement/velocity of every point under the Gauss-point forces
    /// `q1`, `q2` of the active points over the sub-step (after `predict`),
    /// through the states: O(states (|S| + P)), no P x P influence.
    pub(super) fn end_values_sub(&mut self) {
        self.end_values_through_states(Table::Sub)
    }

    /// [`Simulation::end_values_sub`] over the sub-step or the full step
    /// `sel`.
    pub(super) fn end_values_through_states(&mut self, sel: Table) {
        if !self.scratch.projected_all && sel == Table::Sub {
            // the prediction projected only the active points: the end
            // state, prediction plus forces, projected once (as the fused
            // full step, `large.rs`), and taken by `commit` as it is
            return self.end_state_projected(Table::Sub);
        }
        let (tb, st, s) = (&self.tables, &self.state, &mut self.scratch);
        let table = match sel {
            Table::Full => &tb.full,
            Table::Sub => &s.sub,
        };
        let threads = &self.threads;
        s.delta.x.fill(0.0);
        s.delta.v.fill(0.0);
        s.delta
            .add_gauss_forces_on(&tb.basis, table, &st.active, &s.q1, &s.q2, threads);
        s.delta.project_on(&tb.basis, &mut s.du, &mut s.dv, threads);
        for i in 0..tb.p {
            s.ue[i] = s.uh[i] + s.du[i];
            s.ve[i] = s.vh[i] + s.dv[i];
        }
        let tau_s = table.tau_s;
        self.add_residual_ends(tau_s);
    }

    /// Adds the residual compliance's share to the end values `ue`, `ve`
    /// of every point (method §4.7): `C` times the forces' end value and
    /// slope over a (sub-)step of `tau_s`; nothing without residual modes.
    pub(super) fn add_residual_ends(&mut self, tau_s: f64) {
        let (tb, st, s) = (&self.tables, &self.state, &mut self.scratch);
        if tb.residual.is_empty() {
            return;
        }
        let (p, rate) = (tb.p, SQRT3 / tau_s);
        for i in 0..p {
            let (mut du, mut dv) = (0.0, 0.0);
            for &j in &st.active {
                let c = tb.residual[i * p + j];
                du += c * (-GB * s.q1[j] + GA * s.q2[j]);
                dv += c * rate * (s.q2[j] - s.q1[j]);
            }
            s.ue[i] += du;
            s.ve[i] += dv;
        }
    }

    /// End values of every point for the current forces: with the full-step
    /// table through the precomputed P x P influence (O(P |S|)), on sub-steps
    /// through the states.
    pub(super) fn end_values_sub_or_full(&mut self, sel: Table) {
        match sel {
            Table::Sub => self.end_values_sub(),
            Table::Full => {
                let (tb, st, s) = (&self.tables, &self.state, &mut self.scratch);
                let p = tb.p;
                let (ue, ve) = (&mut s.ue[..p], &mut s.ve[..p]);
                let (uh, vh) = (&s.uh[..p], &s.vh[..p]);
                // the free values plus each active point's columns in turn
                // (the first sets, so that no separate copy runs)
                for (k, &j) in st.active.iter().enumerate() {
                    let (a, b) = (s.q1[j], s.q2[j]);
                    let c = &tb.full_inf_cols[4 * p * j..4 * p * (j + 1)];
                    let (x1, rest) = c.split_at(p);
                    let (x2, rest) = rest.split_at(p);
                    let (v1, v2) = rest.split_at(p);
                    if k == 0 {
                        for i in 0..p {
                            ue[i] = uh[i] + (x1[i] * a + x2[i] * b);
                            ve[i] = vh[i] + (v1[i] * a + v2[i] * b);
                        }
                    } else {
                        for i in 0..p {
                            ue[i] += x1[i] * a + x2[i] * b;
                            ve[i] += v1[i] * a + v2[i] * b;
                        }
                    }
                }
                if st.active.is_empty() {
                    ue.copy_from_slice(uh);
                    ve.copy_from_slice(vh);
                }
            }
        }
    }

    /// The `|S| x |S|` blocks of the sub-step influence of the active points
    /// (only what the solve needs: `O(|S|² states)`), with the residual and
    /// tread compliances where there are any, interleaved: entry
    /// `(a, b)` of the blocks `gx1`, `gx2`, `gv1`, `gv2` at `4 (a |S| + b)`
    /// and the next three (one 4-wide update per state and pair; each entry
    /// sums the same products in the same order as four separate blocks).
    pub(super) fn fill_sub_block(&mut self) {
        let (tb, active, sc) = (&self.tables, &self.state.active, &mut self.scratch);
        let n = active.len();
        let (p, ns) = (tb.p, tb.basis.stored_states());
        let g = &mut sc.dense.gss[..4 * n * n];
        // the weights of the four entries, each contiguous over the states
        let wq = sc.sub.weight_columns(ns);
        PairFill {
            out: &tb.basis.out[..p * ns],
            inp_t: &tb.basis.inp_t[..ns * p],
            ns,
            symmetric: tb.basis.symmetric(),
        }
        .fill(active, wq, &mut sc.dense.sub_out_weighted, g);
        if !tb.residual.is_empty() {
            let rate = SQRT3 / sc.sub.tau_s;
            for (a, &i) in active.iter().enumerate() {
                for (b, &j) in active.iter().enumerate() {
                    let (c, k) = (tb.residual[i * p + j], 4 * (a * n + b));
                    g[k] += -GB * c;
                    g[k + 1] += GA * c;
                    g[k + 2] += -rate * c;
                    g[k + 3] += rate * c;
                }
            }
        }
        // tread springs: their compliance `1 / k` on the diagonal, in the
        // end value and the slope (`compliant.rs`)
        if !tb.tread_k_n_m.is_empty() {
            let rate = SQRT3 / sc.sub.tau_s;
            for (a, &i) in active.iter().enumerate() {
                let (kt, k) = (tb.tread_k_n_m[i], 4 * (a * n + a));
                g[k] += -GB / kt;
                g[k + 1] += GA / kt;
                g[k + 2] += -rate / kt;
                g[k + 3] += rate / kt;
            }
        }
    }
}

/// The sub-step influence of every pair of `active` points into `g`
/// (`4` entries a pair, row-major): `Σ_s (a_s[i] w_q[s]) b_s[j]` over the
/// stored states for the four weights `wq` (method §4.5), summed in four
/// lanes of states (`s mod 4`) then `(l0 + l1) + (l2 + l3)`. With a
/// `symmetric` basis the pairs `j < i` are the pairs `(j, i)`: half the
/// work, and the system exactly symmetric. `ow` holds a row's weighted
/// outputs (`4 ns`). Compiled twice on x86-64 (the baseline and AVX2
/// without FMA, picked at run time): the same operations in the same
/// order, bit-identical.
struct PairFill<'a> {
    out: &'a [f64],
    inp_t: &'a [f64],
    ns: usize,
    symmetric: bool,
}

impl PairFill<'_> {
    fn fill(&self, active: &[usize], wq: [&[f64]; 4], ow: &mut [f64], g: &mut [f64]) {
        #[cfg(target_arch = "x86_64")]
        {
            if std::arch::is_x86_feature_detected!("avx2") {
                #[target_feature(enable = "avx2")]
                fn wide(
                    f: &PairFill,
                    active: &[usize],
                    wq: [&[f64]; 4],
                    ow: &mut [f64],
                    g: &mut [f64],
                ) {
                    f.body(active, wq, ow, g)
                }
                // SAFETY: the CPU supports AVX2 (checked just above).
                return unsafe { wide(self, active, wq, ow, g) };
            }
        }
        self.body(active, wq, ow, g)
    }

    #[inline(always)]
    fn body(&self, active: &[usize], wq: [&[f64]; 4], ow: &mut [f64], g: &mut [f64]) {
        let ns = self.ns;
        debug_assert_eq!(ns % 4, 0, "the stored states fill whole lanes");
        let n = active.len();
        let sum = |x: [f64; 4]| (x[0] + x[1]) + (x[2] + x[3]);
        for (a, &i) in active.iter().enumerate() {
            let o = &self.out[i * ns..(i + 1) * ns];
            for (q, owq) in ow[..4 * ns].chunks_exact_mut(ns).enumerate() {
                for ((x, &oi), &w) in owq.iter_mut().zip(o).zip(&wq[q][..ns]) {
                    *x = oi * w;
                }
            }
            let (ow0, rest) = ow[..4 * ns].split_at(ns);
            let (ow1, rest) = rest.split_at(ns);
            let (ow2, ow3) = rest.split_at(ns);
            let first = if self.symmetric { a } else { 0 };
            let mut b = first;
            // two columns at a time share the weighted row's loads
            while b + 2 <= n {
                let (j0, j1) = (active[b], active[b + 1]);
                let inp0 = &self.inp_t[j0 * ns..(j0 + 1) * ns];
                let inp1 = &self.inp_t[j1 * ns..(j1 + 1) * ns];
                let mut acc = [[[0.0f64; 4]; 4]; 2];
                let lanes = (inp0.chunks_exact(4).zip(inp1.chunks_exact(4)))
                    .zip(ow0.chunks_exact(4).zip(ow1.chunks_exact(4)))
                    .zip(ow2.chunks_exact(4).zip(ow3.chunks_exact(4)));
                for (((b0, b1), (x0, x1)), (x2, x3)) in lanes {
                    for l in 0..4 {
                        acc[0][0][l] += x0[l] * b0[l];
                        acc[0][1][l] += x1[l] * b0[l];
                        acc[0][2][l] += x2[l] * b0[l];
                        acc[0][3][l] += x3[l] * b0[l];
                        acc[1][0][l] += x0[l] * b1[l];
                        acc[1][1][l] += x1[l] * b1[l];
                        acc[1][2][l] += x2[l] * b1[l];
                        acc[1][3][l] += x3[l] * b1[l];
                    }
                }
                for (c, acc) in acc.iter().enumerate() {
                    let k = 4 * (a * n + b + c);
                    g[k..k + 4].copy_from_slice(&acc.map(sum));
                }
                b += 2;
            }
            if b < n {
                let j = active[b];
                let inp = &self.inp_t[j * ns..(j + 1) * ns];
                let mut acc = [[0.0f64; 4]; 4];
                let lanes = inp
                    .chunks_exact(4)
                    .zip(ow0.chunks_exact(4).zip(ow1.chunks_exact(4)))
                    .zip(ow2.chunks_exact(4).zip(ow3.chunks_exact(4)));
                for ((b0, (x0, x1)), (x2, x3)) in lanes {
                    for l in 0..4 {
                        acc[0][l] += x0[l] * b0[l];
                        acc[1][l] += x1[l] * b0[l];
                        acc[2][l] += x2[l] * b0[l];
                        acc[3][l] += x3[l] * b0[l];
                    }
                }
                let k = 4 * (a * n + b);
                g[k..k + 4].copy_from_slice(&acc.map(sum));
            }
        }
        if self.symmetric {
            for a in 0..n {
                for b in 0..a {
                    let (from, to) = (4 * (b * n + a), 4 * (a * n + b));
                    g.copy_within(from..from + 4, to);
                }
            }
        }
    }
}

/// The free points' end values of [`Simulation::end_values_solved`] with
/// `M = 2|S|` known at compile time (rows of `2M`: displacement, velocity).
#[inline(always)]
fn free_ends<const M: usize>(
    free: &[usize],
    rows: &[f64],
    q: &[f64],
    uh: &[f64],
    vh: &[f64],
    ue: &mut [f64],
    ve: &mut [f64],
) {
    let Ok(q) = <&[f64; M]>::try_from(q) else {
        return;
    };
    for (&i, row) in free.iter().zip(rows.chunks_exact(2 * M)) {
        let (rx, rv) = row.split_at(M);
        if let (Ok(rx), Ok(rv)) = (<&[f64; M]>::try_from(rx), <&[f64; M]>::try_from(rv)) {
            (ue[i], ve[i]) = free_end(uh[i], vh[i], rx, rv, q);
        }
    }
}

/// `(u + rx · q, v + rv · q)`, each sum from the free value in order.
#[inline(always)]
fn free_end(u: f64, v: f64, rx: &[f64], rv: &[f64], q: &[f64]) -> (f64, f64) {
    let (mut a, mut b) = (u, v);
    for ((x, w), qk) in rx.iter().zip(rv).zip(q) {
        a += x * qk;
        b += w * qk;
    }
    (a, b)
}

#[cfg(test)]
mod tests {
    use super::Table;
    use crate::Simulation;

    /// Full-step factorisations taken back from the cache of active sets
    /// (method §4) give the run of factorising every new set again, bit for
    /// bit, with fewer factorisations.
    #[test]
    fn kept_factorisations_change_no_bit() {
        let text = include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../presets/three_points.ron"
        ));
        let scene = crate::solver::test_problem::problem(text);
        let mut a = Simulation::new(&scene, crate::SolverOptions::default()).unwrap();
        let mut b = Simulation::new(&scene, crate::SolverOptions::default()).unwrap();
        b.factors.cache = super::super::factor_cache::FactorCache::new(b.tables.p, false);
        assert!(a.factors.cache.is_enabled() && !b.factors.cache.is_enabled());
        let bits = |x: &[f64]| x.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        for step in 0..15_000 {
            let (ra, rb) = (a.step().unwrap(), b.step().unwrap());
            assert_eq!(ra, rb, "report at step {step}");
            let (sa, sb) = (&a.state, &b.state);
            for (x, y) in [(&sa.u, &sb.u), (&sa.v, &sb.v), (&sa.q_mean, &sb.q_mean)] {
                assert_eq!(bits(x), bits(y), "outputs at step {step}");
            }
        }
        let (sa, sb) = (a.stats(), b.stats());
        assert!(sa.events > 100, "only {} events", sa.events);
        assert!(
            sa.factorisations < sb.factorisations,
            "{} factorisations with the cache, {} without",
            sa.factorisations,
            sb.factorisations
        );
    }

    /// After a full-step solve the active points end exactly on the road
    /// (what the solve imposes) and every free point's end values from the
    /// packed rows equal those summed from the P x P influence columns.
    #[test]
    fn solved_end_values_match_the_influence_columns() {
        let text = include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../presets/three_points.ron"
        ));
        let scene = crate::solver::test_problem::problem(text);
        let mut sim = Simulation::new(&scene, crate::SolverOptions::default()).unwrap();
        let (mut mixed, mut worst) = (0, 0.0f64);
        for _ in 0..20_000 {
            sim.step().unwrap();
            let n = sim.state.active.len();
            if n == 0 || n == sim.tables.p || sim.state.had_event {
                continue;
            }
            // the next step's trial, solved by hand
            let (t, dt) = (sim.state.t_s, sim.tables.dt_s);
            sim.predict(t, dt, Table::Full).unwrap();
            sim.solve_active(t + dt, Table::Full).unwrap();
            let (ue, ve) = (sim.scratch.ue.clone(), sim.scratch.ve.clone());
            for &j in &sim.state.active {
                let s = &sim.scratch;
                assert_eq!((ue[j], ve[j]), (s.re[j], s.rde[j]), "point {j}");
            }
            sim.end_values_sub_or_full(Table::Full);
            let (st, s) = (&sim.state, &sim.scratch);
            for i in (0..sim.tables.p).filter(|i| !st.active.contains(i)) {
                let scale = s.ue[i].abs() + s.uh[i].abs() + 1e-9;
                worst = worst.max((ue[i] - s.ue[i]).abs() / scale);
                let vscale = s.ve[i].abs() + s.vh[i].abs() + 1e-6;
                worst = worst.max((ve[i] - s.ve[i]).abs() / vscale);
            }
            mixed += 1;
            // back to the state of the step start: a fresh trial next step
            sim.state.had_event = true;
        }
        assert!(
            mixed > 100,
            "only {mixed} steps with free and active points"
        );
        assert!(
            worst < 1e-12,
            "free end values differ by {worst:e} (relative)"
        );
    }

    /// The pair fill against the sum written out state by state, over
    /// sizes odd and even (the two-column blocks and their tail), a single
    /// point, repeated points and a symmetric basis; its two builds agree
    /// bit for bit.
    #[test]
    fn the_pair_fill_is_the_weighted_sum_over_the_states() {
        use super::PairFill;
        let val = |k: usize, seed: f64| ((k as f64 * 0.618 + seed).sin() * 1e3).fract();
        for (p, ns, active) in [
            (5usize, 8usize, vec![0usize, 2, 4]),
            (6, 12, vec![5, 1, 3, 0]),
            (1, 4, vec![0]),
            (7, 16, vec![6, 0, 3, 2, 5]),
            (4, 4, vec![1, 1, 2]),
        ] {
            let out: Vec<f64> = (0..p * ns).map(|k| val(k, 0.3)).collect();
            let inp: Vec<f64> = (0..p * ns).map(|k| val(k, 1.7)).collect();
            // weights over 8 decades, as a sub-step's decaying modes give
            let wq: Vec<f64> = (0..4 * ns)
                .map(|k| val(k, 2.9) * 10f64.powi((k % 9) as i32 - 4))
                .collect();
            for symmetric in [false, true] {
                let inp_t = if symmetric { out.clone() } else { inp.clone() };
                let f = PairFill {
                    out: &out,
                    inp_t: &inp_t,
                    ns,
                    symmetric,
                };
                let n = active.len();
                let mut ow = vec![0.0; 4 * ns];
                let (mut g, mut g_base) = (vec![0.0; 4 * n * n], vec![0.0; 4 * n * n]);
                let cols: [&[f64]; 4] = std::array::from_fn(|q| &wq[q * ns..(q + 1) * ns]);
                f.fill(&active, cols, &mut ow, &mut g);
                f.body(&active, cols, &mut ow, &mut g_base);
                assert_eq!(g, g_base, "the two builds differ");
                for (a, &i) in active.iter().enumerate() {
                    for (b, &j) in active.iter().enumerate() {
                        for q in 0..4 {
                            let (mut want, mut size) = (0.0f64, 0.0f64);
                            for s in 0..ns {
                                let t = out[i * ns + s] * inp_t[j * ns + s] * wq[q * ns + s];
                                want += t;
                                size += t.abs();
                            }
                            let got = g[4 * (a * n + b) + q];
                            assert!(
                                (got - want).abs() <= 1e-14 * size,
                                "p {p}, pair ({i}, {j}), entry {q}: {got} vs {want}"
                            );
                            if symmetric {
                                assert_eq!(got, g[4 * (b * n + a) + q]);
                            }
                        }
                    }
                }
            }
        }
    }
}
