//! Road profile (type, amplitude in mm, wavelength in m) and rolling speed
//! (km/h and m/s). Both apply live.

use super::push_edit;
use crate::Scene;
use crate::gui::model::command::Command;
use crate::gui::widgets::fields::{Apply, NumField, section};
use crate::model::road::{Harmonic, Road};
use egui::{Grid, Ui};

pub fn show(
    ui: &mut Ui,
    scene: &Scene,
    profile: &crate::model::road::RoadProfile,
    cmds: &mut Vec<Command>,
) {
    section(ui, "Road", Apply::Live);
    road_type(ui, scene, cmds);
    match &scene.road {
        Road::Sine {
            amplitude_m,
            wavelength_m,
        } => {
            Grid::new("tirecontact.road")
                .min_row_height(crate::gui::widgets::text_row_px(ui))
                .num_columns(2)
                .show(ui, |ui| {
                    ui.label("amplitude a");
                    push_edit(
                        cmds,
                        NumField::new("road.amplitude_m", *amplitude_m, "mm", Apply::Live)
                            .scale(1e3)
                            .show(ui, |v| {
                                with_road(
                                    scene,
                                    Road::Sine {
                                        amplitude_m: v,
                                        wavelength_m: *wavelength_m,
                                    },
                                )
                            }),
                    );
                    ui.end_row();
                    ui.label("wavelength λ");
                    push_edit(
                        cmds,
                        NumField::new("road.wavelength_m", *wavelength_m, "m", Apply::Live).show(
                            ui,
                            |v| {
                                with_road(
                                    scene,
                                    Road::Sine {
                                        amplitude_m: *amplitude_m,
                                        wavelength_m: v,
                                    },
                                )
                            },
                        ),
                    );
                    ui.end_row();
                });
            if *wavelength_m > 0.0 {
                ui.label(
                    egui::RichText::new(format!(
                        "excitation frequency V/λ = {:.1} Hz",
                        scene.speed_mps / wavelength_m
                    ))
                    .weak(),
                );
            }
        }
        Road::Harmonics { components } => harmonics(ui, scene, components, cmds),
        Road::Measured { file, looped } => {
            ui.label(format!(
                "measured profile {} ({})",
                file.display(),
                if *looped { "looped" } else { "not looped" }
            ));
        }
        Road::Random { .. } => super::random_road::show(ui, scene, cmds),
        Road::Surface { .. } | Road::Crg { .. } => {
            super::patch_panel::surface(ui, scene, Some(profile))
        }
        Road::Texture { .. } => super::patch_panel::texture(ui, scene, cmds),
    }
    section(ui, "Speed", Apply::Live);
    Grid::new("tirecontact.speed")
        .min_row_height(crate::gui::widgets::text_row_px(ui))
        .num_columns(2)
        .show(ui, |ui| {
            ui.label("speed V");
            push_edit(
                cmds,
                NumField::new("speed_kmh", scene.speed_mps, "km/h", Apply::Live)
                    .field("speed_mps")
                    .scale(3.6)
                    .show(ui, |v| with_speed(scene, v)),
            );
            ui.end_row();
            ui.label("");
            push_edit(
                cmds,
                NumField::new("speed_mps", scene.speed_mps, "m/s", Apply::Live)
                    .show(ui, |v| with_speed(scene, v)),
            );
            ui.end_row();
        });
}

