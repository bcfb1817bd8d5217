//! A parameter sweep run from the GUI on a background thread (no egui here):
//! the request is checked at once, the runs go to `crate::studies::sweep::run_sweep`
//! on every core, and the frame loop polls progress and the outcome; a
//! cancel flag stops the runs.

use crate::Scene;
use crate::gui::jobs::Job;
use crate::gui::model::sweep_request::{SweepEnd, SweepRequest, SweepResult};
use crate::identify::ModeCache;
use crate::studies::sweep::report::Columns;
use crate::studies::sweep::{self, SweepError, SweepPoint};
use std::sync::Arc;

/// A sweep running on a background thread.
#[derive(Debug)]
pub struct SweepJob {
    pub request: SweepRequest,
    pub threads: usize,
    pub runs: usize,
    job: Job<Result<Vec<SweepPoint>, SweepError>>,
    started: web_time::Instant,
    base: Box<Scene>,
    columns: Columns,
    /// The last finished sweep's results, kept if this one is cancelled or
    /// fails.
    previous: Option<Box<SweepResult>>,
}

/// Worker threads for a sweep: every core.
pub fn default_threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

impl SweepJob {
    /// Checks `request` against `base` and starts it on a background thread
    /// (which runs `threads` workers; in the browser, one run after the
    /// other in slices within the frames, [`SweepJob::start_in_slices`]).
    /// Errors name the field, value and what was expected.
    /// A ring tyre's modes come from (and are kept in) `cache`.
    pub fn start(
        base: &Scene,
        request: SweepRequest,
        threads: usize,
        cache: Arc<ModeCache>,
    ) -> Result<Self, String> {
        #[cfg(target_arch = "wasm32")]
        {
            let _ = threads;
            return Self::start_in_slices(base, request, cache);
        }
        #[cfg(not(target_arch = "wasm32"))]
        {
            let sw = request.to_sweep(base, threads).map_err(|e| e.to_string())?;
            let scene = base.clone();
            let runs = sw.values.len();
            let threads = sw.threads;
            // the total (solver steps of every run) is known once the scenes are
            let job = Job::spawn("sweep", 0, move |p| {
                let progress = |done: u64, total: u64| {
                    p.set_total(total);
                    p.set(done);
                };
                sweep::run_sweep(&scene, &sw, &cache, &progress, p.cancel_flag())
            })?;
            Ok(Self::new(base, request, threads, runs, job))
        }
    }

    /// The sweep run value after value on the caller's thread, a slice at
    /// each poll ([`Job::in_slices`], [`sweep::SweepRun`]): how a page in
    /// the browser runs it. Its points equal the threaded sweep's.
    pub fn start_in_slices(
        base: &Scene,
        request: SweepRequest,
        cache: Arc<ModeCache>,
    ) -> Result<Self, String> {
        let sw = request.to_sweep(base, 1).map_err(|e| e.to_string())?;
        let mut run = sweep::SweepRun::new(base, &sw).map_err(|e| e.to_string())?;
        let (runs, total) = (sw.values.len(), run.total_steps());
        let job = Job::in_slices("sweep", total, move |p, deadline| {
            let r = run.advance(&cache, p.cancel_flag(), deadline);
            p.set(run.done_steps());
            r
        });
        Ok(Self::new(base, request, 1, runs, job))
    }

    fn new(
        base: &Scene,
        request: SweepRequest,
        threads: usize,
        runs: usize,
        job: Job<Result<Vec<SweepPoint>, SweepError>>,
    ) -> Self {
        SweepJob {
            base: Box::new(base.clone()),
            columns: Columns::of(base, &[request.param.as_str()]),
            request,
            threads,
            runs,
            job,
            started: web_time::Instant::now(),
            previous: None,
        }
    }

    /// Fraction of the solver steps done (0..=1).
    pub fn progress(&self) -> f64 {
        self.job.fraction()
    }

    /// Asks the runs to stop; `poll` then reports `Cancelled`.
    pub fn cancel(&self) {
        self.job.cancel();
    }

    pub fn cancel_requested(&self) -> bool {
        self.job.cancel_requested()
    }

    /// The outcome once the thread finished, else `None` (never blocks).
    pub fn poll(&self) -> Option<SweepEnd> {
        self.job.poll().map(|r| match r {
            Ok(r) => self.end(r),
            Err(e) => SweepEnd::Failed(e),
        })
    }

