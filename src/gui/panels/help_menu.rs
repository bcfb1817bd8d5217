//! The Help menu: what the window shows, how to start, the keyboard
//! shortcuts (listed nowhere else but in tooltips) and the way back to the
//! start after experimenting.

use crate::gui::model::command::Command;
use egui::{RichText, Ui};

/// The keyboard shortcuts: key, what it does. They act when no text field
/// has the keyboard focus (`App::keyboard`).
pub const SHORTCUTS: &[(&str, &str)] = &[
    ("Space", "play / pause"),
    ("Right arrow", "one solver step"),
    ("R", "back to t = 0 (the edits are kept)"),
    ("1  2  3", "time plots, scene view, Green functions"),
    (
        "4  5  6  7  8",
        "research: spectra, sweep, A/B compare, fidelity, identification",
    ),
    ("9", "contact patch (points across the tread)"),
    ("Ctrl+Z", "undo the last scene edit"),
    ("Ctrl+Shift+Z, Ctrl+Y", "redo it"),
    ("Ctrl+O", "open a preset file"),
    ("Ctrl+S", "save"),
    ("Ctrl+Shift+S", "save as"),
    (
        "Enter / Escape",
        "in a field or a file prompt: apply / cancel",
    ),
];

/// The first steps, one line each.
pub const FIRST_STEPS: &[&str] = &[
    "Play (Space) runs the scene: a tyre rolling over a road, touching it at a few contact points.",
    "Time plots: per point, its displacement u (mm, up), the contact force q (N), the gap to the \
     road (mm) and whether it is in contact (raised lane).",
    "Scene view: the road moving under the points, coloured by contact state, forces as arrows.",
    "The left panel edits the scene: hover a field for its meaning, unit and accepted values; \
     'live' fields apply at once, 'restart' fields restart the run.",
    "Guided tour: pairs of presets that differ in one thing, each saying what to watch.",
];

/// The Help menu of the menu bar.
pub fn show(ui: &mut Ui, cmds: &mut Vec<Command>) {
    ui.menu_button("Help", |ui| {
        // no wider than the window, and scrolled within its height (on a
        // phone it was wider than the screen and ran off its bottom)
        let screen = ui.ctx().content_rect();
        if screen.width() < crate::gui::widgets::NARROW_PX {
            let w = screen.width() - 24.0;
            ui.set_max_width(w);
            egui::ScrollArea::vertical()
                .max_height((screen.height() - 48.0).max(120.0))
                .show(ui, |ui| {
                    ui.set_max_width(w);
                    contents(ui, cmds, true);
                });
        } else {
            ui.set_max_width(460.0);
            contents(ui, cmds, false);
        }
    });
}

/// What the Help menu says; `narrow`: the shortcuts as wrapped lines, not
/// a table (its rows did not wrap and widened the menu past a phone's
/// screen).
fn contents(ui: &mut Ui, cmds: &mut Vec<Command>, narrow: bool) {
    {
        ui.strong("Getting started");
        for line in FIRST_STEPS {
            ui.label(format!("• {line}"));
        }
        ui.separator();
        ui.strong("Keyboard shortcuts");
        ui.label(
            RichText::new("(when no text field has the focus; click the plots to leave a field)")
                .small()
                .weak(),
        );
        if narrow {
            for (key, what) in SHORTCUTS {
                ui.horizontal_wrapped(|ui| {
                    ui.label(RichText::new(*key).monospace().strong());
                    ui.label(*what);
                });
            }
        } else {
            egui::Grid::new("tirecontact.help.keys")
                .num_columns(2)
                .striped(true)
                .show(ui, |ui| {
                    for (key, what) in SHORTCUTS {
                        ui.label(RichText::new(*key).monospace().strong());
                        ui.label(*what);
                        ui.end_row();
                    }
                });
        }
        ui.separator();
        ui.strong("Back to the start");
        if ui
            .button("Reopen the default scene")
            .on_hover_text("File > New: the paper's ring tyre, as at the first launch (asks before dropping unsaved edits)")
            .clicked()
        {
            cmds.push(Command::New);
            ui.close();
        }
        ui.label(
            RichText::new("Reset (R) only rewinds the run to t = 0 and keeps your edits.")
                .small()
                .weak(),
        );
        if crate::gui::chrome::web::IN_BROWSER {
            ui.separator();
            ui.strong("In the browser");
            ui.label(crate::gui::chrome::web::BROWSER_LIMITS);
        }
    }
}
