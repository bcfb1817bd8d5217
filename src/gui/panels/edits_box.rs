//! The note of the edits made since the scene was opened or saved, in a box
//! of a fixed height at the top of the editing panel: it grew by a line or
//! two at the first edit of each kind and moved every field below it down,
//! under the pointer (the next click landed on the label above the field
//! meant).

use crate::gui::model::command::Command;
use egui::{RichText, Ui};

/// Rows of body text the box shows; a longer note scrolls inside it.
pub const ROWS: f32 = 3.0;

/// Said while nothing was edited.
pub const NO_EDITS: &str = "No changes since the scene was opened or saved. Your edits \
    are listed here, and Save adds them to the description.";

/// The box: the edits' note (`edits_note`), or `NO_EDITS`.
pub fn show(ui: &mut Ui, edits: &[String]) {
    let row = ui.text_style_height(&egui::TextStyle::Body);
    let h = ROWS * row + (ROWS - 1.0) * ui.spacing().item_spacing.y;
    egui::ScrollArea::vertical()
        .id_salt("tirecontact.edits_note")
        .max_height(h)
        .min_scrolled_height(h)
        .auto_shrink([false, false])
        .show(ui, |ui| match super::edits_note(edits) {
            Some(note) => {
                ui.label(RichText::new(note).italics());
            }
            None => {
                ui.label(RichText::new(NO_EDITS).italics().weak());
            }
        });
}

/// Undo and Redo: each one's name, what it would change (`None`: nothing
/// now), its keys and its command (the File menu's and the buttons').
pub fn undo_actions(
    [undo, redo]: [Option<&str>; 2],
) -> [(&'static str, Option<&str>, &'static str, Command); 2] {
    [
        ("Undo", undo, "Ctrl+Z", Command::Undo),
        ("Redo", redo, "Ctrl+Shift+Z", Command::Redo),
    ]
}

/// Undo and Redo beside the edits (the File menu has them too, with their
/// keys): each disabled when there is nothing, saying on hover what it
/// would change.
pub fn undo_buttons(ui: &mut Ui, undo: [Option<&str>; 2], cmds: &mut Vec<Command>) {
    ui.horizontal(|ui| {
        for (label, what, key, cmd) in undo_actions(undo) {
            let r = ui.add_enabled(what.is_some(), egui::Button::new(label).small());
            let r = match what {
                Some(w) if !w.is_empty() => r.on_hover_text(format!("{w} ({key})")),
                Some(_) => r.on_hover_text(format!("the name or description ({key})")),
                None => r.on_disabled_hover_text("no scene edit to take back or make again"),
            };
            if r.clicked() {
                cmds.push(cmd);
            }
        }
    });
}
