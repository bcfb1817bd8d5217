//! LSCE identification (least-squares complex exponential, method §6).
//!
//! From impulse responses `g_r(k dt)` sampled at `dt`, the linear prediction
//! `g_r(k + p) + Σ_{l<p} a_l g_r(k + l) = 0` of order `p = 2M` (`M` pole
//! pairs) is stacked over all responses (each scaled to unit peak) and solved
//! by least squares. One QR factor of the Hankel matrix with `2 M_max + 1`
//! columns serves every order (the first `p + 1` columns of `R` are the order
//! `p` system). The roots `z` of `z^p + Σ a_l z^l` (eigenvalues of the
//! companion matrix, [`crate::base::linalg::eigenvalues`]) give the poles `s = ln(z) / dt`;
//! the physical ones are conjugate pairs with `Re(s) < 0` (`ξ > 0`, method §6's
//! sign check) inside the band. Residues are fitted by least squares on the
//! responses with the real modal form of method §2, `g = Σ A_k h_k`; a second fit
//! with the companion `e^{-ξωt} cos(ω_d t)` terms measures the part of the
//! complex residues that the real form discards (reported per mode).
//!
//! The stabilisation diagram repeats this for `M = 1..=M_max`; a pole is
//! stable when the previous order has a pole within the frequency, damping and
//! residue-MAC tolerances. Residues are fitted with every physical pole up to
//! the Nyquist frequency (so out-of-band modes keep their share of the
//! responses); the model keeps the in-band ones whose share of the responses
//! is at least `min_contribution`. The model order is the given
//! one or, automatically, chosen with the diagram: among the orders whose
//! in-band model's time-domain fit error is within `order_tolerance` of the
//! best, the smallest whose kept poles persist (`choose_order`).

use crate::base::linalg::{self, LinalgError};
use crate::base::modal::Mode;
use crate::base::modal::unit_impulse;
use dtft::dtft_magnitudes;
use faer::{Mat, MatRef, c64};
use std::f64::consts::TAU;

mod dtft;
mod options;
mod order;
mod picked;
pub use options::IdentifyOptions;
use order::choose_order;
use picked::modes_of_fit;
pub use picked::{modes_of_poles, response_magnitudes};

/// Sampled impulse responses `g_ij(k dt)` (m/(N·s)) of `num_points` points.
#[derive(Debug, Clone, PartialEq)]
pub struct Responses {
    /// Sample interval (s).
    pub dt_s: f64,
    /// Number of points `P`.
    pub num_points: usize,
    /// `(i, j)` of each response: receiving point, loaded point.
    pub pairs: Vec<(usize, usize)>,
    /// One sample vector per pair, all of the same length, `k = 0..len`.
    pub data: Vec<Vec<f64>>,
}

/// Errors of the identification.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LsceError {
    #[error("LSCE: {0}")]
    Input(String),
    #[error(
        "LSCE: no physical pole pair with a share of the responses in the band {lo_hz}..{hi_hz} Hz at model order {order} (raise the order or widen the band)"
    )]
    NoModes {
        lo_hz: f64,
        hi_hz: f64,
        order: usize,
    },
    #[error("LSCE: {0}")]
    Numerical(#[from] LinalgError),
    /// `lowest_source_hz` is NaN when the source's modes are not known (a
    /// measured file): the message then names none.
    #[error("{}", poor_fit(*magnitude_error, *limit, *lo_hz, *hi_hz, *lowest_source_hz))]
    PoorFit {
        magnitude_error: f64,
        limit: f64,
        lo_hz: f64,
        hi_hz: f64,
        lowest_source_hz: f64,
    },
}

/// The message of [`LsceError::PoorFit`].
fn poor_fit(magnitude_error: f64, limit: f64, lo_hz: f64, hi_hz: f64, lowest_hz: f64) -> String {
    let head = format!(
        "LSCE: the identified modes miss the source: |G| error {magnitude_error:.3} over {lo_hz}..{hi_hz} Hz (expected below {limit})"
    );
    if lowest_hz.is_nan() {
        format!(
            "{head}: check the band (identification.band_hz) against the data's modes, or fit a UFF file of FRFs in the frequency domain (`tirecontact identify --data FILE`)"
        )
    } else {
        format!(
            "{head}; the source's lowest mode is at {lowest_hz:.1} Hz: move the band (identification.band_hz) to cover the source's modes"
        )
    }
}

