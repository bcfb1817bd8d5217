//! The weights of a step of any length `τ ∈ [0, dt]` by interpolation
//! (method §4.6, "Events in one solve": the table of a landing's or a
//! release's remaining interval).
//!
//! A step's Gauss-point weights are entire functions of `τ`, smooth on the
//! scale of `dt` whenever `ω dt` is moderate. They are computed exactly
//! ([`mode_step`](super::mode_step)) at the `M` Chebyshev–Lobatto nodes
//! `τ_m = dt (1 − cos(π m / (M − 1))) / 2` and evaluated at any `τ` by the
//! barycentric formula
//!
//! ```text
//! w(τ) = Σ_m λ_m(τ) w(τ_m),   λ_m(τ) = (β_m / (τ − τ_m)) / Σ_k β_k / (τ − τ_k),
//! β_m = (−1)^m (halved at both ends)
//! ```
//!
//! (Berrut and Trefethen 2004), which is exact at the nodes (`τ = dt` gives
//! the full step's table). The influence of a point's Gauss values on
//! every point's end values is linear in the weights, so its columns are
//! interpolated the same way: a landing's responses at every point cost
//! `O(M P)` instead of a table and two projections, `O(ns P)`.
//!
//! `M` is the smallest from 4 to [`MAX_NODES`] whose interpolant matches the
//! exact weights of every mode to [`WEIGHT_TOLERANCE`] of that mode's
//! largest weight, at the points halfway between the nodes (where the
//! error of a Chebyshev interpolant peaks); the columns are checked against
//! exact ones at those points too. A step for which no `M` passes (a very
//! large `ω dt`) has no interpolant, and its events take exact tables.

use super::{ModalBasis, StepTable};
use crate::model::convolution::mode_step::{ModeStep, mode_steps_into};
use std::f64::consts::PI;

/// The most interpolation nodes tried.
pub const MAX_NODES: usize = 16;

/// The largest error of an interpolated weight, relative to the largest
/// value of that weight over `[0, dt]` for its mode.
pub const WEIGHT_TOLERANCE: f64 = 1e-11;

/// The Gauss-point weights of a step of any `τ ∈ [0, dt]`, and their
/// influence columns, interpolated in `τ` (module doc).
#[derive(Debug, Clone)]
pub struct TauInterp {
    dt_s: f64,
    /// The nodes `τ_m` (s) and their barycentric weights `β_m`.
    nodes_s: Vec<f64>,
    beta: Vec<f64>,
    /// Per node, the four Gauss-point weights of every stored state, column
    /// by column (`w1x`, `w1v`, `w2x`, `w2v`): `weights[(m * 4 + c) * ns + s]`.
    weights: Vec<f64>,
    ns: usize,
    /// Per source point `j` and node past the first, its influence columns
    /// (end displacement by `q1`, by `q2`, velocity by `q1`, by `q2` at
    /// every point): `columns[((j * (M − 1) + m − 1) * 4 + c) * P + i]`
    /// for node `m ≥ 1` (node 0, a step of zero length, has zero columns,
    /// neither stored nor summed); empty when they would exceed the budget
    /// given to [`TauInterp::new`].
    columns: Vec<f64>,
    p: usize,
    /// The largest relative error found at set-up (weights, columns).
    pub checked_error: f64,
}

impl TauInterp {
    /// The interpolant of `basis`'s weights on `[0, dt_s]`, with influence
    /// columns when `4 P² (M − 1)` values fit in `column_budget` (and pass their
    /// check); `None` if no number of nodes up to `MAX_NODES` (16) meets
    /// `WEIGHT_TOLERANCE` (1e-11). [`TauInterp::weights`], then
    /// [`TauInterp::add_node_column`] for every [`TauInterp::column_stages`]
    /// and [`TauInterp::finish_columns`], a stage at a time, build the same.
    pub fn new(basis: &ModalBasis, dt_s: f64, column_budget: usize) -> Option<Self> {
        let mut ti = Self::weights(basis, dt_s)?;
        if ti.columns_fit(column_budget) {
            for stage in 0..ti.column_stages() {
                ti.add_node_column(basis, stage);
            }
            ti.finish_columns(basis);
        }
        Some(ti)
    }