    /// Blocks until the thread finished (tests, shutdown).
    pub fn wait(self) -> SweepEnd {
        match self.job.wait() {
            Ok(r) => self.end(r),
            Err(e) => SweepEnd::Failed(e),
        }
    }

    fn end(&self, r: Result<Vec<SweepPoint>, SweepError>) -> SweepEnd {
        match r {
            Ok(points) => SweepEnd::Done(SweepResult {
                request: self.request.clone(),
                base: self.base.clone(),
                columns: self.columns,
                points,
                wall_s: self.started.elapsed().as_secs_f64(),
                threads: self.threads,
            }),
            Err(SweepError::Cancelled) => SweepEnd::Cancelled,
            Err(e) => SweepEnd::Failed(e.to_string()),
        }
    }
}

/// The sweep panel's state machine: idle, running, or the last outcome.
#[derive(Debug, Default)]
pub enum SweepState {
    #[default]
    Idle,
    Running(SweepJob),
    Finished(SweepResult),
    Cancelled,
    Failed(String),
}

impl SweepState {
    pub fn is_running(&self) -> bool {
        matches!(self, SweepState::Running(_))
    }

    /// Starts a sweep unless one runs; on a refused request the state is
    /// unchanged and the error returned.
    pub fn start(
        &mut self,
        base: &Scene,
        request: SweepRequest,
        threads: usize,
        cache: Arc<ModeCache>,
    ) -> Result<(), String> {
        if self.is_running() {
            return Err("a sweep is already running: cancel it first".into());
        }
        let mut job = SweepJob::start(base, request, threads, cache)?;
        job.previous = match std::mem::take(self) {
            SweepState::Finished(r) => Some(Box::new(r)),
            _ => None,
        };
        *self = SweepState::Running(job);
        Ok(())
    }

    pub fn cancel(&self) {
        if let SweepState::Running(job) = self {
            job.cancel();
        }
    }

    /// How the running job ended, once it has (never blocks).
    pub fn ended(&self) -> Option<SweepEnd> {
        match self {
            SweepState::Running(job) => job.poll(),
            _ => None,
        }
    }

    /// Moves to the outcome `end` of the job ([`SweepState::ended`]). A
    /// sweep cancelled or failed leaves the results of the sweep finished
    /// before it, if any (returned as `true`), not an empty view.
    pub fn end(&mut self, end: SweepEnd) -> (&SweepState, bool) {
        let previous = match std::mem::take(self) {
            SweepState::Running(job) => job.previous,
            _ => None,
        };
        let (state, kept) = match (end, previous) {
            (SweepEnd::Done(r), _) => (SweepState::Finished(r), false),
            (SweepEnd::Cancelled | SweepEnd::Failed(_), Some(r)) => {
                (SweepState::Finished(*r), true)
            }
            (SweepEnd::Cancelled, None) => (SweepState::Cancelled, false),
            (SweepEnd::Failed(e), None) => (SweepState::Failed(e), false),
        };
        *self = state;
        (self, kept)
    }

    /// A new document: a cancelled or failed sweep's note, which speaks of
    /// the scene it ran on, goes (back to idle); finished results stay, as
    /// they name their scene, and a running sweep runs on.
    pub fn new_document(&mut self) {
        if matches!(self, SweepState::Cancelled | SweepState::Failed(_)) {
            *self = SweepState::Idle;
        }
    }

    /// The scene was edited: a cancelled or failed sweep's note, which
    /// speaks of the scene before the edit, goes (back to idle), as for a
    /// new document; finished results stay and say they are of the scene
    /// as it was ([`SweepResult::differs_from`]).
    pub fn scene_edited(&mut self) {
        self.new_document();
    }

