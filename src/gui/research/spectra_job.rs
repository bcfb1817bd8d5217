//! The spectra of the run computed off the UI thread (no egui here): the
//! samples are copied out of the history on the UI thread (cheap), the
//! transforms run on a std::thread with a progress count and a cancel flag,
//! and the result comes back through a channel. A job that a newer one
//! replaced is cancelled and its result never read; a result for a history
//! that was restarted meanwhile is dropped.

use super::spectra::{HistoryKey, HistorySpectra, SpectraInput};
use crate::analysis::spectrum::Window;
use crate::gui::jobs::Job;

/// Below this many samples to transform (in all spectra) the spectra are
/// computed at once on the UI thread (a few ms at most): no "computing…"
/// flicker for short runs.
pub const INLINE_MAX_WORK: usize = 100_000;

/// A spectra computation under way.
#[derive(Debug)]
pub struct SpectraJob {
    /// The history the job computes the spectra of.
    pub key: HistoryKey,
    job: Job<Result<HistorySpectra, String>>,
}

/// What a poll of a job found.
#[derive(Debug)]
pub enum SpectraPoll {
    Running,
    /// The spectra (or why there are none) of the job's history.
    Done(Box<Result<HistorySpectra, String>>),
    /// The history was restarted since the job began: its result is stale.
    Stale,
}

impl SpectraJob {
    /// Starts the transforms of `input` (samples of the history `key`).
    pub fn spawn(key: HistoryKey, input: SpectraInput, window: Window) -> Result<Self, String> {
        let total = input.num_spectra() as u64;
        let job = Job::spawn("spectra", total, move |p| {
            input.compute(window, &|| p.cancelled(), &|| p.add(1))
        })?;
        Ok(SpectraJob { key, job })
    }

    /// Fraction of the spectra done (0..=1).
    pub fn progress(&self) -> f64 {
        self.job.fraction()
    }

    /// The result once the thread finished (never blocks); `now` is the
    /// history at this frame.
    pub fn poll(&self, now: &HistoryKey) -> SpectraPoll {
        // a replaced (or dropped) job stops between two spectra
        match self.job.poll() {
            None => SpectraPoll::Running,
            Some(_) if restarted(&self.key, now) => SpectraPoll::Stale,
            Some(r) => SpectraPoll::Done(Box::new(r.flatten())),
        }
    }
}

/// Whether the history `now` is no longer the run (or a continuation of the
/// run) that `then` was taken from: reset, another scene, fewer samples.
pub fn restarted(then: &HistoryKey, now: &HistoryKey) -> bool {
    now.points != then.points || now.len < then.len || now.stride < then.stride
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Scene;
    use crate::gui::model::history::History;
    use crate::gui::research::spectra::history_spectra;

    fn run(steps: usize) -> History {
        let scene = Scene::parse(
            include_str!(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/presets/three_points.ron"
            )),
            "three_points",
        )
        .unwrap();
        let mut sim = crate::Simulation::from_scene(&scene).unwrap();
        let mut h = History::new(scene.num_points(), 1 << 20);
        h.record_initial(&sim);
        for _ in 0..steps {
            sim.step().unwrap();
            h.after_step(&sim);
        }
        h
    }

    /// The job's spectra are those computed on the calling thread.
    #[test]
    fn a_job_delivers_the_same_spectra_as_the_ui_thread() {
        let h = run(8000);
        let (ramp, dt) = (0.03, 1e-5);
        let input = SpectraInput::of_history(&h, ramp, dt).unwrap();
        let key = HistoryKey::of(&h);
        let job = SpectraJob::spawn(key, input, Window::Hann).unwrap();
        let got = loop {
            match job.poll(&key) {
                SpectraPoll::Running => std::thread::yield_now(),
                SpectraPoll::Done(r) => break r.unwrap(),
                SpectraPoll::Stale => panic!("same history, not stale"),
            }
        };
        assert_eq!(job.progress(), 1.0);
        let want = history_spectra(&h, ramp, dt, Window::Hann).unwrap();
        assert_eq!(got.span, want.span);
        for (a, b) in got.spectra.force.iter().zip(&want.spectra.force) {
            assert_eq!(a.amplitude, b.amplitude);
        }
        assert_eq!(
            got.spectra.total_force.amplitude,
            want.spectra.total_force.amplitude
        );
    }

    /// A result for a history restarted meanwhile is dropped; a grown
    /// history (the same run, further on) keeps it.
    #[test]
    fn a_result_for_a_restarted_history_is_stale() {
        let h = run(8000);
        let key = HistoryKey::of(&h);
        let input = SpectraInput::of_history(&h, 0.03, 1e-5).unwrap();
        let job = SpectraJob::spawn(key, input, Window::Hann).unwrap();
        let reset = HistoryKey::of(&run(10));
        loop {
            match job.poll(&reset) {
                SpectraPoll::Running => std::thread::yield_now(),
                SpectraPoll::Stale => break,
                SpectraPoll::Done(_) => panic!("a restarted history takes no old result"),
            }
        }
        let grown = HistoryKey {
            len: key.len + 100,
            ..key
        };
        assert!(!restarted(&key, &grown));
        assert!(restarted(&key, &reset));
    }

    /// A cancelled computation stops with an error instead of spectra.
    #[test]
    fn a_cancelled_computation_stops() {
        let h = run(8000);
        let input = SpectraInput::of_history(&h, 0.03, 1e-5).unwrap();
        let r = input.compute(Window::Hann, &|| true, &|| {});
        assert!(r.is_err());
    }
}