    /// [`TauInterp::new`]'s interpolant of the weights alone (no columns).
    pub fn weights(basis: &ModalBasis, dt_s: f64) -> Option<Self> {
        let (k_modes, ns) = (basis.modes.len(), basis.stored_states());
        if k_modes == 0 || dt_s.is_nan() || dt_s <= 0.0 {
            return None;
        }
        let mut steps = Vec::with_capacity(k_modes);
        for m_nodes in 4..=MAX_NODES {
            let nodes_s = lobatto_nodes(m_nodes, dt_s);
            let beta = (0..m_nodes)
                .map(|m| {
                    let sign = if m % 2 == 0 { 1.0 } else { -1.0 };
                    if m == 0 || m == m_nodes - 1 {
                        0.5 * sign
                    } else {
                        sign
                    }
                })
                .collect();
            let mut weights = vec![0.0; m_nodes * 4 * ns];
            // (a step of zero length weighs nothing: node 0 stays zero)
            for (m, &tau) in nodes_s.iter().enumerate().skip(1) {
                mode_steps_into(&basis.modes, tau, &mut steps);
                for (s, &k) in basis.mode_of_state.iter().enumerate() {
                    for (c, w) in gauss_weights(&steps[k]).into_iter().enumerate() {
                        weights[(m * 4 + c) * ns + s] = w;
                    }
                }
            }
            let mut interp = TauInterp {
                dt_s,
                nodes_s,
                beta,
                weights,
                ns,
                columns: Vec::new(),
                p: basis.num_points,
                checked_error: 0.0,
            };
            let Some(err) = interp.weight_error(basis, &mut steps) else {
                continue;
            };
            interp.checked_error = err;
            return Some(interp);
        }
        None
    }

    /// The number of nodes `M`.
    pub fn num_nodes(&self) -> usize {
        self.nodes_s.len()
    }

    /// Whether the influence columns are kept ([`TauInterp::add_column`]).
    pub fn has_columns(&self) -> bool {
        !self.columns.is_empty()
    }

    /// The barycentric factors `λ_m(τ)` (module doc) into `out[..M]`.
    fn factors(&self, tau_s: f64, out: &mut [f64; MAX_NODES]) {
        let m_nodes = self.nodes_s.len();
        if let Some(m) = self.nodes_s.iter().position(|&t| t == tau_s) {
            out[..m_nodes].fill(0.0);
            out[m] = 1.0;
            return;
        }
        let mut sum = 0.0;
        for m in 0..m_nodes {
            let f = self.beta[m] / (tau_s - self.nodes_s[m]);
            out[m] = f;
            sum += f;
        }
        for f in &mut out[..m_nodes] {
            *f /= sum;
        }
    }

    /// Fills `table`'s Gauss-point weight columns for a step of
    /// `tau_s ∈ [0, dt]`; its propagator and every other entry (the
    /// rows `w1`, `w2` included) are NaN: the table serves force responses
    /// from rest only
    /// ([`ModalState::add_gauss_forces`](super::ModalState::add_gauss_forces),
    /// [`StepTable::weight_columns`]).
    pub fn fill_gauss(&self, basis: &ModalBasis, tau_s: f64, table: &mut StepTable) {
        let ns = self.ns;
        debug_assert_eq!(ns, basis.stored_states());
        let mut lam = [0.0; MAX_NODES];
        self.factors(tau_s, &mut lam);
        table.tau_s = tau_s;
        let c = &mut table.soa;
        if !table.gauss_only || c.w1x.len() != ns {
            // (once: the entries a response from rest does not read)
            table.gauss_only = true;
            table.per_mode.clear();
            for col in [
                &mut c.pxx, &mut c.pxv, &mut c.pvx, &mut c.pvv, &mut c.w1x, &mut c.w1v, &mut c.w2x,
                &mut c.w2v,
            ] {
                col.clear();
                col.resize(ns, f64::NAN);
            }
            for rows in [&mut table.w1, &mut table.w2, &mut table.w_const] {
                rows.clear();
                rows.resize(ns, [f64::NAN; 2]);
            }
            table.phi.clear();
            table.phi.resize(ns, [f64::NAN; 4]);
        }
        // each column the nodes' columns weighted by `λ_m(τ)` (node 0's
        // columns are zero)
        let m_nodes = self.nodes_s.len();
        for (ci, col) in [&mut c.w1x, &mut c.w1v, &mut c.w2x, &mut c.w2v]
            .into_iter()
            .enumerate()
        {
            super::kernels::combine_columns(&lam[..m_nodes], &self.weights, ci, ns, &mut col[..ns]);
        }
    }

