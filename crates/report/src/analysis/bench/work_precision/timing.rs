//! Running and timing the stable solver for the work-precision study:
//! wall time of the steps, the process's CPU time.

use crate::analysis::bench::BenchError;
use crate::analysis::bench::baselines::BaselineRun;
use tirecontact_core::solver::drive::Watch;
use tirecontact_core::solver::simulation::{Simulation, SolverOptions};
use tirecontact_io::identify::{ModeCache, PreparedModel};
use tirecontact_io::scene::{ContactScheme, Scene};
use web_time::Instant;

/// A run of the stable solver recorded every step, its wall time (s, the
/// steps only) and its located events.
pub type StableRun = (BaselineRun, f64, u64);

/// Runs the stable solver and records every step.
pub fn run_stable(
    scene: &Scene,
    scheme: ContactScheme,
    dt: f64,
    duration: f64,
    options: SolverOptions,
    cache: &ModeCache,
) -> Result<StableRun, BenchError> {
    let mut s = scene.clone();
    s.dt_s = dt;
    s.duration_s = duration;
    s.contact_scheme = scheme;
    let n = s.num_steps() as usize;
    let model = PreparedModel::new(&s, cache)?;
    let mut sim = model.simulation(options)?;
    let mut run = BaselineRun {
        t_s: Vec::with_capacity(n),
        u_m: Vec::with_capacity(n),
        q_n: Vec::with_capacity(n),
        overflow_t_s: None,
    };
    let start = Instant::now();
    tirecontact_core::solver::drive::run_to_end(&mut sim, &mut run, Watch::none())?;
    Ok((run, start.elapsed().as_secs_f64(), sim.stats().events))
}

/// Times a bare run (no recording) of the stable solver, in seconds.
pub fn time_stable(
    model: &PreparedModel,
    options: SolverOptions,
) -> Result<(f64, Simulation), BenchError> {
    let mut sim = model.simulation(options)?;
    let start = Instant::now();
    tirecontact_core::solver::drive::run_to_end(&mut sim, &mut (), Watch::none())?;
    Ok((start.elapsed().as_secs_f64(), sim))
}

/// A timing and the last of its runs.
pub type TimedRun = (Timing, Simulation);

/// Wall times of repeated identical runs (s).
#[derive(Debug, Clone, PartialEq)]
pub struct Timing {
    /// Every run's wall time, fastest first.
    pub runs_s: Vec<f64>,
}

impl Timing {
    fn of(mut runs_s: Vec<f64>) -> Self {
        runs_s.sort_by(f64::total_cmp);
        Timing { runs_s }
    }

    /// The median run (the upper one of an even count).
    pub fn median_s(&self) -> f64 {
        self.runs_s[self.runs_s.len() / 2]
    }
    pub fn min_s(&self) -> f64 {
        self.runs_s[0]
    }
    pub fn max_s(&self) -> f64 {
        self.runs_s[self.runs_s.len() - 1]
    }
}

/// [`time_stable`] of the options `a` and `b` (`b` may equal `a`), each
/// `repeats` times (at least once), alternating `a, b, a, b, …` so that a
/// drift of the machine's speed falls on both alike. One short run on a
/// shared machine can be off by 25 %; the median of several is steadier.
/// Returns both timings and the last run of each.
pub fn time_pair(
    scene: &PreparedModel,
    a: SolverOptions,
    b: SolverOptions,
    repeats: usize,
) -> Result<(TimedRun, TimedRun), BenchError> {
    let (mut ta, mut tb) = (Vec::new(), Vec::new());
    let (mut last_a, mut last_b) = (None, None);
    for _ in 0..repeats.max(1) {
        let (t, sim) = time_stable(scene, a)?;
        ta.push(t);
        last_a = Some(sim);
        let (t, sim) = time_stable(scene, b)?;
        tb.push(t);
        last_b = Some(sim);
    }
    match (last_a, last_b) {
        (Some(sa), Some(sb)) => Ok(((Timing::of(ta), sa), (Timing::of(tb), sb))),
        _ => Err(BenchError::NoRun),
    }
}

/// [`time_stable`] `repeats` times (at least once): the timing and the last run.
pub fn time_repeated(
    scene: &PreparedModel,
    options: SolverOptions,
    repeats: usize,
) -> Result<TimedRun, BenchError> {
    let (t, mut sim) = time_stable(scene, options)?;
    let mut runs_s = vec![t];
    for _ in 1..repeats {
        let (t, s) = time_stable(scene, options)?;
        runs_s.push(t);
        sim = s;
    }
    Ok((Timing::of(runs_s), sim))
}

/// The process's CPU time (s, all its threads: a helper thread of a
/// linear-algebra library counts too), where the system tells it.
pub fn process_cpu_s() -> Option<f64> {
    #[cfg(unix)]
    {
        let mut ts = libc::timespec {
            tv_sec: 0,
            tv_nsec: 0,
        };
        // SAFETY: `ts` is a valid timespec for the call to write
        let rc = unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut ts) };
        (rc == 0).then_some(ts.tv_sec as f64 + 1e-9 * ts.tv_nsec as f64)
    }
    #[cfg(not(unix))]
    None
}

/// The CPU time (s) since `start`, a reading of [`process_cpu_s`].
pub(super) fn cpu_since(start: Option<f64>) -> Option<f64> {
    Some(process_cpu_s()? - start?)
}
