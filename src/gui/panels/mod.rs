//! Editing panels. They read the scene and push `Command`s; they never touch
//! the simulation.

pub mod contact_panel;
pub mod modes_table;
pub mod points_panel;
pub mod random_road;
pub mod road_panel;
pub mod run_panel;
pub mod toolbar;

use super::command::Command;
use crate::Scene;
use crate::scene::{Mode, Tyre};

/// The given modes of a scene, mutably (for building edited copies); a ring
/// tyre's modes are identified, not edited (`None`).
pub(crate) fn modes_mut(scene: &mut Scene) -> Option<&mut Vec<Mode>> {
    match &mut scene.tyre {
        Tyre::Modal { modes } => Some(modes),
        Tyre::Ring { .. } => None,
    }
}

pub(crate) fn push_edit(cmds: &mut Vec<Command>, c: Option<Command>) {
    if let Some(c) = c {
        cmds.push(c);
    }
}

/// The whole editing side panel.
pub fn side_panel(ui: &mut egui::Ui, scene: &Scene, modes: &[Mode], cmds: &mut Vec<Command>) {
    egui::ScrollArea::vertical().show(ui, |ui| {
        ui.heading(&scene.name);
        if !scene.description.is_empty() {
            ui.label(egui::RichText::new(&scene.description).weak());
        }
        ui.horizontal(|ui| {
            ui.label("Tags:");
            super::fields::tag(ui, super::fields::Apply::Live);
            ui.label("applied to the running simulation;");
            super::fields::tag(ui, super::fields::Apply::Restart);
            ui.label("restarts the run.");
        });
        ui.separator();
        road_panel::show(ui, scene, cmds);
        ui.separator();
        run_panel::show(ui, scene, cmds);
        ui.separator();
        modes_table::show(ui, scene, modes, cmds);
        ui.separator();
        points_panel::show(ui, scene, cmds);
        ui.separator();
        contact_panel::show(ui, scene, cmds);
    });
}
