//! Time plots per contact point: displacement, force, gap and contact state,
//! with linked time axes, legends, units, follow-latest window and min/max
//! decimation (drawing cost scales with the plot width, not the run length).

use super::legend_place::{self, SHORT_PLOT_PX, legend_text};
use crate::gui::model::history::{History, Quantity};
/// The clip level of impact spikes, shared with the exported and
/// command-line figures.
pub use crate::output::impacts::clip_level;
use egui::{Id, Ui};
use egui_plot::{AxisHints, Line, MarkerShape, Plot, PlotUi, Points};

/// Id of the contact force plot (its `PlotMemory` holds the drawn bounds).
pub const FORCE_PLOT_ID: &str = "tirecontact.time_plots.force";

/// Spacing (px) from which the time axes' labels fade in, and at which
/// they are opaque (a label that does not fit is still left out).
pub const TIME_LABEL_SPACING: std::ops::RangeInclusive<f32> = 36.0..=44.0;

/// Id of the displacement plot.
pub const DISPLACEMENT_PLOT_ID: &str = "tirecontact.time_plots.displacement";

/// Id of the gap plot.
pub const GAP_PLOT_ID: &str = "tirecontact.time_plots.gap";

/// Id of the contact state plot.
pub const CONTACT_PLOT_ID: &str = "tirecontact.time_plots.contact";

/// Points shown by default: the first 16 (every point of a 5 × 3 patch;
/// beyond 8 their colours go along a ramp, as in the PNG).
pub const DEFAULT_SHOWN: usize = 16;

/// Presentation options of the time plots.
#[derive(Debug, Clone, PartialEq)]
pub struct TimePlotOptions {
    /// Keep the latest `window_s` seconds in view.
    pub follow: bool,
    pub window_s: f64,
    /// Which points are drawn.
    pub shown: Vec<bool>,
    /// Fit the force plot's range to the force without impact impulses (an
    /// impact's step-mean force impulse / dt would otherwise set the range);
    /// clipped impacts are marked at the top edge.
    pub clip_impacts: bool,
    /// Width (px) of the widest y axis of the stacked plots at the last
    /// frame: every plot's axis is made as wide, so that their time axes
    /// line up whatever their tick labels (`1 000 000` N beside `3` mm).
    pub axis_px: f32,
    /// The run's time at the last frame (a smaller one: a new run, whose
    /// axes start from the narrowest again).
    pub axis_t_s: f64,
}

impl Default for TimePlotOptions {
    fn default() -> Self {
        TimePlotOptions {
            follow: true,
            window_s: 0.1,
            shown: Vec::new(),
            clip_impacts: true,
            axis_px: 0.0,
            axis_t_s: 0.0,
        }
    }
}

impl TimePlotOptions {
    /// Adapts the point selection to `p` points.
    pub fn fit_points(&mut self, p: usize) {
        if self.shown.len() != p {
            self.shown = (0..p).map(|i| i < DEFAULT_SHOWN).collect();
        }
    }
}

struct PlotDef {
    what: Quantity,
    y_label: &'static str,
    /// The y label of a short plot (the long one is clipped).
    short_label: &'static str,
    scale: f64,
}

const PLOTS: [PlotDef; 4] = [
    PlotDef {
        what: Quantity::Displacement,
        y_label: "displacement u (mm, up)",
        short_label: "u (mm, up)",
        scale: 1e3,
    },
    PlotDef {
        what: Quantity::Force,
        y_label: "contact force q (N)",
        short_label: "q (N)",
        scale: 1.0,
    },
    PlotDef {
        what: Quantity::Gap,
        y_label: "gap u − r (mm)",
        short_label: "gap (mm)",
        scale: 1e3,
    },
    PlotDef {
        what: Quantity::Contact,
        y_label: "in contact (per point)",
        short_label: "contact",
        scale: 1.0,
    },
];

