//! The contact patch: the contact force over the points' grid as a heat
//! map over the road under it (axes in mm, colour bar in N), and the total
//! force and contact area against time. Clicking a row shows its points in
//! the time plots.

use crate::gui::model::command::Command;
use crate::gui::model::history::{History, decimate_min_max};
use crate::gui::views::XTitle;
use crate::output::patch::{PatchLayout, force_colour};
use crate::solver::simulation::Simulation;
use egui::{Align2, Color32, FontId, Pos2, Rect, Sense, Stroke, StrokeKind, Ui, Vec2};
use egui_plot::{Line, Plot, PlotPoints};

/// Road samples per cell side drawn under the heat map.
const ROAD_SAMPLES_PER_CELL: usize = 3;

/// The colour bar's caption.
pub const COLOUR_BAR_CAPTION: &str = "force (N)";

/// The patch at time `t_s`, each figure to three significant digits with
/// its unit: `t = 0.0904 s: total force 439 N, contact area 22.8 cm² (19
/// of 96 points in contact and carrying force, cell 6 × 20 mm)`.
/// `points` is `(points carrying force over the last step, points in
/// contact at its end, points)`: where they differ (a point released inside
/// the step carried force in it; the status bar counts the points in
/// contact at the end) both are said. `cell_m` is the cell along and
/// across (m).
pub fn header_text(
    t_s: f64,
    total_n: f64,
    area_m2: f64,
    points: (usize, usize, usize),
    cell_m: (f64, f64),
) -> String {
    let n = |x: f64| crate::output::summary::short_num(x, 3);
    let (carrying, touching, all) = points;
    let who = if carrying == touching {
        format!("{carrying} of {all} points in contact and carrying force")
    } else {
        format!(
            "{carrying} of {all} points carrying force over the last step, \
             {touching} in contact at its end"
        )
    };
    format!(
        "t = {} s: total force {} N, contact area {} cm² ({who}, cell {} × {} mm)",
        n(t_s),
        n(total_n),
        n(area_m2 * 1e4),
        n(cell_m.0 * 1e3),
        n(cell_m.1 * 1e3),
    )
}

