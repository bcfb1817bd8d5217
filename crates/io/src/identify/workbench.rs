//! The identification workbench's state, without a UI: an identification's
//! stabilisation diagram, the poles picked on it (the automatic choice to
//! begin with) and the modes they give, their residues fitted to the
//! responses again at every pick or drop; the fit of each response pair in
//! `|G|`. The visualiser's view draws it and pushes picks; tests drive it
//! here.

use tirecontact_core::base::modal::{ModalModel, Mode};
use tirecontact_core::model::lsce::{
    Identification, LsceError, Responses, modes_of_poles, response_magnitudes,
};
use tirecontact_core::model::stability;

/// A pole of the diagram: its order's index and its index in that order.
pub type PoleAt = (usize, usize);

/// Two poles within this relative distance in frequency are one physical
/// pole (one mode per physical pole).
const SAME_POLE: f64 = 5e-3;

/// Frequencies (per band) at which `|G|` is compared.
const MAGNITUDE_POINTS: usize = 200;

/// The workbench: what was identified and what is picked.
#[derive(Debug, Clone)]
pub struct Workbench {
    pub responses: Responses,
    pub identification: Identification,
    /// The band of the identification (Hz).
    pub band_hz: (f64, f64),
    /// The poles picked, by frequency.
    pub picked: Vec<PoleAt>,
    /// The modes of the picked poles.
    pub modes: Vec<Mode>,
    /// Relative time error of the picked modes' fit (-).
    pub time_error: f64,
    /// Frequencies (Hz) of the identified modes the automatic choice left
    /// out: no pole within the frequency tolerance of them persists
    /// ([`Workbench::automatic`]).
    pub left_out_hz: Vec<f64>,
    /// `|G|` of each response at [`Self::frequencies`] (m/N), and their
    /// sum over the pairs: the data's, computed once.
    data_magnitudes: Vec<Vec<f64>>,
    summed: Vec<f64>,
    /// The picked modes' fit of each pair, computed at every pick.
    fits: Vec<PairFit>,
}

impl Workbench {
    /// A workbench on `identification` of `responses` over `band_hz`, its
    /// automatic choice picked.
    pub fn new(
        responses: Responses,
        identification: Identification,
        band_hz: (f64, f64),
    ) -> Result<Self, LsceError> {
        let freqs = frequencies(band_hz);
        let data_magnitudes = response_magnitudes(&responses, &freqs)?;
        let summed = (0..freqs.len())
            .map(|q| data_magnitudes.iter().map(|d| d[q]).sum())
            .collect();
        let mut w = Workbench {
            responses,
            identification,
            band_hz,
            picked: Vec::new(),
            modes: Vec::new(),
            time_error: 1.0,
            left_out_hz: Vec::new(),
            data_magnitudes,
            summed,
            fits: Vec::new(),
        };
        w.automatic()?;
        Ok(w)
    }

    /// The pole at `at`: `(freq_hz, damping_ratio)`.
    pub fn pole(&self, at: PoleAt) -> Option<(f64, f64)> {
        let p = self.identification.diagram.get(at.0)?.poles.get(at.1)?;
        Some((p.freq_hz, p.damping_ratio))
    }

    /// Picks the automatic choice: the poles the persistence rule keeps
    /// ([`stability::keep`], the rule of the frequency-domain fit, with
    /// the identification's frequency tolerance) up to the model order the
    /// options gave, else the diagram's highest (as the frequency-domain
    /// fit takes `--order`), each taken at the highest order where it is
    /// stable. A pole stable
    /// in frequency and damping only, or at fewer than a run of orders, is
    /// never picked without the user's click; an identified mode with no
    /// kept pole within the tolerance is listed in [`Self::left_out_hz`].
    pub fn automatic(&mut self) -> Result<(), LsceError> {
        let id = &self.identification;
        let selection = stability::keep(&id.diagram, id.given_order, 1, &id.persistence);
        let tol = id.persistence.freq_tol;
        self.left_out_hz = id
            .modes
            .iter()
            .filter(|m| {
                !selection
                    .kept
                    .iter()
                    .any(|k| (k.pole.freq_hz - m.freq_hz).abs() <= tol * m.freq_hz)
            })
            .map(|m| m.freq_hz)
            .collect();
        self.picked = selection.kept.iter().map(|k| k.at).collect();
        self.refit()
    }