/// How a pole of the stabilisation diagram compares with the previous order.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stability {
    /// No pole of the previous order within the frequency tolerance.
    New,
    /// Frequency stable only.
    Frequency,
    /// Frequency and damping stable.
    FrequencyDamping,
    /// Frequency, damping and residue MAC stable.
    Stable,
}

/// One pole of the stabilisation diagram.
#[derive(Debug, Clone, PartialEq)]
pub struct DiagramPole {
    pub freq_hz: f64,
    pub damping_ratio: f64,
    pub stability: Stability,
}

/// One model order of the stabilisation diagram.
#[derive(Debug, Clone, PartialEq)]
pub struct DiagramOrder {
    /// Model order `M` (pole pairs).
    pub order: usize,
    /// Physical poles in the band.
    pub poles: Vec<DiagramPole>,
    /// Relative L2 error in time over all responses, with every physical
    /// pole of this order (-).
    pub time_error: f64,
    /// The same with the in-band poles only (what the model keeps) (-).
    pub band_time_error: f64,
}

/// Fit of one response.
#[derive(Debug, Clone, PartialEq)]
pub struct ResponseFit {
    pub pair: (usize, usize),
    /// `||g_fit - g|| / ||g||` over the samples (-).
    pub time_error: f64,
    /// `|| |G_fit| - |G| || / || |G| ||` over the band, `G` the DTFT of the
    /// samples (-).
    pub magnitude_error: f64,
}

/// Fit report (method §6).
#[derive(Debug, Clone, PartialEq)]
pub struct FitReport {
    /// Relative L2 error in time over all responses of the kept (in-band)
    /// modes (-). Out-of-band content of the responses counts as error.
    pub time_error: f64,
    /// The same with every physical pole of the chosen order, out-of-band
    /// ones included (the error of the LSCE fit itself) (-).
    pub time_error_all_poles: f64,
    /// Relative L2 error of `|G(ω)|` over the band, all responses (-).
    pub magnitude_error: f64,
    pub per_response: Vec<ResponseFit>,
    /// Relative residuals `‖A x − b‖ / ‖b‖` of the least-squares solves
    /// behind the model (-).
    pub least_squares: LeastSquaresResiduals,
}

/// Relative residuals `‖A x − b‖_F / ‖b‖_F` of the least-squares solves of
/// an identification at the chosen order (-). The prediction's is the
/// misfit of the linear prediction on the Hankel data; the residues' the
/// misfit of the real modal form on the responses with every physical pole.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct LeastSquaresResiduals {
    /// Linear prediction `g(k + p) + Σ a_l g(k + l) = 0` (-).
    pub prediction: f64,
    /// Residues of the real modal form, every physical pole (-).
    pub residues: f64,
    /// Residues of the complex form (sin and cos parts) (-).
    pub complex_residues: f64,
}

/// Result of an identification.
#[derive(Debug, Clone, PartialEq)]
pub struct Identification {
    /// Identified modes, by frequency, with symmetric P×P residues (1/kg).
    pub modes: Vec<Mode>,
    /// The model order used `M`.
    pub model_order: usize,
    /// Per mode: stable (frequency, damping and MAC) against order `M - 1`.
    pub stable: Vec<bool>,
    /// Per mode: norm of the discarded `cos` part of the complex residue over
    /// the norm of the kept `sin` part (`b_k` vs `A_k / ω_d`) (-).
    pub discarded_ratio: Vec<f64>,
    pub diagram: Vec<DiagramOrder>,
    pub report: FitReport,
}

/// A relative fit error below which every order counts as exact (automatic
/// order selection).
pub const EXACT_FIT: f64 = 1e-6;

/// A continuous-time pole: `ω` (rad/s) and `ξ`.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Pole {
    omega: f64,
    xi: f64,
}

impl Pole {
    fn freq_hz(&self) -> f64 {
        self.omega / TAU
    }
    fn in_band(&self, opts: &IdentifyOptions) -> bool {
        let f = self.freq_hz();
        f >= opts.band_hz.0 && f <= opts.band_hz.1
    }
}

