//! Fast recursive convolution in the stable, bounded form (method §3).
//!
//! Per mode `k` and rank term `r` of its residue (`A_k = Σ_r a_kr b_krᵀ`; one
//! term per mode for a mode shape, `rank A_k` terms for a residue matrix), the
//! state is the pair
//!
//! ```text
//! x_kr(t) = ∫_0^t h_k(t-τ) β_kr(τ) dτ,  v_kr(t) = ∫_0^t h_k'(t-τ) β_kr(τ) dτ,  β_kr = b_krᵀ q
//! ```
//!
//! i.e. the real coordinates of method §3's rotated complex state `z`
//! (`x = Im z / ω_d`, `v = Im(λ z) / ω_d`). Unlike `z` they stay well defined
//! through critical damping and for two real poles, so one code path serves
//! every `ξ >= 0`. The state is advanced exactly:
//!
//! ```text
//! (x, v)(t + τ) = Φ(τ) (x, v)(t) + ∫_0^τ e^{Aσ} b q(t + τ - σ) dσ,   A = [[0, 1], [-ω², -2ξω]], b = (0, 1)
//! ```
//!
//! `Φ(τ)` and the exact weights of the assumed force shape (constant, or
//! linear through the two Gauss points, or through the step ends) come from
//! a Taylor series of `h` on `τ / 2^s` (where `(ω + 2ξω) τ / 2^s <= 1/2`, so
//! the series never cancels: this is where `(e^z - 1 - z)/z²` would lose
//! digits) followed by `s` exact doublings. They are computed once per `dt`,
//! and per sub-step only at event steps; the state is bounded for any `ω dt`.
//!
//! The paper's overflowing α/β form is kept in [`paper_alpha_beta`] and a
//! naive O(N²) quadrature of method eq. 3 in [`direct`], as baseline and control.

pub mod direct;
mod kernels;
mod mode_step;
pub mod paper_alpha_beta;
mod tau_interp;

use crate::base::error::BasisError;
use crate::base::linalg;
use crate::base::modal::Mode;
use crate::base::threads::Threads;
pub use mode_step::{ModeStep, mode_step, mode_steps_into};
use std::f64::consts::TAU;
use std::ops::Range;
pub use tau_interp::TauInterp;

/// Dot product with four independent accumulators (lets the compiler use
/// SIMD lanes; the summation order is fixed, so results are deterministic).
#[inline]
pub fn dot(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().min(b.len());
    let (ca, cb) = (a[..n].chunks_exact(4), b[..n].chunks_exact(4));
    let (ra, rb) = (ca.remainder(), cb.remainder());
    let mut acc = [0.0f64; 4];
    for (x, y) in ca.zip(cb) {
        for k in 0..4 {
            acc[k] += x[k] * y[k];
        }
    }
    let mut s = (acc[0] + acc[1]) + (acc[2] + acc[3]);
    for (x, y) in ra.iter().zip(rb) {
        s += x * y;
    }
    s
}

/// `(a·x, a·v)` in one pass over `a`, four accumulators each.
#[inline]
pub fn dot2(a: &[f64], x: &[f64], v: &[f64]) -> (f64, f64) {
    let n = a.len().min(x.len()).min(v.len());
    let (a, x, v) = (&a[..n], &x[..n], &v[..n]);
    let m = n - n % 4;
    let (mut su, mut sv) = ([0.0f64; 4], [0.0f64; 4]);
    for c in (0..m).step_by(4) {
        for k in 0..4 {
            su[k] += a[c + k] * x[c + k];
            sv[k] += a[c + k] * v[c + k];
        }
    }
    let (mut ru, mut rv) = (
        (su[0] + su[1]) + (su[2] + su[3]),
        (sv[0] + sv[1]) + (sv[2] + sv[3]),
    );
    for c in m..n {
        ru += a[c] * x[c];
        rv += a[c] * v[c];
    }
    (ru, rv)
}

