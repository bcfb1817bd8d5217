//! The residues of LSCF's poles (method §6.5.2–6.5.3): the complex LSFD
//! fit with residual terms, the real modal constants of the contact model
//! and the Gauss-Newton refinement of the poles.

use super::{FitError, FrfSet, Pole, check, omegas};
use crate::base::linalg;
use faer::{Mat, c64};
use std::f64::consts::TAU;

/// Relative L2 error `‖H_fit − H‖ / ‖H‖` over the band, all pairs (-).
pub fn relative_error(data: &[Vec<c64>], fit: &[Vec<c64>]) -> f64 {
    let (mut num, mut den) = (0.0, 0.0);
    for (d, f) in data.iter().zip(fit) {
        for (a, b) in d.iter().zip(f) {
            num += (a - b).norm_sqr();
            den += a.norm_sqr();
        }
    }
    if den > 0.0 { (num / den).sqrt() } else { 0.0 }
}

/// Least squares of complex columns `cols[c][f]` with real unknowns against
/// every pair's data (real and imaginary parts stacked, columns scaled to
/// unit norm): the unknowns `[c][pair]` and the relative residual.
fn real_lstsq(cols: &[Vec<c64>], data: &[Vec<c64>]) -> Result<(Vec<Vec<f64>>, f64), FitError> {
    let nf = cols[0].len();
    let norms: Vec<f64> = cols
        .iter()
        .map(|c| {
            let n = c.iter().map(|v| v.norm_sqr()).sum::<f64>().sqrt();
            if n > 0.0 { n } else { 1.0 }
        })
        .collect();
    let a = Mat::from_fn(2 * nf, cols.len(), |r, c| {
        let v = cols[c][r % nf];
        (if r < nf { v.re } else { v.im }) / norms[c]
    });
    let b = Mat::from_fn(2 * nf, data.len(), |r, k| {
        let v = data[k][r % nf];
        if r < nf { v.re } else { v.im }
    });
    let (x, residual) = linalg::lstsq(a.as_ref(), b.as_ref(), 1e-13)?;
    let out = (0..cols.len())
        .map(|c| (0..data.len()).map(|k| x[(c, k)] / norms[c]).collect())
        .collect();
    Ok((out, residual))
}

/// A complex LSFD fit (method §6.5.2): residues and residual terms of every
/// pair.
#[derive(Debug, Clone, PartialEq)]
pub struct ComplexFit {
    /// `r[pair][mode]` of `H = (jω)^q [Σ r/(jω−λ) + r*/(jω−λ*) + U + L/(jω)²]`.
    pub residues: Vec<Vec<c64>>,
    /// Lower residual `L[pair]` (N⁻¹·m·s⁻²... in receptance: m/N × (rad/s)²).
    pub lower: Vec<f64>,
    /// Upper residual `U[pair]` (receptance, m/N).
    pub upper: Vec<f64>,
    /// The model at the set's frequencies, `[pair][frequency]`.
    pub fit: Vec<Vec<c64>>,
    /// Relative L2 error over the band, all pairs (-).
    pub error: f64,
}

/// LSFD of `poles` against every pair of `set` (method §6.5.2, eq. LSFD-1):
/// real unknowns `Re r_k`, `Im r_k`, `U`, `L` per pair.
pub fn lsfd(set: &FrfSet, poles: &[Pole]) -> Result<ComplexFit, FitError> {
    check(set)?;
    let w = omegas(set);
    let q = set.ordinate;
    let mut cols: Vec<Vec<c64>> = Vec::with_capacity(2 * poles.len() + 2);
    for pole in poles {
        let lam = pole.lambda();
        let (b, c): (Vec<c64>, Vec<c64>) = w
            .iter()
            .map(|&om| {
                let jw = c64::new(0.0, om);
                let g = q.factor(om);
                (g / (jw - lam), g / (jw - lam.conj()))
            })
            .unzip();
        cols.push(b.iter().zip(&c).map(|(x, y)| x + y).collect());
        cols.push(
            b.iter()
                .zip(&c)
                .map(|(x, y)| c64::new(0.0, 1.0) * (x - y))
                .collect(),
        );
    }
    cols.push(w.iter().map(|&om| q.factor(om)).collect());
    cols.push(
        w.iter()
            .map(|&om| {
                let jw = c64::new(0.0, om);
                q.factor(om) / (jw * jw)
            })
            .collect(),
    );
    let (x, _) = real_lstsq(&cols, &set.h)?;
    let k = poles.len();
    let np = set.pairs.len();
    let residues: Vec<Vec<c64>> = (0..np)
        .map(|pr| {
            (0..k)
                .map(|m| c64::new(x[2 * m][pr], x[2 * m + 1][pr]))
                .collect()
        })
        .collect();
    let upper: Vec<f64> = (0..np).map(|pr| x[2 * k][pr]).collect();
    let lower: Vec<f64> = (0..np).map(|pr| x[2 * k + 1][pr]).collect();
    let fit: Vec<Vec<c64>> = (0..np)
        .map(|pr| {
            (0..w.len())
                .map(|f| (0..cols.len()).map(|c| cols[c][f] * x[c][pr]).sum::<c64>())
                .collect()
        })
        .collect();
    let error = relative_error(&set.h, &fit);
    Ok(ComplexFit {
        residues,
        lower,
        upper,
        fit,
        error,
    })
}

