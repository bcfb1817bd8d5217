//! The researcher tools' side of `App::apply` and of the frame loop.

use super::App;
use crate::analysis::compare::PinnedRun;
use crate::analysis::spectrum::Window;
use crate::gui::chrome::dialogs::Message;
use crate::gui::chrome::file_prompt::{FileAction, FilePrompt};
use crate::gui::model::command::{Command, ResearchCommand, View};
use crate::gui::model::sweep_request::SweepEnd;
use crate::gui::research::ResearchState;
use crate::gui::research::compare::{pin_label, recording_without_impacts};
use crate::gui::research::fidelity::FidelityRef;
use crate::gui::research::fidelity_job::FidelityJob;
use crate::gui::research::spectra::{HistoryKey, SpectraInput};
use crate::gui::research::spectra_job::{INLINE_MAX_WORK, SpectraJob, SpectraPoll};
use crate::gui::research::sweep_job::default_threads;
use crate::gui::research::workbench_job::{WorkbenchJob, key_of, scene_key};
use crate::gui::views::{
    compare_view, fidelity_view, spectra_view, sweep_view, wall_time_text, workbench_view,
};
use std::path::Path;

impl App {
    /// The researcher tools' state (spectra, sweep, pinned run, fidelity).
    pub fn research(&self) -> &ResearchState {
        &self.research
    }

    fn research_message(&mut self, error: bool, text: impl Into<String>) {
        self.message = Some(Message {
            error,
            text: text.into(),
        });
    }

