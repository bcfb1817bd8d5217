//! Dense decompositions whose results reach the user: faer's SVD,
//! self-adjoint eigendecomposition, QR and eigenvalues behind a few
//! functions that check what they return.
//!
//! Every decomposition here is verified where that is cheap, at set-up and
//! never in the time step: a residue's rank terms must rebuild it
//! ([`rank_terms`]), an SVD must rebuild its matrix and carry its Frobenius
//! norm ([`lstsq`]). A failed check is an error, never a silently wrong run.

use faer::{Mat, MatRef, Side};

/// Relative Frobenius residual within which a decomposition counts as exact
/// (a few hundred ulp of a well-scaled matrix).
pub const REBUILD_TOLERANCE: f64 = 1e-12;

/// A decomposition that failed or did not check.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LinalgError {
    /// The iteration of the decomposition did not converge.
    #[error("{what} did not converge")]
    NoConvergence { what: &'static str },
    /// The input holds NaN or an infinity.
    #[error("{what} of a matrix with a non-finite entry")]
    NonFinite { what: &'static str },
    /// The factors do not rebuild the matrix.
    #[error(
        "{what}: the factors rebuild the matrix only to a relative {residual:.2e} (Frobenius norm), expected at most {limit:.0e}"
    )]
    Rebuild {
        what: &'static str,
        residual: f64,
        limit: f64,
    },
}

/// Keeps faer's decompositions and products on the caller's thread. A
/// crate above may build faer with `rayon` (the report crate's `peers`
/// feature: diffsol asks for it), and faer's default parallelism is then
/// every thread: its results change with the thread count, and the rank
/// and order choices of an identification can follow. The library's first
/// decomposition sets faer's global parallelism to sequential, as it is
/// without `rayon` (once: a caller may set it again afterwards, for all of
/// faer).
pub fn sequential() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| faer::set_global_parallelism(faer::Par::Seq));
}

/// `‖m‖_F`.
pub fn frobenius(m: MatRef<'_, f64>) -> f64 {
    m.norm_l2()
}

/// A square matrix as rank terms, `A = Σ_r a_r b_rᵀ` (up to the cut).
#[derive(Debug, Clone, PartialEq)]
pub struct RankTerms {
    /// `(a_r, b_r)`, largest term first.
    pub terms: Vec<(Vec<f64>, Vec<f64>)>,
    /// Whether `A` was symmetric and decomposed as `Σ λ v vᵀ`.
    pub symmetric: bool,
    /// `‖A − Σ_r a_r b_rᵀ‖_F / ‖A‖_F` of the kept terms (-).
    pub residual: f64,
    /// `‖dropped terms‖_F / ‖A‖_F`: what the cut removes by design (-).
    pub dropped: f64,
}

