//! Message banner, unsaved-changes confirmation and the PNG export
//! settings. They push `Command`s; the banner's [`Message`] and the PNG
//! dialog's [`PngSettings`] are defined here and kept by the app (the dialog
//! edits its settings itself).

use crate::gui::model::command::{Command, Discarding};
use crate::gui::widgets::fields::ERROR_COLOR;
use egui::{Color32, RichText, Ui};

/// A message shown in the banner above the views.
#[derive(Debug, Clone, PartialEq)]
pub struct Message {
    pub error: bool,
    pub text: String,
}

/// Settings of the PNG export dialog.
#[derive(Debug, Clone, PartialEq)]
pub struct PngSettings {
    pub width: u32,
    pub height: u32,
    /// The file, as typed or chosen.
    pub path: String,
    /// Why the last export attempt did not start (no file chosen, bad path).
    pub note: Option<String>,
    /// The path field takes the keyboard at the next frame.
    pub focus: bool,
}

/// Inner margin (px) of the message banner's frame.
const BANNER_MARGIN_PX: f32 = 6.0;

/// How long (s) a message of several lines is shown whole before it folds
/// to its first line, uncovering the top of the view under it.
pub const BANNER_UNFOLDED_S: f64 = 8.0;

/// The folding of the message shown (`message`, a hash of its kind and
/// text), kept by egui while it is shown: when it was first shown and
/// whether the user unfolded (`Some(true)`) or folded it (`Some(false)`);
/// `None` folds it [`BANNER_UNFOLDED_S`] after it was first shown. Another
/// message, or the same one after none was shown, starts afresh.
#[derive(Debug, Clone, Copy)]
struct Fold {
    message: egui::Id,
    since_s: f64,
    open: Option<bool>,
}

/// The message banner above the views (errors in red, with a dismiss
/// button). It takes one banner line of its own above the views whether or
/// not a message is shown; a longer message unfolds downwards over the top
/// of the view, in front of it, and folds back to its first line after
/// [`BANNER_UNFOLDED_S`] (the whole text on hover and behind "More") until
/// dismissed or its cause is gone: the views never move as messages come
/// and go, and no control stays covered.
pub fn banner(ui: &mut Ui, msg: Option<&Message>, cmds: &mut Vec<Command>) {
    // as high as the banner's row of text and small buttons (a phone's
    // touch-target height left an empty band under it)
    let row_px = crate::gui::widgets::text_row_px(ui);
    let size = egui::vec2(ui.available_width(), row_px + 2.0 * BANNER_MARGIN_PX);
    let (strip, _) = ui.allocate_exact_size(size, egui::Sense::hover());
    let key = egui::Id::unique("tirecontact.banner.fold");
    let Some(m) = msg else {
        ui.data_mut(|d| d.remove::<Fold>(key));
        return;
    };
    let message = egui::Id::unique(("tirecontact.banner.message", m.error, &m.text));
    let now = ui.input(|i| i.time);
    // (kept while this message is shown, else started afresh)
    let fold = ui.data_mut(|d| {
        let fold = d
            .get_temp::<Fold>(key)
            .filter(|f| f.message == message)
            .unwrap_or(Fold {
                message,
                since_s: now,
                open: None,
            });
        d.insert_temp(key, fold);
        fold
    });
    let folded = match fold.open {
        Some(open) => !open,
        None => {
            let left_s = fold.since_s + BANNER_UNFOLDED_S - now;
            if left_s > 0.0 {
                ui.ctx().request_repaint_after_secs(left_s as f32);
            }
            left_s <= 0.0
        }
    };
    egui::Area::new(egui::Id::unique("tirecontact.banner"))
        .order(egui::Order::Foreground)
        .fixed_pos(strip.min)
        .constrain(false)
        .show(ui.ctx(), |ui| {
            ui.set_width(strip.width());
            ui.set_max_width(strip.width());
            if let Some(open) = banner_frame(ui, m, folded, cmds) {
                ui.data_mut(|d| {
                    d.insert_temp(
                        key,
                        Fold {
                            open: Some(open),
                            ..fold
                        },
                    )
                });
            }
        });
}