    /// Runs one researcher-tool command (called from `App::apply`). Long
    /// but flat: one short arm per command.
    pub(crate) fn apply_research(&mut self, cmd: ResearchCommand) {
        match cmd {
            ResearchCommand::RecomputeSpectra => self.research.spectra_now = true,
            ResearchCommand::StartSweep(req) => {
                let text = format!(
                    "sweep of {} from {} to {} {} in {} steps started",
                    crate::scene::fields::label(&req.param),
                    req.from,
                    req.to,
                    crate::scene::fields::unit(&req.param).unwrap_or(""),
                    req.steps
                );
                match self.research.sweep.start(
                    &self.doc.scene,
                    req,
                    default_threads(),
                    std::sync::Arc::clone(&self.handles.mode_cache),
                ) {
                    Ok(()) => self.research_message(false, text),
                    Err(e) => self.research_message(true, format!("Sweep refused: {e}")),
                }
            }
            ResearchCommand::CancelSweep => {
                if self.research.sweep.is_running() {
                    self.research.sweep.cancel();
                    self.research_message(false, "cancelling the sweep …");
                }
            }
            ResearchCommand::ExportSweepCsvDialog => {
                self.file_prompt = Some(FilePrompt::new(FileAction::SweepCsv, "sweep.csv"));
            }
            ResearchCommand::ExportSweepCsv(path) => {
                let r = match self.research.sweep.result() {
                    Some(res) => {
                        let mut buf = Vec::new();
                        crate::studies::sweep::report::write_csv(
                            &mut buf,
                            &res.request.param,
                            &res.points,
                            &res.columns,
                        )
                        .map_err(|e| e.to_string())
                        .and_then(|()| write_file(&path, &buf))
                    }
                    None => Err("no finished sweep to export".into()),
                };
                self.report_export(&path, "sweep CSV", r);
            }
            // in a browser: the PNG's bytes offered as a download
            ResearchCommand::ExportSweepPngDialog if crate::gui::chrome::web::IN_BROWSER => {
                let r = self.sweep_figure().and_then(|fig| {
                    let (w, h) = crate::studies::sweep::report::FIGURE_PX;
                    crate::output::figures::render_png_bytes(&fig, w, h).map_err(|e| e.to_string())
                });
                match r {
                    Ok(bytes) => {
                        crate::gui::chrome::web::download("sweep.png", bytes);
                        self.research_message(false, "sweep.png offered as a download");
                    }
                    Err(e) => self.research_message(true, format!("sweep PNG export failed: {e}")),
                }
            }
            ResearchCommand::ExportSweepPngDialog => {
                self.file_prompt = Some(FilePrompt::new(FileAction::SweepPng, "sweep.png"));
            }
            ResearchCommand::ExportSweepPng(path) => {
                // the size of `sweep --plot`'s figure: at 1400 × 1400 the
                // y titles were longer than their plots
                let r = self.sweep_figure().and_then(|fig| {
                    let (w, h) = crate::studies::sweep::report::FIGURE_PX;
                    crate::output::figures::render_png(&fig, &path, w, h).map_err(|e| e.to_string())
                });
                self.report_export(&path, "sweep PNG", r);
            }
            ResearchCommand::PinReference => {
                let rec = self.history.to_recording();
                let label = pin_label(&self.doc.scene, self.sim.time_s());
                let n = self.modes.len();
                self.research.pinned =
                    Some(PinnedRun::new(label.clone(), &self.doc.scene, n, &rec));
                self.research.pinned_without_impacts = Some(PinnedRun::new(
                    label.clone(),
                    &self.doc.scene,
                    n,
                    &recording_without_impacts(&self.history),
                ));
                self.research.difference_without_impacts.invalidate();
                self.research.difference.invalidate();
                self.research_message(false, format!("pinned as reference: {label}"));
            }
            ResearchCommand::Unpin => {
                self.research.pinned = None;
                self.research.pinned_without_impacts = None;
                self.research.difference_without_impacts.invalidate();
                self.research.difference.invalidate();
                self.research_message(false, "reference unpinned");
            }
            ResearchCommand::ExportPinnedCsvDialog => {
                // a typed path, or the desktop's dialog through "Choose…"
                // (the dialog alone did nothing where there is none)
                self.file_prompt = Some(FilePrompt::new(FileAction::PinnedCsv, "reference.csv"));
            }
            ResearchCommand::ExportPinnedCsv(path) => {
                let r = match &self.research.pinned {
                    Some(pin) => {
                        let mut buf = Vec::new();
                        pin.write_csv(&mut buf)
                            .map_err(|e| e.to_string())
                            .and_then(|()| write_file(&path, &buf))
                    }
                    None => Err("no pinned run to export".into()),
                };
                self.report_export(&path, "reference CSV", r);
            }
            ResearchCommand::WorkbenchToggle(at) => self.workbench_do(|w| w.toggle(at)),
            ResearchCommand::WorkbenchAutomatic => self.workbench_do(|w| w.automatic()),
            ResearchCommand::WorkbenchUse => {
                if let Some(modal) = self.workbench_scene() {
                    let n = match &modal.tyre {
                        crate::scene::Tyre::Modal { modes } => modes.len(),
                        _ => 0,
                    };
                    let used = scene_key(&modal);
                    self.apply(Command::EditScene(Box::new(modal)));
                    self.research.workbench_used = Some(used);
                    self.research_message(
                        false,
                        format!("the scene's tyre is now the {n} modes picked on the workbench"),
                    );
                }
            }
            ResearchCommand::WorkbenchSaveDialog => {
                let stem = super::files::file_stem(&self.doc.scene.name);
                self.file_prompt = Some(FilePrompt::new(
                    FileAction::ModalPreset,
                    format!("{stem}_modal.ron"),
                ));
            }
            ResearchCommand::WorkbenchSave(path) => {
                let r = match self.workbench_scene() {
                    Some(s) => s.save(&path).map_err(|e| e.to_string()),
                    None => Err("no picked modes to save".into()),
                };
                self.report_export(&path, "modal preset", r);
            }
            ResearchCommand::SweepEnded(end) => self.sweep_ended(end),
            ResearchCommand::Refresh => self.research_refresh(),
        }
    }