/// The time plots of `history` at run time `now_s` of a run `duration_s`
/// long: the followed window is at most the run (a run shorter than the
/// window fills the axis), and the time axis is labelled up to the
/// window's end only (the strip past it holds the legends).
pub fn show(
    ui: &mut Ui,
    history: &History,
    opts: &mut TimePlotOptions,
    now_s: f64,
    duration_s: f64,
) {
    opts.fit_points(history.num_points());
    header(ui, opts);
    // a phone: one legend for the four plots, in a row above them (the
    // same points in the same colours); their curves get the whole width
    let narrow = ui.ctx().content_rect().width() < crate::gui::widgets::NARROW_PX;
    let t_end = history.last_time().unwrap_or(0.0).max(now_s);
    let window_s = followed_window_s(opts.window_s, duration_s);
    let (t0, t1) = if opts.follow {
        ((t_end - window_s).max(0.0), t_end.max(window_s))
    } else {
        (0.0, t_end.max(1e-9))
    };
    let gap = ui.spacing().item_spacing.y;
    // (a phone's short screen: the four plots share what height there is,
    // so none hides behind the status bar; elsewhere at least 80 px each)
    let min_h = if narrow { 40.0 } else { 80.0 };
    let plot_h = |ui: &Ui| ((ui.available_height() - 3.0 * gap) / 4.0).max(min_h);
    // the frames are the width less the y axes (at least 64 px); a wider
    // axis narrows the strip by a few px (of its share of the frame): 8 px
    // to spare
    let frame_w_px = ui.available_width() - 64.0;
    // the curves fill the window's width, so every corner of it would cover
    // some: the time axis runs on past the window's end by a strip as wide
    // as the widest legend, where the legends go (top right); a strip that
    // would take more than `MAX_LEGEND_STRIP` of the frame (a patch's long
    // legend beside the mode bars) gives way to the shared row of a phone
    let widest_px = if narrow {
        0.0
    } else {
        widest_legend_px(ui, history, opts, plot_h(ui))
    };
    let shared = narrow || widest_px + 12.0 > MAX_LEGEND_STRIP * frame_w_px;
    if shared {
        shared_legend(ui, history, opts);
    }
    let h = plot_h(ui);
    let legend_w_px = if shared { 0.0 } else { widest_px };
    let t1_axis = t1 + legend_strip_s(t1 - t0, legend_w_px, frame_w_px);
    let link = Id::unique("tirecontact.time_axes");
    if t_end < opts.axis_t_s {
        opts.axis_px = 0.0;
    }
    opts.axis_t_s = t_end;
    let axis_px = opts.axis_px.max(64.0);
    let mut widest_axis_px = 0.0f32;
    for (k, def) in PLOTS.iter().enumerate() {
        let last = k == PLOTS.len() - 1;
        let y_label = if h < SHORT_PLOT_PX {
            def.short_label
        } else {
            def.y_label
        };
        // the legend goes to the corner its curves left emptiest on the last
        // frame (the strip past the window's end)
        let legend_id = Id::unique(("tirecontact.time_plots.legend", k));
        let names = legend_names(history, &opts.shown, def, opts.clip_impacts);
        let legend_px = egui::Vec2::new(
            legend_width_px(ui, &names, h),
            legend_place::legend_size(ui, &names.iter().map(String::as_str).collect::<Vec<_>>(), h)
                .y,
        );
        let plot = time_plot(
            ui,
            def,
            k,
            last,
            &Axes {
                h,
                link,
                t1,
                t1_axis,
                axis_px,
            },
            (!shared).then_some(legend_id),
            y_label,
            opts,
        );
        let shown = opts.shown.clone();
        let follow = opts.follow;
        let clip = opts.clip_impacts && def.what == Quantity::Force;
        let left_px = ui.available_rect_before_wrap().left();
        // egui_plot stacks a bottom corner's legend upwards: the entries go
        // in reversed there, so that every legend reads point 0 first (the
        // force plot's flipped as its legend moved between corners)
        let upwards = legend_place::upwards(ui.ctx(), legend_id);
        let shown_plot = plot.show(ui, move |pui| {
            let (a, b) = if follow {
                pui.set_plot_bounds_x(t0..=t1_axis);
                (t0, t1)
            } else if pui.auto_bounds().x {
                (t0, t1)
            } else {
                let bnd = pui.plot_bounds();
                (bnd.min()[0], bnd.max()[0])
            };
            let top = if clip {
                clip_top(pui, history, &shown, a, b)
            } else {
                None
            };
            let mut ink = if follow {
                legend_place::Ink::with_x_bounds(t0, t1_axis)
            } else {
                legend_place::Ink::default()
            };
            draw_series(pui, history, def, &shown, (a, b), top, upwards, &mut ink);
            ink.place(pui, legend_id, legend_px);
        });
        widest_axis_px = widest_axis_px.max(shown_plot.transform.frame().left() - left_px);
    }
    // a wider axis than the others: all as wide from the next frame on
    if widest_axis_px > opts.axis_px + 0.5 {
        opts.axis_px = widest_axis_px;
        ui.ctx().request_repaint();
    }
}