/// Relative cut (of `|λ|` or `σ`) below which a residue's rank term is
/// round-off ([`ModalBasis::new`]).
pub const EXACT_RANK_TOLERANCE: f64 = 1e-13;

/// The modes factored into rank terms: `A_k = Σ_r a_kr b_krᵀ`.
#[derive(Debug, Clone)]
pub struct ModalBasis {
    pub num_points: usize,
    /// `(ω, ξ)` per mode.
    pub modes: Vec<(f64, f64)>,
    /// Mode index of each state.
    pub mode_of_state: Vec<usize>,
    /// `a_s[i]`, stored point-major: `out[i * ns + s]`.
    pub out: Vec<f64>,
    /// `b_s[j]`, stored state-major: `inp[s * P + j]`.
    pub inp: Vec<f64>,
    /// The same `b_s[j]`, stored point-major: `inp_t[j * ns + s]` (the
    /// force kernels run over contiguous states).
    pub inp_t: Vec<f64>,
    /// Rank terms of the modes ([`ModalBasis::num_states`]); the stored
    /// states past them are zero padding ([`ModalBasis::stored_states`]).
    num_terms: usize,
    /// Every term's output vector is its input vector (`out == inp_t`, as
    /// for modes given by shape): the influence between two points is the
    /// same both ways.
    symmetric: bool,
}

/// The stored states are a multiple of this: whole 4-wide lanes in the
/// per-step kernels, no scalar tail. The padding states have zero input
/// and output vectors: they stay zero and add nothing to any output.
pub const STATE_LANES: usize = 4;

impl ModalBasis {
    /// Factors each mode: a `shape` gives one rank term; a `residue` matrix
    /// its rank terms ([`linalg::rank_terms`]: eigendecomposition when
    /// symmetric, SVD otherwise) above `1e-13` of the largest (rank 1 for
    /// `φφᵀ`, 2 for the ring's degenerate pairs, at most `P`), checked to
    /// rebuild the residue to a relative 1e-12 (Frobenius).
    pub fn new(modes: &[Mode], num_points: usize) -> Result<Self, BasisError> {
        Self::reduced(modes, num_points, EXACT_RANK_TOLERANCE)
    }

    /// As [`ModalBasis::new`], keeping the rank terms of each residue above
    /// `rel_tol` of the largest (clamped to at least
    /// [`EXACT_RANK_TOLERANCE`]): a truncated decomposition, whose error on
    /// each residue is at most the largest dropped `|λ|` or `σ` (2-norm).
    /// See `SolverOptions::rank_tolerance`.
    pub fn with_rank_tolerance(
        modes: &[Mode],
        num_points: usize,
        rel_tol: f64,
    ) -> Result<Self, BasisError> {
        Self::reduced(modes, num_points, rel_tol.max(EXACT_RANK_TOLERANCE))
    }

    /// One state per (mode, source) as method §3 states it, without rank
    /// reduction: the "before" of the rank-1 optimisation, for benchmarks,
    /// and a representation of the same model that decomposes nothing.
    pub fn per_source(modes: &[Mode], num_points: usize) -> Self {
        let p = num_points;
        let mut terms = Vec::with_capacity(modes.len() * p);
        for (k, m) in modes.iter().enumerate() {
            let a = m.residue_matrix();
            for j in 0..p {
                let mut e = vec![0.0; p];
                e[j] = 1.0;
                terms.push((k, (0..p).map(|i| a[i][j]).collect(), e));
            }
        }
        Self::assemble(modes, p, terms)
    }

