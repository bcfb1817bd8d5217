//! One shape for every piece of work the visualiser runs off its UI thread
//! (identification, CSV and frame exports, sweeps, spectra, fidelity): a
//! named thread, a progress counter (done of total), a cancel flag, and the
//! result, picked up once by a poll that never blocks. A job dropped while
//! running (replaced by a newer one, or the app closing) is asked to stop.
//!
//! A page in the browser has no threads. There a job made by
//! [`Job::spawn_sliced`] runs in slices inside the polls, each until a
//! deadline ([`SLICE_S`] of a frame), so the page keeps drawing; a plain
//! [`Job::spawn`] runs whole at once.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::mpsc::{Receiver, TryRecvError, channel};

/// What the worker thread sees of its job: where to count progress and
/// whether it was asked to stop.
#[derive(Debug, Clone, Default)]
pub struct Progress {
    done: Arc<AtomicU64>,
    total: Arc<AtomicU64>,
    cancel: Arc<AtomicBool>,
}

impl Progress {
    /// Whether the job was cancelled (or dropped).
    pub fn cancelled(&self) -> bool {
        self.cancel.load(Ordering::Relaxed)
    }

    /// The cancel flag itself, for code that takes an `&AtomicBool`.
    pub fn cancel_flag(&self) -> &AtomicBool {
        &self.cancel
    }

    /// Counts `n` more units done.
    pub fn add(&self, n: u64) {
        self.done.fetch_add(n, Ordering::Relaxed);
    }

    /// Sets the units done.
    pub fn set(&self, done: u64) {
        self.done.store(done, Ordering::Relaxed);
    }

    /// Sets the units of the whole job (when only the worker knows them).
    pub fn set_total(&self, total: u64) {
        self.total.store(total, Ordering::Relaxed);
    }

    /// The shared counter of units done (for code that takes an `&AtomicU64`).
    pub fn done_counter(&self) -> &AtomicU64 {
        &self.done
    }
}

/// The share of a frame a sliced job takes in each poll where it runs
/// on the UI thread (s): a 60 Hz frame is 16.7 ms.
pub const SLICE_S: f64 = 0.008;

/// Work done in slices: each call works until the deadline (`None`: to
/// the end) and returns the result once done.
pub type SliceWork<T> = Box<dyn FnMut(&Progress, Option<web_time::Instant>) -> Option<T> + Send>;

/// A result of type `T` computed on a background thread (or, for a sliced
/// job in the browser, in slices within the polls).
pub struct Job<T> {
    name: &'static str,
    progress: Progress,
    rx: Receiver<T>,
    /// The work left of a job run in the polls, and where its result goes.
    inline: Option<std::sync::Mutex<(SliceWork<T>, std::sync::mpsc::Sender<T>)>>,
}

impl<T> std::fmt::Debug for Job<T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Job")
            .field("name", &self.name)
            .field("progress", &self.progress)
            .field("in_slices", &self.inline.is_some())
            .finish()
    }
}