    /// Picks the pole at `at`, or drops it if picked; a pole within 0.5 %
    /// in frequency of one picked from another order replaces it (one
    /// mode per physical pole).
    pub fn toggle(&mut self, at: PoleAt) -> Result<(), LsceError> {
        let Some((f, _)) = self.pole(at) else {
            return Err(LsceError::Input(format!("no pole {at:?} in the diagram")));
        };
        if let Some(k) = self.picked.iter().position(|&p| p == at) {
            self.picked.remove(k);
        } else {
            let keep: Vec<PoleAt> = self
                .picked
                .iter()
                .copied()
                .filter(|p| {
                    self.pole(*p)
                        .is_none_or(|(g, _)| (g - f).abs() > SAME_POLE * f)
                })
                .collect();
            self.picked = keep;
            self.picked.push(at);
        }
        self.refit()
    }

    /// The pole nearest `(freq_hz, order)` on the diagram, within
    /// `tol_hz` in frequency and one order.
    pub fn nearest(&self, freq_hz: f64, order: f64, tol_hz: f64) -> Option<PoleAt> {
        let mut best: Option<(f64, PoleAt)> = None;
        for (oi, d) in self.identification.diagram.iter().enumerate() {
            let dm = (d.order as f64 - order).abs();
            if dm > 1.0 {
                continue;
            }
            for (k, p) in d.poles.iter().enumerate() {
                let df = (p.freq_hz - freq_hz).abs();
                if df > tol_hz {
                    continue;
                }
                let score = df / tol_hz + dm;
                if best.is_none_or(|(s, _)| score < s) {
                    best = Some((score, (oi, k)));
                }
            }
        }
        best.map(|(_, at)| at)
    }

    /// The modes of the picked poles, residues fitted again.
    fn refit(&mut self) -> Result<(), LsceError> {
        let mut by_freq: Vec<(f64, f64, PoleAt)> = self
            .picked
            .iter()
            .filter_map(|&p| self.pole(p).map(|(f, xi)| (f, xi, p)))
            .collect();
        by_freq.sort_by(|a, b| a.0.total_cmp(&b.0));
        self.picked = by_freq.iter().map(|q| q.2).collect();
        let poles: Vec<(f64, f64)> = by_freq.iter().map(|q| (q.0, q.1)).collect();
        if poles.is_empty() {
            self.modes.clear();
            self.time_error = 1.0;
        } else {
            let (modes, e) = modes_of_poles(&self.responses, &poles)?;
            self.modes = modes;
            self.time_error = e;
        }
        self.fits = self.fit_pairs()?;
        Ok(())
    }

    /// The frequencies (Hz) of the `|G|` comparisons over the band.
    pub fn frequencies(&self) -> Vec<f64> {
        frequencies(self.band_hz)
    }

    /// Per response pair: `|G|` of the data and of the picked modes at
    /// [`Self::frequencies`] (m/N), and their relative L2 difference (-).
    pub fn pair_fits(&self) -> &[PairFit] {
        &self.fits
    }

    /// The sum over the pairs of the data's `|G|` at [`Self::frequencies`]
    /// (drawn under the diagram).
    pub fn summed_magnitude(&self) -> &[f64] {
        &self.summed
    }

