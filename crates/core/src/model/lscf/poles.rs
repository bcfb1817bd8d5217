//! The poles of LSCF (method §6.5.1): the polyreference layout, the lag
//! sums, the poles of each polynomial order, the stabilisation diagram and
//! the poles kept from it.

use super::{FitError, FitOptions, FrfSet, Pole, check, mac};
use crate::base::linalg::{self, LinalgError};
use crate::model::stability::{self, Criteria, DiagramOrder, Selection, Stability};
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

/// The lag sums `τ_ij(d) = Re Σ_f e^{jω_fΔt d} H_i* H_j` of one output
/// (method §6.5.1, eq. LSCF-3), `d = −p…p` stored at `d + p`: the entries
/// of `T_o`.
struct LagSums {
    tau: Vec<Vec<Vec<f64>>>,
}

/// The stabilisation diagram of `set` over orders `1..=opts.max_order`
/// (method §6.5.1): poles in `band_hz` with `ξ > 0`, each marked against
/// the order below (those with `ξ ≥ max_damping_ratio` drawn as
/// [`Stability::Damped`]).
///
/// Every order reuses the work of the highest: the basis `X` of the
/// highest order is factored once, `X = Q U` (its leading columns are
/// every lower order's basis, and the leading columns of `Q` span them),
/// so `S_oᵀ R⁻¹ S_o` of order `p` is `Σ_{r ≤ p} w_r w_rᵀ` with `w_r` the
/// rows of `W_o = Qᵀ Y_o`: one rank-one update per order instead of a
/// decomposition of `R`.
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
    let (dt, phase, scaled, sums) = prepare(set, &lay, p_max);
    let mut reduced = Reduced::new(&phase, &scaled, sums, ni, p_max)?;
    let criteria = opts.stability_criteria();
    let mut diagram: Vec<DiagramOrder> = Vec::with_capacity(p_max);
    // the poles of the order below and their participation vectors
    let mut below: Vec<(Pole, Vec<c64>)> = Vec::new();
    for p in 1..=p_max {
        let m = reduced.next();
        let mut poles = poles_of_order(m.as_ref(), ni, p, dt, band_hz)?;
        mark(&mut poles, &below, &criteria, opts.max_damping_ratio);
        diagram.push(DiagramOrder {
            order: p,
            poles: poles.iter().map(|(pole, _)| pole.clone()).collect(),
        });
        below = poles;
    }
    Ok(diagram)
}

/// The sampling step `Δt = 1/(2 f_max)`, the phases `e^{jω_fΔt d}`
/// (`[f][d + p_max]`, `d = −p_max…p_max`), each output's FRFs scaled to
/// unit RMS (`[o][i][f]`) and their lag sums.
#[allow(clippy::type_complexity)]
fn prepare(
    set: &FrfSet,
    lay: &Layout,
    p_max: usize,
) -> (f64, Vec<Vec<c64>>, Vec<Vec<Vec<c64>>>, Vec<LagSums>) {
    let ni = lay.rows[0].len();
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
    let scaled: Vec<Vec<Vec<c64>>> = lay
        .rows
        .iter()
        .zip(&scale)
        .map(|(row, &g)| {
            row.iter()
                .map(|&k| set.h[k].iter().map(|v| v * g).collect())
                .collect()
        })
        .collect();
    let sums: Vec<LagSums> = scaled
        .iter()
        .map(|hs: &Vec<Vec<c64>>| {
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
            LagSums { tau }
        })
        .collect();
    (dt, phase, scaled, sums)
}

/// The reduced normal matrices `M` of every order, built from the highest
/// order's basis factored once (method §6.5.1): [`Reduced::next`] gives
/// orders 1, 2, … in turn.
struct Reduced {
    sums: Vec<LagSums>,
    /// `W = Qᵀ Y` of every output side by side (`nq × outputs·na_max`).
    w: Mat<f64>,
    /// `Σ_o Σ_{r ≤ p} w_o,r w_o,rᵀ` of the last order given.
    g: Mat<f64>,
    ni: usize,
    p_max: usize,
    /// The last order given.
    p: usize,
}

