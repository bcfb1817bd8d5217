//! One frame of the UI: poll the background jobs, take the solver steps,
//! draw the bars, the layout and the dialogs, then apply the commands they
//! pushed; and the `eframe::App` glue (close request, session save).

use super::*;
use crate::gui::chrome::status_bar;
use crate::gui::model::command::ResearchCommand;

impl App {
    /// The keyboard shortcuts (when no text field has the focus and no
    /// prompt is open: a prompt's keys are its own, even when a click took
    /// the focus off its text field).
    fn keyboard(&self, ctx: &egui::Context, cmds: &mut Vec<Command>) {
        if ctx.egui_wants_keyboard_input() || self.prompt_open() {
            return;
        }
        ctx.input(|i| {
            if i.key_pressed(egui::Key::Space) {
                cmds.push(Command::TogglePlay);
            }
            if i.key_pressed(egui::Key::ArrowRight) {
                cmds.push(Command::Step(1));
            }
            if i.key_pressed(egui::Key::R) && i.modifiers.is_none() {
                cmds.push(Command::Reset);
            }
            // the File menu's shortcuts (shown there)
            if i.modifiers.command && i.key_pressed(egui::Key::S) {
                cmds.push(if i.modifiers.shift {
                    Command::SaveAsDialog
                } else {
                    Command::Save
                });
            }
            if i.modifiers.command && i.key_pressed(egui::Key::O) {
                cmds.push(Command::OpenDialog);
            }
            // (a text field's own undo has its keys while it has the focus)
            if i.modifiers.command && i.key_pressed(egui::Key::Z) {
                cmds.push(if i.modifiers.shift {
                    Command::Redo
                } else {
                    Command::Undo
                });
            }
            if i.modifiers.command && i.key_pressed(egui::Key::Y) {
                cmds.push(Command::Redo);
            }
            for (key, view) in [
                (egui::Key::Num1, View::TimePlots),
                (egui::Key::Num2, View::Scene),
                (egui::Key::Num3, View::Green),
                (egui::Key::Num4, View::Spectra),
                (egui::Key::Num5, View::Sweep),
                (egui::Key::Num6, View::Compare),
                (egui::Key::Num7, View::Fidelity),
                (egui::Key::Num8, View::Workbench),
                (egui::Key::Num9, View::Patch),
            ] {
                if i.key_pressed(key) {
                    cmds.push(Command::ShowView(view));
                }
            }
        });
    }

    /// Whether a prompt (a file, PNG or frames dialog, the
    /// unsaved-changes question or the shared link) is open.
    pub fn prompt_open(&self) -> bool {
        self.file_prompt.is_some()
            || self.png_dialog.is_some()
            || self.frames_dialog.is_some()
            || self.confirm.is_some()
            || self.overwrite.is_some()
            || (self.handles.link_shown && self.handles.shared_link.is_some())
    }

