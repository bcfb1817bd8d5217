//! Fidelity of a modal model against the source of its Green functions: the
//! relative L2 error of the complex receptance matrix `G(ω)` over a band,
//!
//! ```text
//! e = sqrt( Σ_f Σ_ij |G_ij(f) - Ĝ_ij(f)|²  /  Σ_f Σ_ij |G_ij(f)|² )
//! ```
//!
//! over all `P × P` pairs and `n` frequencies at the mid-points of `n` equal
//! slices of the band (a mid-point rule for the L2 norms over frequency).
//! The reference is any [`GreenMatrix`]: the ring tyre's modal model with
//! all its orders ([`tirecontact_core::model::ring::RingParams::modal_model`]), a modal model,
//! or `G(ω)` sampled on a grid ([`SampledGreen`]). Helpers build the edited
//! models a researcher compares: a mode removed, a mode detuned.

use tirecontact_core::base::modal::Mode;
use tirecontact_core::base::modal::{Complex, ModalModel};

/// A `P × P` receptance matrix `G_ij(f)` (m/N) known at any frequency.
pub trait GreenMatrix {
    fn num_points(&self) -> usize;
    /// `G_ij` at `freq_hz` (m/N): displacement at `i` per unit harmonic force at `j`.
    fn receptance(&self, i: usize, j: usize, freq_hz: f64) -> Complex;
}

impl GreenMatrix for ModalModel {
    fn num_points(&self) -> usize {
        self.num_points
    }
    fn receptance(&self, i: usize, j: usize, freq_hz: f64) -> Complex {
        self.frequency_response(i, j, freq_hz)
    }
}

/// `G(ω)` given on a frequency grid (measured, or from another model):
/// linear interpolation between grid points, the end values outside.
#[derive(Debug, Clone, PartialEq)]
pub struct SampledGreen {
    pub num_points: usize,
    /// Increasing frequencies (Hz).
    pub freq_hz: Vec<f64>,
    /// Per frequency, `G` row-major `P × P` (m/N).
    pub g: Vec<Vec<Complex>>,
}

impl SampledGreen {
    /// Samples `source` at `freq_hz`.
    pub fn sample(source: &dyn GreenMatrix, freq_hz: &[f64]) -> Self {
        let p = source.num_points();
        SampledGreen {
            num_points: p,
            freq_hz: freq_hz.to_vec(),
            g: freq_hz
                .iter()
                .map(|&f| {
                    (0..p * p)
                        .map(|ij| source.receptance(ij / p, ij % p, f))
                        .collect()
                })
                .collect(),
        }
    }
}

impl GreenMatrix for SampledGreen {
    fn num_points(&self) -> usize {
        self.num_points
    }
    fn receptance(&self, i: usize, j: usize, freq_hz: f64) -> Complex {
        let ij = i * self.num_points + j;
        let f = &self.freq_hz;
        if f.is_empty() {
            return Complex::default();
        }
        let k = f.partition_point(|&x| x < freq_hz);
        if k == 0 {
            return self.g[0][ij];
        }
        if k == f.len() {
            return self.g[k - 1][ij];
        }
        if f[k] == freq_hz {
            return self.g[k][ij];
        }
        let s = (freq_hz - f[k - 1]) / (f[k] - f[k - 1]);
        let (a, b) = (self.g[k - 1][ij], self.g[k][ij]);
        Complex {
            re: a.re + s * (b.re - a.re),
            im: a.im + s * (b.im - a.im),
        }
    }
}

/// Errors of a fidelity computation.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FidelityError {
    #[error("fidelity band {lo_hz} .. {hi_hz} Hz: expected 0 <= low < high, finite")]
    Band { lo_hz: f64, hi_hz: f64 },
    #[error("fidelity: {n} frequencies, expected at least 1")]
    Frequencies { n: usize },
    #[error("fidelity: reference has {reference} points, model {model}: expected the same points")]
    Points { reference: usize, model: usize },
    #[error("fidelity: mode {k} of {len} modes does not exist")]
    NoMode { k: usize, len: usize },
}

