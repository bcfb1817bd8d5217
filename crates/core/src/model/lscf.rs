//! Frequency-domain identification of measured FRFs (method §6.5): poles by
//! the polyreference least-squares complex-frequency method (LSCF, the
//! "PolyMAX" form: a right matrix-fraction model in the z-domain basis with
//! real coefficients, normal equations reduced per output) over a
//! stabilisation diagram; residues of every measured pair by least squares
//! in the frequency domain (LSFD) with lower and upper residual terms; and
//! real (proportional) modal constants without residual terms, the form a
//! contact model uses.
//!
//! Every fit is made in the ordinate the data hold (receptance, mobility,
//! accelerance): the pole-residue model is multiplied by `(jω)^q`
//! (method §6.5.2), the data are never divided by `ω`.

use crate::base::linalg::{self, LinalgError};
use faer::{Mat, c64};
use std::f64::consts::TAU;

/// What an FRF's values are: response over force, the response
/// displacement (`q = 0`), velocity (`q = 1`) or acceleration (`q = 2`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ordinate {
    Receptance,
    Mobility,
    Accelerance,
}

impl Ordinate {
    /// The power `q` of `jω` that makes a receptance this ordinate.
    pub fn power(self) -> i32 {
        match self {
            Ordinate::Receptance => 0,
            Ordinate::Mobility => 1,
            Ordinate::Accelerance => 2,
        }
    }

    /// Its SI unit.
    pub fn units(self) -> &'static str {
        match self {
            Ordinate::Receptance => "m/N",
            Ordinate::Mobility => "m/(s·N)",
            Ordinate::Accelerance => "m/(s²·N)",
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Ordinate::Receptance => "receptance",
            Ordinate::Mobility => "mobility",
            Ordinate::Accelerance => "accelerance",
        }
    }

    /// `(jω)^q` at `ω` (rad/s).
    pub fn factor(self, omega: f64) -> c64 {
        let jw = c64::new(0.0, omega);
        match self {
            Ordinate::Receptance => c64::new(1.0, 0.0),
            Ordinate::Mobility => jw,
            Ordinate::Accelerance => jw * jw,
        }
    }
}

/// FRFs of measured pairs over one band, in SI, in one ordinate.
#[derive(Debug, Clone, PartialEq)]
pub struct FrfSet {
    /// Frequencies (Hz), increasing, all `> 0`.
    pub freq_hz: Vec<f64>,
    pub ordinate: Ordinate,
    /// `(response, reference)` of each FRF, indices of the caller's degrees
    /// of freedom.
    pub pairs: Vec<(usize, usize)>,
    /// `H[pair][frequency]`.
    pub h: Vec<Vec<c64>>,
}

/// A fit that cannot be made: the input, or a decomposition.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FitError {
    #[error("{0}")]
    Input(String),
    #[error(transparent)]
    Linalg(#[from] LinalgError),
}

/// Options of the frequency-domain fit (method §6.5).
#[derive(Debug, Clone, PartialEq)]
pub struct FitOptions {
    /// Highest polynomial order of the stabilisation diagram, as a pole
    /// count: each order `p` gives `p·N_i` poles (`N_i` the references of
    /// the polyreference model), the diagram goes to `max_order / N_i`.
    pub max_order: usize,
    /// The polynomial order whose poles are kept; `None`: the diagram's
    /// highest.
    pub order: Option<usize>,
    /// Largest damping ratio of a kept pole (-).
    pub max_damping_ratio: f64,
    /// Stable: relative frequency change between orders (-).
    pub freq_tol: f64,
    /// Stable: relative damping change between orders (-).
    pub damping_tol: f64,
    /// Stable: smallest MAC of the participation vectors (-), when there
    /// are several references.
    pub mac_min: f64,
    /// A kept pole is stable in frequency at this many orders below the
    /// chosen one.
    pub persist: usize,
}

impl Default for FitOptions {
    fn default() -> Self {
        FitOptions {
            max_order: 40,
            order: None,
            max_damping_ratio: 0.2,
            freq_tol: 0.01,
            damping_tol: 0.05,
            mac_min: 0.98,
            persist: 5,
        }
    }
}