/// The progress line of the preparation an edit or a new document waits
/// for: what it is doing, how far it is, and Cancel.
pub fn preparation_row(ui: &mut Ui, progress: Option<(&str, f64)>, cmds: &mut Vec<Command>) {
    if let Some((doing, fraction)) = progress {
        job_row(
            ui,
            &format!("Preparing the scene: {doing}…"),
            fraction,
            "stop; the current scene is kept",
            Command::CancelPreparation,
            cmds,
        );
    }
}

/// The progress line of a CSV export (the run re-simulated), and Cancel.
pub fn csv_row(ui: &mut Ui, fraction: Option<f64>, cmds: &mut Vec<Command>) {
    if let Some(fraction) = fraction {
        job_row(
            ui,
            "Writing the CSV: re-running the run from t = 0…",
            fraction,
            "stop; no file is written",
            Command::CancelCsvExport,
            cmds,
        );
    }
}

/// A background job's line: Cancel, a progress bar, what it does. Cancel
/// comes first so that it stays where it is while the text of the stage
/// under way changes length (a button after the text moved under the
/// pointer from one stage to the next).
fn job_row(
    ui: &mut Ui,
    doing: &str,
    fraction: f64,
    cancel_hover: &str,
    cancel: Command,
    cmds: &mut Vec<Command>,
) {
    ui.horizontal_wrapped(|ui| {
        if ui.button("Cancel").on_hover_text(cancel_hover).clicked() {
            cmds.push(cancel);
        }
        ui.add(
            egui::ProgressBar::new(fraction as f32)
                .desired_width(140.0)
                .show_percentage(),
        );
        ui.label(doing);
    });
}

/// The banner's frame, text and Dismiss button; a text of several lines
/// shown `folded` to its first line, and a button that unfolds it (or
/// folds it back): `Some(open)` when pressed.
fn banner_frame(ui: &mut Ui, m: &Message, folded: bool, cmds: &mut Vec<Command>) -> Option<bool> {
    let (fill, color) = if m.error {
        (Color32::from_rgb(255, 235, 235), ERROR_COLOR)
    } else {
        (
            Color32::from_rgb(232, 245, 238),
            Color32::from_rgb(0, 110, 80),
        )
    };
    let mut toggled = None;
    egui::Frame::new()
        .fill(fill)
        .inner_margin(BANNER_MARGIN_PX)
        .corner_radius(4.0)
        .show(ui, |ui| {
            ui.horizontal_top(|ui| {
                // wrapped to the room left of the buttons: unwrapped, a long
                // message (a refused field's reason) would widen the central
                // panel past the window and cut off Dismiss and the plots
                let buttons_px = 130.0;
                let w = (ui.available_width() - buttons_px).max(100.0);
                // a quoted source line and its caret in monospace
                let job = crate::gui::chrome::banner_text::layout(ui, &m.text, color);
                let rows = egui::WidgetText::from(job.clone())
                    .into_galley(ui, Some(egui::TextWrapMode::Wrap), w, egui::TextStyle::Body)
                    .rows
                    .len();
                let foldable = rows > 1;
                ui.allocate_ui_with_layout(
                    egui::vec2(w, 0.0),
                    egui::Layout::top_down(egui::Align::Min),
                    |ui| {
                        ui.set_max_width(w);
                        if foldable && folded {
                            // (a layout job keeps its own wrapping: its first
                            // row, elided, within the room left of the buttons)
                            let mut job = job;
                            job.wrap = egui::text::TextWrapping {
                                max_width: w,
                                max_rows: 1,
                                break_anywhere: false,
                                overflow_character: Some('…'),
                            };
                            ui.add(egui::Label::new(job)).on_hover_text(&m.text);
                        } else {
                            ui.add(egui::Label::new(job).wrap());
                        }
                    },
                );
                ui.with_layout(egui::Layout::right_to_left(egui::Align::Min), |ui| {
                    if ui.small_button("Dismiss").clicked() {
                        cmds.push(Command::DismissMessage);
                    }
                    if foldable {
                        let (label, hover) = if folded {
                            ("More", "show the whole message")
                        } else {
                            ("Less", "fold the message to its first line")
                        };
                        if ui.small_button(label).on_hover_text(hover).clicked() {
                            toggled = Some(folded);
                        }
                    }
                });
            });
        });
    toggled
}