/// A real-mode fit (method §6.5.3): modal constants of every pair, no
/// residual terms.
#[derive(Debug, Clone, PartialEq)]
pub struct RealFit {
    /// `A[pair][mode]` (1/kg) of `H = (jω)^q Σ A/(ω_k² − ω² + 2jξ_kω_kω)`.
    pub constants: Vec<Vec<f64>>,
    pub fit: Vec<Vec<c64>>,
    /// Relative L2 error over the band, all pairs (-).
    pub error: f64,
}

/// The unit-mass receptance `1/(ω_k² − ω² + 2jξ_kω_kω)` times `(jω)^q`.
fn real_column(set: &FrfSet, freq_hz: f64, damping_ratio: f64) -> Vec<c64> {
    let wk = TAU * freq_hz;
    omegas(set)
        .iter()
        .map(|&om| {
            set.ordinate.factor(om) / c64::new(wk * wk - om * om, 2.0 * damping_ratio * wk * om)
        })
        .collect()
}

/// Real modal constants of `poles` against every pair of `set`, least
/// squares over the band without residual terms (eq. LSFD-2).
pub fn real_modes(set: &FrfSet, poles: &[Pole]) -> Result<RealFit, FitError> {
    check(set)?;
    if poles.is_empty() {
        let fit = vec![vec![c64::new(0.0, 0.0); set.freq_hz.len()]; set.pairs.len()];
        return Ok(RealFit {
            constants: vec![Vec::new(); set.pairs.len()],
            error: relative_error(&set.h, &fit),
            fit,
        });
    }
    let cols: Vec<Vec<c64>> = poles
        .iter()
        .map(|p| real_column(set, p.freq_hz, p.damping_ratio))
        .collect();
    let (x, _) = real_lstsq(&cols, &set.h)?;
    let constants: Vec<Vec<f64>> = (0..set.pairs.len())
        .map(|pr| (0..poles.len()).map(|m| x[m][pr]).collect())
        .collect();
    let fit = synthesise_real(set, poles, &constants);
    let error = relative_error(&set.h, &fit);
    Ok(RealFit {
        constants,
        fit,
        error,
    })
}

/// `H[pair][f] = (jω)^q Σ_k A[pair][k] / (ω_k² − ω² + 2jξ_kω_kω)`.
pub fn synthesise_real(set: &FrfSet, poles: &[Pole], constants: &[Vec<f64>]) -> Vec<Vec<c64>> {
    let cols: Vec<Vec<c64>> = poles
        .iter()
        .map(|p| real_column(set, p.freq_hz, p.damping_ratio))
        .collect();
    constants
        .iter()
        .map(|a| {
            (0..set.freq_hz.len())
                .map(|f| cols.iter().zip(a).map(|(c, v)| c[f] * v).sum::<c64>())
                .collect()
        })
        .collect()
}

