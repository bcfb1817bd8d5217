//! Animation export from the GUI: the settings dialog, and the progress
//! window with Cancel of the export job ([`FramesJob`]). The run is
//! replayed from t = 0 with its live edits, as for the CSV export.

use crate::Scene;
use crate::gui::jobs::frames::FramesJob;
use crate::gui::model::command::Command;
use crate::output::animation::FrameSettings;
use egui::{Context, RichText};
use std::path::PathBuf;

/// Distance (px) of a dialog's top below the top of the views' area.
pub const DIALOG_DROP_PX: f32 = 40.0;

/// The dialog's editable settings.
#[derive(Debug, Clone, PartialEq)]
pub struct FramesDialog {
    pub settings: FrameSettings,
    pub dir: String,
    /// Remove the frames of an earlier export from the folder first.
    pub clear_old: bool,
    /// The folder field takes the keyboard at the next frame (set when the
    /// dialog opens: what is typed then goes to the folder, not to the
    /// shortcuts).
    pub focus: bool,
}

impl FramesDialog {
    /// Defaults for a scene: its whole duration at 25 fps, 20x slow motion,
    /// 1280x720 px, into `frames/` beside the working directory.
    pub fn for_scene(scene: &Scene, now_s: f64) -> Self {
        let t1 = scene
            .duration_s
            .min(now_s.max(scene.ramp_s + 0.05))
            .max(1e-3);
        FramesDialog {
            settings: FrameSettings {
                t0_s: 0.0,
                t1_s: t1.min(scene.duration_s),
                fps: 25.0,
                slow_motion: 20.0,
                width: 1280,
                height: 720,
            },
            dir: "frames".to_string(),
            clear_old: false,
            focus: true,
        }
    }
}

/// The settings window; Export (or Enter) pushes `Command::ExportFrames`,
/// Cancel (or Escape) closes it.
/// It opens in `views` (the area below the menu bar and toolbar, above the
/// status bar) and stays there.
pub fn dialog(
    ctx: &Context,
    views: egui::Rect,
    dialog: &mut Option<FramesDialog>,
    cmds: &mut Vec<Command>,
) {
    let Some(d) = dialog else { return };
    let mut open = true;
    let (mut export, mut cancel) = crate::gui::chrome::file_prompt::confirm_keys(ctx);
    egui::Window::new("Export animation frames")
        .collapsible(false)
        .pivot(egui::Align2::CENTER_TOP)
        .default_pos(views.center_top() + egui::vec2(0.0, DIALOG_DROP_PX))
        .constrain_to(views)
        .open(&mut open)
        .show(ctx, |ui| {
            let s = &mut d.settings;
            egui::Grid::new("tirecontact.frames")
                .num_columns(2)
                .show(ui, |ui| {
                    ui.label("from t0");
                    ui.add(
                        egui::DragValue::new(&mut s.t0_s)
                            .speed(0.001)
                            .range(0.0..=1e6)
                            .suffix(" s"),
                    );
                    ui.end_row();
                    ui.label("to t1");
                    ui.add(
                        egui::DragValue::new(&mut s.t1_s)
                            .speed(0.001)
                            .range(0.0..=1e6)
                            .suffix(" s"),
                    );
                    ui.end_row();
                    ui.label("frame rate");
                    ui.add(
                        egui::DragValue::new(&mut s.fps)
                            .speed(1.0)
                            .range(1.0..=240.0)
                            .suffix(" fps"),
                    );
                    ui.end_row();
                    ui.label("slow motion");
                    ui.add(
                        egui::DragValue::new(&mut s.slow_motion)
                            .speed(1.0)
                            .range(0.01..=1e5)
                            .suffix(" video s per simulated s"),
                    );
                    ui.end_row();
                    ui.label("size");
                    ui.horizontal(|ui| {
                        ui.add(
                            egui::DragValue::new(&mut s.width)
                                .range(200..=4000)
                                .suffix(" px"),
                        );
                        ui.label("×");
                        ui.add(
                            egui::DragValue::new(&mut s.height)
                                .range(200..=4000)
                                .suffix(" px"),
                        );
                    });
                    ui.end_row();
                    ui.label("folder");
                    ui.horizontal(|ui| {
                        let field = ui
                            .add(egui::TextEdit::singleline(&mut d.dir).desired_width(220.0))
                            .accessible_name("frames folder");
                        if std::mem::take(&mut d.focus) {
                            crate::gui::chrome::file_prompt::take_keyboard(ui, &field, &d.dir);
                        }
                        let request = || crate::gui::chrome::native_dialog::Request {
                            kind: crate::gui::chrome::native_dialog::Kind::Folder,
                            filter: None,
                            directory: None,
                            file_name: None,
                        };
                        let id = egui::Id::unique("tirecontact.choose.frames_folder");
                        if let Some(Some(p)) =
                            crate::gui::chrome::native_dialog::choose_button(ui, id, request)
                        {
                            d.dir = p.display().to_string();
                        }
                    });
                    ui.end_row();
                });
            let n = d.settings.frame_count();
            ui.label(format!(
                "{n} frames = {:.2} s of video showing {:.4} s of the run (frame_00000.png …)",
                n as f64 / d.settings.fps.max(1e-9),
                d.settings.t1_s - d.settings.t0_s
            ));
            let dir = PathBuf::from(d.dir.trim());
            let shown = std::path::absolute(&dir).unwrap_or_else(|_| dir.clone());
            ui.label(RichText::new(format!("into {}", shown.display())).weak());
            let old = crate::output::animation::old_frames(&dir).len();
            if old > 0 {
                ui.checkbox(
                    &mut d.clear_old,
                    format!("clear the {old} old frames in this folder (else they would mix with the new ones)"),
                );
            }
            ui.horizontal(|ui| {
                export |= ui
                    .button(RichText::new("Export").strong())
                    .on_hover_text("Enter")
                    .clicked();
                cancel |= ui.button("Cancel").on_hover_text("Escape").clicked();
            });
            if export && !cancel {
                cmds.push(Command::ExportFrames {
                    dir: dir.clone(),
                    settings: d.settings,
                    clear_old: d.clear_old,
                });
            }
        });
    if !open || cancel {
        *dialog = None;
    }
}

/// The progress window of a running export, with Cancel.
pub fn progress(
    ctx: &Context,
    views: egui::Rect,
    job: Option<&FramesJob>,
    cmds: &mut Vec<Command>,
) {
    let Some(job) = job else { return };
    egui::Window::new("Exporting frames")
        .collapsible(false)
        .pivot(egui::Align2::CENTER_TOP)
        .default_pos(views.center_top() + egui::vec2(0.0, DIALOG_DROP_PX))
        .constrain_to(views)
        .show(ctx, |ui| {
            let done = job.done();
            ui.label(format!(
                "{done} of {} frames into {}",
                job.total,
                job.dir.display()
            ));
            ui.add(egui::ProgressBar::new(done as f32 / job.total.max(1) as f32).show_percentage());
            if ui.button("Cancel").clicked() {
                cmds.push(Command::CancelFrames);
            }
        });
}