/// How a pole compares with the order below (stabilisation diagram).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PoleStability {
    /// Frequency, damping and participation vector.
    Stable,
    /// Frequency and damping.
    FrequencyDamping,
    /// Frequency only.
    Frequency,
    New,
}

/// A pole `λ = −ξω + jω√(1−ξ²)` found by LSCF.
#[derive(Debug, Clone, PartialEq)]
pub struct Pole {
    pub freq_hz: f64,
    pub damping_ratio: f64,
    /// The participation vector (one entry per reference of the
    /// polyreference model), unit norm.
    pub participation: Vec<c64>,
    pub stability: PoleStability,
}

impl Pole {
    /// `λ` (rad/s).
    pub fn lambda(&self) -> c64 {
        let w = TAU * self.freq_hz;
        let xi = self.damping_ratio;
        c64::new(-xi * w, w * ((1.0 - xi) * (1.0 + xi)).max(0.0).sqrt())
    }

    fn from_lambda(s: c64, participation: Vec<c64>) -> Self {
        let w = s.norm();
        Pole {
            freq_hz: w / TAU,
            damping_ratio: -s.re / w,
            participation,
            stability: PoleStability::New,
        }
    }
}

/// The in-band poles of one polynomial order.
#[derive(Debug, Clone, PartialEq)]
pub struct DiagramOrder {
    pub order: usize,
    pub poles: Vec<Pole>,
}

/// The polyreference layout: which pairs form each output's row of
/// `N_i` references.
#[derive(Debug, Clone, PartialEq)]
struct Layout {
    /// `rows[o][i]`: the pair of output `o`, reference `i`.
    rows: Vec<Vec<usize>>,
}

/// A complete grid of responses × references (or its transpose, by
/// reciprocity) with at least two of each makes a polyreference model with
/// the smaller count as references; anything else (a row, a column, an
/// incomplete matrix) a common-denominator model, every pair an output.
fn layout(pairs: &[(usize, usize)]) -> Layout {
    let mut resp: Vec<usize> = pairs.iter().map(|p| p.0).collect();
    let mut refs: Vec<usize> = pairs.iter().map(|p| p.1).collect();
    resp.sort_unstable();
    resp.dedup();
    refs.sort_unstable();
    refs.dedup();
    let find = |o: usize, i: usize| pairs.iter().position(|&p| p == (o, i));
    if resp.len() >= 2 && refs.len() >= 2 && resp.len() * refs.len() == pairs.len() {
        let (outs, ins, swap) = if refs.len() <= resp.len() {
            (&resp, &refs, false)
        } else {
            (&refs, &resp, true)
        };
        let rows: Option<Vec<Vec<usize>>> = outs
            .iter()
            .map(|&o| {
                ins.iter()
                    .map(|&i| if swap { find(i, o) } else { find(o, i) })
                    .collect()
            })
            .collect();
        if let Some(rows) = rows {
            return Layout { rows };
        }
    }
    Layout {
        rows: (0..pairs.len()).map(|k| vec![k]).collect(),
    }
}

/// Checks a set's shape and values.
fn check(set: &FrfSet) -> Result<(), FitError> {
    let nf = set.freq_hz.len();
    if set.pairs.is_empty() || set.pairs.len() != set.h.len() {
        return Err(FitError::Input("no FRFs to fit".into()));
    }
    if nf < 8 {
        return Err(FitError::Input(format!(
            "{nf} frequencies in the band: expected at least 8"
        )));
    }
    if set.freq_hz.iter().any(|f| !(f.is_finite() && *f > 0.0))
        || set.freq_hz.windows(2).any(|w| w[1] <= w[0])
    {
        return Err(FitError::Input(
            "frequencies: expected increasing values above 0 Hz".into(),
        ));
    }
    for h in &set.h {
        if h.len() != nf {
            return Err(FitError::Input(format!(
                "an FRF of {} values: expected one per frequency ({nf})",
                h.len()
            )));
        }
        if h.iter().any(|v| !(v.re.is_finite() && v.im.is_finite())) {
            return Err(FitError::Input("an FRF holds a non-finite value".into()));
        }
    }
    Ok(())
}

