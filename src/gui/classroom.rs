//! Classroom mode: large fonts, a presenter layout (the scene large
//! with the contact phase of every point written over it, one time plot of a
//! chosen point below, the mode contribution bars beside), slow motion, and
//! the guided preset's explanation shown prominently.

mod mode_bars;
mod scene_phases;

pub use mode_bars::{
    MODE_BARS_PLOT_ID, MODE_BARS_Y_LABEL, mode_bar_color, mode_bars, mode_bars_min_px,
    mode_bars_panel,
};
pub use scene_phases::{TOP_VIEW_DOT_PX, scene_with_phases, top_view_caption};

use super::views::force_labels::{self, force_text};
use super::views::time_plots::{
    IMPACT_LABEL, IMPACT_MARK_COLOR, clip_at, clip_level, force_range, impact_marks,
};
use super::views::{CONTACT_COLOR, FLIGHT_COLOR, point_color, scene_view};
use crate::Simulation;
use crate::gui::model::history::{History, Quantity};
use crate::gui::views::XTitle;
use crate::solver::phase::{ContactPhase, PhaseTracker};
use egui::{Color32, FontId, RichText, TextStyle, Ui};
use egui_plot::{Line, Plot, PlotPoint, Text};
use std::collections::BTreeMap;

/// Text sizes in classroom mode, relative to the normal ones.
pub const FONT_SCALE: f32 = 1.7;
/// Size (px) of the small text in classroom mode.
pub const CLASSROOM_SMALL_PX: f32 = 9.0 * FONT_SCALE;
/// Smallest text (px) of the classroom's views (legends, phase strip, axis
/// numbers and titles): read from the back of a room.
pub const CLASSROOM_MIN_TEXT_PX: f32 = 20.0;
/// Playback speed set when classroom mode starts (simulated s per wall s).
pub const SLOW_MOTION: f64 = 0.05;
/// How long an impact or release label stays up at most (wall-clock s at
/// the current playback speed; also at most `phase::EVENT_SHARE` of the
/// contact or flight it starts).
pub const EVENT_HOLD_WALL_S: f64 = 0.6;
/// Colour of impact / release labels.
pub const EVENT_COLOR: Color32 = Color32::from_rgb(204, 0, 102);
/// Radius (px) of the ring around a point at an impact or release (the
/// points' markers are 7 px).
pub const EVENT_RING_PX: f32 = 11.0;
/// Plot item name of the rings (no legend entry: the labels say it).
const EVENT_RING_NAME: &str = "";

/// Classroom presentation state (the phases are tracked by the app).
#[derive(Debug, Clone, Default)]
pub struct Classroom {
    pub on: bool,
    /// Text styles and theme preference before classroom mode changed them.
    saved: Option<(BTreeMap<TextStyle, FontId>, egui::ThemePreference)>,
    /// The user's theme preference from the last session, when it ended in
    /// classroom mode: egui keeps the preference between runs, so at the
    /// next start it is classroom mode's light one.
    pub theme_before: Option<egui::ThemePreference>,
    /// The last mute or solo refused, until the next one or a way out.
    pub mute_refused: Option<MuteRefusal>,
    /// Point of the plot and the bars.
    pub point: usize,
    /// What the plot shows: force or displacement.
    pub show_force: bool,
    /// Mode bars shown in the normal layout too.
    pub bars: bool,
    /// The view and speed before classroom mode changed them, given back
    /// when it ends (each only if classroom mode's is still in place).
    pub before: Option<(
        crate::gui::model::command::View,
        crate::gui::model::time_control::Speed,
    )>,
    /// Classroom mode was turned off because the window narrowed to a
    /// phone's width: it comes back when the window widens again, unless
    /// a view or the mode was chosen meanwhile.
    pub back_when_wide: bool,
}

impl Classroom {
    /// Scales the text styles up when `on`, back when not (idempotent).
    /// Returns whether the style changed: the frame's root `Ui` took its
    /// style before and must be given the new one (else the frame lays out
    /// in the old text sizes, and the editing panel, shown in classroom
    /// mode's large text on the first frame after it, kept that width).
    pub fn sync_style(&mut self, ctx: &egui::Context) -> bool {
        if !self.on {
            self.theme_before = None;
        }
        let changed = self.on != self.saved.is_some();
        match (self.on, self.saved.is_some()) {
            (true, false) => {
                let theme = self
                    .theme_before
                    .take()
                    .unwrap_or_else(|| ctx.options(|o| o.theme_preference));
                self.saved = Some((ctx.global_style().text_styles.clone(), theme));
                // dark text on white reads best on a projector
                ctx.set_theme(egui::ThemePreference::Light);
                ctx.all_styles_mut(|s| {
                    for f in s.text_styles.values_mut() {
                        f.size *= FONT_SCALE;
                    }
                    // the small text no larger than egui's 9 px scaled:
                    // the scene's legend row in it fits 1280 px
                    if let Some(f) = s.text_styles.get_mut(&TextStyle::Small) {
                        f.size = f.size.min(CLASSROOM_SMALL_PX);
                    }
                    s.spacing.interact_size.y *= 1.3;
                });
            }
            (false, true) => {
                if let Some((saved, theme)) = self.saved.take() {
                    ctx.set_theme(theme);
                    ctx.all_styles_mut(|s| {
                        s.text_styles = saved.clone();
                        s.spacing.interact_size.y /= 1.3;
                    });
                }
            }
            _ => {}
        }
        changed
    }
}