/// Largest share of a time plot's frame the legends' strip past the
/// window's end takes; a wider legend goes to one row above the four plots.
pub const MAX_LEGEND_STRIP: f32 = 0.4;

/// Width (px) of the widest of the four plots' legends at plot height
/// `plot_h_px`.
fn widest_legend_px(ui: &Ui, history: &History, opts: &TimePlotOptions, plot_h_px: f32) -> f32 {
    PLOTS
        .iter()
        .map(|def| {
            let names = legend_names(history, &opts.shown, def, opts.clip_impacts);
            legend_width_px(ui, &names, plot_h_px)
        })
        .fold(0.0, f32::max)
}

/// The legend of the four plots in one wrapped row (narrow windows): a
/// coloured line and the name of each shown point, as in the plots.
fn shared_legend(ui: &mut Ui, history: &History, opts: &TimePlotOptions) {
    let chosen: Vec<usize> = (0..history.num_points())
        .filter(|&i| opts.shown.get(i).copied().unwrap_or(false))
        .collect();
    ui.horizontal_wrapped(|ui| {
        for &i in &chosen {
            let name = crate::output::figures::point_legend_name(&chosen, i);
            // (many points: the first and the last are named, the colours
            // between them run along the ramp, as in the plots' legends)
            if name.is_empty() {
                continue;
            }
            let row_h = ui.text_style_height(&egui::TextStyle::Body);
            let (r, _) = ui.allocate_exact_size(egui::vec2(16.0, row_h), egui::Sense::hover());
            ui.painter().line_segment(
                [r.left_center(), r.right_center()],
                egui::Stroke::new(
                    CURVE_WIDTH_PX.max(2.0),
                    super::shown_point_color(&chosen, i),
                ),
            );
            ui.label(name);
        }
        if opts.clip_impacts {
            ui.label(egui::RichText::new("marks: impacts (clipped)").weak());
        }
    });
}

/// What the four time plots share: their height, the linked time axis
/// (ending past the window by the legends' strip) and the y axes' width.
struct Axes {
    h: f32,
    link: Id,
    /// The window's (or the run's) end: the last time labelled.
    t1: f64,
    t1_axis: f64,
    axis_px: f32,
}

