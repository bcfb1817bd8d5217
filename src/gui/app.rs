//! The app: owns the scene, the simulation, the history and the UI state.
//! `App::apply` is the one place where a `Command` changes anything: it
//! dispatches to the handlers of each concern, in the submodules of `app/`:
//! `files`, `run`, `mode_mutes`, `animation_export`, `research_tools`,
//! `session`, and the frame's `frame_loop` and `layout`.

use super::classroom::{self, Classroom};
use super::panels::{self, toolbar};
use super::views::{green_view, scene_view, time_plots};
use crate::base::modal::Mode;
use crate::gui::chrome::dialogs::{Message, PngSettings};
use crate::gui::chrome::file_prompt::{FileAction, FilePrompt};
use crate::gui::chrome::frames_dialog::FramesDialog;
use crate::gui::jobs::export::{CsvJob, LiveEdit};
use crate::gui::jobs::frames::FramesJob;
use crate::gui::model::command::{Command, Discarding, View};
use crate::gui::model::frame_rate::FrameRate;
use crate::gui::model::history::{DEFAULT_BUDGET, History};
use crate::gui::model::mute_set::Mutes;
use crate::gui::model::presets::GUIDED;
use crate::gui::model::presets::SHIPPED;
use crate::gui::model::time_control::{Speed, TimeControl};
use crate::gui::model::undo::{Direction, EditHistory};
use crate::identify::{ModeCache, PreparedModel};
use crate::output::animation::FrameSettings;
use crate::solver::phase::PhaseTracker;
use crate::{DEFAULT_PRESET, Scene, SceneError, Simulation, SolverOptions};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Duration;
use web_time::Instant;

mod animation_export;
pub(crate) mod files;
mod frame_loop;
mod layout;
mod mode_mutes;
mod research_tools;
mod run;
mod session;
mod share_link;

use files::default_scene;
pub use layout::NARROW_PX;
pub use run::PAUSED_NOTE;

pub struct App {
    /// What the session keeps: the scene, its file, the last saved version.
    pub(super) doc: Document,
    pub(super) sim: Simulation,
    /// The modal model of the scene: given, or identified from the ring tyre.
    pub(super) modes: Vec<Mode>,
    /// The scene the current run started from, and its live edits.
    run_start: Scene,
    live_edits: Vec<LiveEdit>,
    pub(super) history: History,
    pub(super) time: TimeControl,
    pub(super) view: View,
    /// In a narrow window, the editing panel is shown in place of the views.
    pub(super) edit_panel_open: bool,
    pub(super) message: Option<Message>,
    pub(super) confirm: Option<Discarding>,
    pub(super) png_dialog: Option<PngSettings>,
    allow_close: bool,
    quit_requested: bool,
    pub(super) plot_opts: time_plots::TimePlotOptions,
    pub(super) scene_opts: scene_view::SceneViewOptions,
    pub(super) green_opts: green_view::GreenOptions,
    pub(super) classroom: Classroom,
    /// Contact phase of every point (classroom labels).
    pub(super) phases: PhaseTracker,
    pub(super) mutes: Option<Mutes>,
    frames_dialog: Option<FramesDialog>,
    /// A save waiting for the answer to "overwrite this shipped preset?".
    pub(super) overwrite: Option<PathBuf>,
    /// The folder of the last file opened or saved (Save As offers it).
    pub(super) last_dir: Option<PathBuf>,
    /// Researcher tools: spectra, sweep, pinned run, fidelity.
    pub(super) research: super::research::ResearchState,
    /// The open, save or export file prompt, when shown.
    pub(super) file_prompt: Option<crate::gui::chrome::file_prompt::FilePrompt>,
    /// The banner text of the last field refusal (a good edit clears it).
    field_refusal: Option<String>,
    /// A new document came in, or an undo or redo changed the scene under
    /// the fields: the next frame forgets the fields' texts.
    forget_fields: bool,
    /// The scene edits to undo and redo, each with the mode mutes of its
    /// scene (the document's, never persisted).
    pub(super) undo: EditHistory<Option<Mutes>>,
    /// "Save first" saved the scene: what the save said, to be said with
    /// the message of the scene that replaces it.
    pub(super) saved_note: Option<String>,
    /// Work under way and caches: never persisted.
    pub(crate) handles: Handles,
}

/// The document: what a session keeps between runs of the app (with
/// classroom mode) and what Save writes.
pub(super) struct Document {
    pub(super) scene: Scene,
    /// The scene as last loaded or saved (for the unsaved-changes marker).
    pub(super) saved: Scene,
    pub(super) path: Option<PathBuf>,
    /// Opened from a scene link (until it is saved or replaced).
    pub(super) from_link: bool,
}

