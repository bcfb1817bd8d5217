//! The classroom's scene: each point's contact phase written over the
//! side view in lanes that never overlap, the impacts and releases held on
//! screen, and the top view of a patch.

use super::*;

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
    // heights rounded up: the short, wide plot left a 1 mm road flat (not
    // on a patch, whose road window is zoomed to the patch)
    let normal_round = std::mem::replace(
        &mut opts.round_up,
        scene_view::rows_y_m(&sim.problem().points).len() < 2,
    );
    // a patch's top view in a column right of the plot: over the plot it
    // covered the phase labels and the road's left end
    let rows = scene_view::rows_y_m(&sim.problem().points).len();
    let whole = ui.available_rect_before_wrap();
    let side_px = if rows > 1 {
        (TOP_VIEW_WIDTH_FRACTION * whole.width()).clamp(TOP_VIEW_MIN_PX, TOP_VIEW_MAX_PX)
    } else {
        0.0
    };
    let plot_rect = egui::Rect::from_min_max(
        whole.min,
        egui::pos2(whole.right() - side_px, whole.bottom()),
    );
    let mut plot_ui = ui.new_child(
        egui::UiBuilder::new()
            .max_rect(plot_rect)
            .layout(egui::Layout::top_down(egui::Align::Min)),
    );
    let frame = scene_view::show_with(
        &mut plot_ui,
        sim,
        road,
        opts,
        |pui, displaced, labels_floor| {
            let at = PhasesAt { phases, t_s: t };
            if displaced.len() > 1 {
                let lanes = Lanes::of(pui, sim, displaced, labels_floor, body);
                event_labels(pui, &lanes, displaced, at, body);
            } else {
                point_label(pui, displaced, at, heading);
            }
        },
    );
    opts.legend_style = normal_legend;
    opts.legend_above = normal_above;
    opts.row_of_point = normal_row;
    opts.round_up = normal_round;
    ui.advance_cursor_after_rect(plot_ui.min_rect().union(plot_rect));
    if side_px > 0.0 {
        let column = egui::Rect::from_min_max(
            egui::pos2(plot_rect.right() + TOP_VIEW_GAP_PX, frame.top()),
            egui::pos2(whole.right(), whole.bottom()),
        );
        top_view(ui, sim, column, point);
    }
}

/// The top view's column beside the side view: this fraction of the
/// scene's width, within [`TOP_VIEW_MIN_PX`] and [`TOP_VIEW_MAX_PX`].
const TOP_VIEW_WIDTH_FRACTION: f32 = 0.2;
const TOP_VIEW_MIN_PX: f32 = 165.0;
const TOP_VIEW_MAX_PX: f32 = 260.0;
/// Gap (px) between the side view's plot and the top view.
const TOP_VIEW_GAP_PX: f32 = 8.0;

/// Caption of the top view of a patch in the classroom's scene.
pub fn top_view_caption(rows: usize) -> String {
    format!("top view: {rows} rows")
}

/// Radius (px) of the points of the top view at most.
pub const TOP_VIEW_DOT_PX: f32 = 4.5;

/// On a patch, a top view of its points at the top of `column` (right of
/// the side view's plot, level with its top): x along (as the side view),
/// one line per row across the tread, each point a dot coloured by its
/// contact state, the row the side view draws in full underlined and its
/// dots ringed.
fn top_view(ui: &Ui, sim: &Simulation, column: egui::Rect, point: usize) {
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
    let w = column.width();
    let h = galley.size().y + pad * 3.0 + row_px * (rows.len() - 1) as f32;
    if galley.size().x + 2.0 * pad > w || h > column.height() {
        return;
    }
    let rect = egui::Rect::from_min_size(column.min, egui::vec2(w, h));
    let painter = ui.painter_at(rect.expand(1.0));
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