    /// The rank terms of every mode above `rel_tol` of its largest.
    fn reduced(modes: &[Mode], num_points: usize, rel_tol: f64) -> Result<Self, BasisError> {
        let p = num_points;
        let mut terms: Vec<(usize, Vec<f64>, Vec<f64>)> = Vec::new();
        for (k, m) in modes.iter().enumerate() {
            if !m.shape.is_empty() {
                terms.push((k, m.shape.clone(), m.shape.clone()));
                continue;
            }
            let a = faer::Mat::from_fn(p, p, |i, j| m.residue[i][j]);
            let split =
                linalg::rank_terms(a.as_ref(), rel_tol).map_err(|source| BasisError::Residue {
                    mode: k,
                    freq_hz: m.freq_hz,
                    source,
                })?;
            terms.extend(split.terms.into_iter().map(|(a, b)| (k, a, b)));
        }
        Ok(Self::assemble(modes, p, terms))
    }

    /// Stores the terms `(mode, a, b)`, padded with zero states to whole
    /// lanes.
    fn assemble(modes: &[Mode], p: usize, mut terms: Vec<(usize, Vec<f64>, Vec<f64>)>) -> Self {
        let params: Vec<(f64, f64)> = modes
            .iter()
            .map(|m| (TAU * m.freq_hz, m.damping_ratio))
            .collect();
        let num_terms = terms.len();
        // zero padding to whole lanes (on the last term's mode: any valid mode)
        let last_mode = terms.last().map_or(0, |t| t.0);
        while !terms.len().is_multiple_of(STATE_LANES) && !params.is_empty() {
            terms.push((last_mode, vec![0.0; p], vec![0.0; p]));
        }
        let ns = terms.len();
        let mut out = vec![0.0; p * ns];
        let mut inp = vec![0.0; ns * p];
        let mut inp_t = vec![0.0; ns * p];
        for (s, (_, a, b)) in terms.iter().enumerate() {
            for i in 0..p {
                out[i * ns + s] = a[i];
                inp[s * p + i] = b[i];
                inp_t[i * ns + s] = b[i];
            }
        }
        let symmetric = out == inp_t;
        ModalBasis {
            num_points: p,
            modes: params,
            mode_of_state: terms.iter().map(|t| t.0).collect(),
            out,
            inp,
            symmetric,
            inp_t,
            num_terms,
        }
    }

    /// `b_s[j]` point-major for the force kernels: the output vectors
    /// themselves where every term's input is its output
    /// ([`ModalBasis::symmetric`]), so that a step's forces and its
    /// projection read the same memory (the rows the forces read are then
    /// in cache for the projection).
    #[inline]
    pub fn inputs_point_major(&self) -> &[f64] {
        if self.symmetric {
            &self.out
        } else {
            &self.inp_t
        }
    }

    /// Whether every term's output vector is its input vector, so that
    /// `Σ_s a_s[i] b_s[j] w_s` is symmetric in `(i, j)` for any weights.
    pub fn symmetric(&self) -> bool {
        self.symmetric
    }

    /// States of the convolution: the rank terms of all modes.
    pub fn num_states(&self) -> usize {
        self.num_terms
    }

    /// Length of the stored state arrays: [`ModalBasis::num_states`] padded
    /// with zero states to a multiple of [`STATE_LANES`].
    pub fn stored_states(&self) -> usize {
        self.mode_of_state.len()
    }

    /// `Σ_k A_k = g'(0+)`: velocity jump per unit impulse (1/kg), row-major.
    pub fn velocity_jump(&self) -> Vec<f64> {
        self.velocity_jump_on(&Threads::single())
    }

    /// [`ModalBasis::velocity_jump`] on `threads`, split by rows (points
    /// `i`) into contiguous ranges ([`Threads::split`]): each entry is the
    /// same sum over the states in the same order whatever the range, so
    /// the result is the same for any number of threads.
    pub fn velocity_jump_on(&self, threads: &Threads) -> Vec<f64> {
        let (p, ns) = (self.num_points, self.stored_states());
        let mut m = vec![0.0; p * p];
        let rows = |r: Range<usize>, [m]: [&mut [f64]; 1]| self.velocity_jump_rows(r, m);
        if threads.worth(p * p * ns) {
            threads.split(p, 1, [(&mut m, p)], rows);
        } else {
            rows(0..p, [&mut m]);
        }
        m
    }