impl Reduced {
    /// `phase[f][d + p_max] = e^{jω_fΔt d}`, `scaled[o][i][f]` the scaled
    /// FRFs of output `o`, reference `i`.
    fn new(
        phase: &[Vec<c64>],
        scaled: &[Vec<Vec<c64>>],
        sums: Vec<LagSums>,
        ni: usize,
        p_max: usize,
    ) -> Result<Self, FitError> {
        let nf = phase.len();
        let n_max = p_max + 1;
        let na_max = n_max * ni;
        let outs = scaled.len();
        // the real basis of the highest order, [Re z^r; Im z^r], r = 0…p_max
        let x = Mat::from_fn(2 * nf, n_max, |row, r| {
            let e = phase[row % nf][r + p_max];
            if row < nf { e.re } else { e.im }
        });
        linalg::sequential();
        let q = x.qr().compute_thin_Q();
        // Y_o = [−z^s H_oi] of every output side by side
        let y = Mat::from_fn(2 * nf, outs * na_max, |row, c| {
            let (o, rest) = (c / na_max, c % na_max);
            let (s, i) = (rest / ni, rest % ni);
            let f = row % nf;
            let v = -(phase[f][s + p_max] * scaled[o][i][f]);
            if row < nf { v.re } else { v.im }
        });
        let w = q.transpose() * &y;
        if !(0..w.nrows()).all(|r| (0..w.ncols()).all(|c| w[(r, c)].is_finite())) {
            return Err(LinalgError::NonFinite {
                what: "LSCF projection",
            }
            .into());
        }
        let mut reduced = Reduced {
            sums,
            w,
            g: Mat::zeros(na_max, na_max),
            ni,
            p_max,
            p: 0,
        };
        reduced.add_row(0);
        Ok(reduced)
    }

    /// Adds row `r` of every output's `W` to `g` (none past `Q`'s columns:
    /// the basis is then complete).
    fn add_row(&mut self, r: usize) {
        if r >= self.w.nrows() {
            return;
        }
        let na_max = self.g.nrows();
        for o in 0..self.sums.len() {
            let row = self.w.as_ref().row(r).subcols(o * na_max, na_max);
            self.g += row.transpose() * row;
        }
    }

    /// `M = Σ_o (T_o − S_oᵀ R⁻¹ S_o)` of the next order (eq. LSCF-4),
    /// `(p + 1)·N_i` square.
    fn next(&mut self) -> Mat<f64> {
        self.p += 1;
        self.add_row(self.p);
        let (ni, p_max) = (self.ni, self.p_max);
        let na = (self.p + 1) * ni;
        Mat::from_fn(na, na, |a, b| {
            let (r, i) = (a / ni, a % ni);
            let (s, j) = (b / ni, b % ni);
            let l = s + p_max - r;
            self.sums.iter().map(|o| o.tau[i][j][l]).sum::<f64>() - self.g[(a, b)]
        })
    }
}

/// The poles of order `p` from its reduced normal matrix `m` (method
/// §6.5.1, eq. LSCF-4, `(p + 1)·N_i` square): `M α = 0` solved with
/// `α_p = I`, the roots of `det Σ z^r α_r = 0` the eigenvalues of the block
/// companion matrix, `λ = ln(z) / Δt` (eq. LSCF-5); each pole with its
/// participation vector (unit norm, one entry per reference), its category
/// not yet known ([`Stability::New`]).
fn poles_of_order(
    m: faer::MatRef<'_, f64>,
    ni: usize,
    p: usize,
    dt: f64,
    band_hz: (f64, f64),
) -> Result<Vec<(Pole, Vec<c64>)>, FitError> {
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
    let c_norm = linalg::frobenius(comp.as_ref());
    let check = |residual: f64| -> Result<(), FitError> {
        if residual.is_nan() || residual > 1e-8 {
            return Err(LinalgError::Rebuild {
                what: "companion eigenpairs",
                residual,
                limit: 1e-8,
            }
            .into());
        }
        Ok(())
    };
    // the roots and, with several references, the participation vectors
    // (the eigenvectors' first block)
    let (roots, vectors): (Vec<c64>, Option<Mat<c64>>) = if ni == 1 {
        // one reference: a participation vector is one entry (any two have
        // a MAC of 1), so no eigenvectors are computed; the eigenvector of
        // the companion matrix is known, `x_a = z^a`, and each root is
        // checked on it
        let roots = linalg::eigenvalues(comp.as_ref())?;
        for &z in &roots {
            check(scalar_companion_residual(comp.as_ref(), z, c_norm))?;
        }
        (roots, None)
    } else {
        linalg::sequential();
        let eig = comp
            .eigen()
            .map_err(|_| LinalgError::NoConvergence { what: "eigen" })?;
        let (u, s) = (eig.U(), eig.S().column_vector());
        // each eigenpair checked: ‖C v − z v‖ ≤ 1e-8 ‖C‖_F ‖v‖
        // C V as one matrix product (the check's sums one by one took a
        // tenth of a 140-order diagram)
        let comp_c = Mat::<c64>::from_fn(k, k, |a, b| c64::new(comp[(a, b)], 0.0));
        let cu = &comp_c * u;
        for e in 0..k {
            let v_norm = (0..k).map(|a| u[(a, e)].norm_sqr()).sum::<f64>().sqrt();
            let res = (0..k)
                .map(|a| (cu[(a, e)] - s[e] * u[(a, e)]).norm_sqr())
                .sum::<f64>()
                .sqrt();
            check(res / (c_norm * v_norm).max(f64::MIN_POSITIVE))?;
        }
        ((0..k).map(|e| s[e]).collect(), Some(u.to_owned()))
    };
    let mut poles = Vec::new();
    for (e, &z) in roots.iter().enumerate() {
        if z.im <= 0.0 || z.norm() >= 1.0 || z.norm() == 0.0 {
            continue;
        }
        let lam = c64::new(z.norm().ln(), z.im.atan2(z.re)) / dt;
        let mut l: Vec<c64> = match &vectors {
            Some(u) => (0..ni).map(|i| u[(i, e)]).collect(),
            None => vec![c64::new(1.0, 0.0)],
        };
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
        // over-damped poles stay in the diagram, marked, never compared
        if pole.freq_hz >= band_hz.0 && pole.freq_hz <= band_hz.1 && pole.damping_ratio > 0.0 {
            poles.push((pole, l));
        }
    }
    poles.sort_by(|a, b| a.0.freq_hz.total_cmp(&b.0.freq_hz));
    Ok(poles)
}

