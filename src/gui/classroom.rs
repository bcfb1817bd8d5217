//! Classroom mode: large fonts, a presenter layout (the scene large
//! with the contact phase of every point written over it, one time plot of a
//! chosen point below, the mode contribution bars beside), slow motion, and
//! the guided preset's explanation shown prominently.

mod mode_bars;

pub use mode_bars::{
    MODE_BARS_PLOT_ID, MODE_BARS_Y_LABEL, mode_bar_color, mode_bars, mode_bars_min_px,
};

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
    if p.is_event() {
        format!("p{i}: {}", p.label().to_uppercase())
    } else {
        format!("p{i}: {}", p.label())
    }
}

/// The least gap (px) between a phase label in the plot and the force
/// value labels' floor.
const LABEL_GAP_PX: f64 = 2.0;

/// The scene view with each point's phase written above it.
///
/// One point: its phase, large, above it. Several points, below them in
/// the road and above them in the sky: only impacts and releases (the
/// points' colours and the strip above give the steady phases), in up to
/// three lanes of text height below the lowest point and the force value
/// labels and up to two above the highest point, so that no labels overlap.
///
/// On a patch (several rows across the tread) the side view draws the row
/// of `point` (the point of the plot and the bars) in full, with its
/// labels, and the other rows faded behind it.
pub fn scene_with_phases(
    ui: &mut Ui,
    sim: &Simulation,
    road: &crate::model::road::Road,
    opts: &mut scene_view::SceneViewOptions,
    phases: &PhaseTracker,
    point: usize,
) {
    let t = sim.time_s();
    let heading = ui.text_style_height(&TextStyle::Heading);
    let body = ui.text_style_height(&TextStyle::Body);
    let normal_legend = std::mem::replace(&mut opts.legend_style, TextStyle::Small);
    // the legend in a row above the plot: in a corner it covered the tyre
    let normal_above = std::mem::replace(&mut opts.legend_above, true);
    let normal_row = opts.row_of_point.replace(point);
    let frame = scene_view::show_with(ui, sim, road, opts, |pui, displaced, labels_floor| {
        let at = PhasesAt { phases, t_s: t };
        if displaced.len() > 1 {
            let lanes = Lanes::of(pui, sim, displaced, labels_floor, body);
            event_labels(pui, &lanes, displaced, at, body);
        } else {
            point_label(pui, displaced, at, heading);
        }
    });
    opts.legend_style = normal_legend;
    opts.legend_above = normal_above;
    opts.row_of_point = normal_row;
    top_view(ui, sim, frame, point);
}

/// Caption of the top view of a patch in the classroom's scene.
pub fn top_view_caption(rows: usize) -> String {
    format!("top view: {rows} rows")
}

/// Radius (px) of the points of the top view at most.
pub const TOP_VIEW_DOT_PX: f32 = 4.5;