/// Refines the poles by Gauss-Newton on the LSFD residual (variable
/// projection: the residues re-solved at every step; method §6.5.2):
/// `iterations` steps at most, each accepted only when it lowers the
/// error. Returns the refined poles (stability kept) and their fit.
pub fn refine(
    set: &FrfSet,
    poles: &[Pole],
    iterations: usize,
) -> Result<(Vec<Pole>, ComplexFit), FitError> {
    let mut poles = poles.to_vec();
    let mut best = lsfd(set, &poles)?;
    if poles.is_empty() {
        return Ok((poles, best));
    }
    let stack = |fit: &ComplexFit| -> Vec<f64> {
        fit.fit
            .iter()
            .zip(&set.h)
            .flat_map(|(a, b)| a.iter().zip(b).flat_map(|(x, y)| [(x - y).re, (x - y).im]))
            .collect()
    };
    let scale: f64 = set
        .h
        .iter()
        .flatten()
        .map(|v| v.norm_sqr())
        .sum::<f64>()
        .sqrt();
    for _ in 0..iterations {
        let r0 = stack(&best);
        let n = 2 * poles.len();
        // parameters: ln ω_k and ln ξ_k (relative steps)
        let mut jac = Mat::<f64>::zeros(r0.len(), n);
        for k in 0..poles.len() {
            for (c, h) in [(2 * k, 1e-7), (2 * k + 1, 1e-5)] {
                let mut trial = poles.clone();
                if c % 2 == 0 {
                    trial[k].freq_hz *= 1.0 + h;
                } else {
                    trial[k].damping_ratio *= 1.0 + h;
                }
                let r1 = stack(&lsfd(set, &trial)?);
                for (row, (a, b)) in r1.iter().zip(&r0).enumerate() {
                    jac[(row, c)] = (a - b) / (h * scale);
                }
            }
        }
        let rhs = Mat::from_fn(r0.len(), 1, |r, _| -r0[r] / scale);
        let (step, _) = linalg::lstsq(jac.as_ref(), rhs.as_ref(), 1e-12)?;
        let mut improved = false;
        let mut damping = 1.0;
        for _ in 0..6 {
            let mut trial = poles.clone();
            for k in 0..poles.len() {
                let df = (damping * step[(2 * k, 0)]).clamp(-0.02, 0.02);
                let dx = (damping * step[(2 * k + 1, 0)]).clamp(-0.5, 0.5);
                trial[k].freq_hz *= 1.0 + df;
                trial[k].damping_ratio *= 1.0 + dx;
            }
            let fit = lsfd(set, &trial)?;
            if fit.error < best.error {
                poles = trial;
                best = fit;
                improved = true;
                break;
            }
            damping *= 0.5;
        }
        if !improved {
            break;
        }
    }
    // a pole whose fitted term is invisible in the data (on exact data a
    // computational pole can persist through the diagram with a residue
    // at round-off) is no mode: left out, and the rest fitted again
    let norm = scale.max(f64::MIN_POSITIVE);
    let visible: Vec<bool> = (0..poles.len())
        .map(|k| mode_contribution(set, &poles[k], &best.residues, k) >= NEGLIGIBLE_MODE * norm)
        .collect();
    if visible.iter().any(|v| !v) {
        poles = poles
            .into_iter()
            .zip(&visible)
            .filter_map(|(p, &v)| v.then_some(p))
            .collect();
        best = lsfd(set, &poles)?;
    }
    Ok((poles, best))
}

/// Relative size, against the data's L2 norm, below which a fitted pole's
/// own term is no mode ([`refine`]): far below any measurement's noise,
/// far above the round-off of an exact fit.
pub const NEGLIGIBLE_MODE: f64 = 1e-7;

/// The L2 norm over every pair and frequency of each pole's own term in
/// the complex fit `fit` of `poles` (in the set's ordinate): the size of
/// each mode in the data.
pub fn contributions(set: &FrfSet, poles: &[Pole], fit: &ComplexFit) -> Vec<f64> {
    (0..poles.len())
        .map(|k| mode_contribution(set, &poles[k], &fit.residues, k))
        .collect()
}

/// The L2 norm over every pair and frequency of pole `k`'s own term in the
/// complex fit ([`mode_term`]).
fn mode_contribution(set: &FrfSet, pole: &Pole, residues: &[Vec<c64>], k: usize) -> f64 {
    mode_term(set, pole, residues, k)
        .iter()
        .flatten()
        .map(|v| v.norm_sqr())
        .sum::<f64>()
        .sqrt()
}

/// Pole `k`'s own term in a complex fit at every pair and frequency,
/// `(jω)^q [r/(jω−λ) + r*/(jω−λ*)]` with its residues
/// `residues[pair][k]` (`[pair][frequency]`, in the set's ordinate).
pub fn mode_term(set: &FrfSet, pole: &Pole, residues: &[Vec<c64>], k: usize) -> Vec<Vec<c64>> {
    let lam = pole.lambda();
    let w = omegas(set);
    residues
        .iter()
        .map(|r| {
            let r = r[k];
            w.iter()
                .map(|&om| {
                    let jw = c64::new(0.0, om);
                    set.ordinate.factor(om) * (r / (jw - lam) + r.conj() / (jw - lam.conj()))
                })
                .collect()
        })
        .collect()
}