/// Factors the square matrix `a` into rank terms, keeping those whose
/// weight (`|λ|` or `σ`) is above `rel_tol` times the largest.
///
/// A symmetric `a` (exactly: `a[i][j] == a[j][i]`) by its self-adjoint
/// eigendecomposition `A = Σ λ v vᵀ`: `a_r = √|λ| v`, `b_r = sign(λ) √|λ| v`
/// (negative `λ` allowed, the sign carried by the input vector); any other by
/// its SVD `A = Σ σ u vᵀ`: `a_r = √σ u`, `b_r = √σ v`.
///
/// Checked before it is returned: the weights must carry `‖A‖_F`
/// (`Σ λ² = ‖A‖_F²`) and the kept terms must rebuild `A` to
/// [`REBUILD_TOLERANCE`] plus what the cut drops (both relative, Frobenius).
pub fn rank_terms(a: MatRef<'_, f64>, rel_tol: f64) -> Result<RankTerms, LinalgError> {
    sequential();
    let n = a.nrows();
    assert_eq!(n, a.ncols(), "rank_terms of a non-square matrix");
    let what = "residue decomposition";
    if (0..n).any(|i| (0..n).any(|j| !a[(i, j)].is_finite())) {
        return Err(LinalgError::NonFinite { what });
    }
    // decomposed at unit scale (no overflow or underflow in the checks'
    // sums of squares), each factor scaled back by √scale
    let scale = (0..n)
        .flat_map(|i| (0..n).map(move |j| a[(i, j)].abs()))
        .fold(0.0, f64::max);
    if n == 0 || scale == 0.0 {
        return Ok(RankTerms {
            terms: Vec::new(),
            symmetric: true,
            residual: 0.0,
            dropped: 0.0,
        });
    }
    let a = Mat::from_fn(n, n, |i, j| a[(i, j)] / scale);
    let a = a.as_ref();
    let norm = frobenius(a);
    let symmetric = (0..n).all(|i| (0..i).all(|j| a[(i, j)] == a[(j, i)]));
    // (weight, a_r, b_r) of every term
    let mut all: Vec<(f64, Vec<f64>, Vec<f64>)> = Vec::with_capacity(n);
    if symmetric {
        let evd = a
            .self_adjoint_eigen(Side::Lower)
            .map_err(|_| LinalgError::NoConvergence { what })?;
        let (u, s) = (evd.U(), evd.S().column_vector());
        for r in 0..n {
            let lam = s[r];
            let root = lam.abs().sqrt();
            let sign = if lam < 0.0 { -1.0 } else { 1.0 };
            all.push((
                lam.abs(),
                (0..n).map(|i| root * u[(i, r)]).collect(),
                (0..n).map(|i| sign * root * u[(i, r)]).collect(),
            ));
        }
    } else {
        let svd = a.svd().map_err(|_| LinalgError::NoConvergence { what })?;
        let (u, v, s) = (svd.U(), svd.V(), svd.S().column_vector());
        for r in 0..n {
            let root = s[r].max(0.0).sqrt();
            all.push((
                s[r],
                (0..n).map(|i| root * u[(i, r)]).collect(),
                (0..n).map(|i| root * v[(i, r)]).collect(),
            ));
        }
    }
    all.sort_by(|x, y| y.0.total_cmp(&x.0));
    // the weights carry the norm: Σ w² = ‖A‖_F² (catches wrong singular values)
    let carried = all.iter().map(|t| t.0 * t.0).sum::<f64>().sqrt();
    let norm_error = (carried - norm).abs() / norm;
    if norm_error.is_nan() || norm_error > REBUILD_TOLERANCE {
        return Err(LinalgError::Rebuild {
            what,
            residual: norm_error,
            limit: REBUILD_TOLERANCE,
        });
    }
    let wmax = all[0].0;
    let (kept, cut): (Vec<_>, Vec<_>) = all
        .into_iter()
        .partition(|t| t.0 > rel_tol * wmax && t.0 > 0.0);
    let dropped = cut.iter().map(|t| t.0 * t.0).sum::<f64>().sqrt() / norm;
    let mut terms: Vec<(Vec<f64>, Vec<f64>)> = kept.into_iter().map(|t| (t.1, t.2)).collect();
    let residual = rebuild_residual(a, &terms) / norm;
    let limit = REBUILD_TOLERANCE + dropped;
    if residual.is_nan() || residual > limit {
        return Err(LinalgError::Rebuild {
            what,
            residual,
            limit,
        });
    }
    let root = scale.sqrt();
    for (x, y) in terms.iter_mut() {
        x.iter_mut().chain(y.iter_mut()).for_each(|v| *v *= root);
    }
    Ok(RankTerms {
        terms,
        symmetric,
        residual,
        dropped,
    })
}

/// `‖A − Σ_r a_r b_rᵀ‖_F` (`O(rank · n²)`).
pub fn rebuild_residual(a: MatRef<'_, f64>, terms: &[(Vec<f64>, Vec<f64>)]) -> f64 {
    let n = a.nrows();
    let mut s = 0.0;
    for i in 0..n {
        for j in 0..a.ncols() {
            let sum: f64 = terms.iter().map(|(x, y)| x[i] * y[j]).sum();
            let d = a[(i, j)] - sum;
            s += d * d;
        }
    }
    s.sqrt()
}