/// The plot of `def` (the `k`-th, `last` with the time axis title): its
/// legend, linked time axis with 1-2-5 labels, y axis (lanes per point for
/// the contact plot) and id.
fn time_plot<'a>(
    ui: &Ui,
    def: &PlotDef,
    k: usize,
    last: bool,
    axes: &Axes,
    legend_id: Option<Id>,
    y_label: &'a str,
    opts: &TimePlotOptions,
) -> Plot<'a> {
    let mut plot = Plot::new(("tirecontact.time_plot", k)).height(axes.h);
    if let Some(legend_id) = legend_id {
        plot = plot
            .legend(legend_place::legend(ui.ctx(), legend_id, axes.h).follow_insertion_order(true));
    }
    plot = plot
        .link_axis(axes.link, [true, false])
        .link_cursor(axes.link, [true, false])
        .y_axis_label(y_label)
        .y_axis_min_width(axes.axis_px)
        .allow_scroll(false)
        .auto_bounds([!opts.follow, true]);
    // time labels shown down to 40 px apart (the default hides x labels
    // closer than 60 px: a narrow plot kept one label); 1-2-5 time steps
    // labelled from TIME_LABEL_SPACING's end on (powers of ten left a
    // narrow plot one label), every label with the decimals of the
    // labelled step (each mark's own mixed "0.09, 0.1, 0.11")
    let axis = super::LabelledAxis::new(
        f64::from(*TIME_LABEL_SPACING.end()),
        f64::from(*TIME_LABEL_SPACING.start()),
    );
    let marks = axis.clone();
    let mut x_axis = AxisHints::new_x()
        .label_spacing(TIME_LABEL_SPACING)
        .formatter(move |mark, range| axis.label(mark, range));
    if last {
        x_axis = x_axis
            .label("time t (s)")
            .min_thickness(super::titled_x_axis_px(ui));
    }
    // no time is labelled past the window's end (a 0.2 s run's axis read
    // on to 0.22 s in the legends' strip)
    let last_label_s = axes.t1 + 1e-9 * axes.t1.abs();
    plot = plot.custom_x_axes(vec![x_axis]).x_grid_spacer(move |g| {
        let mut marks = marks.marks(g);
        marks.retain(|m| m.value <= last_label_s);
        marks
    });
    plot = plot.id(Id::unique(match def.what {
        Quantity::Force => FORCE_PLOT_ID,
        Quantity::Contact => CONTACT_PLOT_ID,
        Quantity::Gap => GAP_PLOT_ID,
        _ => DISPLACEMENT_PLOT_ID,
    }));
    if !opts.follow {
        plot = plot.include_x(axes.t1_axis);
    }
    if def.what != Quantity::Contact {
        plot = super::nice_y_axis(plot);
    }
    if def.what == Quantity::Contact {
        // one lane per shown point, labelled with the point's index
        let lanes: Vec<usize> = (0..opts.shown.len())
            .filter(|&i| opts.shown.get(i).copied().unwrap_or(false))
            .collect();
        let n = lanes.len();
        // lane labels shown down to 12 px per lane (the default hides
        // y labels closer than 20 px: short plots lost them)
        let axis = AxisHints::new_y()
            .label(y_label)
            .min_thickness(axes.axis_px)
            .label_spacing(LANE_LABEL_SPACING)
            .formatter(move |m, _| {
                let k = m.value.round();
                if (m.value - k).abs() < 1e-9 && k >= 0.0 && (k as usize) < n {
                    format!("p{}", lanes[k as usize])
                } else {
                    String::new()
                }
            });
        plot = plot
            .custom_y_axes(vec![axis])
            .include_y(-0.2)
            .include_y(n.max(1) as f64 - 0.1);
    }
    plot
}

/// Width (px) of a time plot's legend of `names` (egui_plot's layout: per
/// entry a marker as wide as the text is high, a fifth of that, the text;
/// 8 px margins inside the legend's frame, 4 px outside).
fn legend_width_px(ui: &Ui, names: &[String], plot_h_px: f32) -> f32 {
    let style = legend_text(plot_h_px);
    let row_px = ui.text_style_height(&style);
    let text_px = names
        .iter()
        .map(|n| super::axis_title::text_length_px(ui, n, &style))
        .fold(0.0, f32::max);
    text_px + 1.2 * row_px + 2.0 * 8.0 + 2.0 * 4.0
}

/// The followed window (s): `window_s`, at most a run of `duration_s`
/// (a run of 2 ms followed in a 0.1 s window sat in its left 2 %).
pub fn followed_window_s(window_s: f64, duration_s: f64) -> f64 {
    if duration_s.is_finite() && duration_s > 0.0 {
        window_s.min(duration_s)
    } else {
        window_s
    }
}

