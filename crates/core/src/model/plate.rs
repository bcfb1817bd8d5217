//! A tyre with a width (method §5.3): the belt as a tensioned orthotropic
//! plate on an elastic foundation, the classic analytic tyre model of the
//! rolling-noise literature. The belt is unrolled: `x` along the
//! circumference (period `L`, the contact patch's centre at `x = 0`), `y`
//! across the belt (`y = 0` on the centreline, edges at `±W/2`, simply
//! supported by the sidewalls). Its normal displacement `w(x, y, t)` obeys
//!
//! ```text
//! m'' ẅ + B_x w_xxxx + 2 B_xy w_xxyy + B_y w_yyyy - T_x w_xx - T_y w_yy + s w = p(x, y, t),
//! ```
//!
//! `B_xy = √(B_x B_y)`. Its modes are, for `n >= 1` across and `m >= 0` along,
//!
//! ```text
//! φ_nm(x, y) = sin(q_n (y + W/2)) {cos, sin}(k_m x) / √M_nm,   q_n = nπ/W,  k_m = 2πm/L,
//! ω_nm² = (B_x k⁴ + 2 B_xy k² q² + B_y q⁴ + T_x k² + T_y q² + s) / m'',
//! M_nm = m'' (W/2) (L/2) (m >= 1; the cos and sin modes of a pair),  m'' (W/2) L (m = 0),
//! ```
//!
//! mass-normalised (1/√kg), so the Green function between two points of the
//! patch is the modal model of method §2 with `A = φ(a) φ(b)`; every mode has
//! the damping ratio `ξ`.

use crate::base::error::FieldError;
use crate::base::modal::Mode;
use serde::{Deserialize, Serialize};
use std::f64::consts::{PI, TAU};

/// Largest number of plate modes kept (the contact tables hold `P K`
/// values per quantity).
pub const MAX_PLATE_MODES: usize = 4000;

/// Parameters of the plate tyre, SI units. Defaults: of the order of a
/// passenger car tyre's belt (tension along `T_x` = inflation pressure ×
/// radius, 2.2 bar × 0.3 m).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PlateParams {
    /// Belt width `W` (m), > 0.
    pub width_m: f64,
    /// Circumference `L` (m), > 0: the period along `x`.
    pub circumference_m: f64,
    /// Mass per unit area `m''` (kg/m²), > 0.
    pub mass_per_area_kg_m2: f64,
    /// Bending stiffness along `B_x` (N·m), >= 0.
    pub bending_along_nm: f64,
    /// Bending stiffness across `B_y` (N·m), >= 0.
    pub bending_across_nm: f64,
    /// Tension along `T_x` (N/m), >= 0.
    pub tension_along_n_m: f64,
    /// Tension across `T_y` (N/m), >= 0.
    pub tension_across_n_m: f64,
    /// Elastic foundation stiffness per unit area `s` (N/m³), > 0.
    pub foundation_n_m3: f64,
    /// Damping ratio `ξ` of every mode (-), >= 0.
    pub damping_ratio: f64,
    /// Modes up to this frequency (Hz) are kept, > 0.
    pub max_freq_hz: f64,
}

impl Default for PlateParams {
    fn default() -> Self {
        PlateParams {
            width_m: 0.16,
            circumference_m: 1.9,
            mass_per_area_kg_m2: 10.0,
            bending_along_nm: 5.0,
            bending_across_nm: 1.0,
            tension_along_n_m: 6.6e4,
            tension_across_n_m: 1.0e4,
            foundation_n_m3: 2.0e6,
            damping_ratio: 0.05,
            max_freq_hz: 1500.0,
        }
    }
}

/// One plate mode: its indices and angular frequency.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlateMode {
    /// Half-waves across `n >= 1`.
    pub n: u32,
    /// Circumferential order `m >= 0`.
    pub m: u32,
    /// `true`: the `sin(k x)` mode of a pair; `false`: `cos(k x)`.
    pub sine: bool,
    /// `ω_nm` (rad/s).
    pub omega_rad_s: f64,
}

