//! The scene: the road profile moving under the contact line, the undeformed
//! and displaced contact points coloured by contact state, and the contact
//! forces as arrows. Heights are exaggerated (factor shown); the height axis
//! is labelled in true millimetres.

use super::XTitle;
use super::{CONTACT_COLOR, FLIGHT_COLOR};
use crate::Simulation;
use crate::model::road::{Road, ramp};
use egui::{Color32, RichText, Ui};
use egui_plot::{Arrows, Corner, GridMark, Legend, Line, LineStyle, MarkerShape, Plot, Points};

/// Presentation options of the scene view.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneViewOptions {
    /// Choose the exaggeration from the scene's heights.
    pub auto: bool,
    /// Vertical exaggeration (heights drawn this many times larger).
    pub exaggeration: f64,
    /// Text style of the legend (classroom mode: small, so that the legend
    /// leaves the points visible).
    pub legend_style: egui::TextStyle,
    /// The legend as a row above the plot instead of in a corner of it
    /// (classroom mode: a short plot's corner legend covered the tyre).
    pub legend_above: bool,
    /// On a patch (points in several rows across the tread, `y_m`): the
    /// row of this point drawn in full, the other rows faded and small
    /// behind it (the rows share `x`: drawn in full they lie over each
    /// other, and one line through all of them joins the end of a row to
    /// the start of the next). `None`: point 0's row.
    pub row_of_point: Option<usize>,
    /// The automatic exaggeration rounded up to the next 1-2-5 value
    /// instead of down (classroom mode: its short, wide plot rounded a
    /// factor of 3.3 down to ×2 and the paper preset's 1 mm road looked
    /// flat; rounded up, the heights fill the plot's height and the road
    /// window widens a little).
    pub round_up: bool,
}

impl Default for SceneViewOptions {
    fn default() -> Self {
        SceneViewOptions {
            auto: true,
            exaggeration: 20.0,
            legend_style: egui::TextStyle::Body,
            legend_above: false,
            row_of_point: None,
            round_up: false,
        }
    }
}

/// The y extent of the scene plot in heights `hmax`: the plot spans
/// `±HEIGHTS_SPAN / 2 · e · hmax` (room for the force arrows and labels).
const HEIGHTS_SPAN: f64 = 5.0;

/// The automatic exaggeration of the plot about to be drawn in `ui`
/// ([`auto_exaggeration_for`] of the frame the plot will have).
fn auto_exaggeration(ui: &Ui, width_in_heights: f64, round_up: bool) -> (f64, f64) {
    let avail = ui.available_size();
    let row = ui.text_style_height(&egui::TextStyle::Body) + ui.spacing().item_spacing.y;
    // the header, and the legend row (classroom) or the ramp's line
    let above = 2.0 * row;
    let frame_h = (avail.y - above - super::titled_x_axis_px(ui)).max(60.0);
    let frame_w = (avail.x - 44.0 - row).max(100.0);
    auto_exaggeration_for([frame_w, frame_h], width_in_heights, round_up)
}

/// The automatic exaggeration `e` of a scene plot whose frame is
/// `frame_px` (width, height) and whose drawn road is `width_in_heights =
/// (x1 − x0) / hmax` long, with `fit`, the factor at which the heights
/// (`HEIGHTS_SPAN · hmax`, exaggerated) fill the frame's height when its
/// width shows the drawn road at aspect 1; returns `(e, fit)`.
///
/// The normal view takes the largest 1-2-5 value not above `fit`, so that
/// the road spans the plot's width (a fixed factor left a short classroom
/// plot a road in the middle third); the axis then spans `HEIGHTS_SPAN ·
/// hmax · fit / e` true metres. `round_up` (classroom) takes the smallest
/// 1-2-5 value not below `fit` and widens the road window by `e / fit`:
/// the axis spans `HEIGHTS_SPAN · hmax` true metres whatever the plot's
/// shape, so the largest height (the road's or the tyre's) takes a fifth
/// of the plot's height. (Rounded down, the classroom's short, wide plot
/// took ×2 for a fit of 4.9 on the paper preset, a −20…15 mm axis on which
/// its 1 mm road looked flat.)
pub fn auto_exaggeration_for(
    frame_px: [f32; 2],
    width_in_heights: f64,
    round_up: bool,
) -> (f64, f64) {
    let fit = f64::from(frame_px[1] / frame_px[0]) * width_in_heights / HEIGHTS_SPAN;
    let e = if round_up {
        ceil_125(fit)
    } else {
        floor_125(fit)
    };
    (e, fit)
}