    /// Adds to every point's end displacement `u` (m) and velocity `v`
    /// (m/s) the response to Gauss values `q1`, `q2` (N) of point `j` on a
    /// step of `tau_s` from rest, by the interpolated influence columns.
    /// Requires [`TauInterp::has_columns`].
    pub fn add_column(&self, tau_s: f64, j: usize, q1: f64, q2: f64, u: &mut [f64], v: &mut [f64]) {
        let (p, m_nodes) = (self.p, self.nodes_s.len());
        let mut lam = [0.0; MAX_NODES];
        self.factors(tau_s, &mut lam);
        let cols = self.source_columns(j);
        super::kernels::add_node_columns(&lam[1..m_nodes], cols, p, q1, q2, u, v);
    }

    /// Point `j`'s responses at every point to unit Gauss values on a step
    /// of `tau_s` from rest, in one pass over its interpolated influence
    /// columns: `out = [u by q1, v by q1, u by q2, v by q2]` (m/N, m/(N·s)),
    /// overwritten; bit for bit [`TauInterp::add_column`] into zeros with
    /// `(q1, q2) = (1, 0)` and `(0, 1)`. Requires
    /// [`TauInterp::has_columns`].
    pub fn unit_columns(&self, tau_s: f64, j: usize, out: [&mut [f64]; 4]) {
        let (p, m_nodes) = (self.p, self.nodes_s.len());
        let mut lam = [0.0; MAX_NODES];
        self.factors(tau_s, &mut lam);
        let cols = self.source_columns(j);
        super::kernels::unit_node_columns(&lam[1..m_nodes], cols, p, out);
    }

    /// The largest error of the interpolated weights at the points halfway
    /// (in angle) between the nodes, relative to each mode's largest node
    /// value; `None` if above `WEIGHT_TOLERANCE` (1e-11).
    fn weight_error(&self, basis: &ModalBasis, steps: &mut Vec<ModeStep>) -> Option<f64> {
        let (ns, m_nodes) = (self.ns, self.nodes_s.len());
        let mut scale = vec![0.0f64; 4 * ns];
        for m in 0..m_nodes {
            for (s, w) in scale
                .iter_mut()
                .zip(&self.weights[m * 4 * ns..(m + 1) * 4 * ns])
            {
                *s = s.max(w.abs());
            }
        }
        let mut table = StepTable::default();
        let mut worst = 0.0f64;
        for m in 0..m_nodes - 1 {
            let angle = PI * (m as f64 + 0.5) / (m_nodes - 1) as f64;
            let tau = 0.5 * self.dt_s * (1.0 - angle.cos());
            mode_steps_into(&basis.modes, tau, steps);
            self.fill_gauss(basis, tau, &mut table);
            for (s, &k) in basis.mode_of_state.iter().enumerate() {
                let e = gauss_weights(&steps[k]);
                let c = &table.soa;
                let a = [c.w1x[s], c.w1v[s], c.w2x[s], c.w2v[s]];
                for c in 0..4 {
                    let sc = scale[c * ns + s];
                    let err = (e[c] - a[c]).abs() / sc;
                    if sc > 0.0 && (err.is_nan() || err > worst) {
                        // (a NaN stays: it fails the check below)
                        worst = err;
                    }
                }
            }
            if worst.is_nan() || worst > WEIGHT_TOLERANCE {
                return None;
            }
        }
        Some(worst)
    }

    /// Whether the influence columns (`4 P² (M − 1)` values) fit in
    /// `budget`.
    pub fn columns_fit(&self, budget: usize) -> bool {
        let p = self.p;
        p > 0 && 4 * p * p * (self.nodes_s.len() - 1) <= budget
    }

    /// The stages of the columns: one per node past the first and weight
    /// column (`4 (M − 1)`, each a `P × ns × P` product).
    pub fn column_stages(&self) -> usize {
        4 * (self.nodes_s.len() - 1)
    }

