//! The app: owns the scene, the simulation, the history and the UI state.
//! `App::apply` is the one place where a `Command` changes anything.

use super::classroom::{self, Classroom};
use super::command::{Command, Discarding, View};
use super::export::{CsvJob, LiveEdit};
use super::frame_rate::FrameRate;
use super::frames::{FramesDialog, FramesJob};
use super::guided::GUIDED;
use super::history::{DEFAULT_BUDGET, History};
use super::mutes::{self, Mutes};
use super::panels::{self, toolbar};
use super::presets::SHIPPED;
use super::time_control::TimeControl;
use super::views::{green_view, scene_view, time_plots};
use crate::phase::PhaseTracker;
use crate::scene::Mode;
use crate::{DEFAULT_PRESET, Scene, Simulation};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

mod layout;

/// Wall time per frame the solver may use (keeps the UI above 30 fps).
pub const STEP_BUDGET: Duration = Duration::from_millis(12);
/// eframe storage key of the last session.
const SESSION_KEY: &str = "tirecontact.session";

/// A message shown in the banner above the views.
#[derive(Debug, Clone, PartialEq)]
pub struct Message {
    pub error: bool,
    pub text: String,
}

/// What is persisted between sessions.
#[derive(Debug, Serialize, Deserialize)]
struct Session {
    scene_ron: String,
    path: Option<PathBuf>,
    dirty: bool,
}

/// Settings of the PNG export dialog.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PngSettings {
    pub width: u32,
    pub height: u32,
}

pub struct App {
    pub(super) scene: Scene,
    /// The scene as last loaded or saved (for the unsaved-changes marker).
    saved: Scene,
    pub(super) path: Option<PathBuf>,
    pub(super) sim: Simulation,
    /// The modal model of the scene: given, or identified from the ring tyre.
    pub(super) modes: Vec<Mode>,
    /// The scene the current run started from, and its live edits.
    run_start: Scene,
    live_edits: Vec<LiveEdit>,
    pub(super) history: History,
    pub(super) time: TimeControl,
    pub(super) view: View,
    pub(super) message: Option<Message>,
    pub(super) confirm: Option<Discarding>,
    pub(super) png_dialog: Option<PngSettings>,
    csv_job: Option<CsvJob>,
    allow_close: bool,
    quit_requested: bool,
    pub(super) plot_opts: time_plots::TimePlotOptions,
    pub(super) scene_opts: scene_view::SceneViewOptions,
    pub(super) green_opts: green_view::GreenOptions,
    title: String,
    fps: FrameRate,
    pub(super) classroom: Classroom,
    /// Contact phase of every point (classroom labels).
    pub(super) phases: PhaseTracker,
    pub(super) mutes: Option<Mutes>,
    frames_dialog: Option<FramesDialog>,
    frames_job: Option<FramesJob>,
    /// Researcher tools: spectra, sweep, pinned run, fidelity (issue #8).
    pub(super) research: super::research::ResearchState,
}