/// The lag sums of one output (method §6.5.1, eq. LSCF-3): `ρ(d) = Σ_f
/// cos(ω_f Δt d)`, `σ_i(d) = Re Σ_f e^{jω_fΔt d} H_i`, `τ_ij(d) = Re Σ_f
/// e^{jω_fΔt d} H_i* H_j` for `d = −p…p`, stored at `d + p`.
struct LagSums {
    sigma: Vec<Vec<f64>>,
    tau: Vec<Vec<Vec<f64>>>,
}

/// The stabilisation diagram of `set` over orders `1..=opts.max_order`
/// (method §6.5.1): poles in `band_hz` with `0 < ξ < max_damping_ratio`,
/// each marked against the order below.
pub fn stabilisation(
    set: &FrfSet,
    band_hz: (f64, f64),
    opts: &FitOptions,
) -> Result<Vec<DiagramOrder>, FitError> {
    check(set)?;
    let lay = layout(&set.pairs);
    let ni = lay.rows[0].len();
    // the same number of poles whatever the references: order p gives p·N_i
    let p_max = match opts.order {
        Some(p) => p.max(opts.max_order / ni),
        None => opts.max_order / ni,
    }
    .max(1);
    let nf = set.freq_hz.len();
    let f_hi = set.freq_hz[nf - 1];
    let dt = 0.5 / f_hi;
    // each output's row scaled to unit RMS: every output weighs alike (one
    // factor per row keeps the common denominator of its references)
    let scale: Vec<f64> = lay
        .rows
        .iter()
        .map(|row| {
            let ss: f64 = row
                .iter()
                .map(|&k| set.h[k].iter().map(|v| v.norm_sqr()).sum::<f64>())
                .sum();
            let s = (ss / (nf * row.len()) as f64).sqrt();
            if s > 0.0 { 1.0 / s } else { 0.0 }
        })
        .collect();
    let lags = 2 * p_max + 1;
    // e^{jω_fΔt d}, d = −p…p
    let phase: Vec<Vec<c64>> = set
        .freq_hz
        .iter()
        .map(|f| {
            let th = TAU * f * dt;
            (0..lags)
                .map(|l| {
                    let d = l as f64 - p_max as f64;
                    c64::new((th * d).cos(), (th * d).sin())
                })
                .collect()
        })
        .collect();
    let rho: Vec<f64> = (0..lags)
        .map(|l| phase.iter().map(|e| e[l].re).sum())
        .collect();
    let sums: Vec<LagSums> = lay
        .rows
        .iter()
        .zip(&scale)
        .map(|(row, &g)| {
            let hs: Vec<Vec<c64>> = row
                .iter()
                .map(|&k| set.h[k].iter().map(|v| v * g).collect())
                .collect();
            let sigma = (0..ni)
                .map(|i| {
                    (0..lags)
                        .map(|l| (0..nf).map(|f| (phase[f][l] * hs[i][f]).re).sum())
                        .collect()
                })
                .collect();
            let tau = (0..ni)
                .map(|i| {
                    (0..ni)
                        .map(|j| {
                            (0..lags)
                                .map(|l| {
                                    (0..nf)
                                        .map(|f| (phase[f][l] * hs[i][f].conj() * hs[j][f]).re)
                                        .sum()
                                })
                                .collect()
                        })
                        .collect()
                })
                .collect();
            LagSums { sigma, tau }
        })
        .collect();
    let mut diagram: Vec<DiagramOrder> = Vec::with_capacity(p_max);
    for p in 1..=p_max {
        let poles = poles_of_order(&rho, &sums, ni, p, p_max, dt, band_hz, opts)?;
        let poles = match diagram.last() {
            Some(prev) => mark(poles, &prev.poles, opts),
            None => poles,
        };
        diagram.push(DiagramOrder { order: p, poles });
    }
    Ok(diagram)
}

