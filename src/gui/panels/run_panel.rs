//! Time stepping: ramp, time step, duration, contact scheme. Every change
//! restarts the run.

use super::push_edit;
use crate::Scene;
use crate::gui::model::command::Command;
use crate::gui::widgets::fields::{Apply, NumField, section};
use crate::scene::ContactScheme;
use egui::{Grid, Ui};

pub fn show(ui: &mut Ui, scene: &Scene, cmds: &mut Vec<Command>) {
    section(ui, "Time stepping", Apply::Restart);
    Grid::new("tirecontact.run")
.min_row_height(crate::gui::widgets::text_row_px(ui)).num_columns(2).show(ui, |ui| {
        ui.label("ramp")
            .on_hover_text("preload and road are ramped in smoothly over this time");
        push_edit(
            cmds,
            NumField::new("ramp_s", scene.ramp_s, "s", Apply::Restart).show(ui, |v| {
                let mut s = scene.clone();
                s.ramp_s = v;
                s
            }),
        );
        ui.end_row();
        ui.label("time step dt");
        push_edit(
            cmds,
            NumField::new("dt_s", scene.dt_s, "µs", Apply::Restart)
                .scale(1e6)
                .show(ui, |v| {
                    let mut s = scene.clone();
                    s.dt_s = v;
                    s
                }),
        );
        ui.end_row();
        ui.label("duration");
        push_edit(
            cmds,
            NumField::new("duration_s", scene.duration_s, "s", Apply::Restart).show(ui, |v| {
                let mut s = scene.clone();
                s.duration_s = v;
                s
            }),
        );
        ui.end_row();
        ui.label("contact scheme");
        let mut scheme = scene.contact_scheme;
        let rigid = matches!(scene.contact, crate::scene::Contact::Rigid);
        ui.add_enabled_ui(rigid, |ui| {
        egui::ComboBox::from_id_salt("tirecontact.scheme")
            .selected_text(scheme_text(scheme))
            .show_ui(ui, |ui| {
                for s in [ContactScheme::Located, ContactScheme::Paper] {
                    ui.selectable_value(&mut scheme, s, scheme_text(s));
                }
            })
            .response
            .accessible_name("contact scheme")
            .on_hover_text(SCHEME_HELP)
            .on_disabled_hover_text("compliant contact has its own scheme (tread springs, landings and releases always located): this applies to rigid contact only");
        });
        if scheme != scene.contact_scheme {
            let mut s = scene.clone();
            s.contact_scheme = scheme;
            cmds.push(Command::EditScene(Box::new(s)));
        }
        ui.end_row();
    });
    ui.label(egui::RichText::new(format!("{} steps per run", scene.num_steps())).weak());
}

/// What the contact schemes do (the combo box's tooltip).
pub const SCHEME_HELP: &str = "How rigid contact is decided within a time step. \
Events located in the step (default): impacts and releases are found inside the step \
(second order); an impact is an impulse. Paper (step ends only): the paper's scheme, \
contact decided at step ends (first order); a landing shows as one step of a very \
large force (clipped by \"clip impact spikes\"). Changing it restarts the run.";

fn scheme_text(s: ContactScheme) -> &'static str {
    match s {
        ContactScheme::Located => "events located in the step",
        ContactScheme::Paper => "paper (step ends only)",
    }
}
