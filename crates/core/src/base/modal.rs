//! The modal model of the tyre's Green functions (method §2):
//!
//! ```text
//! g_ij(t) = Σ_k A_k[i][j] h_k(t),   h_k'' + 2 ξ_k ω_k h_k' + ω_k² h_k = δ(t)
//! ```
//!
//! `h_k` is evaluated in closed form for every `ξ >= 0` without cancellation:
//! underdamped `e^{-ξωt} sin(ω_d t)/ω_d`, critical `t e^{-ωt}`, overdamped
//! `e^{λ₊ t} (1 - e^{-2κt}) / (2κ)` with the slow pole `λ₊ = -ω²/(ξω + κ)` and
//! `κ = ω √((ξ-1)(ξ+1))` (both limits give `t e^{-ωt}`, so `h` is continuous
//! in `ξ` to round-off).

use serde::{Deserialize, Serialize};
use std::f64::consts::TAU;

/// One mode of the modal model (method §2). Give either `residue` (P×P, row i =
/// receiving point, column j = loaded point, in 1/kg) or `shape` (P values,
/// `A = φ φᵀ`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Mode {
    /// Natural frequency `f_k` (Hz), > 0.
    pub freq_hz: f64,
    /// Damping ratio `ξ_k` (-), >= 0 (0 undamped, 1 critical, > 1 overdamped).
    pub damping_ratio: f64,
    /// Residue matrix `A_k` (1/kg), P×P. Empty when `shape` is given.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub residue: Vec<Vec<f64>>,
    /// Mode shape `φ_k` (1/√kg), P values; `A_k = φ_k φ_kᵀ`. Empty when `residue` is given.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub shape: Vec<f64>,
}

impl Mode {
    /// The residue matrix `A_k` (P×P), from `residue` or from `shape`.
    pub fn residue_matrix(&self) -> Vec<Vec<f64>> {
        if !self.residue.is_empty() {
            self.residue.clone()
        } else {
            self.shape
                .iter()
                .map(|a| self.shape.iter().map(|b| a * b).collect())
                .collect()
        }
    }
}

/// One mode, ready for evaluation.
#[derive(Debug, Clone, PartialEq)]
pub struct ModalMode {
    /// Natural angular frequency `ω` (rad/s).
    pub omega_rad_s: f64,
    /// Damping ratio `ξ` (-).
    pub damping_ratio: f64,
    /// Residue matrix `A` (1/kg), row-major P×P.
    pub residue: Vec<f64>,
}

/// A modal model: `P` points, a list of modes.
#[derive(Debug, Clone, PartialEq)]
pub struct ModalModel {
    pub num_points: usize,
    pub modes: Vec<ModalMode>,
}

/// A complex number (for `G(ω)`), kept minimal on purpose.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Complex {
    pub re: f64,
    pub im: f64,
}

impl Complex {
    pub fn norm(self) -> f64 {
        self.re.hypot(self.im)
    }
}

impl ModalMode {
    /// Builds a mode from its scene description (`P` points).
    pub fn from_scene(m: &Mode) -> Self {
        ModalMode {
            omega_rad_s: TAU * m.freq_hz,
            damping_ratio: m.damping_ratio,
            residue: m.residue_matrix().into_iter().flatten().collect(),
        }
    }

    /// `a = ξω` (1/s).
    pub fn decay_rate(&self) -> f64 {
        self.damping_ratio * self.omega_rad_s
    }

    /// `(h(t), h'(t))` of the unit-mass oscillator (method §2), for every `ξ >= 0`.
    pub fn impulse_response(&self, t_s: f64) -> (f64, f64) {
        unit_impulse(self.omega_rad_s, self.damping_ratio, t_s)
    }

    /// Step response `∫_0^t h` (m per N of a unit-mass oscillator... times `A`):
    /// `(1 - h'(t) - 2ξω h(t)) / ω²`.
    pub fn step_response(&self, t_s: f64) -> f64 {
        let (h, hd) = self.impulse_response(t_s);
        (1.0 - hd - 2.0 * self.decay_rate() * h) / (self.omega_rad_s * self.omega_rad_s)
    }

    /// Receptance of the unit oscillator `1 / (ω² - Ω² + 2iξωΩ)` at `Ω` (rad/s).
    pub fn receptance(&self, big_omega: f64) -> Complex {
        let w = self.omega_rad_s;
        let re = w * w - big_omega * big_omega;
        let im = 2.0 * self.damping_ratio * w * big_omega;
        let d = re * re + im * im;
        Complex {
            re: re / d,
            im: -im / d,
        }
    }
}

