//! The exact step of one mode (method §3): propagator `Φ(τ)` and the weights
//! of constant and linear (Gauss-point) forces, by a Taylor series on
//! `τ/2^s` and `s` exact doublings; four modes at a time for step tables.

/// `(1 + √3)/2` and `(√3 - 1)/2`: values at the step ends of the Lagrange
/// basis through the Gauss points `t1,2 = (1 ∓ 1/√3) τ/2` (method eq. 27).
const GA: f64 = 1.366_025_403_784_438_6;
const GB: f64 = 0.366_025_403_784_438_6;

/// Exact propagator and force weights of one mode over a step `τ`.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ModeStep {
    /// `Φ(τ)` row-major: `[φ_xx, φ_xv, φ_vx, φ_vv]`.
    pub phi: [f64; 4],
    /// Weight `(x, v)` of a force constant over the step: `∫_0^τ e^{Aσ} b dσ`.
    pub w_const: [f64; 2],
    /// Weights of `q1`, `q2`, the values of a linear force at the two Gauss points.
    pub w_gauss: [[f64; 2]; 2],
    /// Weights of `q(t)`, `q(t + τ)`, the values of a linear force at the step ends.
    pub w_ends: [[f64; 2]; 2],
    /// `h(τ)`, `h'(τ)`.
    pub h: [f64; 2],
}

/// `1/n` for the Taylor terms of [`mode_step`] (index 0 unused).
const RECIPROCALS: [f64; 84] = {
    let mut r = [0.0; 84];
    let mut n = 1;
    while n < 84 {
        r[n] = 1.0 / n as f64;
        n += 1;
    }
    r
};

/// Exact step of the unit oscillator `h'' + 2ξω h' + ω² h = δ` over `tau_s`.
pub fn mode_step(omega: f64, xi: f64, tau_s: f64) -> ModeStep {
    let setup = Setup::new(omega, xi, tau_s);
    let [series] = taylor_series([&setup]);
    setup.finish(series, tau_s)
}

/// [`mode_step`] of every mode into `out`, four modes at a time through the
/// Taylor series (four independent chains of dependent operations in flight
/// instead of one: the series is latency-bound). Same results, bit for bit.
pub fn mode_steps_into(modes: &[(f64, f64)], tau_s: f64, out: &mut Vec<ModeStep>) {
    out.clear();
    let mut chunks = modes.chunks_exact(4);
    for c in chunks.by_ref() {
        let setups = [0, 1, 2, 3].map(|k| Setup::new(c[k].0, c[k].1, tau_s));
        let series = taylor_series4(&setups);
        for (st, se) in setups.iter().zip(series) {
            out.push(st.finish(se, tau_s));
        }
    }
    let rest = chunks.remainder();
    if !rest.is_empty() && wide_lanes() {
        // the last one to three modes in four lanes too, the spare lanes
        // repeating the last mode (lanes are independent: the same bits)
        let setups: [Setup; 4] = std::array::from_fn(|k| {
            let (w, xi) = rest[k.min(rest.len() - 1)];
            Setup::new(w, xi, tau_s)
        });
        let series = taylor_series4(&setups);
        for (st, se) in setups.iter().zip(series).take(rest.len()) {
            out.push(st.finish(se, tau_s));
        }
    } else {
        out.extend(rest.iter().map(|&(w, xi)| mode_step(w, xi, tau_s)));
    }
}

/// Whether [`taylor_series4`] runs in AVX lanes (four modes for the price
/// of about one).
#[inline]
fn wide_lanes() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::arch::is_x86_feature_detected!("avx")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// A mode's step split into `s` doublings of a sub-step `δ` with `λ δ <= 0.5`.
struct Setup {
    a: f64,
    w2: f64,
    delta: f64,
    s: u32,
}

/// Sums of the Taylor series over `δ`: `h`, `h'`, `∫h`, `∫σh`, `∫σh'`.
#[derive(Clone, Copy, Default)]
struct Series {
    h: f64,
    hd: f64,
    i0: f64,
    m1: f64,
    mv: f64,
}

impl Setup {
    fn new(omega: f64, xi: f64, tau_s: f64) -> Self {
        let a = xi * omega;
        let w2 = omega * omega;
        let lam = omega + 2.0 * a;
        let mut s = 0u32;
        let mut delta = tau_s;
        while lam * delta > 0.5 && s < 200 {
            delta *= 0.5;
            s += 1;
        }
        Setup { a, w2, delta, s }
    }
}

