//! Identification options of LSCE (method §6), as written in a scene's
//! `tyre: Ring(identification: (...))`.

use crate::base::error::FieldError;
use crate::model::stability::{Criteria, Matching, PERSIST, PersistenceRule};
use serde::{Deserialize, Serialize};

/// Identification options (method §6): sampling of the responses, band, model
/// order and stabilisation criteria.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct IdentifyOptions {
    /// Frequency band kept `[f_lo, f_hi]` (Hz), `0 <= f_lo < f_hi < fs/2`.
    /// Default `(0, 500)`.
    pub band_hz: (f64, f64),
    /// Sample rate `fs` of the impulse responses (Hz). Default 4000 Hz. The
    /// responses hold the source's modes up to `fs/2`; LSCE is best
    /// conditioned with `fs` a few times the highest of them (sampled far
    /// above, the roots crowd near `z = 1` and lose digits).
    pub sample_rate_hz: f64,
    /// Length of the impulse responses (s). Default 0.25 s.
    pub duration_s: f64,
    /// Model order `M` (pole pairs; polynomial order `2M`); `None` chooses it
    /// from the stabilisation diagram. Default `None`.
    pub model_order: Option<usize>,
    /// Highest model order of the stabilisation diagram `M_max`, 1..=200.
    /// Default 40.
    pub max_model_order: usize,
    /// Largest damping ratio of a kept pole (-), in (0, 1). Default 0.5.
    pub max_damping_ratio: f64,
    /// Stabilisation: relative frequency tolerance (-). Default 0.01.
    pub stable_freq_tol: f64,
    /// Stabilisation: relative damping tolerance (-). Default 0.05.
    pub stable_damping_tol: f64,
    /// Stabilisation: smallest MAC of the residue vectors (-). Default 0.95.
    pub stable_mac_min: f64,
    /// Automatic order: the orders whose in-band model's fit error is at
    /// most `(1 + order_tolerance)` times the best, plus
    /// [`super::EXACT_FIT`], are near-best; the smallest of them whose kept
    /// poles persist in the stabilisation diagram is chosen (-). Default
    /// 0.05.
    pub order_tolerance: f64,
    /// Smallest share of a kept mode in the responses,
    /// `||h_k|| ||A_k|| / ||g||` over all responses (-), in [0, 1). Default
    /// 1e-6 (drops poles fitted to round-off).
    pub min_contribution: f64,
}

impl Default for IdentifyOptions {
    fn default() -> Self {
        IdentifyOptions {
            band_hz: (0.0, 500.0),
            sample_rate_hz: 4000.0,
            duration_s: 0.25,
            model_order: None,
            max_model_order: 40,
            max_damping_ratio: 0.5,
            stable_freq_tol: 0.01,
            stable_damping_tol: 0.05,
            stable_mac_min: 0.95,
            order_tolerance: 0.05,
            min_contribution: 1e-6,
        }
    }
}

impl IdentifyOptions {
    /// The stabilisation criteria of LSCE (method §6.3): the options'
    /// tolerances, each pole compared with the nearest in frequency of the
    /// order below.
    pub fn stability_criteria(&self) -> Criteria {
        Criteria {
            freq_tol: self.stable_freq_tol,
            damping_tol: self.stable_damping_tol,
            mac_min: self.stable_mac_min,
            matching: Matching::Nearest,
        }
    }

    /// The persistence rule of a mode kept from the stabilisation diagram
    /// (method §6.5.1, shared with the frequency-domain fit): the
    /// frequency tolerance and a run of [`PERSIST`] stable orders.
    pub fn persistence(&self) -> PersistenceRule {
        PersistenceRule {
            freq_tol: self.stable_freq_tol,
            persist: PERSIST,
        }
    }

    /// Time step of the samples (s).
    pub fn dt_s(&self) -> f64 {
        1.0 / self.sample_rate_hz
    }
    /// Number of samples per response.
    pub fn num_samples(&self) -> usize {
        (self.duration_s * self.sample_rate_hz).round().max(0.0) as usize
    }

    /// Checks every option; errors name the field as `{prefix}.{field}`.
    pub fn validate(&self, prefix: &str) -> Vec<FieldError> {
        self.check(prefix, true)
    }

    /// [`Self::validate`] for responses sampled elsewhere (a measured
    /// tyre): `sample_rate_hz` is the data's, so the checks that depend on
    /// it (the band below Nyquist, the samples in `duration_s`) wait for
    /// the data; the band must still be ordered and the duration positive.
    pub fn validate_for_data(&self, prefix: &str) -> Vec<FieldError> {
        self.check(prefix, false)
    }