/// What the app holds while it runs and never persists: background jobs,
/// the identified rings, the window title and the frame rate.
pub(crate) struct Handles {
    pub(super) csv_job: Option<CsvJob>,
    pub(super) frames_job: Option<FramesJob>,
    /// An edit or a new document waiting for its ring's identification.
    /// The preparation an edit or a document waits for, and its banner.
    pub(super) prepare_job: Option<(crate::gui::jobs::prepare::PrepareJob, String)>,
    /// The rings identified so far (shared with the identification job).
    pub(crate) mode_cache: Arc<ModeCache>,
    pub(super) title: String,
    pub(super) fps: FrameRate,
    /// The link of the last Share, and whether the frame still has to
    /// copy it to the clipboard.
    pub(super) shared_link: Option<String>,
    pub(super) copy_link: bool,
    /// The last Share's link is shown in its window (to copy by hand).
    pub(super) link_shown: bool,
    /// Steps taken between the last two frames and how they ended, for
    /// this frame's [`Command::Advance`].
    pub(super) stepped_ahead: Option<(u64, Result<u64, crate::solver::error::RunError>)>,
    /// While the run steps between frames: the wait before the next frame
    /// (s), so that drawing leaves the solver its share of the cores.
    pub(super) paced_delay_s: Option<f64>,
    pub(super) pacer: crate::gui::model::time_control::FramePacer,
    /// The window is drawn by a software renderer (frames are paced).
    pub(super) software_renderer: bool,
    /// A pointer button was held down at the last frame (the edits of one
    /// drag make one undo step).
    pub(super) pointer_down: bool,
    /// Where the status bar was drawn in the last frame.
    pub(super) status_rect: egui::Rect,
    /// Another scene came in: the editing panel scrolls back to its top
    /// when next drawn.
    pub(super) editor_to_top: bool,
    /// The thread that steps the run between frames at "as fast as
    /// possible", and the stand-in state the app holds while it is lent.
    #[cfg(not(target_arch = "wasm32"))]
    pub(super) run_ahead: Option<crate::gui::jobs::run_ahead::RunAhead>,
    #[cfg(not(target_arch = "wasm32"))]
    pub(super) spare: Option<Box<crate::gui::jobs::run_ahead::Live>>,
}

/// The simulation of `scene` and its modes, the ring's identification
/// taken from (or kept in) `cache`.
pub(super) fn build(
    scene: &Scene,
    cache: &ModeCache,
) -> Result<(Simulation, Vec<Mode>), SceneError> {
    let model = PreparedModel::new(scene, cache)?;
    let sim = model.simulation(SolverOptions::default())?;
    Ok((sim, model.modes().to_vec()))
}

impl App {
    /// An app on `scene` (already validated), loaded from `path` if any.
    pub fn new(scene: Scene, path: Option<PathBuf>) -> Result<Self, String> {
        let mode_cache = Arc::new(ModeCache::new());
        let (sim, modes) = build(&scene, &mode_cache).map_err(|e| e.to_string())?;
        let mut history = History::new(scene.num_points(), DEFAULT_BUDGET);
        history.record_initial(&sim);
        let phases = PhaseTracker::new(scene.num_points(), 0.0);
        let mut time = TimeControl::default();
        time.set_speed(Speed::watchable(scene.duration_s));
        Ok(App {
            modes,
            run_start: scene.clone(),
            doc: Document {
                saved: scene.clone(),
                scene,
                path,
                from_link: false,
            },
            sim,
            live_edits: Vec::new(),
            history,
            time,
            view: View::default(),
            edit_panel_open: false,
            message: None,
            confirm: None,
            png_dialog: None,
            allow_close: false,
            quit_requested: false,
            plot_opts: Default::default(),
            scene_opts: Default::default(),
            green_opts: Default::default(),
            classroom: Classroom::default(),
            phases,
            mutes: None,
            frames_dialog: None,
            overwrite: None,
            last_dir: None,
            research: Default::default(),
            file_prompt: None,
            field_refusal: None,
            forget_fields: false,
            undo: EditHistory::default(),
            saved_note: None,
            handles: Handles {
                csv_job: None,
                frames_job: None,
                prepare_job: None,
                mode_cache,
                title: String::new(),
                fps: FrameRate::new(),
                shared_link: None,
                copy_link: false,
                link_shown: false,
                stepped_ahead: None,
                paced_delay_s: None,
                pacer: Default::default(),
                software_renderer: false,
                pointer_down: false,
                status_rect: egui::Rect::NOTHING,
                editor_to_top: false,
                #[cfg(not(target_arch = "wasm32"))]
                run_ahead: None,
                #[cfg(not(target_arch = "wasm32"))]
                spare: None,
            },
        })
    }

