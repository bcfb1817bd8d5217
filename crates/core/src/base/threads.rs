//! A small persistent pool of worker threads for the per-step kernels of
//! large scenes ([`Threads`]).
//!
//! Work is split by a **fixed partition**: `items` (rows of points, or
//! states) are cut into one contiguous range per thread, a function of
//! `items`, the thread count and an alignment only
//! ([`Threads::part_range`]). Each kernel computes every output element of
//! its range by the same operations in the same order as over the whole
//! range, and no value is summed across ranges, so results are
//! bit-identical for any number of threads, and whichever thread computes
//! a range.
//!
//! A call publishes its job in a counter that the workers watch; the
//! caller and the workers then claim the ranges one at a time from it
//! (the caller takes every range no worker has claimed: a worker that is
//! asleep or descheduled delays nothing but the ranges it already took).
//! Idle workers spin on the counter for [`SPIN_S`] (the next call of a
//! step comes within microseconds), yielding their core to other work
//! after the first [`SPIN_HOT_S`], then sleep on a condition variable.
//! Calls allocate nothing.

use std::cell::UnsafeCell;
use std::ops::Range;
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::sync::{Arc, Condvar, Mutex};
use std::thread::JoinHandle;
use std::time::Duration;
use web_time::Instant;

/// How long an idle worker watches for the next call before it sleeps
/// (s): longer than the serial work between two split kernels of a step
/// (tens of µs at `P = 1000`), so that a running simulation's workers are
/// not woken through the scheduler at every call.
pub const SPIN_S: f64 = 200e-6;

/// How long of [`SPIN_S`] an idle worker spins without yielding its core
/// (s).
pub const SPIN_HOT_S: f64 = 20e-6;

/// Work (multiply-adds per call) from which a kernel is split over the
/// threads. A call itself costs 0.02-0.2 µs while the workers watch (9 µs
/// to wake sleeping ones), but the second core must also fetch the states
/// the first just wrote: on scaling scenes with 2 threads, splitting from
/// 30 000 slowed the steps of `P = 50-60`, `K = 400` off the road (to
/// 0.75-0.85x), while from 60 000 no size lost (`docs/performance.md`,
/// "Threads").
pub const PARALLEL_FROM: usize = 60_000;

/// A job: part `k` of a call.
type Job = dyn Fn(usize) + Sync;

/// Bits of [`Shared::claim`] that count the claimed parts of a call (the
/// call's number is in the bits above).
const PART_BITS: u32 = 16;
const PART_MASK: u64 = (1 << PART_BITS) - 1;

/// What the caller and the workers share.
struct Shared {
    /// The job of the current call: written by the caller before it
    /// publishes the call in `claim` and cleared after every part is
    /// done; read only by a thread that claimed a part of that call
    /// (before it counts the part done).
    job: UnsafeCell<Option<&'static Job>>,
    /// The current call's number (high bits) and its parts claimed so far
    /// (low [`PART_BITS`]).
    claim: AtomicU64,
    /// Parts of the current call done.
    done: AtomicUsize,
    /// Parts of a call: the threads started (set before the first call).
    parts: AtomicUsize,
    /// A call is under way (a second, concurrent or nested, runs serially).
    busy: AtomicBool,
    /// A part of the current call panicked.
    panicked: AtomicBool,
    /// The pool is being dropped.
    stop: AtomicBool,
    /// Workers asleep on `wake`.
    sleepers: AtomicUsize,
    lock: Mutex<()>,
    wake: Condvar,
}

// SAFETY: `job` is written by the one caller holding `busy`, before it
// publishes a call (release on `claim`) and after all its parts are done
// (acquire on `done`); in between it is read only by threads that claimed
// a part of that call (acquire on `claim`) and before they count it done
// (release on `done`).
unsafe impl Sync for Shared {}