/// The Taylor series of `L` modes in lock step; each lane stops adding
/// terms at its own convergence (its increments multiplied by 0 from then
/// on), as [`mode_step`] alone would: bit-identical. Four lanes run through
/// an AVX build where the CPU has it.
#[inline]
fn taylor_series<const L: usize>(setups: [&Setup; L]) -> [Series; L] {
    #[cfg(target_arch = "x86_64")]
    {
        if L > 1 && std::arch::is_x86_feature_detected!("avx") {
            #[target_feature(enable = "avx")]
            fn wide<const L: usize>(setups: [&Setup; L]) -> [Series; L] {
                taylor_series_body(setups)
            }
            // SAFETY: the CPU supports AVX (checked just above).
            return unsafe { wide(setups) };
        }
    }
    taylor_series_body(setups)
}

/// [`taylor_series`] of four modes: in the lanes of AVX registers where
/// the CPU has AVX (the compiler kept the four lanes of the generic code
/// scalar), else the generic code.
#[inline]
fn taylor_series4(setups: &[Setup; 4]) -> [Series; 4] {
    #[cfg(target_arch = "x86_64")]
    {
        if std::arch::is_x86_feature_detected!("avx") {
            // SAFETY: the CPU supports AVX (checked just above).
            return unsafe { taylor_series4_avx(setups) };
        }
    }
    taylor_series([&setups[0], &setups[1], &setups[2], &setups[3]])
}

/// [`taylor_series_body`] for four lanes, written with AVX intrinsics: the
/// same operations in the same order per lane, no FMA (bit-identical; a
/// lane's convergence zeroes its `live` factor as there).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
fn taylor_series4_avx(setups: &[Setup; 4]) -> [Series; 4] {
    use std::arch::x86_64::*;
    let lanes = |f: &dyn Fn(&Setup) -> f64| -> __m256d {
        let a = [f(&setups[0]), f(&setups[1]), f(&setups[2]), f(&setups[3])];
        // SAFETY: `a` holds four f64.
        unsafe { _mm256_loadu_pd(a.as_ptr()) }
    };
    let delta = lanes(&|st| st.delta);
    // the scalar code's products, in its order
    let m2ad = lanes(&|st| -2.0 * (st.a * st.delta));
    let wd2 = lanes(&|st| st.w2 * st.delta * st.delta);
    let dd = lanes(&|st| st.delta * st.delta);
    let inv_delta = lanes(&|st| 1.0 / st.delta);
    let tol = lanes(&|st| 1e-18 * st.delta);
    let zero = _mm256_setzero_pd();
    let sign = _mm256_set1_pd(-0.0);
    let (mut t0, mut t1) = (zero, delta);
    let (mut h, mut hd, mut i0, mut m1, mut mv) = (zero, zero, zero, zero, zero);
    let mut live = _mm256_set1_pd(1.0);
    let mut n = 0usize;
    loop {
        let nf1 = _mm256_set1_pd(n as f64 + 1.0);
        let (r1, r2) = (RECIPROCALS[n + 1], RECIPROCALS[n + 2]);
        let (r1v, r2v, r21) = (
            _mm256_set1_pd(r1),
            _mm256_set1_pd(r2),
            _mm256_set1_pd(r2 * r1),
        );
        let mul = |a, b| _mm256_mul_pd(a, b);
        h = _mm256_add_pd(h, mul(t0, live));
        i0 = _mm256_add_pd(i0, mul(mul(mul(t0, delta), r1v), live));
        m1 = _mm256_add_pd(m1, mul(mul(mul(t0, dd), r2v), live));
        let t1n = mul(t1, nf1);
        hd = _mm256_add_pd(hd, mul(mul(t1n, inv_delta), live));
        mv = _mm256_add_pd(mv, mul(mul(mul(t1n, delta), r2v), live));
        let t2 = _mm256_sub_pd(mul(mul(m2ad, t1), r2v), mul(mul(wd2, t0), r21));
        t0 = t1;
        t1 = t2;
        n += 1;
        if n > 80 {
            live = zero;
        } else if n > 3 {
            let small = |t| _mm256_cmp_pd::<_CMP_LE_OQ>(_mm256_andnot_pd(sign, t), tol);
            let converged = _mm256_and_pd(small(t0), small(t1));
            live = _mm256_andnot_pd(converged, live);
        }
        if _mm256_movemask_pd(_mm256_cmp_pd::<_CMP_NEQ_UQ>(live, zero)) == 0 {
            let out = |v: __m256d| {
                let mut a = [0.0f64; 4];
                // SAFETY: `a` holds four f64.
                unsafe { _mm256_storeu_pd(a.as_mut_ptr(), v) };
                a
            };
            return lanes_to_series([out(h), out(hd), out(i0), out(m1), out(mv)]);
        }
    }
}