/// Draws the patch view; a click on a row pushes [`Command::ShowPoints`].
pub fn show(ui: &mut Ui, sim: &Simulation, history: &History, cmds: &mut Vec<Command>) {
    let scene = sim.problem();
    let layout = match PatchLayout::of(scene) {
        Ok(l) => l,
        Err(e) => {
            ui.add_space(12.0);
            ui.label(format!(
                "The patch view shows scenes whose points lie across the tread as well as along it: {e}."
            ));
            ui.label(
                "Open Presets › Patch on a road texture, or give the points a Grid(...) (docs/presets.md).",
            );
            return;
        }
    };
    let forces = sim.force_n();
    let max_n = colour_bar_max_n(sim);
    // the colours' scale: the run's largest force, or any scale before it
    // has one (no cell is coloured then)
    let scale_n = if max_n > 0.0 { max_n } else { 1.0 };
    let on = crate::output::patch::carrying_points(forces);
    let total: f64 = forces.iter().sum();
    let (ramp_w, _) = crate::model::road::ramp(sim.time_s(), scene.ramp_s);
    // on a ramped run all along, so that the map keeps its place
    if scene.ramp_s > 0.0 {
        let text = if ramp_w < 1.0 {
            format!(
                "preload ramping in ({:.0} %): the points on the road carry little force yet",
                100.0 * ramp_w
            )
        } else {
            "preload in full".to_string()
        };
        ui.label(egui::RichText::new(text).color(ui.visuals().weak_text_color()));
    }
    ui.label(format!(
        "{}; click a row to see its points in the time plots",
        header_text(
            sim.time_s(),
            total,
            layout.contact_area_m2(forces),
            (
                on,
                sim.in_contact().iter().filter(|&&c| c).count(),
                layout.xy_m.len(),
            ),
            layout.cell_m,
        )
    ));
    if ui
        .button(HEAT_MAP_PNG_BUTTON)
        .on_hover_text("the heat map at this time, with its axes in mm and its colour bar in N")
        .clicked()
    {
        cmds.push(Command::ExportHeatMapDialog);
    }
    let h = (ui.available_height() * 0.55).max(160.0);
    let (resp, painter) = ui.allocate_painter(Vec2::new(ui.available_width(), h), Sense::click());
    let area = resp.rect;
    let font = FontId::proportional(13.0);
    let text = ui.visuals().text_color();
    // the map's frame: left axis labels, bottom axis labels, right colour bar
    let map = Rect::from_min_max(
        Pos2::new(area.left() + 70.0, area.top() + 24.0),
        Pos2::new(area.right() - 110.0, area.bottom() - 44.0),
    );
    let (dx, dy) = layout.cell_m;
    let (x0, x1, y0, y1) = layout.extent_m();
    let to_px = |x: f64, y: f64| {
        Pos2::new(
            map.left() + ((x - x0) / (x1 - x0)) as f32 * map.width(),
            map.bottom() - ((y - y0) / (y1 - y0)) as f32 * map.height(),
        )
    };
    // the road under the patch, grey by height (darker is higher)
    let road = sim.road_profile();
    let rolled = sim.rolled_m();
    let (nx, ny) = (
        ((x1 - x0) / dx).round() as usize * ROAD_SAMPLES_PER_CELL,
        ((y1 - y0) / dy).round() as usize * ROAD_SAMPLES_PER_CELL,
    );
    let (nx, ny) = (nx.clamp(1, 400), ny.clamp(1, 200));
    let mut z = vec![0.0; nx * ny];
    for j in 0..ny {
        for i in 0..nx {
            let x = x0 + (i as f64 + 0.5) / nx as f64 * (x1 - x0);
            let y = y0 + (j as f64 + 0.5) / ny as f64 * (y1 - y0);
            z[j * nx + i] = road.sample_at(x + rolled, y).map_or(0.0, |s| s.0);
        }
    }
    let (zmin, zmax) = z
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
    let zspan = (zmax - zmin).max(1e-12);
    for j in 0..ny {
        for i in 0..nx {
            let s = ((z[j * nx + i] - zmin) / zspan) as f32;
            let g = (235.0 - 90.0 * s) as u8;
            let a = to_px(
                x0 + i as f64 / nx as f64 * (x1 - x0),
                y0 + (j + 1) as f64 / ny as f64 * (y1 - y0),
            );
            let b = to_px(
                x0 + (i + 1) as f64 / nx as f64 * (x1 - x0),
                y0 + j as f64 / ny as f64 * (y1 - y0),
            );
            painter.rect_filled(Rect::from_two_pos(a, b), 0.0, Color32::from_gray(g));
        }
    }
    // the points' cells: the force's colour where the point is on the road
    for (k, &(x, y)) in layout.xy_m.iter().enumerate() {
        let r = Rect::from_two_pos(
            to_px(x - 0.5 * dx, y + 0.5 * dy),
            to_px(x + 0.5 * dx, y - 0.5 * dy),
        );
        if forces[k] > 0.0 {
            let c = force_colour(forces[k], scale_n);
            painter.rect_filled(r.shrink(1.0), 0.0, Color32::from_rgb(c.0, c.1, c.2));
        }
        painter.rect_stroke(
            r,
            0.0,
            Stroke::new(1.0, Color32::from_gray(120)),
            StrokeKind::Inside,
        );
    }
    // axes: x along (mm) below, y across (mm) at the left, one label per row
    for &y in &layout.rows_y_m {
        let p = to_px(x0, y);
        painter.text(
            Pos2::new(map.left() - 6.0, p.y),
            Align2::RIGHT_CENTER,
            format!("{:.0}", y * 1e3),
            font.clone(),
            text,
        );
    }
    let step_mm = nice_step((x1 - x0) * 1e3 / 8.0);
    let mut m = (x0 * 1e3 / step_mm).ceil() * step_mm;
    while m <= x1 * 1e3 {
        let p = to_px(m * 1e-3, y0);
        painter.text(
            Pos2::new(p.x, map.bottom() + 4.0),
            Align2::CENTER_TOP,
            format!("{m:.0}"),
            font.clone(),
            text,
        );
        m += step_mm;
    }
    painter.text(
        Pos2::new(map.center().x, area.bottom() - 2.0),
        Align2::CENTER_BOTTOM,
        "along the rolling direction x (mm)",
        font.clone(),
        text,
    );
    painter.text(
        Pos2::new(map.left() - 6.0, map.top() - 4.0),
        Align2::RIGHT_BOTTOM,
        "y (mm)",
        font.clone(),
        text,
    );
    // the colour bar, 0 N at the bottom; its caption above the map's top,
    // level with the y title, and its top label (centred on the bar's top)
    // a font height below the caption: not crowding it
    let bar = Rect::from_min_max(
        Pos2::new(map.right() + 24.0, map.top() + font.size),
        Pos2::new(map.right() + 44.0, map.bottom()),
    );
    let steps = 60;
    for s in 0..steps {
        let f0 = s as f64 / steps as f64;
        // grey while there is no scale to read
        let fill = if max_n > 0.0 {
            let c = force_colour((f0 + 0.5 / steps as f64) * scale_n, scale_n);
            Color32::from_rgb(c.0, c.1, c.2)
        } else {
            Color32::from_gray(200)
        };
        let ya = bar.bottom() - (s as f32 / steps as f32) * bar.height();
        let yb = bar.bottom() - ((s + 1) as f32 / steps as f32) * bar.height();
        painter.rect_filled(
            Rect::from_min_max(Pos2::new(bar.left(), yb), Pos2::new(bar.right(), ya)),
            0.0,
            fill,
        );
    }
    painter.rect_stroke(
        bar,
        0.0,
        Stroke::new(1.0, Color32::from_gray(120)),
        StrokeKind::Outside,
    );
    painter.text(
        Pos2::new(bar.center().x, map.top() - 4.0),
        Align2::CENTER_BOTTOM,
        COLOUR_BAR_CAPTION,
        font.clone(),
        text,
    );
    if max_n > 0.0 {
        for frac in [0.0, 0.5, 1.0] {
            painter.text(
                Pos2::new(bar.right() + 4.0, bar.bottom() - frac as f32 * bar.height()),
                Align2::LEFT_CENTER,
                crate::output::summary::short_num(frac * max_n, 3),
                font.clone(),
                text,
            );
        }
    } else {
        // before any force: no scale to give, said across the bar
        painter.text(
            Pos2::new(bar.right() + 4.0, bar.center().y),
            Align2::LEFT_CENTER,
            NO_FORCE_YET,
            font.clone(),
            text,
        );
    }
    // a click on a row: its points in the time plots
    if resp.clicked()
        && let Some(pos) = resp.interact_pointer_pos()
        && map.contains(pos)
    {
        let y = y0 + f64::from((map.bottom() - pos.y) / map.height()) * (y1 - y0);
        let row = layout
            .rows_y_m
            .iter()
            .enumerate()
            .min_by(|a, b| (a.1 - y).abs().total_cmp(&(b.1 - y).abs()))
            .map_or(0, |(r, _)| r);
        let points: Vec<usize> = (0..layout.xy_m.len())
            .filter(|&k| layout.row_of_point[k] == row)
            .collect();
        cmds.push(Command::ShowPoints(points));
    }
    resp.on_hover_text("click a row to see its points in the time plots");
    totals_plot(ui, &layout, history, sim.problem().duration_s);
}