/// `‖C x − z x‖ / (‖C‖_F ‖x‖)` for the companion matrix `c` of a scalar
/// polynomial (ones above the diagonal, the coefficients in its last row)
/// and its eigenvector at the root `z`, `x_a = z^a` (scaled by `z^{1−k}`
/// when `|z| > 1`, so that no entry exceeds 1).
fn scalar_companion_residual(c: faer::MatRef<'_, f64>, z: c64, c_norm: f64) -> f64 {
    let k = c.nrows();
    let mut x = vec![c64::new(1.0, 0.0); k];
    if z.norm() <= 1.0 {
        for a in 1..k {
            x[a] = x[a - 1] * z;
        }
    } else {
        let w = c64::new(1.0, 0.0) / z;
        for a in (0..k.saturating_sub(1)).rev() {
            x[a] = x[a + 1] * w;
        }
    }
    let mut res = 0.0;
    for a in 0..k {
        let cx = if a + 1 < k {
            x[a + 1]
        } else {
            (0..k).map(|b| x[b] * c[(a, b)]).sum::<c64>()
        };
        res += (cx - z * x[a]).norm_sqr();
    }
    let x_norm = x.iter().map(|v| v.norm_sqr()).sum::<f64>().sqrt();
    res.sqrt() / (c_norm * x_norm).max(f64::MIN_POSITIVE)
}

/// Each pole (with its participation vector) marked against the poles of
/// the order below by the LSCF criteria ([`FitOptions::stability_criteria`]:
/// the best category any pole there gives it, the shape compared the
/// participation vectors' MAC); a pole with `ξ ≥ max_damping_ratio` is
/// [`Stability::Damped`], and such poles of the order below are compared
/// with nothing.
fn mark(
    poles: &mut [(Pole, Vec<c64>)],
    below: &[(Pole, Vec<c64>)],
    criteria: &Criteria,
    max_damping_ratio: f64,
) {
    let below: Vec<&(Pole, Vec<c64>)> = below
        .iter()
        .filter(|(q, _)| q.stability != Stability::Damped)
        .collect();
    for (p, l) in poles {
        p.stability = if p.damping_ratio >= max_damping_ratio {
            Stability::Damped
        } else {
            criteria.classify(
                p.freq_hz,
                p.damping_ratio,
                below.iter().map(|(q, _)| (q.freq_hz, q.damping_ratio)),
                |k| mac(l, &below[k].1),
            )
        };
    }
}

/// The kept poles by persistence (method §6.5.1): the shared rule
/// [`stability::keep`] with the options' chosen order, frequency tolerance
/// and run length `persist`.
pub fn keep(diagram: &[DiagramOrder], references: usize, opts: &FitOptions) -> Selection {
    stability::keep(diagram, opts.order, references, &opts.persistence())
}

