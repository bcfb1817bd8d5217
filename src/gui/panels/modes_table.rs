//! The modes table: frequency, damping ratio, mode shape or residue matrix;
//! add, duplicate, remove. Every change restarts the run.

use super::{modes_mut, push_edit};
use crate::Scene;
use crate::gui::model::command::Command;
use crate::gui::widgets::fields::{Apply, NumField, section};
use crate::model::ring::RingParams;
use crate::scene::{Mode, Tyre};
use egui::{Grid, RichText, Ui};

/// Under the ring's identified modes: where their residues are.
pub const RING_RESIDUES_NOTE: &str = "their residue matrices A (1/kg): in the modes table after \"Edit as a modal model\", or in the file `tirecontact identify PRESET -o FILE` writes";

/// Largest number of points whose residue matrix is edited inline.
const MAX_INLINE_MATRIX: usize = 8;

/// The tyre's modes: a modal tyre's table, or the summary of a ring, a
/// measured tyre or a plate with the modes identified from it (an FE
/// tyre has its own panel, `fe_panel`).
pub fn show(ui: &mut Ui, scene: &Scene, modes: &[Mode], cmds: &mut Vec<Command>) {
    match &scene.tyre {
        Tyre::Ring { ring, .. } => return ring_summary(ui, scene, ring, modes, cmds),
        Tyre::Measured {
            file,
            identification,
            ..
        } => return measured_summary(ui, scene, file, identification, modes, cmds),
        Tyre::Plate { plate } => return plate_summary(ui, scene, plate, modes, cmds),
        Tyre::Modal { .. } | Tyre::FeModes { .. } => {}
    }
    section(ui, "Modes", Apply::Restart);
    let p = scene.num_points();
    Grid::new("tirecontact.modes")
        .min_row_height(crate::gui::widgets::text_row_px(ui))
        .striped(true)
        .num_columns(4)
        .show(ui, |ui| {
            ui.label("#");
            ui.label("frequency");
            ui.label("damping ratio");
            ui.label("");
            ui.end_row();
            for (k, m) in modes.iter().enumerate() {
                ui.label(k.to_string());
                let name = format!("tyre.modes[{k}].freq_hz");
                push_edit(
                    cmds,
                    NumField::new(&name, m.freq_hz, "Hz", Apply::Restart)
                        .show(ui, |v| with_mode(scene, k, |m| m.freq_hz = v)),
                );
                let name = format!("tyre.modes[{k}].damping_ratio");
                push_edit(
                    cmds,
                    NumField::new(&name, m.damping_ratio, "", Apply::Restart)
                        .width(55.0)
                        .show(ui, |v| with_mode(scene, k, |m| m.damping_ratio = v)),
                );
                ui.horizontal(|ui| {
                    if ui
                        .small_button("Duplicate")
                        .on_hover_text("add a copy of this mode after it")
                        .clicked()
                    {
                        let mut s = scene.clone();
                        if let Some(ms) = modes_mut(&mut s) {
                            ms.insert(k + 1, m.clone());
                            cmds.push(Command::EditScene(Box::new(s)));
                        }
                    }
                    let remove =
                        ui.add_enabled(modes.len() > 1, egui::Button::new("Remove").small());
                    if remove
                        .on_hover_text("remove this mode from the tyre (restarts the run)")
                        .on_disabled_hover_text("a scene needs at least one mode")
                        .clicked()
                    {
                        let mut s = scene.clone();
                        if let Some(ms) = modes_mut(&mut s) {
                            ms.remove(k);
                            cmds.push(Command::EditScene(Box::new(s)));
                        }
                    }
                });
                ui.end_row();
            }
        });
    if ui
        .button("Add mode")
        .on_hover_text("a new mode at 1.5x the last frequency, same shape")
        .clicked()
    {
        let mut s = scene.clone();
        if let Some(ms) = modes_mut(&mut s) {
            let mut m = ms.last().cloned().unwrap_or(Mode {
                freq_hz: 100.0,
                damping_ratio: 0.05,
                residue: Vec::new(),
                shape: vec![0.3; p],
            });
            m.freq_hz *= 1.5;
            ms.push(m);
            cmds.push(Command::EditScene(Box::new(s)));
        }
    }
    for (k, m) in modes.iter().enumerate() {
        let title = if m.shape.is_empty() {
            format!("mode {k}: residue matrix A (1/kg), {p}x{p}")
        } else {
            format!("mode {k}: shape φ (1/√kg), {p} values")
        };
        egui::CollapsingHeader::new(title)
            .id_salt(("tirecontact.mode_detail", k))
            .show(ui, |ui| {
                if m.shape.is_empty() {
                    residue_grid(ui, scene, k, m, cmds);
                } else {
                    shape_grid(ui, scene, k, m, cmds);
                }
            });
    }
}