    /// The figure of the finished sweep.
    fn sweep_figure(&self) -> Result<crate::output::figures::Figure, String> {
        let res = self
            .research
            .sweep
            .result()
            .ok_or("no finished sweep to export")?;
        Ok(crate::studies::sweep::report::figure(
            &format!(
                "{}: sweep of {}",
                res.base.name,
                crate::scene::fields::label(&res.request.param)
            ),
            &crate::studies::sweep::report::sweep_subtitle(
                &res.request.param,
                res.points.len(),
                res.request.from,
                res.request.to,
            ),
            &res.request.param,
            &res.points,
            &res.columns,
        ))
    }

    fn report_export(&mut self, path: &Path, what: &str, r: Result<(), String>) {
        match r {
            Ok(()) => self.research_message(false, format!("wrote {} ({what})", path.display())),
            Err(e) => self.research_message(true, format!("{what} export failed: {e}")),
        }
    }

    /// A new document (opened or new scene): a held ring reference belongs
    /// to the old one, and so does a cancelled or failed sweep's note (a
    /// finished sweep's results stay: they name their scene).
    pub(crate) fn research_new_document(&mut self) {
        self.research.fidelity_ref = FidelityRef::of_scene(&self.doc.scene);
        self.research.workbench_used = None;
        self.research.sweep.new_document();
    }

    /// The research jobs' ends this frame, as commands (never blocks).
    pub(crate) fn research_polls(&self) -> Vec<Command> {
        let mut cmds = Vec::new();
        if let Some(end) = self.research.sweep.ended() {
            cmds.push(Command::Research(ResearchCommand::SweepEnded(end)));
        }
        cmds
    }

    /// Applies `f` to the workbench (a pick, a drop, the automatic choice).
    fn workbench_do(
        &mut self,
        f: impl FnOnce(
            &mut crate::identify::workbench::Workbench,
        ) -> Result<(), crate::model::lsce::LsceError>,
    ) {
        let r = match &mut self.research.workbench {
            Some((_, Ok(w))) => f(w).map_err(|e| e.to_string()),
            _ => Err("no identification on the workbench".into()),
        };
        if let Err(e) = r {
            self.research_message(true, format!("workbench: {e}"));
        }
    }

    /// The scene with the workbench's picked modes as its modal tyre.
    fn workbench_scene(&self) -> Option<crate::Scene> {
        let Some((_, Ok(w))) = &self.research.workbench else {
            return None;
        };
        if w.modes.is_empty() {
            return None;
        }
        let mut s = self.doc.scene.clone();
        s.tyre = crate::scene::Tyre::Modal {
            modes: w.modes.clone(),
        };
        Some(s)
    }

    /// The workbench of the scene's tyre: kept while the tyre and points
    /// stay, else identified again on a background thread.
    fn update_workbench(&mut self) {
        if let Some(job) = &self.research.workbench_job
            && let Some(r) = job.poll()
        {
            let key = job.key.clone();
            self.research.workbench = Some((key, r.bench));
            self.research.frf_fit = r.frf;
            self.research.workbench_job = None;
        }
        let used = self.research.workbench_used.as_ref();
        if used.is_some_and(|u| *u == scene_key(&self.doc.scene)) {
            // the scene's tyre is the workbench's choice: keep it to refine
            return;
        }
        self.research.workbench_used = None;
        let Some(key) = key_of(&self.doc.scene) else {
            self.research.workbench = None;
            self.research.frf_fit = None;
            self.research.workbench_job = None;
            return;
        };
        let fresh = self.research.workbench.as_ref().is_some_and(|w| w.0 == key);
        let running = self
            .research
            .workbench_job
            .as_ref()
            .is_some_and(|j| j.key == key);
        if !fresh && !running {
            match WorkbenchJob::spawn(&self.doc.scene, key.clone()) {
                Ok(job) => self.research.workbench_job = Some(job),
                Err(e) => {
                    self.research.workbench = Some((key, Err(e)));
                    self.research.frf_fit = None;
                }
            }
        }
    }