impl PlateParams {
    /// `q_n = nπ/W` (rad/m).
    pub fn q(&self, n: u32) -> f64 {
        n as f64 * PI / self.width_m
    }

    /// `k_m = 2πm/L` (rad/m).
    pub fn k(&self, m: u32) -> f64 {
        TAU * m as f64 / self.circumference_m
    }

    /// The plate's stiffness per unit area for wavenumbers `(k, q)` (N/m³):
    /// the operator's symbol.
    pub fn stiffness(&self, k: f64, q: f64) -> f64 {
        let bxy = (self.bending_along_nm * self.bending_across_nm).sqrt();
        let (k2, q2) = (k * k, q * q);
        self.bending_along_nm * k2 * k2
            + 2.0 * bxy * k2 * q2
            + self.bending_across_nm * q2 * q2
            + self.tension_along_n_m * k2
            + self.tension_across_n_m * q2
            + self.foundation_n_m3
    }

    /// `ω_nm` (rad/s).
    pub fn omega(&self, n: u32, m: u32) -> f64 {
        (self.stiffness(self.k(m), self.q(n)) / self.mass_per_area_kg_m2).sqrt()
    }

    /// Modal mass `M_nm` (kg).
    pub fn modal_mass_kg(&self, m: u32) -> f64 {
        let along = if m == 0 { 1.0 } else { 0.5 };
        self.mass_per_area_kg_m2 * 0.5 * self.width_m * along * self.circumference_m
    }

    /// Mass-normalised shape of mode `md` at `(x, y)` (1/√kg).
    pub fn shape(&self, md: &PlateMode, x_m: f64, y_m: f64) -> f64 {
        let across = (self.q(md.n) * (y_m + 0.5 * self.width_m)).sin();
        let kx = self.k(md.m) * x_m;
        let along = if md.sine { kx.sin() } else { kx.cos() };
        across * along / self.modal_mass_kg(md.m).sqrt()
    }

    /// The modes up to `max_freq_hz`, by increasing frequency (at most
    /// [`MAX_PLATE_MODES`]; `n` and `m` up to `max_n`, `max_m`).
    pub fn plate_modes_up_to(&self, max_freq_hz: f64, max_n: u32, max_m: u32) -> Vec<PlateMode> {
        let w_max = TAU * max_freq_hz;
        let mut out = Vec::new();
        for n in 1..=max_n {
            if self.omega(n, 0) > w_max {
                break;
            }
            for m in 0..=max_m {
                let omega_rad_s = self.omega(n, m);
                if omega_rad_s > w_max {
                    break;
                }
                out.push(PlateMode {
                    n,
                    m,
                    sine: false,
                    omega_rad_s,
                });
                if m > 0 {
                    out.push(PlateMode {
                        n,
                        m,
                        sine: true,
                        omega_rad_s,
                    });
                }
            }
        }
        out.sort_by(|a, b| a.omega_rad_s.total_cmp(&b.omega_rad_s));
        out
    }

    /// The kept modes (up to [`PlateParams::max_freq_hz`]).
    pub fn plate_modes(&self) -> Vec<PlateMode> {
        let mut modes = self.plate_modes_up_to(self.max_freq_hz, 10_000, 100_000);
        modes.truncate(MAX_PLATE_MODES);
        modes
    }

    /// The modal model at points `(x_i, y_i)` (method §2): one mode per
    /// plate mode, shapes mass-normalised.
    pub fn modes(&self, points: &[(f64, f64)]) -> Vec<Mode> {
        self.plate_modes()
            .iter()
            .map(|md| Mode {
                freq_hz: md.omega_rad_s / TAU,
                damping_ratio: self.damping_ratio,
                residue: Vec::new(),
                shape: points.iter().map(|&(x, y)| self.shape(md, x, y)).collect(),
            })
            .collect()
    }