/// Asks before dropping unsaved edits, naming them (`edits`, with units).
pub fn confirm_window(
    ctx: &egui::Context,
    pending: Option<&Discarding>,
    edits: &[String],
    cmds: &mut Vec<Command>,
) {
    let Some(d) = pending else { return };
    let what = match d {
        Discarding::New => "start a new scene",
        Discarding::OpenPath(_) | Discarding::Text { .. } => "open another preset",
        Discarding::Preset(_) => "open a shipped preset",
        Discarding::Guided(_) => "open a guided-tour preset",
        Discarding::Quit => "quit",
    };
    let shown = egui::Modal::new(egui::Id::unique("tirecontact.confirm")).show(ctx, |ui| {
        ui.heading("Unsaved changes");
        ui.label(format!(
            "The scene has unsaved changes. Discard them and {what}?"
        ));
        if !edits.is_empty() {
            ui.set_max_width(520.0);
            ui.add(
                egui::Label::new(RichText::new(format!("Changed: {}.", edits.join("; "))).weak())
                    .wrap(),
            );
        }
        ui.horizontal(|ui| {
            if ui.button("Discard changes").clicked() {
                cmds.push(Command::ConfirmDiscard);
            }
            if ui.button("Save first").clicked() {
                cmds.push(Command::SaveFirst);
            }
            if ui.button("Cancel").on_hover_text("Escape").clicked() {
                cmds.push(Command::CancelDiscard);
            }
        });
    });
    // Escape (or a click beside the question) keeps the changes, as Cancel;
    // Enter does not discard them (no default for a destructive choice)
    if shown.should_close() && !cmds.contains(&Command::CancelDiscard) {
        cmds.push(Command::CancelDiscard);
    }
}

/// Asks before a save replaces `path`, a preset shipped with the app.
/// Escape (or a click beside the question) keeps the file.
pub fn overwrite_window(
    ctx: &egui::Context,
    path: Option<&std::path::Path>,
    cmds: &mut Vec<Command>,
) {
    let Some(p) = path else { return };
    let shown = egui::Modal::new(egui::Id::unique("tirecontact.overwrite")).show(ctx, |ui| {
        ui.heading("Overwrite a shipped preset?");
        ui.set_max_width(520.0);
        ui.add(
            egui::Label::new(format!(
                "{} is a preset shipped with tirecontact. Saving replaces it for everyone \
                 using this folder.",
                p.display()
            ))
            .wrap(),
        );
        ui.horizontal(|ui| {
            if ui.button("Overwrite").clicked() {
                cmds.push(Command::ConfirmOverwrite);
            }
            if ui.button("Save as…").clicked() {
                cmds.push(Command::CancelOverwrite);
                cmds.push(Command::SaveAsDialog);
            }
            if ui.button("Cancel").on_hover_text("Escape").clicked() {
                cmds.push(Command::CancelOverwrite);
            }
        });
    });
    if shown.should_close() && !cmds.contains(&Command::CancelOverwrite) {
        cmds.push(Command::CancelOverwrite);
    }
}

/// The accessible name of the shared link's text field.
pub const LINK_FIELD: &str = "link to the scene";