/// The smallest 1, 2 or 5 times a power of ten not below `x` (1 for `x`
/// at most 1 or not finite).
pub fn ceil_125(x: f64) -> f64 {
    let f = floor_125(x);
    if !(x.is_finite() && x > 1.0) || f >= x {
        return f;
    }
    // the next value of the 1-2-5 sequence above f
    let e = 10f64.powf(f.log10().floor());
    match (f / e).round() as u32 {
        1 => 2.0 * e,
        2 => 5.0 * e,
        _ => 10.0 * e,
    }
}

/// The largest 1, 2 or 5 times a power of ten not above `x` (1 for `x`
/// below 1 or not finite).
pub fn floor_125(x: f64) -> f64 {
    if !(x.is_finite() && x >= 1.0) {
        return 1.0;
    }
    let e = 10f64.powf(x.log10().floor());
    let m = x / e;
    let m = if m < 2.0 {
        1.0
    } else if m < 5.0 {
        2.0
    } else {
        5.0
    };
    m * e
}

/// Rounds to 1, 2 or 5 times a power of ten.
pub fn round_125(x: f64) -> f64 {
    if !(x.is_finite() && x > 0.0) {
        return 1.0;
    }
    let e = 10f64.powf(x.log10().floor());
    let m = x / e;
    let m = if m < 1.5 {
        1.0
    } else if m < 3.5 {
        2.0
    } else if m < 7.5 {
        5.0
    } else {
        10.0
    };
    m * e
}

/// Horizontal extent drawn (m): the contact line and about a wavelength
/// around it; on a patch (several rows across the tread) the patch's length
/// and [`PATCH_MARGIN`] of it on either side (a road texture's drawn
/// wavelength left a 0.16 m patch a tenth of a 0.7 m window).
fn x_extent(sim: &Simulation, road: &Road) -> (f64, f64) {
    let pts = &sim.problem().points;
    let lo = pts.iter().map(|p| p.x_m).fold(f64::INFINITY, f64::min);
    let hi = pts.iter().map(|p| p.x_m).fold(f64::NEG_INFINITY, f64::max);
    if rows_y_m(pts).len() > 1 && hi > lo {
        let margin = PATCH_MARGIN * (hi - lo);
        return (lo - margin, hi + margin);
    }
    let lambda = road.drawn_wavelength_m();
    let margin = (0.5 * (hi - lo)).max(0.6 * lambda.min(2.0)).max(0.05);
    (lo - margin, hi + margin)
}

/// The road drawn on either side of a patch, as a fraction of the patch's
/// length.
pub const PATCH_MARGIN: f64 = 0.2;

/// Marks of the height axis (plot units: exaggerated metres; `to_mm`
/// converts them to true mm) at a 1-2-5 step of true mm, about eight over
/// the plot's height as before, but never closer than `label_px` (a short
/// plot in large text: a label and a half). With `to_mm` = 1, the marks of
/// the position axis in m.
pub fn height_marks(g: egui_plot::GridInput, to_mm: f64, label_px: f64) -> Vec<GridMark> {
    let (a, b) = (g.bounds.0 * to_mm, g.bounds.1 * to_mm);
    // true mm per px (the grid input's step is 8 px of plot units)
    let mm_per_px = g.base_step_size * to_mm / 8.0;
    if !(a.is_finite() && b.is_finite() && b > a && mm_per_px.is_finite() && mm_per_px > 0.0) {
        return Vec::new();
    }
    // eight steps rounded to 1-2-5 (as before), or the least 1-2-5 step
    // a label and a half apart when that is coarser
    let step = round_125((b - a) / 8.0).max(super::nice_step(label_px * mm_per_px));
    let mut out = Vec::new();
    let mut k = (a / step).ceil();
    while k * step <= b && out.len() < 100 {
        out.push(GridMark {
            value: k * step / to_mm,
            step_size: step / to_mm,
        });
        k += 1.0;
    }
    out
}