fn road_type(ui: &mut Ui, scene: &Scene, cmds: &mut Vec<Command>) {
    let kind = scene.road.kind();
    ui.horizontal(|ui| {
        ui.label("type");
        egui::ComboBox::from_id_salt("tirecontact.road_type")
            .selected_text(kind)
            .show_ui(ui, |ui| {
                if ui.selectable_label(kind == "sine", "sine").clicked() && kind != "sine" {
                    let (a, l) = match &scene.road {
                        Road::Harmonics { components } => components
                            .first()
                            .map_or((0.002, 0.5), |c| (c.amplitude_m.abs(), c.wavelength_m)),
                        _ => (0.002, 0.5),
                    };
                    cmds.push(edit(with_road(
                        scene,
                        Road::Sine {
                            amplitude_m: a,
                            wavelength_m: l,
                        },
                    )));
                }
                if ui
                    .selectable_label(kind == "harmonics", "harmonics")
                    .clicked()
                    && kind != "harmonics"
                {
                    let first = match &scene.road {
                        Road::Sine {
                            amplitude_m,
                            wavelength_m,
                        } => Harmonic {
                            amplitude_m: *amplitude_m,
                            wavelength_m: *wavelength_m,
                            phase_rad: 0.0,
                        },
                        _ => Harmonic {
                            amplitude_m: 0.002,
                            wavelength_m: 0.5,
                            phase_rad: 0.0,
                        },
                    };
                    cmds.push(edit(with_road(
                        scene,
                        Road::Harmonics {
                            components: vec![first],
                        },
                    )));
                }
                if ui
                    .selectable_label(kind == "random", "random (ISO 8608)")
                    .clicked()
                    && kind != "random"
                {
                    cmds.push(edit(with_road(scene, super::random_road::default_road())));
                }
                ui.add_enabled(
                    false,
                    egui::Button::selectable(kind == "measured", "measured"),
                )
                .on_disabled_hover_text(
                    "measured profiles are set in the preset file (road: Measured(file: ...))",
                );
            })
            .response
            .accessible_name("road type")
            .on_hover_text(ROAD_TYPE_HELP);
    });
}

fn harmonics(ui: &mut Ui, scene: &Scene, comps: &[Harmonic], cmds: &mut Vec<Command>) {
    Grid::new("tirecontact.harmonics")
        .min_row_height(crate::gui::widgets::text_row_px(ui))
        .striped(true)
        .num_columns(4)
        .show(ui, |ui| {
            ui.label("amplitude");
            ui.label("wavelength");
            ui.label("phase");
            ui.label("");
            ui.end_row();
            for (k, c) in comps.iter().enumerate() {
                let with = |f: &dyn Fn(&mut Harmonic)| {
                    let mut v = comps.to_vec();
                    f(&mut v[k]);
                    with_road(scene, Road::Harmonics { components: v })
                };
                let name = format!("road.components[{k}].amplitude_m");
                push_edit(
                    cmds,
                    NumField::new(&name, c.amplitude_m, "mm", Apply::Live)
                        .scale(1e3)
                        .width(55.0)
                        .show(ui, |v| with(&|h| h.amplitude_m = v)),
                );
                let name = format!("road.components[{k}].wavelength_m");
                push_edit(
                    cmds,
                    NumField::new(&name, c.wavelength_m, "m", Apply::Live)
                        .width(55.0)
                        .show(ui, |v| with(&|h| h.wavelength_m = v)),
                );
                let name = format!("road.components[{k}].phase_rad");
                push_edit(
                    cmds,
                    NumField::new(&name, c.phase_rad, "rad", Apply::Live)
                        .width(45.0)
                        .show(ui, |v| with(&|h| h.phase_rad = v)),
                );
                if ui
                    .add_enabled(comps.len() > 1, egui::Button::new("Remove").small())
                    .clicked()
                {
                    let mut v = comps.to_vec();
                    v.remove(k);
                    cmds.push(edit(with_road(scene, Road::Harmonics { components: v })));
                }
                ui.end_row();
            }
        });
    if ui.button("Add harmonic").clicked() {
        let mut v = comps.to_vec();
        let mut h = v.last().cloned().unwrap_or(Harmonic {
            amplitude_m: 0.001,
            wavelength_m: 0.5,
            phase_rad: 0.0,
        });
        h.wavelength_m /= 2.0;
        h.amplitude_m /= 2.0;
        v.push(h);
        cmds.push(edit(with_road(scene, Road::Harmonics { components: v })));
    }
}

fn edit(s: Scene) -> Command {
    Command::EditScene(Box::new(s))
}

fn with_road(scene: &Scene, road: Road) -> Scene {
    let mut s = scene.clone();
    s.road = road;
    s
}

fn with_speed(scene: &Scene, v: f64) -> Scene {
    let mut s = scene.clone();
    s.speed_mps = v;
    s
}

/// What the road types are (the road type list's tooltip).
pub const ROAD_TYPE_HELP: &str = "The road profile under the tyre (applied live): sine, one \
    wave of an amplitude and a wavelength; harmonics, a sum of sines; random, an ISO 8608 road \
    of a class A (smooth) to H (very rough); measured, a profile file (set in the preset file).";
