//! The unit oscillator of method §2 in closed form, from its poles, written
//! from docs/method.md alone (not the crate's code): the reference of the exact-step
//! and plain-scheme checks.

/// Minimal complex arithmetic.
#[derive(Clone, Copy, Debug)]
pub struct C {
    pub re: f64,
    pub im: f64,
}

impl C {
    pub fn new(re: f64, im: f64) -> Self {
        C { re, im }
    }
    pub fn add(self, o: C) -> C {
        C::new(self.re + o.re, self.im + o.im)
    }
    pub fn sub(self, o: C) -> C {
        C::new(self.re - o.re, self.im - o.im)
    }
    pub fn mul(self, o: C) -> C {
        C::new(
            self.re * o.re - self.im * o.im,
            self.re * o.im + self.im * o.re,
        )
    }
    pub fn div(self, o: C) -> C {
        let d = o.re * o.re + o.im * o.im;
        C::new(
            (self.re * o.re + self.im * o.im) / d,
            (self.im * o.re - self.re * o.im) / d,
        )
    }
    pub fn scale(self, s: f64) -> C {
        C::new(self.re * s, self.im * s)
    }
    pub fn exp(self) -> C {
        let e = self.re.exp();
        C::new(e * self.im.cos(), e * self.im.sin())
    }
}

/// The four integrals of the unit oscillator `h'' + 2ξωh' + ω²h = δ` over
/// `[0, τ]` that every step quantity is made of:
/// `(h(τ), h'(τ), I0 = ∫_0^τ h, I1 = ∫_0^τ s h(s) ds)`, from the pole form
/// `h = (e^{l₊t} - e^{l₋t}) / (l₊ - l₋)` (double pole at `ξ = 1`).
pub fn integrals(omega: f64, xi: f64, tau: f64) -> (f64, f64, f64, f64) {
    if xi == 1.0 {
        // double pole -ω: h = t e^{-ωt}
        let e = (-omega * tau).exp();
        let wt = omega * tau;
        return (
            tau * e,
            e * (1.0 - wt),
            (1.0 - e * (1.0 + wt)) / (omega * omega),
            (2.0 - e * (wt * wt + 2.0 * wt + 2.0)) / omega.powi(3),
        );
    }
    let a = xi * omega;
    // poles l₊, l₋ (the slow real pole without cancellation)
    let (lp, lm) = if xi < 1.0 {
        let wd = omega * ((1.0 - xi) * (1.0 + xi)).sqrt();
        (C::new(-a, wd), C::new(-a, -wd))
    } else {
        let kappa = omega * ((xi - 1.0) * (xi + 1.0)).sqrt();
        (
            C::new(-omega * omega / (a + kappa), 0.0),
            C::new(-a - kappa, 0.0),
        )
    };
    let one = C::new(1.0, 0.0);
    let f = |l: C| {
        let e = l.scale(tau).exp();
        let j0 = e.sub(one).div(l);
        let j1 = e.mul(l.scale(tau).sub(one)).add(one).div(l.mul(l));
        [e, l.mul(e), j0, j1]
    };
    let (fp, fm) = (f(lp), f(lm));
    let den = lp.sub(lm);
    let g = |k: usize| fp[k].sub(fm[k]).div(den).re;
    (g(0), g(1), g(2), g(3))
}

/// `(x, v)` at `τ` from rest under `q(σ) = c0 + c1 σ`, `σ ∈ [0, τ]`.
pub fn linear_response(ints: (f64, f64, f64, f64), tau: f64, c0: f64, c1: f64) -> [f64; 2] {
    let (h, _, i0, i1) = ints;
    // ∫ h(τ-σ) σ dσ = τ I0 - I1;  ∫ h'(τ-σ) σ dσ = I0 (h(0) = 0)
    [c0 * i0 + c1 * (tau * i0 - i1), c0 * h + c1 * i0]
}

/// Free propagator `Φ(τ)` of `(x, v)`: `x(τ) = x0 (h' + 2ξωh) + v0 h`,
/// `v(τ) = -ω² x0 h + v0 h'`, row-major.
pub fn propagator(omega: f64, xi: f64, tau: f64) -> [f64; 4] {
    let (h, hd, _, _) = integrals(omega, xi, tau);
    [hd + 2.0 * xi * omega * h, h, -omega * omega * h, hd]
}

/// Weights `[x, v]` of `q1`, `q2`, the values at the two Gauss points
/// `(1 ∓ 1/√3) τ / 2` of a force linear over the step (method §4 step 3).
pub fn gauss_weights(omega: f64, xi: f64, tau: f64) -> [[f64; 2]; 2] {
    let ints = integrals(omega, xi, tau);
    let s1 = 0.5 * (1.0 - 1.0 / 3f64.sqrt()) * tau;
    let s2 = 0.5 * (1.0 + 1.0 / 3f64.sqrt()) * tau;
    let d = s2 - s1;
    [
        linear_response(ints, tau, s2 / d, -1.0 / d),
        linear_response(ints, tau, -s1 / d, 1.0 / d),
    ]
}
