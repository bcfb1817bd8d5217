//! The spectra of the run computed off the UI thread (no egui here): the
//! samples are copied out of the history on the UI thread (cheap), the
//! transforms run on a std::thread with a progress count and a cancel flag,
//! and the result comes back through a channel. A job that a newer one
//! replaced is cancelled and its result never read; a result for a history
//! that was restarted meanwhile is dropped.

use super::spectra::{HistoryKey, HistorySpectra, SpectraInput, SpectraRun};
use crate::analysis::spectrum::Window;
use crate::gui::jobs::{Job, Progress};

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
    /// (In the browser, a spectrum at a time within the frames:
    /// [`Job::spawn_sliced`].)
    pub fn spawn(key: HistoryKey, input: SpectraInput, window: Window) -> Result<Self, String> {
        Self::start(key, input, window, false)
    }

    /// The transforms run on the caller's thread, a slice at each poll
    /// ([`Job::in_slices`]): how a page in the browser runs them. The
    /// spectra equal the threaded job's.
    pub fn spawn_in_slices(
        key: HistoryKey,
        input: SpectraInput,
        window: Window,
    ) -> Result<Self, String> {
        Self::start(key, input, window, true)
    }

    fn start(
        key: HistoryKey,
        input: SpectraInput,
        window: Window,
        in_slices: bool,
    ) -> Result<Self, String> {
        let total = input.num_spectra() as u64;
        let mut run = SpectraRun::new(input, window);
        let work = move |p: &Progress, deadline: Option<web_time::Instant>| loop {
            if p.cancelled() {
                return Some(Err("cancelled".to_string()));
            }
            let r = run.stage();
            p.set(run.done() as u64);
            match r {
                Err(e) => return Some(Err(e)),
                Ok(Some(s)) => {
                    p.set(total);
                    return Some(Ok(s));
                }
                Ok(None) if deadline.is_some_and(|d| web_time::Instant::now() >= d) => {
                    return None;
                }
                Ok(None) => {}
            }
        };
        let job = if in_slices {
            Job::in_slices("spectra", total, work)
        } else {
            Job::spawn_sliced("spectra", total, work)?
        };
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
    use crate::SceneSimulation;
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

    /// The spectra computed in slices (the browser's way, a spectrum at a
    /// time within the polls) are those of each signal transformed alone:
    /// per point its force and displacement over the steady span, and the
    /// sum of the forces, to the bit.
    #[test]
    fn spectra_in_slices_are_each_signal_s_spectrum() {
        use crate::analysis::spectrum::spectrum;
        use crate::gui::model::history::Quantity;
        use crate::gui::research::spectra::steady_range;
        let h = run(8000);
        let (ramp, dt) = (0.03, 1e-5);
        let key = HistoryKey::of(&h);
        let input = SpectraInput::of_history(&h, ramp, dt).unwrap();
        let job = SpectraJob::spawn_in_slices(key, input, Window::Hann).unwrap();
        assert_eq!(job.progress(), 0.0, "nothing runs before the first poll");
        let got = loop {
            match job.poll(&key) {
                SpectraPoll::Running => {}
                SpectraPoll::Done(r) => break r.unwrap(),
                SpectraPoll::Stale => panic!("same history, not stale"),
            }
        };
        assert_eq!(job.progress(), 1.0);
        let spacing = h.stride() as f64 * dt;
        let (k0, k1) = steady_range(h.times(), ramp, spacing);
        let signal = |q: Quantity, i: usize| (k0..k1).map(|k| h.value(q, i, k)).collect::<Vec<_>>();
        let alone = |x: &[f64]| spectrum(x, 1.0 / spacing, Window::Hann, true).unwrap();
        let mut total = vec![0.0; k1 - k0];
        for i in 0..h.num_points() {
            let q = signal(Quantity::Force, i);
            for (t, x) in total.iter_mut().zip(&q) {
                *t += x;
            }
            assert_eq!(got.spectra.force[i].amplitude, alone(&q).amplitude);
            let u = signal(Quantity::Displacement, i);
            assert_eq!(got.spectra.displacement[i].amplitude, alone(&u).amplitude);
        }
        assert_eq!(got.spectra.total_force.amplitude, alone(&total).amplitude);
        // cancelled between slices: an error, not spectra
        let input = SpectraInput::of_history(&h, ramp, dt).unwrap();
        let job = SpectraJob::spawn_in_slices(key, input, Window::Hann).unwrap();
        job.job.cancel();
        match job.poll(&key) {
            SpectraPoll::Done(r) => assert!(r.is_err()),
            p => panic!("{p:?}"),
        }
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