/// A mute or solo refused (rigid contact would be singular): shown beside
/// the mode bars with the ways out.
#[derive(Debug, Clone, PartialEq)]
pub struct MuteRefusal {
    pub mode: usize,
    pub solo: bool,
    pub text: String,
    /// The contact was rigid (compliant contact is a way out).
    pub rigid: bool,
}

impl Classroom {
    /// The theme preference classroom mode gives back when it ends (`None`
    /// when it is off).
    pub fn user_theme(&self) -> Option<egui::ThemePreference> {
        self.saved
            .as_ref()
            .map(|s| s.1)
            .or(self.theme_before.filter(|_| self.on))
    }
}

fn phase_color(p: ContactPhase) -> Color32 {
    match p {
        ContactPhase::Impact | ContactPhase::Release => EVENT_COLOR,
        ContactPhase::InContact => CONTACT_COLOR,
        ContactPhase::FreeFlight => FLIGHT_COLOR,
    }
}

/// `p0: IMPACT` (events in capitals).
pub fn phase_text(i: usize, p: ContactPhase) -> String {
    format!("p{i}: {}", p.shown())
}

/// A strip of the phases of every point (also what the tests read), or,
/// when the points' labels do not fit one row in the classroom's type
/// scale, the number of points in each phase.
pub fn phase_strip(ui: &mut Ui, t_s: f64, phases: &PhaseTracker) {
    const PREFIX: &str = "contact phase:";
    let n = phases.num_points();
    let body = egui::TextStyle::Body.resolve(ui.style());
    let width_at = |text: String, px: f32| {
        ui.painter()
            .layout_no_wrap(
                text,
                egui::FontId::new(px, body.family.clone()),
                Color32::WHITE,
            )
            .size()
            .x
    };
    let all = ContactPhase::ALL;
    // every label in a slot as wide as its widest text, so that the strip
    // keeps its layout as phases change, on one row
    let gap = ui.spacing().item_spacing.x;
    let avail = ui.available_width();
    let per_point_slot = |px: f32| {
        all.iter()
            .map(|&ph| width_at(phase_text(n.saturating_sub(1), ph), px))
            .fold(0.0, f32::max)
    };
    let count_slot = |px: f32| {
        all.iter()
            .map(|&ph| width_at(count_text(n, ph), px))
            .fold(0.0, f32::max)
    };
    // each point's phase when every point's slot fits one row in the
    // classroom's type scale; else how many points are in each phase (a
    // patch's 96 points took the strip down to 13 px at 1280 px, and a
    // second row would push the scene down and up as it wrapped)
    let least_px = CLASSROOM_MIN_TEXT_PX.min(body.size);
    let per_point =
        width_at(PREFIX.into(), least_px) + n as f32 * (per_point_slot(least_px) + gap) <= avail;
    let slots = if per_point { n } else { all.len() };
    let slot_w = |px: f32| {
        if per_point {
            per_point_slot(px)
        } else {
            count_slot(px)
        }
    };
    let need = |px: f32| width_at(PREFIX.into(), px) + slots as f32 * (slot_w(px) + gap);
    // as large as fits, down to the classroom's least size for the points'
    // labels; a window narrower than the counts' row: smaller, never wrapped
    let px = if need(body.size) <= avail {
        body.size
    } else {
        (body.size * avail / need(body.size))
            .max(0.6 * body.size)
            .floor()
    };
    let slot = slot_w(px);
    ui.horizontal(|ui| {
        ui.label(RichText::new(PREFIX).strong().size(px));
        if per_point {
            for i in 0..n {
                let ph = phases.phase(i, t_s);
                let text = RichText::new(phase_text(i, ph))
                    .strong()
                    .size(px)
                    .color(phase_color(ph));
                ui.add_sized(
                    [slot, ui.spacing().interact_size.y],
                    egui::Label::new(text).wrap_mode(egui::TextWrapMode::Extend),
                )
                .on_hover_text(format!(
                    "{} impacts, {} releases so far",
                    phases.impacts(i),
                    phases.releases(i)
                ));
            }
        } else {
            for ph in all {
                let count = (0..n).filter(|&i| phases.phase(i, t_s) == ph).count();
                let text = RichText::new(count_text(count, ph))
                    .strong()
                    .size(px)
                    .color(phase_color(ph));
                ui.add_sized(
                    [slot, ui.spacing().interact_size.y],
                    egui::Label::new(text).wrap_mode(egui::TextWrapMode::Extend),
                )
                .on_hover_text(format!("how many of the {n} points are in each phase"));
            }
        }
    });
}

