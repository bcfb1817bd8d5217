//! The side panel of an FE tyre (`Tyre::FeModes`, method §5.4): its file,
//! nodes, axes, damping (editable when it is one ratio or Rayleigh's α,
//! β) and the modes read; changes restart the run, as for every tyre
//! field.

use super::push_edit;
use crate::Scene;
use crate::gui::model::command::Command;
use crate::gui::widgets::fields::{Apply, NumField, section};
use crate::readers::fe_modes::{FeDamping, FeNodes};
use crate::scene::{Mode, Tyre};
use egui::{Grid, Ui};

/// `scene` with its FE tyre's damping replaced.
fn with_damping(scene: &Scene, damping: FeDamping) -> Scene {
    let mut s = scene.clone();
    if let Tyre::FeModes { damping: d, .. } = &mut s.tyre {
        *d = damping;
    }
    s
}

pub fn show(ui: &mut Ui, scene: &Scene, modes: &[Mode], cmds: &mut Vec<Command>) {
    let Some(spec) = scene.tyre.fe_spec(None) else {
        return;
    };
    section(
        ui,
        "Tyre: FE modes (UFF 55/2414, docs/method.md §5.4)",
        Apply::Restart,
    );
    let num = crate::gui::widgets::number::format_number;
    Grid::new("tirecontact.fe_modes")
        .min_row_height(crate::gui::widgets::text_row_px(ui))
        .num_columns(2)
        .show(ui, |ui| {
            ui.label("file");
            ui.label(spec.file.display().to_string());
            ui.end_row();
            ui.label("nodes");
            ui.label(match &spec.nodes {
                FeNodes::Nearest => format!(
                    "nearest each point (within {} mm)",
                    num(spec.nearest_within_m * 1e3)
                ),
                FeNodes::List(v) if v.len() <= 6 => format!("{v:?}"),
                FeNodes::List(v) => format!("{} listed, {} … {}", v.len(), v[0], v[v.len() - 1]),
            });
            ui.end_row();
            ui.label("normal to the road");
            ui.label(format!("{} (away from the road)", spec.direction.name()));
            ui.end_row();
            ui.label("axes");
            ui.label(format!(
                "x along {}, y across {}",
                spec.axes.along.name(),
                spec.axes.across.name()
            ));
            ui.end_row();
            ui.label("damping");
            match &spec.damping {
                FeDamping::Ratio(x) => push_edit(
                    cmds,
                    NumField::new("tyre.damping.0", *x, "", Apply::Restart)
                        .width(55.0)
                        .show(ui, |v| with_damping(scene, FeDamping::Ratio(v))),
                ),
                FeDamping::Rayleigh {
                    alpha_per_s,
                    beta_s,
                } => {
                    let (a, b) = (*alpha_per_s, *beta_s);
                    ui.horizontal(|ui| {
                        ui.label("α");
                        push_edit(
                            cmds,
                            NumField::new("tyre.damping.alpha_per_s", a, "1/s", Apply::Restart)
                                .show(ui, |v| {
                                    with_damping(
                                        scene,
                                        FeDamping::Rayleigh {
                                            alpha_per_s: v,
                                            beta_s: b,
                                        },
                                    )
                                }),
                        );
                        ui.label("β");
                        push_edit(
                            cmds,
                            NumField::new("tyre.damping.beta_s", b, "s", Apply::Restart).show(
                                ui,
                                |v| {
                                    with_damping(
                                        scene,
                                        FeDamping::Rayleigh {
                                            alpha_per_s: a,
                                            beta_s: v,
                                        },
                                    )
                                },
                            ),
                        );
                    });
                }
                FeDamping::Modal(v) => {
                    ui.label(format!("one ratio per mode ({})", v.len()));
                }
                FeDamping::FromFile => {
                    ui.label("the records' viscous damping ratios");
                }
            }
            ui.end_row();
            ui.label("modes");
            match (modes.first(), modes.last()) {
                (Some(a), Some(b)) => ui.label(format!(
                    "{} from {} Hz to {} Hz",
                    modes.len(),
                    num(a.freq_hz),
                    num(b.freq_hz)
                )),
                _ => ui.label("none read yet"),
            };
            ui.end_row();
        });
    ui.label(
        egui::RichText::new(
            "the file, nodes and axes are edited in the preset file; `tirecontact check` lists the modes read, the node of each point and the unit factors",
        )
        .weak(),
    );
    super::modes_table::identified_modes(ui, scene, modes, cmds);
}
