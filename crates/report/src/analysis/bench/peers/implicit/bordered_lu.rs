//! The Newton matrix of the implicit peer factored by block elimination
//! ([`BorderedLu`]): the modes' 2 × 2 blocks and the impulses' 1 × 1
//! blocks, bordered by the points' forces.

use diffsol::{FaerContext, FaerSparseMat, FaerVec, LaError, LaLinearOp, Matrix, MatrixCommon};
use diffsol_la::LinearSolver;
use faer::linalg::solvers::{PartialPivLu, SolveCore};

/// Where an entry of the Newton matrix goes in [`BorderedLu`].
#[derive(Debug, Clone, Copy)]
enum Slot {
    /// Block `b`'s `(r, c)` entry.
    Block(usize, usize, usize),
    /// Row `r` of block `b`, border column `j`.
    Right(usize, usize, usize),
    /// Border row `i`, column `c` of block `b`.
    Below(usize, usize, usize),
    /// Border `(i, j)`.
    Border(usize, usize),
    /// A structural non-zero outside the bordered block-diagonal form.
    Outside,
}

/// LU of a bordered block-diagonal matrix
///
/// `N = [A B; C D]`, `A = diag(A_1, …, A_n)` with 1×1 or 2×2 blocks,
///
/// by block elimination: `S = D - Σ_b C_b A_b⁻¹ B_b` (dense, `P × P`,
/// LU with partial pivoting), then `N x = r` as `z_b = A_b⁻¹ r_b`,
/// `S x_D = r_D - Σ_b C_b z_b`, `x_b = z_b - A_b⁻¹ B_b x_D`. The Newton
/// matrix `M - γ ∂f/∂y` of [`Switched`](super::Switched) has this form: a 2×2 block per
/// mode (`η_s`, `η'_s`), a 1×1 block per impulse and the forces as the
/// border. Cost `O(n P²)` to factor and `O(n P)` to solve, against
/// `O((2K + P)³)` and `O((2K + P)²)` dense.
///
/// A diffsol [`LinearSolver`] of [`FaerSparseMat`]: diffsol assembles the
/// matrix on the Jacobian's sparsity pattern, this reads its entries.
#[derive(Default)]
pub(super) struct BorderedLu {
    /// The blocks' indices (a 1×1 block's second is `usize::MAX`).
    blocks: Vec<[usize; 2]>,
    /// The border's indices.
    border: Vec<usize>,
    /// The matrix, on diffsol's sparsity pattern.
    matrix: Option<FaerSparseMat<f64>>,
    /// Where each stored entry of `matrix` goes.
    slots: Vec<Slot>,
    /// `A_b`, row-major 2×2 (identity in the unused row and column of a
    /// 1×1 block), then their inverses.
    a: Vec<[f64; 4]>,
    a_inv: Vec<[f64; 4]>,
    /// `B_b`: 2 rows of `P` per block.
    b: Vec<f64>,
    /// `C_b`: its 2 columns of `P` per block.
    c: Vec<f64>,
    /// `S`'s LU.
    s_lu: Option<PartialPivLu<f64>>,
    /// Why the last factorisation failed.
    failure: Option<BorderedLuError>,
}

/// Why [`BorderedLu`] could not factor the Newton matrix.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub(super) enum BorderedLuError {
    #[error("bordered LU: no matrix set")]
    NoMatrix,
    #[error("bordered LU: stored entry {entry} is outside the bordered block-diagonal form")]
    OutsideForm { entry: usize },
    #[error("bordered LU: block {block} is singular")]
    SingularBlock { block: usize },
}

impl BorderedLu {
    /// The layout of [`Switched`](super::Switched)'s Newton matrix: `ns` modes, `p` points.
    pub(super) fn for_switched(ns: usize, p: usize) -> Self {
        let mut blocks: Vec<[usize; 2]> = (0..ns).map(|s| [s, ns + s]).collect();
        blocks.extend((0..p).map(|i| [2 * ns + i, usize::MAX]));
        BorderedLu {
            blocks,
            border: (2 * ns + p..2 * ns + 2 * p).collect(),
            ..Default::default()
        }
    }

