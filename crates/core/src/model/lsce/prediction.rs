//! The linear prediction of LSCE (method §6.2, 1–3): the QR factor of the
//! stacked Hankel data, and the physical poles of one model order from the
//! roots of its prediction polynomial.

use super::{IdentifyOptions, LsceError, Pole, lstsq};
use crate::base::linalg;
use faer::{Mat, c64};

/// Responses stacked per QR of the Hankel data ([`hankel_add`]): a few at
/// a time keeps the stacked block small.
pub(super) const HANKEL_CHUNK: usize = 4;

/// The triangular factor `R` of the stacked Hankel matrix with `cols`
/// columns (rows `[g(k), ..., g(k + cols - 1)]`, responses scaled to unit
/// peak), a chunk at a time: stacks the Hankel rows of the (nonzero)
/// responses of `chunk` under the factor `acc` so far and replaces it by
/// the `R` of their QR.
pub(super) fn hankel_add(acc: &mut Mat<f64>, chunk: &[Vec<f64>], len: usize, cols: usize) {
    let rows = len - cols + 1;
    let blocks: Vec<&Vec<f64>> = chunk
        .iter()
        .filter(|d| d.iter().any(|x| *x != 0.0))
        .collect();
    if blocks.is_empty() {
        return;
    }
    let n = acc.nrows() + rows * blocks.len();
    let mut m = Mat::<f64>::zeros(n, cols);
    for i in 0..acc.nrows() {
        for c in 0..cols {
            m[(i, c)] = acc[(i, c)];
        }
    }
    let mut row = acc.nrows();
    for d in blocks {
        let peak = d.iter().fold(0.0_f64, |a, x| a.max(x.abs()));
        for k in 0..rows {
            for c in 0..cols {
                m[(row, c)] = d[k + c] / peak;
            }
            row += 1;
        }
    }
    *acc = linalg::qr_r(m.as_ref());
}

/// Roots of the order-`p` prediction polynomial -> the physical poles
/// (`0 < ξ < max_damping_ratio`) up to the Nyquist frequency.
pub(super) fn poles_of_order(
    rmat: &Mat<f64>,
    p: usize,
    dt: f64,
    opts: &IdentifyOptions,
) -> Result<(Vec<Pole>, f64), LsceError> {
    let k = p.min(rmat.nrows());
    let a_mat = Mat::from_fn(k, p, |i, j| rmat[(i, j)]);
    let b = Mat::from_fn(k, 1, |i, _| -rmat[(i, p)]);
    let (a, _) = lstsq(a_mat.as_ref(), b.as_ref(), 1e-13)?;
    // the residual over the whole stacked system: `R` keeps the part of `b`
    // outside the span of `A` in its rows below `k` (none when `k = p`)
    let whole = |i: usize| {
        let fit: f64 = (0..p.min(rmat.ncols()))
            .map(|j| rmat[(i, j)] * a[(j, 0)])
            .sum();
        fit + rmat[(i, p)]
    };
    let rows = rmat.nrows().min(p + 1);
    let num: f64 = (0..rows).map(|i| whole(i).powi(2)).sum::<f64>().sqrt();
    let den: f64 = (0..rows).map(|i| rmat[(i, p)].powi(2)).sum::<f64>().sqrt();
    let residual = if den > 0.0 { num / den } else { 0.0 };
    let mut comp = Mat::<f64>::zeros(p, p);
    for i in 0..p - 1 {
        comp[(i, i + 1)] = 1.0;
    }
    for l in 0..p {
        comp[(p - 1, l)] = -a[(l, 0)];
    }
    let roots = linalg::eigenvalues(comp.as_ref())?;
    let mut poles: Vec<Pole> = roots
        .iter()
        .filter(|z| z.im > 0.0 && z.norm() > 0.0)
        .map(|z: &c64| {
            let s = c64::new(z.norm().ln(), z.im.atan2(z.re)) / dt;
            let omega = s.norm();
            Pole {
                omega,
                xi: -s.re / omega,
            }
        })
        .filter(|pl| pl.xi > 0.0 && pl.xi < opts.max_damping_ratio)
        .collect();
    poles.sort_by(|x, y| x.omega.total_cmp(&y.omega));
    Ok((poles, residual))
}
