//! The residues of LSCE (method §6.2, 4–5, and §6.4): the real modal basis
//! of a set of poles, the residues fitted on the responses, the model kept
//! at the chosen order and its fit report.

use super::dtft::dtft_magnitudes;
use super::{
    FitReport, IdentifyOptions, LeastSquaresResiduals, LsceError, Pole, ResponseFit, Responses,
    lstsq,
};
use crate::base::modal::unit_impulse;
use faer::Mat;

/// Sampled `h_k` (and, with `with_cos`, `e^{-ξωt} cos(ω_d t)`) per pole.
pub(super) fn basis(poles: &[Pole], dt: f64, len: usize, with_cos: bool) -> Mat<f64> {
    let k = poles.len();
    let cols = if with_cos { 2 * k } else { k };
    Mat::from_fn(len, cols, |n, c| {
        let t = n as f64 * dt;
        let pl = poles[c % k];
        if c < k {
            unit_impulse(pl.omega, pl.xi, t).0
        } else {
            let wd = pl.omega * ((1.0 - pl.xi) * (1.0 + pl.xi)).sqrt();
            (-pl.xi * pl.omega * t).exp() * (wd * t).cos()
        }
    })
}

pub(super) fn data_matrix(r: &Responses, len: usize) -> Mat<f64> {
    Mat::from_fn(len, r.data.len(), |n, c| r.data[c][n])
}

/// Relative L2 error `||fit - data|| / ||data||` per column and overall.
pub(super) fn time_errors(fit: &Mat<f64>, data: &Mat<f64>) -> (Vec<f64>, f64) {
    let (mut num, mut den) = (0.0, 0.0);
    let per = (0..data.ncols())
        .map(|c| {
            let e = (fit.col(c) - data.col(c)).squared_norm_l2();
            let d = data.col(c).squared_norm_l2();
            num += e;
            den += d;
            if d > 0.0 { (e / d).sqrt() } else { e.sqrt() }
        })
        .collect();
    (per, if den > 0.0 { (num / den).sqrt() } else { 0.0 })
}

pub(super) fn mac(a: &[f64], b: &[f64]) -> f64 {
    let ab: f64 = a.iter().zip(b).map(|(x, y)| x * y).sum();
    let aa: f64 = a.iter().map(|x| x * x).sum();
    let bb: f64 = b.iter().map(|x| x * x).sum();
    if aa > 0.0 && bb > 0.0 {
        ab * ab / (aa * bb)
    } else {
        0.0
    }
}

#[derive(Debug)]
pub(super) struct OrderFit {
    pub(super) poles: Vec<Pole>,
    /// Residue per pole and response (K × responses).
    pub(super) residues: Mat<f64>,
    pub(super) time_error: f64,
    /// Relative residual of the residues' least squares (-).
    pub(super) residual: f64,
}

/// Row `r` of `m`, as a vector.
pub(super) fn row(m: &Mat<f64>, r: usize) -> Vec<f64> {
    (0..m.ncols()).map(|c| m[(r, c)]).collect()
}

/// `‖row r of m‖₂`.
pub(super) fn row_norm(m: &Mat<f64>, r: usize) -> f64 {
    m.row(r).norm_l2()
}

/// The rows `rows` of `m`, in that order.
pub(super) fn select_rows(m: &Mat<f64>, rows: &[usize]) -> Mat<f64> {
    Mat::from_fn(rows.len(), m.ncols(), |r, c| m[(rows[r], c)])
}

/// Residues by least squares through the normal equations (cheap, used for
/// the diagram) or the SVD of the basis (`accurate`).
pub(super) fn fit_order(
    poles: Vec<Pole>,
    data: &Mat<f64>,
    dt: f64,
    accurate: bool,
) -> Result<OrderFit, LsceError> {
    let len = data.nrows();
    if poles.is_empty() {
        let zero = Mat::zeros(len, data.ncols());
        return Ok(OrderFit {
            poles,
            residues: Mat::zeros(0, data.ncols()),
            time_error: time_errors(&zero, data).1,
            residual: 1.0,
        });
    }
    let b = basis(&poles, dt, len, false);
    let residues = if accurate {
        lstsq(b.as_ref(), data.as_ref(), 1e-14)?.0
    } else {
        let gram = b.transpose() * &b;
        let rhs = b.transpose() * data;
        lstsq(gram.as_ref(), rhs.as_ref(), 1e-15)?.0
    };
    let fit = &b * &residues;
    let time_error = time_errors(&fit, data).1;
    Ok(OrderFit {
        poles,
        // the residual of `b x = data` (the normal equations' own is not
        // the misfit)
        residual: time_error,
        time_error,
        residues,
    })
}

