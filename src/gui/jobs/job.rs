//! One shape for every piece of work the visualiser runs off its UI thread
//! (identification, CSV and frame exports, sweeps, spectra, fidelity): a
//! named thread, a progress counter (done of total), a cancel flag, and the
//! result, picked up once by a poll that never blocks. A job dropped while
//! running (replaced by a newer one, or the app closing) is asked to stop.

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

/// A result of type `T` computed on a background thread.
#[derive(Debug)]
pub struct Job<T> {
    name: &'static str,
    progress: Progress,
    rx: Receiver<T>,
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
            return Ok(Job { name, progress, rx });
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
        Ok(Job { name, progress, rx })
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
        match self.rx.try_recv() {
            Ok(r) => Some(Ok(r)),
            Err(TryRecvError::Empty) => None,
            Err(TryRecvError::Disconnected) => Some(Err(self.lost())),
        }
    }

    /// Blocks until the worker finished (tests, shutdown).
    pub fn wait(&self) -> Result<T, String> {
        self.rx.recv().map_err(|_| self.lost())
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
}