impl Shared {
    /// Claims and runs parts of the call numbered `call` (of `parts`)
    /// until none is left; returns the last value of `claim` seen.
    fn take_parts(&self, call: u64, parts: usize) -> u64 {
        let mut c = self.claim.load(Ordering::Acquire);
        loop {
            if c >> PART_BITS != call || (c & PART_MASK) as usize >= parts {
                return c;
            }
            match self
                .claim
                .compare_exchange_weak(c, c + 1, Ordering::AcqRel, Ordering::Acquire)
            {
                Ok(_) => {
                    let k = (c & PART_MASK) as usize;
                    // SAFETY: part `k` of the current call is ours: the
                    // caller set `job` before publishing the call and
                    // keeps it until this part is counted done below.
                    if let Some(job) = unsafe { *self.job.get() } {
                        let ran = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| job(k)));
                        if ran.is_err() {
                            self.panicked.store(true, Ordering::Relaxed);
                        }
                    }
                    self.done.fetch_add(1, Ordering::Release);
                    c = self.claim.load(Ordering::Acquire);
                }
                Err(now) => c = now,
            }
        }
    }
}

/// The worker threads and what they share.
struct Pool {
    shared: Arc<Shared>,
    workers: Vec<JoinHandle<()>>,
}

/// The threads of a [`Simulation`](crate::Simulation)'s kernels: the
/// caller's and `count - 1` persistent workers (none for one thread: the
/// kernels then run as they would without a pool, at no cost). See the
/// module's documentation for the partition and why it is deterministic.
pub struct Threads {
    count: usize,
    /// Work from which a kernel is split ([`Threads::worth`]).
    parallel_from: usize,
    /// Calls split over the threads so far.
    split_calls: AtomicU64,
    pool: Option<Pool>,
}

impl std::fmt::Debug for Threads {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Threads")
            .field("count", &self.count)
            .field("parallel_from", &self.parallel_from)
            .finish()
    }
}

impl Default for Threads {
    fn default() -> Self {
        Threads::single()
    }
}

impl Threads {
    /// The caller's thread alone.
    pub const fn single() -> Self {
        Threads {
            count: 1,
            parallel_from: PARALLEL_FROM,
            split_calls: AtomicU64::new(0),
            pool: None,
        }
    }

    /// `count` threads (the caller's and `count - 1` workers; 0 counts as
    /// 1, at most 2¹⁶). A worker the system refuses to start is done
    /// without: results do not depend on the count.
    pub fn new(count: usize) -> Self {
        let count = count.min(1 << PART_BITS);
        if count <= 1 {
            return Threads::single();
        }
        let shared = Arc::new(Shared {
            job: UnsafeCell::new(None),
            claim: AtomicU64::new(0),
            done: AtomicUsize::new(0),
            parts: AtomicUsize::new(count),
            busy: AtomicBool::new(false),
            panicked: AtomicBool::new(false),
            stop: AtomicBool::new(false),
            sleepers: AtomicUsize::new(0),
            lock: Mutex::new(()),
            wake: Condvar::new(),
        });
        let mut workers = Vec::with_capacity(count - 1);
        for k in 1..count {
            let sh = Arc::clone(&shared);
            let spawned = std::thread::Builder::new()
                .name(format!("tirecontact-{k}"))
                .spawn(move || worker(&sh));
            match spawned {
                Ok(h) => workers.push(h),
                Err(_) => break,
            }
        }
        if workers.is_empty() {
            return Threads::single();
        }
        // (published to the workers with the first call)
        shared.parts.store(workers.len() + 1, Ordering::Relaxed);
        Threads {
            count: workers.len() + 1,
            pool: Some(Pool { shared, workers }),
            ..Threads::single()
        }
    }

    /// The same threads, splitting the kernels of at least `work`
    /// multiply-adds (default [`PARALLEL_FROM`]; 0 or 1: every kernel).
    pub fn with_parallel_from(mut self, work: usize) -> Self {
        self.parallel_from = work;
        self
    }

    /// Kernel calls split over the threads so far ([`Threads::run`],
    /// [`Threads::split`]; 0 on one thread).
    pub fn split_calls(&self) -> u64 {
        self.split_calls.load(Ordering::Relaxed)
    }