fn check_input(r: &Responses) -> Result<usize, LsceError> {
    if r.data.is_empty() || r.data.len() != r.pairs.len() {
        return Err(LsceError::Input(format!(
            "{} responses for {} pairs: expected at least one, one per pair",
            r.data.len(),
            r.pairs.len()
        )));
    }
    if !(r.dt_s.is_finite() && r.dt_s > 0.0) {
        return Err(LsceError::Input(format!(
            "dt_s = {}: expected a sample interval > 0 s",
            r.dt_s
        )));
    }
    let len = r.data[0].len();
    for (k, (d, &(i, j))) in r.data.iter().zip(&r.pairs).enumerate() {
        if d.len() != len {
            return Err(LsceError::Input(format!(
                "response {k} has {} samples, response 0 has {len}",
                d.len()
            )));
        }
        if i >= r.num_points || j >= r.num_points {
            return Err(LsceError::Input(format!(
                "pair ({i}, {j}) names a point >= P = {}",
                r.num_points
            )));
        }
        if let Some(x) = d.iter().find(|x| !x.is_finite()) {
            return Err(LsceError::Input(format!(
                "response {k} holds a non-finite sample {x}"
            )));
        }
    }
    Ok(len)
}

/// Least squares by the checked SVD of [`linalg::lstsq`]: the solution and
/// its relative residual.
fn lstsq(a: MatRef<'_, f64>, b: MatRef<'_, f64>, rcond: f64) -> Result<(Mat<f64>, f64), LsceError> {
    Ok(linalg::lstsq(a, b, rcond)?)
}

/// Responses stacked per QR of the Hankel data ([`hankel_add`]): a few at
/// a time keeps the stacked block small.
const HANKEL_CHUNK: usize = 4;

/// The triangular factor `R` of the stacked Hankel matrix with `cols`
/// columns (rows `[g(k), ..., g(k + cols - 1)]`, responses scaled to unit
/// peak), a chunk at a time: stacks the Hankel rows of the (nonzero)
/// responses of `chunk` under the factor `acc` so far and replaces it by
/// the `R` of their QR.
fn hankel_add(acc: &mut Mat<f64>, chunk: &[Vec<f64>], len: usize, cols: usize) {
    let rows = len - cols + 1;
    let blocks: Vec<&Vec<f64>> = chunk
        .iter()
        .filter(|d| d.iter().any(|x| *x != 0.0))
        .collect();
    if blocks.is_empty() {
        return;
    }
    let n = acc.nrows() + rows * blocks.len();
    let mut m = Mat::<f64>::zeros(n, cols);
    for i in 0..acc.nrows() {
        for c in 0..cols {
            m[(i, c)] = acc[(i, c)];
        }
    }
    let mut row = acc.nrows();
    for d in blocks {
        let peak = d.iter().fold(0.0_f64, |a, x| a.max(x.abs()));
        for k in 0..rows {
            for c in 0..cols {
                m[(row, c)] = d[k + c] / peak;
            }
            row += 1;
        }
    }
    *acc = linalg::qr_r(m.as_ref());
}