impl App {
    /// An app on `scene` (already validated), loaded from `path` if any.
    pub fn new(scene: Scene, path: Option<PathBuf>) -> Result<Self, String> {
        let sim = Simulation::new(&scene).map_err(|e| e.to_string())?;
        let mut history = History::new(scene.num_points(), DEFAULT_BUDGET);
        history.record_initial(&sim);
        let modes = scene.modes().map_err(|e| e.to_string())?;
        let phases = PhaseTracker::new(scene.num_points(), 0.0);
        let mut time = TimeControl::default();
        time.set_speed(super::time_control::Speed::watchable(scene.duration_s));
        Ok(App {
            modes,
            saved: scene.clone(),
            run_start: scene.clone(),
            scene,
            path,
            sim,
            live_edits: Vec::new(),
            history,
            time,
            view: View::default(),
            message: None,
            confirm: None,
            png_dialog: None,
            csv_job: None,
            allow_close: false,
            quit_requested: false,
            plot_opts: Default::default(),
            scene_opts: Default::default(),
            green_opts: Default::default(),
            title: String::new(),
            fps: FrameRate::new(),
            classroom: Classroom::default(),
            phases,
            mutes: None,
            frames_dialog: None,
            frames_job: None,
            research: Default::default(),
        })
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

    /// The last session from eframe's storage, else the default preset.
    pub fn restore(storage: Option<&dyn eframe::Storage>) -> Self {
        let session = storage
            .and_then(|s| s.get_string(SESSION_KEY))
            .and_then(|text| ron::from_str::<Session>(&text).ok());
        if let Some(s) = session {
            let file = s
                .path
                .as_ref()
                .map_or("(last session)".to_string(), |p| p.display().to_string());
            if let Ok(mut scene) = Scene::parse(&s.scene_ron, &file) {
                scene.base_dir = s
                    .path
                    .as_deref()
                    .and_then(Path::parent)
                    .map(Path::to_path_buf);
                if let Ok(mut app) = App::new(scene, s.path.clone()) {
                    if s.dirty {
                        // the saved version is the file's, if it still reads
                        app.saved = s
                            .path
                            .as_deref()
                            .and_then(|p| Scene::load(p).ok())
                            .unwrap_or_else(default_scene);
                    }
                    app.message = Some(Message {
                        error: false,
                        text: "restored the last session".to_string(),
                    });
                    return app;
                }
            }
        }
        App::with_default_preset()
    }

    /// The app on the preset at `path`; on error, the default preset with
    /// the error shown.
    pub fn open_at_start(path: &Path) -> Self {
        let mut app = App::with_default_preset();
        app.open(path);
        app
    }

    fn session(&self) -> Session {
        Session {
            scene_ron: self.scene.to_ron_string(),
            path: self.path.clone(),
            dirty: self.is_dirty(),
        }
    }

    pub fn scene(&self) -> &Scene {
        &self.scene
    }
    /// The modal model in use (given, or identified from the ring tyre).
    pub fn modes(&self) -> &[Mode] {
        &self.modes
    }
    pub fn simulation(&self) -> &Simulation {
        &self.sim
    }
    pub fn history(&self) -> &History {
        &self.history
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
    /// Whether an animation export is running.
    pub fn exporting_frames(&self) -> bool {
        self.frames_job.is_some()
    }
    /// Blocks until a running frames export ends; returns its result.
    pub fn wait_frames_export(&mut self) -> Option<Result<u64, String>> {
        let job = self.frames_job.take()?;
        let r = job.wait();
        self.frames_done(&r);
        Some(r)
    }
    fn frames_done(&mut self, r: &Result<u64, String>) {
        match r {
            Ok(n) => self.info(format!("wrote {n} animation frames")),
            Err(e) => self.error(format!("Animation export stopped: {e}")),
        }
    }
    pub fn message(&self) -> Option<&Message> {
        self.message.as_ref()
    }
    pub fn is_dirty(&self) -> bool {
        self.scene != self.saved
    }
    pub fn pending_confirmation(&self) -> Option<&Discarding> {
        self.confirm.as_ref()
    }
    /// Whether a CSV export is still running.
    pub fn exporting_csv(&self) -> bool {
        self.csv_job.is_some()
    }
    /// Blocks until a running CSV export ends; returns its result.
    pub fn wait_csv_export(&mut self) -> Option<Result<String, String>> {
        let job = self.csv_job.take()?;
        let r = job.wait();
        self.message = Some(match &r {
            Ok(t) => Message {
                error: false,
                text: t.clone(),
            },
            Err(e) => Message {
                error: true,
                text: format!("CSV export failed: {e}"),
            },
        });
        Some(r)
    }

    /// Window title: scene name, file, and `*` when there are unsaved changes.
    pub fn title(&self) -> String {
        let file = self
            .path
            .as_deref()
            .and_then(Path::file_name)
            .map_or("unsaved".to_string(), |n| n.to_string_lossy().into_owned());
        format!(
            "{}{} ({file}) — tirecontact",
            if self.is_dirty() { "* " } else { "" },
            self.scene.name
        )
    }

    fn info(&mut self, text: impl Into<String>) {
        self.message = Some(Message {
            error: false,
            text: text.into(),
        });
    }
    fn error(&mut self, text: impl Into<String>) {
        self.message = Some(Message {
            error: true,
            text: text.into(),
        });
    }

    /// Runs one command. The only place the app's state changes.
    pub fn apply(&mut self, cmd: Command) {
        match cmd {
            Command::Play => self.play(),
            Command::Pause => self.time.pause(),
            Command::TogglePlay => {
                if self.time.is_playing() {
                    self.time.pause();
                } else {
                    self.play();
                }
            }
            Command::Step(n) => self.time.step(n),
            Command::Reset => self.reset_run(),
            Command::SetSpeed(s) => self.time.set_speed(s),
            Command::EditScene(scene) => self.edit(*scene),
            Command::New => self.guard(Discarding::New),
            Command::OpenDialog => self.guard(Discarding::OpenDialog),
            Command::OpenPath(p) => self.guard(Discarding::OpenPath(p)),
            Command::OpenPreset(k) => self.guard(Discarding::Preset(k)),
            Command::Quit => self.guard(Discarding::Quit),
            Command::ConfirmDiscard => {
                if let Some(d) = self.confirm.take() {
                    self.discard_and(d);
                }
            }
            Command::CancelDiscard => self.confirm = None,
            Command::Save => match self.path.clone() {
                Some(p) => self.save_to(&p),
                None => self.apply(Command::SaveAsDialog),
            },
            Command::SaveAsDialog => {
                let name = self.path.as_deref().and_then(Path::file_name).map_or_else(
                    || format!("{}.ron", file_stem(&self.scene.name)),
                    |n| n.to_string_lossy().into_owned(),
                );
                if let Some(p) = rfd::FileDialog::new()
                    .add_filter("RON scene", &["ron"])
                    .set_file_name(name)
                    .save_file()
                {
                    self.save_to(&p);
                }
            }
            Command::SavePath(p) => self.save_to(&p),
            Command::ExportPngDialog => {
                self.png_dialog = Some(PngSettings {
                    width: 1600,
                    height: 1200,
                });
            }
            Command::ExportPng {
                path,
                width,
                height,
            } => {
                self.png_dialog = None;
                match super::export::export_png(
                    &path,
                    width,
                    height,
                    &self.scene,
                    &self.modes,
                    &self.history,
                    &self.plot_opts.shown,
                ) {
                    Ok(()) => self.info(format!("wrote {} ({width}x{height} px)", path.display())),
                    Err(e) => self.error(format!("PNG export failed: {e}")),
                }
            }
            Command::ExportCsvDialog => {
                if let Some(p) = rfd::FileDialog::new()
                    .add_filter("CSV", &["csv"])
                    .set_file_name(format!("{}.csv", file_stem(&self.scene.name)))
                    .save_file()
                {
                    self.apply(Command::ExportCsv(p));
                }
            }
            Command::ExportCsv(path) => {
                if self.csv_job.is_some() {
                    self.error("a CSV export is already running");
                } else {
                    self.info(format!("writing {} …", path.display()));
                    self.csv_job = Some(CsvJob::spawn(
                        path,
                        self.run_start.clone(),
                        self.live_edits.clone(),
                        self.sim.steps(),
                    ));
                }
            }
            Command::DismissMessage => self.message = None,
            Command::ShowView(v) => {
                // the presenter layout has one view; another one leaves it
                self.classroom.on = false;
                self.view = v;
            }
            Command::Research(c) => self.apply_research(c),
            Command::SetClassroom(on) => {
                self.classroom.on = on;
                if on {
                    self.view = View::Scene;
                    self.time
                        .set_speed(super::time_control::Speed::Factor(classroom::SLOW_MOTION));
                }
            }
            Command::OpenGuided(k) => self.guard(Discarding::Guided(k)),
            Command::ShowModeBars(on) => self.classroom.bars = on,
            Command::ToggleMute(k) => self.set_mutes(k, false),
            Command::SoloMode(k) => self.set_mutes(k, true),
            Command::UnmuteAll => {
                if let Some(m) = self.mutes.take() {
                    let mut s = self.scene.clone();
                    s.tyre = m.original.clone();
                    self.edit(s);
                    if self.scene.tyre != m.original {
                        self.mutes = Some(m);
                    }
                }
            }
            Command::ExportFramesDialog => {
                self.frames_dialog = Some(FramesDialog::for_scene(&self.scene, self.sim.time_s()));
            }
            Command::ExportFrames { dir, settings } => {
                if self.frames_job.is_some() {
                    self.error("an animation export is already running");
                } else {
                    match FramesJob::spawn(
                        dir,
                        settings,
                        self.run_start.clone(),
                        self.live_edits.clone(),
                    ) {
                        Ok(job) => {
                            self.frames_dialog = None;
                            self.frames_job = Some(job);
                        }
                        Err(e) => self.error(format!("Animation export refused: {e}")),
                    }
                }
            }
            Command::CancelFrames => {
                if let Some(job) = &self.frames_job {
                    job.cancel();
                }
            }
        }
        // an edit of the tyre other than by the mutes ends them
        if self
            .mutes
            .as_ref()
            .is_some_and(|m| m.tyre != self.scene.tyre)
        {
            self.mutes = None;
        }
    }

    /// Mutes (or solos) mode `k` through a scene edit, refused with the
    /// reason when the muted model cannot be simulated.
    fn set_mutes(&mut self, k: usize, solo: bool) {
        let (original, base, current) = match &self.mutes {
            Some(m) => (m.original.clone(), m.base.clone(), m.muted.clone()),
            None => (self.scene.tyre.clone(), self.modes.clone(), Vec::new()),
        };
        let muted = mutes::toggled(&current, base.len(), k, solo);
        if muted.iter().all(|m| !m) {
            self.apply(Command::UnmuteAll);
            return;
        }
        if let Some(why) =
            mutes::refusal(&base, &muted, self.scene.num_points(), &self.scene.contact)
        {
            self.error(format!("Mute refused: {why}"));
            return;
        }
        let tyre = mutes::muted_tyre(&base, &muted);
        let mut s = self.scene.clone();
        s.tyre = tyre.clone();
        self.edit(s);
        if self.scene.tyre == tyre {
            self.mutes = Some(Mutes {
                original,
                base,
                muted,
                tyre,
            });
        }
    }

    /// Drops an informational message (errors stay until dismissed).
    fn clear_info(&mut self) {
        if self.message.as_ref().is_some_and(|m| !m.error) {
            self.message = None;
        }
    }

    fn play(&mut self) {
        self.clear_info();
        if self.sim.finished() {
            self.reset_run();
        }
        self.time.play();
    }

    fn reset_run(&mut self) {
        self.clear_info();
        self.sim.reset();
        self.time.reset();
        self.run_start = self.sim.scene().clone();
        self.live_edits.clear();
        self.history = History::new(self.sim.num_points(), DEFAULT_BUDGET);
        self.history.record_initial(&self.sim);
        self.phases = PhaseTracker::new(self.sim.num_points(), self.phases.hold_s);
    }

    /// Runs `d` now if there is nothing to lose, else asks first.
    fn guard(&mut self, d: Discarding) {
        if self.is_dirty() {
            self.confirm = Some(d);
        } else {
            self.discard_and(d);
        }
    }

    fn discard_and(&mut self, d: Discarding) {
        match d {
            Discarding::New => {
                self.replace(default_scene(), None, "new scene (default preset)");
            }
            Discarding::OpenDialog => {
                if let Some(p) = rfd::FileDialog::new()
                    .add_filter("RON scene", &["ron"])
                    .pick_file()
                {
                    self.open(&p);
                }
            }
            Discarding::OpenPath(p) => self.open(&p),
            Discarding::Preset(k) => match SHIPPED.get(k) {
                Some((name, file, text)) => match Scene::parse(text, file) {
                    Ok(scene) => {
                        self.replace(scene, None, &format!("opened shipped preset “{name}”"))
                    }
                    Err(e) => self.error(format!("shipped preset {file}: {e}")),
                },
                None => self.error(format!("no shipped preset #{k}")),
            },
            Discarding::Guided(k) => match GUIDED.get(k) {
                Some((name, file, text)) => match Scene::parse(text, file) {
                    Ok(scene) => self.replace(scene, None, &format!("guided tour: “{name}”")),
                    Err(e) => self.error(format!("guided preset {file}: {e}")),
                },
                None => self.error(format!("no guided preset #{k}")),
            },
            Discarding::Quit => {
                self.allow_close = true;
                self.time.pause();
                self.quit_requested = true;
            }
        }
    }

    /// Opens a preset file; a broken one leaves the current scene untouched.
    fn open(&mut self, path: &Path) {
        match Scene::load(path) {
            Ok(scene) => {
                let p = path.to_path_buf();
                self.replace(scene, Some(p), &format!("opened {}", path.display()));
            }
            Err(e) => self.error(format!(
                "Cannot open this preset; the current scene is kept.\n{e}"
            )),
        }
    }

    /// Replaces the document (scene, file) and restarts the run.
    fn replace(&mut self, scene: Scene, path: Option<PathBuf>, what: &str) {
        match Simulation::new(&scene).and_then(|sim| Ok((sim, scene.modes()?))) {
            Ok((sim, modes)) => {
                self.sim = sim;
                self.modes = modes;
                self.saved = scene.clone();
                self.scene = scene;
                self.path = path;
                self.time.reset();
                self.set_watchable_speed();
                self.reset_run();
                self.research_new_document();
                self.info(what.to_string());
            }
            Err(e) => self.error(format!(
                "Cannot use this scene; the current scene is kept.\n{e}"
            )),
        }
    }

    /// A freshly opened scene plays slowly enough to be watched (classroom
    /// mode keeps its slow motion).
    fn set_watchable_speed(&mut self) {
        let speed = if self.classroom.on {
            super::time_control::Speed::Factor(classroom::SLOW_MOTION)
        } else {
            super::time_control::Speed::watchable(self.scene.duration_s)
        };
        self.time.set_speed(speed);
    }

    fn save_to(&mut self, path: &Path) {
        match self.scene.save(path) {
            Ok(()) => {
                self.path = Some(path.to_path_buf());
                self.scene.base_dir = path.parent().map(Path::to_path_buf);
                self.saved = self.scene.clone();
                self.info(format!("saved {}", path.display()));
            }
            Err(e) => self.error(format!("Save failed (the file on disk is unchanged): {e}")),
        }
    }

    /// Applies an edited scene: road and speed live, everything else restarts.
    fn edit(&mut self, new: Scene) {
        if let Err(errors) = new.validate() {
            let list: Vec<String> = errors.iter().map(ToString::to_string).collect();
            self.error(format!("Edit refused: {}", list.join("; ")));
            return;
        }
        let old = &self.scene;
        let restart = new.tyre != old.tyre
            || new.points != old.points
            || new.dt_s != old.dt_s
            || new.duration_s != old.duration_s
            || new.ramp_s != old.ramp_s
            || new.contact_scheme != old.contact_scheme
            || new.contact != old.contact;
        if restart {
            match Simulation::new(&new).and_then(|sim| Ok((sim, new.modes()?))) {
                Ok((sim, modes)) => {
                    let playing = self.time.is_playing();
                    self.sim = sim;
                    self.modes = modes;
                    self.scene = new;
                    self.reset_run();
                    if playing {
                        self.time.play();
                    }
                }
                Err(e) => self.error(format!("Edit refused: {e}")),
            }
            return;
        }
        if new.road != old.road
            && let Err(e) = self.sim.set_road(&new.road)
        {
            self.error(format!("Road refused: {e}"));
            return;
        }
        if new.speed_mps != old.speed_mps {
            self.sim.set_speed(new.speed_mps);
        }
        if new.road != old.road || new.speed_mps != old.speed_mps {
            self.live_edits.push(LiveEdit {
                step: self.sim.steps(),
                road: new.road.clone(),
                speed_mps: new.speed_mps,
            });
        }
        self.scene = new;
    }

    /// Takes this frame's solver steps within the time budget.
    fn advance(&mut self, frame_s: f64) {
        let dt = self.sim.dt_s();
        let want = self.time.steps_this_frame(frame_s, dt);
        if want == 0 {
            return;
        }
        let start = Instant::now();
        let mut taken = 0;
        while taken < want {
            if self.sim.finished() {
                self.time.pause();
                self.info(format!("run complete: t = {:.4} s", self.sim.time_s()));
                break;
            }
            match self.sim.step() {
                Ok(_) => {
                    self.history.after_step(&self.sim);
                    self.phases.after_step(
                        self.sim.time_s(),
                        self.sim.in_contact(),
                        self.sim.force_n(),
                    );
                    taken += 1;
                }
                Err(e) => {
                    self.time.pause();
                    self.error(format!(
                        "Solver error, run paused: {e}\nEdit the scene or reset."
                    ));
                    break;
                }
            }
            if start.elapsed() > STEP_BUDGET {
                break;
            }
        }
        self.time.report(taken, dt, frame_s);
    }

    fn keyboard(&self, ctx: &egui::Context, cmds: &mut Vec<Command>) {
        if ctx.egui_wants_keyboard_input() {
            return;
        }
        ctx.input(|i| {
            if i.key_pressed(egui::Key::Space) {
                cmds.push(Command::TogglePlay);
            }
            if i.key_pressed(egui::Key::ArrowRight) {
                cmds.push(Command::Step(1));
            }
            if i.key_pressed(egui::Key::R) && i.modifiers.is_none() {
                cmds.push(Command::Reset);
            }
            for (key, view) in [
                (egui::Key::Num1, View::TimePlots),
                (egui::Key::Num2, View::Scene),
                (egui::Key::Num3, View::Green),
                (egui::Key::Num4, View::Spectra),
                (egui::Key::Num5, View::Sweep),
                (egui::Key::Num6, View::Compare),
                (egui::Key::Num7, View::Fidelity),
            ] {
                if i.key_pressed(key) {
                    cmds.push(Command::ShowView(view));
                }
            }
        });
    }

    fn poll_jobs(&mut self) {
        if let Some(job) = &self.csv_job
            && let Some(r) = job.poll()
        {
            self.csv_job = None;
            match r {
                Ok(t) => self.info(t),
                Err(e) => self.error(format!("CSV export failed: {e}")),
            }
        }
        if let Some(job) = &self.frames_job
            && let Some(r) = job.poll()
        {
            self.frames_job = None;
            self.frames_done(&r);
        }
    }

    /// One frame of the whole UI (also driven headless by the tests).
    pub fn show(&mut self, ui: &mut egui::Ui) {
        let started = Instant::now();
        let ctx = ui.ctx().clone();
        let frame_s = ctx.input(|i| f64::from(i.unstable_dt));
        // a minimised window neither simulates nor asks for frames: the run
        // resumes where it was when the window is shown again
        let hidden = ctx.input(|i| i.viewport().minimized == Some(true));
        self.poll_jobs();
        if !hidden {
            self.advance(frame_s);
        }
        self.research_frame(&ctx);
        let mut cmds = Vec::new();
        self.keyboard(&ctx, &mut cmds);
        let status = toolbar::ToolbarStatus {
            playing: self.time.is_playing(),
            speed: self.time.speed(),
            time_s: self.sim.time_s(),
            duration_s: self.scene.duration_s,
            steps: self.sim.steps(),
            achieved_factor: self.time.achieved_factor(),
            view: self.view,
            exporting_csv: self.csv_job.is_some(),
            classroom: self.classroom.on,
            mode_bars: self.classroom.bars,
            exporting_frames: self.frames_job.is_some(),
        };
        self.classroom.sync_style(&ctx);
        // impacts and releases stay up EVENT_HOLD_WALL_S of wall-clock time
        self.phases.hold_s = match self.time.speed() {
            super::time_control::Speed::Factor(f) => classroom::EVENT_HOLD_WALL_S * f,
            super::time_control::Speed::Max => 0.0,
        }
        .max(20.0 * self.sim.dt_s());
        egui::Panel::top("tirecontact.top").show(ui, |ui| {
            toolbar::menu_bar(ui, &status, &mut cmds);
            toolbar::transport(ui, &status, &mut cmds);
        });
        egui::Panel::bottom("tirecontact.status").show(ui, |ui| {
            super::dialogs::status_bar(ui, self);
        });
        if self.classroom.on {
            self.classroom_layout(ui, &mut cmds);
        } else {
            self.normal_layout(ui, &mut cmds);
        }
        super::dialogs::confirm_window(&ctx, self.confirm.as_ref(), &mut cmds);
        super::dialogs::png_window(&ctx, &mut self.png_dialog, &mut cmds);
        super::frames::dialog(&ctx, &mut self.frames_dialog, &mut cmds);
        super::frames::progress(&ctx, self.frames_job.as_ref(), &mut cmds);
        for c in cmds {
            self.apply(c);
        }
        let title = self.title();
        if title != self.title {
            ctx.send_viewport_cmd(egui::ViewportCommand::Title(title.clone()));
            self.title = title;
        }
        self.fps.tick(
            self.sim.time_s(),
            self.time.is_playing(),
            started.elapsed().as_secs_f64(),
        );
        if self.csv_job.is_some()
            || self.frames_job.is_some()
            || (!hidden && (self.time.is_playing() || self.time.pending_steps() > 0))
        {
            ctx.request_repaint();
        }
    }

    /// Measured frames per second (0 until a second has passed).
    pub fn fps(&self) -> f64 {
        self.fps.fps
    }

    /// Mean time per frame spent in solver steps and UI code (ms).
    pub fn app_ms(&self) -> f64 {
        self.fps.app_ms
    }
}

fn default_scene() -> Scene {
    match Scene::parse(DEFAULT_PRESET, crate::DEFAULT_PRESET_NAME) {
        Ok(s) => s,
        Err(e) => panic!("embedded default preset is invalid: {e}"),
    }
}

fn file_stem(name: &str) -> String {
    let s: String = name
        .chars()
        .map(|c| {
            if c.is_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '_'
            }
        })
        .collect();
    if s.is_empty() { "scene".to_string() } else { s }
}

impl eframe::App for App {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        let ctx = ui.ctx().clone();
        if ctx.input(|i| i.viewport().close_requested()) && !self.allow_close && self.is_dirty() {
            ctx.send_viewport_cmd(egui::ViewportCommand::CancelClose);
            self.confirm = Some(Discarding::Quit);
        }
        self.show(ui);
        if self.quit_requested {
            self.quit_requested = false;
            ctx.send_viewport_cmd(egui::ViewportCommand::Close);
        }
    }

    fn save(&mut self, storage: &mut dyn eframe::Storage) {
        if let Ok(text) = ron::to_string(&self.session()) {
            storage.set_string(SESSION_KEY, text);
        }
    }
}
