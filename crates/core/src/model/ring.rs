//! The ring tyre model (method §5): a circular ring on an elastic foundation.
//!
//! The tread is an Euler-Bernoulli curved beam (bending stiffness `EI`,
//! membrane stiffness `EA`, mass `m` per unit length of circumference, radius
//! `R`), pre-tensioned by the inflation pressure (`T = p0 b R`), carried by
//! distributed radial and tangential springs (sidewall and rim, `k_r`, `k_t`
//! per unit length) and damped modally (one ratio `ξ` for every mode).
//!
//! In-plane motion: radial displacement `w(θ, t)` (positive outward) and
//! tangential `v(θ, t)`. With `ε = (w + v')/R`, `κ = (v' - w'')/R²` and the
//! second-order energy of the tension less the work of the follower pressure,
//! `T/(2R) ∮ (w'² + v'² + 2 w v') dθ` (it vanishes for rigid translation and
//! rotation), order `n` (`w = W cos nθ`, `v = V sin nθ`) has the stiffness per
//! unit length
//!
//! ```text
//! K(n) = EA/R² [1 n; n n²] + EI/R⁴ [n⁴ n³; n³ n²] + T/R² [n² n; n n²] + diag(k_r, k_t)
//! ```
//!
//! and the mass `m I`: each order gives a 2×2 symmetric eigenproblem, two
//! modes, each a degenerate cos/sin pair for `n >= 1`. With the radial motion
//! alone (`motion: RadialOnly`, the membrane term left out) this is method §5's
//! tensioned beam,
//! `ω_n² = (EI (n/R)⁴ + T (n/R)² + k_r) / m`; with no foundation, no tension
//! and `EA -> ∞` it is the free inextensional ring of NAFEMS VM09.
//!
//! Radial Green function between contact points `i`, `j` (a point at road
//! position `x` sits at `θ = x / R` from the bottom; the radial direction
//! there is taken as the vertical, method §1 signs: outward radial at the bottom
//! is down, so `u = -w` and `q = -F_r`, and the receptance keeps its sign):
//!
//! ```text
//! g_ij(t) = Σ_n Σ_branch c_n W² cos(n (θ_i - θ_j)) h_{n,branch}(t) / (2π R m),  c_0 = 1, c_n = 2
//! ```
//!
//! i.e. the modal model of method §2 with the rank-2 residue
//! `A = c_n W² [cos nθ_i cos nθ_j + sin nθ_i sin nθ_j] / (2π R m)` per order
//! and branch ([`RingParams::modes`]).

use crate::base::error::FieldError;
use crate::base::modal::Mode;
use crate::base::modal::{ModalModel, unit_impulse};
use serde::{Deserialize, Serialize};
use std::f64::consts::{PI, TAU};

/// Which in-plane motion the ring has.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum RingMotion {
    /// Radial and tangential (the ring tyre model). Default.
    #[default]
    RadialTangential,
    /// Radial only (`v = 0`): the tensioned beam on an elastic foundation
    /// closed on itself (method §5's closed form; `EA` plays no part).
    RadialOnly,
}

/// Parameters of the ring tyre (method §5). Defaults: the reference passenger tyre.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RingParams {
    /// Ring (belt) radius `R` (m), > 0. Default 0.31 m.
    pub radius_m: f64,
    /// Belt width `b` (m), > 0; with `inflation_pa` gives the tension
    /// `T = p0 b R`. Default 0.165 m.
    pub belt_width_m: f64,
    /// Mass per unit length of circumference `m` (kg/m), > 0. Default 3.70 kg/m
    /// (22.4 kg/m² times 0.165 m).
    pub mass_per_length_kg_m: f64,
    /// Inflation pressure `p0` (Pa), >= 0. Default 2.0e5 Pa (2 bar).
    pub inflation_pa: f64,
    /// Radial foundation stiffness per unit length of circumference `k_r`
    /// (N/m²), > 0. Default 3.3e5 N/m².
    pub radial_stiffness_n_m2: f64,
    /// Tangential foundation stiffness per unit length `k_t` (N/m²), >= 0.
    /// Default 1.59e5 N/m².
    pub tangential_stiffness_n_m2: f64,
    /// Bending stiffness of the belt `EI` (N·m²), >= 0. Default 6 N·m²
    /// (assumed; 4-10 is typical).
    pub bending_stiffness_n_m2: f64,
    /// Membrane (extensional) stiffness of the belt `EA` (N), >= 0. Default
    /// 5.0e6 N (assumed: a nearly inextensible steel belt; its extensional
    /// modes lie above 500 Hz). Not used with `motion: RadialOnly`.
    pub extensional_stiffness_n: f64,
    /// Modal damping ratio `ξ` of every mode (-), in [0, 1). Default 0.05.
    pub damping_ratio: f64,
    /// Highest circumferential order `N` (-): orders `0..=N` are used,
    /// 1..=2000. Default 40.
    pub max_order: usize,
    /// In-plane motion. Default `RadialTangential`.
    pub motion: RingMotion,
}