    /// The checks, those depending on `sample_rate_hz` only when `sampled`.
    fn check(&self, prefix: &str, sampled: bool) -> Vec<FieldError> {
        let mut errors = Vec::new();
        let mut push = |field: &str, value: String, expected: String| {
            errors.push(FieldError {
                field: format!("{prefix}.{field}"),
                value,
                expected,
            })
        };
        let fs = if sampled {
            self.sample_rate_hz
        } else {
            f64::INFINITY
        };
        if sampled && !(fs.is_finite() && fs > 0.0 && fs <= 1e6) {
            push(
                "sample_rate_hz",
                fs.to_string(),
                "a sample rate in (0, 1e6] Hz".into(),
            );
        }
        let (lo, hi) = self.band_hz;
        if !(lo.is_finite() && hi.is_finite() && lo >= 0.0 && lo < hi && hi < 0.5 * fs) {
            let expected = if sampled {
                format!("0 <= f_lo < f_hi < fs/2 = {} Hz", 0.5 * fs)
            } else {
                "0 <= f_lo < f_hi (and f_hi below the data's Nyquist frequency)".to_string()
            };
            push("band_hz", format!("({lo}, {hi})"), expected);
        }
        if !(1..=200).contains(&self.max_model_order) {
            push(
                "max_model_order",
                self.max_model_order.to_string(),
                "a highest model order in 1..=200 pole pairs".into(),
            );
        }
        if let Some(m) = self.model_order
            && !(1..=self.max_model_order.max(1)).contains(&m)
        {
            push(
                "model_order",
                format!("Some({m})"),
                format!(
                    "None or a model order in 1..=max_model_order = {}",
                    self.max_model_order
                ),
            );
        }
        let n = self.num_samples();
        // (an out-of-range max_model_order is reported above: the bound
        // uses the nearest allowed order, which cannot overflow)
        let need = 4 * self.max_model_order.clamp(1, 200) + 8;
        let positive = self.duration_s.is_finite() && self.duration_s > 0.0;
        if sampled && (!positive || n < need || n > 2_000_000) {
            push(
                "duration_s",
                self.duration_s.to_string(),
                format!(
                    "a duration giving {need}..=2e6 samples at {fs} Hz (4 per pole of max_model_order, plus 8); {n} now"
                ),
            );
        } else if !positive {
            push(
                "duration_s",
                self.duration_s.to_string(),
                "a duration > 0 s (the first seconds of the data identified)".into(),
            );
        }
        let ratios = [
            (
                "max_damping_ratio",
                self.max_damping_ratio,
                "a damping ratio in (0, 1)",
            ),
            (
                "stable_freq_tol",
                self.stable_freq_tol,
                "a relative tolerance in (0, 1)",
            ),
            (
                "stable_damping_tol",
                self.stable_damping_tol,
                "a relative tolerance in (0, 1)",
            ),
            ("stable_mac_min", self.stable_mac_min, "a MAC in (0, 1)"),
        ];
        for (f, x, e) in ratios {
            if !(x.is_finite() && x > 0.0 && x < 1.0) {
                push(f, x.to_string(), e.into());
            }
        }
        if !(self.order_tolerance.is_finite() && self.order_tolerance >= 0.0) {
            push(
                "order_tolerance",
                self.order_tolerance.to_string(),
                "a relative tolerance >= 0".into(),
            );
        }
        if !(self.min_contribution.is_finite() && (0.0..1.0).contains(&self.min_contribution)) {
            push(
                "min_contribution",
                self.min_contribution.to_string(),
                "a share in [0, 1)".into(),
            );
        }
        errors
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// For data sampled elsewhere the checks that need the sample rate
    /// wait for the data: 3 s of responses (3e6 samples at a nominal
    /// 1 MHz) and a 3 kHz band are not refused; a reversed band and a
    /// negative duration still are.
    #[test]
    fn options_for_data_skip_only_the_checks_that_need_its_sampling() {
        let o = IdentifyOptions {
            duration_s: 3.0,
            band_hz: (0.0, 3000.0),
            ..IdentifyOptions::default()
        };
        assert!(o.validate_for_data("t").is_empty());
        assert!(
            !o.validate("t").is_empty(),
            "sampled at 4 kHz the band is past Nyquist"
        );
        let bad = IdentifyOptions {
            duration_s: -1.0,
            band_hz: (500.0, 100.0),
            ..o
        };
        let fields: Vec<String> = bad
            .validate_for_data("t")
            .into_iter()
            .map(|e| e.field)
            .collect();
        assert_eq!(fields, ["t.band_hz", "t.duration_s"]);
    }
}
