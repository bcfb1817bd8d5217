//! Export: the time plots as a PNG (headless figure: title, scene parameters,
//! axes with units, legends) and the run as CSV in the format of
//! `tirecontact run`.
//!
//! The CSV is written by re-running the scene from t = 0 on a background
//! thread, every step, replaying the live edits (road, speed) at the steps
//! where they were made: the file holds exactly the run that was shown, at
//! full resolution, whatever the history's decimation.

use crate::drive::{self, Probe, Watch};
use crate::error::RunError;
use crate::gui::jobs::{Job, Progress};
use crate::gui::model::history::{History, Quantity};
use crate::gui::views::time_plots::{clip_level, force_range};
use crate::identify::{ModeCache, PreparedModel};
use crate::modal::Mode;
use crate::output::csv::RunWriter;
use crate::output::figures::{Figure, Panel, Series, Style, render_png};
use crate::road::{Road, RoadProfile};
use crate::{Scene, Simulation, SolverOptions};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::AtomicBool;

/// Samples per series in an exported figure (min/max decimated).
const FIGURE_BUCKETS: usize = 2000;

/// Palette index of the clipped impacts' dots: black.
const IMPACT_COLOR: usize = 6;

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

/// Modes listed one by one in a subtitle (more are given as ranges).
const SUMMARY_MODES: usize = 4;

fn min_max(v: impl Iterator<Item = f64>) -> (f64, f64) {
    v.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
        (lo.min(x), hi.max(x))
    })
}

/// One line of scene parameters for figure subtitles.
pub fn scene_summary(scene: &Scene, modes: &[Mode]) -> String {
    let n_modes = modes.len();
    // a few modes listed, more summarised (the subtitle is one line)
    let modes: Vec<String> = if n_modes <= SUMMARY_MODES {
        modes
            .iter()
            .map(|m| format!("{:.1} Hz/{:.3}", m.freq_hz, m.damping_ratio))
            .collect()
    } else {
        let (f, z) = (
            min_max(modes.iter().map(|m| m.freq_hz)),
            min_max(modes.iter().map(|m| m.damping_ratio)),
        );
        vec![format!(
            "{:.1} … {:.1} Hz/{:.3} … {:.3}",
            f.0, f.1, z.0, z.1
        )]
    };
    let road = match &scene.road {
        Road::Sine {
            amplitude_m,
            wavelength_m,
        } => format!("sine a = {} mm, λ = {} m", amplitude_m * 1e3, wavelength_m),
        Road::Harmonics { components } => format!("{} harmonics", components.len()),
        Road::Measured { file, .. } => format!("measured {}", file.display()),
        Road::Random { class, seed, .. } => format!("ISO 8608 class {class:?}, seed {seed}"),
    };
    format!(
        "{} points; {n_modes} modes (f/ξ): {}; road {}; V = {} m/s ({:.1} km/h); ramp {} s; dt = {:e} s",
        scene.num_points(),
        modes.join(", "),
        road,
        scene.speed_mps,
        scene.speed_mps * 3.6,
        scene.ramp_s,
        scene.dt_s
    )
}

/// Name of the exported force panel's series of clipped impacts (the
/// same as the CLI's figures).
pub use crate::output::record::CLIPPED_IMPACTS;

/// The figure of the time plots over the whole recorded run. With
/// `clip_impacts` (the time plots' "clip impact spikes"), the force panel
/// is cut at the level the time plots use (a margin above the force without
/// impacts of the shown points) and the clipped samples are marked with dots
/// at that level, so the rolling force stays readable in a report.
pub fn time_figure(
    scene: &Scene,
    modes: &[Mode],
    history: &History,
    shown: &[bool],
    clip_impacts: bool,
) -> Figure {
    let t1 = history.last_time().unwrap_or(0.0);
    let shown_points: Vec<usize> = (0..history.num_points())
        .filter(|&i| shown.get(i).copied().unwrap_or(true))
        .collect();
    let force_top = if clip_impacts {
        force_range(history, &shown_points, 0.0, t1, FIGURE_BUCKETS).map(clip_level)
    } else {
        None
    };
    let defs = [
        (Quantity::Displacement, "displacement", "u (mm, up)", 1e3),
        (Quantity::Force, "contact force (step mean)", "q (N)", 1.0),
        (Quantity::Gap, "gap to the road", "gap (mm)", 1e3),
        (
            Quantity::Contact,
            "contact state (lane per point, raised = contact)",
            "point",
            1.0,
        ),
    ];
    let panels = defs
        .iter()
        .enumerate()
        .map(|(panel_index, &(what, title, y_label, scale))| {
            let top = force_top.filter(|_| what == Quantity::Force);
            let mut marks = Vec::new();
            let mut series: Vec<Series> = shown_points
                .iter()
                .enumerate()
                .map(|(lane, &i)| {
                    let mut pts: Vec<(f64, f64)> = history
                        .decimated(what, i, 0.0, t1, FIGURE_BUCKETS, scale)
                        .into_iter()
                        .map(|[t, y]| (t, y))
                        .collect();
                    if what == Quantity::Contact {
                        for p in &mut pts {
                            p.1 = lane as f64 + 0.7 * p.1;
                        }
                    }
                    if let Some(top) = top {
                        for p in &mut pts {
                            if p.1 > top {
                                p.1 = top;
                                marks.push(*p);
                            }
                        }
                    }
                    // the points' colours are the same in every panel: one
                    // legend, in the first (four legends of 5-50 entries
                    // covered the data and overflowed short panels)
                    let name = if panel_index == 0 {
                        format!("point {i}")
                    } else {
                        String::new()
                    };
                    let mut s = Series::line(name, pts);
                    s.color = Some(i);
                    if what == Quantity::Force {
                        // one-pixel lines: wide ones overshoot the panel at
                        // the spikes of impacts (clipped or not)
                        s.style = Style::ThinLine;
                    }
                    s
                })
                .collect();
            // (clipped impacts are said by their legend entry)
            let title = title.to_string();
            if top.is_some() && !marks.is_empty() {
                series.push(Series {
                    name: CLIPPED_IMPACTS.to_string(),
                    points: marks,
                    style: Style::Markers(3),
                    color: Some(IMPACT_COLOR),
                });
            }
            // the contact lanes named after their points
            let y_names = match what {
                Quantity::Contact => shown_points.iter().map(|i| format!("p{i}")).collect(),
                _ => Vec::new(),
            };
            Panel {
                title,
                x_label: "time t (s)".to_string(),
                y_label: y_label.to_string(),
                series,
                y_names,
                ..Panel::default()
            }
        })
        .collect();
    Figure {
        title: format!("{} — t = 0 … {:.4} s", scene.name, t1),
        subtitle: scene_summary(scene, modes),
        panels,
    }
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
    crate::fsio::write_atomic(path, &bytes).map_err(|e| format!("{}: {e}", path.display()))?;
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