impl<T: Send + 'static> Job<T> {
    /// Runs `work` on a thread named `tirecontact-{name}`; `total` is the
    /// job's size in the units its progress counts (0: set by the worker).
    pub fn spawn(
        name: &'static str,
        total: u64,
        work: impl FnOnce(&Progress) -> T + Send + 'static,
    ) -> Result<Self, String> {
        let progress = Progress::default();
        progress.set_total(total);
        let (tx, rx) = channel();
        let p = progress.clone();
        // a page in the browser has no threads: the work runs now, and the
        // first poll picks up its result
        #[cfg(target_arch = "wasm32")]
        {
            let _ = tx.send(work(&p));
            return Ok(Job {
                name,
                progress,
                rx,
                inline: None,
            });
        }
        #[cfg(not(target_arch = "wasm32"))]
        std::thread::Builder::new()
            .name(format!("tirecontact-{name}"))
            .spawn(move || {
                // the receiver is gone when a newer job replaced this one or
                // the app closed: nothing to report to
                let _ = tx.send(work(&p));
            })
            .map_err(|e| format!("cannot start the {name} thread: {e}"))?;
        #[cfg(not(target_arch = "wasm32"))]
        Ok(Job {
            name,
            progress,
            rx,
            inline: None,
        })
    }

    /// Runs `work` to its end on a thread, or, in the browser, in slices
    /// of [`SLICE_S`] inside [`Job::poll`] ([`Job::in_slices`]).
    pub fn spawn_sliced(
        name: &'static str,
        total: u64,
        work: impl FnMut(&Progress, Option<web_time::Instant>) -> Option<T> + Send + 'static,
    ) -> Result<Self, String> {
        #[cfg(target_arch = "wasm32")]
        {
            return Ok(Self::in_slices(name, total, work));
        }
        #[cfg(not(target_arch = "wasm32"))]
        {
            let mut work = work;
            Self::spawn(name, total, move |p| {
                loop {
                    if let Some(t) = work(p, None) {
                        break t;
                    }
                }
            })
        }
    }

    /// The job of `work` run on the caller's thread, a slice at each
    /// [`Job::poll`] (what [`Job::spawn_sliced`] makes in the browser).
    pub fn in_slices(
        name: &'static str,
        total: u64,
        work: impl FnMut(&Progress, Option<web_time::Instant>) -> Option<T> + Send + 'static,
    ) -> Self {
        let progress = Progress::default();
        progress.set_total(total);
        let (tx, rx) = channel();
        Job {
            name,
            progress,
            rx,
            inline: Some(std::sync::Mutex::new((Box::new(work), tx))),
        }
    }
}

impl<T> Job<T> {
    /// What the worker sees of the job (its progress and cancel flag).
    pub fn handle(&self) -> Progress {
        self.progress.clone()
    }

    /// Units done so far.
    pub fn done(&self) -> u64 {
        self.progress.done.load(Ordering::Relaxed)
    }

    /// Units of the whole job (0 while unknown).
    pub fn total(&self) -> u64 {
        self.progress.total.load(Ordering::Relaxed)
    }

    /// Fraction done (0..=1; 0 while the total is unknown).
    pub fn fraction(&self) -> f64 {
        match self.total() {
            0 => 0.0,
            t => (self.done() as f64 / t as f64).min(1.0),
        }
    }

    /// Asks the worker to stop (it looks at the flag between units of work).
    pub fn cancel(&self) {
        self.progress.cancel.store(true, Ordering::Relaxed);
    }

    pub fn cancel_requested(&self) -> bool {
        self.progress.cancelled()
    }

    /// The result once the worker finished, `None` while it runs (never
    /// blocks); an error if the worker died without a result.
    pub fn poll(&self) -> Option<Result<T, String>> {
        let deadline = web_time::Instant::now() + std::time::Duration::from_secs_f64(SLICE_S);
        self.run_slice(Some(deadline));
        match self.rx.try_recv() {
            Ok(r) => Some(Ok(r)),
            Err(TryRecvError::Empty) => None,
            Err(TryRecvError::Disconnected) => Some(Err(self.lost())),
        }
    }

    /// Blocks until the worker finished (tests, shutdown).
    pub fn wait(&self) -> Result<T, String> {
        self.run_slice(None);
        self.rx.recv().map_err(|_| self.lost())
    }

    /// A slice of a job run in the polls, until `deadline`; its result, if
    /// it ends, is sent to the receiver. Nothing for a threaded job.
    fn run_slice(&self, deadline: Option<web_time::Instant>) {
        let Some(inline) = &self.inline else {
            return;
        };
        let mut guard = inline.lock().unwrap_or_else(|e| e.into_inner());
        let (work, tx) = &mut *guard;
        if let Some(t) = work(&self.progress, deadline) {
            let _ = tx.send(t);
        }
    }

    fn lost(&self) -> String {
        format!("the {} thread stopped without a result", self.name)
    }
}