/// Legend entry of the force arrows and their value labels.
pub const FORCE_NAME: &str = "contact force (length relative to the largest now; value in N)";
/// [`FORCE_NAME`] in the legend row above the classroom's plot (one row
/// at 1280 px).
pub const FORCE_NAME_SHORT: &str = "contact force (N)";
/// Colour of the force arrows and of their legend entry.
pub const FORCE_COLOR: Color32 = Color32::from_rgb(0, 114, 178);

/// Legend entries of the road, the undeformed tyre and the points in
/// contact and in flight, and the road's colour.
pub const ROAD_NAME: &str = "road (moving)";
/// [`ROAD_NAME`] in the classroom's legend row, which also says where the
/// road goes (its header has no room for it).
pub const ROAD_NAME_LEFT: &str = "road (moving left)";
pub const ROAD_COLOR: Color32 = Color32::from_rgb(140, 86, 75);
pub const UNDEFORMED_NAME: &str = "undeformed tyre";
/// Radius (px) of the undeformed tyre's hollow markers at the points.
const UNDEFORMED_MARKER_PX: f32 = 4.0;
pub const CONTACT_NAME: &str = "in contact";
pub const FLIGHT_NAME: &str = "in flight";

/// Id of the scene plot (its `PlotMemory` holds the frame).
pub const SCENE_PLOT_ID: &str = "tirecontact.scene_view";

/// Colour of the faded rows of a patch behind the row drawn in full.
pub const FADED_ROW_COLOR: Color32 = Color32::from_rgba_premultiplied(120, 120, 120, 120);
/// Radius (px) of the faded rows' markers (the row in full: 7 px).
pub const FADED_ROW_MARKER_PX: f32 = 3.5;
/// Plot item name of the faded rows (no legend entry: the header names them).
const FADED_ROW_NAME: &str = "";

/// The rows across the tread of `scene`'s points: their distinct `y_m`,
/// increasing.
pub fn rows_y_m(points: &[crate::scene::Point]) -> Vec<f64> {
    let mut rows: Vec<f64> = points.iter().map(|p| p.y_m).collect();
    rows.sort_by(f64::total_cmp);
    rows.dedup();
    rows
}

/// The row drawn in full under `opts` (its index among [`rows_y_m`], the
/// number of rows and its `y_m`), where the scene has more than one row.
fn focus_row(
    points: &[crate::scene::Point],
    opts: &SceneViewOptions,
) -> Option<(usize, usize, f64)> {
    let point = opts.row_of_point.unwrap_or(0);
    let rows = rows_y_m(points);
    let y = points.get(point.min(points.len().checked_sub(1)?))?.y_m;
    (rows.len() > 1).then(|| (rows.partition_point(|r| *r < y), rows.len(), y))
}

/// The header's text naming the row drawn in full: `row 2 of 6 across the
/// tread (y = -30 mm) · the other 5 faded`.
pub fn row_text(row: usize, rows: usize, y_m: f64) -> String {
    format!(
        "row {} of {rows} across the tread (y = {} mm) · the other {} faded",
        row + 1,
        crate::gui::widgets::number::format_number(y_m * 1e3),
        rows - 1
    )
}

/// Legend entry of the displaced tyre's line.
pub const DISPLACED_NAME: &str = "tyre (displaced)";

/// Colour of the displaced tyre's line in theme `v`: light grey on the dark
/// theme's plot background, dark grey on the light theme's (a fixed dark
/// grey, 60, was barely seen on the dark background).
pub fn displaced_tyre_color(v: &egui::Visuals) -> Color32 {
    if v.dark_mode {
        Color32::from_gray(220)
    } else {
        Color32::from_gray(60)
    }
}

/// The scene view of `sim` on `road` (the scene's description of the road
/// it runs on, which sets the window drawn).
pub fn show(ui: &mut Ui, sim: &Simulation, road: &Road, opts: &mut SceneViewOptions) {
    show_with(ui, sim, road, opts, |_, _, _| {});
}