impl Default for RingParams {
    fn default() -> Self {
        RingParams {
            radius_m: 0.31,
            belt_width_m: 0.165,
            mass_per_length_kg_m: 3.70,
            inflation_pa: 2.0e5,
            radial_stiffness_n_m2: 3.3e5,
            tangential_stiffness_n_m2: 1.59e5,
            bending_stiffness_n_m2: 6.0,
            extensional_stiffness_n: 5.0e6,
            damping_ratio: 0.05,
            max_order: 40,
            motion: RingMotion::RadialTangential,
        }
    }
}

/// One mode of one circumferential order, mass-normalised over the ring.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OrderMode {
    /// Circumferential order `n`.
    pub order: usize,
    /// Natural angular frequency `ω` (rad/s).
    pub omega_rad_s: f64,
    /// Radial and tangential amplitudes `(W, V)` of the unit eigenvector.
    pub radial: f64,
    pub tangential: f64,
}

impl OrderMode {
    /// Natural frequency (Hz).
    pub fn freq_hz(&self) -> f64 {
        self.omega_rad_s / TAU
    }
}

impl RingParams {
    /// Inflation tension `T = p0 b R` (N).
    pub fn tension_n(&self) -> f64 {
        self.inflation_pa * self.belt_width_m * self.radius_m
    }

    /// The stiffness per unit length of order `n` (N/m², symmetric 2×2).
    pub fn stiffness(&self, n: usize) -> [[f64; 2]; 2] {
        let r = self.radius_m;
        let nf = n as f64;
        let ea = self.extensional_stiffness_n / (r * r);
        let ei = self.bending_stiffness_n_m2 / r.powi(4);
        let t = self.tension_n() / (r * r);
        let n2 = nf * nf;
        [
            [
                ea + ei * n2 * n2 + t * n2 + self.radial_stiffness_n_m2,
                ea * nf + ei * n2 * nf + t * nf,
            ],
            [
                ea * nf + ei * n2 * nf + t * nf,
                ea * n2 + ei * n2 + t * n2 + self.tangential_stiffness_n_m2,
            ],
        ]
    }

    /// The modes of order `n`, lowest frequency first: two (radial-tangential)
    /// or one (radial only). Pure arithmetic; no validation.
    pub fn order_modes(&self, n: usize) -> Vec<OrderMode> {
        let k = self.stiffness(n);
        let m = self.mass_per_length_kg_m;
        let mk = |lambda: f64, radial: f64, tangential: f64| OrderMode {
            order: n,
            omega_rad_s: lambda.max(0.0).sqrt(),
            radial,
            tangential,
        };
        if self.motion == RingMotion::RadialOnly {
            // v = 0 and no membrane term: the tensioned beam of method §5,
            // ω² = (EI (n/R)⁴ + T (n/R)² + k_r) / m, whatever EA is
            let ea = self.extensional_stiffness_n / (self.radius_m * self.radius_m);
            return vec![mk((k[0][0] - ea) / m, 1.0, 0.0)];
        }
        let (a, b, d) = (k[0][0] / m, k[0][1] / m, k[1][1] / m);
        if b == 0.0 {
            let mut v = vec![mk(a, 1.0, 0.0), mk(d, 0.0, 1.0)];
            v.sort_by(|x, y| x.omega_rad_s.total_cmp(&y.omega_rad_s));
            return v;
        }
        // λ = (a+d)/2 ∓ sqrt(((a-d)/2)² + b²); the lower root without cancellation
        let half = 0.5 * (a - d);
        let rad = half.hypot(b);
        let mean = 0.5 * (a + d);
        let hi = mean + rad;
        let lo = (a * d - b * b) / hi; // product of the roots = det
        [lo, hi]
            .iter()
            .map(|&l| {
                // eigenvector: (b, l - a) or (l - d, b), the better-conditioned
                let (w1, v1) = (b, l - a);
                let (w2, v2) = (l - d, b);
                let (w, v) = if w1.hypot(v1) >= w2.hypot(v2) {
                    (w1, v1)
                } else {
                    (w2, v2)
                };
                let s = w.hypot(v);
                let sign = if w < 0.0 { -1.0 } else { 1.0 };
                mk(l, sign * w / s, sign * v / s)
            })
            .collect()
    }