    /// What the status bar shows.
    fn status(&self) -> status_bar::Status<'_> {
        let st = self.sim.stats();
        status_bar::Status {
            path: self.doc.path.as_deref(),
            from_link: self.doc.from_link,
            scene_name: &self.doc.scene.name,
            dirty: self.is_dirty(),
            points: self.doc.scene.num_points(),
            modes: self.modes.len(),
            steps: st.steps,
            events: st.events,
            in_contact: self.sim.in_contact().iter().filter(|c| **c).count(),
            samples: self.history.len(),
            stride: self.history.stride(),
            playing: self.time.is_playing(),
            fps: self.fps(),
            app_ms: self.app_ms(),
            exporting_csv: self.exporting_csv(),
        }
    }

    /// The background jobs that ended since the last frame, as commands.
    fn jobs_ended(&self) -> Vec<Command> {
        let mut ended: Vec<Command> = [
            self.poll_csv(),
            self.poll_frames(),
            self.poll_preparation(),
            self.poll_picked(),
        ]
        .into_iter()
        .flatten()
        .collect();
        ended.extend(self.research_polls());
        ended
    }

    /// One frame of the whole UI (also driven headless by the tests).
    pub fn show(&mut self, ui: &mut egui::Ui) {
        let started = Instant::now();
        let ctx = ui.ctx().clone();
        let frame_s = ctx.input(|i| f64::from(i.unstable_dt));
        // a minimised window neither simulates nor asks for frames: the run
        // resumes where it was when the window is shown again
        let hidden = ctx.input(|i| i.viewport().minimized == Some(true));
        // the background jobs' ends and the frame's solver steps are
        // commands like the user's, applied first
        for cmd in self.jobs_ended() {
            self.apply(cmd);
        }
        if !hidden {
            self.apply(Command::Advance { frame_s });
        }
        self.apply(Command::Research(ResearchCommand::Refresh));
        if self.research_busy() {
            ctx.request_repaint();
        }
        // the edits of one drag make one undo step
        self.handles.pointer_down = ctx.input(|i| i.pointer.any_down());
        if !self.handles.pointer_down {
            self.undo.end_drag();
        }
        let mut cmds = Vec::new();
        self.keyboard(&ctx, &mut cmds);
        let status = toolbar::ToolbarStatus {
            playing: self.time.is_playing(),
            speed: self.time.speed(),
            time_s: self.sim.time_s(),
            duration_s: self.doc.scene.duration_s,
            steps: self.sim.steps(),
            achieved_factor: self.time.achieved_factor(),
            view: self.view,
            exporting_csv: self.handles.csv_job.is_some(),
            classroom: self.classroom.on,
            mode_bars: self.classroom.bars,
            exporting_frames: self.handles.frames_job.is_some(),
            patch: {
                let y0 = self.doc.scene.points.first().map(|p| p.y_m);
                self.doc.scene.points.iter().any(|p| Some(p.y_m) != y0)
            },
            editing: self.edit_panel_open
                && ctx.content_rect().width() < crate::gui::widgets::NARROW_PX,
            // (not while an edit or a document is prepared: it would drop it)
            undo: self
                .undo
                .undo_label()
                .filter(|_| self.handles.prepare_job.is_none())
                .map(str::to_string),
            redo: self
                .undo
                .redo_label()
                .filter(|_| self.handles.prepare_job.is_none())
                .map(str::to_string),
        };
        // a phone: classroom mode's presenter layout does not fit it; it
        // comes back when the window widens again
        let narrow = ctx.content_rect().width() < crate::gui::widgets::NARROW_PX;
        if narrow && self.classroom.on {
            self.set_classroom(false);
            self.classroom.back_when_wide = true;
        } else if !narrow && self.classroom.back_when_wide {
            self.set_classroom(true);
        }
        if !self.classroom.on && legible_small_text(&ctx) {
            ui.set_style(ctx.global_style());
        }
        // the phone's and classroom mode's sizes each apply to the plain
        // style: the one going is undone before the other is applied (the
        // phone's, applied over classroom mode's, kept its sizes and gave
        // them back to the widened window)
        let restyled = if narrow {
            self.classroom.sync_style(&ctx) | touch_targets(&ctx, true)
        } else {
            touch_targets(&ctx, false) | self.classroom.sync_style(&ctx)
        };
        if restyled {
            ui.set_style(ctx.global_style());
        }
        // impacts and releases stay up EVENT_HOLD_WALL_S of wall-clock time
        self.phases.hold_s = match self.time.speed() {
            Speed::Factor(f) => classroom::EVENT_HOLD_WALL_S * f,
            Speed::Max => 0.0,
        }
        .max(20.0 * self.sim.dt_s());
        let top = egui::Panel::top("tirecontact.top").show(ui, |ui| {
            toolbar::menu_bar(ui, &status, &mut cmds);
            toolbar::transport(ui, &status, &mut cmds);
        });
        let bar = self.status();
        let bottom = egui::Panel::bottom("tirecontact.status").show(ui, |ui| {
            status_bar::show(ui, &bar);
        });
        self.handles.status_rect = bottom.response.rect;
        // the dialogs open in the views' area, never over the menu bar
        let content = ctx.content_rect();
        let views = egui::Rect::from_x_y_ranges(
            content.x_range(),
            top.response.rect.bottom()..=bottom.response.rect.top().max(top.response.rect.bottom()),
        );
        if self.classroom.on {
            self.classroom_layout(ui, &mut cmds);
        } else {
            self.normal_layout(ui, &mut cmds);
        }
        let unsaved = if self.confirm.is_some() {
            self.changes()
        } else {
            Vec::new()
        };
        crate::gui::chrome::dialogs::confirm_window(
            &ctx,
            self.confirm.as_ref(),
            &unsaved,
            &mut cmds,
        );
        crate::gui::chrome::dialogs::overwrite_window(&ctx, self.overwrite.as_deref(), &mut cmds);
        crate::gui::chrome::dialogs::link_window(
            &ctx,
            self.handles
                .shared_link
                .as_deref()
                .filter(|_| self.handles.link_shown),
            &mut cmds,
        );
        crate::gui::chrome::dialogs::png_window(&ctx, views, &mut self.png_dialog, &mut cmds);
        crate::gui::chrome::file_prompt::window(&ctx, &mut self.file_prompt, &mut cmds);
        crate::gui::chrome::frames_dialog::dialog(&ctx, views, &mut self.frames_dialog, &mut cmds);
        crate::gui::chrome::frames_dialog::progress(
            &ctx,
            views,
            self.handles.frames_job.as_ref(),
            &mut cmds,
        );
        for c in cmds {
            self.apply(c);
        }
        if std::mem::take(&mut self.handles.copy_link)
            && let Some(link) = &self.handles.shared_link
        {
            ctx.copy_text(link.clone());
            // and in a window: a system without a clipboard (or a page
            // refused it) leaves it to be copied by hand
            self.handles.link_shown = true;
        }
        if std::mem::take(&mut self.forget_fields) {
            crate::gui::widgets::fields::forget_all(&ctx);
            ctx.request_repaint();
        }
        let title = self.title();
        if title != self.handles.title {
            ctx.send_viewport_cmd(egui::ViewportCommand::Title(title.clone()));
            crate::gui::chrome::web::set_page_title(&title);
            self.handles.title = title;
        }
        crate::gui::chrome::web::publish_run(self.sim.time_s(), self.sim.steps());
        self.handles.fps.tick(
            self.sim.time_s(),
            self.time.is_playing(),
            started.elapsed().as_secs_f64(),
        );
        if self.handles.csv_job.is_some()
            || self.handles.frames_job.is_some()
            || self.handles.prepare_job.is_some()
            || crate::gui::chrome::web::picking()
            || (!hidden && (self.time.is_playing() || self.time.pending_steps() > 0))
        {
            match self.handles.paced_delay_s {
                // the run steps between frames: drawing less often leaves
                // it the cores (input still brings a frame at once)
                Some(delay_s) if self.time.is_playing() => {
                    ctx.request_repaint_after(Duration::from_secs_f64(delay_s))
                }
                _ => ctx.request_repaint(),
            }
        }
    }
}