/// On a patch, a top view of its points in the lower left corner of the
/// scene plot `frame` (below the road line, left of the points): x along
/// (as the side view), one line per row across the tread, each point a dot
/// coloured by its contact state, the row the side view draws in full
/// underlined and its dots ringed.
fn top_view(ui: &Ui, sim: &Simulation, frame: egui::Rect, point: usize) {
    let scene = sim.problem();
    let rows = scene_view::rows_y_m(&scene.points);
    if rows.len() < 2 {
        return;
    }
    let text_px = CLASSROOM_MIN_TEXT_PX;
    let caption = top_view_caption(rows.len());
    let text_color = ui.visuals().strong_text_color();
    let galley = ui
        .painter()
        .layout_no_wrap(caption, FontId::proportional(text_px), text_color);
    let pad = 6.0;
    let row_px = 10.0;
    let w = (0.28 * frame.width()).clamp(galley.size().x + 2.0 * pad, 260.0);
    let h = galley.size().y + pad * 3.0 + row_px * (rows.len() - 1) as f32;
    if w > frame.width() - 8.0 || h > frame.height() - 8.0 {
        return;
    }
    let rect = egui::Rect::from_min_size(
        egui::pos2(frame.left() + 4.0, frame.bottom() - 4.0 - h),
        egui::vec2(w, h),
    );
    let painter = ui.painter_at(frame);
    painter.rect(
        rect,
        4.0,
        ui.visuals().extreme_bg_color.gamma_multiply(0.92),
        egui::Stroke::new(1.0, Color32::GRAY),
        egui::StrokeKind::Inside,
    );
    painter.galley(
        rect.min + egui::vec2(pad, pad * 0.5),
        galley.clone(),
        text_color,
    );
    let (xmin, xmax) = scene
        .points
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            (a.min(p.x_m), b.max(p.x_m))
        });
    let grid = egui::Rect::from_min_max(
        egui::pos2(
            rect.left() + 2.0 * pad,
            rect.top() + galley.size().y + 1.5 * pad,
        ),
        egui::pos2(rect.right() - 2.0 * pad, rect.bottom() - 1.5 * pad),
    );
    let span = (xmax - xmin).max(1e-12);
    let at = |x_m: f64, row: usize| {
        egui::pos2(
            grid.left() + grid.width() * ((x_m - xmin) / span) as f32,
            // y across the tread upwards, as seen from above with the road
            // moving left
            grid.bottom() - row_px * row as f32,
        )
    };
    let along = scene.points.len().div_ceil(rows.len()).max(1);
    let dot = (0.4 * grid.width() / along as f32)
        .min(0.4 * row_px)
        .min(TOP_VIEW_DOT_PX);
    let row_of = |y: f64| rows.partition_point(|r| *r < y);
    let focus = scene
        .points
        .get(point.min(scene.points.len().saturating_sub(1)))
        .map(|p| row_of(p.y_m));
    if let Some(r) = focus {
        let y = at(xmin, r).y;
        painter.line_segment(
            [
                egui::pos2(grid.left() - pad, y),
                egui::pos2(grid.right() + pad, y),
            ],
            egui::Stroke::new(1.5, text_color),
        );
    }
    for (p, on_road) in scene.points.iter().zip(sim.in_contact()) {
        let r = row_of(p.y_m);
        let c = at(p.x_m, r);
        let color = if *on_road {
            CONTACT_COLOR
        } else {
            FLIGHT_COLOR
        };
        painter.circle_filled(c, dot, color);
        if Some(r) == focus {
            painter.circle_stroke(c, dot + 1.5, egui::Stroke::new(1.0, text_color));
        }
    }
}

/// The phases of the points at one time.
#[derive(Clone, Copy)]
struct PhasesAt<'a> {
    phases: &'a PhaseTracker,
    t_s: f64,
}

impl PhasesAt<'_> {
    fn of(&self, i: usize) -> ContactPhase {
        self.phases.phase(i, self.t_s)
    }
}

/// A phase label: the point and its phase, in the phase's colour.
fn phase_label(i: usize, ph: ContactPhase, size: f32) -> RichText {
    RichText::new(phase_text(i, ph))
        .size(size)
        .strong()
        .color(phase_color(ph))
}

/// Size (px) of `text` in the body font of size `body`.
fn measure(pui: &egui_plot::PlotUi<'_>, text: &str, body: f32) -> egui::Vec2 {
    pui.ctx().fonts_mut(|f| {
        f.layout_no_wrap(text.to_owned(), FontId::proportional(body), Color32::WHITE)
            .size()
    })
}

/// Lanes for the event labels of several points: as high as a label,
/// below the points and the force value labels, as many (up to three) as
/// fit above the plot's bottom, then up to two in the sky above them. Each
/// event label goes to the first lane where it clears the labels left of it
/// (sorted by x); one that fits no lane is left to the strip above the plot.
struct Lanes {
    /// y of a label's top (or bottom, in the sky) and its anchor.
    lanes: Vec<(f64, egui::Align2)>,
    /// Whether a lane reaches into the force value labels.
    near_forces: Vec<bool>,
    /// Extents (px) of the force value labels.
    force_spans: Vec<(f32, f32)>,
}

