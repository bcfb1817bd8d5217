//! The two layouts of a frame: the normal one (editing panel, views) and
//! classroom mode's presenter layout, and the commands switching them.

use super::*;

pub use crate::gui::widgets::NARROW_PX;

impl App {
    pub(super) fn show_view(&mut self, v: View) {
        // the presenter layout has one view; another one leaves it
        self.set_classroom(false);
        self.view = v;
        // (a phone: the views come back in place of the editing panel)
        self.edit_panel_open = false;
    }

    /// Classroom mode on (presenter layout, slow motion) or off; off gives
    /// back the view and the speed it replaced, unless the user changed
    /// them meanwhile.
    pub(super) fn set_classroom(&mut self, on: bool) {
        self.classroom.back_when_wide = false;
        let slow = Speed::Factor(classroom::SLOW_MOTION);
        if on && !self.classroom.on {
            self.classroom.before = Some((self.view, self.time.speed()));
        }
        if !on && let Some((view, speed)) = self.classroom.before.take() {
            if self.view == View::Scene {
                self.view = view;
            }
            if self.time.speed() == slow {
                self.time.set_speed(speed);
            }
        }
        self.classroom.on = on;
        if on {
            self.view = View::Scene;
            self.time.set_speed(slow);
        }
    }

    /// Presenter layout: explanation, the scene large with phase labels, one
    /// plot of a chosen point, the mode bars on the right; no editing panel.
    pub(super) fn classroom_layout(&mut self, ui: &mut egui::Ui, cmds: &mut Vec<Command>) {
        egui::Panel::right("tirecontact.classroom_bars")
            .resizable(true)
            .default_size(0.34 * ui.available_width())
            .show(ui, |ui| {
                // a short window: the panel scrolls down to the Mute/Solo rows
                classroom::mode_bars_panel(ui, |ui| {
                    let reserve_px = classroom::mode_bars_min_px(ui, self.modes.len());
                    let edits = self.edits();
                    classroom::explanation(
                        ui,
                        &self.doc.scene.name,
                        &self.doc.scene.description,
                        &edits,
                        reserve_px,
                    );
                    ui.separator();
                    classroom::mode_bars(
                        ui,
                        &self.sim,
                        &self.modes,
                        self.mutes.as_ref(),
                        &mut self.classroom,
                        cmds,
                    );
                });
            });
        egui::CentralPanel::default().show(ui, |ui| {
            crate::gui::chrome::dialogs::banner(ui, self.message.as_ref(), cmds);
            crate::gui::chrome::dialogs::preparation_row(ui, self.preparation_progress(), cmds);
            crate::gui::chrome::dialogs::csv_row(ui, self.csv_progress(), cmds);
            classroom::phase_strip(ui, self.sim.time_s(), &self.phases);
            let h = (ui.available_height() * 0.68).max(150.0);
            let w = ui.available_width();
            ui.allocate_ui(egui::vec2(w, h), |ui| {
                ui.set_min_size(egui::vec2(w, h));
                classroom::scene_with_phases(
                    ui,
                    &self.sim,
                    &self.doc.scene.road,
                    &mut self.scene_opts,
                    &self.phases,
                    self.classroom.point,
                );
            });
            classroom::point_plot(ui, &self.history, &mut self.classroom, self.sim.time_s());
        });
    }

    /// The editing panel's fields (disabled while an edit waits for its
    /// preparation).
    /// `to_top`: a new document came in, the panel scrolls back to its top.
    fn editor(
        &self,
        ui: &mut egui::Ui,
        editable: bool,
        to_top: bool,
        edits: &[String],
        cmds: &mut Vec<Command>,
    ) {
        ui.add_enabled_ui(editable, |ui| {
            panels::side_panel(
                ui,
                to_top,
                &self.doc.scene,
                edits,
                [self.undo.undo_label(), self.undo.redo_label()],
                &self.modes,
                self.sim.road_profile(),
                cmds,
            )
        });
    }