/// Roots of the order-`p` prediction polynomial -> the physical poles
/// (`0 < ξ < max_damping_ratio`) up to the Nyquist frequency.
fn poles_of_order(
    rmat: &Mat<f64>,
    p: usize,
    dt: f64,
    opts: &IdentifyOptions,
) -> Result<(Vec<Pole>, f64), LsceError> {
    let k = p.min(rmat.nrows());
    let a_mat = Mat::from_fn(k, p, |i, j| rmat[(i, j)]);
    let b = Mat::from_fn(k, 1, |i, _| -rmat[(i, p)]);
    let (a, _) = lstsq(a_mat.as_ref(), b.as_ref(), 1e-13)?;
    // the residual over the whole stacked system: `R` keeps the part of `b`
    // outside the span of `A` in its rows below `k` (none when `k = p`)
    let whole = |i: usize| {
        let fit: f64 = (0..p.min(rmat.ncols()))
            .map(|j| rmat[(i, j)] * a[(j, 0)])
            .sum();
        fit + rmat[(i, p)]
    };
    let rows = rmat.nrows().min(p + 1);
    let num: f64 = (0..rows).map(|i| whole(i).powi(2)).sum::<f64>().sqrt();
    let den: f64 = (0..rows).map(|i| rmat[(i, p)].powi(2)).sum::<f64>().sqrt();
    let residual = if den > 0.0 { num / den } else { 0.0 };
    let mut comp = Mat::<f64>::zeros(p, p);
    for i in 0..p - 1 {
        comp[(i, i + 1)] = 1.0;
    }
    for l in 0..p {
        comp[(p - 1, l)] = -a[(l, 0)];
    }
    let roots = linalg::eigenvalues(comp.as_ref())?;
    let mut poles: Vec<Pole> = roots
        .iter()
        .filter(|z| z.im > 0.0 && z.norm() > 0.0)
        .map(|z: &c64| {
            let s = c64::new(z.norm().ln(), z.im.atan2(z.re)) / dt;
            let omega = s.norm();
            Pole {
                omega,
                xi: -s.re / omega,
            }
        })
        .filter(|pl| pl.xi > 0.0 && pl.xi < opts.max_damping_ratio)
        .collect();
    poles.sort_by(|x, y| x.omega.total_cmp(&y.omega));
    Ok((poles, residual))
}

/// Sampled `h_k` (and, with `with_cos`, `e^{-ξωt} cos(ω_d t)`) per pole.
fn basis(poles: &[Pole], dt: f64, len: usize, with_cos: bool) -> Mat<f64> {
    let k = poles.len();
    let cols = if with_cos { 2 * k } else { k };
    Mat::from_fn(len, cols, |n, c| {
        let t = n as f64 * dt;
        let pl = poles[c % k];
        if c < k {
            unit_impulse(pl.omega, pl.xi, t).0
        } else {
            let wd = pl.omega * ((1.0 - pl.xi) * (1.0 + pl.xi)).sqrt();
            (-pl.xi * pl.omega * t).exp() * (wd * t).cos()
        }
    })
}

fn data_matrix(r: &Responses, len: usize) -> Mat<f64> {
    Mat::from_fn(len, r.data.len(), |n, c| r.data[c][n])
}

/// Relative L2 error `||fit - data|| / ||data||` per column and overall.
fn time_errors(fit: &Mat<f64>, data: &Mat<f64>) -> (Vec<f64>, f64) {
    let (mut num, mut den) = (0.0, 0.0);
    let per = (0..data.ncols())
        .map(|c| {
            let e = (fit.col(c) - data.col(c)).squared_norm_l2();
            let d = data.col(c).squared_norm_l2();
            num += e;
            den += d;
            if d > 0.0 { (e / d).sqrt() } else { e.sqrt() }
        })
        .collect();
    (per, if den > 0.0 { (num / den).sqrt() } else { 0.0 })
}

fn mac(a: &[f64], b: &[f64]) -> f64 {
    let ab: f64 = a.iter().zip(b).map(|(x, y)| x * y).sum();
    let aa: f64 = a.iter().map(|x| x * x).sum();
    let bb: f64 = b.iter().map(|x| x * x).sum();
    if aa > 0.0 && bb > 0.0 {
        ab * ab / (aa * bb)
    } else {
        0.0
    }
}

#[derive(Debug)]
struct OrderFit {
    poles: Vec<Pole>,
    /// Residue per pole and response (K × responses).
    residues: Mat<f64>,
    time_error: f64,
    /// Relative residual of the residues' least squares (-).
    residual: f64,
}

/// Row `r` of `m`, as a vector.
fn row(m: &Mat<f64>, r: usize) -> Vec<f64> {
    (0..m.ncols()).map(|c| m[(r, c)]).collect()
}

/// `‖row r of m‖₂`.
fn row_norm(m: &Mat<f64>, r: usize) -> f64 {
    m.row(r).norm_l2()
}

/// The rows `rows` of `m`, in that order.
fn select_rows(m: &Mat<f64>, rows: &[usize]) -> Mat<f64> {
    Mat::from_fn(rows.len(), m.ncols(), |r, c| m[(rows[r], c)])
}

