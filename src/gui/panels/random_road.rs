//! Random road (ISO 8608 class A–H, seed, loop length, band of spatial
//! frequencies). Applied live: a new class or seed regenerates the profile
//! under the running simulation.

use super::push_edit;
use crate::Scene;
use crate::gui::model::command::Command;
use crate::gui::widgets::fields::{Apply, NumField};
use crate::model::road::{Road, RoadClass};
use egui::{Grid, Ui};

pub const CLASSES: [(RoadClass, &str); 8] = [
    (RoadClass::A, "A (very good)"),
    (RoadClass::B, "B (good)"),
    (RoadClass::C, "C (average)"),
    (RoadClass::D, "D (poor)"),
    (RoadClass::E, "E (very poor)"),
    (RoadClass::F, "F"),
    (RoadClass::G, "G"),
    (RoadClass::H, "H (roughest)"),
];

/// The road offered when switching to "random".
pub fn default_road() -> Road {
    Road::Random {
        class: RoadClass::C,
        seed: 1,
        length_m: 100.0,
        min_wavenumber_cpm: 1.0,
        max_wavenumber_cpm: 20.0,
    }
}

pub(crate) fn class_name(c: RoadClass) -> &'static str {
    CLASSES
        .iter()
        .find(|(k, _)| *k == c)
        .map_or("?", |(_, n)| n)
}

/// The seed row of a random road or a texture (`what`: "road",
/// "texture"): the seed, and a button for the next one; the edit sets the
/// road's seed ([`Road::seed_mut`]).
pub(super) fn seed_row(ui: &mut Ui, scene: &Scene, seed: u64, what: &str, cmds: &mut Vec<Command>) {
    ui.label("seed");
    ui.horizontal(|ui| {
        let mut s = seed;
        ui.add(egui::DragValue::new(&mut s).speed(1.0))
            .accessible_name(format!("{what} seed"))
            .on_hover_text(format!(
                "phases of the {what}: the same seed gives the same {what}"
            ));
        if ui.small_button(format!("new {what}")).clicked() {
            s = seed.wrapping_add(1);
        }
        if s != seed {
            let mut edited = scene.clone();
            if let Some(seed) = edited.road.seed_mut() {
                *seed = s;
            }
            cmds.push(Command::EditScene(Box::new(edited)));
        }
    });
    ui.end_row();
}

/// The random road's fields: class, seed, length and wavenumber band, each
/// refusing bad values. Long but flat: one field after another.
pub fn show(ui: &mut Ui, scene: &Scene, cmds: &mut Vec<Command>) {
    let Road::Random {
        class,
        seed,
        length_m,
        min_wavenumber_cpm,
        max_wavenumber_cpm,
    } = scene.road.clone()
    else {
        return;
    };
    let with = |f: &dyn Fn(&mut Road)| {
        let mut s = scene.clone();
        f(&mut s.road);
        s
    };
    Grid::new("tirecontact.random_road")
        .min_row_height(crate::gui::widgets::text_row_px(ui))
        .num_columns(2)
        .show(ui, |ui| {
            ui.label("ISO 8608 class");
            let mut chosen = class;
            egui::ComboBox::from_id_salt("tirecontact.road_class")
                .selected_text(class_name(class))
                .show_ui(ui, |ui| {
                    for (c, name) in CLASSES {
                        ui.selectable_value(&mut chosen, c, name);
                    }
                })
                .response
                .accessible_name("road class")
                .on_hover_text(
                    "displacement PSD Gd(0.1 cycles/m) = 16e-6 × 4^k m³, k = 0 for A … 7 for H",
                );
            if chosen != class {
                cmds.push(Command::EditScene(Box::new(with(&|r| {
                    if let Road::Random { class, .. } = r {
                        *class = chosen;
                    }
                }))));
            }
            ui.end_row();
            seed_row(ui, scene, seed, "road", cmds);
            ui.label("loop length L");
            push_edit(
                cmds,
                NumField::new("road.length_m", length_m, "m", Apply::Live).show(ui, |v| {
                    with(&|r| {
                        if let Road::Random { length_m, .. } = r {
                            *length_m = v;
                        }
                    })
                }),
            );
            ui.end_row();
            ui.label("lowest n");
            push_edit(
                cmds,
                NumField::new(
                    "road.min_wavenumber_cpm",
                    min_wavenumber_cpm,
                    "cycles/m",
                    Apply::Live,
                )
                .show(ui, |v| {
                    with(&|r| {
                        if let Road::Random {
                            min_wavenumber_cpm, ..
                        } = r
                        {
                            *min_wavenumber_cpm = v;
                        }
                    })
                }),
            );
            ui.end_row();
            ui.label("highest n");
            push_edit(
                cmds,
                NumField::new(
                    "road.max_wavenumber_cpm",
                    max_wavenumber_cpm,
                    "cycles/m",
                    Apply::Live,
                )
                .show(ui, |v| {
                    with(&|r| {
                        if let Road::Random {
                            max_wavenumber_cpm, ..
                        } = r
                        {
                            *max_wavenumber_cpm = v;
                        }
                    })
                }),
            );
            ui.end_row();
        });
    // wrapped: cut at the panel's edge in a narrow panel
    ui.add(
        egui::Label::new(
            egui::RichText::new(format!(
                "wavelengths {:.3} m to {:.3} m; excitation {:.1} Hz to {:.1} Hz at V",
                1.0 / max_wavenumber_cpm,
                1.0 / min_wavenumber_cpm,
                scene.speed_mps * min_wavenumber_cpm,
                scene.speed_mps * max_wavenumber_cpm
            ))
            .weak(),
        )
        .wrap(),
    );
}