    /// Field errors (`prefix` names the plate).
    pub fn validate(&self, prefix: &str) -> Vec<FieldError> {
        let mut errors = Vec::new();
        let push = |errors: &mut Vec<FieldError>, field: &str, value: f64, expected: &str| {
            errors.push(FieldError {
                field: format!("{prefix}.{field}"),
                value: crate::base::error::fmt_num(value),
                expected: expected.to_string(),
            })
        };
        // (bounds far outside any tyre, so that every lowest-mode
        // frequency they allow is a number a time step can be set against)
        for (f, x, lo, hi, e) in [
            (
                "width_m",
                self.width_m,
                1e-3,
                10.0,
                "a belt width from 0.001 to 10 m",
            ),
            (
                "circumference_m",
                self.circumference_m,
                1e-2,
                100.0,
                "a circumference from 0.01 to 100 m",
            ),
            (
                "mass_per_area_kg_m2",
                self.mass_per_area_kg_m2,
                1e-3,
                1e4,
                "a mass per area from 0.001 to 1e4 kg/m²",
            ),
            (
                "bending_along_nm",
                self.bending_along_nm,
                0.0,
                1e6,
                "a bending stiffness from 0 to 1e6 N·m",
            ),
            (
                "bending_across_nm",
                self.bending_across_nm,
                0.0,
                1e6,
                "a bending stiffness from 0 to 1e6 N·m",
            ),
            (
                "tension_along_n_m",
                self.tension_along_n_m,
                0.0,
                1e9,
                "a tension from 0 to 1e9 N/m",
            ),
            (
                "tension_across_n_m",
                self.tension_across_n_m,
                0.0,
                1e9,
                "a tension from 0 to 1e9 N/m",
            ),
            (
                "foundation_n_m3",
                self.foundation_n_m3,
                f64::MIN_POSITIVE,
                1e12,
                "a foundation stiffness > 0 and <= 1e12 N/m³ (a free belt has rigid-body modes)",
            ),
            (
                "damping_ratio",
                self.damping_ratio,
                0.0,
                1e4,
                "a damping ratio from 0 to 1e4",
            ),
            (
                "max_freq_hz",
                self.max_freq_hz,
                f64::MIN_POSITIVE,
                1e6,
                "a frequency > 0 and <= 1e6 Hz",
            ),
        ] {
            if !(x.is_finite() && x >= lo && x <= hi) {
                push(&mut errors, f, x, e);
            }
        }
        if errors.is_empty() {
            let f0 = self.omega(1, 0) / TAU;
            if f0 > self.max_freq_hz {
                push(
                    &mut errors,
                    "max_freq_hz",
                    self.max_freq_hz,
                    &format!("a frequency >= the plate's lowest mode, {f0:.1} Hz"),
                );
            }
        }
        errors
    }
}

