//! The contact patch and the roads that vary across the tread. A scene
//! whose points are a `Grid(...)`: points along and rows across, their
//! spacing and the preload (a flat press or a parabolic footprint); every
//! change restarts the run (the points change). A texture road: class,
//! seed, periods along and across and its wavenumber band, applied live as
//! every road edit (generated off the UI thread). A surface road: its file
//! and the facts of its grid (read only: the file is the road).

use super::push_edit;
use crate::Scene;
use crate::gui::model::command::Command;
use crate::gui::widgets::fields::{Apply, NumField, section};
use crate::model::road::{Road, RoadProfile};
use crate::scene::points::{PointGrid, Points, Preload};
use egui::{Grid, Ui};

/// The scene with its points the grid `g` (the grid form kept for Save).
fn with_grid(scene: &Scene, g: PointGrid) -> Scene {
    let mut s = scene.clone();
    s.points = Points::from_grid(g);
    s
}

/// A count typed in a field: the nearest whole number, 0 for anything
/// below one half (refused by the grid's check, naming the field).
fn count(v: f64) -> usize {
    if v.is_finite() && v >= 0.5 {
        v.round().min(u32::MAX as f64) as usize
    } else {
        0
    }
}

/// The grid's fields, when the scene's points are a `Grid(...)`.
pub fn grid(ui: &mut Ui, scene: &Scene, cmds: &mut Vec<Command>) {
    let Some(&g) = scene.points.grid() else {
        return;
    };
    section(ui, "Contact patch (grid)", Apply::Restart);
    ui.label(
        egui::RichText::new(format!(
            "{} points: {} along the rolling direction in each of {} rows across",
            g.along * g.across,
            g.along,
            g.across
        ))
        .weak(),
    );
    Grid::new("tirecontact.patch_grid")
        .min_row_height(crate::gui::widgets::text_row_px(ui))
        .num_columns(2)
        .show(ui, |ui| {
            ui.label("points along");
            push_edit(
                cmds,
                NumField::new("points.along", g.along as f64, "", Apply::Restart).show(ui, |v| {
                    with_grid(
                        scene,
                        PointGrid {
                            along: count(v),
                            ..g
                        },
                    )
                }),
            );
            ui.end_row();
            ui.label("rows across");
            push_edit(
                cmds,
                NumField::new("points.across", g.across as f64, "", Apply::Restart).show(ui, |v| {
                    with_grid(
                        scene,
                        PointGrid {
                            across: count(v),
                            ..g
                        },
                    )
                }),
            );
            ui.end_row();
            ui.label("spacing along Δx");
            push_edit(
                cmds,
                NumField::new("points.spacing_m.0", g.spacing_m.0, "mm", Apply::Restart)
                    .scale(1e3)
                    .show(ui, |v| {
                        with_grid(
                            scene,
                            PointGrid {
                                spacing_m: (v, g.spacing_m.1),
                                ..g
                            },
                        )
                    }),
            );
            ui.end_row();
            ui.label("spacing across Δy");
            push_edit(
                cmds,
                NumField::new("points.spacing_m.1", g.spacing_m.1, "mm", Apply::Restart)
                    .scale(1e3)
                    .show(ui, |v| {
                        with_grid(
                            scene,
                            PointGrid {
                                spacing_m: (g.spacing_m.0, v),
                                ..g
                            },
                        )
                    }),
            );
            ui.end_row();
            ui.label("preload");
            let parabolic = matches!(g.preload, Preload::Parabolic { .. });
            let depth_m = match g.preload {
                Preload::Flat { depth_m } | Preload::Parabolic { depth_m, .. } => depth_m,
            };
            let mut chosen = parabolic;
            egui::ComboBox::from_id_salt("tirecontact.preload")
                .selected_text(if parabolic {
                    "parabolic footprint"
                } else {
                    "flat press"
                })
                .show_ui(ui, |ui| {
                    ui.selectable_value(&mut chosen, false, "flat press");
                    ui.selectable_value(&mut chosen, true, "parabolic footprint");
                })
                .response
                .accessible_name("preload")
                .on_hover_text(
                    "flat: every point pressed the depth into the road; parabolic: \
                     h(x) = -depth (1 - (2x / length)²) along the rolling direction",
                );
            if chosen != parabolic {
                let preload = if chosen {
                    // a footprint as long as the grid (a point spacing beyond it)
                    Preload::Parabolic {
                        depth_m,
                        length_m: (g.along as f64 + 1.0) * g.spacing_m.0,
                    }
                } else {
                    Preload::Flat { depth_m }
                };
                cmds.push(Command::EditScene(Box::new(with_grid(
                    scene,
                    PointGrid { preload, ..g },
                ))));
            }
            ui.end_row();
            ui.label("press depth");
            push_edit(
                cmds,
                NumField::new("points.preload.depth_m", depth_m, "mm", Apply::Restart)
                    .scale(1e3)
                    .show(ui, |v| {
                        let preload = match g.preload {
                            Preload::Flat { .. } => Preload::Flat { depth_m: v },
                            Preload::Parabolic { length_m, .. } => Preload::Parabolic {
                                depth_m: v,
                                length_m,
                            },
                        };
                        with_grid(scene, PointGrid { preload, ..g })
                    }),
            );
            ui.end_row();
            if let Preload::Parabolic { length_m, .. } = g.preload {
                ui.label("footprint length");
                push_edit(
                    cmds,
                    NumField::new("points.preload.length_m", length_m, "mm", Apply::Restart)
                        .scale(1e3)
                        .show(ui, |v| {
                            with_grid(
                                scene,
                                PointGrid {
                                    preload: Preload::Parabolic {
                                        depth_m,
                                        length_m: v,
                                    },
                                    ..g
                                },
                            )
                        }),
                );
                ui.end_row();
            }
        });
}