    /// The rows `r` (points `i`) of [`ModalBasis::velocity_jump`] into `m`
    /// (`r.len() × P`, row-major): each entry the same sum in the same
    /// order as the whole matrix's.
    pub fn velocity_jump_rows(&self, r: Range<usize>, m: &mut [f64]) {
        let (p, ns) = (self.num_points, self.stored_states());
        // (`inp_t` holds `inp`'s values point-major: the same products,
        // over contiguous memory)
        for (k, i) in r.enumerate() {
            let a = &self.out[i * ns..(i + 1) * ns];
            for j in 0..p {
                let b = &self.inp_t[j * ns..(j + 1) * ns];
                m[k * p + j] = (0..ns).map(|s| a[s] * b[s]).sum();
            }
        }
    }
}

/// Per-state propagators and weights for one step length (structure of arrays).
#[derive(Debug, Clone, Default)]
pub struct StepTable {
    pub tau_s: f64,
    pub phi: Vec<[f64; 4]>,
    pub w_const: Vec<[f64; 2]>,
    pub w1: Vec<[f64; 2]>,
    pub w2: Vec<[f64; 2]>,
    per_mode: Vec<ModeStep>,
    /// The same propagators and Gauss-point weights as separate columns
    /// (structure of arrays, for the vectorised kernels).
    soa: StepColumns,
    /// Only the Gauss-point weight columns hold this step's values (set
    /// by [`TauInterp::fill_gauss`], which left every other entry NaN).
    gauss_only: bool,
}

impl StepTable {
    /// The Gauss-point weights as columns over the states, in the order of
    /// a point pair's four entries in the contact system: end value by
    /// `q1`, by `q2`, slope by `q1`, by `q2` (`w1[s][0]`, `w2[s][0]`,
    /// `w1[s][1]`, `w2[s][1]`), the first `ns` states each.
    pub fn weight_columns(&self, ns: usize) -> [&[f64]; 4] {
        let c = &self.soa;
        [&c.w1x[..ns], &c.w2x[..ns], &c.w1v[..ns], &c.w2v[..ns]]
    }
}

/// States per range of the threaded state kernels (`predict`,
/// `add_gauss_forces`): whole blocks of the force kernel, whose written
/// states then never share a cache line between threads.
const STATE_ALIGN: usize = 16;

/// Rows (points) per range of the threaded projections: a cache line of
/// outputs.
const ROW_ALIGN: usize = 8;

/// `Φ` and the Gauss-point weights of every state, one array per entry.
#[derive(Debug, Clone, Default)]
struct StepColumns {
    pxx: Vec<f64>,
    pxv: Vec<f64>,
    pvx: Vec<f64>,
    pvv: Vec<f64>,
    w1x: Vec<f64>,
    w1v: Vec<f64>,
    w2x: Vec<f64>,
    w2v: Vec<f64>,
}

impl StepTable {
    pub fn new(basis: &ModalBasis, tau_s: f64) -> Self {
        let mut t = StepTable::default();
        t.fill(basis, tau_s);
        t
    }

    /// Recomputes the table for `tau_s` in place (no allocation once sized;
    /// event steps fill the sub-step table twice per event, method §4).
    pub fn fill(&mut self, basis: &ModalBasis, tau_s: f64) {
        let ns = basis.stored_states();
        self.tau_s = tau_s;
        self.gauss_only = false;
        mode_steps_into(&basis.modes, tau_s, &mut self.per_mode);
        self.place_per_mode(basis, ns);
    }