/// Residues by least squares through the normal equations (cheap, used for
/// the diagram) or the SVD of the basis (`accurate`).
fn fit_order(
    poles: Vec<Pole>,
    data: &Mat<f64>,
    dt: f64,
    accurate: bool,
) -> Result<OrderFit, LsceError> {
    let len = data.nrows();
    if poles.is_empty() {
        let zero = Mat::zeros(len, data.ncols());
        return Ok(OrderFit {
            poles,
            residues: Mat::zeros(0, data.ncols()),
            time_error: time_errors(&zero, data).1,
            residual: 1.0,
        });
    }
    let b = basis(&poles, dt, len, false);
    let residues = if accurate {
        lstsq(b.as_ref(), data.as_ref(), 1e-14)?.0
    } else {
        let gram = b.transpose() * &b;
        let rhs = b.transpose() * data;
        lstsq(gram.as_ref(), rhs.as_ref(), 1e-15)?.0
    };
    let fit = &b * &residues;
    let time_error = time_errors(&fit, data).1;
    Ok(OrderFit {
        poles,
        // the residual of `b x = data` (the normal equations' own is not
        // the misfit)
        residual: time_error,
        time_error,
        residues,
    })
}

fn stability(
    pole: &Pole,
    res: &[f64],
    prev: Option<&(Vec<Pole>, Vec<Vec<f64>>)>,
    opts: &IdentifyOptions,
) -> Stability {
    let Some((pp, pr)) = prev else {
        return Stability::New;
    };
    let best = pp
        .iter()
        .enumerate()
        .min_by(|a, b| {
            (a.1.omega - pole.omega)
                .abs()
                .total_cmp(&(b.1.omega - pole.omega).abs())
        })
        .map(|(k, q)| (k, *q));
    let Some((k, q)) = best else {
        return Stability::New;
    };
    if (q.omega - pole.omega).abs() > opts.stable_freq_tol * pole.omega {
        return Stability::New;
    }
    if (q.xi - pole.xi).abs() > opts.stable_damping_tol * pole.xi {
        return Stability::Frequency;
    }
    if mac(res, &pr[k]) < opts.stable_mac_min {
        return Stability::FrequencyDamping;
    }
    Stability::Stable
}

/// Identifies a modal model from sampled impulse responses (method §6).
pub fn identify(r: &Responses, opts: &IdentifyOptions) -> Result<Identification, LsceError> {
    LsceRun::new(r.clone(), opts)?.finish()
}

/// [`identify`] one stage at a time, for a caller that must return between
/// stages (a page in the browser, which has one thread): the QR of the
/// Hankel data a few responses at a time, then each order of the
/// stabilisation diagram, then the model at the chosen order and its
/// report. The stages are [`identify`]'s own, in its order: the result is
/// the same to the bit.
#[derive(Debug)]
pub struct LsceRun {
    r: Responses,
    opts: IdentifyOptions,
    len: usize,
    cols: usize,
    /// The Hankel data's `R` so far, and the responses stacked into it.
    rmat: Mat<f64>,
    stacked: usize,
    /// The data matrix and its norm, once the `R` is complete.
    data: Option<(Mat<f64>, f64)>,
    orders: Vec<usize>,
    diagram: Vec<DiagramOrder>,
    kept_at: Vec<Vec<usize>>,
    prev: Option<BandPoles>,
    /// The chosen order, its model and its prediction residual.
    model: Option<(usize, KeptModel, f64)>,
    stages_done: usize,
}

impl LsceRun {
    /// Checks the options and the responses (the errors of [`identify`]).
    pub fn new(r: Responses, opts: &IdentifyOptions) -> Result<Self, LsceError> {
        crate::base::linalg::sequential();
        let errors = opts.validate("options");
        if let Some(e) = errors.first() {
            return Err(LsceError::Input(e.to_string()));
        }
        let len = check_input(&r)?;
        let m_max = opts.max_model_order;
        let cols = 2 * m_max + 1;
        if len < 2 * cols {
            return Err(LsceError::Input(format!(
                "{len} samples per response: expected at least {} for max_model_order = {m_max}",
                2 * cols
            )));
        }
        Ok(LsceRun {
            r,
            opts: opts.clone(),
            len,
            cols,
            rmat: Mat::<f64>::zeros(0, cols),
            stacked: 0,
            data: None,
            orders: Vec::new(),
            diagram: Vec::new(),
            kept_at: Vec::new(),
            prev: None,
            model: None,
            stages_done: 0,
        })
    }

