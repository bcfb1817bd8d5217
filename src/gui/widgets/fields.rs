//! Numeric fields that refuse invalid values at the field, with the reason.
//!
//! A field shows a value of the scene in a display unit. When the user
//! commits a new text (Enter or focus lost), the text is parsed, the scene is
//! rebuilt with the new value and validated as a whole; if that fails the
//! value is refused and the reason stays next to the field (the scene keeps
//! its old value), otherwise a `Command::EditScene` is returned. The typed
//! text and the reason are widget state, kept in egui's memory.

use super::number::format_number;
use crate::Scene;
use crate::gui::model::command::Command;
use egui::{Color32, Id, RichText, Ui};

/// Accessible name of a refused field's mark.
pub const NOT_APPLIED: &str = "not applied";

/// Colour of refused values and error text.
pub const ERROR_COLOR: Color32 = Color32::from_rgb(220, 50, 47);
/// Colour of the "live" tag.
pub const LIVE_COLOR: Color32 = Color32::from_rgb(0, 158, 115);
/// Colour of the "restart" tag.
pub const RESTART_COLOR: Color32 = Color32::from_rgb(230, 159, 0);

/// How a change of a field reaches the running simulation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Apply {
    /// Applied to the running simulation at once.
    Live,
    /// Changing it restarts the run from t = 0.
    Restart,
}

impl Apply {
    pub fn tooltip(self) -> &'static str {
        match self {
            Apply::Live => "applied live: the run goes on",
            Apply::Restart => "changing this restarts the run from t = 0",
        }
    }
}

/// A section heading with its live/restart tag.
pub fn section(ui: &mut Ui, title: &str, apply: Apply) {
    super::text_row(ui, |ui| {
        ui.strong(title);
        tag(ui, apply);
    });
}

/// The small coloured "live" / "restart" tag.
pub fn tag(ui: &mut Ui, apply: Apply) {
    let (text, color) = match apply {
        Apply::Live => ("live", LIVE_COLOR),
        Apply::Restart => ("restart", RESTART_COLOR),
    };
    ui.label(RichText::new(text).small().color(color))
        .on_hover_text(apply.tooltip());
}

#[derive(Clone, Default)]
struct FieldState {
    /// Model value (SI) the text was last synchronised with.
    shown: f64,
    text: String,
    error: Option<String>,
}

/// One numeric field.
pub struct NumField<'a> {
    /// Accessible name and memory key, e.g. `tyre.modes[0].freq_hz`.
    pub name: &'a str,
    /// Scene field checked by validation (often equal to `name`).
    pub field: &'a str,
    /// Current value (SI).
    pub value: f64,
    /// Display value = SI value × scale (e.g. 1000 for mm).
    pub scale: f64,
    /// Display unit, shown after the field.
    pub unit: &'a str,
    pub apply: Apply,
    pub width: f32,
}

impl<'a> NumField<'a> {
    pub fn new(name: &'a str, value: f64, unit: &'a str, apply: Apply) -> Self {
        NumField {
            name,
            field: name,
            value,
            scale: 1.0,
            unit,
            apply,
            width: 70.0,
        }
    }
    pub fn scale(mut self, scale: f64) -> Self {
        self.scale = scale;
        self
    }
    pub fn field(mut self, field: &'a str) -> Self {
        self.field = field;
        self
    }
    pub fn width(mut self, width: f32) -> Self {
        self.width = width;
        self
    }

    /// What the field means, its unit, the values it accepts and how an
    /// edit reaches the run (`field_help`); a field unknown there names its
    /// preset field and unit.
    pub fn tooltip(&self) -> String {
        match crate::gui::widgets::field_help::help(self.name) {
            Some(h) => h.tooltip(self.name, self.scale, self.unit, self.apply.tooltip()),
            None => format!(
                "{} in {} ({})",
                self.name,
                if self.unit.is_empty() { "-" } else { self.unit },
                self.apply.tooltip()
            ),
        }
    }

