//! Editing panels. They read the scene and push `Command`s; they never touch
//! the simulation.

pub mod about_panel;
pub mod contact_panel;
pub mod edits_box;
pub mod fe_panel;
pub mod help_menu;
pub mod modes_table;
pub mod patch_panel;
pub mod points_panel;
pub mod random_road;
pub mod road_panel;
pub mod run_panel;
pub mod toolbar;

use crate::Scene;
use crate::gui::model::command::Command;
use crate::scene::{Mode, Tyre};

/// The given modes of a scene, mutably (for building edited copies); a ring
/// or measured tyre's modes are identified, not edited (`None`).
pub(crate) fn modes_mut(scene: &mut Scene) -> Option<&mut Vec<Mode>> {
    match &mut scene.tyre {
        Tyre::Modal { modes } => Some(modes),
        Tyre::Ring { .. } | Tyre::Measured { .. } | Tyre::Plate { .. } | Tyre::FeModes { .. } => {
            None
        }
    }
}

/// The line under a scene's description when the scene was edited since it
/// was opened or saved: the edits, and that a save adds them to the text.
pub fn edits_note(edits: &[String]) -> Option<String> {
    (!edits.is_empty()).then(|| {
        format!(
            "Changed since opened or saved: {}. The description was written before \
             these changes; saving adds them to it.",
            edits.join("; ")
        )
    })
}

pub(crate) fn push_edit(cmds: &mut Vec<Command>, c: Option<Command>) {
    if let Some(c) = c {
        cmds.push(c);
    }
}

/// The whole editing side panel. `edits`: what changed since the scene was
/// opened or saved (its description does not say); `undo`: what Undo and
/// Redo would change (`None`: nothing); `to_top`: scroll back to the top
/// (another scene came in).
pub fn side_panel(
    ui: &mut egui::Ui,
    to_top: bool,
    scene: &Scene,
    edits: &[String],
    undo: [Option<&str>; 2],
    modes: &[Mode],
    road: &crate::model::road::RoadProfile,
    cmds: &mut Vec<Command>,
) {
    let mut area = egui::ScrollArea::vertical();
    if to_top {
        area = area.vertical_scroll_offset(0.0);
    }
    area.show(ui, |ui| {
        ui.heading(&scene.name);
        if !scene.description.is_empty() && !about_panel::is_open(ui) {
            ui.label(egui::RichText::new(&scene.description).weak());
        }
        // a box of a fixed height: the fields below stay where they are
        edits_box::show(ui, edits);
        edits_box::undo_buttons(ui, undo, cmds);
        about_panel::show(ui, scene, cmds);
        // wrapped: a phone's width cut it at "restarts the ru"
        crate::gui::widgets::text_row_wrapped(ui, |ui| {
            ui.label("Tags:");
            crate::gui::widgets::fields::tag(ui, crate::gui::widgets::fields::Apply::Live);
            ui.label("applied to the running simulation;");
            crate::gui::widgets::fields::tag(ui, crate::gui::widgets::fields::Apply::Restart);
            ui.label("restarts the run.");
        });
        ui.separator();
        road_panel::show(ui, scene, road, cmds);
        ui.separator();
        run_panel::show(ui, scene, cmds);
        ui.separator();
        if matches!(scene.tyre, Tyre::FeModes { .. }) {
            fe_panel::show(ui, scene, modes, cmds);
        } else {
            modes_table::show(ui, scene, modes, cmds);
        }
        ui.separator();
        if scene.points.grid().is_some() {
            patch_panel::grid(ui, scene, cmds);
        } else {
            points_panel::show(ui, scene, cmds);
        }
        ui.separator();
        contact_panel::show(ui, scene, cmds);
    });
}
