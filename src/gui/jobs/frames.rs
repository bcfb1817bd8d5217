//! The animation export's background job: the run replayed from t = 0
//! with its live edits, one PNG per frame (`output::animation`), with
//! progress and Cancel.

use crate::gui::jobs::Job;
use crate::gui::jobs::export::{LiveEdit, replay};
use crate::identify::{ModeCache, PreparedModel};
use crate::output::animation::{FrameSettings, FrameWriter, RoadChange, frames_error};
use crate::{Scene, SolverOptions};
use std::path::PathBuf;

/// A frames export running on its own thread.
pub struct FramesJob {
    pub dir: PathBuf,
    pub total: u64,
    job: Job<Result<u64, String>>,
}

impl FramesJob {
    pub fn spawn(
        dir: PathBuf,
        settings: FrameSettings,
        start: Scene,
        cache: &ModeCache,
        edits: Vec<LiveEdit>,
        clear_old: bool,
    ) -> Result<Self, String> {
        settings
            .check(start.duration_s)
            .map_err(|e| e.to_string())?;
        // refused here, with the dialog still open, rather than by the job
        if !clear_old {
            crate::output::animation::refuse_old_frames(&dir).map_err(|e| e.to_string())?;
        }
        let model = PreparedModel::new(&start, cache).map_err(|e| e.to_string())?;
        let mut sim = model
            .simulation(SolverOptions::default())
            .map_err(|e| e.to_string())?;
        let d = dir.clone();
        let total = settings.frame_count();
        let road = start.road.clone();
        let job = Job::spawn("frames export", total, move |progress| {
            // (the axes span the roads and speeds of the edits replayed)
            let dt_s = sim.dt_s();
            let changes: Vec<RoadChange<'_>> = edits
                .iter()
                .map(|e| RoadChange {
                    t_s: e.step as f64 * dt_s,
                    profile: &e.profile,
                    speed_mps: e.speed_mps,
                })
                .collect();
            let mut frames = FrameWriter::new(
                &sim,
                &road,
                &changes,
                &d,
                &settings,
                clear_old,
                progress.done_counter(),
                progress.cancel_flag(),
            )
            .map_err(|e| e.to_string())?;
            let end = sim.problem().num_steps();
            replay(&mut sim, &edits, end, &mut frames, None)
                .map_err(|e| frames_error(e).to_string())?;
            frames
                .finish(&sim)
                .map_err(|e| frames_error(e.into()).to_string())
        })?;
        Ok(FramesJob { dir, total, job })
    }

    /// Frames written so far.
    pub fn done(&self) -> u64 {
        self.job.done()
    }

    /// Asks the thread to stop before the next frame.
    pub fn cancel(&self) {
        self.job.cancel();
    }

    /// Whether Cancel was asked for.
    pub fn cancel_requested(&self) -> bool {
        self.job.cancel_requested()
    }

    /// The result, once the thread has finished.
    pub fn poll(&self) -> Option<Result<u64, String>> {
        self.job.poll().map(Result::flatten)
    }

    /// Blocks until the export ends (tests).
    pub fn wait(self) -> Result<u64, String> {
        self.job.wait().and_then(|r| r)
    }
}
