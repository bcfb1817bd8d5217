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
    let mut work = FidelityWork::new(reference, x_m, modes.to_vec())?;
    loop {
        if let Some(r) = work.advance(cancelled, done, None) {
            return r;
        }
    }
}

/// The fidelity figures computed error by error, in slices until a
/// deadline ([`FidelityWork::advance`]): on a thread, or within the
/// frames of a page in the browser.
pub struct FidelityWork {
    reference: FidelityRef,
    freqs: Vec<f64>,
    src: ModalModel,
    p: usize,
    modes: Vec<Mode>,
    fidelity: Option<crate::analysis::fidelity::Fidelity>,
    removal_costs: Vec<f64>,
}

impl FidelityWork {
    pub fn new(reference: &FidelityRef, x_m: &[f64], modes: Vec<Mode>) -> Result<Self, String> {
        let freqs = band_frequencies(reference.band_hz.0, reference.band_hz.1, FIDELITY_FREQS)
            .map_err(|e| e.to_string())?;
        Ok(FidelityWork {
            reference: reference.clone(),
            src: reference.model(x_m),
            p: x_m.len(),
            freqs,
            removal_costs: Vec::with_capacity(modes.len()),
            modes,
            fidelity: None,
        })
    }

    /// Computes errors until `deadline` (`None`: all): the figures once
    /// every error is done, `None` before; `cancelled` is asked and `done`
    /// called around each error.
    pub fn advance(
        &mut self,
        cancelled: &dyn Fn() -> bool,
        done: &dyn Fn(),
        deadline: Option<web_time::Instant>,
    ) -> Option<Result<FidelityFigures, String>> {
        let (p, freqs) = (self.p, &self.freqs);
        let error = |modes: &[Mode]| {
            relative_l2_error(&self.src, &ModalModel::from_modes(modes, p), freqs)
                .map_err(|e| e.to_string())
        };
        loop {
            if cancelled() {
                return Some(Err("the fidelity computation was cancelled".to_string()));
            }
            let k = self.removal_costs.len();
            match &self.fidelity {
                None => match error(&self.modes) {
                    Ok(e) => self.fidelity = Some(e),
                    Err(e) => return Some(Err(e)),
                },
                Some(_) if k < self.modes.len() => {
                    let cut = match without_mode(&self.modes, k) {
                        Ok(cut) => cut,
                        Err(e) => return Some(Err(e.to_string())),
                    };
                    match error(&cut) {
                        Ok(e) => self.removal_costs.push(e.relative_l2),
                        Err(e) => return Some(Err(e)),
                    }
                }
                Some(fidelity) => {
                    return Some(Ok(FidelityFigures {
                        fidelity: fidelity.clone(),
                        removal_costs: std::mem::take(&mut self.removal_costs),
                        band_hz: self.reference.band_hz,
                        num_freqs: FIDELITY_FREQS,
                    }));
                }
            }
            done();
            if deadline.is_some_and(|d| web_time::Instant::now() >= d)
                && self.removal_costs.len() < self.modes.len()
            {
                return None;
            }
        }
    }
}

/// A fidelity computation under way.
#[derive(Debug)]
pub struct FidelityJob {
    /// What the job computes the figures of.
    pub key: FidelityKey,
    job: Job<Result<FidelityFigures, String>>,
}

impl FidelityJob {
    /// Starts the figures of `key` on a std::thread (in the browser, in
    /// slices within the frames).
    pub fn spawn(key: FidelityKey) -> Result<Self, String> {
        Self::start(key, false)
    }

    /// The figures of `key` computed in slices at each poll, on the
    /// caller's thread ([`Job::in_slices`]).
    pub fn spawn_in_slices(key: FidelityKey) -> Result<Self, String> {
        Self::start(key, true)
    }

    fn start(key: FidelityKey, in_slices: bool) -> Result<Self, String> {
        let total = key.2.len() as u64 + 1;
        let (reference, x_m, modes) = key.clone();
        let mut work = FidelityWork::new(&reference, &x_m, modes)?;
        let slice = move |p: &crate::gui::jobs::Progress, deadline| {
            work.advance(&|| p.cancelled(), &|| p.add(1), deadline)
        };
        let job = if in_slices {
            Job::in_slices("fidelity", total, slice)
        } else {
            Job::spawn_sliced("fidelity", total, slice)?
        };
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

    /// In slices (the browser's way) the figures are those of the thread,
    /// over several polls.
    #[test]
    fn figures_in_slices_equal_the_thread_s() {
        let key = paper_key();
        let job = FidelityJob::spawn_in_slices(key.clone()).unwrap();
        let mut polls = 0;
        let got = loop {
            polls += 1;
            if let Some(r) = job.poll() {
                break r.unwrap();
            }
        };
        assert_eq!(got, figures(&key.0, &key.1, &key.2).unwrap());
        assert_eq!(job.progress(), 1.0);
        assert!(polls >= 1);
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