/// `12 IMPACT` (events in capitals): how many points are in phase `p`.
pub fn count_text(count: usize, p: ContactPhase) -> String {
    format!("{count} {}", p.shown())
}

/// Point picker shared by the plot and the bars.
/// Text colour of point `i` in the point picker: the point's colour, or,
/// selected, the selection's text colour (the point's colour on the
/// selection's fill was unreadable: point 0's blue on the dark theme's blue).
pub fn picker_color(visuals: &egui::Visuals, i: usize, selected: bool) -> Color32 {
    if selected {
        visuals.selection.stroke.color
    } else {
        super::views::point_label_color(visuals, i)
    }
}

pub fn point_picker(ui: &mut Ui, cls: &mut Classroom, p: usize) {
    if p > 1 && p <= PICKER_BUTTONS_MAX {
        ui.horizontal(|ui| {
            ui.label("point");
            for i in 0..p {
                let color = picker_color(ui.visuals(), i, cls.point == i);
                ui.selectable_value(
                    &mut cls.point,
                    i,
                    RichText::new(i.to_string()).color(color).strong(),
                );
            }
        });
    } else if p > PICKER_BUTTONS_MAX {
        // a patch's points: a number field (24 buttons in one row made the
        // presenter panel as wide as the window, the scene 130 px wide)
        ui.horizontal(|ui| {
            ui.label("point");
            let color = picker_color(ui.visuals(), cls.point, false);
            ui.visuals_mut().override_text_color = Some(color);
            ui.add(egui::DragValue::new(&mut cls.point).range(0..=p - 1))
                .on_hover_text("drag or type the point whose modes are shown");
            ui.visuals_mut().override_text_color = None;
            ui.label(format!("of 0 to {}", p - 1));
        });
    }
    cls.point = cls.point.min(p.saturating_sub(1));
}

/// Points up to which the picker is a row of buttons (more: a number field).
pub const PICKER_BUTTONS_MAX: usize = 10;

/// One plot of the chosen point: force or displacement over the last 0.1 s.
pub fn point_plot(ui: &mut Ui, history: &History, cls: &mut Classroom, now_s: f64) {
    let i = cls.point.min(history.num_points().saturating_sub(1));
    let (what, long, short, scale) = if cls.show_force {
        (Quantity::Force, "contact force q (N)", "q (N)", 1.0)
    } else {
        (
            Quantity::Displacement,
            "displacement u (mm, up)",
            "u (mm, up)",
            1e3,
        )
    };
    let window = 0.1;
    let t1 = history.last_time().unwrap_or(0.0).max(now_s).max(window);
    let t0 = t1 - window;
    let buckets = (ui.available_width() as usize).clamp(100, 4000);
    let mut pts = history.decimated(what, i, t0, t1, buckets, scale);
    // impacts clipped and marked ▼ as in the time plots: rigid contact draws
    // an impact as impulse / dt, which left the force a flat line under spikes
    let mut marks = Vec::new();
    if what == Quantity::Force
        && let Some(top) = force_range(history, &[i], t0, t1, buckets).map(clip_level)
    {
        clip_at(&mut pts, top, &mut marks);
    }
    ui.horizontal_wrapped(|ui| {
        ui.selectable_value(&mut cls.show_force, true, "contact force");
        ui.selectable_value(&mut cls.show_force, false, "displacement");
        ui.separator();
        legend_row(ui, i, !marks.is_empty());
    });
    // the vertical label is centred on the plot frame: in a short plot the
    // long one ran up over the force / displacement switch above
    let frame_h = ui.available_height() - 3.0 * ui.text_style_height(&TextStyle::Body);
    let label = fitting_label(ui, long, short, frame_h);
    // a time label centred closer to the frame's edge than half its width
    // was cut by it: "0.1" left of 0.17 s at the right edge, a wrong time
    let half_label_px = 0.5
        * ui.painter()
            .layout_no_wrap(
                "0.000".to_owned(),
                TextStyle::Body.resolve(ui.style()),
                Color32::WHITE,
            )
            .size()
            .x;
    // the frame: the width less the y axis (its labels and title, about
    // three body rows); a few px either way only moves the cut-off
    let frame_w = (ui.available_width() - 3.0 * ui.text_style_height(&TextStyle::Body)).max(1.0);
    super::views::nice_y_axis(Plot::new("tirecontact.classroom_plot"))
        .id(egui::Id::unique(CLASSROOM_PLOT_ID))
        .x_title(ui, "time t (s)")
        .x_axis_formatter(move |m, range| {
            let span = range.end() - range.start();
            let px = |v: f64| (v / span) as f32 * frame_w;
            let from_edge = px(m.value - range.start()).min(px(range.end() - m.value));
            if span > 0.0 && from_edge < half_label_px + 2.0 {
                String::new()
            } else {
                // egui_plot's own format
                let n = (-m.step_size.log10().round()).max(0.0) as usize;
                egui::emath::format_with_decimals_in_range(m.value, n..=n)
            }
        })
        .y_axis_label(label)
        .allow_scroll(false)
        .allow_drag(false)
        .include_y(0.0)
        .show(ui, |pui| {
            pui.set_plot_bounds_x(t0..=t1);
            pui.line(
                Line::new(format!("point {i}"), pts)
                    .color(point_color(i))
                    .width(2.5)
                    .allow_band(false),
            );
            impact_marks(pui, marks, egui_plot::MarkerShape::Down);
        });
}