/// The number of references `N_i` of the polyreference model of `pairs`
/// (method §6.5.1): its orders add `N_i` poles each.
pub fn references(pairs: &[(usize, usize)]) -> usize {
    layout(pairs).rows[0].len()
}

/// The chosen order and the poles [`keep`] keeps.
pub fn select(
    diagram: &[DiagramOrder],
    references: usize,
    opts: &FitOptions,
) -> (usize, Vec<Pole>) {
    let s = keep(diagram, references, opts);
    (s.order, s.kept.into_iter().map(|k| k.pole).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pole(freq_hz: f64, damping_ratio: f64, stability: Stability) -> Pole {
        Pole {
            freq_hz,
            damping_ratio,
            stability,
        }
    }

    /// A diagram of 40 orders: a dominant pole at 51.5 Hz stable from
    /// order 13 to 39 and split at 40 into two poles stable in frequency
    /// only; a pole at 120 Hz stable throughout; a low orders' blend at
    /// 90 Hz stable from 3 to 10 only; an over-damped pole at every order.
    fn diagram() -> Vec<DiagramOrder> {
        use Stability::*;
        (1..=40)
            .map(|p| {
                let mut poles = vec![pole(37.0, 0.45, Damped)];
                if (3..=10).contains(&p) {
                    poles.push(pole(90.0, 0.01, if p == 3 { New } else { Stable }));
                }
                match p {
                    1..=12 => poles.push(pole(51.5, 0.0003, Frequency)),
                    13..=39 => poles.push(pole(51.5 + 1e-4 * p as f64, 0.0003, Stable)),
                    _ => {
                        poles.push(pole(51.3, 0.0006, Frequency));
                        poles.push(pole(51.7, 0.0002, Frequency));
                    }
                }
                poles.push(pole(120.0, 0.01, if p == 1 { New } else { Stable }));
                poles.sort_by(|a, b| a.freq_hz.total_cmp(&b.freq_hz));
                DiagramOrder { order: p, poles }
            })
            .collect()
    }

    #[test]
    fn a_mode_split_at_the_top_order_is_kept_by_its_persistence() {
        let d = diagram();
        let s = keep(&d, 1, &FitOptions::default());
        assert_eq!(s.order, 40);
        let f: Vec<f64> = s.kept.iter().map(|k| k.pole.freq_hz).collect();
        assert_eq!(f.len(), 2, "{f:?}");
        // taken at order 39, where it is stable; the split poles of that
        // order are none, its run 13 to 39
        assert!((f[0] - 51.5039).abs() < 1e-9, "{f:?}");
        assert_eq!((s.kept[0].order, s.kept[0].stable_orders), (39, (13, 39)));
        assert!((f[1] - 120.0).abs() < 1e-9);
        assert_eq!((s.kept[1].order, s.kept[1].stable_orders), (40, (2, 40)));
        // the old rule's chosen order alone: the 51.5 Hz mode would be lost
        assert_ne!(d[39].poles[1].stability, Stability::Stable);
        // an order in the blend's run keeps it; the top order does not
        let low = FitOptions {
            order: Some(9),
            ..FitOptions::default()
        };
        let s = keep(&d, 1, &low);
        assert!(s.kept.iter().any(|k| k.pole.freq_hz == 90.0));
        // the over-damped pole is never kept
        assert!(s.kept.iter().all(|k| k.pole.damping_ratio < 0.2));
    }

    #[test]
    fn two_stable_poles_of_one_order_within_the_tolerance_are_one_mode() {
        use Stability::*;
        let d: Vec<DiagramOrder> = (1..=12)
            .map(|p| DiagramOrder {
                order: p,
                poles: if p < 12 {
                    vec![pole(687.0, 0.004, if p == 1 { New } else { Stable })]
                } else {
                    vec![pole(686.9, 0.004, Stable), pole(687.4, 0.004, Stable)]
                },
            })
            .collect();
        let s = keep(&d, 1, &FitOptions::default());
        assert_eq!(s.kept.len(), 1, "{:?}", s.kept);
        assert_eq!(s.kept[0].split_hz, [687.4]);
        assert_eq!(s.kept[0].order, 12);
        // no order: nothing kept, nothing panics
        assert!(keep(&[], 1, &FitOptions::default()).kept.is_empty());
    }

    /// A root of a scalar polynomial is checked on the companion matrix's
    /// known eigenvector: at the roots of `(z − 0.5)(z − 2)(z² + 1)` the
    /// residual is at round-off, as it is at the eigenvalues computed;
    /// at a number that is no root it is not.
    #[test]
    fn a_scalar_companions_roots_are_checked_on_their_known_eigenvectors() {
        let alpha = [1.0, -2.5, 2.0, -2.5];
        let k = alpha.len();
        let c = Mat::from_fn(k, k, |a, b| {
            if a + 1 < k {
                if b == a + 1 { 1.0 } else { 0.0 }
            } else {
                -alpha[b]
            }
        });
        let n = linalg::frobenius(c.as_ref());
        for z in [c64::new(0.5, 0.0), c64::new(2.0, 0.0), c64::new(0.0, 1.0)] {
            let r = scalar_companion_residual(c.as_ref(), z, n);
            assert!(r < 1e-15, "{z}: {r:e}");
        }
        for z in linalg::eigenvalues(c.as_ref()).unwrap() {
            let r = scalar_companion_residual(c.as_ref(), z, n);
            assert!(r < 1e-13, "{z}: {r:e}");
        }
        assert!(scalar_companion_residual(c.as_ref(), c64::new(0.6, 0.0), n) > 1e-3);
    }

    /// The reduced matrices built once from the highest order's factored
    /// basis equal `T − Sᵀ R⁻¹ S` built for each order from its own basis
    /// (the sums over frequencies written out, `R` solved by SVD): a row of
    /// three FRFs of two modes with noise, orders 1 to 30.
    #[test]
    fn reduced_matrices_built_once_equal_those_built_per_order() {
        use crate::model::lscf::{FrfSet, Ordinate};
        let freq_hz: Vec<f64> = (1..=400).map(|k| 0.5 * k as f64).collect();
        let mut seed: u64 = 7;
        let mut noise = move || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1);
            0.01 * ((seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5)
        };
        let modes = [
            (40.0, 0.02, [1.0, 0.5, -0.3]),
            (130.0, 0.01, [0.7, -0.6, 0.4]),
        ];
        let h: Vec<Vec<c64>> = (0..3)
            .map(|j| {
                freq_hz
                    .iter()
                    .map(|&f| {
                        let w = TAU * f;
                        modes
                            .iter()
                            .map(|&(fk, xi, sh)| {
                                let wk = TAU * fk;
                                c64::new(sh[0] * sh[j], 0.0)
                                    / c64::new(wk * wk - w * w, 2.0 * xi * wk * w)
                            })
                            .sum::<c64>()
                            * c64::new(1.0 + noise(), noise())
                    })
                    .collect()
            })
            .collect();
        let set = FrfSet {
            freq_hz,
            ordinate: Ordinate::Receptance,
            pairs: vec![(0, 0), (0, 1), (0, 2)],
            h,
        };
        let lay = layout(&set.pairs);
        let p_max = 30;
        let (_, phase, scaled, sums) = prepare(&set, &lay, p_max);
        let mut reduced = Reduced::new(&phase, &scaled, sums, 1, p_max).unwrap();
        let nf = set.freq_hz.len();
        let z = |f: usize, r: usize| phase[f][r + p_max];
        for p in 1..=p_max {
            let m = reduced.next();
            let n = p + 1;
            let r_mat = Mat::from_fn(n, n, |r, s| {
                (0..nf).map(|f| (z(f, r).conj() * z(f, s)).re).sum::<f64>()
            });
            let mut direct = Mat::<f64>::zeros(n, n);
            for hs in &scaled {
                let h = &hs[0];
                let s_o = Mat::from_fn(n, n, |r, s| {
                    (0..nf)
                        .map(|f| -(z(f, r).conj() * z(f, s) * h[f]).re)
                        .sum::<f64>()
                });
                let t_o = Mat::from_fn(n, n, |r, s| {
                    (0..nf)
                        .map(|f| ((z(f, r) * h[f]).conj() * z(f, s) * h[f]).re)
                        .sum::<f64>()
                });
                let (rinv_s, _) = linalg::lstsq(r_mat.as_ref(), s_o.as_ref(), 1e-14).unwrap();
                direct += &t_o - s_o.transpose() * &rinv_s;
            }
            let scale = linalg::frobenius(direct.as_ref());
            let diff = linalg::frobenius((&m - &direct).as_ref()) / scale;
            assert!(diff < 1e-9, "order {p}: relative difference {diff:e}");
        }
    }
}
