//! The fidelity figures computed off the UI thread (no egui here): the
//! relative L2 error of the modes in use and the error without each mode
//! (one error per mode, each 500 frequencies × p² receptances of the ring
//! and of the modal sum: a ring preset's figures took the UI thread for
//! whole frames). The job counts the errors done, stops between two when
//! cancelled (or dropped: a newer job for edited modes replaces it) and
//! sends its figures through a channel.

use super::fidelity::{FIDELITY_FREQS, FidelityFigures, FidelityRef};
use crate::analysis::fidelity::{band_frequencies, relative_l2_error, without_mode};
use crate::base::modal::ModalModel;
use crate::base::modal::Mode;
use crate::gui::jobs::Job;

/// What the figures depend on: the reference, the points' positions (m)
/// and the modes.
pub type FidelityKey = (FidelityRef, Vec<f64>, Vec<Mode>);

/// The figures of [`super::fidelity::figures`], with `cancelled` asked and
/// `done` called around each of the `modes.len() + 1` error computations.
pub fn figures_cancellable(
    reference: &FidelityRef,
    x_m: &[f64],
    modes: &[Mode],
    cancelled: &dyn Fn() -> bool,
    done: &dyn Fn(),
) -> Result<FidelityFigures, String> {
    let freqs = band_frequencies(reference.band_hz.0, reference.band_hz.1, FIDELITY_FREQS)
        .map_err(|e| e.to_string())?;
    let src = reference.model(x_m);
    let p = x_m.len();
    let stopped = || Err("the fidelity computation was cancelled".to_string());
    if cancelled() {
        return stopped();
    }
    let fidelity = relative_l2_error(&src, &ModalModel::from_modes(modes, p), &freqs)
        .map_err(|e| e.to_string())?;
    done();
    let mut removal_costs = Vec::with_capacity(modes.len());
    for k in 0..modes.len() {
        if cancelled() {
            return stopped();
        }
        let cut = without_mode(modes, k).map_err(|e| e.to_string())?;
        let e = relative_l2_error(&src, &ModalModel::from_modes(&cut, p), &freqs)
            .map_err(|e| e.to_string())?;
        removal_costs.push(e.relative_l2);
        done();
    }
    Ok(FidelityFigures {
        fidelity,
        removal_costs,
        band_hz: reference.band_hz,
        num_freqs: FIDELITY_FREQS,
    })
}

/// A fidelity computation under way.
#[derive(Debug)]
pub struct FidelityJob {
    /// What the job computes the figures of.
    pub key: FidelityKey,
    job: Job<Result<FidelityFigures, String>>,
}

impl FidelityJob {
    /// Starts the figures of `key` on a std::thread.
    pub fn spawn(key: FidelityKey) -> Result<Self, String> {
        let total = key.2.len() as u64 + 1;
        let (reference, x_m, modes) = key.clone();
        let job = Job::spawn("fidelity", total, move |p| {
            figures_cancellable(&reference, &x_m, &modes, &|| p.cancelled(), &|| p.add(1))
        })?;
        Ok(FidelityJob { key, job })
    }

    /// Whether the job computes the figures of `key`.
    pub fn is_for(&self, reference: &FidelityRef, x_m: &[f64], modes: &[Mode]) -> bool {
        self.key.0 == *reference && self.key.1 == x_m && self.key.2 == modes
    }

    /// Fraction of the errors done (0..=1).
    pub fn progress(&self) -> f64 {
        self.job.fraction()
    }

    /// The figures once the thread finished (never blocks); `None` while
    /// it runs. A replaced (or dropped) job stops between two error
    /// computations.
    pub fn poll(&self) -> Option<Result<FidelityFigures, String>> {
        self.job.poll().map(Result::flatten)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Scene;
    use crate::gui::research::fidelity::figures;
    use std::sync::atomic::{AtomicU64, Ordering};

    fn paper_key() -> FidelityKey {
        let scene = Scene::parse(
            include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/presets/paper.ron")),
            "paper",
        )
        .unwrap();
        let r = FidelityRef::of_scene(&scene).unwrap();
        let x: Vec<f64> = scene.points.iter().map(|p| p.x_m).collect();
        let mut modes = r.ring.modes(&x);
        modes.remove(0);
        (r, x, modes)
    }

    /// The job's figures are those of the library's `removal_costs` path
    /// computed on the calling thread.
    #[test]
    fn a_job_delivers_the_figures_of_the_ui_thread() {
        let key = paper_key();
        let job = FidelityJob::spawn(key.clone()).unwrap();
        assert!(job.is_for(&key.0, &key.1, &key.2));
        assert!(!job.is_for(&key.0, &key.1, &key.2[1..]));
        let got = loop {
            match job.poll() {
                None => std::thread::yield_now(),
                Some(r) => break r.unwrap(),
            }
        };
        assert_eq!(job.progress(), 1.0);
        let want = figures(&key.0, &key.1, &key.2).unwrap();
        assert_eq!(got, want);
        assert!(got.fidelity.relative_l2 > 0.0);
    }

    /// A cancelled computation stops with an error instead of figures.
    #[test]
    fn a_cancelled_computation_stops() {
        let (r, x, modes) = paper_key();
        let calls = AtomicU64::new(0);
        let res = figures_cancellable(
            &r,
            &x,
            &modes,
            &|| calls.load(Ordering::Relaxed) >= 2,
            &|| {
                calls.fetch_add(1, Ordering::Relaxed);
            },
        );
        assert!(res.unwrap_err().contains("cancelled"));
        assert_eq!(calls.load(Ordering::Relaxed), 2);
    }
}