/// The legend of the point plot, in the row of its force / displacement
/// switch above it: the plot's curve fills the window's width, so in any
/// corner the legend covered some of it (fixed top left it covered the
/// curve's start; in a strip past the window's end, as in the time plots, it
/// took 343 of the 717 px of the frame at 1280 × 720 with the clipped
/// impacts' entry in classroom text).
fn legend_row(ui: &mut Ui, point: usize, clipped: bool) {
    use super::views::scene_legend::{Key, item};
    let style = TextStyle::Body;
    item(
        ui,
        &format!("point {point}"),
        point_color(point),
        Key::Line,
        &style,
    );
    if clipped {
        ui.add_space(8.0);
        item(
            ui,
            IMPACT_LABEL,
            IMPACT_MARK_COLOR,
            Key::TriangleDown,
            &style,
        );
    }
}

/// Plot id of the classroom's point plot.
pub const CLASSROOM_PLOT_ID: &str = "tirecontact.classroom_plot";

/// `long` if it fits along `length_px` in the body font, else `short`.
fn fitting_label<'a>(ui: &Ui, long: &'a str, short: &'a str, length_px: f32) -> &'a str {
    let w = ui
        .painter()
        .layout_no_wrap(
            long.to_owned(),
            TextStyle::Body.resolve(ui.style()),
            Color32::WHITE,
        )
        .size()
        .x;
    if w + 8.0 <= length_px { long } else { short }
}

/// Share of the presenter panel's height the scene description may take
/// before it scrolls (the mode bars below fit the rest).
pub const DESCRIPTION_SHARE: f32 = 0.5;

/// The explanation of the scene, large (the guided presets' "what to watch").
/// `reserve_px`: height kept below it (for the mode bars).
/// `edits`: what changed since the scene was opened or saved, said under
/// the description (which was written before them).
pub fn explanation(ui: &mut Ui, name: &str, description: &str, edits: &[String], reserve_px: f32) {
    let note = super::panels::edits_note(edits);
    if description.is_empty() && note.is_none() {
        return;
    }
    egui::Frame::new()
        .fill(ui.visuals().faint_bg_color)
        .stroke(ui.visuals().widgets.noninteractive.bg_stroke)
        .inner_margin(8.0)
        .corner_radius(4.0)
        .show(ui, |ui| {
            // the name as a heading when it fits on one row; a long one in
            // strong body text (two heading rows cost the description a row)
            let heading = egui::TextStyle::Heading.resolve(ui.style());
            let one_row = ui
                .painter()
                .layout_no_wrap(name.to_owned(), heading, Color32::WHITE)
                .size()
                .x
                <= ui.available_width();
            if one_row {
                ui.label(RichText::new(name).strong().heading());
            } else {
                ui.label(RichText::new(name).strong());
            }
            // up to half the panel, in whole lines (no line cut in half); a
            // longer text scrolls with its scroll bar always shown
            let row_px = ui.text_style_height(&egui::TextStyle::Body);
            let room = (ui.available_height() * DESCRIPTION_SHARE)
                .min(ui.available_height() - reserve_px - 24.0);
            let lines = (room / row_px).floor().max(2.0);
            // a solid bar: the thin floating one was invisible on a projector
            ui.spacing_mut().scroll = egui::style::ScrollStyle::solid();
            egui::ScrollArea::vertical()
                .max_height(lines * row_px)
                .scroll_bar_visibility(egui::scroll_area::ScrollBarVisibility::AlwaysVisible)
                .show(ui, |ui| {
                    ui.label(RichText::new(description).color(ui.visuals().strong_text_color()));
                    if let Some(note) = &note {
                        ui.label(RichText::new(note).italics());
                    }
                });
        });
}