#[inline(always)]
fn taylor_series_body<const L: usize>(setups: [&Setup; L]) -> [Series; L] {
    // Taylor series on delta: T_n = c_n δ^n / n!, c_0 = 0, c_1 = 1,
    // c_{n+2} = -2a c_{n+1} - ω² c_n.
    let delta = setups.map(|st| st.delta);
    let ad = setups.map(|st| st.a * st.delta);
    let wd2 = setups.map(|st| st.w2 * st.delta * st.delta);
    let dd = delta.map(|d| d * d);
    let inv_delta = delta.map(|d| 1.0 / d);
    let tol = delta.map(|d| 1e-18 * d);
    let mut t0 = [0.0f64; L];
    let mut t1 = delta;
    let (mut h, mut hd, mut i0, mut m1, mut mv) =
        ([0.0f64; L], [0.0; L], [0.0; L], [0.0; L], [0.0; L]);
    // 1 while a lane adds terms, 0 after its convergence
    let mut live = [1.0f64; L];
    let mut n = 0usize;
    loop {
        let nf = n as f64;
        // reciprocals from the table: no division in the loop
        let (r1, r2) = (RECIPROCALS[n + 1], RECIPROCALS[n + 2]);
        for l in 0..L {
            // term n of h, I0, M1 uses T_n; of h', ∫σh' uses T_{n+1}
            h[l] += t0[l] * live[l];
            i0[l] += t0[l] * delta[l] * r1 * live[l];
            m1[l] += t0[l] * dd[l] * r2 * live[l];
            hd[l] += t1[l] * (nf + 1.0) * inv_delta[l] * live[l];
            mv[l] += t1[l] * (nf + 1.0) * delta[l] * r2 * live[l];
            let t2 = -2.0 * ad[l] * t1[l] * r2 - wd2[l] * t0[l] * (r2 * r1);
            t0[l] = t1[l];
            t1[l] = t2;
        }
        n += 1;
        let mut any = false;
        for l in 0..L {
            let converged = n > 3 && t0[l].abs() <= tol[l] && t1[l].abs() <= tol[l] || n > 80;
            if converged {
                live[l] = 0.0;
            }
            any |= live[l] != 0.0;
        }
        if !any {
            return lanes_to_series([h, hd, i0, m1, mv]);
        }
    }
}

/// Per-lane sums `[h, h', ∫h, ∫σh, ∫σh']` as one [`Series`] per lane.
#[inline(always)]
fn lanes_to_series<const L: usize>([h, hd, i0, m1, mv]: [[f64; L]; 5]) -> [Series; L] {
    std::array::from_fn(|l| Series {
        h: h[l],
        hd: hd[l],
        i0: i0[l],
        m1: m1[l],
        mv: mv[l],
    })
}

impl Setup {
    /// The doublings from `δ` to `τ`, and the step's propagator and weights.
    fn finish(&self, series: Series, tau_s: f64) -> ModeStep {
        let (a, w2, mut delta) = (self.a, self.w2, self.delta);
        let Series { h, hd, i0, m1, mv } = series;
        // Doublings: e = (h, h'), g0 = ∫ e, gm = ∫ σ e.
        let mut e = [h, hd];
        let mut g0 = [i0, h];
        let mut gm = [m1, mv];
        for _ in 0..self.s {
            let phi = phi_of(e, a, w2);
            let apply =
                |p: &[f64; 4], y: [f64; 2]| [p[0] * y[0] + p[1] * y[1], p[2] * y[0] + p[3] * y[1]];
            let shifted = [gm[0] + delta * g0[0], gm[1] + delta * g0[1]];
            let pg = apply(&phi, shifted);
            gm = [gm[0] + pg[0], gm[1] + pg[1]];
            let p0 = apply(&phi, g0);
            g0 = [g0[0] + p0[0], g0[1] + p0[1]];
            e = apply(&phi, e);
            delta *= 2.0;
        }
        let phi = phi_of(e, a, w2);
        let g1 = [gm[0] / tau_s, gm[1] / tau_s]; // ∫ (σ/τ) e^{Aσ} b dσ
        let w_start = g1;
        let w_end = [g0[0] - g1[0], g0[1] - g1[1]];
        let w_gauss = [
            [
                GA * w_start[0] - GB * w_end[0],
                GA * w_start[1] - GB * w_end[1],
            ],
            [
                -GB * w_start[0] + GA * w_end[0],
                -GB * w_start[1] + GA * w_end[1],
            ],
        ];
        ModeStep {
            phi,
            w_const: g0,
            w_gauss,
            w_ends: [w_start, w_end],
            h: e,
        }
    }
}

#[inline]
fn phi_of(e: [f64; 2], a: f64, w2: f64) -> [f64; 4] {
    let (h, hd) = (e[0], e[1]);
    [hd + 2.0 * a * h, h, -w2 * h, hd]
}