/// The static deflection (m/N) at `b` of a tensioned beam on an elastic
/// foundation, `B u'''' - T u'' + K u = δ(x - a)`, infinite, in closed form:
/// `u(x) = i Σ_{Im k_j > 0} e^{i k_j |x - a|} / D'(k_j)` over the roots of
/// `D(k) = B k⁴ + T k² + K` (residues). Used to check the plate.
pub fn beam_static_deflection(b_nm2: f64, t_n: f64, k_n_m2: f64, dx_m: f64) -> f64 {
    use rustfft::num_complex::Complex;
    let x = dx_m.abs();
    let i = Complex::new(0.0, 1.0);
    if b_nm2 == 0.0 {
        // a string: u = e^{-a|x|} / (2 T a), a = √(K/T)
        let a = (k_n_m2 / t_n).sqrt();
        return (-a * x).exp() / (2.0 * t_n * a);
    }
    // k² = (-T ± √(T² - 4 B K)) / (2B)
    let disc = Complex::new(t_n * t_n - 4.0 * b_nm2 * k_n_m2, 0.0).sqrt();
    let mut sum = Complex::new(0.0, 0.0);
    for sgn in [1.0, -1.0] {
        let k2 = (Complex::new(-t_n, 0.0) + disc * sgn) / (2.0 * b_nm2);
        let mut k = k2.sqrt();
        if k.im < 0.0 {
            k = -k;
        }
        let dprime = k * k * k * (4.0 * b_nm2) + k * (2.0 * t_n);
        sum += (i * k * x).exp() / dprime;
    }
    (i * sum).re
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plate() -> PlateParams {
        PlateParams::default()
    }

    /// Each mode satisfies the plate equation (its operator applied by
    /// finite differences equals `ω² m'' φ`), vanishes on the edges, and
    /// the modes are mass-orthonormal (midpoint quadrature).
    #[test]
    fn modes_solve_the_plate_equation_and_are_orthonormal() {
        let p = PlateParams {
            max_freq_hz: 600.0,
            ..plate()
        };
        let modes = p.plate_modes();
        assert!(modes.len() > 10, "{} modes", modes.len());
        let bxy = (p.bending_along_nm * p.bending_across_nm).sqrt();
        for md in &modes {
            let f = |x: f64, y: f64| p.shape(md, x, y);
            let (x, y) = (0.037, 0.021);
            let h = 2e-3;
            let d2x = |x: f64, y: f64| (f(x + h, y) - 2.0 * f(x, y) + f(x - h, y)) / (h * h);
            let d2y = |x: f64, y: f64| (f(x, y + h) - 2.0 * f(x, y) + f(x, y - h)) / (h * h);
            let d4x = (d2x(x + h, y) - 2.0 * d2x(x, y) + d2x(x - h, y)) / (h * h);
            let d4y = (d2y(x, y + h) - 2.0 * d2y(x, y) + d2y(x, y - h)) / (h * h);
            let d2x2y = (d2y(x + h, y) - 2.0 * d2y(x, y) + d2y(x - h, y)) / (h * h);
            let lhs = p.bending_along_nm * d4x + 2.0 * bxy * d2x2y + p.bending_across_nm * d4y
                - p.tension_along_n_m * d2x(x, y)
                - p.tension_across_n_m * d2y(x, y)
                + p.foundation_n_m3 * f(x, y);
            let rhs = md.omega_rad_s.powi(2) * p.mass_per_area_kg_m2 * f(x, y);
            let scale = md.omega_rad_s.powi(2) * p.mass_per_area_kg_m2 * f(x, y).abs().max(1e-3);
            assert!(
                (lhs - rhs).abs() < 2e-2 * scale,
                "mode {md:?}: operator {lhs:e} vs ω² m'' φ {rhs:e}"
            );
            for edge in [-0.5 * p.width_m, 0.5 * p.width_m] {
                assert!(f(0.3, edge).abs() < 1e-12, "edge of {md:?}");
            }
        }
        // orthonormality over the belt (midpoint rule, exact for these
        // trigonometric products on a fine enough periodic grid)
        let (nx, ny) = (400, 200);
        let (dx, dy) = (p.circumference_m / nx as f64, p.width_m / ny as f64);
        let take: Vec<&PlateMode> = modes.iter().take(24).collect();
        for (a, ma) in take.iter().enumerate() {
            for (b, mb) in take.iter().enumerate().skip(a) {
                let mut s = 0.0;
                for i in 0..nx {
                    for j in 0..ny {
                        let x = (i as f64 + 0.5) * dx;
                        let y = -0.5 * p.width_m + (j as f64 + 0.5) * dy;
                        s +=
                            p.mass_per_area_kg_m2 * p.shape(ma, x, y) * p.shape(mb, x, y) * dx * dy;
                    }
                }
                let want = if a == b { 1.0 } else { 0.0 };
                assert!((s - want).abs() < 1e-9, "modes {a}, {b}: {s}");
            }
        }
    }

    /// Keeping only the first width mode, the plate is a tensioned beam on
    /// an elastic foundation: the modal sum's static compliance between two
    /// points equals the beam's closed form (roots of its symbol).
    #[test]
    fn first_width_mode_is_a_tensioned_beam_on_an_elastic_foundation() {
        for p in [
            plate(),
            // bending-dominated (complex roots) and a string (no bending)
            PlateParams {
                tension_along_n_m: 100.0,
                bending_along_nm: 50.0,
                ..plate()
            },
            PlateParams {
                bending_along_nm: 0.0,
                bending_across_nm: 0.0,
                ..plate()
            },
        ] {
            let q = p.q(1);
            let bxy = (p.bending_along_nm * p.bending_across_nm).sqrt();
            let (bb, tt, kk) = (
                p.bending_along_nm,
                p.tension_along_n_m + 2.0 * bxy * q * q,
                p.foundation_n_m3 + p.tension_across_n_m * q * q + p.bending_across_nm * q.powi(4),
            );
            let modes = p.plate_modes_up_to(1e9, 1, 20_000);
            let (a, b) = ((0.0, 0.013), (0.021, -0.030));
            for dx in [0.0, 0.021, 0.08] {
                let bpt = (b.0 + dx, b.1);
                let sum: f64 = modes
                    .iter()
                    .map(|md| {
                        p.shape(md, a.0, a.1) * p.shape(md, bpt.0, bpt.1) / md.omega_rad_s.powi(2)
                    })
                    .sum();
                // the projection of a point load on sin(q (y + W/2)) is
                // 2/W sin(q (ya + W/2)); the images of the periodic belt
                // are below 1e-12 here
                let across = |y: f64| (q * (y + 0.5 * p.width_m)).sin();
                let beam: f64 = (-3..=3)
                    .map(|j| {
                        beam_static_deflection(
                            bb,
                            tt,
                            kk,
                            bpt.0 - a.0 + j as f64 * p.circumference_m,
                        )
                    })
                    .sum();
                let want = 2.0 / p.width_m * across(a.1) * across(bpt.1) * beam;
                assert!(
                    (sum / want - 1.0).abs() < 1e-6,
                    "{p:?} dx {dx}: modal {sum:e} vs beam {want:e} m/N"
                );
            }
        }
    }

    /// The static deflection under a point load: the modal sum over both
    /// directions against the direct solution (a closed-form beam per width
    /// mode, summed across), converged.
    #[test]
    fn static_point_load_deflection_by_modes_equals_the_direct_solution() {
        let p = plate();
        let load = (0.0, 0.02);
        let bxy = (p.bending_along_nm * p.bending_across_nm).sqrt();
        let direct = |x: f64, y: f64| -> f64 {
            (1..=400u32)
                .map(|n| {
                    let q = p.q(n);
                    let across = |y: f64| (q * (y + 0.5 * p.width_m)).sin();
                    let (tt, kk) = (
                        p.tension_along_n_m + 2.0 * bxy * q * q,
                        p.foundation_n_m3
                            + p.tension_across_n_m * q * q
                            + p.bending_across_nm * q.powi(4),
                    );
                    2.0 / p.width_m
                        * across(load.1)
                        * across(y)
                        * beam_static_deflection(p.bending_along_nm, tt, kk, x - load.0)
                })
                .sum()
        };
        let modes = p.plate_modes_up_to(1e12, 400, 3000);
        for (x, y) in [(0.0, 0.02), (0.01, 0.02), (0.03, -0.05), (-0.05, 0.0)] {
            let modal: f64 = modes
                .iter()
                .map(|md| p.shape(md, load.0, load.1) * p.shape(md, x, y) / md.omega_rad_s.powi(2))
                .sum();
            let d = direct(x, y);
            assert!(
                (modal / d - 1.0).abs() < 1e-4,
                "at ({x}, {y}): modal {modal:e} vs direct {d:e} m/N"
            );
        }
    }

    #[test]
    fn fields_are_validated_by_name() {
        let bad = PlateParams {
            width_m: 0.0,
            damping_ratio: -1.0,
            ..plate()
        };
        let fields: Vec<String> = bad
            .validate("tyre.plate")
            .into_iter()
            .map(|e| e.field)
            .collect();
        assert_eq!(fields, ["tyre.plate.width_m", "tyre.plate.damping_ratio"]);
        let low = PlateParams {
            max_freq_hz: 10.0,
            ..plate()
        };
        let e = low.validate("tyre.plate");
        assert_eq!(e.len(), 1);
        assert!(e[0].expected.contains("lowest mode"), "{}", e[0].expected);
        assert!(plate().validate("tyre.plate").is_empty());
    }
}
