//! The file name of an open, save or export: typed in a field, or picked
//! with the desktop's file dialog ("Choose…").
//!
//! The native dialog alone (rfd) returns "no file" both when the user
//! cancels and when the desktop has no file chooser (no xdg portal, no
//! zenity: a bare X server, a remote session). Then Open, Save and the
//! exports silently did nothing. The typed field always works; "Choose…"
//! fills it when a dialog is available, and says so when none appeared.

use crate::gui::chrome::native_dialog::{Kind, Request, choose_button};
use crate::gui::model::command::{Command, ResearchCommand};
use egui::{RichText, Ui};
use std::path::{Path, PathBuf};

/// What the chosen file is for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FileAction {
    /// Open a scene (through the unsaved-changes guard).
    Open,
    /// Save the scene to a new file.
    SaveAs,
    /// Export the run as CSV.
    ExportCsv,
    /// Export the contact patch's heat map as PNG.
    HeatMapPng,
    /// The researcher tools' exports: the sweep as CSV or PNG, the pinned
    /// reference run as CSV.
    SweepCsv,
    SweepPng,
    PinnedCsv,
    /// The scene with the workbench's modes as its modal tyre.
    ModalPreset,
}

impl FileAction {
    /// The prompt's heading.
    pub fn title(self) -> &'static str {
        match self {
            FileAction::Open => "Open a scene",
            FileAction::SaveAs => "Save the scene as",
            FileAction::ExportCsv => "Export the run as CSV",
            FileAction::HeatMapPng => "Export the contact patch's heat map as PNG",
            FileAction::SweepCsv => "Export the sweep as CSV",
            FileAction::SweepPng => "Export the sweep as PNG",
            FileAction::PinnedCsv => "Export the pinned run as CSV",
            FileAction::ModalPreset => "Save as a modal preset",
        }
    }
    fn button(self) -> &'static str {
        match self {
            FileAction::Open => "Open",
            FileAction::SaveAs | FileAction::ModalPreset => "Save",
            FileAction::ExportCsv | FileAction::SweepCsv | FileAction::PinnedCsv => "Export CSV",
            FileAction::SweepPng | FileAction::HeatMapPng => "Export PNG",
        }
    }
    /// File-type name and extension of the dialog's filter.
    fn filter(self) -> (&'static str, &'static str) {
        match self {
            FileAction::Open | FileAction::SaveAs | FileAction::ModalPreset => ("RON scene", "ron"),
            FileAction::ExportCsv | FileAction::SweepCsv | FileAction::PinnedCsv => ("CSV", "csv"),
            FileAction::SweepPng | FileAction::HeatMapPng => ("PNG image", "png"),
        }
    }
    fn command(self, path: PathBuf) -> Command {
        match self {
            FileAction::Open => Command::OpenPath(path),
            FileAction::SaveAs => Command::SavePath(path),
            FileAction::ExportCsv => Command::ExportCsv(path),
            FileAction::HeatMapPng => Command::ExportHeatMap(path),
            FileAction::SweepCsv => Command::Research(ResearchCommand::ExportSweepCsv(path)),
            FileAction::SweepPng => Command::Research(ResearchCommand::ExportSweepPng(path)),
            FileAction::PinnedCsv => Command::Research(ResearchCommand::ExportPinnedCsv(path)),
            FileAction::ModalPreset => Command::Research(ResearchCommand::WorkbenchSave(path)),
        }
    }
}

/// An open file prompt: its purpose, the path as typed, and a note (the
/// dialog did not appear, the path is empty).
#[derive(Debug, Clone, PartialEq)]
pub struct FilePrompt {
    pub action: FileAction,
    pub path: String,
    pub note: Option<String>,
    /// The action held by the unsaved-changes question, done after the save.
    pub then: Option<crate::gui::model::command::Discarding>,
    /// The path field takes the keyboard at the next frame (set when the
    /// prompt opens: what is typed then goes to the path, not to the
    /// shortcuts).
    pub focus: bool,
}

impl FilePrompt {
    pub fn new(action: FileAction, path: impl Into<String>) -> Self {
        FilePrompt {
            action,
            path: path.into(),
            note: None,
            then: None,
            focus: true,
        }
    }
}

/// The working directory relative paths are resolved against (for the hint).
pub(crate) fn cwd_text() -> String {
    std::env::current_dir().map_or_else(
        |_| "the working directory".to_string(),
        |d| d.display().to_string(),
    )
}