    /// Whether a research job runs (the frame loop then asks for frames).
    pub(crate) fn research_busy(&self) -> bool {
        self.research.sweep.is_running()
            || (self.view == View::Spectra && self.research.spectra_job.is_some())
            || (self.view == View::Fidelity && self.research.fidelity_job.is_some())
            || (self.view == View::Workbench && self.research.workbench_job.is_some())
    }

    /// A sweep's end: its outcome kept (a cancelled or failed sweep keeps
    /// the last finished one's results), and said in the banner.
    fn sweep_ended(&mut self, end: SweepEnd) {
        let (error, text) = match &end {
            SweepEnd::Done(r) => (
                false,
                format!(
                    "sweep of {} done: {} runs ({} failed) on {} threads in {}",
                    crate::scene::fields::label(&r.request.param),
                    r.points.len(),
                    r.failed(),
                    r.threads,
                    wall_time_text(r.wall_s)
                ),
            ),
            SweepEnd::Cancelled => (false, "sweep cancelled".to_string()),
            SweepEnd::Failed(e) => (true, format!("sweep failed: {e}")),
        };
        let done = matches!(end, SweepEnd::Done(_));
        let (_, kept) = self.research.sweep.end(end);
        let text = match (done, kept) {
            (true, _) => text,
            (false, true) => format!("{text}; the previous sweep's results are kept"),
            (false, false) => format!("{text}; no results kept, the app is unchanged"),
        };
        self.research_message(error, text);
    }

    /// Follows the scene's ring reference and refreshes what the shown view
    /// needs ([`ResearchCommand::Refresh`]). Never blocks.
    fn research_refresh(&mut self) {
        let held = self.research.fidelity_ref.take();
        self.research.fidelity_ref = FidelityRef::follow(held, &self.doc.scene);
        let key = HistoryKey::of(&self.history);
        let playing = self.time.is_playing();
        self.poll_spectra(&key);
        match self.view {
            View::Spectra => {
                let force = std::mem::take(&mut self.research.spectra_now);
                let auto = self.research.spectra_opts.auto || !playing;
                // a computation under way counts as done for staleness
                let basis = (self.research.spectra_job.as_ref()).map(|j| j.key).or(self
                    .research
                    .spectra
                    .key()
                    .copied());
                let stale = self
                    .research
                    .spectra
                    .stale_since(basis.as_ref(), &key, playing);
                if force || (auto && stale) {
                    self.start_spectra(key);
                }
            }
            View::Compare => {
                let points = &self.doc.scene.points;
                if let Some(pin) = &self.research.pinned {
                    let h = &self.history;
                    self.research.difference.refresh(key, playing, false, || {
                        pin.difference(points, &h.to_recording())
                    });
                }
                if let Some(pin) = &self.research.pinned_without_impacts {
                    let h = &self.history;
                    self.research
                        .difference_without_impacts
                        .refresh(key, playing, false, || {
                            pin.difference(points, &recording_without_impacts(h))
                        });
                }
            }
            View::Fidelity => self.update_fidelity(),
            View::Workbench => self.update_workbench(),
            _ => {}
        }
    }

    /// The fidelity figures of the modes in use, computed on a background
    /// thread: a finished job's figures are kept if they are still those of
    /// the scene; a job for modes edited since is replaced (and cancelled).
    fn update_fidelity(&mut self) {
        let Some(r) = self.research.fidelity_ref.clone() else {
            self.research.fidelity_job = None;
            return;
        };
        let x: Vec<f64> = self.doc.scene.points.iter().map(|p| p.x_m).collect();
        if let Some(job) = &self.research.fidelity_job
            && let Some(result) = job.poll()
        {
            if job.is_for(&r, &x, &self.modes) {
                let key = job.key.clone();
                self.research.fidelity.set(key, result);
            }
            self.research.fidelity_job = None;
        }
        let wanted = self
            .research
            .fidelity
            .current(&r, &x, &self.modes)
            .is_none();
        let under_way =
            (self.research.fidelity_job.as_ref()).is_some_and(|j| j.is_for(&r, &x, &self.modes));
        if wanted && !under_way {
            let key = (r, x, self.modes.clone());
            match FidelityJob::spawn(key.clone()) {
                Ok(job) => {
                    self.research.fidelity_job = Some(job);
                    self.research.fidelity_jobs += 1;
                }
                // shown in the view, not retried every frame
                Err(e) => self.research.fidelity.set(key, Err(e)),
            }
        }
    }

