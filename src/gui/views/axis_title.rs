//! Y axis titles that fit their plot: egui_plot draws a y title rotated and
//! centred on the plot frame, never shortened, so in short stacked plots (the
//! A/B compare view's four rows at 1280 × 720) a long title ran past its plot
//! into the neighbours' titles. `fit` takes the full title in body text if it
//! fits the frame's height, else the short title, else small text; a
//! shortened title shows the full one on hover (`hover`).

use egui::{Id, Pos2, Rect, RichText, Sense, TextStyle, Ui};

/// Room (px) kept free at each end of a y title.
const END_GAP_PX: f32 = 4.0;

/// A y title chosen to fit: the text to give egui_plot and whether it was
/// shortened or made small (then `hover` shows the full title).
#[derive(Debug, Clone, PartialEq)]
pub struct YTitle {
    pub text: RichText,
    pub shortened: bool,
}

/// Length (px) of `text` set in `style`, unwrapped.
pub fn text_length_px(ui: &Ui, text: &str, style: &TextStyle) -> f32 {
    let font = style.resolve(ui.style());
    ui.painter()
        .layout_no_wrap(text.to_owned(), font, egui::Color32::WHITE)
        .size()
        .x
}

/// Height (px) of the frame of a plot `plot_h_px` high (its x axis below
/// takes the tick labels' row, and the title's row when `x_title`).
pub fn frame_height_px(ui: &Ui, plot_h_px: f32, x_title: bool) -> f32 {
    let row = TextStyle::Body.resolve(ui.style()).size + 6.0;
    plot_h_px - row * if x_title { 2.0 } else { 1.0 }
}

/// The y title of a frame `frame_h_px` high: `full` in body text, `short` in
/// body text, `full` in small text or `short` in small text, the first that
/// fits (the last when none does; small text is hard to read, so the short
/// title in body text comes first).
pub fn fit(ui: &Ui, full: &str, short: &str, frame_h_px: f32) -> YTitle {
    let room = frame_h_px - 2.0 * END_GAP_PX;
    let options = [
        (full, TextStyle::Body),
        (short, TextStyle::Body),
        (full, TextStyle::Small),
        (short, TextStyle::Small),
    ];
    let pick = options
        .iter()
        .find(|(t, s)| text_length_px(ui, t, s) <= room)
        .unwrap_or(&options[3]);
    let (text, style) = (pick.0, pick.1.clone());
    YTitle {
        shortened: text != full || style != TextStyle::Body,
        text: RichText::new(text).text_style(style),
    }
}

fn key(id: Id) -> Id {
    id.with("tirecontact.y_title_frame_h")
}

/// The y title of plot `id` (`plot_h_px` high): fitted to its frame's height
/// on the last frame (estimated before the first).
pub fn fit_plot(ui: &Ui, id: Id, full: &str, short: &str, plot_h_px: f32, x_title: bool) -> YTitle {
    let frame_h = ui
        .ctx()
        .data(|d| d.get_temp::<f32>(key(id)))
        .unwrap_or_else(|| frame_height_px(ui, plot_h_px, x_title));
    fit(ui, full, short, frame_h)
}

/// After plot `id` is shown: keeps its frame's height for the next frame's
/// fit (repainting at once when it changed) and shows `full` on hover over
/// the y axis when the title was shortened.
pub fn after_plot<R>(ui: &Ui, id: Id, title: &YTitle, full: &str, r: &egui_plot::PlotResponse<R>) {
    let frame = *r.transform.frame();
    let h = frame.height();
    let old = ui.ctx().data(|d| d.get_temp::<f32>(key(id)));
    if old.is_none_or(|o| (o - h).abs() > 0.5) {
        ui.ctx().data_mut(|d| d.insert_temp(key(id), h));
        ui.ctx().request_repaint();
    }
    hover(ui, id, title, full, frame, 64.0);
}

/// Shows `full` on hover over the y axis (64 px left of `frame`, or
/// `axis_w_px`) when the title was shortened.
pub fn hover(ui: &Ui, id: Id, title: &YTitle, full: &str, frame: Rect, axis_w_px: f32) {
    if !title.shortened {
        return;
    }
    let r = Rect::from_min_max(
        Pos2::new(frame.left() - axis_w_px, frame.top()),
        Pos2::new(frame.left(), frame.bottom()),
    );
    ui.interact(r, id.with("tirecontact.y_title_hover"), Sense::hover())
        .on_hover_text(full);
}
