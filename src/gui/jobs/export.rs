//! Export: the time plots as a PNG (headless figure: title, scene parameters,
//! axes with units, legends) and the run as CSV in the format of
//! `tirecontact run`.
//!
//! The CSV is written by re-running the scene from t = 0 on a background
//! thread, every step, replaying the live edits (road, speed) at the steps
//! where they were made: the file holds exactly the run that was shown, at
//! full resolution, whatever the history's decimation.

use crate::base::modal::Mode;
use crate::gui::jobs::{Job, Progress};
use crate::gui::model::history::History;
use crate::identify::{ModeCache, PreparedModel, PreparedModelRun};
use crate::model::road::{Road, RoadProfile};
use crate::output::csv::RunWriter;
use crate::output::figures::Figure;
use crate::output::record::{FigureSpec, PLOT_SAMPLES, RunPanel};
use crate::output::summary::{scene_summary, short_num};
use crate::solver::drive::{self, Probe, Watch};
use crate::solver::error::RunError;
use crate::solver::simulation::SimulationBuild;
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
        sim.set_road(self.profile.clone());
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

/// Re-runs `start` for `steps` steps, replaying `edits`, into `path` (CSV);
/// counts the steps in `progress` and stops if it is cancelled.
pub fn write_csv(
    path: &Path,
    start: &PreparedModel,
    edits: &[LiveEdit],
    steps: u64,
    progress: Option<&Progress>,
) -> Result<String, String> {
    let mut sim = start
        .simulation(SolverOptions::default())
        .map_err(|e| e.to_string())?;
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

/// A CSV export running on its own thread (in the browser, in slices
/// within the frames, the file then offered as a download).
pub struct CsvJob {
    pub path: PathBuf,
    job: Job<Result<String, String>>,
}

/// Where a CSV export is: the start scene prepared (its ring identified),
/// its solver built, then the run replayed into the CSV.
enum CsvStage {
    Model(Box<PreparedModelRun>),
    Build(Box<SimulationBuild>),
    Run(Box<Simulation>, Box<RunWriter<Vec<u8>>>),
}

/// Steps re-run per stage of a CSV export in slices: about `2^16 / P²` (a
/// step's contact solve grows as `P²`), 1 to 256.
fn csv_block_steps(p: usize) -> u64 {
    (65_536 / (p * p).max(1)).clamp(1, 256) as u64
}

impl CsvJob {
    /// Re-runs `start` (its modes from `cache`) on a new thread (in the
    /// browser, in slices within the polls: [`Job::spawn_sliced`]); the
    /// CSV then goes to `deliver` (a file, or the browser's download).
    pub fn spawn(
        path: PathBuf,
        start: Scene,
        cache: Arc<ModeCache>,
        edits: Vec<LiveEdit>,
        steps: u64,
        deliver: Deliver,
    ) -> Result<Self, String> {
        Self::start(path, start, cache, edits, steps, deliver, false)
    }

    /// The export run on the caller's thread, a slice at each poll
    /// ([`Job::in_slices`]): how a page in the browser runs it. It writes
    /// the threaded export's file.
    pub fn spawn_in_slices(
        path: PathBuf,
        start: Scene,
        cache: Arc<ModeCache>,
        edits: Vec<LiveEdit>,
        steps: u64,
        deliver: Deliver,
    ) -> Result<Self, String> {
        Self::start(path, start, cache, edits, steps, deliver, true)
    }

    fn start(
        path: PathBuf,
        start: Scene,
        cache: Arc<ModeCache>,
        edits: Vec<LiveEdit>,
        steps: u64,
        deliver: Deliver,
        in_slices: bool,
    ) -> Result<Self, String> {
        let mut deliver = Some(deliver);
        let p = path.clone();
        let block = csv_block_steps(start.num_points());
        let mut stage = Some(CsvStage::Model(Box::new(PreparedModelRun::new(
            &start, &cache,
        ))));
        let work = move |progress: &Progress, deadline: Option<web_time::Instant>| loop {
            if progress.cancelled() {
                return Some(Err("cancelled".to_string()));
            }
            let Some(current) = &mut stage else {
                return Some(Err("the export already ended".to_string()));
            };
            match current {
                CsvStage::Model(run) => match run.stage(&cache) {
                    Err(e) => return Some(Err(e.to_string())),
                    Ok(None) => {}
                    Ok(Some(model)) => {
                        *current = CsvStage::Build(Box::new(Simulation::build_in_stages(
                            model.problem().clone(),
                            SolverOptions::default(),
                        )));
                    }
                },
                CsvStage::Build(b) => match b.stage() {
                    Err(e) => return Some(Err(crate::SceneError::from(e).to_string())),
                    Ok(None) => {}
                    Ok(Some(sim)) => {
                        let w = match RunWriter::new(Vec::new(), sim.num_points(), 1) {
                            Ok(w) => w,
                            Err(e) => return Some(Err(e.to_string())),
                        };
                        *current = CsvStage::Run(Box::new(sim), Box::new(w));
                    }
                },
                CsvStage::Run(sim, w) => {
                    let from = sim.steps();
                    let to = (from + block).min(steps);
                    // the edits not yet replayed (one at step `from` was not)
                    let first = edits.partition_point(|e| e.step < from);
                    let mut counted = (&mut **w, StepCounter(progress));
                    let r = replay(
                        sim,
                        &edits[first..],
                        to,
                        &mut counted,
                        Some(progress.cancel_flag()),
                    );
                    if let Err(e) = r {
                        return Some(Err(e.to_string()));
                    }
                    // the whole run, or the scene ended before it
                    if sim.steps() >= steps || sim.steps() < to {
                        let Some(CsvStage::Run(sim, w)) = stage.take() else {
                            unreachable!("running");
                        };
                        let Some(deliver) = deliver.take() else {
                            unreachable!("delivered once");
                        };
                        return Some(deliver_csv(&p, *w, &sim, deliver));
                    }
                }
            }
            if deadline.is_some_and(|d| web_time::Instant::now() >= d) {
                return None;
            }
        };
        let job = if in_slices {
            Job::in_slices("CSV export", steps, work)
        } else {
            Job::spawn_sliced("CSV export", steps, work)?
        };
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

/// Where the bytes of a finished CSV export go, given its path: the
/// message to show, or why they could not go there.
pub type Deliver = Box<dyn FnOnce(&Path, Vec<u8>) -> Result<String, String> + Send>;

/// The desktop's delivery: the file written atomically.
pub fn write_file() -> Deliver {
    Box::new(|path, bytes| {
        crate::fsio::write_atomic(path, &bytes).map_err(|e| format!("{}: {e}", path.display()))?;
        Ok(format!("wrote {}", path.display()))
    })
}

/// The CSV of a replayed run handed to `deliver`, the run's span after its
/// message.
fn deliver_csv(
    path: &Path,
    w: RunWriter<Vec<u8>>,
    sim: &Simulation,
    deliver: Deliver,
) -> Result<String, String> {
    let bytes = w.finish().map_err(|e| e.to_string())?;
    let said = deliver(path, bytes)?;
    Ok(format!(
        "{said} ({} steps, t = 0 … {:.5} s)",
        sim.steps(),
        sim.time_s()
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::SceneSimulation;
    use crate::output::figures::{render_png, render_png_bytes};

    /// The paper preset (a ring tyre: its identification is part of the
    /// export), with a speed edit made at step 700 of 2000.
    fn paper_run() -> (Scene, Vec<LiveEdit>) {
        let scene = Scene::parse(
            include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/presets/paper.ron")),
            "paper",
        )
        .unwrap();
        let profile = crate::scene::load_road(&scene.road, None).unwrap();
        let edits = vec![LiveEdit {
            step: 700,
            road: scene.road.clone(),
            profile,
            speed_mps: 0.5 * scene.speed_mps,
        }];
        (scene, edits)
    }

    /// The page's PNG of the time plots: a PNG of the asked size, with the
    /// pixels of the figure drawn in memory, and the same image as the
    /// desktop's file.
    #[test]
    fn the_plots_png_bytes_decode_as_the_figure_at_its_size() {
        let scene = Scene::parse(
            include_str!(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/presets/three_points.ron"
            )),
            "three_points",
        )
        .unwrap();
        let mut sim = Simulation::from_scene(&scene).unwrap();
        let modes = ModeCache::new().modes(&scene).unwrap().to_vec();
        let mut history = History::new(scene.num_points(), 100_000);
        history.record_initial(&sim);
        for _ in 0..2000 {
            sim.step().unwrap();
            history.after_step(&sim);
        }
        let shown = vec![true; scene.num_points()];
        let fig = time_figure(&scene, &modes, &history, &shown, true);
        for (w, h) in [(1600, 1200), (641, 487)] {
            let png = render_png_bytes(&fig, w, h).unwrap();
            assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
            let img = image::load_from_memory_with_format(&png, image::ImageFormat::Png)
                .unwrap()
                .to_rgb8();
            assert_eq!(img.dimensions(), (w, h));
            let (rgb, _) = crate::output::figures::render_rgb_layout(&fig, w, h).unwrap();
            assert!(img.as_raw() == &rgb, "{w}x{h}: the PNG is not the figure");
            // and the figure: more than a blank page
            let dark = rgb.chunks(3).filter(|p| p.iter().all(|c| *c < 100)).count();
            assert!(dark > 1000, "{w}x{h}: {dark} dark pixels");
            // the desktop's file holds the same image
            let path = std::env::temp_dir()
                .join(format!("tirecontact-plots-{}-{w}.png", std::process::id()));
            render_png(&fig, &path, w, h).unwrap();
            let file = image::open(&path).unwrap().to_rgb8();
            std::fs::remove_file(&path).ok();
            assert!(
                file.as_raw() == img.as_raw(),
                "{w}x{h}: file and bytes differ"
            );
        }
        // a size out of range is an error naming it, no panic
        let e = render_png_bytes(&fig, 100, 50).unwrap_err().to_string();
        assert!(e.contains("100x50"), "{e}");
    }

    /// A CSV export in slices (the browser's way) writes the bytes of the
    /// whole re-run on a thread, live edit included, over several polls; a
    /// cancelled one writes nothing.
    #[test]
    fn a_csv_export_in_slices_writes_the_threaded_export_s_file() {
        let dir = std::env::temp_dir().join(format!("tirecontact-csv-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let (scene, edits) = paper_run();
        let cache = Arc::new(ModeCache::new());
        let (whole, sliced) = (dir.join("whole.csv"), dir.join("sliced.csv"));
        let model = PreparedModel::new(&scene, &ModeCache::new()).unwrap();
        write_csv(&whole, &model, &edits, 2000, None).unwrap();
        let job = CsvJob::spawn_in_slices(
            sliced.clone(),
            scene.clone(),
            cache,
            edits.clone(),
            2000,
            write_file(),
        )
        .unwrap();
        let mut polls = 0;
        let r = loop {
            polls += 1;
            if let Some(r) = job.poll() {
                break r;
            }
        };
        assert!(r.as_ref().is_ok_and(|m| m.contains("2000 steps")), "{r:?}");
        assert!(polls >= 2, "one poll ran the whole export");
        let (a, b) = (
            std::fs::read(&whole).unwrap(),
            std::fs::read(&sliced).unwrap(),
        );
        // the header, t = 0, the 2000 steps
        assert_eq!(String::from_utf8_lossy(&a).lines().count(), 2002);
        assert!(a == b, "the sliced export differs from the whole one");
        // cancelled between slices: an error, no file
        let gone = dir.join("cancelled.csv");
        let job = CsvJob::spawn_in_slices(
            gone.clone(),
            scene,
            Arc::new(ModeCache::new()),
            edits,
            2000,
            write_file(),
        )
        .unwrap();
        job.job.cancel();
        assert_eq!(job.poll(), Some(Err("cancelled".to_string())));
        assert!(!gone.exists());
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// A stage of the re-run holds at most `2^16` point pairs' worth of
    /// steps (one step for a thousand points), at least one step.
    #[test]
    fn csv_blocks_shrink_with_the_points() {
        for p in [1, 5, 16, 100, 1000, 5000] {
            let b = csv_block_steps(p) as usize;
            assert!(b >= 1 && (b == 1 || b * p * p <= 65_536), "{p}: {b}");
        }
        assert_eq!(csv_block_steps(1000), 1);
        assert_eq!(csv_block_steps(5), 256);
    }
}