/// Time (s) past the end of a window `span_s` long that leaves a strip
/// `legend_w_px` (plus 12 px) wide at the right of a plot frame `frame_w_px`
/// wide (at most three quarters of the frame).
pub fn legend_strip_s(span_s: f64, legend_w_px: f32, frame_w_px: f32) -> f64 {
    let strip_px = (legend_w_px + 12.0).min(0.75 * frame_w_px).max(0.0);
    let rest_px = (frame_w_px - strip_px).max(1.0);
    span_s * f64::from(strip_px) / f64::from(rest_px)
}

/// Stroke width (px) of the time plots' curves.
pub const CURVE_WIDTH_PX: f32 = 1.5;

/// Clear background (px) kept between the ink of neighbouring contact
/// lanes (one lane's raised stroke and the next one's floor).
pub const LANE_CLEAR_PX: f32 = 3.5;

/// Height (in lanes) a contact lane rises while its point is in contact:
/// 0.7 of a lane where lanes are tall, less where they are a few px apart
/// (at 0.7, lanes 10 px apart kept 1.8 px between their strokes, which
/// anti-aliasing closed), at least 0.2 (sixteen lanes at 1280 × 720 are
/// 6 px apart: a rise of 0.3 left 2.3 px clear). `lane_px`: px per lane.
pub fn lane_raise(lane_px: f32) -> f64 {
    let free = (lane_width_px(lane_px) + LANE_CLEAR_PX) / lane_px.max(1e-3);
    f64::from((1.0 - free).clamp(0.2, 0.7))
}

/// Stroke width (px) of a contact lane `lane_px` apart from the next: the
/// curves' width, 1 px where lanes are under 10 px apart (room for a
/// visible rise).
pub fn lane_width_px(lane_px: f32) -> f32 {
    if lane_px < 10.0 { 1.0 } else { CURVE_WIDTH_PX }
}

/// Spacing (px) from which the contact plot's lane labels fade in, and at
/// which they are opaque.
pub const LANE_LABEL_SPACING: std::ops::RangeInclusive<f32> = 12.0..=16.0;

/// Legend entry of the clipped impacts' marks.
pub const IMPACT_LABEL: &str = "impact (impulse / dt, clipped)";

/// The entries of a time plot's legend: one per shown point, and the
/// clipped impacts' marks in a clipped force plot (for its size).
fn legend_names(history: &History, shown: &[bool], def: &PlotDef, clip: bool) -> Vec<String> {
    let chosen: Vec<usize> = (0..history.num_points())
        .filter(|&i| shown.get(i).copied().unwrap_or(false))
        .collect();
    let mut names: Vec<String> = chosen
        .iter()
        .map(|&i| crate::output::figures::point_legend_name(&chosen, i))
        .filter(|n| !n.is_empty())
        .collect();
    if clip && def.what == Quantity::Force {
        names.push(IMPACT_LABEL.to_owned());
    }
    names
}

/// Min/max buckets of a plot: one per two pixels of width, so each line
/// has about one vertex per pixel (its min and max per bucket): the peaks
/// survive and the renderer draws half the vertices of one bucket per pixel.
fn buckets_for(pui: &PlotUi<'_>) -> usize {
    ((pui.response().rect.width() / 2.0) as usize).clamp(100, 2000)
}