fn shape_grid(ui: &mut Ui, scene: &Scene, k: usize, m: &Mode, cmds: &mut Vec<Command>) {
    Grid::new(("tirecontact.shape", k))
        .min_row_height(crate::gui::widgets::text_row_px(ui))
        .show(ui, |ui| {
            for (i, &a) in m.shape.iter().enumerate() {
                ui.label(format!("point {i}"));
                let name = format!("tyre.modes[{k}].shape[{i}]");
                push_edit(
                    cmds,
                    NumField::new(&name, a, "1/√kg", Apply::Restart).show(ui, |v| {
                        with_mode(scene, k, |m| {
                            if let Some(x) = m.shape.get_mut(i) {
                                *x = v;
                            }
                        })
                    }),
                );
                ui.end_row();
            }
        });
}

fn residue_grid(ui: &mut Ui, scene: &Scene, k: usize, m: &Mode, cmds: &mut Vec<Command>) {
    let p = m.residue.len();
    if p > MAX_INLINE_MATRIX {
        ui.label(format!(
            "{p}x{p} matrix: edit it in the preset file (inline editing up to {MAX_INLINE_MATRIX} points)"
        ));
        return;
    }
    ui.label("row i = receiving point, column j = loaded point");
    Grid::new(("tirecontact.residue", k))
        .min_row_height(crate::gui::widgets::text_row_px(ui))
        .show(ui, |ui| {
            // the points' indices: columns j above, rows i on the left
            ui.label(RichText::new("i \\ j").weak());
            for j in 0..p {
                ui.label(RichText::new(j.to_string()).weak());
            }
            ui.end_row();
            for (i, row) in m.residue.iter().enumerate() {
                ui.label(RichText::new(i.to_string()).weak());
                for (j, &a) in row.iter().enumerate() {
                    let name = format!("tyre.modes[{k}].residue[{i}][{j}]");
                    push_edit(
                        cmds,
                        NumField::new(&name, a, "", Apply::Restart)
                            .width(60.0)
                            .show(ui, |v| {
                                with_mode(scene, k, |m| {
                                    if let Some(x) = m.residue.get_mut(i).and_then(|r| r.get_mut(j))
                                    {
                                        *x = v;
                                    }
                                })
                            }),
                    );
                }
                ui.end_row();
            }
        });
}

/// The scene with mode `k` changed by `f`.
fn with_mode(scene: &Scene, k: usize, f: impl FnOnce(&mut Mode)) -> Scene {
    let mut s = scene.clone();
    if let Some(m) = modes_mut(&mut s).and_then(|ms| ms.get_mut(k)) {
        f(m);
    }
    s
}

/// A ring tyre: its parameters and the modes identified from it (read-only),
/// and a way to turn them into an editable modal model.
fn ring_summary(
    ui: &mut Ui,
    scene: &Scene,
    ring: &RingParams,
    modes: &[Mode],
    cmds: &mut Vec<Command>,
) {
    section(ui, "Tyre: ring model (docs/method.md §5)", Apply::Restart);
    Grid::new("tirecontact.ring")
        .min_row_height(crate::gui::widgets::text_row_px(ui))
        .num_columns(2)
        .show(ui, |ui| {
            let rows = [
                ("radius", ring.radius_m, "m"),
                ("belt width", ring.belt_width_m, "m"),
                ("mass per length", ring.mass_per_length_kg_m, "kg/m"),
                ("inflation", ring.inflation_pa * 1e-5, "bar"),
                ("radial stiffness", ring.radial_stiffness_n_m2, "N/m²"),
                (
                    "tangential stiffness",
                    ring.tangential_stiffness_n_m2,
                    "N/m²",
                ),
                ("bending stiffness EI", ring.bending_stiffness_n_m2, "N m²"),
                ("damping ratio", ring.damping_ratio, ""),
            ];
            for (name, v, unit) in rows {
                ui.label(name);
                ui.label(format!(
                    "{} {unit}",
                    crate::gui::widgets::number::format_number(v)
                ));
                ui.end_row();
            }
        });
    ui.label(
        egui::RichText::new("ring parameters are edited in the preset file; the modes below are identified from the ring by LSCE at the points' positions")
            .weak(),
    );
    identified_modes(ui, scene, modes, cmds);
}