    /// Stage `stage` of the columns: `G = A diag(w) Bᵀ` of one node and
    /// weight column (`A[i][s] = a_s[i]`, `B[j][s] = b_s[j]`), sizing the
    /// columns at the first (node 0, a step of zero length, has zero
    /// columns).
    pub fn add_node_column(&mut self, basis: &ModalBasis, stage: usize) {
        use faer::{Accum, Mat, Par, linalg::matmul::matmul};
        let (p, m_nodes, ns) = (self.p, self.nodes_s.len(), self.ns);
        if self.columns.len() != 4 * p * p * (m_nodes - 1) {
            self.columns = vec![0.0; 4 * p * p * (m_nodes - 1)];
        }
        let (m, c) = (1 + stage / 4, stage % 4);
        let a = Mat::from_fn(p, ns, |i, s| basis.out[i * ns + s]);
        let inp = basis.inputs_point_major();
        let w = &self.weights[(m * 4 + c) * ns..(m * 4 + c + 1) * ns];
        let wb = Mat::from_fn(ns, p, |s, j| w[s] * inp[j * ns + s]);
        let mut g = Mat::<f64>::zeros(p, p);
        matmul(
            g.as_mut(),
            Accum::Replace,
            a.as_ref(),
            wb.as_ref(),
            1.0,
            Par::Seq,
        );
        // weight column `c` (`w1x, w1v, w2x, w2v`) fills slot `x1, x2, v1,
        // v2` of each source
        let slot = [0, 2, 1, 3][c];
        for j in 0..p {
            let col = &mut self.columns[((j * (m_nodes - 1) + m - 1) * 4 + slot) * p..][..p];
            for (i, x) in col.iter_mut().enumerate() {
                *x = g[(i, j)];
            }
        }
    }

    /// Checks the columns built by every stage (against exact sums at a few sources);
    /// columns that fail are dropped (the weights alone stay).
    pub fn finish_columns(&mut self, basis: &ModalBasis) {
        match self.column_error(basis) {
            Some(err) => self.checked_error = self.checked_error.max(err),
            None => self.columns = Vec::new(),
        }
    }

    /// The interpolated columns of a few sources against columns summed
    /// exactly from the modes (a reconstruction residual, `O(P ns)` per
    /// column), relative to each column kind's largest value; `None` above
    /// the tolerance (with the summation's rounding allowed for).
    fn column_error(&self, basis: &ModalBasis) -> Option<f64> {
        let (p, m_nodes, ns) = (self.p, self.nodes_s.len(), basis.stored_states());
        let mut table = StepTable::default();
        let (mut u, mut v) = (vec![0.0; p], vec![0.0; p]);
        let mut exact = vec![0.0; 4 * p];
        let mut worst = 0.0f64;
        let sources = [0, p / 2, p - 1];
        for m in 0..m_nodes - 1 {
            let angle = PI * (m as f64 + 0.5) / (m_nodes - 1) as f64;
            let tau = 0.5 * self.dt_s * (1.0 - angle.cos());
            table.fill(basis, tau);
            for &j in &sources {
                exact.fill(0.0);
                for s in 0..ns {
                    let b = basis.inputs_point_major()[j * ns + s];
                    if b == 0.0 {
                        continue;
                    }
                    let (w1, w2) = (table.w1[s], table.w2[s]);
                    for i in 0..p {
                        let ab = basis.out[i * ns + s] * b;
                        exact[i] += ab * w1[0];
                        exact[p + i] += ab * w2[0];
                        exact[2 * p + i] += ab * w1[1];
                        exact[3 * p + i] += ab * w2[1];
                    }
                }
                for (c, (q1, q2)) in [(1.0, 0.0), (0.0, 1.0)].into_iter().enumerate() {
                    u.fill(0.0);
                    v.fill(0.0);
                    self.add_column(tau, j, q1, q2, &mut u, &mut v);
                    for (kind, got) in [(c, &u), (2 + c, &v)] {
                        let want = &exact[kind * p..(kind + 1) * p];
                        let scale = self.column_scale(j, kind);
                        if scale > 0.0 {
                            for (a, b) in got.iter().zip(want) {
                                let err = (a - b).abs() / scale;
                                if err.is_nan() || err > worst {
                                    worst = err;
                                }
                            }
                        }
                    }
                }
            }
        }
        // the exact sums and the node columns round alike at 1e-16 of the
        // terms; a mode's weight error enters with its share of the sum
        (worst <= 100.0 * WEIGHT_TOLERANCE).then_some(worst)
    }

    /// The largest magnitude of column kind `c` of source `j` over the nodes.
    fn column_scale(&self, j: usize, c: usize) -> f64 {
        let p = self.p;
        self.source_columns(j)
            .chunks_exact(p)
            .skip(c)
            .step_by(4)
            .flatten()
            .fold(0.0f64, |a, x| a.max(x.abs()))
    }