    /// Copies the per-mode steps into every stored state's entries (the
    /// rows and the columns), sizing them once.
    fn place_per_mode(&mut self, basis: &ModalBasis, ns: usize) {
        let c = &mut self.soa;
        if self.phi.len() != ns || c.pxx.len() != ns {
            self.phi.resize(ns, [0.0; 4]);
            self.w_const.resize(ns, [0.0; 2]);
            self.w1.resize(ns, [0.0; 2]);
            self.w2.resize(ns, [0.0; 2]);
            for col in [
                &mut c.pxx, &mut c.pxv, &mut c.pvx, &mut c.pvv, &mut c.w1x, &mut c.w1v, &mut c.w2x,
                &mut c.w2v,
            ] {
                col.resize(ns, 0.0);
            }
        }
        // (slices of length `ns`: one bounds check per state, for the mode)
        let (phi, w_const) = (&mut self.phi[..ns], &mut self.w_const[..ns]);
        let (w1, w2) = (&mut self.w1[..ns], &mut self.w2[..ns]);
        let (pxx, pxv, pvx, pvv) = (
            &mut c.pxx[..ns],
            &mut c.pxv[..ns],
            &mut c.pvx[..ns],
            &mut c.pvv[..ns],
        );
        let (w1x, w1v, w2x, w2v) = (
            &mut c.w1x[..ns],
            &mut c.w1v[..ns],
            &mut c.w2x[..ns],
            &mut c.w2v[..ns],
        );
        for (s, &k) in basis.mode_of_state[..ns].iter().enumerate() {
            let m = &self.per_mode[k];
            phi[s] = m.phi;
            w_const[s] = m.w_const;
            w1[s] = m.w_gauss[0];
            w2[s] = m.w_gauss[1];
            (pxx[s], pxv[s], pvx[s], pvv[s]) = (m.phi[0], m.phi[1], m.phi[2], m.phi[3]);
            (w1x[s], w1v[s]) = (m.w_gauss[0][0], m.w_gauss[0][1]);
            (w2x[s], w2v[s]) = (m.w_gauss[1][0], m.w_gauss[1][1]);
        }
    }
}

/// Influence of the Gauss-point forces over a step on the end displacement
/// and velocity of every point: `u_i += Σ_j Gx1[i][j] q1_j + Gx2[i][j] q2_j`,
/// likewise `v` (row-major P×P each).
#[derive(Debug, Clone, Default)]
pub struct Influence {
    pub gx1: Vec<f64>,
    pub gx2: Vec<f64>,
    pub gv1: Vec<f64>,
    pub gv2: Vec<f64>,
}

impl Influence {
    /// Full P×P influence for a step table.
    pub fn new(basis: &ModalBasis, table: &StepTable) -> Self {
        let mut g = Influence::default();
        g.fill(basis, table);
        g
    }

    /// Recomputes in place (sized once).
    pub fn fill(&mut self, basis: &ModalBasis, table: &StepTable) {
        self.fill_on(basis, table, &Threads::single());
    }

    /// [`Influence::new`] on `threads`.
    pub fn new_on(basis: &ModalBasis, table: &StepTable, threads: &Threads) -> Self {
        let mut g = Influence::default();
        g.fill_on(basis, table, threads);
        g
    }

    /// [`Influence::fill`] on `threads`, split by rows (points `i`) into
    /// contiguous ranges ([`Threads::split`]): each entry sums the same
    /// terms in the same order (states ascending) whatever the range, so
    /// the result is the same for any number of threads.
    pub fn fill_on(&mut self, basis: &ModalBasis, table: &StepTable, threads: &Threads) {
        let (p, ns) = (basis.num_points, basis.stored_states());
        self.zeroed(p);
        let rows = |r: Range<usize>, out: [&mut [f64]; 4]| influence_rows(basis, table, r, out);
        if threads.worth(4 * p * p * ns) {
            let outs = [
                (&mut self.gx1[..], p),
                (&mut self.gx2[..], p),
                (&mut self.gv1[..], p),
                (&mut self.gv2[..], p),
            ];
            threads.split(p, 1, outs, rows);
        } else {
            rows(
                0..p,
                [&mut self.gx1, &mut self.gx2, &mut self.gv1, &mut self.gv2],
            );
        }
    }