/// `n` mid-point frequencies of `n` equal slices of `[lo_hz, hi_hz]` (Hz).
pub fn band_frequencies(lo_hz: f64, hi_hz: f64, n: usize) -> Result<Vec<f64>, FidelityError> {
    if !(lo_hz.is_finite() && hi_hz.is_finite() && lo_hz >= 0.0 && hi_hz > lo_hz) {
        return Err(FidelityError::Band { lo_hz, hi_hz });
    }
    if n == 0 {
        return Err(FidelityError::Frequencies { n });
    }
    Ok((0..n)
        .map(|q| lo_hz + (hi_hz - lo_hz) * (q as f64 + 0.5) / n as f64)
        .collect())
}

/// The relative L2 error of `model` against `reference` at `freq_hz`, in
/// total and per pair `(i, j)` (row-major `P × P`, each relative to the
/// reference's norm of that pair).
#[derive(Debug, Clone, PartialEq)]
pub struct Fidelity {
    /// All pairs together (-).
    pub relative_l2: f64,
    /// Per pair (-), row-major `P × P`.
    pub per_pair: Vec<f64>,
}

/// Relative L2 error of `model` against `reference` over `freq_hz` (see the
/// module text). Zero when the reference is zero and so is the model.
pub fn relative_l2_error(
    reference: &dyn GreenMatrix,
    model: &dyn GreenMatrix,
    freq_hz: &[f64],
) -> Result<Fidelity, FidelityError> {
    let p = reference.num_points();
    if model.num_points() != p {
        return Err(FidelityError::Points {
            reference: p,
            model: model.num_points(),
        });
    }
    if freq_hz.is_empty() {
        return Err(FidelityError::Frequencies { n: 0 });
    }
    let mut num = vec![0.0; p * p];
    let mut den = vec![0.0; p * p];
    for &f in freq_hz {
        for i in 0..p {
            for j in 0..p {
                let a = reference.receptance(i, j, f);
                let b = model.receptance(i, j, f);
                let (dr, di) = (a.re - b.re, a.im - b.im);
                num[i * p + j] += dr * dr + di * di;
                den[i * p + j] += a.re * a.re + a.im * a.im;
            }
        }
    }
    let ratio = |n: f64, d: f64| {
        if d > 0.0 {
            (n / d).sqrt()
        } else if n > 0.0 {
            f64::INFINITY
        } else {
            0.0
        }
    };
    Ok(Fidelity {
        relative_l2: ratio(num.iter().sum(), den.iter().sum()),
        per_pair: num.iter().zip(&den).map(|(&n, &d)| ratio(n, d)).collect(),
    })
}

/// The modes without mode `k`.
pub fn without_mode(modes: &[Mode], k: usize) -> Result<Vec<Mode>, FidelityError> {
    if k >= modes.len() {
        return Err(FidelityError::NoMode {
            k,
            len: modes.len(),
        });
    }
    let mut m = modes.to_vec();
    m.remove(k);
    Ok(m)
}

/// The modes with mode `k`'s frequency multiplied by `freq_factor` and its
/// damping ratio set to `damping_ratio` (when given).
pub fn detuned(
    modes: &[Mode],
    k: usize,
    freq_factor: f64,
    damping_ratio: Option<f64>,
) -> Result<Vec<Mode>, FidelityError> {
    if k >= modes.len() {
        return Err(FidelityError::NoMode {
            k,
            len: modes.len(),
        });
    }
    let mut m = modes.to_vec();
    m[k].freq_hz *= freq_factor;
    if let Some(z) = damping_ratio {
        m[k].damping_ratio = z;
    }
    Ok(m)
}

/// What dropping each mode costs: the error against `reference` of the
/// model without mode `k`, for every `k` (-).
pub fn removal_costs(
    reference: &dyn GreenMatrix,
    modes: &[Mode],
    freq_hz: &[f64],
) -> Result<Vec<f64>, FidelityError> {
    let p = reference.num_points();
    (0..modes.len())
        .map(|k| {
            let m = ModalModel::from_modes(&without_mode(modes, k)?, p);
            Ok(relative_l2_error(reference, &m, freq_hz)?.relative_l2)
        })
        .collect()
}

/// `|G_ij(f)|` (m/N) of a matrix on a grid, for plotting beside another.
pub fn magnitude_curve(
    g: &dyn GreenMatrix,
    i: usize,
    j: usize,
    freq_hz: &[f64],
) -> Vec<(f64, f64)> {
    freq_hz
        .iter()
        .map(|&f| (f, g.receptance(i, j, f).norm()))
        .collect()
}