#[allow(clippy::too_many_arguments)]
fn draw_series(
    pui: &mut PlotUi<'_>,
    h: &History,
    def: &PlotDef,
    shown: &[bool],
    (a, b): (f64, f64),
    clip_top: Option<f64>,
    upwards: bool,
    ink: &mut legend_place::Ink,
) {
    let mut marks = Vec::new();
    let mut lines = Vec::new();
    let buckets = buckets_for(pui);
    let chosen: Vec<usize> = shown
        .iter()
        .enumerate()
        .filter(|(_, s)| **s)
        .map(|(i, _)| i)
        .collect();
    let lane_px = pui.transform().dpos_dvalue_y().abs() as f32;
    for (lane, &i) in chosen.iter().enumerate() {
        let mut pts = h.decimated(def.what, i, a, b, buckets, def.scale);
        let mut width = CURVE_WIDTH_PX;
        if def.what == Quantity::Contact {
            // lane of the point, raised while in contact
            let raise = lane_raise(lane_px);
            for p in &mut pts {
                p[1] = lane as f64 + raise * p[1];
            }
            width = lane_width_px(lane_px);
        }
        if let Some(top) = clip_top {
            clip_at(&mut pts, top, &mut marks);
        }
        ink.add(pui, &pts);
        lines.push(
            Line::new(crate::output::figures::point_legend_name(&chosen, i), pts)
                .color(super::shown_point_color(&chosen, i))
                .width(width)
                .allow_band(false),
        );
    }
    if upwards {
        impact_marks(pui, marks, MarkerShape::Down);
        for l in lines.into_iter().rev() {
            pui.line(l);
        }
    } else {
        for l in lines {
            pui.line(l);
        }
        impact_marks(pui, marks, MarkerShape::Down);
    }
}

/// Lowers the points of `pts` above `top` to `top`, collecting them in
/// `marks` (the impacts a clipped force plot marks ▼).
pub fn clip_at(pts: &mut [[f64; 2]], top: f64, marks: &mut Vec<[f64; 2]>) {
    for p in pts {
        if p[1] > top {
            p[1] = top;
            marks.push(*p);
        }
    }
}

/// Colour of the marks of clipped impacts: a mid grey, seen on the dark
/// theme's and the light (classroom) theme's plot background alike (light
/// grey vanished on white).
pub const IMPACT_MARK_COLOR: egui::Color32 = egui::Color32::from_gray(140);

/// Draws the marks of clipped impacts, `shape` ▼ (`Down`) at a top edge
/// (nothing when there are none).
pub fn impact_marks(pui: &mut PlotUi<'_>, marks: Vec<[f64; 2]>, shape: MarkerShape) {
    if !marks.is_empty() {
        pui.points(
            Points::new(IMPACT_LABEL, marks)
                .shape(shape)
                .filled(true)
                .radius(4.0)
                .color(IMPACT_MARK_COLOR),
        );
    }
}

/// The level at which the force plot clips impact spikes: a margin above
/// the force without impacts of the shown points over `[a, b]` (N).
fn clip_top(pui: &PlotUi<'_>, h: &History, shown: &[bool], a: f64, b: f64) -> Option<f64> {
    let buckets = buckets_for(pui);
    let points: Vec<usize> = (0..h.num_points())
        .filter(|&i| shown.get(i).copied().unwrap_or(false))
        .collect();
    force_range(h, &points, a, b, buckets).map(clip_level)
}

/// Lowest and highest force without impacts of `points` over `[a, b]` (N).
pub fn force_range(
    h: &History,
    points: &[usize],
    a: f64,
    b: f64,
    buckets: usize,
) -> Option<(f64, f64)> {
    y_range(
        points
            .iter()
            .flat_map(|&i| h.decimated(Quantity::ForceWithoutImpacts, i, a, b, buckets, 1.0))
            .map(|p| p[1]),
    )
}

/// Lowest and highest of `ys` (`None` when empty).
pub fn y_range(ys: impl IntoIterator<Item = f64>) -> Option<(f64, f64)> {
    ys.into_iter().fold(None, |acc, y| match acc {
        None => Some((y, y)),
        Some((lo, hi)) => Some((f64::min(lo, y), f64::max(hi, y))),
    })
}