    /// Natural frequencies (Hz) of order `n`, lowest first.
    pub fn order_frequencies_hz(&self, n: usize) -> Vec<f64> {
        self.order_modes(n).iter().map(OrderMode::freq_hz).collect()
    }

    /// Every order mode `n = 0..=N` with a radial component (the rigid
    /// rotation of order 0 has none and is left out), in order of `n`.
    pub fn all_modes(&self) -> Vec<OrderMode> {
        (0..=self.max_order)
            .flat_map(|n| self.order_modes(n))
            .filter(|m| m.radial != 0.0)
            .collect()
    }

    /// The ring's own modal model at contact points `x_m` (m along the
    /// contact line, angle `x/R`): one [`Mode`] per order and branch, with the
    /// radial residue matrix (1/kg, rank 2 for `n >= 1`), method §2 and §5.
    /// Modes of zero frequency (a free ring's rigid motions) are left out.
    pub fn modes(&self, x_m: &[f64]) -> Vec<Mode> {
        self.all_modes()
            .into_iter()
            .filter(|m| m.omega_rad_s > 0.0)
            .map(|m| self.mode_at(&m, x_m))
            .collect()
    }

    /// The [`Mode`] (residue at the points `x_m`) of one order mode.
    pub fn mode_at(&self, m: &OrderMode, x_m: &[f64]) -> Mode {
        let c = if m.order == 0 { 1.0 } else { 2.0 };
        let scale = c * m.radial * m.radial / (TAU * self.radius_m * self.mass_per_length_kg_m);
        let n = m.order as f64;
        let theta: Vec<f64> = x_m.iter().map(|x| x / self.radius_m).collect();
        let residue = theta
            .iter()
            .map(|ti| {
                theta
                    .iter()
                    .map(|tj| scale * (n * (ti - tj)).cos())
                    .collect()
            })
            .collect();
        Mode {
            freq_hz: m.freq_hz(),
            damping_ratio: self.damping_ratio,
            residue,
            shape: Vec::new(),
        }
    }

    /// The modal model at the points `x_m` (all orders `0..=N`).
    pub fn modal_model(&self, x_m: &[f64]) -> ModalModel {
        ModalModel::from_modes(&self.modes(x_m), x_m.len())
    }

    /// Radial Green function `g(Δθ, t)` (m/(N·s)) between two points an angle
    /// `dtheta_rad` apart, summed over the order modes below `max_freq_hz`.
    pub fn green_angle(&self, dtheta_rad: f64, t_s: f64, max_freq_hz: f64) -> f64 {
        let rm = TAU * self.radius_m * self.mass_per_length_kg_m;
        self.all_modes()
            .iter()
            .filter(|m| m.omega_rad_s > 0.0 && m.freq_hz() < max_freq_hz)
            .map(|m| {
                let c = if m.order == 0 { 1.0 } else { 2.0 };
                let (h, _) = unit_impulse(m.omega_rad_s, self.damping_ratio, t_s);
                c * m.radial * m.radial * (m.order as f64 * dtheta_rad).cos() * h / rm
            })
            .sum()
    }

    /// Sampled radial impulse responses `g_ij(k dt)` (m/(N·s)), `k = 0..len`,
    /// for the pairs `i <= j` of the points `x_m`, from the order modes below
    /// the Nyquist frequency `1/(2 dt)` (an ideal anti-aliasing filter on the
    /// modal sum). Returns the pairs and the responses.
    pub fn sampled_responses(
        &self,
        x_m: &[f64],
        dt_s: f64,
        len: usize,
    ) -> (Vec<(usize, usize)>, Vec<Vec<f64>>) {
        let model = self.sampling_model(x_m, dt_s);
        let mut pairs = Vec::new();
        let mut data = Vec::new();
        for i in 0..x_m.len() {
            let (p, d) = sampled_row(&model, i, dt_s, len);
            pairs.extend(p);
            data.extend(d);
        }
        (pairs, data)
    }