    /// Source `j`'s columns, node by node from node 1 (`4 P` values each).
    fn source_columns(&self, j: usize) -> &[f64] {
        let len = 4 * self.p * (self.nodes_s.len() - 1);
        &self.columns[j * len..(j + 1) * len]
    }
}

/// `M` Chebyshev–Lobatto nodes on `[0, dt]`, ascending, both ends exact.
fn lobatto_nodes(m_nodes: usize, dt_s: f64) -> Vec<f64> {
    (0..m_nodes)
        .map(|m| {
            if m == 0 {
                0.0
            } else if m == m_nodes - 1 {
                dt_s
            } else {
                0.5 * dt_s * (1.0 - (PI * m as f64 / (m_nodes - 1) as f64).cos())
            }
        })
        .collect()
}

/// A mode step's four Gauss-point weights in column order (`w1x`, `w1v`,
/// `w2x`, `w2v`).
fn gauss_weights(st: &ModeStep) -> [f64; 4] {
    [
        st.w_gauss[0][0],
        st.w_gauss[0][1],
        st.w_gauss[1][0],
        st.w_gauss[1][1],
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::base::modal::Mode;
    use crate::model::convolution::ModalState;
    use proptest::prelude::*;

    /// `n` modes on `p` points, shapes and residues of rank 2 mixed, the
    /// frequencies spread from `f0` over `span` (Hz).
    fn basis(n: usize, p: usize, f0: f64, span: f64, xi: f64, seed: u64) -> ModalBasis {
        let mut r = seed;
        let mut next = || {
            r = r
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (r >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let modes: Vec<Mode> = (0..n)
            .map(|k| {
                let shape: Vec<f64> = (0..p).map(|_| next()).collect();
                let other: Vec<f64> = (0..p).map(|_| next()).collect();
                let residue = (0..p)
                    .map(|i| {
                        (0..p)
                            .map(|j| shape[i] * shape[j] + other[i] * other[j])
                            .collect()
                    })
                    .collect();
                Mode {
                    freq_hz: f0 + span * k as f64 / n.max(1) as f64,
                    damping_ratio: xi,
                    residue: if k % 3 == 1 { residue } else { vec![] },
                    shape: if k % 3 == 1 { vec![] } else { shape },
                }
            })
            .collect();
        ModalBasis::new(&modes, p).unwrap()
    }

    /// Every point's end displacements and velocities of a state.
    fn ends(basis: &ModalBasis, a: &ModalState) -> (Vec<f64>, Vec<f64>) {
        let p = basis.num_points;
        let (mut u, mut v) = (vec![0.0; p], vec![0.0; p]);
        a.project(basis, &mut u, &mut v);
        (u, v)
    }

    /// The largest difference of `got` and `want`, relative to the largest
    /// magnitude in `scale`.
    fn gap(got: &[f64], want: &[f64], scale: &[f64]) -> f64 {
        let s = scale.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        got.iter()
            .zip(want)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
            / s
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(24))]

        /// At any `τ` in `[0, dt]` (ends, tiny, nodes' neighbours), the
        /// interpolated weights give the exact table's responses at every
        /// point, by state and by the interpolated columns, for modes up to
        /// `ω dt` of about 3.
        #[test]
        fn interpolated_steps_match_exact_ones(
            n in 1usize..40,
            p in 1usize..9,
            f_top_hz in 50.0f64..5000.0,
            xi in 0.0f64..0.3,
            dt_exp in -5.5f64..-4.0,
            seed in any::<u64>(),
            frac in prop::collection::vec(0.0f64..1.0, 6),
        ) {
            let dt = 10f64.powf(dt_exp);
            let b = basis(n, p, 20.0, f_top_hz, xi, seed);
            let ti = TauInterp::new(&b, dt, usize::MAX)
                .expect("an interpolant for omega dt below 3.5");
            prop_assert!(ti.has_columns());
            prop_assert!(ti.checked_error <= 100.0 * WEIGHT_TOLERANCE);
            let mut taus: Vec<f64> = frac.iter().map(|f| f * dt).collect();
            taus.extend([0.0, dt, 1e-9 * dt, dt * (1.0 - 1e-12)]);
            let (mut exact, mut approx) = (StepTable::default(), StepTable::default());
            let q1: Vec<f64> = (0..p).map(|j| 1.0 + j as f64).collect();
            let q2: Vec<f64> = (0..p).map(|j| 0.5 - j as f64).collect();
            let all: Vec<usize> = (0..p).collect();
            // errors are measured against the full step's response: what
            // a short step's error adds to a step's end values
            let mut full = ModalState::zeros(&b);
            full.add_gauss_forces(&b, &StepTable::new(&b, dt), &all, &q1, &q2);
            let (uf, vf) = ends(&b, &full);
            for tau in taus {
                // both unit responses in one pass: `add_column` into zeros
                // with unit values, bit for bit, at every source
                for j in 0..p {
                    let mut units = vec![vec![f64::NAN; p]; 4];
                    let [a, b2, c, d] = &mut units[..] else { unreachable!() };
                    ti.unit_columns(tau, j, [a, b2, c, d]);
                    for (k, (g1, g2)) in [(1.0, 0.0), (0.0, 1.0)].into_iter().enumerate() {
                        let (mut u, mut v) = (vec![0.0; p], vec![0.0; p]);
                        ti.add_column(tau, j, g1, g2, &mut u, &mut v);
                        let bits = |w: &[f64]| w.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                        prop_assert_eq!(bits(&units[2 * k]), bits(&u), "tau {} source {}: u", tau, j);
                        prop_assert_eq!(bits(&units[2 * k + 1]), bits(&v), "tau {} source {}: v", tau, j);
                    }
                }
                exact.fill(&b, tau);
                ti.fill_gauss(&b, tau, &mut approx);
                let (mut se, mut sa) = (ModalState::zeros(&b), ModalState::zeros(&b));
                se.add_gauss_forces(&b, &exact, &all, &q1, &q2);
                sa.add_gauss_forces(&b, &approx, &all, &q1, &q2);
                if tau > 0.0 {
                    let ((ue, ve), (ua, va)) = (ends(&b, &se), ends(&b, &sa));
                    prop_assert!(gap(&ua, &ue, &uf) < 1e-9, "tau {tau}: u");
                    prop_assert!(gap(&va, &ve, &vf) < 1e-9, "tau {tau}: v");
                    // the columns: every point's end values, source by source
                    let (mut u, mut v) = (vec![0.0; p], vec![0.0; p]);
                    for j in 0..p {
                        ti.add_column(tau, j, q1[j], q2[j], &mut u, &mut v);
                    }
                    prop_assert!(gap(&u, &ue, &uf) < 1e-9, "tau {tau}: columns u");
                    prop_assert!(gap(&v, &ve, &vf) < 1e-9, "tau {tau}: columns v");
                } else {
                    prop_assert!(sa.x.iter().chain(&sa.v).all(|&x| x == 0.0));
                }
            }
        }
    }

    /// At a node the interpolant returns the node's exact table to the bit
    /// (`τ = dt` is the full step's).
    #[test]
    fn the_full_step_is_a_node() {
        let b = basis(12, 4, 100.0, 1500.0, 0.02, 7);
        let dt = 1e-5;
        let ti = TauInterp::new(&b, dt, usize::MAX).unwrap();
        // (`ω dt` = 0.093 at the top mode, 1475 Hz: a handful of nodes)
        assert!(ti.num_nodes() <= 8, "{} nodes", ti.num_nodes());
        let (full, mut t) = (StepTable::new(&b, dt), StepTable::default());
        ti.fill_gauss(&b, dt, &mut t);
        let ns = b.stored_states();
        assert_eq!(t.weight_columns(ns), full.weight_columns(ns));
        assert!(t.phi.iter().all(|p| p.iter().all(|x| x.is_nan())));
        assert!(t.w1.iter().all(|p| p.iter().all(|x| x.is_nan())));
    }

    /// Modes far beyond the step (`ω dt` of hundreds) have no interpolant
    /// within the tolerance: none is built, rather than a wrong one.
    #[test]
    fn no_interpolant_for_very_stiff_steps() {
        let b = basis(6, 3, 1e5, 1e6, 0.01, 3);
        assert!(TauInterp::new(&b, 1e-3, usize::MAX).is_none());
        // and the column budget is honoured
        let b = basis(6, 3, 100.0, 1000.0, 0.01, 3);
        let ti = TauInterp::new(&b, 1e-5, 10).unwrap();
        assert!(!ti.has_columns());
    }
}
