//! The one engine that sweeps and studies run their scenes on: scenes
//! numbered `0..n`, taken in order by the next free thread, each prepared
//! (a ring's modes from the shared cache), run and summarised
//! ([`super::run_summary_timed`]). Every run is independent and
//! deterministic, so results do not depend on the thread count.

use super::{RunSummary, RunTiming, SummaryError, run_summary_timed};
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use tirecontact_io::Scene;
use tirecontact_io::identify::{ModeCache, PreparedModel};
use web_time::Instant;

/// What the threads' time went to: the runs' parts summed, and the threads'
/// whole time (s), the difference being the callers' own work per run
/// (writing a table row).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PoolTiming {
    pub runs: RunTiming,
    pub busy_s: f64,
}

/// Runs scenes `0..n` on `threads` threads (at least 1, at most `n`).
/// `scene(k)` makes scene `k` (an error is that run's result);
/// `on_steps(d)` is told of `d` more steps done; `on_done(k, result)` is
/// called from the worker as run `k` ends. `cancel` stops every run (those
/// not started are not reported).
pub fn run_each(
    n: usize,
    threads: usize,
    cache: &ModeCache,
    cancel: &AtomicBool,
    scene: &(dyn Fn(usize) -> Result<Scene, SummaryError> + Sync),
    on_steps: &(dyn Fn(u64) + Sync),
    on_done: &(dyn Fn(usize, Result<RunSummary, SummaryError>) + Sync),
) -> PoolTiming {
    let next = AtomicUsize::new(0);
    let total = Mutex::new(PoolTiming::default());
    let workers = threads.clamp(1, n.max(1));
    let work = || {
        let mut mine = RunTiming::default();
        let busy = Instant::now();
        loop {
            let k = next.fetch_add(1, Ordering::Relaxed);
            if k >= n || cancel.load(Ordering::Relaxed) {
                break;
            }
            let t0 = Instant::now();
            let model = scene(k).and_then(|s| Ok(PreparedModel::new(&s, cache)?));
            mine.setup_s += t0.elapsed().as_secs_f64();
            let r = model.and_then(|m| run_summary_timed(&m, on_steps, cancel, &mut mine));
            on_done(k, r);
        }
        let mut t = total.lock().unwrap_or_else(|e| e.into_inner());
        t.runs.add(&mine);
        t.busy_s += busy.elapsed().as_secs_f64();
    };
    // one worker runs on the caller's thread (a page in the browser has
    // no other)
    if workers == 1 {
        work();
    } else {
        std::thread::scope(|scope| {
            for _ in 0..workers {
                scope.spawn(work);
            }
        });
    }
    total.into_inner().unwrap_or_else(|e| e.into_inner())
}