/// The path field and its "Choose…" button (the desktop's dialog, which
/// fills the field). `focus`: the field takes the keyboard now (once: it is
/// cleared). Returns the note to show when no dialog gave a file.
pub fn path_row(
    ui: &mut Ui,
    path: &mut String,
    accessible: &str,
    filter: (&str, &str),
    save: bool,
    focus: &mut bool,
) -> Option<String> {
    let mut note = None;
    ui.horizontal(|ui| {
        let field = ui
            .add(egui::TextEdit::singleline(path).desired_width(320.0))
            .accessible_name(accessible)
            .on_hover_text(format!("a path; a relative one is in {}", cwd_text()));
        if std::mem::take(focus) {
            take_keyboard(ui, &field, path);
        } else if field.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter)) {
            // Enter confirms the prompt; one refused (a folder, no name)
            // stays open, and retyping must edit the path, not fire shortcuts
            field.request_focus();
        }
        let id = egui::Id::unique(("tirecontact.choose", accessible));
        let request = || {
            let current = Path::new(path.trim());
            Request {
                kind: if save { Kind::Save } else { Kind::Open },
                filter: Some((filter.0.to_string(), filter.1.to_string())),
                directory: current
                    .parent()
                    .filter(|d| d.is_dir())
                    .map(Path::to_path_buf),
                file_name: current
                    .file_name()
                    .map(|n| n.to_string_lossy().into_owned()),
            }
        };
        match choose_button(ui, id, request) {
            Some(Some(p)) => *path = p.display().to_string(),
            Some(None) => {
                note = Some(
                    "No file was chosen. If no dialog appeared, this desktop has none: \
                     type the path in the field."
                        .to_string(),
                )
            }
            None => {}
        }
    });
    note
}

/// Gives the keyboard to the text `field` holding `text`, its text selected
/// (what is typed then replaces the offered name instead of adding to it).
pub fn take_keyboard(ui: &Ui, field: &egui::Response, text: &str) {
    field.request_focus();
    let mut state = egui::text_edit::TextEditState::load(ui.ctx(), field.id).unwrap_or_default();
    state
        .cursor
        .set_char_range(Some(egui::text::CCursorRange::select_all_str(text)));
    state.store(ui.ctx(), field.id);
}

/// The path typed in `text`, or the reason it cannot be used.
pub fn typed_path(text: &str, ext: &str) -> Result<PathBuf, String> {
    let t = text.trim();
    if t.is_empty() {
        return Err(format!("Type a file path first (e.g. scene.{ext})."));
    }
    let p = PathBuf::from(t);
    if p.is_dir() {
        return Err(format!(
            "{t} is a folder; add a file name (e.g. {}).",
            p.join(format!("scene.{ext}")).display()
        ));
    }
    Ok(p)
}

/// [`typed_path`] of a file to write: its folder must exist too, so that a
/// path that cannot be written is refused in the prompt, which stays open
/// with the path as typed, rather than after it closed.
pub fn typed_path_to_write(text: &str, ext: &str) -> Result<PathBuf, String> {
    let p = typed_path(text, ext)?;
    match p.parent() {
        Some(dir) if !dir.as_os_str().is_empty() && !dir.is_dir() => Err(format!(
            "There is no folder {}: type the path of an existing folder.",
            dir.display()
        )),
        _ => Ok(p),
    }
}

/// Enter confirms and Escape cancels a prompt (as its buttons), whether or
/// not its path field has the keyboard.
pub fn confirm_keys(ctx: &egui::Context) -> (bool, bool) {
    ctx.input(|i| {
        (
            i.key_pressed(egui::Key::Enter),
            i.key_pressed(egui::Key::Escape),
        )
    })
}

/// The prompt window; pushes the action's command and closes when the user
/// confirms a usable path.
pub fn window(ctx: &egui::Context, prompt: &mut Option<FilePrompt>, cmds: &mut Vec<Command>) {
    let Some(p) = prompt else { return };
    let mut open = true;
    let mut done = false;
    let (enter, escape) = confirm_keys(ctx);
    egui::Window::new(p.action.title())
        .id(egui::Id::unique("tirecontact.file_prompt"))
        .open(&mut open)
        .collapsible(false)
        .resizable(false)
        // over the views, clear of the menu it came from
        .pivot(egui::Align2::CENTER_TOP)
        .default_pos(ctx.content_rect().center_top() + egui::vec2(0.0, 120.0))
        .show(ctx, |ui| {
            let save = p.action != FileAction::Open;
            if let Some(n) = path_row(
                ui,
                &mut p.path,
                "file path",
                p.action.filter(),
                save,
                &mut p.focus,
            ) {
                p.note = Some(n);
            }
            ui.label(RichText::new(format!("A relative path is in {}.", cwd_text())).weak());
            if let Some(n) = &p.note {
                ui.label(RichText::new(n.as_str()).color(crate::gui::widgets::fields::ERROR_COLOR));
            }
            ui.horizontal(|ui| {
                if ui
                    .button(RichText::new(p.action.button()).strong())
                    .on_hover_text("Enter")
                    .clicked()
                    || enter
                {
                    let check = if p.action == FileAction::Open {
                        typed_path
                    } else {
                        typed_path_to_write
                    };
                    match check(&p.path, p.action.filter().1) {
                        Ok(path) => {
                            cmds.push(p.action.command(path));
                            if let Some(d) = p.then.take() {
                                cmds.push(Command::ContinueAfterSave(d));
                            }
                            done = true;
                        }
                        Err(e) => p.note = Some(e),
                    }
                }
                if ui.button("Cancel").on_hover_text("Escape").clicked() || escape {
                    done = true;
                }
            });
        });
    if done || !open {
        *prompt = None;
    }
}