impl App {
    /// One frame as eframe runs it: the run taken back from the stepping
    /// thread, the close request, the frame ([`App::show`]), and the run
    /// lent again when it plays as fast as possible.
    pub fn frame(&mut self, ui: &mut egui::Ui) {
        #[cfg(not(target_arch = "wasm32"))]
        self.reclaim_run();
        let ctx = ui.ctx().clone();
        if ctx.input(|i| i.viewport().close_requested()) && !self.allow_close && self.is_dirty() {
            ctx.send_viewport_cmd(egui::ViewportCommand::CancelClose);
            self.confirm = Some(Discarding::Quit);
        }
        self.show(ui);
        if self.quit_requested {
            self.quit_requested = false;
            ctx.send_viewport_cmd(egui::ViewportCommand::Close);
        }
        #[cfg(not(target_arch = "wasm32"))]
        self.lend_run(ctx.input(|i| i.viewport().minimized == Some(true)));
    }
}

impl eframe::App for App {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        self.frame(ui);
    }

    fn save(&mut self, storage: &mut dyn eframe::Storage) {
        // (between frames the run may be with the stepping thread)
        #[cfg(not(target_arch = "wasm32"))]
        self.reclaim_run();
        self.save_session(storage);
    }
}

/// Least height (px) of a button, menu row or field in a window narrower
/// than [`NARROW_PX`](crate::gui::widgets::NARROW_PX) (a phone): a fingertip's target (egui's 18 px rows
/// gave 20 px buttons and 23 px menu rows).
pub const TOUCH_TARGET_PX: f32 = 44.0;

/// Gives buttons, menu rows and fields [`TOUCH_TARGET_PX`] in a narrow
/// window and egui's sizes back in a wide one; whether it changed.
fn touch_targets(ctx: &egui::Context, narrow: bool) -> bool {
    let id = crate::gui::widgets::touch_targets_id();
    let saved: Option<(egui::Vec2, egui::Vec2)> = ctx.data(|d| d.get_temp(id));
    match (narrow, saved) {
        (true, None) => {
            let s = ctx.global_style();
            ctx.data_mut(|d| {
                d.insert_temp(id, (s.spacing.interact_size, s.spacing.button_padding))
            });
            ctx.all_styles_mut(|s| {
                s.spacing.interact_size.y = s.spacing.interact_size.y.max(TOUCH_TARGET_PX);
                s.spacing.button_padding.y = s.spacing.button_padding.y.max(8.0);
            });
            true
        }
        (false, Some((interact, padding))) => {
            ctx.data_mut(|d| d.remove::<(egui::Vec2, egui::Vec2)>(id));
            ctx.all_styles_mut(|s| {
                s.spacing.interact_size = interact;
                s.spacing.button_padding = padding;
            });
            true
        }
        _ => false,
    }
}

/// The least size (px) of the small text (legends of short plots, short
/// axis titles): egui's 9 px was hard to read at 1280 × 720.
pub const SMALL_TEXT_PX: f32 = 11.0;

/// Raises the small text style to [`SMALL_TEXT_PX`]; whether it changed
/// (once per context; classroom mode scales from it and restores it).
fn legible_small_text(ctx: &egui::Context) -> bool {
    let small = egui::TextStyle::Small;
    let size = ctx.global_style().text_styles.get(&small).map(|f| f.size);
    if size.is_none_or(|px| px >= SMALL_TEXT_PX) {
        return false;
    }
    ctx.all_styles_mut(|s| {
        if let Some(f) = s.text_styles.get_mut(&small) {
            f.size = f.size.max(SMALL_TEXT_PX);
        }
    });
    true
}
