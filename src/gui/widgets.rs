//! Widgets of the editing panels: numeric fields that refuse bad values
//! with the reason, and what each field means; and the width below which
//! the window is laid out for a phone.

pub mod field_help;
pub mod fields;
pub mod number;

/// Below this window width (logical px: a phone) the editing panel hides
/// behind a button instead of covering the views, and the menu bar folds
/// into a few menus.
pub const NARROW_PX: f32 = 700.0;

/// Where egui keeps the button and field sizes a narrow window replaced
/// by touch targets (its `interact_size` and `button_padding`), to give
/// them back in a wide one.
pub fn touch_targets_id() -> egui::Id {
    egui::Id::unique("tirecontact.touch_targets")
}

/// Height (px) of a row of text alone (labels, separators, a spinner):
/// egui's row height, except where a phone raised `interact_size.y` to a
/// fingertip's target, which `ui.horizontal` also takes as the least
/// height of any row: there a row of plain text was 47 px high.
pub fn text_row_px(ui: &egui::Ui) -> f32 {
    let saved: Option<(egui::Vec2, egui::Vec2)> = ui.data(|d| d.get_temp(touch_targets_id()));
    let interact = saved.map_or(ui.spacing().interact_size.y, |(size, _)| size.y);
    interact.max(ui.text_style_height(&egui::TextStyle::Body))
}

/// A row of text alone, [`text_row_px`] high: `ui.horizontal` without a
/// phone's touch-target height.
pub fn text_row<R>(
    ui: &mut egui::Ui,
    add: impl FnOnce(&mut egui::Ui) -> R,
) -> egui::InnerResponse<R> {
    let size = egui::vec2(ui.available_size_before_wrap().x, text_row_px(ui));
    ui.allocate_ui_with_layout(size, egui::Layout::left_to_right(egui::Align::Center), add)
}

/// Rows of text alone that wrap at the width available
/// (`ui.horizontal_wrapped`), the first [`text_row_px`] high.
pub fn text_row_wrapped<R>(
    ui: &mut egui::Ui,
    add: impl FnOnce(&mut egui::Ui) -> R,
) -> egui::InnerResponse<R> {
    let size = egui::vec2(ui.available_size_before_wrap().x, text_row_px(ui));
    let layout = egui::Layout::left_to_right(egui::Align::Center).with_main_wrap(true);
    ui.allocate_ui_with_layout(size, layout, add)
}