    /// Threads taking part in a call (1: the caller's alone).
    pub fn count(&self) -> usize {
        self.count
    }

    /// Whether a kernel of `work` multiply-adds is split over the threads:
    /// more than one thread and at least [`PARALLEL_FROM`] (or the work
    /// set by [`Threads::with_parallel_from`]).
    #[inline]
    pub fn worth(&self, work: usize) -> bool {
        self.count > 1 && work >= self.parallel_from
    }

    /// Part `k` of the fixed partition of `0..items` into `parts`
    /// contiguous ranges: `[k c, (k + 1) c)` clipped to `items`, with
    /// `c = ⌈items / parts⌉` rounded up to a multiple of `align` (later
    /// parts may be empty).
    pub fn part_range(items: usize, parts: usize, align: usize, k: usize) -> Range<usize> {
        let align = align.max(1);
        let c = items.div_ceil(parts.max(1)).div_ceil(align) * align;
        (k * c).min(items)..((k + 1) * c).min(items)
    }

    /// Runs `f(k)` once for every part `k` in `0..count`, each on the
    /// calling thread or a worker (whichever claims it first), and
    /// returns when all are done. A call made while another is under way
    /// (from another thread, or from inside a part) runs its parts in
    /// order on its own thread. A panic of a part is raised again here
    /// once every part has finished.
    pub fn run<'a>(&self, f: &'a (dyn Fn(usize) + Sync + 'a)) {
        let Some(pool) = &self.pool else {
            f(0);
            return;
        };
        self.split_calls.fetch_add(1, Ordering::Relaxed);
        let sh = &*pool.shared;
        if sh.busy.swap(true, Ordering::Acquire) {
            for k in 0..self.count {
                f(k);
            }
            return;
        }
        // SAFETY: the reference is read only by the threads that claim a
        // part of this call, before they count it done; this function
        // returns only when every part is done, so it never outlives `f`.
        let job: &'static Job =
            unsafe { std::mem::transmute::<&'a (dyn Fn(usize) + Sync + 'a), &'static Job>(f) };
        // SAFETY: every part of the last call is done and the new call is
        // not yet published: no thread reads `job`; `busy` excludes other
        // callers.
        unsafe { *sh.job.get() = Some(job) };
        sh.done.store(0, Ordering::Relaxed);
        let call = (sh.claim.load(Ordering::Relaxed) >> PART_BITS) + 1;
        sh.claim.store(call << PART_BITS, Ordering::SeqCst);
        if sh.sleepers.load(Ordering::SeqCst) > 0 {
            let _g = sh.lock.lock().unwrap_or_else(|e| e.into_inner());
            sh.wake.notify_all();
        }
        sh.take_parts(call, self.count);
        // the parts claimed by workers
        let mut spins = 0u32;
        while sh.done.load(Ordering::Acquire) < self.count {
            // (a worker may be descheduled: let it run)
            if spins < 1 << 12 {
                spins += 1;
                std::hint::spin_loop();
            } else {
                std::thread::yield_now();
            }
        }
        // SAFETY: every part is done: no thread reads `job`.
        unsafe { *sh.job.get() = None };
        sh.busy.store(false, Ordering::Release);
        if sh.panicked.swap(false, Ordering::Relaxed) {
            panic!("a part of a threaded kernel panicked");
        }
    }