/// The poles of order `p` (method §6.5.1): the reduced normal equations
/// `M = Σ_o (T_o − S_oᵀ R⁻¹ S_o)` (eq. LSCF-4) solved with `α_p = I`, the
/// roots of `det Σ z^r α_r = 0` the eigenvalues of the block companion
/// matrix, `λ = ln(z) / Δt` (eq. LSCF-5).
fn poles_of_order(
    rho: &[f64],
    sums: &[LagSums],
    ni: usize,
    p: usize,
    p_max: usize,
    dt: f64,
    band_hz: (f64, f64),
    opts: &FitOptions,
) -> Result<Vec<Pole>, FitError> {
    let n = p + 1;
    let lag = |r: usize, s: usize| (s as isize - r as isize + p_max as isize) as usize;
    let r_mat = Mat::from_fn(n, n, |r, s| rho[lag(r, s)]);
    let na = n * ni;
    let mut m = Mat::<f64>::zeros(na, na);
    // the same R for every output: one decomposition, all outputs' S at once
    let s_all = Mat::from_fn(n, sums.len() * na, |r, c| {
        let (o, rest) = (c / na, c % na);
        let (s, i) = (rest / ni, rest % ni);
        -sums[o].sigma[i][lag(r, s)]
    });
    let (rinv_s, _) = linalg::lstsq(r_mat.as_ref(), s_all.as_ref(), 1e-14)?;
    for (o, sum) in sums.iter().enumerate() {
        // S_oᵀ R⁻¹ S_o as one matrix product (a scalar triple loop took a
        // quarter of a 140-order diagram)
        let cols = o * na..(o + 1) * na;
        let s_o = s_all.as_ref().subcols(cols.start, na);
        let rinv_s_o = rinv_s.as_ref().subcols(cols.start, na);
        let srs = s_o.transpose() * rinv_s_o;
        for a in 0..na {
            let (r, i) = (a / ni, a % ni);
            for b in 0..na {
                let (s, j) = (b / ni, b % ni);
                m[(a, b)] += sum.tau[i][j][lag(r, s)] - srs[(a, b)];
            }
        }
    }
    let k = p * ni;
    let maa = Mat::from_fn(k, k, |a, b| m[(a, b)]);
    let mab = Mat::from_fn(k, ni, |a, b| -m[(a, k + b)]);
    let (alpha, _) = linalg::lstsq(maa.as_ref(), mab.as_ref(), 1e-14)?;
    // left null vectors l of A(z) = Σ z^r α_r: z x = C x with x = [l; z l; …],
    // the last block row −α_rᵀ
    let comp = Mat::from_fn(k, k, |a, b| {
        if a < k - ni {
            if b == a + ni { 1.0 } else { 0.0 }
        } else {
            let (r, i) = (b / ni, b % ni);
            -alpha[(r * ni + i, a - (k - ni))]
        }
    });
    linalg::sequential();
    let eig = comp
        .eigen()
        .map_err(|_| LinalgError::NoConvergence { what: "eigen" })?;
    let (u, s) = (eig.U(), eig.S().column_vector());
    // each eigenpair checked: ‖C v − z v‖ ≤ 1e-8 ‖C‖_F ‖v‖
    let c_norm = linalg::frobenius(comp.as_ref());
    // C V as one matrix product (the check's sums one by one took a tenth
    // of a 140-order diagram)
    let comp_c = Mat::<c64>::from_fn(k, k, |a, b| c64::new(comp[(a, b)], 0.0));
    let cu = &comp_c * u;
    for e in 0..k {
        let v_norm = (0..k).map(|a| u[(a, e)].norm_sqr()).sum::<f64>().sqrt();
        let res = (0..k)
            .map(|a| (cu[(a, e)] - s[e] * u[(a, e)]).norm_sqr())
            .sum::<f64>()
            .sqrt();
        let residual = res / (c_norm * v_norm).max(f64::MIN_POSITIVE);
        if residual.is_nan() || residual > 1e-8 {
            return Err(LinalgError::Rebuild {
                what: "companion eigenpairs",
                residual,
                limit: 1e-8,
            }
            .into());
        }
    }
    let mut poles = Vec::new();
    for e in 0..k {
        let z = s[e];
        if z.im <= 0.0 || z.norm() >= 1.0 || z.norm() == 0.0 {
            continue;
        }
        let lam = c64::new(z.norm().ln(), z.im.atan2(z.re)) / dt;
        let mut l: Vec<c64> = (0..ni).map(|i| u[(i, e)]).collect();
        let norm = l.iter().map(|v| v.norm_sqr()).sum::<f64>().sqrt();
        if norm > 0.0 {
            l.iter_mut().for_each(|v| *v /= norm);
        }
        let pole = Pole::from_lambda(lam, l);
        if pole.freq_hz >= band_hz.0
            && pole.freq_hz <= band_hz.1
            && pole.damping_ratio > 0.0
            && pole.damping_ratio < opts.max_damping_ratio
        {
            poles.push(pole);
        }
    }
    poles.sort_by(|a, b| a.freq_hz.total_cmp(&b.freq_hz));
    Ok(poles)
}