    /// Stages of the whole identification (the QR chunks, the data, the
    /// diagram's orders, the model, the report).
    pub fn num_stages(&self) -> usize {
        Self::stages_for(self.r.data.len(), &self.opts)
    }

    /// [`LsceRun::num_stages`] of `num_responses` responses identified
    /// with `opts`.
    pub fn stages_for(num_responses: usize, opts: &IdentifyOptions) -> usize {
        num_responses.div_ceil(HANKEL_CHUNK) + 1 + opts.max_model_order + 2
    }

    /// The responses identified.
    pub fn into_responses(self) -> Responses {
        self.r
    }

    /// Stages done so far.
    pub fn stages_done(&self) -> usize {
        self.stages_done
    }

    /// Runs every stage left.
    pub fn finish(mut self) -> Result<Identification, LsceError> {
        loop {
            if let Some(id) = self.stage()? {
                return Ok(id);
            }
        }
    }

    /// Runs the next stage; the identification once the last one ran.
    pub fn stage(&mut self) -> Result<Option<Identification>, LsceError> {
        self.stages_done += 1;
        let (len, dt, opts) = (self.len, self.r.dt_s, &self.opts);
        // one QR factor of the Hankel data serves every order (method §6.2, 1)
        if self.stacked < self.r.data.len() {
            let end = (self.stacked + HANKEL_CHUNK).min(self.r.data.len());
            hankel_add(
                &mut self.rmat,
                &self.r.data[self.stacked..end],
                len,
                self.cols,
            );
            self.stacked = end;
            return Ok(None);
        }
        let Some((data, data_norm)) = &self.data else {
            if self.rmat.nrows() == 0 {
                return Err(LsceError::Input("every response is zero".into()));
            }
            let m_max = opts.max_model_order;
            self.orders = match opts.model_order {
                Some(m) if m > m_max => {
                    return Err(LsceError::Input(format!("model order {m} > {m_max}")));
                }
                _ => (1..=m_max).collect(),
            };
            let data = data_matrix(&self.r, len);
            let norm = data.norm_l2();
            self.data = Some((data, norm));
            return Ok(None);
        };
        let (data, data_norm) = (data, *data_norm);
        // the stabilisation diagram, an order at a time (method §6.3)
        if self.diagram.len() < self.orders.len() {
            let m = self.orders[self.diagram.len()];
            let (order, kept, band) =
                diagram_order(&self.rmat, data, m, dt, data_norm, self.prev.as_ref(), opts)?;
            self.kept_at.push(kept);
            self.diagram.push(order);
            self.prev = Some(band);
            return Ok(None);
        }
        let Some((chosen, model, prediction_residual)) = &self.model else {
            // the given order, or the diagram's choice (method §6.3)
            let chosen = match opts.model_order {
                Some(m) => m,
                None => {
                    choose_order(&self.diagram, &self.kept_at, opts).unwrap_or(opts.max_model_order)
                }
            };
            let (all, prediction_residual) = poles_of_order(&self.rmat, 2 * chosen, dt, opts)?;
            let no_modes = LsceError::NoModes {
                lo_hz: opts.band_hz.0,
                hi_hz: opts.band_hz.1,
                order: chosen,
            };
            if !all.iter().any(|pl| pl.in_band(opts)) {
                return Err(no_modes);
            }
            let Some(model) = kept_model(all, data, dt, data_norm, opts)? else {
                return Err(no_modes);
            };
            self.model = Some((chosen, model, prediction_residual));
            return Ok(None);
        };
        let r = &self.r;
        let modes = modes_of_fit(r, &model.fit);
        let stable = stable_modes(&model.fit.poles, &self.diagram, *chosen, opts);
        let least_squares = LeastSquaresResiduals {
            prediction: *prediction_residual,
            residues: model.fit.residual,
            complex_residues: model.complex_residual,
        };
        let report = fit_report(r, &model.fit, data, dt, opts, least_squares);
        Ok(Some(Identification {
            modes,
            model_order: *chosen,
            stable,
            discarded_ratio: model.discarded_ratio.clone(),
            diagram: std::mem::take(&mut self.diagram),
            report,
        }))
    }
}