/// [`show`], with `extra(plot, displaced, labels_floor)` drawing more items
/// (returns the plot's frame)
/// over the scene (`displaced[i]` = drawn position of point `i`,
/// exaggerated plot units; `labels_floor` = the lowest y the force value
/// labels reach, if any are drawn).
pub fn show_with(
    ui: &mut Ui,
    sim: &Simulation,
    road: &Road,
    opts: &mut SceneViewOptions,
    extra: impl FnOnce(&mut egui_plot::PlotUi<'_>, &[[f64; 2]], Option<f64>),
) -> egui::Rect {
    let scene = sim.problem();
    let (mut x0, mut x1) = x_extent(sim, road);
    let u = sim.displacement_m();
    let hmax = scene
        .points
        .iter()
        .zip(u)
        .map(|(p, u)| p.h_m.abs().max((p.h_m + u).abs()))
        .fold(sim.road_profile().scale_m(), f64::max)
        .max(1e-6);
    if opts.auto {
        let (e, fit) = auto_exaggeration(ui, (x1 - x0) / hmax, opts.round_up);
        opts.exaggeration = e;
        // rounded up, the heights are taller than the plot at the drawn
        // width: at aspect 1 the plot shows more road, drawn to its edges
        if e > fit && fit > 0.0 {
            let (mid, half) = (0.5 * (x0 + x1), 0.5 * (x1 - x0) * e / fit);
            (x0, x1) = (mid - half, mid + half);
        }
    }
    let e = opts.exaggeration;
    header(ui, sim, opts);
    let focus = focus_row(&scene.points, opts);
    let geo = Geometry::of(sim, (x0, x1), e, hmax, focus.map(|f| f.2));
    let label_color = ui.visuals().strong_text_color();
    let tyre_color = displaced_tyre_color(ui.visuals());
    let plot = with_legend(
        ui,
        Plot::new("tirecontact.scene_view")
            .id(egui::Id::unique(SCENE_PLOT_ID))
            .data_aspect(1.0),
        opts,
        tyre_color,
    );
    // the y title fits the plot's height (a short classroom plot: "height
    // (mm)", the full title on hover); the plot fills the height left, so
    // its frame's height is known before it is drawn
    let title_id = egui::Id::unique("tirecontact.scene_view.y_title");
    let frame_h_px = super::axis_title::frame_height_px(ui, ui.available_height(), true);
    let title = super::axis_title::fit(ui, Y_TITLE, Y_TITLE_SHORT, frame_h_px);
    // labelled heights at least a label and a half apart: eight steps over
    // the plot's height left a short classroom plot's labels (body text,
    // x1.7) closer than their height, and egui_plot drew none
    let label_px = f64::from(1.5 * ui.text_style_height(&egui::TextStyle::Body)).max(30.0);
    let x_label_px = f64::from(4.0 * ui.text_style_height(&egui::TextStyle::Body));
    let r = plot
        .x_title(ui, "position along the contact line x (m)")
        .y_axis_label(title.text.clone())
        // positions (m) at a 1-2-5 step, labels at least four text heights
        // apart: eight steps left classroom text no room, and egui_plot
        // drew no position label at all at 1280 px
        .x_grid_spacer(move |g| height_marks(g, 1.0, x_label_px))
        .x_axis_formatter(|m, _| crate::gui::widgets::number::format_number(m.value))
        .y_grid_spacer(move |g| height_marks(g, 1e3 / e, label_px))
        .y_axis_formatter(move |m, _| crate::gui::widgets::number::format_number(m.value / e * 1e3))
        .y_axis_min_width(44.0)
        .include_x(x0)
        .include_x(x1)
        .include_y(geo.y_floor)
        .include_y(-geo.y_floor)
        .allow_scroll(false)
        .show(ui, |pui| {
            let (labels_floor, displaced) = geo.draw(pui, tyre_color, label_color);
            extra(pui, &displaced, labels_floor);
        });
    super::axis_title::hover(ui, title_id, &title, Y_TITLE, *r.transform.frame(), 44.0);
    *r.transform.frame()
}

/// Above the plot: the exaggeration (auto or set), time, speed, points in
/// contact, and the ramp's progress.
fn header(ui: &mut Ui, sim: &Simulation, opts: &mut SceneViewOptions) {
    let scene = sim.problem();
    let t = sim.time_s();
    let (w, _) = ramp(t, scene.ramp_s);
    let contact = sim.in_contact();
    let e = opts.exaggeration;
    ui.horizontal_wrapped(|ui| {
        // classroom (large text, a short plot): the same in fewer words,
        // on one row at 1280 px
        let factor = crate::gui::widgets::number::format_number(e);
        let what = if opts.legend_above {
            format!("heights ×{factor}")
        } else {
            format!("vertical exaggeration ×{factor}")
        };
        ui.label(RichText::new(what).strong()).on_hover_text(
            "heights are drawn this many times larger than lengths; the height axis shows true mm",
        );
        ui.checkbox(&mut opts.auto, "auto");
        ui.add_enabled(
            !opts.auto,
            egui::DragValue::new(&mut opts.exaggeration)
                .range(1.0..=1e6)
                .speed(1.0)
                .prefix("×"),
        );
        ui.separator();
        let n_contact = contact.iter().filter(|c| **c).count();
        // each label whole on a row (wrapped, "ramping" ended a row and
        // "in: w = 0.00" began the next at 1280 x 720)
        let whole = |text: RichText| egui::Label::new(text).wrap_mode(egui::TextWrapMode::Extend);
        if opts.legend_above {
            // the time is in the toolbar above, in large type
            // (the road's legend entry says it moves left)
            ui.label(format!(
                "V = {:.1} km/h · {} of {} on the road",
                scene.speed_mps * 3.6,
                n_contact,
                contact.len()
            ));
        } else {
            // four labels, each whole: at phone width they take rows of
            // their own instead of one row wider than the window
            for info in [
                format!("t = {t:.5} s"),
                format!("V = {:.1} km/h", scene.speed_mps * 3.6),
                "road moves to the left under the tyre".to_string(),
                format!("{} of {} points in contact", n_contact, contact.len()),
            ] {
                ui.add(whole(RichText::new(info)));
            }
        }
        if let Some((row, rows, y_m)) = focus_row(&scene.points, opts) {
            ui.add(whole(RichText::new(row_text(row, rows, y_m))))
                .on_hover_text(
                    "the points across the tread share their x: the chosen point's row is drawn \
                     in full, the other rows small and grey behind it; choose a point to see \
                     its row",
                );
        }
        // classroom mode (legend above the plot): the ramp's progress in
        // few words, on the header's row (tests/gui/scene_view/layout.rs)
        if opts.legend_above && w < 1.0 {
            ui.add(whole(
                RichText::new(format!("ramping in {:.0} %", 100.0 * w))
                    .color(Color32::from_rgb(230, 159, 0)),
            ))
            .on_hover_text("the road and the preload are eased in at the start (ramp)");
        }
        // shown all along a ramped run, in the room of its widest text: the
        // header keeps its rows and the plot its place when the ramp ends
        if scene.ramp_s > 0.0 && !opts.legend_above {
            let (text, color) = if w < 1.0 {
                (
                    format!("road and preload ramping in: {:.0} %", 100.0 * w),
                    Color32::from_rgb(230, 159, 0),
                )
            } else {
                (
                    "road and preload in full".to_string(),
                    ui.visuals().weak_text_color(),
                )
            };
            let widest = ui
                .painter()
                .layout_no_wrap(
                    "road and preload ramping in: 100 %".to_string(),
                    egui::TextStyle::Body.resolve(ui.style()),
                    color,
                )
                .size();
            ui.add_sized(widest, whole(RichText::new(text).color(color)))
                .on_hover_text(format!(
                    "the road and the preload are eased in over the first {} s (ramp), so \
                     that the run starts at rest without a shock",
                    crate::gui::widgets::number::format_number(scene.ramp_s)
                ));
        }
    });
}

/// The legend: a row of keys above the plot (classroom mode, in its large
/// text; a phone, compact: in a corner of the narrow plot its six entries
/// would cover about half of it), or inside it.
fn with_legend<'a>(
    ui: &mut Ui,
    mut plot: Plot<'a>,
    opts: &SceneViewOptions,
    tyre_color: Color32,
) -> Plot<'a> {
    let phone = ui.ctx().content_rect().width() < crate::gui::widgets::NARROW_PX;
    if opts.legend_above || phone {
        use super::scene_legend::{Entry, Key, row};
        let mut entries = vec![
            Entry {
                name: ROAD_NAME_LEFT,
                short: "road (to left)",
                color: ROAD_COLOR,
                key: Key::Line,
            },
            Entry {
                name: UNDEFORMED_NAME,
                short: "undeformed",
                color: Color32::GRAY,
                key: Key::DashedLine,
            },
            Entry {
                name: DISPLACED_NAME,
                short: "tyre",
                color: tyre_color,
                key: Key::Line,
            },
            Entry {
                name: CONTACT_NAME,
                short: "in contact",
                color: CONTACT_COLOR,
                key: Key::Disc,
            },
            Entry {
                name: FLIGHT_NAME,
                short: "in flight",
                color: FLIGHT_COLOR,
                key: Key::Diamond,
            },
        ];
        // the force's entry even while no point pushes: the row (and so the
        // plot's height and, at aspect 1, its x range) stays the same as
        // points land and leave (it wrapped to a second line and back)
        entries.push(Entry {
            name: FORCE_NAME_SHORT,
            short: "force (N)",
            color: FORCE_COLOR,
            key: Key::Disc,
        });
        if opts.legend_above {
            row(
                ui,
                &entries,
                &opts.legend_style,
                super::scene_legend::ROW_MIN_PX,
            );
        } else {
            // from small text up to body text as the row has room, its
            // rows as high as their text: the keys are not touch targets
            // (a phone's rows are at least 44 px high)
            ui.scope(|ui| {
                ui.spacing_mut().interact_size.y = 0.0;
                row(ui, &entries, &egui::TextStyle::Small, 0.0);
            });
        }
    } else {
        plot = plot.legend(
            Legend::default()
                .position(Corner::RightTop)
                .follow_insertion_order(true)
                .text_style(opts.legend_style.clone()),
        );
    }
    plot
}

