//! The document and its files: new/open (behind the unsaved-changes guard),
//! shipped and guided presets, save and save as (atomic, through
//! `Scene::save`), and the PNG and CSV exports of the run with their dialogs.

use super::*;
use crate::gui::jobs::prepare::{Then, needs_preparing};

impl App {
    /// The app on the preset at `path`; on error, the default preset with
    /// the error shown.
    pub fn open_at_start(path: &Path) -> Self {
        let mut app = App::with_default_preset();
        app.open(path);
        app
    }

    /// Whether a CSV export is still running.
    pub fn exporting_csv(&self) -> bool {
        self.handles.csv_job.is_some()
    }

    /// Blocks until a running CSV export ends; returns its result.
    pub fn wait_csv_export(&mut self) -> Option<Result<String, String>> {
        let job = self.handles.csv_job.take()?;
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

    /// Runs `d` now if there is nothing to lose, else asks first.
    pub(super) fn guard(&mut self, d: Discarding) {
        if self.is_dirty() {
            self.confirm = Some(d);
        } else {
            self.discard_and(d);
        }
    }

    /// The user confirmed the held action.
    pub(super) fn confirm_discard(&mut self) {
        if let Some(d) = self.confirm.take() {
            self.discard_and(d);
        }
    }

    /// "Save first": saves, then does the held action once the scene is
    /// saved; without a file, the file prompt asks for one and carries the
    /// action (done after its save, dropped if the prompt is cancelled).
    pub(super) fn save_first(&mut self) {
        let Some(d) = self.confirm.take() else {
            return self.save_document();
        };
        match self.doc.path.clone() {
            Some(p) => {
                self.save_to(&p);
                if !self.is_dirty() {
                    self.discard_after_save(d);
                }
            }
            None => {
                self.open_file_prompt(FileAction::SaveAs);
                if let Some(prompt) = &mut self.file_prompt {
                    prompt.then = Some(d);
                }
            }
        }
    }

    /// [`Self::discard_and`] after "Save first" saved the scene: the
    /// message of the scene that replaces it says the save too (it took
    /// the save's place in the banner, and the user saw no sign of it).
    pub(super) fn discard_after_save(&mut self, d: Discarding) {
        self.saved_note = self
            .message
            .as_ref()
            .filter(|m| !m.error)
            .map(|m| m.text.clone());
        self.discard_and(d);
    }

    pub(super) fn discard_and(&mut self, d: Discarding) {
        match d {
            Discarding::New => {
                self.replace(default_scene(), None, "new scene (default preset)");
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
            Discarding::Text { name, text } => match Scene::parse(&text, &name) {
                Ok(scene) => self.replace(scene, None, &format!("opened {name}")),
                Err(e) => self.open_failed(&e.to_string()),
            },
            Discarding::Quit => {
                self.allow_close = true;
                self.time.pause();
                self.quit_requested = true;
            }
        }
    }

    /// Opens a preset file, read on a background thread (the window keeps
    /// drawing); a broken one leaves the current scene untouched.
    fn open(&mut self, path: &Path) {
        self.prepare(Then::Open(path.to_path_buf()));
    }

    /// A preset that could not be opened: the current scene is kept.
    pub(super) fn open_failed(&mut self, e: &str) {
        let head =
            self.pause_for_error("Cannot open this preset; the current scene is kept.".to_string());
        self.error(format!("{head}\n{e}"))
    }

    /// Replaces the document (scene, file) and restarts the run; a scene
    /// that reads a file or identifies a ring is prepared off the UI thread
    /// first.
    pub(super) fn replace(&mut self, scene: Scene, path: Option<PathBuf>, what: &str) {
        // the latest edit or document wins over one still waiting
        self.handles.prepare_job = None;
        if needs_preparing(&scene, &self.handles.mode_cache) {
            self.prepare(Then::Replace {
                scene,
                path,
                what: what.to_string(),
            });
            return;
        }
        let built = super::build(&scene, &self.handles.mode_cache);
        self.replace_with(scene, path, what, built);
    }

    /// Replaces the document by `scene`, run by `built`.
    pub(super) fn replace_with(
        &mut self,
        scene: Scene,
        path: Option<PathBuf>,
        what: &str,
        built: Result<(Simulation, Vec<Mode>), SceneError>,
    ) {
        self.handles.prepare_job = None;
        match built {
            Ok((sim, modes)) => {
                self.sim = sim;
                self.modes = modes;
                self.doc.saved = scene.clone();
                self.doc.scene = scene;
                if let Some(dir) = path.as_deref().and_then(Path::parent)
                    && !is_shipped_folder(dir)
                {
                    self.last_dir = Some(dir.to_path_buf());
                }
                self.doc.path = path;
                self.doc.from_link = false;
                self.time.reset();
                self.set_watchable_speed();
                self.reset_run();
                self.research_new_document();
                self.forget_fields = true;
                self.field_refusal = None;
                self.undo.clear();
                self.handles.editor_to_top = true;
                let what = match self.saved_note.take() {
                    Some(saved) => format!("{saved}, then {what}"),
                    None => what.to_string(),
                };
                self.info(what);
            }
            Err(e) => {
                self.saved_note = None;
                self.error(format!(
                    "Cannot use this scene; the current scene is kept.\n{e}"
                ))
            }
        }
    }

    /// Saves to the current file, or asks for one.
    pub(super) fn save_document(&mut self) {
        match self.doc.path.clone() {
            Some(p) => self.save_to(&p),
            None => self.save_as_dialog(),
        }
    }

    pub(super) fn save_as_dialog(&mut self) {
        self.open_file_prompt(FileAction::SaveAs);
    }

    /// Shows the file prompt for `action`, filled with a sensible path: the
    /// current file, or a name from the scene's.
    pub(super) fn open_file_prompt(&mut self, action: FileAction) {
        let stem = file_stem(&self.doc.scene.name);
        if crate::gui::chrome::web::IN_BROWSER {
            return self.browser_file(action, &stem);
        }
        let path = match action {
            FileAction::Open => self
                .doc
                .path
                .as_deref()
                .and_then(Path::parent)
                .map_or_else(String::new, |d| {
                    format!("{}{}", d.display(), std::path::MAIN_SEPARATOR)
                }),
            // the current file, or a name in the folder of the last file
            // opened or saved outside the shipped presets (else the working
            // directory). A shipped preset is never offered (Save As from
            // the question about overwriting one offered it again, and
            // Enter asked again): its name in that folder, else in the
            // home folder.
            FileAction::SaveAs => match (&self.doc.path, &self.last_dir) {
                (Some(p), _) if !is_shipped_preset(p) => p.display().to_string(),
                (Some(p), dir) => {
                    let name = p.file_name().map_or_else(
                        || format!("{stem}.ron"),
                        |n| n.to_string_lossy().into_owned(),
                    );
                    match dir.clone().or_else(std::env::home_dir) {
                        Some(d) => d.join(name).display().to_string(),
                        None => name,
                    }
                }
                (None, Some(d)) => d.join(format!("{stem}.ron")).display().to_string(),
                (None, None) => format!("{stem}.ron"),
            },
            FileAction::ExportCsv => format!("{stem}.csv"),
            FileAction::HeatMapPng => format!("{stem}_heat_map.png"),
            FileAction::SweepCsv => "sweep.csv".to_string(),
            FileAction::SweepPng => "sweep.png".to_string(),
            FileAction::PinnedCsv => "reference.csv".to_string(),
            FileAction::ModalPreset => format!("{stem}_modal.ron"),
        };
        self.file_prompt = Some(FilePrompt::new(action, path));
    }

    /// Saves atomically (`Scene::save`): a failed save leaves the file as
    /// it was (and the scene as it was).
    ///
    /// The description gets a closing line listing the edits since the scene
    /// was opened or last saved (the text above it described the scene
    /// before them).
    pub(super) fn save_to(&mut self, path: &Path) {
        if self.overwrite.is_none() && is_shipped_preset(path) {
            // a quick save over a preset shipped with the app: ask first
            self.overwrite = Some(path.to_path_buf());
            return;
        }
        self.write_scene(path);
    }

    /// Writes the scene to `path` (see [`Self::save_to`]).
    pub(super) fn write_scene(&mut self, path: &Path) {
        let mut out = self.doc.scene.clone();
        out.description = crate::scene::described_with_edits(
            &self.doc.scene.description,
            &self.doc.saved.name,
            &self.edits(),
        );
        match out.save(path) {
            Ok(()) => {
                self.undo
                    .described(&self.doc.scene.description, &out.description);
                self.doc.scene.description = out.description;
                self.doc.path = Some(path.to_path_buf());
                if let Some(dir) = path.parent().filter(|d| !is_shipped_folder(d)) {
                    self.last_dir = Some(dir.to_path_buf());
                }
                self.doc.scene.base_dir = path.parent().map(Path::to_path_buf);
                self.doc.saved = self.doc.scene.clone();
                self.info(format!("saved {}", path.display()));
            }
            Err(e) => self.error(format!("Save failed (the file on disk is unchanged): {e}")),
        }
    }

    pub(super) fn open_png_dialog(&mut self) {
        if crate::gui::chrome::web::IN_BROWSER {
            // no file to choose: the PNG at the dialog's size, downloaded
            let name = format!("{}_plots.png", file_stem(&self.doc.scene.name));
            return self.export_png(Path::new(&name), 1600, 1200);
        }
        self.png_dialog = Some(PngSettings {
            width: 1600,
            height: 1200,
            path: format!("{}_plots.png", file_stem(&self.doc.scene.name)),
            note: None,
            focus: true,
        });
    }

    pub(super) fn export_png(&mut self, path: &Path, width: u32, height: u32) {
        // an empty figure (time axis -1 to 1 s, no curve) is not a plot: say
        // what to do instead, in the dialog if it is open
        let nothing = if self.history.len() < 2 {
            Some(
                "Nothing to export yet: the run has no steps (t = 0). Press Play (Space) or Step, then export.",
            )
        } else if !self.plot_opts.shown.iter().any(|&s| s) {
            Some("No point is shown: tick at least one point above the time plots, then export.")
        } else {
            None
        };
        if let Some(n) = nothing {
            let n = format!("{n} ({} not written)", path.display());
            match &mut self.png_dialog {
                Some(d) => d.note = Some(n),
                None => self.error(n),
            }
            return;
        }
        self.png_dialog = None;
        let fig = crate::gui::jobs::export::time_figure(
            &self.doc.scene,
            &self.modes,
            &self.history,
            &self.plot_opts.shown,
            self.plot_opts.clip_impacts,
        );
        if crate::gui::chrome::web::IN_BROWSER {
            let name = path
                .file_name()
                .map_or("plots.png".into(), |n| n.to_string_lossy().into_owned());
            match crate::output::figures::render_png_bytes(&fig, width, height) {
                Ok(bytes) => {
                    crate::gui::chrome::web::download(&name, bytes);
                    self.info(format!(
                        "{name} ({width}x{height} px) offered as a download"
                    ));
                }
                Err(e) => self.error(format!("PNG export failed: {e}")),
            }
            return;
        }
        match crate::output::figures::render_png(&fig, path, width, height) {
            Ok(()) => self.info(format!("wrote {} ({width}x{height} px)", path.display())),
            Err(e) => self.error(format!("PNG export failed: {e}")),
        }
    }

    /// Writes the contact patch's heat map at the current time to `path`
    /// (PNG, 1600 × 1000 px), its colour bar from 0 to the run's largest
    /// force, as the patch view draws it.
    pub(super) fn export_heat_map(&mut self, path: &Path) {
        if crate::gui::chrome::web::IN_BROWSER {
            return self.not_in_browser(FileAction::HeatMapPng.title());
        }
        let layout = match crate::output::patch::PatchLayout::of(self.sim.problem()) {
            Ok(l) => l,
            Err(e) => return self.error(format!("No heat map: {e}")),
        };
        let max_n = crate::gui::views::patch_view::colour_bar_max_n(&self.sim);
        let title = format!(
            "{} — contact force at t = {} s",
            self.doc.scene.name,
            crate::output::summary::short_num(self.sim.time_s(), 4)
        );
        match crate::output::patch::render_heat_map(
            &layout,
            self.sim.force_n(),
            max_n,
            &title,
            path,
            (1600, 1000),
        ) {
            Ok(()) => self.info(format!("wrote {} (1600x1000 px)", path.display())),
            Err(e) => self.error(format!("Heat map export failed: {e}")),
        }
    }

    pub(super) fn export_csv_dialog(&mut self) {
        self.open_file_prompt(FileAction::ExportCsv);
    }

    /// Starts the CSV export of the current run (re-simulated from its
    /// start with its live edits) on a background thread.
    pub(super) fn export_csv(&mut self, path: PathBuf) {
        if self.handles.csv_job.is_some() {
            self.error("a CSV export is already running");
        } else {
            // in the browser: a download of the file's name
            let deliver: crate::gui::jobs::export::Deliver = if crate::gui::chrome::web::IN_BROWSER
            {
                Box::new(|path, bytes| {
                    let name = path
                        .file_name()
                        .map_or("run.csv".into(), |n| n.to_string_lossy().into_owned());
                    crate::gui::chrome::web::download(&name, bytes);
                    Ok(format!("{name} offered as a download"))
                })
            } else {
                crate::gui::jobs::export::write_file()
            };
            match CsvJob::spawn(
                path.clone(),
                self.run_start.clone(),
                Arc::clone(&self.handles.mode_cache),
                self.live_edits.clone(),
                self.sim.steps(),
                deliver,
            ) {
                Ok(job) => {
                    self.info(format!("writing {} …", path.display()));
                    self.handles.csv_job = Some(job);
                }
                Err(e) => self.error(format!("CSV export refused: {e}")),
            }
        }
    }

    /// Picks up the result of a finished CSV export (once a frame).
    /// The CSV export's end, once its job finished (never blocks).
    pub(super) fn poll_csv(&self) -> Option<Command> {
        let r = self.handles.csv_job.as_ref()?.poll()?;
        Some(Command::CsvExportEnded(r))
    }

    /// Stops the CSV export under way (it stops at its next steps; no
    /// file is written).
    pub(super) fn cancel_csv_export(&mut self) {
        if self.handles.csv_job.take().is_some() {
            self.info("CSV export cancelled: no file written.");
        }
    }

    /// The CSV export's progress (fraction of the steps re-run), while
    /// one runs.
    pub fn csv_progress(&self) -> Option<f64> {
        self.handles.csv_job.as_ref().map(CsvJob::fraction)
    }

    pub(super) fn csv_export_ended(&mut self, r: Result<String, String>) {
        self.handles.csv_job = None;
        match r {
            Ok(t) => self.info(t),
            Err(e) => self.error(format!("CSV export failed: {e}")),
        }
    }
}

/// The embedded default preset.
pub(super) fn default_scene() -> Scene {
    match Scene::parse(DEFAULT_PRESET, crate::DEFAULT_PRESET_NAME) {
        Ok(s) => s,
        Err(e) => panic!("embedded default preset is invalid: {e}"),
    }
}

/// Whether `path` is an existing file in a folder of presets shipped with
/// the app: the repository's `presets/`, or any folder named `presets`
/// holding one of the shipped presets' files.
pub(crate) fn is_shipped_preset(path: &Path) -> bool {
    if !path.is_file() {
        return false;
    }
    std::path::absolute(path)
        .ok()
        .and_then(|p| p.parent().map(Path::to_path_buf))
        .is_some_and(|dir| is_shipped_folder(&dir))
}

/// Whether `dir` is a folder of presets shipped with the app (see
/// [`is_shipped_preset`]).
pub(crate) fn is_shipped_folder(dir: &Path) -> bool {
    let Ok(dir) = std::path::absolute(dir) else {
        return false;
    };
    let canonical = |d: &Path| std::fs::canonicalize(d).ok();
    let repository = Path::new(env!("CARGO_MANIFEST_DIR")).join("presets");
    if canonical(&dir).is_some() && canonical(&dir) == canonical(&repository) {
        return true;
    }
    dir.file_name().is_some_and(|n| n == "presets")
        && SHIPPED.iter().any(|(_, file, _)| dir.join(file).is_file())
}

/// A file name stem from a scene name: lower-case alphanumerics, each run
/// of anything else one `_` ("Paper: ring tyre" gives `paper_ring_tyre`,
/// not `paper__ring_tyre`).
pub(crate) fn file_stem(name: &str) -> String {
    let mut s = String::new();
    for c in name.chars() {
        if c.is_alphanumeric() {
            s.push(c.to_ascii_lowercase());
        } else if !s.is_empty() && !s.ends_with('_') {
            s.push('_');
        }
    }
    let s = s.trim_end_matches('_');
    if s.is_empty() {
        "scene".to_string()
    } else {
        s.to_string()
    }
}