    /// Splits `0..items` by [`Threads::part_range`] (`align`) over the
    /// threads and runs `f(range, chunks)` for each non-empty range, where
    /// `chunks[m]` is the range's part of `outs[m].0`, which holds
    /// `outs[m].1` values per item (item `i` at `[i w, (i + 1) w)`).
    ///
    /// # Panics
    /// If an output holds fewer than `items` items.
    pub fn split<const N: usize>(
        &self,
        items: usize,
        align: usize,
        outs: [(&mut [f64], usize); N],
        f: impl Fn(Range<usize>, [&mut [f64]; N]) + Sync,
    ) {
        for (o, w) in &outs {
            assert!(o.len() >= items * w, "output shorter than its items");
        }
        let raw: [(Raw, usize); N] = outs.map(|(o, w)| (Raw(o.as_mut_ptr()), w));
        let parts = self.count;
        self.run(&|k| {
            let r = Self::part_range(items, parts, align, k);
            if r.is_empty() {
                return;
            }
            // SAFETY: the ranges of different parts are disjoint, each part
            // runs once per call, the outputs hold `items` items (asserted)
            // and stay mutably borrowed until `run` returns.
            let chunks = raw.map(|(p, w)| unsafe {
                std::slice::from_raw_parts_mut(p.get().add(r.start * w), r.len() * w)
            });
            f(r, chunks)
        });
    }
}

/// An output's start, shared with the parts (each writes its own range).
#[derive(Clone, Copy)]
struct Raw(*mut f64);
// SAFETY: used only by `Threads::split`, whose parts write disjoint ranges.
unsafe impl Send for Raw {}
unsafe impl Sync for Raw {}

impl Raw {
    /// The pointer (a method: closures then capture the whole `Raw`).
    fn get(self) -> *mut f64 {
        self.0
    }
}

impl Drop for Pool {
    /// Stops the workers and waits for them.
    fn drop(&mut self) {
        let sh = &*self.shared;
        sh.stop.store(true, Ordering::SeqCst);
        // a new call with every part claimed: the workers look, and stop
        let call = (sh.claim.load(Ordering::Relaxed) >> PART_BITS) + 1;
        sh.claim
            .store(call << PART_BITS | PART_MASK, Ordering::SeqCst);
        {
            let _g = sh.lock.lock().unwrap_or_else(|e| e.into_inner());
            sh.wake.notify_all();
        }
        for h in self.workers.drain(..) {
            let _ = h.join();
        }
    }
}

/// A worker's loop: waits for a call (spinning, then asleep), takes
/// parts of it while any is left.
fn worker(sh: &Shared) {
    let mut seen = 0u64;
    loop {
        let c = wait_for_call(sh, seen);
        if sh.stop.load(Ordering::Acquire) {
            return;
        }
        seen = c >> PART_BITS;
        sh.take_parts(seen, sh.parts.load(Ordering::Relaxed));
    }
}