/// Modal assurance criterion of two complex vectors (-).
pub fn mac(a: &[c64], b: &[c64]) -> f64 {
    let dot: c64 = a.iter().zip(b).map(|(x, y)| x.conj() * y).sum();
    let na: f64 = a.iter().map(|v| v.norm_sqr()).sum();
    let nb: f64 = b.iter().map(|v| v.norm_sqr()).sum();
    if na > 0.0 && nb > 0.0 {
        dot.norm_sqr() / (na * nb)
    } else {
        1.0
    }
}

/// Whether `a` matches `b` in frequency and damping within the options'
/// tolerances.
fn close(a: &Pole, b: &Pole, opts: &FitOptions) -> (bool, bool) {
    let f = (a.freq_hz - b.freq_hz).abs() <= opts.freq_tol * a.freq_hz;
    let x = (a.damping_ratio - b.damping_ratio).abs() <= opts.damping_tol * a.damping_ratio;
    (f, f && x)
}

/// Each pole marked against the order below: the best category any pole
/// there gives it (a polyreference model of a low-rank matrix has close
/// twins of a physical pole; the nearest in frequency may be the twin).
fn mark(mut poles: Vec<Pole>, below: &[Pole], opts: &FitOptions) -> Vec<Pole> {
    let rank = |s: PoleStability| match s {
        PoleStability::Stable => 3,
        PoleStability::FrequencyDamping => 2,
        PoleStability::Frequency => 1,
        PoleStability::New => 0,
    };
    for p in &mut poles {
        p.stability = below
            .iter()
            .map(|q| match close(p, q, opts) {
                (true, true) if mac(&p.participation, &q.participation) >= opts.mac_min => {
                    PoleStability::Stable
                }
                (true, true) => PoleStability::FrequencyDamping,
                (true, false) => PoleStability::Frequency,
                _ => PoleStability::New,
            })
            .max_by_key(|&s| rank(s))
            .unwrap_or(PoleStability::New);
    }
    poles
}

/// The kept poles: those of the chosen order that are stable (frequency,
/// damping, vector) against the order below and stable in frequency at
/// each of the `persist` orders below; two within the frequency tolerance
/// keep the first.
pub fn select(diagram: &[DiagramOrder], opts: &FitOptions) -> (usize, Vec<Pole>) {
    let order = opts.order.unwrap_or(diagram.len()).clamp(1, diagram.len());
    let at = |p: usize| &diagram[p - 1].poles;
    let mut kept: Vec<Pole> = Vec::new();
    for pole in at(order) {
        if pole.stability != PoleStability::Stable {
            continue;
        }
        let lowest = order.saturating_sub(opts.persist).max(1);
        let persists = (lowest..order).all(|q| at(q).iter().any(|b| close(pole, b, opts).0));
        let twin = kept.iter().any(|k| close(k, pole, opts).0);
        if persists && !twin {
            kept.push(pole.clone());
        }
    }
    (order, kept)
}

/// `ω` (rad/s) of each frequency.
fn omegas(set: &FrfSet) -> Vec<f64> {
    set.freq_hz.iter().map(|f| TAU * f).collect()
}

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