/// The last Share's link in a selectable text field: it was copied to the
/// clipboard too, but where there is none (or a page was refused it) the
/// text is copied from here by hand. Close, Escape or a click beside it
/// closes it.
pub fn link_window(ctx: &egui::Context, link: Option<&str>, cmds: &mut Vec<Command>) {
    let Some(link) = link else { return };
    let shown = egui::Modal::new(egui::Id::unique("tirecontact.link")).show(ctx, |ui| {
        ui.heading("Link to this scene");
        ui.set_max_width(560.0);
        ui.add(
            egui::Label::new(
                "Copied to the clipboard. If pasting gives nothing, select the text below \
                 (Ctrl+A in it) and copy it (Ctrl+C).",
            )
            .wrap(),
        );
        // a &str: selectable and copyable, never edited
        let mut text = link;
        // a long link (a large patch) scrolls instead of growing the window
        // past the screen
        egui::ScrollArea::vertical()
            .max_height(300.0)
            .show(ui, |ui| {
                ui.add(
                    egui::TextEdit::multiline(&mut text)
                        .desired_width(540.0)
                        .desired_rows(4)
                        .font(egui::TextStyle::Monospace),
                )
                .accessible_name(LINK_FIELD);
            });
        ui.label(egui::RichText::new(format!("{} characters", link.chars().count())).weak());
        if ui.button("Close").on_hover_text("Escape").clicked() {
            cmds.push(Command::CloseLink);
        }
    });
    if shown.should_close() && !cmds.contains(&Command::CloseLink) {
        cmds.push(Command::CloseLink);
    }
}