/// The value of [`Shared::claim`] once it holds a call after the call
/// numbered `seen` (or the pool stops): spins for [`SPIN_HOT_S`], yields
/// the core between looks until [`SPIN_S`], then sleeps until a caller
/// wakes the sleepers.
fn wait_for_call(sh: &Shared, seen: u64) -> u64 {
    let start = Instant::now();
    let (hot, spin) = (
        Duration::from_secs_f64(SPIN_HOT_S),
        Duration::from_secs_f64(SPIN_S),
    );
    let new = |c: u64| c >> PART_BITS != seen;
    loop {
        for _ in 0..64 {
            let c = sh.claim.load(Ordering::Acquire);
            if new(c) {
                return c;
            }
            std::hint::spin_loop();
        }
        let waited = start.elapsed();
        if waited >= spin {
            break;
        }
        if waited >= hot {
            std::thread::yield_now();
        }
    }
    let mut g = sh.lock.lock().unwrap_or_else(|e| e.into_inner());
    // (SeqCst with the caller's store of a call and load of `sleepers`:
    // either it sees this sleeper and notifies under the lock, or the new
    // call is seen here)
    sh.sleepers.fetch_add(1, Ordering::SeqCst);
    while !new(sh.claim.load(Ordering::SeqCst)) {
        g = sh.wake.wait(g).unwrap_or_else(|e| e.into_inner());
    }
    sh.sleepers.fetch_sub(1, Ordering::SeqCst);
    drop(g);
    sh.claim.load(Ordering::Acquire)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_partition_covers_every_item_once_in_order() {
        for items in [0, 1, 5, 16, 17, 100, 1001] {
            for parts in 1..5 {
                for align in [1, 4, 16] {
                    let ranges: Vec<_> = (0..parts)
                        .map(|k| Threads::part_range(items, parts, align, k))
                        .collect();
                    let mut next = 0;
                    for r in &ranges {
                        assert_eq!(r.start, next.min(items), "{items} {parts} {align}");
                        assert!(r.start.is_multiple_of(align) || r.is_empty());
                        next = r.end.max(next);
                    }
                    assert_eq!(next, items, "{items} {parts} {align}");
                }
            }
        }
    }

    #[test]
    fn every_part_runs_once_per_call() {
        for n in 1..4 {
            let threads = Threads::new(n);
            assert_eq!(threads.count(), n);
            let caller = std::thread::current().id();
            let mut by_workers = 0;
            for call in 0..3000 {
                let hits: Vec<AtomicUsize> = (0..n).map(|_| AtomicUsize::new(0)).collect();
                let elsewhere = AtomicUsize::new(0);
                threads.run(&|k| {
                    hits[k].fetch_add(1, Ordering::Relaxed);
                    if std::thread::current().id() != caller {
                        elsewhere.fetch_add(1, Ordering::Relaxed);
                    }
                    // (some work, so that the workers take parts)
                    let mut x = k as f64;
                    for _ in 0..2000 {
                        x = std::hint::black_box(x * 0.5 + 1.0);
                    }
                });
                assert!(
                    hits.iter().all(|h| h.load(Ordering::Relaxed) == 1),
                    "{n} threads, call {call}"
                );
                by_workers += elsewhere.load(Ordering::Relaxed);
            }
            // one thread has no worker; with more, the workers took parts
            assert_eq!(by_workers == 0, n == 1, "{n} threads: {by_workers}");
        }
    }

    #[test]
    fn split_writes_each_item_of_each_output() {
        let threads = Threads::new(3);
        let (mut a, mut b) = (vec![0.0; 101], vec![0.0; 202]);
        threads.split(101, 4, [(&mut a, 1), (&mut b, 2)], |r, [a, b]| {
            assert_eq!((a.len(), b.len()), (r.len(), 2 * r.len()));
            for (k, i) in r.enumerate() {
                a[k] = i as f64;
                b[2 * k] = -(i as f64);
                b[2 * k + 1] = i as f64 + 0.5;
            }
        });
        for i in 0..101 {
            assert_eq!(
                (a[i], b[2 * i], b[2 * i + 1]),
                (i as f64, -(i as f64), i as f64 + 0.5)
            );
        }
    }

    #[test]
    fn a_nested_call_runs_its_parts_in_place() {
        let threads = Threads::new(2);
        let inner = AtomicUsize::new(0);
        threads.run(&|_| {
            threads.run(&|_| {
                inner.fetch_add(1, Ordering::Relaxed);
            });
        });
        // two outer parts, each running both inner parts (serially when the
        // pool is busy)
        assert_eq!(inner.load(Ordering::Relaxed), 4);
    }

    #[test]
    fn a_panic_of_a_part_reaches_the_caller_and_the_pool_stays_usable() {
        let threads = Threads::new(2);
        let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            threads.run(&|k| assert_eq!(k, 0, "part 1 panics"));
        }));
        assert!(r.is_err());
        let hits = AtomicUsize::new(0);
        threads.run(&|_| {
            hits.fetch_add(1, Ordering::Relaxed);
        });
        assert_eq!(hits.load(Ordering::Relaxed), 2);
    }

    #[test]
    fn workers_asleep_wake_for_a_call() {
        let threads = Threads::new(2);
        std::thread::sleep(Duration::from_secs_f64(20.0 * SPIN_S));
        let hits = AtomicUsize::new(0);
        threads.run(&|_| {
            hits.fetch_add(1, Ordering::Relaxed);
        });
        assert_eq!(hits.load(Ordering::Relaxed), 2);
    }
}
