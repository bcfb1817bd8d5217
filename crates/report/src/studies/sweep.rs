//! Parameter sweeps: the numeric fields of a scene by path
//! (`speed_mps`, `road.amplitude_m`, `points[2].h_m`, `tyre.modes[0].freq_hz`,
//! `tyre.ring.inflation_pa`, ...; `[*]` sets every index at once), and runs
//! of a scene over a list of values on several threads, each summarised over
//! its steady part (`t >= ramp_s`): max force, force RMS and contact fraction
//! per point, third-octave band levels of the total force.
//!
//! Every run is independent and deterministic, so a sweep point equals the
//! single run of the scene with that value, whatever the thread count.

use crate::analysis::metrics::{ContactMetrics, ContactSummary};
use crate::analysis::spectrum::run::{DEFAULT_BANDS_HZ, SteadyRecorder};
use crate::analysis::spectrum::{BandLevel, SpectrumError, Window};
use tirecontact_core::base::error::{FieldError, IoError};
use tirecontact_core::solver::drive::Watch;
use tirecontact_core::solver::error::{RunError, SolverError};
use tirecontact_core::solver::simulation::{Simulation, SimulationBuild, SolverOptions};
use tirecontact_io::identify::{ModeCache, PreparedModel, PreparedModelRun};
use tirecontact_io::scene::Scene;
use tirecontact_io::scene::SceneError;
use tirecontact_io::scene::fields::{grid_fields, numeric_fields, set_grid_field, wildcard};
pub mod engine;
pub mod report;

use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};

/// Errors of a sweep: its request (parameter, values), or its scenes
/// before anything runs. A run that fails is kept in its point
/// ([`SummaryError`]), the others run on.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SweepError {
    #[error("unknown parameter `{path}`: expected one of {}", .valid.join(", "))]
    UnknownParam { path: String, valid: Vec<String> },
    /// The scene is invalid with the value: every bad field, what it was
    /// and what it expects.
    #[error("{}", invalid_value(.path, *.value, .errors))]
    InvalidValue {
        path: String,
        value: f64,
        errors: Vec<FieldError>,
    },
    #[error("sweep: range {from} .. {to}: expected finite values")]
    Range { from: f64, to: f64 },
    #[error("sweep: steps = 0: expected at least 1")]
    NoSteps,
    #[error(
        "sweep: steps = {steps}: expected at most {MAX_SWEEP_VALUES} values (each value is one run of the scene)"
    )]
    TooManySteps { steps: usize },
    #[error("sweep: no values to sweep")]
    NoValues,
    /// The base scene's tyre could not be identified.
    #[error("sweep: {0}")]
    Identification(#[source] SceneError),
    /// The steady part of the scene with this value is too short (or too
    /// long) for the summary's spectrum.
    #[error("{param} = {value}: {source}")]
    Steady {
        param: String,
        value: f64,
        #[source]
        source: SpectrumError,
    },
    #[error("sweep cancelled")]
    Cancelled,
}

/// The bad fields of a scene with `path = value`, each with what it
/// expects; the value is named when no bad field is the swept one.
fn invalid_value(path: &str, value: f64, errors: &[FieldError]) -> String {
    let message = errors
        .iter()
        .map(ToString::to_string)
        .collect::<Vec<_>>()
        .join("; ");
    if errors.iter().any(|e| matches(path, &e.field)) {
        message
    } else {
        format!("with {path} = {value}: {message}")
    }
}

