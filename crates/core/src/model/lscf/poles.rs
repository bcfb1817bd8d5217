//! The poles of LSCF (method §6.5.1): the polyreference layout, the lag
//! sums, the poles of each polynomial order, the stabilisation diagram and
//! the poles kept from it.

use super::{FitError, FitOptions, FrfSet, Pole, check, mac};
use crate::base::linalg::{self, LinalgError};
use crate::model::stability::{Criteria, DiagramOrder, Stability};
use faer::{Mat, c64};
use std::f64::consts::TAU;

/// The polyreference layout: which pairs form each output's row of
/// `N_i` references.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Layout {
    /// `rows[o][i]`: the pair of output `o`, reference `i`.
    pub(super) rows: Vec<Vec<usize>>,
}

/// A complete grid of responses × references (or its transpose, by
/// reciprocity) with at least two of each makes a polyreference model with
/// the smaller count as references; anything else (a row, a column, an
/// incomplete matrix) a common-denominator model, every pair an output.
pub(super) fn layout(pairs: &[(usize, usize)]) -> Layout {
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
    let criteria = opts.stability_criteria();
    let mut diagram: Vec<DiagramOrder> = Vec::with_capacity(p_max);
    // the poles of the order below and their participation vectors
    let mut below: Vec<(Pole, Vec<c64>)> = Vec::new();
    for p in 1..=p_max {
        let mut poles = poles_of_order(&rho, &sums, ni, p, p_max, dt, band_hz, opts)?;
        mark(&mut poles, &below, &criteria);
        diagram.push(DiagramOrder {
            order: p,
            poles: poles.iter().map(|(pole, _)| pole.clone()).collect(),
        });
        below = poles;
    }
    Ok(diagram)
}

/// The poles of order `p` (method §6.5.1): the reduced normal equations
/// `M = Σ_o (T_o − S_oᵀ R⁻¹ S_o)` (eq. LSCF-4) solved with `α_p = I`, the
/// roots of `det Σ z^r α_r = 0` the eigenvalues of the block companion
/// matrix, `λ = ln(z) / Δt` (eq. LSCF-5); each pole with its participation
/// vector (unit norm, one entry per reference), its category not yet known
/// ([`Stability::New`]).
fn poles_of_order(
    rho: &[f64],
    sums: &[LagSums],
    ni: usize,
    p: usize,
    p_max: usize,
    dt: f64,
    band_hz: (f64, f64),
    opts: &FitOptions,
) -> Result<Vec<(Pole, Vec<c64>)>, FitError> {
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
        let w = lam.norm();
        let pole = Pole {
            freq_hz: w / TAU,
            damping_ratio: -lam.re / w,
            stability: Stability::New,
        };
        if pole.freq_hz >= band_hz.0
            && pole.freq_hz <= band_hz.1
            && pole.damping_ratio > 0.0
            && pole.damping_ratio < opts.max_damping_ratio
        {
            poles.push((pole, l));
        }
    }
    poles.sort_by(|a, b| a.0.freq_hz.total_cmp(&b.0.freq_hz));
    Ok(poles)
}

/// Whether `a` matches `b` in frequency within the options' tolerance.
fn same_frequency(a: &Pole, b: &Pole, opts: &FitOptions) -> bool {
    (a.freq_hz - b.freq_hz).abs() <= opts.freq_tol * a.freq_hz
}

/// Each pole (with its participation vector) marked against the poles of
/// the order below by the LSCF criteria ([`FitOptions::stability_criteria`]:
/// the best category any pole there gives it, the shape compared the
/// participation vectors' MAC).
fn mark(poles: &mut [(Pole, Vec<c64>)], below: &[(Pole, Vec<c64>)], criteria: &Criteria) {
    for (p, l) in poles {
        p.stability = criteria.classify(
            p.freq_hz,
            p.damping_ratio,
            below.iter().map(|(q, _)| (q.freq_hz, q.damping_ratio)),
            |k| mac(l, &below[k].1),
        );
    }
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
        if pole.stability != Stability::Stable {
            continue;
        }
        let lowest = order.saturating_sub(opts.persist).max(1);
        let persists = (lowest..order).all(|q| at(q).iter().any(|b| same_frequency(pole, b, opts)));
        let twin = kept.iter().any(|k| same_frequency(k, pole, opts));
        if persists && !twin {
            kept.push(pole.clone());
        }
    }
    (order, kept)
}