    /// The pairs' fits of the picked modes: both `|G|` the DTFT of their
    /// samples (so that sampling and truncation are alike).
    fn fit_pairs(&self) -> Result<Vec<PairFit>, LsceError> {
        let freqs = self.frequencies();
        let r = &self.responses;
        let model = ModalModel::from_modes(&self.modes, r.num_points);
        let len = r.data.first().map_or(0, Vec::len);
        let sampled = Responses {
            data: r
                .pairs
                .iter()
                .map(|&(i, j)| {
                    (0..len)
                        .map(|n| model.green(i, j, n as f64 * r.dt_s).0)
                        .collect()
                })
                .collect(),
            ..r.clone()
        };
        let fitted = response_magnitudes(&sampled, &freqs)?;
        Ok(r.pairs
            .iter()
            .zip(&self.data_magnitudes)
            .zip(fitted)
            .map(|((&pair, d), m)| {
                let num: f64 = d.iter().zip(&m).map(|(a, b)| (a - b) * (a - b)).sum();
                let den: f64 = d.iter().map(|a| a * a).sum();
                PairFit {
                    pair,
                    data: d.clone(),
                    model: m,
                    error: if den > 0.0 { (num / den).sqrt() } else { 0.0 },
                }
            })
            .collect())
    }
}

/// [`MAGNITUDE_POINTS`] frequencies (Hz) spread over `band_hz`.
fn frequencies((lo, hi): (f64, f64)) -> Vec<f64> {
    (0..MAGNITUDE_POINTS)
        .map(|q| lo + (hi - lo) * (q as f64 + 0.5) / MAGNITUDE_POINTS as f64)
        .collect()
}

/// One response pair's `|G|`: data, model and their relative L2 difference.
#[derive(Debug, Clone, PartialEq)]
pub struct PairFit {
    pub pair: (usize, usize),
    pub data: Vec<f64>,
    pub model: Vec<f64>,
    pub error: f64,
}

#[cfg(test)]
mod tests {
    use super::*;
    use tirecontact_core::model::lsce::{IdentifyOptions, identify};
    use tirecontact_core::model::stability::Stability;

    /// Responses of a two-point, two-mode model, and their identification.
    fn bench() -> Workbench {
        let m = crate::readers::two_mode_test_model();
        let dt = 1.0 / 2000.0;
        let pairs = vec![(0, 0), (0, 1), (1, 1)];
        let data = pairs
            .iter()
            .map(|&(i, j)| (0..800).map(|n| m.green(i, j, n as f64 * dt).0).collect())
            .collect();
        let r = Responses {
            dt_s: dt,
            num_points: 2,
            pairs,
            data,
        };
        let opts = IdentifyOptions {
            band_hz: (0.0, 400.0),
            max_model_order: 12,
            ..Default::default()
        };
        let id = identify(&r, &opts).unwrap();
        Workbench::new(r, id, opts.band_hz).unwrap()
    }

    #[test]
    fn the_automatic_choice_gives_the_identified_modes() {
        let w = bench();
        assert_eq!(w.modes.len(), 2);
        for (a, b) in w.modes.iter().zip(&w.identification.modes) {
            assert!((a.freq_hz - b.freq_hz).abs() < 1e-9 * b.freq_hz);
        }
        assert!(w.time_error < 1e-6, "{}", w.time_error);
        assert!(w.pair_fits().iter().all(|p| p.error < 1e-3));
    }

    /// The pole of the diagram's highest order nearest `freq_hz`.
    fn at_top_order(w: &Workbench, freq_hz: f64) -> PoleAt {
        let oi = w.identification.diagram.len() - 1;
        let poles = &w.identification.diagram[oi].poles;
        let k = (0..poles.len())
            .min_by(|&a, &b| {
                (poles[a].freq_hz - freq_hz)
                    .abs()
                    .total_cmp(&(poles[b].freq_hz - freq_hz).abs())
            })
            .unwrap();
        (oi, k)
    }

