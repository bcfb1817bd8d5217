//! The scene's name and description, editable: a preset saved for a report
//! or a class carries the name and the text its author gives it (the name
//! is the window title's and the status bar's). Neither restarts the run.

use crate::Scene;
use crate::gui::model::command::Command;
use egui::{Id, Ui};

/// What a text field showed and holds while it is edited (egui memory).
#[derive(Clone, Default)]
struct TextState {
    /// The scene's text the field was last synchronised with.
    shown: String,
    text: String,
}

/// A text field of the scene named `name` (its accessible name and memory
/// key) holding `current`; the committed new text (Enter for one line, or
/// focus lost) when it differs.
fn text_field(ui: &mut Ui, name: &str, current: &str, multiline: bool) -> Option<String> {
    let id = Id::unique(("tirecontact.text", name));
    let mut st: TextState = ui.data(|d| d.get_temp(id)).unwrap_or_default();
    let focused = ui.memory(|m| m.has_focus(id));
    if !focused && st.shown != current {
        st = TextState {
            shown: current.to_string(),
            text: current.to_string(),
        };
    }
    let edit = if multiline {
        egui::TextEdit::multiline(&mut st.text).desired_rows(4)
    } else {
        egui::TextEdit::singleline(&mut st.text)
    };
    let resp = ui
        .add(edit.id(id).desired_width(f32::INFINITY))
        .accessible_name(name);
    let mut out = None;
    if resp.lost_focus() && st.text != current {
        out = Some(st.text.clone());
        st.shown = st.text.clone();
    }
    ui.data_mut(|d| d.insert_temp(id, st));
    out
}

/// Memory key of whether the section was open at the last frame.
fn open_key() -> Id {
    Id::unique("tirecontact.about.open")
}

/// Whether the "Name and description" section was open at the last frame:
/// its field then shows the description, which the panel does not repeat
/// above it.
pub fn is_open(ui: &Ui) -> bool {
    ui.data(|d| d.get_temp(open_key())).unwrap_or(false)
}

/// The "Name and description" section (collapsed at first).
pub fn show(ui: &mut Ui, scene: &Scene, cmds: &mut Vec<Command>) {
    let r = egui::CollapsingHeader::new("Name and description")
        .id_salt("tirecontact.about")
        .show(ui, |ui| {
            ui.label("name (window title, status bar, figures)");
            if let Some(name) = text_field(ui, "scene.name", &scene.name, false) {
                let name = name.trim();
                if name.is_empty() {
                    cmds.push(Command::FieldRefused {
                        field: "scene.name".to_string(),
                        text: format!(
                            "scene.name: an empty name; expected some text. The scene keeps \
                             \"{}\".",
                            scene.name
                        ),
                    });
                } else {
                    let mut s = scene.clone();
                    s.name = name.to_string();
                    cmds.push(Command::EditScene(Box::new(s)));
                }
            }
            ui.label("description (what the scene shows; saved with it)");
            if let Some(text) = text_field(ui, "scene.description", &scene.description, true) {
                let mut s = scene.clone();
                s.description = text;
                cmds.push(Command::EditScene(Box::new(s)));
            }
            ui.label(
                egui::RichText::new("Editing these does not restart the run.")
                    .small()
                    .weak(),
            );
        });
    let open = r.openness > 0.0;
    ui.data_mut(|d| d.insert_temp(open_key(), open));
}