/// The L2 norm over every pair and frequency of pole `k`'s own term in the
/// complex fit, `(jω)^q [r/(jω−λ) + r*/(jω−λ*)]` with its residues
/// `residues[pair][k]`.
fn mode_contribution(set: &FrfSet, pole: &Pole, residues: &[Vec<c64>], k: usize) -> f64 {
    let lam = pole.lambda();
    let mut sum = 0.0;
    let w = omegas(set);
    for r in residues {
        let r = r[k];
        for &om in &w {
            let jw = c64::new(0.0, om);
            let g = set.ordinate.factor(om);
            sum += (g * (r / (jw - lam) + r.conj() / (jw - lam.conj()))).norm_sqr();
        }
    }
    sum.sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn layouts_pick_the_references_of_the_polyreference_model() {
        // a row, a column, an incomplete matrix: one reference
        for pairs in [
            vec![(0, 0), (0, 1), (0, 2)],
            vec![(0, 0), (1, 0), (2, 0)],
            vec![(0, 0), (0, 1), (1, 1)],
        ] {
            let l = layout(&pairs);
            assert!(l.rows.iter().all(|r| r.len() == 1), "{pairs:?}");
            assert_eq!(l.rows.len(), pairs.len());
        }
        // 3 responses × 2 references: two references, three outputs
        let pairs: Vec<(usize, usize)> = (0..3).flat_map(|o| (3..5).map(move |i| (o, i))).collect();
        let l = layout(&pairs);
        assert_eq!((l.rows.len(), l.rows[0].len()), (3, 2));
        assert_eq!(pairs[l.rows[2][1]], (2, 4));
        // 2 responses × 3 references: swapped by reciprocity
        let pairs: Vec<(usize, usize)> = (0..2).flat_map(|o| (2..5).map(move |i| (o, i))).collect();
        let l = layout(&pairs);
        assert_eq!((l.rows.len(), l.rows[0].len()), (3, 2));
        assert_eq!(pairs[l.rows[0][1]], (1, 2));
    }

    #[test]
    fn ordinates_multiply_by_powers_of_j_omega() {
        let w = 3.0;
        assert_eq!(Ordinate::Receptance.factor(w), c64::new(1.0, 0.0));
        assert_eq!(Ordinate::Mobility.factor(w), c64::new(0.0, 3.0));
        assert_eq!(Ordinate::Accelerance.factor(w), c64::new(-9.0, 0.0));
        let a = [c64::new(1.0, 2.0), c64::new(-0.5, 0.0)];
        let b: Vec<c64> = a.iter().map(|v| v * c64::new(0.0, -3.0)).collect();
        assert!((mac(&a, &b) - 1.0).abs() < 1e-15);
        assert!(mac(&a, &[c64::new(0.0, 0.0), c64::new(1.0, 0.0)]) < 0.1);
    }

    #[test]
    fn bad_sets_are_refused_not_panicked_on() {
        let good = FrfSet {
            freq_hz: (1..=10).map(f64::from).collect(),
            ordinate: Ordinate::Receptance,
            pairs: vec![(0, 0)],
            h: vec![vec![c64::new(1.0, 0.0); 10]],
        };
        let mut nan = good.clone();
        nan.h[0][3].re = f64::NAN;
        let mut short = good.clone();
        short.freq_hz.truncate(5);
        short.h[0].truncate(5);
        let mut zero = good.clone();
        zero.freq_hz[0] = 0.0;
        let mut ragged = good.clone();
        ragged.h[0].pop();
        for (set, want) in [
            (nan, "non-finite"),
            (short, "5 frequencies"),
            (zero, "above 0 Hz"),
            (ragged, "9 values"),
        ] {
            let e = stabilisation(&set, (0.0, 10.0), &FitOptions::default())
                .unwrap_err()
                .to_string();
            assert!(e.contains(want), "{e}");
            assert!(lsfd(&set, &[]).is_err());
        }
        // no poles: the fit is the residual terms alone, finite
        let fit = lsfd(&good, &[]).unwrap();
        assert!(fit.error.is_finite());
    }
}
