//! Contact law: the paper's rigid kinematic contact, or a tread
//! spring in series with the tyre at each point (one stiffness for every
//! point, or one per point). Changing it restarts the run.

use super::push_edit;
use crate::Scene;
use crate::gui::model::command::Command;
use crate::gui::widgets::fields::{Apply, NumField, section};
use crate::scene::Contact;
use egui::{Grid, Ui};

/// Tread stiffness offered when switching to compliant contact (N/m).
pub const DEFAULT_TREAD_N_M: f64 = 2e6;

pub fn show(ui: &mut Ui, scene: &Scene, cmds: &mut Vec<Command>) {
    section(ui, "Contact", Apply::Restart);
    let rigid = scene.contact.is_rigid();
    ui.horizontal(|ui| {
        if ui
            .selectable_label(rigid, "Rigid")
            .on_hover_text("the paper's kinematic contact: a point on the road follows it")
            .clicked()
            && !rigid
        {
            cmds.push(with_contact(scene, Contact::Rigid));
        }
        if ui
            .selectable_label(!rigid, "Compliant")
            .on_hover_text(
                "a tread spring k (N/m) between each point and the road: q = k max(0, r - u)",
            )
            .clicked()
            && rigid
        {
            cmds.push(with_contact(
                scene,
                Contact::Compliant {
                    stiffness_n_m: vec![DEFAULT_TREAD_N_M],
                },
            ));
        }
    });
    let Contact::Compliant { stiffness_n_m } = &scene.contact else {
        return;
    };
    let p = scene.num_points();
    let per_point = stiffness_n_m.len() > 1;
    Grid::new("tirecontact.contact")
        .min_row_height(crate::gui::widgets::text_row_px(ui))
        .num_columns(2)
        .show(ui, |ui| {
            for (i, &k) in stiffness_n_m.iter().enumerate() {
                ui.label(if per_point {
                    format!("tread stiffness, point {i}")
                } else {
                    "tread stiffness (all points)".to_string()
                });
                let name = format!("contact.stiffness_n_m[{i}]");
                push_edit(
                    cmds,
                    NumField::new(&name, k, "kN/mm", Apply::Restart)
                        .scale(1e-6)
                        .show(ui, |v| {
                            let mut ks = stiffness_n_m.clone();
                            ks[i] = v;
                            scene_with(scene, Contact::Compliant { stiffness_n_m: ks })
                        }),
                );
                ui.end_row();
            }
        });
    if p > 1 {
        let label = if per_point {
            "one stiffness for all points"
        } else {
            "one stiffness per point"
        };
        if ui.small_button(label).clicked() {
            let ks = if per_point {
                vec![stiffness_n_m[0]]
            } else {
                vec![stiffness_n_m[0]; p]
            };
            cmds.push(with_contact(
                scene,
                Contact::Compliant { stiffness_n_m: ks },
            ));
        }
    }
    ui.label(egui::RichText::new("1 kN/mm = 1e6 N/m; larger values tend to rigid contact").weak());
}

fn scene_with(scene: &Scene, contact: Contact) -> Scene {
    let mut s = scene.clone();
    s.contact = contact;
    s
}

fn with_contact(scene: &Scene, contact: Contact) -> Command {
    Command::EditScene(Box::new(scene_with(scene, contact)))
}
