//! Contact points: position along the contact line and across the tread,
//! and undeformed height; add and remove (the modes' shapes and residues
//! follow). Every change restarts the run.

use super::{modes_mut, push_edit};
use crate::Scene;
use crate::gui::model::command::Command;
use crate::gui::widgets::fields::{Apply, NumField, section};
use crate::scene::Point;
use egui::{Grid, Ui};

/// Points listed without a scroll area of their own.
const MAX_LISTED: usize = 64;

pub fn show(ui: &mut Ui, scene: &Scene, cmds: &mut Vec<Command>) {
    section(ui, "Contact points", Apply::Restart);
    ui.label(egui::RichText::new("h < 0: the undeformed tyre is below the road (preload)").weak());
    let p = scene.num_points();
    // a phone: each point's Remove on a row of its own, under its position
    // (beside the three fields it ran past a 390 px screen's edge)
    let narrow = ui.ctx().content_rect().width() < crate::gui::widgets::NARROW_PX;
    Grid::new("tirecontact.points")
        .min_row_height(crate::gui::widgets::text_row_px(ui))
        .striped(true)
        .num_columns(5)
        .show(ui, |ui| {
            ui.label("#");
            ui.label("position x");
            ui.label("across y");
            ui.label("height h");
            ui.label("");
            ui.end_row();
            for (i, pt) in scene.points.iter().enumerate().take(MAX_LISTED) {
                ui.label(i.to_string());
                let name = format!("points[{i}].x_m");
                push_edit(
                    cmds,
                    NumField::new(&name, pt.x_m, "m", Apply::Restart)
                        .show(ui, |v| with_point(scene, i, |pt| pt.x_m = v)),
                );
                let name = format!("points[{i}].y_m");
                push_edit(
                    cmds,
                    NumField::new(&name, pt.y_m, "m", Apply::Restart)
                        .show(ui, |v| with_point(scene, i, |pt| pt.y_m = v)),
                );
                let name = format!("points[{i}].h_m");
                push_edit(
                    cmds,
                    NumField::new(&name, pt.h_m, "mm", Apply::Restart)
                        .scale(1e3)
                        .show(ui, |v| with_point(scene, i, |pt| pt.h_m = v)),
                );
                if narrow {
                    ui.end_row();
                    ui.label("");
                }
                // small beside the fields; a fingertip's size on a phone
                let button = egui::Button::new("Remove");
                let button = if narrow { button } else { button.small() };
                let remove = ui.add_enabled(p > 1, button);
                if remove
                    .on_hover_text("remove this contact point (restarts the run)")
                    .on_disabled_hover_text("a scene needs at least one point")
                    .clicked()
                {
                    cmds.push(Command::EditScene(Box::new(remove_point(scene, i))));
                }
                ui.end_row();
            }
        });
    if p > MAX_LISTED {
        ui.label(format!(
            "… {} more points (edit them in the preset file)",
            p - MAX_LISTED
        ));
    }
    if ui
        .button("Add point")
        .on_hover_text("a point after the last one, at its y; its mode shape values copy the last point's, its residues are uncoupled")
        .clicked()
    {
        cmds.push(Command::EditScene(Box::new(add_point(scene))));
    }
}

fn with_point(scene: &Scene, i: usize, f: impl FnOnce(&mut Point)) -> Scene {
    let mut s = scene.clone();
    if let Some(pt) = s.points.get_mut(i) {
        f(pt);
    }
    s
}

/// The scene with one more point after the last, on its line across the
/// tread (its `y`).
pub fn add_point(scene: &Scene) -> Scene {
    let mut s = scene.clone();
    let p = s.points.len();
    let last = s.points.last().copied().unwrap_or(Point {
        x_m: 0.0,
        y_m: 0.0,
        h_m: 0.0,
    });
    let spacing = if p >= 2 {
        last.x_m - s.points[p - 2].x_m
    } else {
        0.02
    };
    let spacing = if spacing.abs() > 0.0 { spacing } else { 0.02 };
    s.points.push(Point {
        x_m: last.x_m + spacing,
        y_m: last.y_m,
        h_m: last.h_m,
    });
    for m in modes_mut(&mut s).into_iter().flatten() {
        if let Some(&a) = m.shape.last() {
            m.shape.push(a);
        }
        if !m.residue.is_empty() {
            let d = m
                .residue
                .last()
                .and_then(|r| r.last())
                .copied()
                .unwrap_or(0.0);
            for row in &mut m.residue {
                row.push(0.0);
            }
            let mut row = vec![0.0; p + 1];
            row[p] = d;
            m.residue.push(row);
        }
    }
    s
}

/// The scene without point `i`.
pub fn remove_point(scene: &Scene, i: usize) -> Scene {
    let mut s = scene.clone();
    if i >= s.points.len() {
        return s;
    }
    s.points.remove(i);
    for m in modes_mut(&mut s).into_iter().flatten() {
        if i < m.shape.len() {
            m.shape.remove(i);
        }
        if i < m.residue.len() {
            m.residue.remove(i);
        }
        for row in &mut m.residue {
            if i < row.len() {
                row.remove(i);
            }
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn adding_and_removing_points_keeps_the_scene_valid() {
        let scene = Scene::parse(
            include_str!(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/presets/single_mode.ron"
            )),
            "single_mode",
        )
        .unwrap();
        let two = add_point(&scene);
        assert_eq!(two.num_points(), 2);
        assert!(two.validate().is_ok(), "{:?}", two.validate());
        let three = add_point(&two);
        assert!(three.validate().is_ok());
        let back = remove_point(&three, 1);
        assert_eq!(back.num_points(), 2);
        assert!(back.validate().is_ok());
    }
}