impl Lanes {
    fn of(
        pui: &egui_plot::PlotUi<'_>,
        sim: &Simulation,
        displaced: &[[f64; 2]],
        labels_floor: Option<f64>,
        body: f32,
    ) -> Self {
        let b = pui.plot_bounds();
        let per_px = pui.transform().dvalue_dpos()[1].abs();
        let points_lowest = displaced.iter().map(|d| d[1]).fold(f64::INFINITY, f64::min);
        let lane_px = f64::from(measure(pui, "p0: IMPACT", body).y) + 2.0;
        let top = labels_floor.map_or(points_lowest, |f| f.min(points_lowest));
        let room = (top - b.min()[1]) / (per_px * lane_px) - 0.3;
        let below = (room.floor() as usize).clamp(1, 3);
        // one lane even when none fits: moved up as far as needed
        let top = top.max(b.min()[1] + per_px * lane_px * 1.3);
        // lanes: (y of the label's top, anchor); below the points first,
        // then in the sky above them (a short plot at 1280 x 720 had
        // room for one lane below, and four of five events at the end
        // of the paper preset's run were shown only in the strip)
        let mut lanes: Vec<(f64, egui::Align2)> = (0..below)
            .map(|k| {
                (
                    top - per_px * lane_px * (0.3 + k as f64),
                    egui::Align2::CENTER_TOP,
                )
            })
            .collect();
        // a lane moved up into the force value labels (the boxes' ink
        // came within 0.6 px, and overlapped by 3.5 px early in the paper
        // preset's run at 1280 x 720) first goes down to just under the
        // labels' text, if the plot has room for it there: the two texts'
        // line boxes then meet, their ink the lines' leading apart (7 px
        // under "592 N"). The value labels' floor is a line height and
        // 4 px under their tops, a little more than their text. A lane
        // still in them takes only labels LABEL_GAP_PX clear of them
        // sideways; the value labels are centred under every point with
        // a force (the force view labels those that fit; all are kept
        // clear of).
        let force_px = pui
            .ctx()
            .global_style()
            .text_styles
            .get(&TextStyle::Body)
            .map_or(14.0, |f| f.size);
        let force_text_h = pui.ctx().fonts_mut(|f| {
            f.layout_no_wrap(
                "0 N".to_owned(),
                FontId::proportional(force_px),
                Color32::WHITE,
            )
            .size()
            .y
        });
        let text_floor = labels_floor.map(|f| {
            f + per_px * f64::from(force_labels::LINE_HEIGHT * force_px + 4.0 - force_text_h)
        });
        let label_h = per_px * (lane_px - 2.0);
        if let Some(tf) = text_floor {
            for lane in &mut lanes {
                if tf < lane.0 && tf - label_h >= b.min()[1] {
                    lane.0 = tf;
                }
            }
        }
        let near_forces: Vec<bool> = lanes
            .iter()
            .map(|(y, _)| text_floor.is_some_and(|f| *y > f))
            .collect();
        let force_spans: Vec<(f32, f32)> = sim
            .force_n()
            .iter()
            .zip(displaced)
            .filter(|(q, d)| **q > 0.0 && d[0].is_finite())
            .map(|(q, d)| {
                let x = pui.transform().position_from_point_x(d[0]);
                let w = measure(pui, &force_text(*q), body).x;
                (x - 0.5 * w, x + 0.5 * w)
            })
            .collect();
        let points_highest = displaced
            .iter()
            .map(|d| d[1])
            .fold(f64::NEG_INFINITY, f64::max);
        // clear of the markers (7 px radius)
        let sky = points_highest + per_px * 12.0;
        let sky_room = (b.max()[1] - sky) / (per_px * lane_px) - 0.1;
        for k in 0..(sky_room.max(0.0).floor() as usize).min(2) {
            lanes.push((
                sky + per_px * lane_px * k as f64,
                egui::Align2::CENTER_BOTTOM,
            ));
        }
        Lanes {
            lanes,
            near_forces,
            force_spans,
        }
    }
}