    /// Maps each row or column index to its place: `(true, b, r)` row or
    /// column `r` of block `b`, `(false, i, 0)` border index `i`.
    fn places(&self, n: usize) -> Vec<(bool, usize, usize)> {
        let mut at = vec![(false, usize::MAX, 0); n];
        for (b, idx) in self.blocks.iter().enumerate() {
            for (r, &k) in idx.iter().enumerate() {
                if k != usize::MAX {
                    at[k] = (true, b, r);
                }
            }
        }
        for (i, &k) in self.border.iter().enumerate() {
            at[k] = (false, i, 0);
        }
        at
    }

    fn factor(&mut self) -> Result<(), BorderedLuError> {
        let matrix = self.matrix.as_ref().ok_or(BorderedLuError::NoMatrix)?;
        let (nb, p) = (self.blocks.len(), self.border.len());
        if let Some(entry) = self.slots.iter().position(|s| matches!(s, Slot::Outside)) {
            return Err(BorderedLuError::OutsideForm { entry });
        }
        self.a.clear();
        self.a.extend(self.blocks.iter().map(|idx| {
            if idx[1] == usize::MAX {
                [0.0, 0.0, 0.0, 1.0]
            } else {
                [0.0; 4]
            }
        }));
        self.b.clear();
        self.b.resize(nb * 2 * p, 0.0);
        self.c.clear();
        self.c.resize(nb * 2 * p, 0.0);
        let mut s = faer::Mat::<f64>::zeros(p, p);
        let values = matrix.inner()[0].val();
        for (slot, &v) in self.slots.iter().zip(values) {
            match *slot {
                Slot::Block(b, r, c) => self.a[b][2 * r + c] += v,
                Slot::Right(b, r, j) => self.b[(2 * b + r) * p + j] += v,
                Slot::Below(i, b, c) => self.c[(2 * b + c) * p + i] += v,
                Slot::Border(i, j) => s[(i, j)] += v,
                Slot::Outside => unreachable!(),
            }
        }
        self.a_inv.clear();
        for (b, a) in self.a.iter().enumerate() {
            let det = a[0] * a[3] - a[1] * a[2];
            if !(det.is_finite() && det != 0.0) {
                return Err(BorderedLuError::SingularBlock { block: b });
            }
            self.a_inv
                .push([a[3] / det, -a[1] / det, -a[2] / det, a[0] / det]);
        }
        // S = D - Σ_b C_b (A_b⁻¹ B_b)
        let mut g = vec![0.0; 2 * p];
        for b in 0..nb {
            let ai = self.a_inv[b];
            let (b0, b1) = (
                &self.b[2 * b * p..(2 * b + 1) * p],
                &self.b[(2 * b + 1) * p..(2 * b + 2) * p],
            );
            if b0.iter().chain(b1).all(|&x| x == 0.0) {
                continue;
            }
            for j in 0..p {
                g[j] = ai[0] * b0[j] + ai[1] * b1[j];
                g[p + j] = ai[2] * b0[j] + ai[3] * b1[j];
            }
            let (c0, c1) = (
                &self.c[2 * b * p..(2 * b + 1) * p],
                &self.c[(2 * b + 1) * p..(2 * b + 2) * p],
            );
            for i in 0..p {
                let (x0, x1) = (c0[i], c1[i]);
                if x0 == 0.0 && x1 == 0.0 {
                    continue;
                }
                for j in 0..p {
                    s[(i, j)] -= x0 * g[j] + x1 * g[p + j];
                }
            }
        }
        self.s_lu = Some(s.partial_piv_lu());
        Ok(())
    }

