//! The paper's α/β fast convolution (paper eqs. 4-6, 9, 28-29), kept as a
//! **baseline only**: it accumulates
//! `α(t) = ∫_0^t e^{ξωτ} cos(ω_d τ) q dτ`, `β(t) = ∫_0^t e^{ξωτ} sin(ω_d τ) q dτ`
//! and multiplies by `e^{-ξωt}`, which overflows in float64 once
//! `ξωt > 709.78` (method §3). The solver never uses it.

/// One underdamped mode, single source, force constant over each step.
#[derive(Debug, Clone)]
pub struct AlphaBeta {
    a: f64,
    wd: f64,
    dt_s: f64,
    alpha: f64,
    beta: f64,
    t_s: f64,
}

impl AlphaBeta {
    /// `omega` (rad/s), `xi < 1`, step `dt_s`.
    pub fn new(omega: f64, xi: f64, dt_s: f64) -> Self {
        AlphaBeta {
            a: xi * omega,
            wd: omega * ((1.0 - xi) * (1.0 + xi)).sqrt(),
            dt_s,
            alpha: 0.0,
            beta: 0.0,
            t_s: 0.0,
        }
    }

    /// Advances one step with force `q` (N) constant over it; returns the
    /// displacement of the unit-mass oscillator at the step end, which becomes
    /// NaN or infinite once `e^{ξωt}` overflows.
    pub fn step(&mut self, q: f64) -> f64 {
        let (t0, t1) = (self.t_s, self.t_s + self.dt_s);
        // ∫ e^{(a + i ω_d) τ} dτ = e^{lτ}/l, evaluated between t0 and t1
        let prim = |t: f64| {
            let e = (self.a * t).exp();
            let (s, c) = (self.wd * t).sin_cos();
            let d = self.a * self.a + self.wd * self.wd;
            // Re and Im of e^{lt} / l
            let re = e * (c * self.a + s * self.wd) / d;
            let im = e * (s * self.a - c * self.wd) / d;
            (re, im)
        };
        let (r1, i1) = prim(t1);
        let (r0, i0) = prim(t0);
        self.alpha += q * (r1 - r0);
        self.beta += q * (i1 - i0);
        self.t_s = t1;
        let (s, c) = (self.wd * t1).sin_cos();
        (-self.a * t1).exp() * (s * self.alpha - c * self.beta) / self.wd
    }

    /// Time (s) after which `e^{ξωt}` overflows float64.
    pub fn overflow_time_s(&self) -> f64 {
        f64::MAX.ln() / self.a
    }
}