/// The in-band poles of one order of the stabilisation diagram and their
/// residues (one per response).
type BandPoles = (Vec<Pole>, Vec<Vec<f64>>);

/// One order `m` of the stabilisation diagram (method §6.2, 1–5, and §6.3):
/// its in-band poles, each stable or not against `prev` (the in-band poles
/// and residues of the order below), and its time errors; the in-band poles
/// the model would keep at this order (indices into the diagram's poles);
/// and its own in-band poles and residues, for the order above.
fn diagram_order(
    rmat: &Mat<f64>,
    data: &Mat<f64>,
    m: usize,
    dt: f64,
    data_norm: f64,
    prev: Option<&BandPoles>,
    opts: &IdentifyOptions,
) -> Result<(DiagramOrder, Vec<usize>, BandPoles), LsceError> {
    let (poles, _) = poles_of_order(rmat, 2 * m, dt, opts)?;
    // residues with every physical pole, so that the out-of-band ones
    // take their own share of the responses; the diagram shows the band
    let fit = fit_order(poles, data, dt, false)?;
    let (band_poles, res): (Vec<Pole>, Vec<Vec<f64>>) = fit
        .poles
        .iter()
        .enumerate()
        .filter(|(_, pl)| pl.in_band(opts))
        .map(|(c, pl)| (*pl, row(&fit.residues, c)))
        .unzip();
    let dpoles: Vec<DiagramPole> = band_poles
        .iter()
        .zip(&res)
        .map(|(pl, rv)| DiagramPole {
            freq_hz: pl.freq_hz(),
            damping_ratio: pl.xi,
            stability: stability(pl, rv, prev, opts),
        })
        .collect();
    let in_band: Vec<usize> = (0..fit.poles.len())
        .filter(|&c| fit.poles[c].in_band(opts))
        .collect();
    let band_basis = basis(
        &in_band.iter().map(|&c| fit.poles[c]).collect::<Vec<_>>(),
        dt,
        data.nrows(),
        false,
    );
    // the in-band poles the model would keep at this order (a share of
    // the responses, as `kept_model` keeps them): indices into `dpoles`
    let kept = (0..in_band.len())
        .filter(|&k| {
            let share = band_basis.col(k).norm_l2() * row_norm(&fit.residues, in_band[k]);
            share >= opts.min_contribution * data_norm
        })
        .collect::<Vec<usize>>();
    let band_fit = &band_basis * select_rows(&fit.residues, &in_band);
    let order = DiagramOrder {
        order: m,
        poles: dpoles,
        time_error: fit.time_error,
        band_time_error: time_errors(&band_fit, data).1,
    };
    Ok((order, kept, (band_poles, res)))
}

/// The model at the chosen order and what the real form of its residues
/// leaves out.
#[derive(Debug)]
struct KeptModel {
    /// The kept poles and their residues; the time error and residual of
    /// the fit with every physical pole.
    fit: OrderFit,
    /// Per kept mode: the discarded `cos` part of its complex residue over
    /// the kept `sin` part.
    discarded_ratio: Vec<f64>,
    /// Relative residual of the complex-residue fit (-).
    complex_residual: f64,
}