/// Least-squares solution of `A X = B` by the SVD of `A`, singular values
/// below `rcond σ_max` treated as zero (minimum-norm solution), with the
/// relative residual `‖A X − B‖_F / ‖B‖_F` (0 for `B = 0`).
///
/// The SVD is checked before use: `U Σ Vᵀ` must rebuild `A` to a relative
/// `1e-10` (Frobenius), else [`LinalgError::Rebuild`].
pub fn lstsq(
    a: MatRef<'_, f64>,
    b: MatRef<'_, f64>,
    rcond: f64,
) -> Result<(Mat<f64>, f64), LinalgError> {
    sequential();
    let what = "least-squares SVD";
    assert_eq!(a.nrows(), b.nrows(), "lstsq: row counts differ");
    let finite =
        |m: MatRef<'_, f64>| (0..m.nrows()).all(|i| (0..m.ncols()).all(|j| m[(i, j)].is_finite()));
    if !finite(a) || !finite(b) {
        return Err(LinalgError::NonFinite { what });
    }
    let svd = a
        .thin_svd()
        .map_err(|_| LinalgError::NoConvergence { what })?;
    let (u, v, s) = (svd.U(), svd.V(), svd.S().column_vector());
    let k = s.nrows();
    let norm = frobenius(a);
    if norm > 0.0 {
        // U Σ Vᵀ against A: O(m n k), the cost of the SVD itself
        let us = Mat::from_fn(u.nrows(), k, |i, r| u[(i, r)] * s[r]);
        let rebuilt = &us * v.transpose();
        let residual = frobenius((&rebuilt - a).as_ref()) / norm;
        let limit = 1e-10;
        if residual.is_nan() || residual > limit {
            return Err(LinalgError::Rebuild {
                what,
                residual,
                limit,
            });
        }
    }
    let smax = (0..k).map(|r| s[r]).fold(0.0, f64::max);
    // X = V Σ⁺ Uᵀ B
    let mut utb = u.transpose() * b;
    for r in 0..k {
        let inv = if s[r] > rcond * smax && s[r] > 0.0 {
            1.0 / s[r]
        } else {
            0.0
        };
        for c in 0..utb.ncols() {
            utb[(r, c)] *= inv;
        }
    }
    let x = v * &utb;
    let bn = frobenius(b);
    let residual = if bn > 0.0 {
        frobenius((a * &x - b).as_ref()) / bn
    } else {
        0.0
    };
    Ok((x, residual))
}

/// The triangular factor `R` (`min(m, n) × n`) of `A = Q R`.
pub fn qr_r(a: MatRef<'_, f64>) -> Mat<f64> {
    sequential();
    a.qr().thin_R().to_owned()
}

/// The eigenvalues of a real square matrix (complex pairs both listed).
pub fn eigenvalues(a: MatRef<'_, f64>) -> Result<Vec<faer::c64>, LinalgError> {
    sequential();
    let what = "eigenvalues";
    if (0..a.nrows()).any(|i| (0..a.ncols()).any(|j| !a[(i, j)].is_finite())) {
        return Err(LinalgError::NonFinite { what });
    }
    a.eigenvalues()
        .map_err(|_| LinalgError::NoConvergence { what })
}

/// The singular values of `a`, largest first.
pub fn singular_values(a: MatRef<'_, f64>) -> Result<Vec<f64>, LinalgError> {
    sequential();
    let what = "singular values";
    if (0..a.nrows()).any(|i| (0..a.ncols()).any(|j| !a[(i, j)].is_finite())) {
        return Err(LinalgError::NonFinite { what });
    }
    a.singular_values()
        .map_err(|_| LinalgError::NoConvergence { what })
}

/// The numerical rank of `a`: singular values above `abs_tol`.
pub fn rank(a: MatRef<'_, f64>, abs_tol: f64) -> Result<usize, LinalgError> {
    Ok(singular_values(a)?
        .into_iter()
        .filter(|&s| s > abs_tol)
        .count())
}