/// Why one run of a sweep or a study has no summary: its row keeps the
/// message, the other rows run on.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SummaryError {
    /// A value of the run's scene cannot be set (a study's factor).
    #[error(transparent)]
    Param(#[from] SweepError),
    /// The run's scene is invalid with its values together: every bad
    /// field, what it was and what it expects.
    #[error("{}", join_fields(.0))]
    InvalidScene(Vec<FieldError>),
    /// The run could not be set up: its tyre identified, its road read,
    /// its modes factored.
    #[error(transparent)]
    Setup(#[from] SceneError),
    /// The steady part is too short or too long for a spectrum, or the
    /// spectrum failed.
    #[error(transparent)]
    Spectrum(#[from] SpectrumError),
    /// A step could not be solved.
    #[error(transparent)]
    Solver(#[from] SolverError),
    /// What the run's recorders write failed.
    #[error("writing the run's output: {0}")]
    Output(#[source] IoError),
    /// The run's cancel flag was set.
    #[error("cancelled")]
    Cancelled,
    /// The run was not started (the sweep was cancelled first).
    #[error("not run")]
    NotRun,
}

impl From<RunError> for SummaryError {
    fn from(e: RunError) -> Self {
        match e {
            RunError::Solver(e) => SummaryError::Solver(e),
            RunError::Output(e) => SummaryError::Output(e.into()),
            RunError::Cancelled { .. } => SummaryError::Cancelled,
        }
    }
}

fn join_fields(errors: &[FieldError]) -> String {
    errors
        .iter()
        .map(ToString::to_string)
        .collect::<Vec<_>>()
        .join("; ")
}

fn matches(pattern: &str, path: &str) -> bool {
    pattern == path
        || (pattern.contains("[*]") && wildcard(path) == wildcard(pattern) && {
            // every explicit index of the pattern must agree
            let idx = |s: &str| -> Vec<String> {
                s.split('[')
                    .skip(1)
                    .map(|t| t.split(']').next().unwrap_or("").to_string())
                    .collect()
            };
            idx(pattern)
                .iter()
                .zip(idx(path))
                .all(|(a, b)| a == "*" || *a == b)
        })
}

/// The numeric parameter paths of `scene` (what [`set_param`] accepts; a
/// `[*]` in place of an index addresses every index).
pub fn param_paths(scene: &Scene) -> Vec<String> {
    let mut s = scene.clone();
    let grid = grid_fields(scene).into_iter().map(|(p, _)| p.to_string());
    let mut paths: Vec<String> = numeric_fields(&mut s, true)
        .into_iter()
        .map(|(p, _)| p)
        .collect();
    // the grid's fields before the points it expands to
    let at = paths
        .iter()
        .position(|p| p.starts_with("points["))
        .unwrap_or(paths.len());
    paths.splice(at..at, grid);
    paths
}

/// The value of the parameter at `path` (the first match of a wildcard;
/// spaces around the path are ignored).
pub fn get_param(scene: &Scene, path: &str) -> Result<f64, SweepError> {
    let path = path.trim();
    if let Some((_, v)) = grid_fields(scene).into_iter().find(|(p, _)| *p == path) {
        return Ok(v);
    }
    let mut s = scene.clone();
    let fields = numeric_fields(&mut s, true);
    fields
        .into_iter()
        .find(|(p, _)| matches(path, p))
        .map(|(_, v)| *v)
        .ok_or_else(|| unknown(scene, path))
}

fn unknown(scene: &Scene, path: &str) -> SweepError {
    // an indexed list collapsed to its first and last path, with this
    // scene's indices (`points[0].h_m … points[2].h_m`: the range is seen)
    let mut groups: Vec<(String, String, String)> = Vec::new();
    for p in param_paths(scene) {
        let w = wildcard(&p);
        match groups.iter_mut().find(|g| g.0 == w) {
            Some(g) => g.2 = p,
            None => groups.push((w, p.clone(), p)),
        }
    }
    let mut shown: Vec<String> = groups
        .into_iter()
        .map(|(_, first, last)| {
            if first == last {
                first
            } else {
                format!("{first} … {last}")
            }
        })
        .collect();
    if shown.iter().any(|s| s.contains('[')) {
        shown.push("or [*] for an index (every point, mode…: `points[*].h_m`)".into());
    }
    SweepError::UnknownParam {
        path: path.to_string(),
        valid: shown,
    }
}

/// Sets the parameter at `path` (every match of a wildcard) to `value` and
/// validates the scene; an invalid result names the field and what it expects.
/// Spaces around the path are ignored.
pub fn set_param(scene: &mut Scene, path: &str, value: f64) -> Result<(), SweepError> {
    let path = path.trim();
    let before = scene.clone();
    let invalid = |errors| SweepError::InvalidValue {
        path: path.to_string(),
        value,
        errors,
    };
    if let Some(set) = set_grid_field(scene, path, value) {
        if let Err(e) = set {
            *scene = before;
            return Err(invalid(vec![e]));
        }
        return scene.validate().map_err(invalid);
    }
    let mut hits = 0;
    // the points' fields only for a path of theirs (a grid stays a grid)
    for (p, v) in numeric_fields(scene, path.starts_with("points[")) {
        if matches(path, &p) {
            *v = value;
            hits += 1;
        }
    }
    if hits == 0 {
        return Err(unknown(&before, path));
    }
    scene.validate().map_err(invalid)
}

/// The most values a sweep runs (each is a whole run of the scene).
pub const MAX_SWEEP_VALUES: usize = 100_000;

/// `steps` values from `from` to `to`, evenly spaced (both ends included).
pub fn linspace(from: f64, to: f64, steps: usize) -> Result<Vec<f64>, SweepError> {
    if !(from.is_finite() && to.is_finite()) {
        return Err(SweepError::Range { from, to });
    }
    match steps {
        0 => Err(SweepError::NoSteps),
        n if n > MAX_SWEEP_VALUES => Err(SweepError::TooManySteps { steps: n }),
        1 => Ok(vec![from]),
        n => Ok((0..n)
            .map(|k| from + (to - from) * k as f64 / (n - 1) as f64)
            .collect()),
    }
}

/// The summary of one run's steady part.
#[derive(Debug, Clone, PartialEq)]
pub struct RunSummary {
    /// Contact metrics of the steady part, per point (limits as dt → 0).
    pub contact: ContactSummary,
    /// Third-octave levels of the total force (dB re 1 N, Hann window,
    /// mean removed), bands 20 Hz - 5 kHz below Nyquist.
    pub bands: Vec<BandLevel>,
    /// The cell of one point when the points make a contact patch (m²,
    /// [`crate::output::patch::PatchLayout`]): the contact area is the
    /// points in contact times this.
    pub cell_area_m2: Option<f64>,
    /// Steps run.
    pub steps: u64,
}

/// Where a summarised run's time went (s): building the simulation and
/// its recorders, stepping (the probes included), the spectrum and bands.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct RunTiming {
    pub setup_s: f64,
    pub stepping_s: f64,
    pub summary_s: f64,
}

impl RunTiming {
    pub fn add(&mut self, o: &RunTiming) {
        self.setup_s += o.setup_s;
        self.stepping_s += o.stepping_s;
        self.summary_s += o.summary_s;
    }
    pub fn total_s(&self) -> f64 {
        self.setup_s + self.stepping_s + self.summary_s
    }
}

/// Runs a prepared scene to its end and summarises its steady part
/// (`t >= ramp_s`). `on_steps` is called with the number of steps done since
/// its last call (every 1024 steps and at the end); `cancel` stops the run
/// early.
pub fn run_summary(
    model: &PreparedModel,
    on_steps: &dyn Fn(u64),
    cancel: &AtomicBool,
) -> Result<RunSummary, SummaryError> {
    run_summary_timed(model, on_steps, cancel, &mut RunTiming::default())
}

/// [`run_summary`], adding where its time went to `timing`.
pub fn run_summary_timed(
    model: &PreparedModel,
    on_steps: &dyn Fn(u64),
    cancel: &AtomicBool,
    timing: &mut RunTiming,
) -> Result<RunSummary, SummaryError> {
    let t0 = web_time::Instant::now();
    let mut run = SummaryRun::new(model)?;
    let t1 = web_time::Instant::now();
    timing.setup_s += (t1 - t0).as_secs_f64();
    run.advance(on_steps, cancel, None)?;
    let t2 = web_time::Instant::now();
    timing.stepping_s += (t2 - t1).as_secs_f64();
    let summary = run.finish();
    timing.summary_s += t2.elapsed().as_secs_f64();
    summary
}

/// A summarised run ([`run_summary`]) that can be advanced in slices:
/// built, stepped until a deadline as often as needed, then summarised.
/// Slices change no result: the steps are the same, in the same order.
pub struct SummaryRun {
    sim: Simulation,
    metrics: ContactMetrics,
    /// The area of a patch's cell (m²; `None`: not a patch).
    cell_area_m2: Option<f64>,
}

impl SummaryRun {
    /// The simulation of `model` and its metrics; a steady part too short
    /// or too long for a spectrum is refused here, before any step.
    pub fn new(model: &PreparedModel) -> Result<Self, SummaryError> {
        Self::with_simulation(model.simulation(SolverOptions::default())?, model.scene())
    }

    /// [`SummaryRun::new`] on a simulation built already (at rest) from
    /// `scene`.
    pub fn with_simulation(sim: Simulation, scene: &Scene) -> Result<Self, SummaryError> {
        SteadyRecorder::steady_samples(scene, None)?;
        let metrics = ContactMetrics::new(scene, None).keeping_total_force();
        let cell_area_m2 = crate::output::patch::PatchLayout::of(scene)
            .ok()
            .map(|l| l.cell_area_m2());
        Ok(SummaryRun {
            sim,
            metrics,
            cell_area_m2,
        })
    }

    /// Steps until the scene's end or `deadline` (`None`: the end);
    /// `on_steps` is told of the steps done (every 1024 steps and at the
    /// end of the call); `cancel` stops the run. `true` once at the end.
    pub fn advance(
        &mut self,
        on_steps: &dyn Fn(u64),
        cancel: &AtomicBool,
        deadline: Option<web_time::Instant>,
    ) -> Result<bool, SummaryError> {
        let mut reported = 0;
        let mut progress = |done: u64, _: &Simulation| {
            on_steps(done - reported);
            reported = done;
        };
        let mut watch = Watch::cancel(cancel).with_progress(&mut progress);
        watch.deadline = deadline;
        tirecontact_core::solver::drive::run_to_end(&mut self.sim, &mut self.metrics, watch)?;
        Ok(self.sim.finished())
    }

    /// The summary of the steady part (after [`SummaryRun::advance`] has
    /// reached the end).
    pub fn finish(self) -> Result<RunSummary, SummaryError> {
        let scene = self.sim.problem();
        let fs = 1.0 / scene.dt_s;
        let hi = DEFAULT_BANDS_HZ.1.min(0.5 * fs / 10f64.powf(0.05));
        let bands = crate::analysis::spectrum::spectrum(
            self.metrics.total_force_n(),
            fs,
            Window::Hann,
            true,
        )
        .map(|s| s.third_octave_levels(DEFAULT_BANDS_HZ.0, hi, 1.0))?;
        Ok(RunSummary {
            contact: self.metrics.summary(),
            bands,
            cell_area_m2: self.cell_area_m2,
            steps: scene.num_steps(),
        })
    }
}

/// A sweep run value after value on the caller's thread, in slices
/// ([`SweepRun::advance`] until a deadline): what a page in the browser,
/// which has no threads, runs within its frames. Its points equal
/// [`run_sweep`]'s.
pub struct SweepRun {
    values: Vec<f64>,
    scenes: Vec<Scene>,
    /// The value being run and its run (`None` before it is prepared).
    next: usize,
    current: Option<SummaryRun>,
    /// The value's scene being prepared and its solver built (before its
    /// run).
    preparing: Option<Preparing>,
    points: Vec<SweepPoint>,
    total_steps: u64,
    done_steps: u64,
}

impl SweepRun {
    /// The sweep's scenes, checked before anything runs.
    pub fn new(base: &Scene, sweep: &Sweep) -> Result<Self, SweepError> {
        let scenes = sweep_scenes(base, sweep)?;
        Ok(SweepRun {
            values: sweep.values.clone(),
            total_steps: scenes.iter().map(Scene::num_steps).sum(),
            scenes,
            next: 0,
            current: None,
            preparing: None,
            points: Vec::new(),
            done_steps: 0,
        })
    }

    /// The steps of every run.
    pub fn total_steps(&self) -> u64 {
        self.total_steps
    }

    /// The steps done so far.
    pub fn done_steps(&self) -> u64 {
        self.done_steps
    }

    /// Runs until `deadline` (`None`: to the end): the sweep's points once
    /// every value ran, `None` before. A value's preparation (a ring's
    /// identification, from `cache`) is done whole within a call.
    pub fn advance(
        &mut self,
        cache: &ModeCache,
        cancel: &AtomicBool,
        deadline: Option<web_time::Instant>,
    ) -> Option<Result<Vec<SweepPoint>, SweepError>> {
        let past = || deadline.is_some_and(|d| web_time::Instant::now() >= d);
        while self.next < self.scenes.len() {
            if cancel.load(Ordering::Relaxed) {
                return Some(Err(SweepError::Cancelled));
            }
            let k = self.next;
            let value = self.values[k];
            let run = match self.current.take() {
                Some(run) => Ok(run),
                None => {
                    // the scene prepared and its solver built a stage at a
                    // time (a ring's identification, a large patch's
                    // tables take many slices)
                    let prep = self.preparing.get_or_insert_with(|| {
                        Preparing::Model(Box::new(PreparedModelRun::new(&self.scenes[k], cache)))
                    });
                    let sim = loop {
                        if cancel.load(Ordering::Relaxed) {
                            return Some(Err(SweepError::Cancelled));
                        }
                        match prep {
                            Preparing::Model(run) => match run.stage(cache) {
                                Ok(Some(m)) => {
                                    *prep =
                                        Preparing::Build(Box::new(Simulation::build_in_stages(
                                            m.problem().clone(),
                                            SolverOptions::default(),
                                        )));
                                }
                                Err(e) => break Err(SummaryError::from(e)),
                                Ok(None) => {}
                            },
                            Preparing::Build(b) => match b.stage() {
                                Ok(Some(sim)) => break Ok(sim),
                                Err(e) => break Err(SummaryError::from(SceneError::from(e))),
                                Ok(None) => {}
                            },
                        }
                        if past() {
                            return None;
                        }
                    };
                    self.preparing = None;
                    sim.and_then(|sim| SummaryRun::with_simulation(sim, &self.scenes[k]))
                }
            };
            let done = std::cell::Cell::new(0);
            let outcome = run.and_then(|mut run| {
                let end = run.advance(&|d| done.set(done.get() + d), cancel, deadline)?;
                Ok((end, run))
            });
            self.done_steps += done.get();
            let result = match outcome {
                Ok((false, run)) => {
                    self.current = Some(run);
                    return None;
                }
                Ok((true, run)) => run.finish(),
                Err(SummaryError::Cancelled) => {
                    return Some(Err(SweepError::Cancelled));
                }
                Err(e) => Err(e),
            };
            self.points.push(SweepPoint { value, result });
            self.next += 1;
            if past() && self.next < self.scenes.len() {
                return None;
            }
        }
        Some(Ok(std::mem::take(&mut self.points)))
    }
}

/// Where the preparation of a sweep value's run is.
enum Preparing {
    Model(Box<PreparedModelRun>),
    Build(Box<SimulationBuild>),
}

/// One point of a sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepPoint {
    pub value: f64,
    pub result: Result<RunSummary, SummaryError>,
}

/// A sweep's definition.
#[derive(Debug, Clone)]
pub struct Sweep {
    pub param: String,
    pub values: Vec<f64>,
    /// Worker threads (>= 1).
    pub threads: usize,
}

/// The scenes of a sweep, one per value, checked before anything runs.
pub fn sweep_scenes(base: &Scene, sweep: &Sweep) -> Result<Vec<Scene>, SweepError> {
    if sweep.values.is_empty() {
        return Err(SweepError::NoValues);
    }
    sweep
        .values
        .iter()
        .map(|&v| {
            let mut s = base.clone();
            set_param(&mut s, &sweep.param, v)?;
            // a steady part too short (or too long) for the summary's
            // spectrum: said before any run, not after every one
            SteadyRecorder::steady_samples(&s, None).map_err(|source| SweepError::Steady {
                param: sweep.param.clone(),
                value: v,
                source,
            })?;
            Ok(s)
        })
        .collect()
}

/// Runs the sweep on `sweep.threads` threads (values taken in order by the
/// next free thread). `progress(done_steps, total_steps)` is called from the
/// workers; `cancel` stops every run. Failed runs keep their error. A ring
/// tyre's modes come from `cache` (and are kept there).
pub fn run_sweep(
    base: &Scene,
    sweep: &Sweep,
    cache: &ModeCache,
    progress: &(dyn Fn(u64, u64) + Sync),
    cancel: &AtomicBool,
) -> Result<Vec<SweepPoint>, SweepError> {
    let scenes = sweep_scenes(base, sweep)?;
    // identify a ring tyre once up front rather than in every thread at
    // once; a swept ring parameter is identified per value in the threads
    cache
        .modes(&scenes[0])
        .map_err(SweepError::Identification)?;
    let total: u64 = scenes.iter().map(Scene::num_steps).sum();
    let done = std::sync::atomic::AtomicU64::new(0);
    let results: Mutex<Vec<Option<Result<RunSummary, SummaryError>>>> =
        Mutex::new(vec![None; scenes.len()]);
    engine::run_each(
        scenes.len(),
        sweep.threads,
        cache,
        cancel,
        &|k| Ok(scenes[k].clone()),
        &|d| {
            let now = done.fetch_add(d, Ordering::Relaxed) + d;
            progress(now, total);
        },
        &|k, r| results.lock().unwrap_or_else(|e| e.into_inner())[k] = Some(r),
    );
    if cancel.load(Ordering::Relaxed) {
        return Err(SweepError::Cancelled);
    }
    let results = results.into_inner().unwrap_or_else(|e| e.into_inner());
    Ok(sweep
        .values
        .iter()
        .zip(results)
        .map(|(&value, r)| SweepPoint {
            value,
            result: r.unwrap_or(Err(SummaryError::NotRun)),
        })
        .collect())
}
