//! LSCE identification (least-squares complex exponential, method §6).
//!
//! From impulse responses `g_r(k dt)` sampled at `dt`, the linear prediction
//! `g_r(k + p) + Σ_{l<p} a_l g_r(k + l) = 0` of order `p = 2M` (`M` pole
//! pairs) is stacked over all responses (each scaled to unit peak) and solved
//! by least squares. One QR factor of the Hankel matrix with `2 M_max + 1`
//! columns serves every order (the first `p + 1` columns of `R` are the order
//! `p` system). The roots `z` of `z^p + Σ a_l z^l` (eigenvalues of the
//! companion matrix, [`crate::base::linalg::eigenvalues`]) give the poles `s = ln(z) / dt`;
//! the physical ones are conjugate pairs with `Re(s) < 0` (`ξ > 0`, method §6's
//! sign check) inside the band. Residues are fitted by least squares on the
//! responses with the real modal form of method §2, `g = Σ A_k h_k`; a second fit
//! with the companion `e^{-ξωt} cos(ω_d t)` terms measures the part of the
//! complex residues that the real form discards (reported per mode).
//!
//! The stabilisation diagram repeats this for `M = 1..=M_max`; a pole is
//! stable when the previous order has a pole within the frequency, damping and
//! residue-MAC tolerances. Residues are fitted with every physical pole up to
//! the Nyquist frequency (so out-of-band modes keep their share of the
//! responses); the model keeps the in-band ones whose share of the responses
//! is at least `min_contribution`. The model order is the given
//! one or, automatically, chosen with the diagram: among the orders whose
//! in-band model's time-domain fit error is within `order_tolerance` of the
//! best, the smallest whose kept poles persist (`choose_order`).

use crate::base::linalg::{self, LinalgError};
use crate::base::modal::Mode;
use crate::model::stability::{DiagramOrder, PersistenceRule};
use faer::{Mat, MatRef};
use std::f64::consts::TAU;

mod dtft;
mod fit;
mod options;
mod order;
mod picked;
mod prediction;
mod run;
pub use options::IdentifyOptions;
pub use picked::{modes_of_poles, response_magnitudes};
pub use run::LsceRun;

/// Sampled impulse responses `g_ij(k dt)` (m/(N·s)) of `num_points` points.
#[derive(Debug, Clone, PartialEq)]
pub struct Responses {
    /// Sample interval (s).
    pub dt_s: f64,
    /// Number of points `P`.
    pub num_points: usize,
    /// `(i, j)` of each response: receiving point, loaded point.
    pub pairs: Vec<(usize, usize)>,
    /// One sample vector per pair, all of the same length, `k = 0..len`.
    pub data: Vec<Vec<f64>>,
}

/// Errors of the identification.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LsceError {
    #[error("LSCE: {0}")]
    Input(String),
    #[error(
        "LSCE: no physical pole pair with a share of the responses in the band {lo_hz}..{hi_hz} Hz at model order {order} (raise the order or widen the band)"
    )]
    NoModes {
        lo_hz: f64,
        hi_hz: f64,
        order: usize,
    },
    #[error("LSCE: {0}")]
    Numerical(#[from] LinalgError),
    /// `lowest_source_hz` is NaN when the source's modes are not known (a
    /// measured file): the message then names none.
    #[error("{}", poor_fit(*magnitude_error, *limit, *lo_hz, *hi_hz, *lowest_source_hz))]
    PoorFit {
        magnitude_error: f64,
        limit: f64,
        lo_hz: f64,
        hi_hz: f64,
        lowest_source_hz: f64,
    },
}

/// The message of [`LsceError::PoorFit`].
fn poor_fit(magnitude_error: f64, limit: f64, lo_hz: f64, hi_hz: f64, lowest_hz: f64) -> String {
    let head = format!(
        "LSCE: the identified modes miss the source: |G| error {magnitude_error:.3} over {lo_hz}..{hi_hz} Hz (expected below {limit})"
    );
    if lowest_hz.is_nan() {
        format!(
            "{head}: check the band (identification.band_hz) against the data's modes, or fit a UFF file of FRFs in the frequency domain (`tirecontact identify --data FILE`)"
        )
    } else {
        format!(
            "{head}; the source's lowest mode is at {lowest_hz:.1} Hz: move the band (identification.band_hz) to cover the source's modes"
        )
    }
}

/// The time-domain fit errors of one model order of the stabilisation
/// diagram (method §6.3).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OrderErrors {
    /// Model order `M` (pole pairs).
    pub order: usize,
    /// Relative L2 error in time over all responses, with every physical
    /// pole of this order (-).
    pub time_error: f64,
    /// The same with the in-band poles only (what the model keeps) (-).
    pub band_time_error: f64,
}

/// Fit of one response.
#[derive(Debug, Clone, PartialEq)]
pub struct ResponseFit {
    pub pair: (usize, usize),
    /// `||g_fit - g|| / ||g||` over the samples (-).
    pub time_error: f64,
    /// `|| |G_fit| - |G| || / || |G| ||` over the band, `G` the DTFT of the
    /// samples (-).
    pub magnitude_error: f64,
}