    /// Sizes the four matrices to `P × P` zeros.
    pub fn zeroed(&mut self, p: usize) {
        for m in [&mut self.gx1, &mut self.gx2, &mut self.gv1, &mut self.gv2] {
            m.clear();
            m.resize(p * p, 0.0);
        }
    }

    /// Adds the rows `r` (points `i`) of [`Influence::fill`] to the
    /// matrices sized by [`Influence::zeroed`]: each entry the same terms
    /// in the same order as the whole fill's, so a fill row block by row
    /// block is the whole fill to the bit.
    pub fn add_rows(&mut self, basis: &ModalBasis, table: &StepTable, r: Range<usize>) {
        let p = basis.num_points;
        let span = r.start * p..r.end * p;
        influence_rows(
            basis,
            table,
            r,
            [
                &mut self.gx1[span.clone()],
                &mut self.gx2[span.clone()],
                &mut self.gv1[span.clone()],
                &mut self.gv2[span],
            ],
        );
    }
}

/// The rows `r` of an [`Influence`] into `[gx1, gx2, gv1, gv2]` (each
/// `r.len() × P`, zero on entry): the terms summed over the states
/// ascending.
fn influence_rows(
    basis: &ModalBasis,
    table: &StepTable,
    r: Range<usize>,
    [gx1, gx2, gv1, gv2]: [&mut [f64]; 4],
) {
    let (p, ns) = (basis.num_points, basis.stored_states());
    for (k, i) in r.enumerate() {
        let row = k * p..(k + 1) * p;
        let (gx1, gx2) = (&mut gx1[row.clone()], &mut gx2[row.clone()]);
        let (gv1, gv2) = (&mut gv1[row.clone()], &mut gv2[row]);
        for s in 0..ns {
            let a = basis.out[i * ns + s];
            if a == 0.0 {
                continue;
            }
            let (w1, w2) = (table.w1[s], table.w2[s]);
            let b = &basis.inp[s * p..(s + 1) * p];
            for j in 0..p {
                let ab = a * b[j];
                gx1[j] += ab * w1[0];
                gx2[j] += ab * w2[0];
                gv1[j] += ab * w1[1];
                gv2[j] += ab * w2[1];
            }
        }
    }
}

/// The convolution state `(x, v)` per rank term.
#[derive(Debug, Clone, PartialEq)]
pub struct ModalState {
    pub x: Vec<f64>,
    pub v: Vec<f64>,
}

impl ModalState {
    pub fn zeros(basis: &ModalBasis) -> Self {
        let ns = basis.stored_states();
        ModalState {
            x: vec![0.0; ns],
            v: vec![0.0; ns],
        }
    }

    pub fn reset(&mut self) {
        self.x.fill(0.0);
        self.v.fill(0.0);
    }

    /// `out = Φ(τ) self` (free evolution over the step, no new force).
    #[inline]
    pub fn predict_into(&self, table: &StepTable, out: &mut ModalState) {
        kernels::predict(&table.soa, &self.x, &self.v, &mut out.x, &mut out.v);
    }

    /// [`ModalState::predict_into`] on `threads` when it pays
    /// ([`Threads::worth`]), split by states into contiguous ranges: each
    /// state is computed alone, so the result is the same for any number
    /// of threads.
    #[inline(always)]
    pub fn predict_into_on(&self, table: &StepTable, out: &mut ModalState, threads: &Threads) {
        if threads.worth(4 * self.x.len()) {
            self.predict_split(table, out, threads);
        } else {
            self.predict_into(table, out);
        }
    }