    /// `N x = r` (or `Nᵀ x = r`) in place.
    fn solve(&self, x: &mut FaerVec<f64>, transpose: bool) -> Result<(), LaError> {
        let lu = self.s_lu.as_ref().ok_or_else(|| {
            LaError::Other(
                self.failure
                    .as_ref()
                    .map_or_else(|| "bordered LU: not factored".into(), |e| e.to_string()),
            )
        })?;
        let p = self.border.len();
        // Nᵀ = [Aᵀ Cᵀ; Bᵀ Dᵀ]: the same elimination with B and C swapped
        let (right, below) = if transpose {
            (&self.c, &self.b)
        } else {
            (&self.b, &self.c)
        };
        let inv = |b: usize| {
            let a = self.a_inv[b];
            if transpose {
                [a[0], a[2], a[1], a[3]]
            } else {
                a
            }
        };
        let get = |x: &FaerVec<f64>, k: usize| if k == usize::MAX { 0.0 } else { x[k] };
        // z_b = A_b⁻¹ r_b; r_D -= Σ_b C_b z_b
        let mut z = vec![0.0; 2 * self.blocks.len()];
        let mut rd = faer::Mat::<f64>::from_fn(p, 1, |i, _| x[self.border[i]]);
        for (b, idx) in self.blocks.iter().enumerate() {
            let a = inv(b);
            let (r0, r1) = (get(x, idx[0]), get(x, idx[1]));
            let (z0, z1) = (a[0] * r0 + a[1] * r1, a[2] * r0 + a[3] * r1);
            z[2 * b] = z0;
            z[2 * b + 1] = z1;
            let (c0, c1) = (
                &below[2 * b * p..(2 * b + 1) * p],
                &below[(2 * b + 1) * p..(2 * b + 2) * p],
            );
            for i in 0..p {
                rd[(i, 0)] -= c0[i] * z0 + c1[i] * z1;
            }
        }
        if transpose {
            lu.solve_transpose_in_place_with_conj(faer::Conj::No, rd.as_mut());
        } else {
            lu.solve_in_place_with_conj(faer::Conj::No, rd.as_mut());
        }
        // x_b = z_b - A_b⁻¹ B_b x_D
        for (b, idx) in self.blocks.iter().enumerate() {
            let a = inv(b);
            let (b0, b1) = (
                &right[2 * b * p..(2 * b + 1) * p],
                &right[(2 * b + 1) * p..(2 * b + 2) * p],
            );
            let (mut y0, mut y1) = (0.0, 0.0);
            for j in 0..p {
                y0 += b0[j] * rd[(j, 0)];
                y1 += b1[j] * rd[(j, 0)];
            }
            x[idx[0]] = z[2 * b] - (a[0] * y0 + a[1] * y1);
            if idx[1] != usize::MAX {
                x[idx[1]] = z[2 * b + 1] - (a[2] * y0 + a[3] * y1);
            }
        }
        for (i, &k) in self.border.iter().enumerate() {
            x[k] = rd[(i, 0)];
        }
        Ok(())
    }
}

impl BorderedLu {
    /// Takes `matrix` (its pattern: later ones share it) and finds where
    /// each of its stored entries goes.
    fn set_matrix(&mut self, matrix: FaerSparseMat<f64>) {
        let at = self.places(matrix.nrows());
        let (entries, _) = matrix.triplet_iter();
        self.slots = entries
            .map(|(r, c)| match (at[r], at[c]) {
                ((true, b, i), (true, b2, j)) if b == b2 => Slot::Block(b, i, j),
                ((true, b, i), (false, j, _)) => Slot::Right(b, i, j),
                ((false, i, _), (true, b, j)) => Slot::Below(i, b, j),
                ((false, i, _), (false, j, _)) => Slot::Border(i, j),
                _ => Slot::Outside,
            })
            .collect();
        self.matrix = Some(matrix);
        self.s_lu = None;
    }
}

impl LinearSolver<FaerSparseMat<f64>> for BorderedLu {
    fn set_sparsity<
        C: LaLinearOp<V = FaerVec<f64>, T = f64, M = FaerSparseMat<f64>, C = FaerContext>,
    >(
        &mut self,
        op: &C,
    ) {
        self.set_matrix(FaerSparseMat::new_from_sparsity(
            op.nrows(),
            op.ncols(),
            op.sparsity(),
            *op.context(),
        ));
    }

    fn set_linearisation<
        C: LaLinearOp<V = FaerVec<f64>, T = f64, M = FaerSparseMat<f64>, C = FaerContext>,
    >(
        &mut self,
        op: &C,
    ) {
        if let Some(m) = self.matrix.as_mut() {
            op.matrix_inplace(m);
        }
        self.s_lu = None;
        self.failure = self.factor().err();
    }

    fn solve_in_place(&self, x: &mut FaerVec<f64>) -> Result<(), LaError> {
        self.solve(x, false)
    }