fn header(ui: &mut Ui, opts: &mut TimePlotOptions) {
    ui.horizontal_wrapped(|ui| {
        ui.checkbox(&mut opts.follow, "follow latest")
            .on_hover_text("keep the latest time window in view; off: zoom and pan freely (double-click resets)");
        ui.add_enabled(
            opts.follow,
            egui::DragValue::new(&mut opts.window_s)
                .range(1e-4..=1e4)
                .speed(0.01)
                .suffix(" s"),
        )
        .on_hover_text("width of the followed time window");
        ui.separator();
        ui.label("points:");
        let n = opts.shown.len();
        // more than eight shown: their labels in the lines' ramp colours
        let chosen: Vec<usize> = (0..n).filter(|&i| opts.shown[i]).collect();
        // 24 boxes, from the first shown point's group of eight (a patch's
        // row 3 clicked: points 48 to 71, not 0 to 23 all unticked)
        let start = checkbox_start(&chosen, n);
        let end = (start + HEADER_POINTS).min(n);
        // (each note whole on one row: it wrapped at a row's end)
        let note = |ui: &mut Ui, text: String| {
            ui.add(egui::Label::new(text).wrap_mode(egui::TextWrapMode::Extend));
        };
        if start > 0 {
            note(ui, format!("(0–{} …)", start - 1));
        }
        for (i, s) in opts.shown.iter_mut().enumerate().take(end).skip(start) {
            let color = super::checkbox_point_color(ui.visuals(), &chosen, i);
            ui.checkbox(s, egui::RichText::new(i.to_string()).color(color));
        }
        if n > end {
            note(ui, format!("(+{} more)", n - end));
        }
        if ui.small_button("all").clicked() {
            opts.shown.iter_mut().for_each(|s| *s = true);
        }
        if ui.small_button("none").clicked() {
            opts.shown.iter_mut().for_each(|s| *s = false);
        }
        ui.separator();
        clip_checkbox(ui, &mut opts.clip_impacts);
    });
}

/// Points with a box of their own above the time plots.
const HEADER_POINTS: usize = 24;

/// The first point of the header's boxes: 0, or the group of eight of the
/// first shown point where that is past the first `HEADER_POINTS`.
pub fn checkbox_start(chosen: &[usize], n: usize) -> usize {
    match chosen.first() {
        Some(&f) if f >= HEADER_POINTS && n > HEADER_POINTS => (f - f % 8).min(n - HEADER_POINTS),
        _ => 0,
    }
}

/// The "clip impact spikes" switch of a force plot.
pub fn clip_checkbox(ui: &mut Ui, clip_impacts: &mut bool) {
    ui.checkbox(clip_impacts, "clip impact spikes")
        .on_hover_text(
            "Rigid contact makes an impact an impulse: its step is drawn as impulse / dt, \
         far above the contact force. On: the force axis fits the force without \
         impacts and clipped impacts are marked ▼ at the top. Off: the full range. \
         With the paper contact scheme (no located impacts) a landing step is the \
         impact: in a step where a point's force turns positive, each point's rise \
         over its previous step's force counts as impulse / dt.",
        );
}

#[cfg(test)]
mod tests {
    use super::legend_strip_s;

    #[test]
    fn the_header_boxes_start_at_the_first_shown_points_group() {
        use super::checkbox_start;
        assert_eq!(checkbox_start(&[0, 1, 2], 96), 0);
        assert_eq!(checkbox_start(&[20, 21], 96), 0);
        let row: Vec<usize> = (48..64).collect();
        assert_eq!(checkbox_start(&row, 96), 48);
        assert_eq!(checkbox_start(&[90], 96), 72);
        assert_eq!(checkbox_start(&[], 96), 0);
    }

    #[test]
    fn the_legend_strip_takes_the_legend_width_of_the_frame() {
        // a 0.1 s window in a 1000 px frame, legend 188 px (+ 12): the
        // strip is 200 px, so the axis spans 0.1 s over 800 px plus 0.025 s
        let s = legend_strip_s(0.1, 188.0, 1000.0);
        assert!((s - 0.025).abs() < 1e-12, "{s}");
        let px = 1000.0 * s / (0.1 + s);
        assert!((px - 200.0).abs() < 1e-9, "{px}");
        // a legend wider than the frame: at most three quarters of it
        let s = legend_strip_s(0.1, 5000.0, 400.0);
        assert!((400.0 * s / (0.1 + s) - 300.0).abs() < 1e-9);
    }
}