    /// [`ModalState::predict_into_on`] split over the threads.
    #[inline(never)]
    fn predict_split(&self, table: &StepTable, out: &mut ModalState, threads: &Threads) {
        let (c, x, v) = (&table.soa, &self.x, &self.v);
        let outs = [(&mut out.x[..], 1), (&mut out.v[..], 1)];
        threads.split(x.len(), STATE_ALIGN, outs, |r, [ox, ov]| {
            kernels::predict_range(c, r.start, &x[r.clone()], &v[r], ox, ov)
        });
    }

    /// Adds the response at the step end to Gauss-point forces `q1`, `q2`
    /// applied at the points listed in `active` (N).
    #[inline]
    pub fn add_gauss_forces(
        &mut self,
        basis: &ModalBasis,
        table: &StepTable,
        active: &[usize],
        q1: &[f64],
        q2: &[f64],
    ) {
        if active.is_empty() {
            return;
        }
        kernels::add_gauss_forces(
            &table.soa,
            basis.inputs_point_major(),
            active,
            q1,
            q2,
            &mut self.x,
            &mut self.v,
        );
    }

    /// [`ModalState::add_gauss_forces`] on `threads` when it pays
    /// ([`Threads::worth`]), split by states into contiguous ranges of
    /// whole blocks: each state's sum over the active points runs in
    /// their order whatever the range, so the result is the same for any
    /// number of threads.
    #[inline(always)]
    pub fn add_gauss_forces_on(
        &mut self,
        basis: &ModalBasis,
        table: &StepTable,
        active: &[usize],
        q1: &[f64],
        q2: &[f64],
        threads: &Threads,
    ) {
        if !active.is_empty() && threads.worth(2 * active.len() * self.x.len()) {
            self.add_gauss_forces_split(basis, table, active, q1, q2, threads);
        } else {
            self.add_gauss_forces(basis, table, active, q1, q2);
        }
    }

    /// [`ModalState::add_gauss_forces_on`] split over the threads.
    #[inline(never)]
    fn add_gauss_forces_split(
        &mut self,
        basis: &ModalBasis,
        table: &StepTable,
        active: &[usize],
        q1: &[f64],
        q2: &[f64],
        threads: &Threads,
    ) {
        let (ns, c, inp_t) = (self.x.len(), &table.soa, basis.inputs_point_major());
        let outs = [(&mut self.x[..], 1), (&mut self.v[..], 1)];
        threads.split(ns, STATE_ALIGN, outs, |r, [x, v]| {
            kernels::add_gauss_forces_range(c, r.start, inp_t, ns, active, q1, q2, x, v)
        });
    }

    /// Adds the response to forces constant over the step (N), all points.
    pub fn add_constant_forces(&mut self, basis: &ModalBasis, table: &StepTable, q: &[f64]) {
        let p = basis.num_points;
        for s in 0..self.x.len() {
            let b: f64 = basis.inp[s * p..(s + 1) * p]
                .iter()
                .zip(q)
                .map(|(b, q)| b * q)
                .sum();
            self.x[s] += table.w_const[s][0] * b;
            self.v[s] += table.w_const[s][1] * b;
        }
    }

    /// Applies impulses (N·s) at the points in `active`: `v` jumps, `x` does not
    /// (`h(0) = 0`, `h'(0) = 1`).
    pub fn add_impulses(&mut self, basis: &ModalBasis, active: &[usize], impulse: &[f64]) {
        // (the inputs of the active points in contiguous memory, `inp_t`)
        let ns = basis.stored_states();
        for s in 0..self.v.len() {
            self.v[s] += active
                .iter()
                .map(|&j| basis.inp_t[j * ns + s] * impulse[j])
                .sum::<f64>();
        }
    }

    /// Point displacements `u` (m) and velocities `v` (m/s) from the state.
    #[inline(always)]
    pub fn project(&self, basis: &ModalBasis, u: &mut [f64], v: &mut [f64]) {
        kernels::project(&basis.out, basis.num_points, &self.x, &self.v, u, v);
    }