/// `(h(t), h'(t))` for `h'' + 2ξω h' + ω² h = δ(t)`, `t >= 0`.
pub fn unit_impulse(omega: f64, xi: f64, t: f64) -> (f64, f64) {
    if t <= 0.0 {
        return (0.0, if t == 0.0 { 1.0 } else { 0.0 });
    }
    let a = xi * omega;
    if xi < 1.0 {
        // (1 - ξ)(1 + ξ) is exact where 1 - ξ² would cancel.
        let wd = omega * ((1.0 - xi) * (1.0 + xi)).sqrt();
        let e = (-a * t).exp();
        let (s, c) = (wd * t).sin_cos();
        let sn = s / wd; // sin(ω_d t)/ω_d, exact limit t as ω_d -> 0
        (e * sn, e * (c - a * sn))
    } else if xi == 1.0 {
        let e = (-omega * t).exp();
        (t * e, e * (1.0 - omega * t))
    } else {
        let kappa = omega * ((xi - 1.0) * (xi + 1.0)).sqrt();
        let l_slow = -omega * omega / (a + kappa);
        let l_fast = -a - kappa;
        let e = (l_slow * t).exp();
        // (1 - e^{-2κt}) / (2κ), -> t as κ -> 0
        let s = -(-2.0 * kappa * t).exp_m1() / (2.0 * kappa);
        (e * s, e * (1.0 + l_fast * s))
    }
}

impl ModalModel {
    /// Builds the model of a scene's modes for `num_points` points.
    pub fn from_modes(modes: &[Mode], num_points: usize) -> Self {
        ModalModel {
            num_points,
            modes: modes.iter().map(ModalMode::from_scene).collect(),
        }
    }

    /// `g_ij(t)` (m/(N·s)) and `g'_ij(t)` (m/(N·s²)), method §2.
    pub fn green(&self, i: usize, j: usize, t_s: f64) -> (f64, f64) {
        let p = self.num_points;
        self.modes.iter().fold((0.0, 0.0), |(g, gd), m| {
            let (h, hd) = m.impulse_response(t_s);
            let a = m.residue[i * p + j];
            (g + a * h, gd + a * hd)
        })
    }

    /// Frequency response `G_ij(Ω)` (m/N) at `freq_hz`.
    pub fn frequency_response(&self, i: usize, j: usize, freq_hz: f64) -> Complex {
        let p = self.num_points;
        self.modes.iter().fold(Complex::default(), |acc, m| {
            let h = m.receptance(TAU * freq_hz);
            let a = m.residue[i * p + j];
            Complex {
                re: acc.re + a * h.re,
                im: acc.im + a * h.im,
            }
        })
    }

    /// Static compliance `Σ_k A_k / ω_k²` (m/N), row-major P×P.
    pub fn static_compliance(&self) -> Vec<f64> {
        let p = self.num_points;
        let mut c = vec![0.0; p * p];
        for m in &self.modes {
            let w2 = m.omega_rad_s * m.omega_rad_s;
            for (ci, a) in c.iter_mut().zip(&m.residue) {
                *ci += a / w2;
            }
        }
        c
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn continuous_across_critical_damping() {
        let w = TAU * 100.0;
        for &t in &[1e-5, 1e-3, 5e-3, 2e-2] {
            let (h1, d1) = unit_impulse(w, 1.0, t);
            for &xi in &[1.0 - 1e-12, 1.0 + 1e-12, 1.0 - 1e-9, 1.0 + 1e-9] {
                let (h, d) = unit_impulse(w, xi, t);
                // dh/dξ is O(t² ω h): the step of 1e-9 moves h by ~1e-9 relative at most
                let tol = 4.0 * (xi - 1.0).abs() * (1.0 + (w * t).powi(2)) + 1e-14;
                assert!(
                    (h - h1).abs() <= tol * h1.abs(),
                    "xi={xi} t={t}: {h} vs {h1}"
                );
                assert!((d - d1).abs() <= tol * (d1.abs() + h1.abs() * w), "xi={xi}");
            }
        }
    }

    #[test]
    fn derivative_matches_difference_all_regimes() {
        for &xi in &[0.0, 0.05, 0.999, 1.0, 1.001, 3.0, 50.0] {
            let w = TAU * 80.0;
            for &t in &[1e-4, 3e-3, 1e-2] {
                let e = 1e-8;
                let fd = (unit_impulse(w, xi, t + e).0 - unit_impulse(w, xi, t - e).0) / (2.0 * e);
                let (_, d) = unit_impulse(w, xi, t);
                assert!(
                    (fd - d).abs() < 1e-6 * (1.0 + d.abs()),
                    "xi={xi} t={t}: {fd} vs {d}"
                );
            }
        }
    }
}