/// The model at the chosen order and what the real form of its residues
/// leaves out.
#[derive(Debug)]
pub(super) struct KeptModel {
    /// The kept poles and their residues; the time error and residual of
    /// the fit with every physical pole.
    pub(super) fit: OrderFit,
    /// Per kept mode: the discarded `cos` part of its complex residue over
    /// the kept `sin` part.
    pub(super) discarded_ratio: Vec<f64>,
    /// Relative residual of the complex-residue fit (-).
    pub(super) complex_residual: f64,
}

/// The model of the chosen order's physical poles `all` (method §6.2, 4–5):
/// residues fitted with every one of them, then the in-band poles with a
/// share of the responses kept (a spurious pole fitted to round-off has
/// none); `None` when no pole is kept. A second fit, with the companion
/// `cos` terms, gives the part of each complex residue that the real form
/// discards.
pub(super) fn kept_model(
    all: Vec<Pole>,
    data: &Mat<f64>,
    dt: f64,
    data_norm: f64,
    opts: &IdentifyOptions,
) -> Result<Option<KeptModel>, LsceError> {
    let len = data.nrows();
    let n_all = all.len();
    // complex-residue fit (sin and cos parts): the discarded part
    let (full, complex_residual) =
        lstsq(basis(&all, dt, len, true).as_ref(), data.as_ref(), 1e-14)?;
    let fit_all = fit_order(all, data, dt, true)?;
    let b_all = basis(&fit_all.poles, dt, len, false);
    let kept: Vec<usize> = (0..n_all)
        .filter(|&c| {
            let share = b_all.col(c).norm_l2() * row_norm(&fit_all.residues, c);
            fit_all.poles[c].in_band(opts) && share >= opts.min_contribution * data_norm
        })
        .collect();
    if kept.is_empty() {
        return Ok(None);
    }
    let discarded_ratio = kept
        .iter()
        .map(|&c| {
            let pl = fit_all.poles[c];
            let wd = pl.omega * ((1.0 - pl.xi) * (1.0 + pl.xi)).sqrt();
            let sin_part = row_norm(&full, c) / wd;
            let cos_part = row_norm(&full, n_all + c);
            if sin_part > 0.0 {
                cos_part / sin_part
            } else {
                f64::INFINITY
            }
        })
        .collect();
    let fit = OrderFit {
        poles: kept.iter().map(|&c| fit_all.poles[c]).collect(),
        residues: select_rows(&fit_all.residues, &kept),
        time_error: fit_all.time_error,
        residual: fit_all.residual,
    };
    Ok(Some(KeptModel {
        fit,
        discarded_ratio,
        complex_residual,
    }))
}

/// The fit report of the kept modes `fit` (method §6.4): the time errors
/// of the kept modes and of every physical pole, and the `|G|` errors over
/// 200 frequencies across the band, overall and per response.
pub(super) fn fit_report(
    r: &Responses,
    fit: &OrderFit,
    data: &Mat<f64>,
    dt: f64,
    opts: &IdentifyOptions,
    least_squares: LeastSquaresResiduals,
) -> FitReport {
    let time_error_all_poles = fit.time_error;
    let fitted = &basis(&fit.poles, dt, data.nrows(), false) * &fit.residues;
    let (per_time, time_error) = time_errors(&fitted, data);
    let nf = 200;
    let (lo, hi) = opts.band_hz;
    let freqs: Vec<f64> = (0..nf)
        .map(|q| lo + (hi - lo) * (q as f64 + 0.5) / nf as f64)
        .collect();
    let gd = dtft_magnitudes(data, dt, &freqs);
    let gf = dtft_magnitudes(&fitted, dt, &freqs);
    let (per_mag, magnitude_error) = time_errors(&gf, &gd);
    let per_response = r
        .pairs
        .iter()
        .enumerate()
        .map(|(c, &pair)| ResponseFit {
            pair,
            time_error: per_time[c],
            magnitude_error: per_mag[c],
        })
        .collect();
    FitReport {
        time_error,
        time_error_all_poles,
        magnitude_error,
        per_response,
        least_squares,
    }
}