/// What the scene plot draws, in plot units (heights exaggerated).
struct Geometry {
    road: Vec<[f64; 2]>,
    /// The points drawn in full (one row of a patch, or all).
    undeformed: Vec<[f64; 2]>,
    displaced: Vec<[f64; 2]>,
    /// Every point's drawn position, NaN for those of faded rows.
    displaced_all: Vec<[f64; 2]>,
    /// The points of the faded rows.
    faded: Vec<[f64; 2]>,
    /// Contact of the points drawn in full.
    contact: Vec<bool>,
    /// Force arrows of the points that push: tails, tips and forces (N).
    a_from: Vec<[f64; 2]>,
    a_to: Vec<[f64; 2]>,
    a_q: Vec<f64>,
    y_floor: f64,
}

impl Geometry {
    /// With `focus_y_m`, only the points of that row in full.
    fn of(
        sim: &Simulation,
        (x0, x1): (f64, f64),
        e: f64,
        hmax: f64,
        focus_y_m: Option<f64>,
    ) -> Self {
        let pts = &sim.problem().points;
        let shown: Vec<bool> = pts
            .iter()
            .map(|p| focus_y_m.is_none_or(|y| p.y_m == y))
            .collect();
        // road seen in the tyre's frame: w z(x + V t) + (1 - w) h(x)
        // under a patch's row in full: the road at its y
        let road: Vec<[f64; 2]> =
            crate::output::animation::road_in_tyre_frame_at(sim, x0, x1, 400, focus_y_m)
                .into_iter()
                .map(|[x, y]| [x, e * y])
                .collect();
        // the points in full along x: the lines join neighbours of one row
        let mut order: Vec<usize> = (0..pts.len()).filter(|&i| shown[i]).collect();
        order.sort_by(|&a, &b| pts[a].x_m.total_cmp(&pts[b].x_m));
        let undeformed: Vec<[f64; 2]> = order
            .iter()
            .map(|&i| [pts[i].x_m, e * pts[i].h_m])
            .collect();
        let every: Vec<[f64; 2]> = pts
            .iter()
            .zip(sim.displacement_m())
            .map(|(p, u)| [p.x_m, e * (p.h_m + u)])
            .collect();
        let displaced: Vec<[f64; 2]> = order.iter().map(|&i| every[i]).collect();
        let faded: Vec<[f64; 2]> = every
            .iter()
            .zip(&shown)
            .filter(|(_, s)| !**s)
            .map(|(d, _)| *d)
            .collect();
        let displaced_all: Vec<[f64; 2]> = every
            .iter()
            .zip(&shown)
            .map(|(d, s)| if *s { *d } else { [f64::NAN; 2] })
            .collect();
        let in_contact = sim.in_contact();
        let contact: Vec<bool> = order
            .iter()
            .map(|&i| in_contact.get(i).copied().unwrap_or(false))
            .collect();
        let qmax = sim
            .force_n()
            .iter()
            .zip(&shown)
            .filter(|(_, s)| **s)
            .fold(0.0, |m: f64, (q, _)| m.max(*q))
            .max(1e-12);
        let arrow_len = 0.25 * e * hmax * 2.0;
        let (mut a_from, mut a_to, mut a_q) = (Vec::new(), Vec::new(), Vec::new());
        for (i, q) in sim.force_n().iter().enumerate() {
            if *q > 0.0 && shown[i] {
                let [x, y] = every[i];
                a_from.push([x, y - arrow_len * q / qmax]);
                a_to.push([x, y]);
                a_q.push(*q);
            }
        }
        Geometry {
            road,
            undeformed,
            displaced,
            displaced_all,
            faded,
            contact,
            a_from,
            a_to,
            a_q,
            y_floor: -e * hmax * 0.5 * HEIGHTS_SPAN,
        }
    }