/// A row-major `n × n` slice as a matrix.
pub fn from_row_major(n: usize, m: &[f64]) -> Mat<f64> {
    Mat::from_fn(n, n, |i, j| m[i * n + j])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rebuilt(t: &RankTerms, n: usize) -> Mat<f64> {
        Mat::from_fn(n, n, |i, j| t.terms.iter().map(|(a, b)| a[i] * b[j]).sum())
    }

    #[test]
    fn extreme_scales_rebuild_without_overflow() {
        for scale in [1e-300, 1e-150, 1.0, 1e150, 1e300] {
            // rank 2, indefinite: λ = 3 s, -s
            let a = Mat::from_fn(3, 3, |i, j| {
                scale * [[1.0, 2.0, 0.0], [2.0, 1.0, 0.0], [0.0, 0.0, 0.0]][i][j]
            });
            let t = rank_terms(a.as_ref(), 1e-13).unwrap();
            assert_eq!(t.terms.len(), 2, "scale {scale:e}");
            let r = rebuilt(&t, 3);
            let err = (0..3)
                .flat_map(|i| (0..3).map(move |j| (i, j)))
                .map(|(i, j)| ((r[(i, j)] - a[(i, j)]) / scale).abs())
                .fold(0.0, f64::max);
            assert!(err < 1e-14, "scale {scale:e}: {err:e}");
        }
    }

    #[test]
    fn non_finite_entries_are_refused() {
        let mut a = Mat::<f64>::identity(3, 3);
        a[(1, 2)] = f64::NAN;
        assert!(matches!(
            rank_terms(a.as_ref(), 1e-13),
            Err(LinalgError::NonFinite { .. })
        ));
        let b = Mat::<f64>::zeros(3, 1);
        assert!(matches!(
            lstsq(a.as_ref(), b.as_ref(), 1e-14),
            Err(LinalgError::NonFinite { .. })
        ));
    }

    #[test]
    fn lstsq_gives_the_closed_form_line_fit() {
        // y = 2 - 3 x + noise ±e on 7 points: the normal equations in closed form
        let xs: Vec<f64> = (0..7).map(|k| k as f64 * 0.5).collect();
        let ys: Vec<f64> = xs
            .iter()
            .enumerate()
            .map(|(k, x)| 2.0 - 3.0 * x + if k % 2 == 0 { 0.1 } else { -0.1 })
            .collect();
        let a = Mat::from_fn(7, 2, |i, j| if j == 0 { 1.0 } else { xs[i] });
        let b = Mat::from_fn(7, 1, |i, _| ys[i]);
        let (x, residual) = lstsq(a.as_ref(), b.as_ref(), 1e-14).unwrap();
        let n = 7.0;
        let (sx, sy) = (xs.iter().sum::<f64>(), ys.iter().sum::<f64>());
        let sxx: f64 = xs.iter().map(|x| x * x).sum();
        let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| x * y).sum();
        let slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
        let icept = (sy - slope * sx) / n;
        assert!((x[(0, 0)] - icept).abs() < 1e-13 && (x[(1, 0)] - slope).abs() < 1e-13);
        let r2: f64 = (0..7)
            .map(|i| (icept + slope * xs[i] - ys[i]).powi(2))
            .sum();
        let b2: f64 = ys.iter().map(|y| y * y).sum();
        assert!((residual - (r2 / b2).sqrt()).abs() < 1e-13);
    }

    #[test]
    fn lstsq_of_a_rank_deficient_system_is_the_minimum_norm_solution() {
        // two equal columns: x1 + x2 = 1 in least squares, min norm x1 = x2 = 1/2
        let a = Mat::from_fn(4, 2, |_, _| 1.0);
        let b = Mat::from_fn(4, 1, |_, _| 1.0);
        let (x, residual) = lstsq(a.as_ref(), b.as_ref(), 1e-12).unwrap();
        assert!((x[(0, 0)] - 0.5).abs() < 1e-14 && (x[(1, 0)] - 0.5).abs() < 1e-14);
        assert!(residual < 1e-14);
    }

    #[test]
    fn companion_eigenvalues_are_the_polynomial_roots() {
        // roots: a repeated pair 0.9 e^{±0.3i} (twice), 0.5, -0.7
        let pair = faer::c64::new(0.9 * 0.3f64.cos(), 0.9 * 0.3f64.sin());
        let roots = [
            pair,
            pair.conj(),
            pair,
            pair.conj(),
            0.5.into(),
            (-0.7).into(),
        ];
        // coefficients of Π (z - r), lowest first
        let mut c = vec![faer::c64::new(1.0, 0.0)];
        for r in roots {
            let mut next = vec![faer::c64::new(0.0, 0.0); c.len() + 1];
            for (k, ck) in c.iter().enumerate() {
                next[k + 1] += ck;
                next[k] -= ck * r;
            }
            c = next;
        }
        let p = roots.len();
        let comp = Mat::from_fn(p, p, |i, j| {
            if i + 1 == j {
                1.0
            } else if i == p - 1 {
                -c[j].re
            } else {
                0.0
            }
        });
        let found = eigenvalues(comp.as_ref()).unwrap();
        assert_eq!(found.len(), p);
        for (k, r) in roots.into_iter().enumerate() {
            let nearest = found
                .iter()
                .map(|z| (z - r).norm())
                .fold(f64::INFINITY, f64::min);
            // a double root moves by O(√(ε κ)) under round-off (1e-7 here),
            // a simple one by O(ε κ)
            let tol = if k < 4 { 1e-6 } else { 1e-12 };
            assert!(nearest < tol, "root {r}: nearest {nearest:e}");
        }
    }

    #[test]
    fn rank_counts_singular_values_above_the_tolerance() {
        let a = Mat::from_fn(5, 5, |i, j| ((i + 1) * (j + 1)) as f64); // rank 1
        assert_eq!(rank(a.as_ref(), 1e-10).unwrap(), 1);
        assert_eq!(rank(Mat::<f64>::identity(4, 4).as_ref(), 1e-10).unwrap(), 4);
    }
}