/// A plate tyre: its parameters, each edited as the other tyres' (a
/// refused value named with its field, the value and the range accepted),
/// and the number of modes kept.
fn plate_summary(
    ui: &mut Ui,
    scene: &Scene,
    plate: &crate::model::plate::PlateParams,
    modes: &[Mode],
    cmds: &mut Vec<Command>,
) {
    use crate::model::plate::PlateParams;
    section(
        ui,
        "Tyre: orthotropic plate (docs/method.md §5.3)",
        Apply::Restart,
    );
    type Get = fn(&mut PlateParams) -> &mut f64;
    let rows: [(&str, &str, &str, Get); 10] = [
        ("width W", "tyre.plate.width_m", "m", |p| &mut p.width_m),
        ("circumference L", "tyre.plate.circumference_m", "m", |p| {
            &mut p.circumference_m
        }),
        (
            "mass per area",
            "tyre.plate.mass_per_area_kg_m2",
            "kg/m²",
            |p| &mut p.mass_per_area_kg_m2,
        ),
        (
            "bending along Bx",
            "tyre.plate.bending_along_nm",
            "N·m",
            |p| &mut p.bending_along_nm,
        ),
        (
            "bending across By",
            "tyre.plate.bending_across_nm",
            "N·m",
            |p| &mut p.bending_across_nm,
        ),
        (
            "tension along Tx",
            "tyre.plate.tension_along_n_m",
            "N/m",
            |p| &mut p.tension_along_n_m,
        ),
        (
            "tension across Ty",
            "tyre.plate.tension_across_n_m",
            "N/m",
            |p| &mut p.tension_across_n_m,
        ),
        ("foundation s", "tyre.plate.foundation_n_m3", "N/m³", |p| {
            &mut p.foundation_n_m3
        }),
        ("damping ratio", "tyre.plate.damping_ratio", "", |p| {
            &mut p.damping_ratio
        }),
        ("modes up to", "tyre.plate.max_freq_hz", "Hz", |p| {
            &mut p.max_freq_hz
        }),
    ];
    Grid::new("tirecontact.plate")
        .min_row_height(crate::gui::widgets::text_row_px(ui))
        .num_columns(2)
        .show(ui, |ui| {
            for (label, path, unit, get) in rows {
                ui.label(label);
                let mut now = plate.clone();
                let value = *get(&mut now);
                push_edit(
                    cmds,
                    NumField::new(path, value, unit, Apply::Restart).show(ui, |v| {
                        let mut s = scene.clone();
                        if let Tyre::Plate { plate } = &mut s.tyre {
                            *get(plate) = v;
                        }
                        s
                    }),
                );
                ui.end_row();
            }
        });
    let lowest = modes.first().map_or(f64::NAN, |m| m.freq_hz);
    ui.label(
        egui::RichText::new(format!(
            "{} modes from {} Hz, in closed form at the points",
            modes.len(),
            crate::gui::widgets::number::format_number(lowest)
        ))
        .weak(),
    );
}

/// A measured tyre: its data file and identification band, and the modes
/// identified from its responses (read-only), with the way to a modal model.
fn measured_summary(
    ui: &mut Ui,
    scene: &Scene,
    file: &std::path::Path,
    identification: &crate::model::lsce::IdentifyOptions,
    modes: &[Mode],
    cmds: &mut Vec<Command>,
) {
    section(
        ui,
        "Tyre: measured responses (LSCE, docs/method.md §6)",
        Apply::Restart,
    );
    let num = crate::gui::widgets::number::format_number;
    Grid::new("tirecontact.measured")
        .min_row_height(crate::gui::widgets::text_row_px(ui))
        .num_columns(2)
        .show(ui, |ui| {
            ui.label("data file");
            ui.label(file.display().to_string());
            ui.end_row();
            ui.label("band");
            ui.label(format!(
                "{} … {} Hz",
                num(identification.band_hz.0),
                num(identification.band_hz.1)
            ));
            ui.end_row();
            ui.label("identified over");
            ui.label(format!("the first {} s", num(identification.duration_s)));
            ui.end_row();
        });
    ui.label(
        egui::RichText::new("the data file and the identification options are edited in the preset file; the modes below are identified from the data by LSCE")
            .weak(),
    );
    identified_modes(ui, scene, modes, cmds);
}

/// "Edit as a modal model" and the list of a tyre's identified modes.
pub(super) fn identified_modes(
    ui: &mut Ui,
    scene: &Scene,
    modes: &[Mode],
    cmds: &mut Vec<Command>,
) {
    if ui
        .button("Edit as a modal model")
        .on_hover_text(
            "replace the tyre by its identified modes, which can then be tuned one by one",
        )
        .clicked()
    {
        let mut s = scene.clone();
        s.tyre = Tyre::Modal {
            modes: modes.to_vec(),
        };
        cmds.push(Command::EditScene(Box::new(s)));
    }
    let how = if matches!(scene.tyre, Tyre::FeModes { .. }) {
        "modes read"
    } else {
        "identified modes"
    };
    egui::CollapsingHeader::new(format!("{} {how}, used by the run", modes.len()))
        .id_salt("tirecontact.ring_modes")
        .show(ui, |ui| {
            Grid::new("tirecontact.ring_modes_grid")
                .min_row_height(crate::gui::widgets::text_row_px(ui))
                .striped(true)
                .show(ui, |ui| {
                    ui.label("#");
                    ui.label("frequency (Hz)");
                    ui.label("damping ratio");
                    ui.end_row();
                    for (k, m) in modes.iter().enumerate() {
                        ui.label(k.to_string());
                        ui.label(format!("{:.2}", m.freq_hz));
                        ui.label(format!("{:.4}", m.damping_ratio));
                        ui.end_row();
                    }
                });
            // a researcher looked here for the residues in vain
            ui.label(RING_RESIDUES_NOTE);
        });
}