/// Fit report (method §6).
#[derive(Debug, Clone, PartialEq)]
pub struct FitReport {
    /// Relative L2 error in time over all responses of the kept (in-band)
    /// modes (-). Out-of-band content of the responses counts as error.
    pub time_error: f64,
    /// The same with every physical pole of the chosen order, out-of-band
    /// ones included (the error of the LSCE fit itself) (-).
    pub time_error_all_poles: f64,
    /// Relative L2 error of `|G(ω)|` over the band, all responses (-).
    pub magnitude_error: f64,
    pub per_response: Vec<ResponseFit>,
    /// Relative residuals `‖A x − b‖ / ‖b‖` of the least-squares solves
    /// behind the model (-).
    pub least_squares: LeastSquaresResiduals,
}

/// Relative residuals `‖A x − b‖_F / ‖b‖_F` of the least-squares solves of
/// an identification at the chosen order (-). The prediction's is the
/// misfit of the linear prediction on the Hankel data; the residues' the
/// misfit of the real modal form on the responses with every physical pole.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct LeastSquaresResiduals {
    /// Linear prediction `g(k + p) + Σ a_l g(k + l) = 0` (-).
    pub prediction: f64,
    /// Residues of the real modal form, every physical pole (-).
    pub residues: f64,
    /// Residues of the complex form (sin and cos parts) (-).
    pub complex_residues: f64,
}

/// Result of an identification.
#[derive(Debug, Clone, PartialEq)]
pub struct Identification {
    /// Identified modes, by frequency, with symmetric P×P residues (1/kg).
    pub modes: Vec<Mode>,
    /// The model order used `M`.
    pub model_order: usize,
    /// The model order the options gave (`None`: chosen from the diagram).
    pub given_order: Option<usize>,
    /// Per mode: stable (frequency, damping and MAC) against order `M - 1`.
    pub stable: Vec<bool>,
    /// Per mode: norm of the discarded `cos` part of the complex residue over
    /// the norm of the kept `sin` part (`b_k` vs `A_k / ω_d`) (-).
    pub discarded_ratio: Vec<f64>,
    /// The stabilisation diagram: the in-band poles of every order.
    pub diagram: Vec<DiagramOrder>,
    /// The time errors of every order of the diagram, in its order.
    pub order_errors: Vec<OrderErrors>,
    /// The rule that keeps a pole of the diagram as a mode
    /// ([`crate::model::stability::keep`]), with the options' tolerance.
    pub persistence: PersistenceRule,
    pub report: FitReport,
}

/// A relative fit error below which every order counts as exact (automatic
/// order selection).
pub const EXACT_FIT: f64 = 1e-6;

/// A continuous-time pole: `ω` (rad/s) and `ξ`.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Pole {
    omega: f64,
    xi: f64,
}

impl Pole {
    fn freq_hz(&self) -> f64 {
        self.omega / TAU
    }
    fn in_band(&self, opts: &IdentifyOptions) -> bool {
        let f = self.freq_hz();
        f >= opts.band_hz.0 && f <= opts.band_hz.1
    }
}

fn check_input(r: &Responses) -> Result<usize, LsceError> {
    if r.data.is_empty() || r.data.len() != r.pairs.len() {
        return Err(LsceError::Input(format!(
            "{} responses for {} pairs: expected at least one, one per pair",
            r.data.len(),
            r.pairs.len()
        )));
    }
    if !(r.dt_s.is_finite() && r.dt_s > 0.0) {
        return Err(LsceError::Input(format!(
            "dt_s = {}: expected a sample interval > 0 s",
            r.dt_s
        )));
    }
    let len = r.data[0].len();
    for (k, (d, &(i, j))) in r.data.iter().zip(&r.pairs).enumerate() {
        if d.len() != len {
            return Err(LsceError::Input(format!(
                "response {k} has {} samples, response 0 has {len}",
                d.len()
            )));
        }
        if i >= r.num_points || j >= r.num_points {
            return Err(LsceError::Input(format!(
                "pair ({i}, {j}) names a point >= P = {}",
                r.num_points
            )));
        }
        if let Some(x) = d.iter().find(|x| !x.is_finite()) {
            return Err(LsceError::Input(format!(
                "response {k} holds a non-finite sample {x}"
            )));
        }
    }
    Ok(len)
}

/// Least squares by the checked SVD of [`linalg::lstsq`]: the solution and
/// its relative residual.
fn lstsq(a: MatRef<'_, f64>, b: MatRef<'_, f64>, rcond: f64) -> Result<(Mat<f64>, f64), LsceError> {
    Ok(linalg::lstsq(a, b, rcond)?)
}

/// Identifies a modal model from sampled impulse responses (method §6).
pub fn identify(r: &Responses, opts: &IdentifyOptions) -> Result<Identification, LsceError> {
    LsceRun::new(r.clone(), opts)?.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A poor fit of a ring names the ring's lowest mode; of a file (its
    /// modes unknown), no mode: an identified pole is no hint.
    #[test]
    fn a_poor_fit_names_the_sources_lowest_mode_only_when_known() {
        let e = |lowest| {
            LsceError::PoorFit {
                magnitude_error: 0.42,
                limit: 0.3,
                lo_hz: 0.0,
                hi_hz: 500.0,
                lowest_source_hz: lowest,
            }
            .to_string()
        };
        let ring = e(12.34);
        assert!(
            ring.contains("0.420") && ring.contains("lowest mode is at 12.3 Hz"),
            "{ring}"
        );
        let file = e(f64::NAN);
        assert!(
            file.contains("0.420") && !file.contains("lowest mode") && file.contains("--data"),
            "{file}"
        );
    }
}