impl<T> Drop for Job<T> {
    /// A replaced or dropped job stops at its next look at the flag.
    fn drop(&mut self) {
        self.cancel();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    fn poll_until<T>(job: &Job<T>) -> Result<T, String> {
        for _ in 0..2000 {
            if let Some(r) = job.poll() {
                return r;
            }
            std::thread::sleep(Duration::from_millis(2));
        }
        panic!("the job did not finish");
    }

    #[test]
    fn a_job_reports_progress_and_its_result_once() {
        let (go_tx, go_rx) = channel::<()>();
        let job = Job::spawn("test", 4, move |p| {
            p.add(1);
            go_rx.recv().unwrap();
            p.add(3);
            42
        })
        .unwrap();
        assert!(job.poll().is_none(), "running: no result yet");
        go_tx.send(()).unwrap();
        assert_eq!(poll_until(&job), Ok(42));
        assert_eq!((job.done(), job.total()), (4, 4));
        assert_eq!(job.fraction(), 1.0);
        // picked up once: the channel is then closed
        assert!(job.poll().unwrap().is_err());
    }

    #[test]
    fn cancel_and_drop_reach_the_worker() {
        let job = Job::spawn("test", 0, |p| {
            while !p.cancelled() {
                std::thread::sleep(Duration::from_millis(1));
            }
            "stopped"
        })
        .unwrap();
        assert_eq!(job.fraction(), 0.0, "total unknown");
        job.cancel();
        assert!(job.cancel_requested());
        assert_eq!(poll_until(&job), Ok("stopped"));

        let (seen_tx, seen_rx) = channel();
        let job = Job::spawn("test", 0, move |p| {
            while !p.cancelled() {
                std::thread::sleep(Duration::from_millis(1));
            }
            seen_tx.send(()).unwrap();
        })
        .unwrap();
        drop(job);
        seen_rx
            .recv_timeout(Duration::from_secs(10))
            .expect("a dropped job is cancelled");
    }

    #[test]
    fn a_worker_that_panics_is_an_error_not_a_hang() {
        let job: Job<u8> = Job::spawn("test", 1, |_| panic!("boom")).unwrap();
        let e = poll_until(&job).unwrap_err();
        assert!(e.contains("test thread stopped"), "{e}");
    }

    /// A job in slices (the browser's) runs a slice per poll until the
    /// deadline, keeps its progress between slices, and gives its result
    /// once; on a thread the same work gives the same result.
    #[test]
    fn a_sliced_job_runs_within_the_polls() {
        let work = || {
            let mut left = 50u32;
            move |p: &Progress, deadline: Option<web_time::Instant>| {
                while left > 0 {
                    if p.cancelled() {
                        return Some(None);
                    }
                    std::thread::sleep(Duration::from_millis(1));
                    left -= 1;
                    p.add(1);
                    // (the slice that does the last unit gives the result,
                    // even past its deadline on a loaded machine)
                    if left > 0 && deadline.is_some_and(|d| web_time::Instant::now() >= d) {
                        return None;
                    }
                }
                Some(Some("done"))
            }
        };
        let job = Job::in_slices("test", 50, work());
        assert_eq!(job.done(), 0, "nothing runs before the first poll");
        let mut polls = 0;
        let r = loop {
            polls += 1;
            let t = web_time::Instant::now();
            if let Some(r) = job.poll() {
                break r;
            }
            // a poll returns after its slice, not after the whole job
            assert!(
                t.elapsed().as_secs_f64() < 0.2,
                "a poll ran {:?}",
                t.elapsed()
            );
            assert!(job.done() > 0 && job.done() < 50);
        };
        assert_eq!(r, Ok(Some("done")));
        assert!(polls >= 3, "{polls} polls: the job was not sliced");
        assert_eq!(job.fraction(), 1.0);
        let threaded = Job::spawn_sliced("test", 50, work()).unwrap();
        assert_eq!(threaded.wait(), Ok(Some("done")));
        // cancelled between slices
        let job = Job::in_slices("test", 50, work());
        assert!(job.poll().is_none());
        job.cancel();
        assert_eq!(poll_until(&job), Ok(None));
    }
}