/// A texture road's fields: class, seed, periods and wavenumber band.
pub fn texture(ui: &mut Ui, scene: &Scene, cmds: &mut Vec<Command>) {
    let Road::Texture {
        class,
        seed,
        length_m,
        width_m,
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
    ui.label(
        egui::RichText::new(
            "a random surface: every profile along or across has the ISO 8608 class's spectrum",
        )
        .weak(),
    );
    Grid::new("tirecontact.texture")
        .min_row_height(crate::gui::widgets::text_row_px(ui))
        .num_columns(2)
        .show(ui, |ui| {
            ui.label("ISO 8608 class");
            let mut chosen = class;
            egui::ComboBox::from_id_salt("tirecontact.texture_class")
                .selected_text(super::random_road::class_name(class))
                .show_ui(ui, |ui| {
                    for (c, name) in super::random_road::CLASSES {
                        ui.selectable_value(&mut chosen, c, name);
                    }
                })
                .response
                .accessible_name("texture class");
            if chosen != class {
                cmds.push(Command::EditScene(Box::new(with(&|r| {
                    if let Road::Texture { class, .. } = r {
                        *class = chosen;
                    }
                }))));
            }
            ui.end_row();
            super::random_road::seed_row(ui, scene, seed, "texture", cmds);
            let fields: [(&str, &str, f64, &str, f64); 4] = [
                ("period along", "road.length_m", length_m, "m", 1.0),
                ("period across", "road.width_m", width_m, "mm", 1e3),
                (
                    "lowest n",
                    "road.min_wavenumber_cpm",
                    min_wavenumber_cpm,
                    "cycles/m",
                    1.0,
                ),
                (
                    "highest n",
                    "road.max_wavenumber_cpm",
                    max_wavenumber_cpm,
                    "cycles/m",
                    1.0,
                ),
            ];
            for (k, (label, name, value, unit, scale)) in fields.into_iter().enumerate() {
                ui.label(label);
                push_edit(
                    cmds,
                    NumField::new(name, value, unit, Apply::Live)
                        .scale(scale)
                        .show(ui, |v| {
                            with(&|r| {
                                if let Road::Texture {
                                    length_m,
                                    width_m,
                                    min_wavenumber_cpm,
                                    max_wavenumber_cpm,
                                    ..
                                } = r
                                {
                                    *[length_m, width_m, min_wavenumber_cpm, max_wavenumber_cpm]
                                        [k] = v;
                                }
                            })
                        }),
                );
                ui.end_row();
            }
        });
    if min_wavenumber_cpm > 0.0 && max_wavenumber_cpm > 0.0 {
        ui.add(
            egui::Label::new(
                egui::RichText::new(format!(
                    "wavelengths {:.1} mm to {:.1} mm; excitation {:.0} Hz to {:.0} Hz at V",
                    1e3 / max_wavenumber_cpm,
                    1e3 / min_wavenumber_cpm,
                    scene.speed_mps * min_wavenumber_cpm,
                    scene.speed_mps * max_wavenumber_cpm
                ))
                .weak(),
            )
            .wrap(),
        );
    }
}

/// A surface road's file and, once read, the facts of its grid.
pub fn surface(ui: &mut Ui, scene: &Scene, profile: Option<&RoadProfile>) {
    let title = match &scene.road {
        Road::Surface { file, looped } => format!(
            "road surface {} ({})",
            file.display(),
            if *looped {
                "looped along x"
            } else {
                "not looped"
            }
        ),
        Road::Crg {
            file,
            u_start_m,
            v_offset_m,
        } => format!(
            "OpenCRG road {} (from u = {}, v offset {} m; not looped)",
            file.display(),
            u_start_m.map_or("its start".to_string(), |u| format!("{u} m")),
            v_offset_m
        ),
        _ => return,
    };
    ui.add(egui::Label::new(title).wrap());
    if let (Road::Crg { .. }, Some(RoadProfile::Surface(g))) = (&scene.road, profile) {
        for line in crg_lines(scene, g) {
            ui.add(egui::Label::new(egui::RichText::new(line).weak()).wrap());
        }
        ui.label(
            egui::RichText::new("the file is the road: edit it, then open the preset again").weak(),
        );
        return;
    }
    if let Some(RoadProfile::Surface(g)) = profile
        && g.datum_m != 0.0
    {
        ui.add(
            egui::Label::new(
                egui::RichText::new(format!(
                    "heights from the road's mean plane: {:.4} m taken off the file's",
                    g.datum_m
                ))
                .weak(),
            )
            .wrap(),
        );
    }
    if let Some(RoadProfile::Surface(g)) = profile {
        let (x0, x1) = g.x_range_m();
        let y = g
            .y_range_m()
            .map_or("repeating across".to_string(), |(a, b)| {
                format!("y {:.1} mm to {:.1} mm", a * 1e3, b * 1e3)
            });
        let mpd = g.mpd_m().map_or(String::new(), |m| {
            format!("; mean profile depth {:.2} mm", m * 1e3)
        });
        ui.add(
            egui::Label::new(
                egui::RichText::new(format!(
                    "{} × {} nodes ({} in all), Δx {:.2} mm, Δy {:.2} mm; x {:.3} m to {:.3} m, {y}{mpd}",
                    g.nx,
                    g.ny,
                    g.nx * g.ny,
                    g.dx_m * 1e3,
                    g.dy_m * 1e3,
                    x0,
                    x1
                ))
                .weak(),
            )
            .wrap(),
        );
    }
    ui.label(
        egui::RichText::new("the file is the road: edit it, then open the preset again").weak(),
    );
}

/// What the side panel says of an OpenCRG road, a line each: the file's
/// `u` and `v` ranges and grid spacing, its absolute height and how the
/// heights are referred to the mean road plane, and the strip the run
/// travels (`u` from `u_start_m` over the points' `x` plus speed ×
/// duration, `v` of the points' `y` from `v_offset_m`).
pub fn crg_lines(scene: &Scene, g: &crate::model::road::SurfaceGrid) -> Vec<String> {
    let (u0, v0) = g.file_origin_m;
    let (x0, x1) = g.x_range_m();
    let (y0, y1) = g.y_range_m().unwrap_or((g.y0_m, g.y0_m));
    let (mut xa, mut xb, mut ya, mut yb) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for p in scene.points.iter() {
        xa = xa.min(p.x_m);
        xb = xb.max(p.x_m);
        ya = ya.min(p.y_m);
        yb = yb.max(p.y_m);
    }
    let travel = scene.speed_mps.max(0.0) * scene.duration_s;
    let mut lines = vec![
        format!(
            "file's grid: u {:.3} m to {:.3} m, v {:.3} m to {:.3} m (v positive to the left); {} × {} nodes, Δu {:.2} mm, Δv {:.2} mm",
            x0 + u0,
            x1 + u0,
            y0 + v0,
            y1 + v0,
            g.nx,
            g.ny,
            g.dx_m * 1e3,
            g.dy_m * 1e3
        ),
        format!(
            "absolute height: the file's mean road plane at {:.4} m (h datum); heights here are the file's less it, so h_m is measured from that plane",
            g.datum_m
        ),
    ];
    if xa.is_finite() {
        lines.push(format!(
            "travelled strip: u {:.3} m to {:.3} m (from u = {:.3} m under x = 0, speed × duration {:.3} m), v {:.3} m to {:.3} m (v offset {:.3} m)",
            u0 + xa,
            u0 + xb + travel,
            u0,
            travel,
            v0 + ya,
            v0 + yb,
            v0
        ));
    }
    lines
}
