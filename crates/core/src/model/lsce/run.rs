//! The stages of an LSCE identification (method §6.2–6.4): the Hankel
//! data's QR, the stabilisation diagram an order at a time, the model at
//! the chosen order and its report.

use super::fit::{
    KeptModel, basis, data_matrix, fit_order, fit_report, kept_model, mac, row, row_norm,
    select_rows, time_errors,
};
use super::order::choose_order;
use super::picked::modes_of_fit;
use super::prediction::{HANKEL_CHUNK, hankel_add, poles_of_order};
use super::{
    Identification, IdentifyOptions, LeastSquaresResiduals, LsceError, OrderErrors, Pole,
    Responses, check_input,
};
use crate::model::stability::{DiagramOrder, DiagramPole, Stability};
use faer::Mat;

/// [`identify`](super::identify) one stage at a time, for a caller that
/// must return between stages (a page in the browser, which has one
/// thread): the QR of the Hankel data a few responses at a time, then each
/// order of the stabilisation diagram, then the model at the chosen order
/// and its report. The stages are `identify`'s own, in its order: the
/// result is the same to the bit.
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
    order_errors: Vec<OrderErrors>,
    kept_at: Vec<Vec<usize>>,
    prev: Option<BandPoles>,
    /// The chosen order, its model and its prediction residual.
    model: Option<(usize, KeptModel, f64)>,
    stages_done: usize,
}

impl LsceRun {
    /// Checks the options and the responses (the errors of
    /// [`identify`](super::identify)).
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
            order_errors: Vec::new(),
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
            let (order, errors, kept, band) =
                diagram_order(&self.rmat, data, m, dt, data_norm, self.prev.as_ref(), opts)?;
            self.kept_at.push(kept);
            self.diagram.push(order);
            self.order_errors.push(errors);
            self.prev = Some(band);
            return Ok(None);
        }
        let Some((chosen, model, prediction_residual)) = &self.model else {
            // the given order, or the diagram's choice (method §6.3)
            let chosen = match opts.model_order {
                Some(m) => m,
                None => choose_order(&self.diagram, &self.order_errors, &self.kept_at, opts)
                    .unwrap_or(opts.max_model_order),
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
            given_order: self.opts.model_order,
            stable,
            discarded_ratio: model.discarded_ratio.clone(),
            diagram: std::mem::take(&mut self.diagram),
            order_errors: std::mem::take(&mut self.order_errors),
            persistence: self.opts.persistence(),
            report,
        }))
    }
}

/// The in-band poles of one order of the stabilisation diagram and their
/// residues (one per response).
type BandPoles = (Vec<Pole>, Vec<Vec<f64>>);

/// One order `m` of the stabilisation diagram (method §6.2, 1–5, and §6.3):
/// its in-band poles, each classified against `prev` (the in-band poles
/// and residues of the order below; the residues' MAC is the shape
/// compared), and its time errors; the in-band poles
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
) -> Result<(DiagramOrder, OrderErrors, Vec<usize>, BandPoles), LsceError> {
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
    let criteria = opts.stability_criteria();
    let dpoles: Vec<DiagramPole> = band_poles
        .iter()
        .zip(&res)
        .map(|(pl, rv)| DiagramPole {
            freq_hz: pl.freq_hz(),
            damping_ratio: pl.xi,
            stability: match prev {
                None => Stability::New,
                Some((pp, pr)) => {
                    criteria.classify(pl.omega, pl.xi, pp.iter().map(|q| (q.omega, q.xi)), |k| {
                        mac(rv, &pr[k])
                    })
                }
            },
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
    };
    let errors = OrderErrors {
        order: m,
        time_error: fit.time_error,
        band_time_error: time_errors(&band_fit, data).1,
    };
    Ok((order, errors, kept, (band_poles, res)))
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