/// The model of the chosen order's physical poles `all` (method §6.2, 4–5):
/// residues fitted with every one of them, then the in-band poles with a
/// share of the responses kept (a spurious pole fitted to round-off has
/// none); `None` when no pole is kept. A second fit, with the companion
/// `cos` terms, gives the part of each complex residue that the real form
/// discards.
fn kept_model(
    all: Vec<Pole>,
    data: &Mat<f64>,
    dt: f64,
    data_norm: f64,
    opts: &IdentifyOptions,
) -> Result<Option<KeptModel>, LsceError> {
    let len = data.nrows();
    let n_all = all.len();
    // complex-residue fit (sin and cos parts): the discarded part
    let (full, complex_residual) =
        lstsq(basis(&all, dt, len, true).as_ref(), data.as_ref(), 1e-14)?;
    let fit_all = fit_order(all, data, dt, true)?;
    let b_all = basis(&fit_all.poles, dt, len, false);
    let kept: Vec<usize> = (0..n_all)
        .filter(|&c| {
            let share = b_all.col(c).norm_l2() * row_norm(&fit_all.residues, c);
            fit_all.poles[c].in_band(opts) && share >= opts.min_contribution * data_norm
        })
        .collect();
    if kept.is_empty() {
        return Ok(None);
    }
    let discarded_ratio = kept
        .iter()
        .map(|&c| {
            let pl = fit_all.poles[c];
            let wd = pl.omega * ((1.0 - pl.xi) * (1.0 + pl.xi)).sqrt();
            let sin_part = row_norm(&full, c) / wd;
            let cos_part = row_norm(&full, n_all + c);
            if sin_part > 0.0 {
                cos_part / sin_part
            } else {
                f64::INFINITY
            }
        })
        .collect();
    let fit = OrderFit {
        poles: kept.iter().map(|&c| fit_all.poles[c]).collect(),
        residues: select_rows(&fit_all.residues, &kept),
        time_error: fit_all.time_error,
        residual: fit_all.residual,
    };
    Ok(Some(KeptModel {
        fit,
        discarded_ratio,
        complex_residual,
    }))
}

/// The fit report of the kept modes `fit` (method §6.4): the time errors
/// of the kept modes and of every physical pole, and the `|G|` errors over
/// 200 frequencies across the band, overall and per response.
fn fit_report(
    r: &Responses,
    fit: &OrderFit,
    data: &Mat<f64>,
    dt: f64,
    opts: &IdentifyOptions,
    least_squares: LeastSquaresResiduals,
) -> FitReport {
    let time_error_all_poles = fit.time_error;
    let fitted = &basis(&fit.poles, dt, data.nrows(), false) * &fit.residues;
    let (per_time, time_error) = time_errors(&fitted, data);
    let nf = 200;
    let (lo, hi) = opts.band_hz;
    let freqs: Vec<f64> = (0..nf)
        .map(|q| lo + (hi - lo) * (q as f64 + 0.5) / nf as f64)
        .collect();
    let gd = dtft_magnitudes(data, dt, &freqs);
    let gf = dtft_magnitudes(&fitted, dt, &freqs);
    let (per_mag, magnitude_error) = time_errors(&gf, &gd);
    let per_response = r
        .pairs
        .iter()
        .enumerate()
        .map(|(c, &pair)| ResponseFit {
            pair,
            time_error: per_time[c],
            magnitude_error: per_mag[c],
        })
        .collect();
    FitReport {
        time_error,
        time_error_all_poles,
        magnitude_error,
        per_response,
        least_squares,
    }
}

/// Per kept pole: stable (method §6.3) when it is stable against order
/// `chosen - 1` or persists, stable, at order `chosen + 1`.
fn stable_modes(
    poles: &[Pole],
    diagram: &[DiagramOrder],
    chosen: usize,
    opts: &IdentifyOptions,
) -> Vec<bool> {
    let at = |m: usize| diagram.iter().find(|d| d.order == m);
    poles
        .iter()
        .map(|pl| {
            let f = pl.freq_hz();
            let near = |d: &DiagramOrder| {
                d.poles.iter().any(|dp| {
                    dp.stability == Stability::Stable
                        && (dp.freq_hz - f).abs() <= opts.stable_freq_tol * f
                })
            };
            at(chosen).is_some_and(near) || at(chosen + 1).is_some_and(near)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A poor fit of a ring names the ring's lowest mode; of a file (its
    /// modes unknown), no mode: an identified pole is no hint.
    #[test]
    fn a_poor_fit_names_the_sources_lowest_mode_only_when_known() {
        let e = |lowest| {
            LsceError::PoorFit {
                magnitude_error: 0.42,
                limit: 0.3,
                lo_hz: 0.0,
                hi_hz: 500.0,
                lowest_source_hz: lowest,
            }
            .to_string()
        };
        let ring = e(12.34);
        assert!(
            ring.contains("0.420") && ring.contains("lowest mode is at 12.3 Hz"),
            "{ring}"
        );
        let file = e(f64::NAN);
        assert!(
            file.contains("0.420") && !file.contains("lowest mode") && file.contains("--data"),
            "{file}"
        );
    }
}