    fn solve_transpose_in_place(&self, x: &mut FaerVec<f64>) -> Result<(), LaError> {
        self.solve(x, true)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use diffsol::Vector;

    /// A bordered block-diagonal matrix of `ns` 2×2 blocks, `p` 1×1 blocks
    /// and a border of `p` (the layout of the Newton matrix of
    /// the implicit peer), entries from a fixed sequence, and its dense copy.
    fn bordered(
        ns: usize,
        p: usize,
        extra: Option<(usize, usize)>,
    ) -> (FaerSparseMat<f64>, faer::Mat<f64>) {
        let n = 2 * ns + 2 * p;
        let mut entries = Vec::new();
        let mut k = 0.0f64;
        let mut next = || {
            k += 1.0;
            (1.7 * k).sin()
        };
        for s in 0..ns {
            for (r, c) in [(s, s), (s, ns + s), (ns + s, s), (ns + s, ns + s)] {
                let diag = if r == c { 4.0 } else { 0.0 };
                entries.push((r, c, diag + next()));
            }
            for i in 0..p {
                let w = 2 * ns + p + i;
                entries.push((ns + s, w, next()));
                entries.push((w, s, next()));
                entries.push((w, ns + s, next()));
            }
        }
        for i in 0..p {
            let (j, w) = (2 * ns + i, 2 * ns + p + i);
            entries.push((j, j, 3.0 + next()));
            entries.push((j, w, next()));
            for l in 0..p {
                let wl = 2 * ns + p + l;
                entries.push((w, wl, if l == i { 5.0 } else { 0.0 } + next()));
            }
        }
        if let Some((r, c)) = extra {
            entries.push((r, c, 1.0));
        }
        let mut dense = faer::Mat::<f64>::zeros(n, n);
        for &(r, c, v) in &entries {
            dense[(r, c)] += v;
        }
        let sparse = FaerSparseMat::try_from_triplets(
            n,
            n,
            entries.iter().map(|&(r, c, _)| (r, c)).collect(),
            entries.iter().map(|&(_, _, v)| v).collect(),
            FaerContext::default(),
        )
        .unwrap();
        (sparse, dense)
    }

    /// The block elimination solves `N x = b` and `Nᵀ x = b` as faer's
    /// dense LU does, to round-off.
    #[test]
    fn bordered_lu_solves_as_a_dense_lu() {
        use faer::linalg::solvers::Solve;
        let (ns, p) = (5, 3);
        let (sparse, dense) = bordered(ns, p, None);
        let n = dense.nrows();
        let mut lu = BorderedLu::for_switched(ns, p);
        lu.set_matrix(sparse);
        lu.factor().unwrap();
        let b: Vec<f64> = (0..n).map(|i| (0.3 * i as f64).cos()).collect();
        let bm = faer::Mat::from_fn(n, 1, |i, _| b[i]);
        let dense_lu = dense.partial_piv_lu();
        for transpose in [false, true] {
            let want = if transpose {
                dense.transpose().partial_piv_lu().solve(&bm)
            } else {
                dense_lu.solve(&bm)
            };
            let mut x = FaerVec::from_vec(b.clone(), FaerContext::default());
            lu.solve(&mut x, transpose).unwrap();
            for i in 0..n {
                assert!(
                    (x[i] - want[(i, 0)]).abs() < 1e-12 * (1.0 + want[(i, 0)].abs()),
                    "transpose {transpose}: x[{i}] = {} against {}",
                    x[i],
                    want[(i, 0)]
                );
            }
        }
    }

    /// An entry coupling two modes is outside the form: the solve says so
    /// instead of dropping it.
    #[test]
    fn bordered_lu_refuses_a_matrix_outside_its_form() {
        let (ns, p) = (4, 2);
        let (sparse, _) = bordered(ns, p, Some((0, 1)));
        let mut lu = BorderedLu::for_switched(ns, p);
        lu.set_matrix(sparse);
        let err = lu.factor().unwrap_err();
        assert!(matches!(err, BorderedLuError::OutsideForm { .. }), "{err}");
        lu.failure = Some(err);
        let mut x = FaerVec::from_vec(vec![1.0; 2 * ns + 2 * p], FaerContext::default());
        assert!(lu.solve(&mut x, false).is_err());
    }
}