    /// Says that the window is drawn by a software renderer
    /// ([`crate::gui::model::time_control::is_software_renderer`]).
    pub fn set_software_renderer(&mut self, software: bool) {
        self.handles.software_renderer = software;
    }

    /// The app on the embedded default preset.
    pub fn with_default_preset() -> Self {
        let scene = default_scene();
        match App::new(scene, None) {
            Ok(app) => app,
            // the embedded preset is tested to build; this is unreachable in practice
            Err(e) => panic!("embedded default preset does not build: {e}"),
        }
    }

    pub fn scene(&self) -> &Scene {
        &self.doc.scene
    }
    /// The modal model in use (given, or identified from the ring tyre).
    pub fn modes(&self) -> &[Mode] {
        &self.modes
    }
    /// The run. Between two frames of [`App::frame`] that play "as fast
    /// as possible" it is with the stepping thread: [`App::reclaim_run`]
    /// takes it back.
    pub fn simulation(&self) -> &Simulation {
        &self.sim
    }
    pub fn history(&self) -> &History {
        &self.history
    }
    /// The time plots' options (window, shown points).
    pub fn plot_options(&self) -> &time_plots::TimePlotOptions {
        &self.plot_opts
    }
    /// The scene view's options (exaggeration, legend).
    pub fn scene_options(&self) -> &scene_view::SceneViewOptions {
        &self.scene_opts
    }
    pub fn time_control(&self) -> &TimeControl {
        &self.time
    }
    /// Whether classroom mode is on.
    pub fn classroom(&self) -> bool {
        self.classroom.on
    }
    /// Contact phases of the points in the current run.
    pub fn phases(&self) -> &PhaseTracker {
        &self.phases
    }
    /// Muted modes (`None`: every mode plays, the scene's own tyre).
    pub fn mutes(&self) -> Option<&Mutes> {
        self.mutes.as_ref()
    }
    pub fn message(&self) -> Option<&Message> {
        self.message.as_ref()
    }
    /// Where the status bar was drawn in the last frame (points).
    pub fn status_bar_rect(&self) -> egui::Rect {
        self.handles.status_rect
    }
    pub fn is_dirty(&self) -> bool {
        self.doc.scene != self.doc.saved
    }
    /// What changed since the scene was opened or saved, in words with
    /// units (the description was written before it); none once the user
    /// edited the description itself (the text is then theirs).
    pub fn edits(&self) -> Vec<String> {
        if self.doc.scene.description != self.doc.saved.description {
            return Vec::new();
        }
        self.changes()
    }
    /// What changed since the scene was opened or saved; a ring tyre made
    /// a modal model is compared through its identified modes.
    pub(crate) fn changes(&self) -> Vec<String> {
        let identified = self.handles.mode_cache.identified(&self.doc.saved);
        crate::scene::edits_since_identified(
            &self.doc.saved,
            identified.as_deref().map(Vec::as_slice),
            &self.doc.scene,
        )
    }
    pub fn pending_confirmation(&self) -> Option<&Discarding> {
        self.confirm.as_ref()
    }
    /// The main view shown.
    pub fn view(&self) -> View {
        self.view
    }
    /// The file prompt (open, save as, CSV export), when shown.
    pub fn file_prompt(&self) -> Option<&FilePrompt> {
        self.file_prompt.as_ref()
    }

    /// Window title: scene name, file, and `*` when there are unsaved changes.
    pub fn title(&self) -> String {
        let file = self.doc.path.as_deref().and_then(Path::file_name).map_or(
            if self.doc.from_link {
                "from a link"
            } else {
                "built-in preset"
            }
            .to_string(),
            |n| n.to_string_lossy().into_owned(),
        );
        format!(
            "{}{} ({file}) — tirecontact",
            if self.is_dirty() { "* " } else { "" },
            self.doc.scene.name
        )
    }

    fn info(&mut self, text: impl Into<String>) {
        self.message = Some(Message {
            error: false,
            text: text.into(),
        });
    }
    fn error(&mut self, text: impl Into<String>) {
        // (a save's note waits for the scene that follows it, not a failure)
        self.saved_note = None;
        self.message = Some(Message {
            error: true,
            text: text.into(),
        });
    }