    /// Picks up the spectra of a finished background job (a stale one is
    /// dropped).
    fn poll_spectra(&mut self, now: &HistoryKey) {
        let Some(job) = &self.research.spectra_job else {
            return;
        };
        match job.poll(now) {
            SpectraPoll::Running => {}
            SpectraPoll::Done(r) => {
                let key = job.key;
                self.research.spectra_job = None;
                self.research.spectra.set(key, *r);
            }
            SpectraPoll::Stale => self.research.spectra_job = None,
        }
    }

    /// Computes the spectra of the history `key`: at once when short, else
    /// on a background thread (replacing, and so cancelling, a running one).
    fn start_spectra(&mut self, key: HistoryKey) {
        self.research.spectra_job = None;
        let input = SpectraInput::of_history(&self.history, self.doc.scene.ramp_s, self.sim.dt_s());
        let r = match input {
            Ok(input) if input.work() > INLINE_MAX_WORK => {
                match SpectraJob::spawn(key, input, Window::Hann) {
                    Ok(job) => {
                        self.research.spectra_job = Some(job);
                        self.research.spectra_jobs += 1;
                        return;
                    }
                    Err(e) => Err(e),
                }
            }
            Ok(input) => input.compute(Window::Hann, &|| false, &|| {}),
            Err(e) => Err(e),
        };
        self.research.spectra.set(key, r);
    }

    /// Draws the researcher view `self.view` (views only read the app; they
    /// change their own presentation options and push commands).
    pub(crate) fn show_research_view(&mut self, ui: &mut egui::Ui, cmds: &mut Vec<Command>) {
        match self.view {
            View::Spectra => spectra_view::show(
                ui,
                &self.doc.scene,
                &self.modes,
                &self.research.spectra,
                self.research.spectra_computing(),
                &mut self.research.spectra_opts,
                self.time.is_playing(),
                cmds,
            ),
            View::Sweep => sweep_view::show(
                ui,
                &self.doc.scene,
                &self.research.sweep,
                &mut self.research.sweep_form,
                cmds,
            ),
            View::Compare => compare_view::show(
                ui,
                &compare_view::Compared {
                    history: &self.history,
                    scene: &self.doc.scene,
                    num_modes: self.modes.len(),
                    pinned: self.research.pinned.as_ref(),
                    pinned_smooth: self.research.pinned_without_impacts.as_ref(),
                    diff: self.research.difference.get(),
                    diff_smooth: self.research.difference_without_impacts.get(),
                },
                &mut self.research.compare_opts,
                cmds,
            ),
            View::Fidelity => fidelity_view::show(
                ui,
                &self.doc.scene,
                &self.modes,
                self.research.fidelity_ref.as_ref(),
                self.research.fidelity_ref.as_ref().and_then(|r| {
                    let x: Vec<f64> = self.doc.scene.points.iter().map(|p| p.x_m).collect();
                    self.research.fidelity.current(r, &x, &self.modes)
                }),
                self.research.fidelity_computing(),
                &mut self.research.fidelity_opts,
            ),
            View::Workbench => workbench_view::show(
                ui,
                &workbench_view::Shown {
                    scene: &self.doc.scene,
                    bench: self.research.workbench(),
                    frf: self.research.frf_fit(),
                    computing: self.research.workbench_computing(),
                    in_use: self.research.workbench_in_use(),
                    run_modes: self.modes.len(),
                },
                cmds,
            ),
            _ => {}
        }
    }
}

fn write_file(path: &Path, bytes: &[u8]) -> Result<(), String> {
    crate::fsio::write_atomic(path, bytes).map_err(|e| format!("{}: {e}", path.display()))
}