    pub(super) fn normal_layout(&mut self, ui: &mut egui::Ui, cmds: &mut Vec<Command>) {
        let cmds_left = &mut *cmds;
        // while an edit waits for its ring's identification the fields show
        // the running scene: no further edit until the waiting one applies
        let editable = self.handles.prepare_job.is_none();
        let edits = self.edits();
        let to_top = std::mem::take(&mut self.handles.editor_to_top);
        if ui.available_width() < NARROW_PX {
            // a phone: the editing panel behind a button, not over the views
            if self.edit_panel_open {
                egui::CentralPanel::default().show(ui, |ui| {
                    if ui.button("Back to the views").clicked() {
                        cmds_left.push(Command::ShowEditPanel(false));
                    }
                    // a refused value's reason, the views' banner being hidden
                    crate::gui::chrome::dialogs::banner(ui, self.message.as_ref(), cmds_left);
                    self.editor(ui, editable, to_top, &edits, cmds_left);
                });
                return;
            }
            // (for the editing panel when it is shown)
            self.handles.editor_to_top = to_top;
            egui::Panel::top("tirecontact.edit_button").show(ui, |ui| {
                if ui
                    .button("Edit the scene")
                    .on_hover_text("the editing panel, in place of the views")
                    .clicked()
                {
                    cmds_left.push(Command::ShowEditPanel(true));
                }
            });
            egui::CentralPanel::default().show(ui, |ui| {
                crate::gui::chrome::dialogs::banner(ui, self.message.as_ref(), cmds);
                crate::gui::chrome::dialogs::preparation_row(ui, self.preparation_progress(), cmds);
                crate::gui::chrome::dialogs::csv_row(ui, self.csv_progress(), cmds);
                self.show_current_view(ui, cmds);
            });
            return;
        }
        // the side panels give way in a small window: the view keeps at
        // least 40 % of the width
        let w = ui.available_width();
        egui::Panel::left("tirecontact.edit")
            .resizable(true)
            .default_size(380.0f32.min(0.35 * w))
            .max_size(0.35 * w)
            .show(ui, |ui| {
                self.editor(ui, editable, to_top, &edits, cmds_left);
            });
        if self.classroom.bars {
            egui::Panel::right("tirecontact.mode_bars")
                .resizable(true)
                .default_size(320.0f32.min(0.25 * w))
                .max_size(0.25 * w)
                .show(ui, |ui| {
                    classroom::mode_bars_panel(ui, |ui| {
                        classroom::mode_bars(
                            ui,
                            &self.sim,
                            &self.modes,
                            self.mutes.as_ref(),
                            &mut self.classroom,
                            cmds,
                        );
                    });
                });
        }
        egui::CentralPanel::default().show(ui, |ui| {
            crate::gui::chrome::dialogs::banner(ui, self.message.as_ref(), cmds);
            crate::gui::chrome::dialogs::preparation_row(ui, self.preparation_progress(), cmds);
            crate::gui::chrome::dialogs::csv_row(ui, self.csv_progress(), cmds);
            self.show_current_view(ui, cmds);
        });
    }

    /// The view chosen (time plots, scene, …) in `ui`.
    fn show_current_view(&mut self, ui: &mut egui::Ui, cmds: &mut Vec<Command>) {
        match self.view {
            View::TimePlots => {
                time_plots::show(
                    ui,
                    &self.history,
                    &mut self.plot_opts,
                    self.sim.time_s(),
                    self.doc.scene.duration_s,
                );
            }
            View::Scene => {
                // on a patch: the row of the classroom's chosen point, as
                // its side view draws it
                let normal_row = self.scene_opts.row_of_point.replace(self.classroom.point);
                scene_view::show(ui, &self.sim, &self.doc.scene.road, &mut self.scene_opts);
                self.scene_opts.row_of_point = normal_row;
            }
            View::Green => {
                green_view::show(ui, &self.doc.scene, &self.modes, &mut self.green_opts);
            }
            View::Patch => {
                crate::gui::views::patch_view::show(ui, &self.sim, &self.history, cmds);
            }
            View::Spectra | View::Sweep | View::Compare | View::Fidelity | View::Workbench => {
                self.show_research_view(ui, cmds);
            }
        }
    }
}