    /// Runs one command. The only place the app's state changes: each arm
    /// hands over to the handler of its concern.
    pub fn apply(&mut self, cmd: Command) {
        match cmd {
            // the run (app/run.rs)
            Command::Play => self.play(),
            Command::Pause => self.time.pause(),
            Command::TogglePlay => self.toggle_play(),
            Command::Step(n) => self.time.step(n),
            Command::Reset => self.reset_run(),
            Command::Advance { frame_s } => self.advance(frame_s),
            Command::PreparationEnded(r) => self.preparation_ended(r),
            Command::CancelPreparation => self.cancel_preparation(),
            Command::CancelCsvExport => self.cancel_csv_export(),
            Command::SetSpeed(s) => self.time.set_speed(s),
            Command::EditScene(scene) => self.edit(*scene),
            Command::Undo => self.undo_redo(Direction::Undo),
            Command::Redo => self.undo_redo(Direction::Redo),
            // the document and its files (app/files.rs)
            Command::New => self.guard(Discarding::New),
            // the file first, then the unsaved-changes guard (OpenPath)
            Command::OpenDialog => self.open_file_prompt(FileAction::Open),
            Command::OpenPath(p) => self.guard(Discarding::OpenPath(p)),
            Command::OpenText { name, text } => self.guard(Discarding::Text { name, text }),
            Command::OpenPreset(k) => self.guard(Discarding::Preset(k)),
            Command::OpenGuided(k) => self.guard(Discarding::Guided(k)),
            Command::Quit => self.guard(Discarding::Quit),
            Command::ConfirmDiscard => self.confirm_discard(),
            Command::CancelDiscard => self.confirm = None,
            Command::Save => self.save_document(),
            Command::SaveAsDialog => self.save_as_dialog(),
            Command::SavePath(p) => self.save_to(&p),
            Command::ConfirmOverwrite => {
                if let Some(p) = self.overwrite.take() {
                    self.write_scene(&p);
                }
            }
            Command::CancelOverwrite => self.overwrite = None,
            Command::CloseLink => self.handles.link_shown = false,
            Command::ExportPngDialog => self.open_png_dialog(),
            Command::ExportPng {
                path,
                width,
                height,
            } => self.export_png(&path, width, height),
            Command::ExportCsvDialog => self.export_csv_dialog(),
            Command::ExportHeatMapDialog => self.open_file_prompt(FileAction::HeatMapPng),
            Command::ExportHeatMap(path) => self.export_heat_map(&path),
            Command::ExportCsv(path) => self.export_csv(path),
            Command::CsvExportEnded(r) => self.csv_export_ended(r),
            // views and layouts (app/layout.rs)
            Command::DismissMessage => self.message = None,
            Command::ShowView(v) => self.show_view(v),
            Command::ShowEditPanel(open) => self.edit_panel_open = open,
            Command::ShowPoints(points) => {
                let p = self.doc.scene.num_points();
                self.plot_opts.shown = (0..p).map(|i| points.contains(&i)).collect();
                self.show_view(View::TimePlots);
            }
            Command::SetClassroom(on) => self.set_classroom(on),
            Command::ShowModeBars(on) => self.classroom.bars = on,
            // mode mute and solo (app/mode_mutes.rs)
            Command::ToggleMute(k) => self.set_mutes(k, false),
            Command::SoloMode(k) => self.set_mutes(k, true),
            Command::MuteWithCompliantContact => {
                if let Some(r) = self.classroom.mute_refused.take() {
                    self.clear_refusal(Some(r.clone()));
                    let contact = crate::scene::Contact::Compliant {
                        stiffness_n_m: vec![crate::gui::panels::contact_panel::DEFAULT_TREAD_N_M],
                    };
                    self.set_mutes_with(r.mode, r.solo, Some(contact));
                }
            }
            Command::DismissMuteRefusal => {
                let refused = self.classroom.mute_refused.take();
                self.clear_refusal(refused);
            }
            Command::UnmuteAll => self.unmute_all(),
            // animation export (app/animation_export.rs)
            Command::ExportFramesDialog => self.open_frames_dialog(),
            Command::ExportFrames {
                dir,
                settings,
                clear_old,
            } => self.export_frames(dir, settings, clear_old),
            Command::CancelFrames => self.cancel_frames(),
            Command::FramesExportEnded(r) => self.frames_export_ended(r),
            // researcher tools (app/research_tools.rs)
            Command::Research(c) => self.apply_research(c),
            // a field's refusal (app/run.rs)
            Command::FieldRefused { field: _, text } => self.field_refused(text),
            Command::FieldRestored { field } => self.field_restored(&field),
            Command::SaveFirst => self.save_first(),
            Command::Share => self.share(),
            Command::ContinueAfterSave(d) => {
                if !self.is_dirty() && self.overwrite.is_none() {
                    self.discard_after_save(d);
                }
            }
        }
        self.end_mutes_on_other_edits();
    }

    /// Measured frames per second (0 until a second has passed).
    pub fn fps(&self) -> f64 {
        self.handles.fps.fps
    }

    /// Mean time per frame spent in solver steps and UI code (ms).
    pub fn app_ms(&self) -> f64 {
        self.handles.fps.app_ms
    }
}