/// The impact and release labels of several points, each in the first
/// lane where it fits; every point with an event ringed.
fn event_labels(
    pui: &mut egui_plot::PlotUi<'_>,
    lanes: &Lanes,
    displaced: &[[f64; 2]],
    at: PhasesAt<'_>,
    body: f32,
) {
    let Lanes {
        lanes,
        near_forces,
        force_spans,
    } = lanes;
    let mut events: Vec<(usize, f32, f32)> = displaced
        .iter()
        .enumerate()
        // the faded rows of a patch (NaN) take no label
        .filter(|(i, d)| d[0].is_finite() && at.of(*i).is_event())
        .map(|(i, d)| {
            let x = pui.transform().position_from_point_x(d[0]);
            let w = measure(pui, &phase_text(i, at.of(i)), body).x;
            (i, x - 0.5 * w, x + 0.5 * w)
        })
        .collect();
    // impacts take the lanes first (the headline event), then
    // releases, each kind from left to right
    events.sort_by(|a, b| {
        let release = |i: usize| at.of(i) != ContactPhase::Impact;
        release(a.0).cmp(&release(b.0)).then(a.1.total_cmp(&b.1))
    });
    // every point with an event ringed in the labels' colour: the
    // points of a five-point tyre lie closer than a label is wide,
    // and labels that fit no lane are left to the strip above
    let ringed: Vec<[f64; 2]> = events.iter().map(|e| displaced[e.0]).collect();
    if !ringed.is_empty() {
        pui.points(
            egui_plot::Points::new(EVENT_RING_NAME, ringed)
                .color(EVENT_COLOR)
                .shape(egui_plot::MarkerShape::Circle)
                .filled(false)
                .radius(EVENT_RING_PX),
        );
    }
    // the labels' extents (px) in each lane, a text height apart at
    // least: 6 px apart, "p0: RELEASE p3: IMPACT" read as one label
    let gap = body;
    let mut taken: Vec<Vec<(f32, f32)>> = vec![Vec::new(); lanes.len()];
    let gap_px = LABEL_GAP_PX as f32;
    for (i, left, r) in events {
        let free = |k: &usize| {
            taken[*k]
                .iter()
                .all(|&(l0, r0)| r0 + gap <= left || r + gap <= l0)
                && (!near_forces.get(*k).copied().unwrap_or(false)
                    || force_spans
                        .iter()
                        .all(|&(l0, r0)| r0 + gap_px <= left || r + gap_px <= l0))
        };
        let Some(lane) = (0..lanes.len()).find(free) else {
            continue;
        };
        taken[lane].push((left, r));
        let (y, anchor) = lanes[lane];
        let d = displaced[i];
        pui.text(
            Text::new("", PlotPoint::new(d[0], y), phase_label(i, at.of(i), body)).anchor(anchor),
        );
    }
}

/// One point: its phase above it, in the sky the legend (now above the
/// plot) left free; the force arrow and its value are below it.
fn point_label(
    pui: &mut egui_plot::PlotUi<'_>,
    displaced: &[[f64; 2]],
    at: PhasesAt<'_>,
    heading: f32,
) {
    let per_px = pui.transform().dvalue_dpos()[1].abs();
    for (i, d) in displaced.iter().enumerate() {
        let ph = at.of(i);
        let size = if ph.is_event() {
            heading * 1.25
        } else {
            heading
        };
        let y = d[1] + per_px * 10.0;
        pui.text(
            Text::new("", PlotPoint::new(d[0], y), phase_label(i, ph, size))
                .anchor(egui::Align2::CENTER_BOTTOM),
        );
    }
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
    let all = [
        ContactPhase::Impact,
        ContactPhase::Release,
        ContactPhase::InContact,
        ContactPhase::FreeFlight,
    ];
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
    if p.is_event() {
        format!("{count} {}", p.label().to_uppercase())
    } else {
        format!("{count} {}", p.label())
    }
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
