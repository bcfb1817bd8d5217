//! The note of the edits made since the scene was opened or saved, in a box
//! of a fixed height at the top of the editing panel: it grew by a line or
//! two at the first edit of each kind and moved every field below it down,
//! under the pointer (the next click landed on the label above the field
//! meant).

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
