//! The animation export (one PNG per frame of the run) as a background job:
//! its settings dialog, start, cancel, progress polling and result.

use super::*;

impl App {
    /// Whether an animation export is running.
    pub fn exporting_frames(&self) -> bool {
        self.handles.frames_job.is_some()
    }

    /// Blocks until a running frames export ends; returns its result.
    pub fn wait_frames_export(&mut self) -> Option<Result<u64, String>> {
        let job = self.handles.frames_job.take()?;
        let dir = job.dir.clone();
        let cancelled = job.cancel_requested();
        let r = job.wait();
        self.frames_done(&dir, &r, cancelled);
        Some(r)
    }

    /// Says how the export ended, and where the frames went: a stop the
    /// user asked for (`cancelled`) is information, not an error.
    fn frames_done(&mut self, dir: &Path, r: &Result<u64, String>, cancelled: bool) {
        match r {
            Ok(n) => self.info(format!(
                "wrote {n} animation frames (frame_00000.png …) into {}",
                std::path::absolute(dir)
                    .unwrap_or_else(|_| dir.to_path_buf())
                    .display()
            )),
            Err(e) => {
                // the frames written before the stop stay: say where
                let kept = crate::output::animation::old_frames(dir).len();
                let at = std::path::absolute(dir).unwrap_or_else(|_| dir.to_path_buf());
                let text = format!(
                    "Animation export stopped: {e}. The {} written so far stay in {} \
                     (frame_00000.png …).",
                    crate::base::error::count(kept, "frame"),
                    at.display()
                );
                if cancelled {
                    self.info(text);
                } else {
                    self.error(text);
                }
            }
        }
    }

    pub(super) fn open_frames_dialog(&mut self) {
        if crate::gui::chrome::web::IN_BROWSER {
            return self.not_in_browser("Animation frames");
        }
        self.frames_dialog = Some(FramesDialog::for_scene(&self.doc.scene, self.sim.time_s()));
    }

    /// Starts the export of the current run (re-simulated from its start
    /// with its live edits) into `dir`.
    pub(super) fn export_frames(&mut self, dir: PathBuf, settings: FrameSettings, clear_old: bool) {
        if self.handles.frames_job.is_some() {
            self.error("an animation export is already running");
            return;
        }
        match FramesJob::spawn(
            dir,
            settings,
            self.run_start.clone(),
            &self.handles.mode_cache,
            self.live_edits.clone(),
            clear_old,
        ) {
            Ok(job) => {
                self.frames_dialog = None;
                // replaces an earlier message (a refusal) for the export
                self.info(format!(
                    "exporting {} animation frames into {} …",
                    settings.frame_count(),
                    std::path::absolute(&job.dir)
                        .unwrap_or_else(|_| job.dir.clone())
                        .display()
                ));
                self.handles.frames_job = Some(job);
            }
            Err(e) => self.error(format!("Animation export refused: {e}")),
        }
    }

    pub(super) fn cancel_frames(&self) {
        if let Some(job) = &self.handles.frames_job {
            job.cancel();
        }
    }

    /// Picks up the result of a finished export (once a frame).
    /// The frames export's end, once its job finished (never blocks).
    pub(super) fn poll_frames(&self) -> Option<Command> {
        let r = self.handles.frames_job.as_ref()?.poll()?;
        Some(Command::FramesExportEnded(r))
    }

    pub(super) fn frames_export_ended(&mut self, r: Result<u64, String>) {
        if let Some(job) = self.handles.frames_job.take() {
            self.frames_done(&job.dir, &r, job.cancel_requested());
        }
    }
}