    /// Marks every pole within 1 % of `freq_hz` at the orders `orders`
    /// (diagram indices) as `stability`.
    fn mark(w: &mut Workbench, freq_hz: f64, orders: std::ops::Range<usize>, s: Stability) {
        for d in &mut w.identification.diagram[orders] {
            for p in &mut d.poles {
                if (p.freq_hz - freq_hz).abs() < 0.01 * freq_hz {
                    p.stability = s;
                }
            }
        }
    }

    /// The automatic choice is the persistence rule: a pole not stable at
    /// the top order is taken at the highest order where it is; a pole
    /// stable in frequency and damping only (its residues' shape changing
    /// from order to order), or stable at fewer than 5 consecutive orders,
    /// is never picked, and its mode is said to be left out.
    #[test]
    fn the_automatic_choice_keeps_only_persisting_poles() {
        let mut w = bench();
        let top = w.identification.diagram.len();
        let (oi, k) = at_top_order(&w, 170.0);
        w.identification.diagram[oi].poles[k].stability = Stability::New;
        w.automatic().unwrap();
        assert_eq!(w.modes.len(), 2);
        assert!(w.left_out_hz.is_empty());
        assert!(!w.picked.contains(&(oi, k)));
        let high = *w.picked.last().unwrap();
        assert_eq!(high.0, oi - 1, "taken at the order below the top");
        let (f, _) = w.pole(high).unwrap();
        assert!((f - 170.0).abs() < 0.01 * 170.0, "{f}");
        // stable in frequency and damping only, at every order: left out
        mark(&mut w, 170.0, 0..top, Stability::FrequencyDamping);
        w.automatic().unwrap();
        assert_eq!(w.modes.len(), 1);
        assert!((w.modes[0].freq_hz - 60.0).abs() < 0.01);
        assert_eq!(w.left_out_hz.len(), 1);
        assert!((w.left_out_hz[0] - 170.0).abs() < 0.01);
        // stable at the 4 orders up to the top only: a run too short
        mark(&mut w, 170.0, top - 4..top, Stability::Stable);
        w.automatic().unwrap();
        assert_eq!(w.modes.len(), 1);
        // at 5: kept
        mark(&mut w, 170.0, top - 5..top, Stability::Stable);
        w.automatic().unwrap();
        assert_eq!(w.modes.len(), 2);
        assert!(w.left_out_hz.is_empty());
        // a click still picks a pole the rule leaves out
        mark(&mut w, 170.0, 0..top, Stability::New);
        w.automatic().unwrap();
        assert_eq!(w.modes.len(), 1);
        w.toggle((oi, k)).unwrap();
        assert_eq!(w.modes.len(), 2);
    }

    #[test]
    fn dropping_a_pole_drops_its_mode_and_picking_it_back_restores_the_fit() {
        let mut w = bench();
        let before = w.time_error;
        let high = *w.picked.last().unwrap();
        w.toggle(high).unwrap();
        assert_eq!(w.modes.len(), 1);
        assert!((w.modes[0].freq_hz - 60.0).abs() < 0.01);
        assert!(
            w.time_error > 0.1,
            "the 170 Hz mode's share is missing: {}",
            w.time_error
        );
        let errors = w.pair_fits();
        assert!(errors.iter().any(|p| p.error > 0.1));
        // picked again from another order: the same mode, fitted again
        let (f, _) = w.pole(high).unwrap();
        let other = high.0 - 1;
        let at = w
            .nearest(f, w.identification.diagram[other].order as f64, 1.0)
            .unwrap();
        assert_eq!(at.0, other);
        w.toggle(at).unwrap();
        assert_eq!(w.modes.len(), 2);
        assert!(
            w.time_error < 10.0 * before.max(1e-9),
            "{} vs {before}",
            w.time_error
        );
        // a pole within 0.5 % of a picked one replaces it
        w.toggle(high).unwrap();
        assert_eq!(w.modes.len(), 2);
        assert!(w.picked.contains(&high) && !w.picked.contains(&at));
    }
}