    /// The finished result, if any.
    pub fn result(&self) -> Option<&SweepResult> {
        match self {
            SweepState::Finished(r) => Some(r),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::AtomicBool;

    fn scene() -> Scene {
        let mut s = Scene::parse(
            include_str!(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/presets/single_mode.ron"
            )),
            "single_mode",
        )
        .unwrap();
        s.duration_s = 0.08;
        s
    }

    fn req(param: &str, from: f64, to: f64, steps: usize) -> SweepRequest {
        SweepRequest {
            param: param.into(),
            from,
            to,
            steps,
        }
    }

    #[test]
    fn bad_requests_are_refused_before_anything_runs() {
        let s = scene();
        let mut st = SweepState::Idle;
        let e = st
            .start(&s, req("speed", 1.0, 2.0, 3), 2, Arc::new(ModeCache::new()))
            .unwrap_err();
        assert!(e.contains("unknown parameter `speed`"), "{e}");
        let e = st
            .start(
                &s,
                req("speed_mps", 1.0, 2.0, 0),
                2,
                Arc::new(ModeCache::new()),
            )
            .unwrap_err();
        assert!(e.contains("steps = 0"), "{e}");
        let e = st
            .start(
                &s,
                req("dt_s", -1.0, 1e-5, 2),
                2,
                Arc::new(ModeCache::new()),
            )
            .unwrap_err();
        assert!(e.contains("dt_s"), "{e}");
        assert!(matches!(st, SweepState::Idle));
    }

    #[test]
    fn a_sweep_finishes_with_the_library_result() {
        let s = scene();
        let r = req("speed_mps", 10.0, 20.0, 3);
        let mut st = SweepState::Idle;
        st.start(&s, r.clone(), 2, Arc::new(ModeCache::new()))
            .unwrap();
        assert!(
            st.start(&s, r.clone(), 2, Arc::new(ModeCache::new()))
                .is_err(),
            "second start refused"
        );
        let SweepState::Running(job) = std::mem::take(&mut st) else {
            panic!("not running")
        };
        let SweepEnd::Done(res) = job.wait() else {
            panic!("not done")
        };
        let lib = sweep::run_sweep(
            &s,
            &r.to_sweep(&s, 1).unwrap(),
            &ModeCache::new(),
            &|_, _| {},
            &AtomicBool::new(false),
        )
        .unwrap();
        assert_eq!(res.points, lib);
        assert_eq!(res.failed(), 0);
    }

    /// Waits for the running sweep's end and moves to it: whether earlier
    /// results were kept.
    fn finish(st: &mut SweepState) -> bool {
        loop {
            if let Some(end) = st.ended() {
                return st.end(end).1;
            }
            std::thread::sleep(std::time::Duration::from_millis(5));
        }
    }

    /// A sweep cancelled after one finished leaves that one's results (the
    /// view had shown nothing, and the banner said "no results kept"); the
    /// first sweep cancelled leaves none.
    #[test]
    fn a_cancelled_sweep_keeps_the_results_before_it() {
        let s = scene();
        let cache = || Arc::new(ModeCache::new());
        let mut st = SweepState::Idle;
        st.start(&s, req("speed_mps", 10.0, 20.0, 3), 2, cache())
            .unwrap();
        st.cancel();
        assert!(!finish(&mut st));
        assert!(matches!(st, SweepState::Cancelled));
        st.start(&s, req("speed_mps", 10.0, 20.0, 3), 2, cache())
            .unwrap();
        assert!(!finish(&mut st));
        let first = st.result().expect("the first sweep's results").clone();
        st.start(&s, req("speed_mps", 5.0, 30.0, 400), 2, cache())
            .unwrap();
        assert!(st.result().is_none(), "running");
        st.cancel();
        assert!(finish(&mut st), "the results before it are kept");
        let kept = st.result().expect("results after the cancel");
        assert_eq!(kept.points, first.points);
        assert_eq!(kept.request, first.request);
    }

    /// The browser's sweep: run in slices within the polls, each poll
    /// returning after its slice, with the threaded sweep's points.
    #[test]
    fn a_sweep_in_slices_polls_to_the_library_result() {
        // runs of 50 000 steps: far longer than one 8 ms slice on any machine
        let mut s = scene();
        s.duration_s = 0.5;
        let r = req("speed_mps", 10.0, 20.0, 3);
        let job = SweepJob::start_in_slices(&s, r.clone(), Arc::new(ModeCache::new())).unwrap();
        let mut polls = 0;
        let end = loop {
            polls += 1;
            if let Some(end) = job.poll() {
                break end;
            }
            assert!(job.progress() > 0.0 && job.progress() < 1.0);
        };
        let SweepEnd::Done(res) = end else {
            panic!("not done: {end:?}")
        };
        let lib = sweep::run_sweep(
            &s,
            &r.to_sweep(&s, 2).unwrap(),
            &ModeCache::new(),
            &|_, _| {},
            &AtomicBool::new(false),
        )
        .unwrap();
        assert_eq!(res.points, lib);
        assert!(polls > 1, "one poll ran the whole sweep");
        // cancelled between slices
        let job = SweepJob::start_in_slices(&s, r, Arc::new(ModeCache::new())).unwrap();
        job.cancel();
        assert!(matches!(job.poll(), Some(SweepEnd::Cancelled)));
    }

    /// A sweep of a ring tyre in slices identifies the ring a stage at a
    /// time: polls return while it is identified (no step run yet), and
    /// the points are the threaded sweep's.
    #[test]
    fn a_ring_sweep_in_slices_identifies_in_stages() {
        let mut s = Scene::parse(
            include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/presets/paper.ron")),
            "paper",
        )
        .unwrap();
        s.duration_s = s.ramp_s + 0.01;
        let r = req("speed_mps", 10.0, 20.0, 2);
        let (polls_identifying, polls) = sliced_sweep_agrees_with_the_library(&s, &r);
        assert!(
            polls_identifying >= 2,
            "{polls_identifying} of {polls} polls while the ring was identified"
        );
    }

    /// Runs the sweep `r` of `s` in slices to its end, checks that its
    /// points are the library's sweep's, and returns the polls that found
    /// no run done yet (progress 0: identifying or setting up) and all the
    /// polls.
    fn sliced_sweep_agrees_with_the_library(s: &Scene, r: &SweepRequest) -> (usize, usize) {
        let job = SweepJob::start_in_slices(s, r.clone(), Arc::new(ModeCache::new())).unwrap();
        let (mut before_first_run, mut polls) = (0, 0);
        let end = loop {
            polls += 1;
            if let Some(end) = job.poll() {
                break end;
            }
            if job.progress() == 0.0 {
                before_first_run += 1;
            }
        };
        let SweepEnd::Done(res) = end else {
            panic!("not done: {end:?}")
        };
        let lib = sweep::run_sweep(
            s,
            &r.to_sweep(s, 2).unwrap(),
            &ModeCache::new(),
            &|_, _| {},
            &AtomicBool::new(false),
        )
        .unwrap();
        assert_eq!(res.points, lib);
        (before_first_run, polls)
    }

    /// A sweep of a 200-point patch in slices builds each run's solver
    /// tables a block at a time: polls return during the set-up, and the
    /// points are the threaded sweep's.
    #[test]
    fn a_patch_sweep_in_slices_sets_up_in_stages() {
        let text = include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/presets/patch_texture.ron"
        ))
        .replace("along: 16", "along: 20")
        .replace("across: 6", "across: 10")
        .replace("spacing_m: (0.006, 0.02)", "spacing_m: (0.006, 0.005)");
        let mut s = Scene::parse(&text, "patch").unwrap();
        s.duration_s = s.ramp_s + 0.001;
        let r = req("speed_mps", 10.0, 20.0, 2);
        let (polls_setting_up, _) = sliced_sweep_agrees_with_the_library(&s, &r);
        assert!(
            polls_setting_up >= 2,
            "{polls_setting_up} polls during the set-up"
        );
    }

    #[test]
    fn dropping_a_running_job_cancels_its_runs() {
        let mut s = scene();
        s.duration_s = 5.0;
        let job = SweepJob::start(
            &s,
            req("speed_mps", 10.0, 20.0, 8),
            2,
            Arc::new(ModeCache::new()),
        )
        .unwrap();
        let seen = job.job.handle();
        assert!(!seen.cancelled());
        drop(job);
        assert!(seen.cancelled());
    }

    #[test]
    fn cancel_ends_in_cancelled() {
        let mut s = scene();
        s.duration_s = 5.0;
        let mut st = SweepState::Idle;
        st.start(
            &s,
            req("speed_mps", 10.0, 20.0, 8),
            2,
            Arc::new(ModeCache::new()),
        )
        .unwrap();
        st.cancel();
        let SweepState::Running(job) = std::mem::take(&mut st) else {
            panic!("not running")
        };
        assert!(job.cancel_requested());
        assert_eq!(job.wait(), SweepEnd::Cancelled);
    }
}