    /// Shows the field; `with` builds the edited scene from a new SI value.
    /// One body on purpose: the text kept while typing, the parse, the
    /// refusal and the restore share the field's state read at the top and
    /// stored at the end.
    pub fn show(self, ui: &mut Ui, with: impl FnOnce(f64) -> Scene) -> Option<Command> {
        let id = Id::unique(("tirecontact.field", self.name));
        let mut st: FieldState = ui.data(|d| d.get_temp(id)).unwrap_or_else(|| FieldState {
            shown: f64::NAN,
            ..FieldState::default()
        });
        let focused = ui.memory(|m| m.has_focus(id));
        if !focused && !same(st.shown, self.value) {
            st = FieldState {
                shown: self.value,
                text: format_number(self.value * self.scale),
                error: None,
            };
        }
        let mut cmd = None;
        // a refusal changes no widget's size or place: the field is ringed
        // and its text red, the reason is in its hover text and the banner.
        // (The reason beside the field widened the editing panel and moved
        // every field right of it; under it, it added a row, and the row
        // went away as the value was fixed, so the next click missed.)
        ui.horizontal(|ui| {
            // as wide as its text: narrower, it showed the start of a
            // long value (0.0497 for 0.0497672), a wrong number
            let width = self.width.max(fit_width(ui, &st.text));
            let mut edit = egui::TextEdit::singleline(&mut st.text)
                .id(id)
                .desired_width(width)
                // a grid cell offers the width of its column's last frame
                // (at first 40 px), which `desired_width` does not exceed
                .min_size(egui::vec2(width, 0.0));
            if st.error.is_some() {
                edit = edit.text_color(ERROR_COLOR);
            }
            let resp = ui.add(edit).accessible_name(self.name);
            let hover = match &st.error {
                Some(e) => format!(
                    "{NOT_APPLIED}: {e}; the scene keeps its previous value\n\n{}",
                    self.tooltip()
                ),
                None => self.tooltip(),
            };
            let resp = resp.on_hover_text(&hover);
            if st.error.is_some() {
                ui.painter().rect_stroke(
                    resp.rect.expand(1.0),
                    3.0,
                    egui::Stroke::new(1.5, ERROR_COLOR),
                    egui::StrokeKind::Outside,
                );
                // named for screen readers (and the tests), taking no room:
                // over the field, not allocated in the row; its hover text
                // the field's
                let mark = ui.interact(resp.rect, id.with(NOT_APPLIED), egui::Sense::hover());
                mark.widget_info(|| {
                    egui::WidgetInfo::labeled(egui::Role::Label, true, NOT_APPLIED)
                });
                mark.on_hover_text(&hover);
            }
            if !self.unit.is_empty() {
                ui.label(self.unit);
            }
            let unchanged = st.text.trim() == format_number(self.value * self.scale);
            if resp.lost_focus() && unchanged && st.error.take().is_some() {
                // the kept value typed back after a refusal: nothing to
                // apply, and nothing refused any more
                cmd = Some(Command::FieldRestored {
                    field: self.name.to_string(),
                });
            }
            if resp.lost_focus() && !unchanged {
                match parse_number(&st.text) {
                    Err(e) => st.error = Some(e),
                    Ok(x) => {
                        let v = x / self.scale;
                        let scene = with(v);
                        match scene.validate() {
                            Ok(()) => {
                                st.error = None;
                                st.shown = v;
                                cmd = Some(Command::EditScene(Box::new(scene)));
                            }
                            Err(errors) => {
                                let mine: Vec<_> =
                                    errors.iter().filter(|e| e.field == self.field).collect();
                                let shown: Vec<String> = if mine.is_empty() {
                                    errors.iter().map(ToString::to_string).collect()
                                } else {
                                    mine.iter()
                                        .map(|e| format!("expected {}", e.expected))
                                        .collect()
                                };
                                let unit = if self.unit.is_empty() {
                                    String::new()
                                } else {
                                    format!(" {}", self.unit)
                                };
                                st.error = Some(format!(
                                    "refused: {} (got {}{unit})",
                                    shown.join("; "),
                                    st.text.trim()
                                ));
                            }
                        }
                    }
                }
                // the whole reason goes to the message banner, which has
                // the room for it; the field keeps a short mark
                if let Some(e) = &st.error {
                    cmd = Some(Command::FieldRefused {
                        field: self.name.to_string(),
                        text: format!(
                            "{}: {e}; the scene keeps {}{}.",
                            banner_name(self.name),
                            format_number(self.value * self.scale),
                            if self.unit.is_empty() {
                                String::new()
                            } else {
                                format!(" {}", self.unit)
                            }
                        ),
                    });
                }
            }
        });
        ui.data_mut(|d| d.insert_temp(id, st));
        cmd
    }
}

/// Width (px) a single-line field needs to show `text` whole: the text in
/// the body font and the field's margins (8 px each side) with a pixel to
/// spare, at most 320 px.
fn fit_width(ui: &Ui, text: &str) -> f32 {
    let w = ui
        .painter()
        .layout_no_wrap(
            text.to_owned(),
            egui::TextStyle::Body.resolve(ui.style()),
            Color32::WHITE,
        )
        .size()
        .x;
    (w + 18.0).min(320.0)
}

/// Forgets every field's typed text and refusal (a new document: a text
/// refused in the old one must not stay up over an equal value of the new).
pub fn forget_all(ctx: &egui::Context) {
    ctx.data_mut(|d| d.remove_by_type::<FieldState>());
}

fn same(a: f64, b: f64) -> bool {
    a == b || (a.is_nan() && b.is_nan())
}

/// Parses a number as typed by a person: `1.5`, `1,5`, `2e-3`, ` 7 `.
pub fn parse_number(text: &str) -> Result<f64, String> {
    let t = text.trim().replace(',', ".");
    if t.is_empty() {
        return Err("refused: empty; expected a number".to_string());
    }
    match t.parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        Ok(_) => Err(format!("refused: {t}; expected a finite number")),
        Err(_) => Err(format!(
            "refused: '{t}' is not a number; expected one such as 1.5 or 2e-3"
        )),
    }
}

/// A field as the banner names it: its label in the editor, then its
/// preset path (`road amplitude a (road.amplitude_m)`); the path alone for
/// a field without such a label.
pub fn banner_name(name: &str) -> String {
    let label = if name == "speed_kmh" {
        "speed V".to_string()
    } else {
        crate::scene::fields::label(name)
    };
    // the path is said only where it adds to the label: "points along",
    // not "points along (points.along)"
    let words = |s: &str| {
        s.chars()
            .filter(|c| c.is_alphanumeric())
            .collect::<String>()
    };
    if label == name || words(&label) == words(name) {
        label
    } else {
        format!("{label} ({name})")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_parse_as_typed() {
        assert_eq!(parse_number(" 1,5 "), Ok(1.5));
        assert_eq!(parse_number("2e-3"), Ok(2e-3));
        assert!(parse_number("abc").is_err());
        assert!(parse_number("").is_err());
        assert!(parse_number("inf").is_err());
    }

    #[test]
    fn banners_name_a_field_by_its_label_and_the_path_only_where_it_adds() {
        assert_eq!(
            banner_name("road.amplitude_m"),
            "road amplitude a (road.amplitude_m)"
        );
        assert_eq!(banner_name("points.along"), "points along");
        assert_eq!(banner_name("speed_kmh"), "speed V (speed_kmh)");
        assert_eq!(banner_name("no.such"), "no.such");
    }
}