/// The patch view's button exporting its heat map.
pub const HEAT_MAP_PNG_BUTTON: &str = "Heat map as PNG…";

/// The colour bar's label before the run has a force (on two lines in the
/// room right of the bar).
pub const NO_FORCE_YET: &str = "no force\nyet";

/// The top of the colour bar (N): the run's largest force so far (0 before
/// any).
pub fn colour_bar_max_n(sim: &Simulation) -> f64 {
    sim.stats()
        .max_force_n
        .iter()
        .copied()
        .filter(|f| f.is_finite())
        .fold(0.0, f64::max)
}

/// Total force (N) and contact area (cm², the points carrying force times
/// the cell) against time, from the history, on a time axis from 0 to the
/// run's `duration_s` until the run has samples to show.
fn totals_plot(ui: &mut Ui, layout: &PatchLayout, history: &History, duration_s: f64) {
    let t = history.times();
    let (force_n, carrying) = history.totals();
    let cell_cm2 = layout.cell_area_m2() * 1e4;
    // min/max pairs per pixel column: what the plot can show of thousands
    // of samples, peaks kept
    let buckets = ui.available_width().max(1.0) as usize;
    let total = PlotPoints::new(decimate_min_max(t, |k| force_n[k], buckets));
    let area = PlotPoints::new(decimate_min_max(t, |k| carrying[k] * cell_cm2, buckets));
    let h = ((ui.available_height() - 8.0) / 2.0).max(80.0);
    // before the run has two samples: the run's time span (egui_plot's
    // empty plot ran from -0.5 to 0.5 s); then the samples' own
    let empty_end_s = if t.len() < 2 && duration_s.is_finite() && duration_s > 0.0 {
        duration_s
    } else {
        0.0
    };
    // (one curve each, named by its axis: no legend over the data); y
    // numbers at 1-2-5 steps down to 30 px apart (egui_plot's own spacing
    // left a short plot only its 0)
    // (both quantities are never negative: before any force, the axis runs
    // from 0 to 1 without margins, not around 0 into negative values)
    let any_force = force_n.iter().any(|&f| f > 0.0);
    let any_area = carrying.iter().any(|&c| c > 0.0);
    let plot = |ui: &Ui, id: &'static str, y_title: &'static str, some: bool| {
        let p = super::nice_y_axis(Plot::new(id))
            .id(egui::Id::unique(id))
            .height(h)
            .x_title(ui, "time t (s)")
            .nice_x()
            .y_axis_label(y_title)
            .allow_scroll(false)
            .include_y(0.0)
            .include_x(0.0)
            .include_x(empty_end_s);
        if some {
            p
        } else {
            p.include_y(1.0).set_margin_fraction(egui::vec2(0.05, 0.0))
        }
    };
    plot(ui, TOTAL_FORCE_PLOT_ID, TOTAL_FORCE_TITLE, any_force)
        .show(ui, |pu| pu.line(Line::new(TOTAL_FORCE_TITLE, total)));
    plot(ui, CONTACT_AREA_PLOT_ID, CONTACT_AREA_TITLE, any_area)
        .show(ui, |pu| pu.line(Line::new(CONTACT_AREA_TITLE, area)));
}

/// Plot id of the patch view's total force against time.
pub const TOTAL_FORCE_PLOT_ID: &str = "tirecontact.patch.total";
/// Plot id of the patch view's contact area against time.
pub const CONTACT_AREA_PLOT_ID: &str = "tirecontact.patch.area";
/// The y title of the total force plot.
pub const TOTAL_FORCE_TITLE: &str = "total force (N)";
/// The y title of the contact area plot.
pub const CONTACT_AREA_TITLE: &str = "contact area (cm²)";

/// A 1-2-5 step at least `raw`.
fn nice_step(raw: f64) -> f64 {
    let e = 10f64.powf(raw.max(1e-9).log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * e)
        .find(|&s| s >= raw)
        .unwrap_or(10.0 * e)
}
