//! The scene view's legend as a row above the plot (classroom mode): in a
//! short scene plot (about 200 px at 1280 × 720) egui_plot's legend, six
//! entries high in a corner, covered the tyre. Each entry is one widget
//! (named like the item, for screen readers and the tests): its key drawn
//! as in the plot (a line, dashed or solid; a ring, a disc or a diamond; a
//! dot for the force arrows, as egui_plot's legend draws it) and its name.

use egui::{Color32, Pos2, Role, Sense, Shape, Stroke, TextStyle, Ui, Vec2, WidgetInfo};

/// How an entry's key is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Key {
    Line,
    DashedLine,
    DottedLine,
    Ring,
    Disc,
    Diamond,
    /// ▼, as the marks of clipped impacts.
    TriangleDown,
}

/// One legend entry.
#[derive(Debug, Clone, PartialEq)]
pub struct Entry {
    /// Its name (also its accessible name).
    pub name: &'static str,
    /// A shorter name, shown when the names do not fit one row at the
    /// smallest readable size.
    pub short: &'static str,
    pub color: Color32,
    pub key: Key,
}

/// Smallest text (px) of a legend row (classroom mode: read from the back
/// of a room; its small text was 15 px).
pub const ROW_MIN_PX: f32 = 20.0;

/// Width (px) of an entry's key.
const KEY_W_PX: f32 = 18.0;

/// The entries in a wrapped row, text at least `min_px` high (or
/// `style`'s size, if larger) and up to body text, as far as one row has
/// room; their short names when the names do not fit one row at the
/// smallest size.
pub fn row(ui: &mut Ui, entries: &[Entry], style: &TextStyle, min_px: f32) {
    let gap_px = 14.0;
    let font = style.resolve(ui.style());
    let min_px = min_px.max(font.size);
    let body = TextStyle::Body.resolve(ui.style()).size.max(min_px);
    let at_min = egui::FontId::new(min_px, font.family.clone());
    let needed = |short: bool| -> f32 {
        entries
            .iter()
            .map(|e| {
                let text = if short { e.short } else { e.name };
                let w = ui
                    .painter()
                    .layout_no_wrap(text.to_owned(), at_min.clone(), Color32::WHITE)
                    .size()
                    .x;
                KEY_W_PX + 4.0 + w + gap_px
            })
            .sum()
    };
    let short = needed(false) > ui.available_width();
    let room = ui.available_width() / needed(short).max(1.0);
    let size = (min_px * 0.97 * room).clamp(min_px, body);
    let font = egui::FontId::new(size, font.family);
    ui.horizontal_wrapped(|ui| {
        ui.spacing_mut().item_spacing.x = gap_px;
        for e in entries {
            let shown = if short { e.short } else { e.name };
            item_in(ui, e.name, shown, e.color, e.key, font.clone());
        }
    });
}

/// One legend entry named `name` (any text), its key `key` in `color`.
pub fn item(ui: &mut Ui, name: &str, color: Color32, key: Key, style: &TextStyle) {
    item_in(ui, name, name, color, key, style.resolve(ui.style()));
}

/// [`item`] in `font`, showing `shown` (its accessible name `name`).
fn item_in(ui: &mut Ui, name: &str, shown: &str, color: Color32, key: Key, font: egui::FontId) {
    let text_color = ui.visuals().text_color();
    let galley = ui
        .painter()
        .layout_no_wrap(shown.to_owned(), font, text_color);
    let size = Vec2::new(KEY_W_PX + 4.0 + galley.size().x, galley.size().y);
    let (rect, response) = ui.allocate_exact_size(size, Sense::hover());
    response.widget_info(|| WidgetInfo::labeled(Role::Label, true, name));
    let c = Pos2::new(rect.left() + 0.5 * KEY_W_PX, rect.center().y);
    let r = 0.3 * galley.size().y;
    let p = ui.painter();
    match key {
        Key::Line => {
            p.line_segment(
                [c - Vec2::new(8.0, 0.0), c + Vec2::new(8.0, 0.0)],
                Stroke::new(2.0, color),
            );
        }
        Key::DashedLine => {
            for x in [-8.0, -1.0, 6.0] {
                p.line_segment(
                    [c + Vec2::new(x, 0.0), c + Vec2::new(x + 3.0, 0.0)],
                    Stroke::new(1.5, color),
                );
            }
        }
        Key::DottedLine => {
            for x in [-8.0, -4.0, 0.0, 4.0, 8.0] {
                p.circle_filled(c + Vec2::new(x, 0.0), 1.0, color);
            }
        }
        Key::Ring => {
            p.circle_stroke(c, r, Stroke::new(1.5, color));
        }
        Key::Disc => {
            p.circle_filled(c, r, color);
        }
        Key::Diamond => {
            let pts = vec![
                c + Vec2::new(0.0, -r * 1.2),
                c + Vec2::new(r * 1.2, 0.0),
                c + Vec2::new(0.0, r * 1.2),
                c + Vec2::new(-r * 1.2, 0.0),
            ];
            p.add(Shape::convex_polygon(pts, color, Stroke::NONE));
        }
        Key::TriangleDown => {
            let pts = vec![
                c + Vec2::new(-r * 1.2, -r),
                c + Vec2::new(r * 1.2, -r),
                c + Vec2::new(0.0, r),
            ];
            p.add(Shape::convex_polygon(pts, color, Stroke::NONE));
        }
    }
    p.galley(
        Pos2::new(rect.left() + KEY_W_PX + 4.0, rect.top()),
        galley,
        text_color,
    );
}