/// PNG export settings: size in pixels, then the file dialog.
pub fn png_window(
    ctx: &egui::Context,
    views: egui::Rect,
    settings: &mut Option<PngSettings>,
    cmds: &mut Vec<Command>,
) {
    let Some(s) = settings else { return };
    let mut open = true;
    let (mut go, mut cancel) = crate::gui::chrome::file_prompt::confirm_keys(ctx);
    egui::Window::new("Export plots as PNG")
        .pivot(egui::Align2::CENTER_TOP)
        .default_pos(
            views.center_top() + egui::vec2(0.0, crate::gui::chrome::frames_dialog::DIALOG_DROP_PX),
        )
        .constrain_to(views)
        .open(&mut open)
        .collapsible(false)
        .resizable(false)
        .show(ctx, |ui| {
            ui.label("Displacement, force, gap and contact of the shown points over the whole run, with the scene parameters as subtitle.");
            egui::Grid::new("tirecontact.png").show(ui, |ui| {
                ui.label("width");
                ui.add(egui::DragValue::new(&mut s.width).range(200..=8000).suffix(" px"))
                    .on_hover_text("200 to 8000 px: a value outside is brought to the nearest");
                ui.end_row();
                ui.label("height");
                ui.add(egui::DragValue::new(&mut s.height).range(200..=8000).suffix(" px"))
                    .on_hover_text("200 to 8000 px: a value outside is brought to the nearest");
                ui.end_row();
            });
            ui.horizontal(|ui| {
                for (w, h) in [(1200, 900), (1600, 1200), (2400, 1800), (3200, 2400)] {
                    if ui.small_button(format!("{w}x{h}")).clicked() {
                        s.width = w;
                        s.height = h;
                    }
                }
            });
            ui.label("file");
            if let Some(n) = crate::gui::chrome::file_prompt::path_row(
                ui,
                &mut s.path,
                "PNG file path",
                ("PNG image", "png"),
                true,
                &mut s.focus,
            ) {
                s.note = Some(n);
            }
            // as the other file prompts: where a relative path goes, and a
            // Cancel beside the action (the title bar's × was the only way out)
            ui.label(
                RichText::new(format!(
                    "A relative path is in {}.",
                    crate::gui::chrome::file_prompt::cwd_text()
                ))
                .weak(),
            );
            if let Some(n) = &s.note {
                ui.label(RichText::new(n.as_str()).color(ERROR_COLOR));
            }
            ui.horizontal(|ui| {
                go |= ui
                    .button(RichText::new("Export PNG").strong())
                    .on_hover_text("Enter")
                    .clicked();
                cancel |= ui.button("Cancel").on_hover_text("Escape").clicked();
            });
        });
    if cancel {
        *settings = None;
        return;
    }
    if go {
        match crate::gui::chrome::file_prompt::typed_path_to_write(&s.path, "png") {
            Ok(path) => cmds.push(Command::ExportPng {
                path,
                width: s.width,
                height: s.height,
            }),
            Err(e) => s.note = Some(e),
        }
    } else if !open {
        *settings = None;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One frame at `t_s` of a 400 px wide window showing `msg` in the
    /// banner: the banner's height (px), if shown.
    fn frame(ctx: &egui::Context, t_s: f64, msg: Option<&Message>) -> Option<f32> {
        frame_texts(ctx, t_s, msg).0
    }

    /// A painted text: its string, whether it was elided, its left and
    /// right edges (px).
    type Painted = (String, bool, f32, f32);

    /// [`frame`], and the texts painted.
    fn frame_texts(
        ctx: &egui::Context,
        t_s: f64,
        msg: Option<&Message>,
    ) -> (Option<f32>, Vec<Painted>) {
        let raw = egui::RawInput {
            time: Some(t_s),
            screen_rect: Some(egui::Rect::from_min_size(
                egui::Pos2::ZERO,
                egui::vec2(400.0, 800.0),
            )),
            ..Default::default()
        };
        let mut cmds = Vec::new();
        let mut out = ctx.run_ui(raw, |ui| banner(ui, msg, &mut cmds));
        // (no painter takes the font textures here)
        out.textures_delta.clear();
        let texts = out
            .shapes
            .iter()
            .filter_map(|c| match &c.shape {
                egui::Shape::Text(t) => Some((
                    t.galley.text().to_owned(),
                    t.galley.elided,
                    t.visual_bounding_rect().left(),
                    t.visual_bounding_rect().right(),
                )),
                _ => None,
            })
            .collect();
        let height = msg.and_then(|_| {
            ctx.memory(|m| m.area_rect(egui::Id::unique("tirecontact.banner")))
                .map(|r| r.height())
        });
        (height, texts)
    }

    /// A message folds [`BANNER_UNFOLDED_S`] after it is first shown; the
    /// same message shown again after none was, or another message, is
    /// shown whole for that long again, even after the user unfolded or
    /// folded the first.
    #[test]
    fn each_showing_of_a_message_folds_after_its_own_delay() {
        let ctx = egui::Context::default();
        let long = |text: &str| Message {
            error: true,
            text: format!(
                "{text}: {}",
                "a reason long enough to wrap at phone width ".repeat(4)
            ),
        };
        let (a, b) = (long("first"), long("second"));
        let whole = frame(&ctx, 0.0, Some(&a)).unwrap();
        assert_eq!(frame(&ctx, 1.0, Some(&a)), Some(whole));
        let (folded, texts) = frame_texts(&ctx, BANNER_UNFOLDED_S + 0.1, Some(&a));
        let folded = folded.unwrap();
        assert!(folded < 0.6 * whole, "{folded} px folded, {whole} px whole");
        // its first row, elided, left of the More and Dismiss buttons
        let (_, elided, _, right) = texts
            .iter()
            .find(|(t, ..)| t.starts_with("first"))
            .expect("the message's text");
        let more_left = texts
            .iter()
            .filter(|(t, ..)| t == "More" || t == "Dismiss")
            .map(|&(_, _, left, _)| left)
            .fold(f32::INFINITY, f32::min);
        assert!(*elided, "folded text not elided");
        assert!(
            *right < 400.0 - 100.0 && *right < more_left,
            "text to {right} px, buttons from {more_left}"
        );
        // unfolded by the user: stays so while shown
        ctx.data_mut(|d| {
            let key = egui::Id::unique("tirecontact.banner.fold");
            let f = d.get_temp::<Fold>(key).unwrap();
            d.insert_temp(
                key,
                Fold {
                    open: Some(true),
                    ..f
                },
            );
        });
        assert_eq!(frame(&ctx, 30.0, Some(&a)), Some(whole));
        // dismissed, then shown again: whole, then folded after the delay
        assert_eq!(frame(&ctx, 31.0, None), None);
        assert_eq!(frame(&ctx, 32.0, Some(&a)), Some(whole));
        assert_eq!(
            frame(&ctx, 32.0 + BANNER_UNFOLDED_S + 0.1, Some(&a)),
            Some(folded)
        );
        // another message replacing it: whole again
        assert_eq!(frame(&ctx, 50.0, Some(&b)), Some(whole));
    }
}