    /// Road, undeformed and displaced tyre, contact states and force
    /// arrows with their values; returns the lowest y of the value labels
    /// and the points' drawn positions (NaN for the faded rows').
    fn draw(
        self,
        pui: &mut egui_plot::PlotUi<'_>,
        tyre_color: Color32,
        label_color: Color32,
    ) -> (Option<f64>, Vec<[f64; 2]>) {
        let Geometry {
            road,
            undeformed,
            displaced,
            displaced_all,
            faded,
            contact,
            a_from,
            a_to,
            a_q,
            y_floor,
        } = self;
        pui.line(
            Line::new(ROAD_NAME, road)
                .color(ROAD_COLOR)
                .width(2.0)
                .fill(y_floor as f32)
                .fill_alpha(0.25),
        );
        if !faded.is_empty() {
            pui.points(
                Points::new(FADED_ROW_NAME, faded)
                    .color(FADED_ROW_COLOR)
                    .filled(true)
                    .radius(FADED_ROW_MARKER_PX),
            );
        }
        pui.line(
            Line::new(UNDEFORMED_NAME, undeformed.clone())
                .color(Color32::GRAY)
                .style(LineStyle::dashed_dense()),
        );
        pui.points(
            Points::new(UNDEFORMED_NAME, undeformed.clone())
                .color(Color32::GRAY)
                .filled(false)
                .radius(UNDEFORMED_MARKER_PX),
        );
        pui.line(
            Line::new(DISPLACED_NAME, displaced.clone())
                .color(tyre_color)
                .width(2.0),
        );
        // points on the road as discs, in flight as diamonds
        for (on_road, name, color, shape) in [
            (true, CONTACT_NAME, CONTACT_COLOR, MarkerShape::Circle),
            (false, FLIGHT_NAME, FLIGHT_COLOR, MarkerShape::Diamond),
        ] {
            let pts: Vec<[f64; 2]> = displaced
                .iter()
                .zip(&contact)
                .filter(|(_, c)| **c == on_road)
                .map(|(p, _)| *p)
                .collect();
            pui.points(
                Points::new(name, pts)
                    .color(color)
                    .shape(shape)
                    .filled(true)
                    .radius(7.0),
            );
        }
        let mut labels_floor = None;
        if !a_from.is_empty() {
            pui.arrows(
                Arrows::new(FORCE_NAME, a_from.clone(), a_to)
                    .color(FORCE_COLOR)
                    .tip_length(8.0),
            );
            // the labels share the arrows' legend entry, in their colour
            labels_floor = super::force_labels::draw(
                pui,
                FORCE_NAME,
                FORCE_COLOR,
                &a_from,
                &a_q,
                label_color,
                &undeformed,
                UNDEFORMED_MARKER_PX,
            );
        }
        (labels_floor, displaced_all)
    }
}

/// The scene plot's y title, and its short form.
pub const Y_TITLE: &str = "true height (mm)";
pub const Y_TITLE_SHORT: &str = "height (mm)";

#[cfg(test)]
mod tests;