    /// [`ModalState::project`] on `threads` when it pays
    /// ([`Threads::worth`]), split by rows (points) into contiguous
    /// ranges: each point's sums are the same whatever the range, so the
    /// result is the same for any number of threads.
    #[inline(always)]
    pub fn project_on(&self, basis: &ModalBasis, u: &mut [f64], v: &mut [f64], threads: &Threads) {
        if threads.worth(2 * basis.num_points * self.x.len()) {
            self.project_split(basis, u, v, threads);
        } else {
            self.project(basis, u, v);
        }
    }

    /// [`ModalState::project_on`] split over the threads.
    #[inline(never)]
    fn project_split(&self, basis: &ModalBasis, u: &mut [f64], v: &mut [f64], threads: &Threads) {
        let (p, ns) = (basis.num_points, basis.stored_states());
        let (out, x, xv) = (&basis.out, &self.x, &self.v);
        threads.split(p, ROW_ALIGN, [(u, 1), (v, 1)], |r, [u, v]| {
            kernels::project(&out[r.start * ns..r.end * ns], r.len(), x, xv, u, v)
        });
    }

    /// [`ModalState::project`] at the points `rows` only (the same values).
    #[inline]
    pub fn project_rows(&self, basis: &ModalBasis, rows: &[usize], u: &mut [f64], v: &mut [f64]) {
        let ns = basis.stored_states();
        kernels::project_rows(&basis.out, ns, rows, &self.x, &self.v, u, v);
    }

    /// [`ModalState::project_rows`] with the values of `rows[k]` into
    /// `u[k]`, `v[k]` (packed in the list's order; the same sums).
    #[inline]
    pub fn project_rows_packed(
        &self,
        basis: &ModalBasis,
        rows: &[usize],
        u: &mut [f64],
        v: &mut [f64],
    ) {
        let ns = basis.stored_states();
        kernels::project_rows_packed(&basis.out, ns, rows, &self.x, &self.v, u, v);
    }

    /// [`ModalState::project_rows`] on `threads` when it pays
    /// ([`Threads::worth`]): the list `rows` split into contiguous ranges,
    /// each row's values into `packed` (two buffers of at least
    /// `rows.len()`, at the row's place in the list), then copied to its
    /// point. Each row is the same sum whatever the range: the same values
    /// for any number of threads.
    pub fn project_rows_on(
        &self,
        basis: &ModalBasis,
        rows: &[usize],
        u: &mut [f64],
        v: &mut [f64],
        packed: [&mut [f64]; 2],
        threads: &Threads,
    ) {
        let ns = basis.stored_states();
        if !threads.worth(2 * rows.len() * ns) {
            return self.project_rows(basis, rows, u, v);
        }
        let [pu, pv] = packed;
        let (out, x, xv) = (&basis.out, &self.x, &self.v);
        threads.split(
            rows.len(),
            ROW_ALIGN,
            [(&mut *pu, 1), (&mut *pv, 1)],
            |r, [pu, pv]| kernels::project_rows_packed(out, ns, &rows[r], x, xv, pu, pv),
        );
        for (k, &i) in rows.iter().enumerate() {
            (u[i], v[i]) = (pu[k], pv[k]);
        }
    }

    /// Adds another state of the same size.
    pub fn add(&mut self, other: &ModalState) {
        for (a, b) in self.x.iter_mut().zip(&other.x) {
            *a += b;
        }
        for (a, b) in self.v.iter_mut().zip(&other.v) {
            *a += b;
        }
    }

    /// Copies another state of the same size (no allocation).
    pub fn copy_from(&mut self, other: &ModalState) {
        self.x.copy_from_slice(&other.x);
        self.v.copy_from_slice(&other.v);
    }

    pub fn is_finite(&self) -> bool {
        self.x.iter().chain(&self.v).all(|x| x.is_finite())
    }
}

#[cfg(test)]
mod tests;
