//! Export: the time plots as a PNG (headless figure: title, scene parameters,
//! axes with units, legends) and the run as CSV in the format of
//! `tirecontact run`.
//!
//! The CSV is written by re-running the scene from t = 0 on a background
//! thread, every step, replaying the live edits (road, speed) at the steps
//! where they were made: the file holds exactly the run that was shown, at
//! full resolution, whatever the history's decimation.

use crate::base::error::RunError;
use crate::base::modal::Mode;
use crate::gui::jobs::{Job, Progress};
use crate::gui::model::history::History;
use crate::identify::{ModeCache, PreparedModel};
use crate::model::road::{Road, RoadProfile};
use crate::output::csv::RunWriter;
use crate::output::figures::{Figure, render_png};
use crate::output::record::{FigureSpec, PLOT_SAMPLES, RunPanel};
use crate::output::summary::{scene_summary, short_num};
use crate::solver::drive::{self, Probe, Watch};
use crate::{Scene, Simulation, SolverOptions};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::AtomicBool;

/// A road or speed change made while the run was going.
#[derive(Debug, Clone, PartialEq)]
pub struct LiveEdit {
    /// Solver steps taken before the change.
    pub step: u64,
    pub road: Road,
    /// `road`'s profile, loaded when the edit was made.
    pub profile: RoadProfile,
    pub speed_mps: f64,
}

impl LiveEdit {
    /// Replays the edit on `sim`.
    pub fn apply(&self, sim: &mut Simulation) {
        sim.set_road(&self.road, self.profile.clone());
        sim.set_speed(self.speed_mps);
    }
}

/// Counts a job's progress in solver steps.
struct StepCounter<'a>(&'a Progress);

impl Probe for StepCounter<'_> {
    fn after_step(&mut self, _sim: &Simulation) -> std::io::Result<()> {
        self.0.add(1);
        Ok(())
    }
}

/// Runs `sim` on to `steps` steps, replaying each live edit (in step order)
/// before the step it was made at, and telling `probe` (its start too if
/// `sim` has not stepped). Stops early where the scene ends or the probe is
/// satisfied; `cancel` stops it with [`RunError::Cancelled`].
pub fn replay(
    sim: &mut Simulation,
    edits: &[LiveEdit],
    steps: u64,
    probe: &mut impl Probe,
    cancel: Option<&AtomicBool>,
) -> Result<(), RunError> {
    let watch = || cancel.map_or_else(Watch::none, Watch::cancel);
    if sim.steps() == 0 {
        probe.start(sim)?;
    }
    for e in edits.iter().filter(|e| e.step < steps) {
        drive::run(sim, e.step.saturating_sub(sim.steps()), probe, watch())?;
        if sim.steps() < e.step {
            // the run stopped before this edit
            return Ok(());
        }
        e.apply(sim);
    }
    drive::run(sim, steps.saturating_sub(sim.steps()), probe, watch())?;
    Ok(())
}

/// Name of the exported force panel's series of clipped impacts (the
/// same as the CLI's figures).
pub use crate::output::record::CLIPPED_IMPACTS;

/// The figure of the time plots over the whole recorded run, drawn as
/// `run --plot` draws its figure (the history as a recording of at most
/// [`PLOT_SAMPLES`] windows, forces window means): the four quantities of
/// the time plots for the `shown` points. With `clip_impacts` (the time
/// plots' "clip impact spikes"), the force panel is cut a margin above the
/// force without impacts of the shown points, the cut samples marked by
/// dots at that level, so the rolling force stays readable in a report.
pub fn time_figure(
    scene: &Scene,
    modes: &[Mode],
    history: &History,
    shown: &[bool],
    clip_impacts: bool,
) -> Figure {
    let t1 = history.last_time().unwrap_or(0.0);
    let points: Vec<usize> = (0..history.num_points())
        .filter(|&i| shown.get(i).copied().unwrap_or(true))
        .collect();
    let rec = history.to_recording();
    // the t = 0 sample, then at most the command line's figure windows
    let rec = rec.merged_after_start((rec.len().max(1) - 1).div_ceil(PLOT_SAMPLES as usize));
    rec.figure(&FigureSpec {
        title: &format!("{} — t = 0 … {} s", scene.name, short_num(t1, 4)),
        subtitle: &scene_summary(scene, modes),
        dt_s: scene.dt_s,
        clip_impacts,
        points: Some(&points),
        panels: &RunPanel::TIME_PLOTS,
    })
}

/// Writes the time plots as a `width × height` PNG (force clipped as in
/// [`time_figure`] with `clip_impacts`).
pub fn export_png(
    path: &Path,
    width: u32,
    height: u32,
    scene: &Scene,
    modes: &[Mode],
    history: &History,
    shown: &[bool],
    clip_impacts: bool,
) -> Result<(), String> {
    let fig = time_figure(scene, modes, history, shown, clip_impacts);
    render_png(&fig, path, width, height).map_err(|e| e.to_string())
}

/// Re-runs `start` for `steps` steps, replaying `edits`, into `path` (CSV);
/// counts the steps in `progress` and stops if it is cancelled.
pub fn write_csv(
    path: &Path,
    start: &PreparedModel,
    edits: &[LiveEdit],
    steps: u64,
    progress: Option<&Progress>,
) -> Result<String, String> {
    let mut sim = Simulation::new(start, SolverOptions::default()).map_err(|e| e.to_string())?;
    let start = start.scene();
    let mut bytes = Vec::new();
    {
        let mut w = RunWriter::new(&mut bytes, start.num_points(), 1).map_err(|e| e.to_string())?;
        let mut counted = (&mut w, progress.map(StepCounter));
        replay(
            &mut sim,
            edits,
            steps,
            &mut counted,
            progress.map(Progress::cancel_flag),
        )
        .map_err(|e| e.to_string())?;
        w.finish().map_err(|e| e.to_string())?;
    }
    crate::base::fsio::write_atomic(path, &bytes)
        .map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(format!(
        "wrote {} ({} steps, t = 0 … {:.5} s)",
        path.display(),
        steps,
        sim.time_s()
    ))
}

/// A CSV export running on its own thread.
pub struct CsvJob {
    pub path: PathBuf,
    job: Job<Result<String, String>>,
}

impl CsvJob {
    /// Re-runs `start` (its modes from `cache`) on a new thread.
    pub fn spawn(
        path: PathBuf,
        start: Scene,
        cache: Arc<ModeCache>,
        edits: Vec<LiveEdit>,
        steps: u64,
    ) -> Result<Self, String> {
        let p = path.clone();
        let job = Job::spawn("CSV export", steps, move |progress| {
            PreparedModel::new(&start, &cache)
                .map_err(|e| e.to_string())
                .and_then(|model| write_csv(&p, &model, &edits, steps, Some(progress)))
        })?;
        Ok(CsvJob { path, job })
    }

    /// Fraction of the steps re-run (0..=1).
    pub fn fraction(&self) -> f64 {
        self.job.fraction()
    }

    /// The result, once the thread has finished.
    pub fn poll(&self) -> Option<Result<String, String>> {
        self.job.poll().map(Result::flatten)
    }

    /// Blocks until the export ends (tests).
    pub fn wait(self) -> Result<String, String> {
        self.job.wait().and_then(|r| r)
    }
}