    /// The order modes below the Nyquist frequency `1/(2 dt)` at the points
    /// `x_m`: the model [`RingParams::sampled_responses`] samples
    /// ([`sampled_row`] a row of it at a time).
    pub fn sampling_model(&self, x_m: &[f64], dt_s: f64) -> ModalModel {
        let nyquist = 0.5 / dt_s;
        let modes: Vec<Mode> = self
            .all_modes()
            .into_iter()
            .filter(|m| m.omega_rad_s > 0.0 && m.freq_hz() < nyquist)
            .map(|m| self.mode_at(&m, x_m))
            .collect();
        ModalModel::from_modes(&modes, x_m.len())
    }

    /// Checks every parameter; errors name the field as `{prefix}.{field}`.
    pub fn validate(&self, prefix: &str) -> Vec<FieldError> {
        let mut errors = Vec::new();
        let mut push = |field: &str, value: String, expected: &str| {
            errors.push(FieldError {
                field: format!("{prefix}.{field}"),
                value,
                expected: expected.to_string(),
            })
        };
        let positive = [
            ("radius_m", self.radius_m, "a ring radius > 0 m"),
            ("belt_width_m", self.belt_width_m, "a belt width > 0 m"),
            (
                "mass_per_length_kg_m",
                self.mass_per_length_kg_m,
                "a mass per length > 0 kg/m",
            ),
            (
                "radial_stiffness_n_m2",
                self.radial_stiffness_n_m2,
                "a radial foundation stiffness > 0 N/m² (a free ring has rigid-body modes)",
            ),
        ];
        for (f, x, e) in positive {
            if !(x.is_finite() && x > 0.0) {
                push(f, x.to_string(), e);
            }
        }
        let nonneg = [
            ("inflation_pa", self.inflation_pa, "a pressure >= 0 Pa"),
            (
                "tangential_stiffness_n_m2",
                self.tangential_stiffness_n_m2,
                "a tangential foundation stiffness >= 0 N/m²",
            ),
            (
                "bending_stiffness_n_m2",
                self.bending_stiffness_n_m2,
                "a bending stiffness >= 0 N·m²",
            ),
            (
                "extensional_stiffness_n",
                self.extensional_stiffness_n,
                "a membrane stiffness >= 0 N",
            ),
        ];
        for (f, x, e) in nonneg {
            if !(x.is_finite() && x >= 0.0) {
                push(f, x.to_string(), e);
            }
        }
        if !(self.damping_ratio.is_finite() && (0.0..1.0).contains(&self.damping_ratio)) {
            push(
                "damping_ratio",
                self.damping_ratio.to_string(),
                "a modal damping ratio in [0, 1)",
            );
        }
        if !(1..=2000).contains(&self.max_order) {
            push(
                "max_order",
                self.max_order.to_string(),
                "a highest circumferential order in 1..=2000",
            );
        }
        errors
    }
}

/// Free inextensional ring, in-plane flexural frequency of order `n >= 2`
/// (Hz), method §5: `n (n² - 1) / (2π R²) sqrt(EI / (m (n² + 1)))`.
pub fn free_ring_inextensional_hz(n: usize, radius_m: f64, ei_n_m2: f64, m_kg_m: f64) -> f64 {
    let nf = n as f64;
    nf * (nf * nf - 1.0) / (2.0 * PI * radius_m * radius_m)
        * (ei_n_m2 / (m_kg_m * (nf * nf + 1.0))).sqrt()
}

/// Row `i` of [`RingParams::sampled_responses`]: the pairs `(i, j)`,
/// `j >= i`, and their responses `g_ij(k dt)`, `k = 0..len`, sampled from
/// `model` ([`RingParams::sampling_model`]).
pub fn sampled_row(
    model: &ModalModel,
    i: usize,
    dt_s: f64,
    len: usize,
) -> (Vec<(usize, usize)>, Vec<Vec<f64>>) {
    (i..model.num_points)
        .map(|j| {
            let g = (0..len)
                .map(|k| model.green(i, j, k as f64 * dt_s).0)
                .collect();
            ((i, j), g)
        })
        .unzip()
}
