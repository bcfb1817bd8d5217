//! A/B comparison: the current run's displacement and force per point with
//! the pinned reference run overlaid (dashed, legend "ref: point i"), and
//! the difference current − reference per quantity. The pin is kept by the
//! app across parameter edits and restarts. As in the time plots, the force
//! plot can clip impact spikes (fit the force without impacts, mark ▼).

use super::XTitle;
use super::time_plots::DEFAULT_SHOWN;
use super::time_plots::{clip_at, clip_checkbox, clip_level, force_range, impact_marks, y_range};
use super::{axis_title, legend_place, shown_point_color};
use crate::Scene;
use crate::analysis::compare::{PinnedRun, RunDifference};
use crate::gui::model::command::{Command, ResearchCommand};
use crate::gui::model::history::{History, Quantity, decimate_min_max};
use crate::gui::research::state::CompareOptions;
use crate::output::summary::short_num;
use egui::{Id, RichText, Ui};
use egui_plot::{Line, LineStyle, MarkerShape, Plot};

/// Plot id of the force plot (its bounds are read by the tests).
pub const FORCE_PLOT_ID: &str = "tirecontact.compare.force";
/// Plot id of the displacement plot.
pub const DISPLACEMENT_PLOT_ID: &str = "tirecontact.compare.displacement";
/// Plot id of the force difference plot.
pub const FORCE_DIFF_PLOT_ID: &str = "tirecontact.compare.force_diff";
/// Plot id of the displacement difference plot.
pub const DISPLACEMENT_DIFF_PLOT_ID: &str = "tirecontact.compare.displacement_diff";
/// Legend entries: one per run style; the colour of a curve is its point's
/// (the coloured point check boxes above the plots are the key).
pub const CURRENT: &str = "current run (solid)";
pub const REFERENCE: &str = "reference (dashed)";
pub const DIFFERENCE: &str = "current − reference";
/// Legend entry of the clipped impacts' marks (`time_plots::impact_marks`).
const IMPACT_LABEL: &str = "impact (impulse / dt, clipped)";

/// What the view compares.
pub struct Compared<'a> {
    /// The current run's samples, of `scene` with a tyre of `num_modes`.
    pub history: &'a History,
    pub scene: &'a Scene,
    pub num_modes: usize,
    pub pinned: Option<&'a PinnedRun>,
    /// The pinned run with its force without impacts as `q`, and
    /// `diff_smooth` its difference: they set the clipped force axes.
    pub pinned_smooth: Option<&'a PinnedRun>,
    pub diff: Option<&'a RunDifference>,
    pub diff_smooth: Option<&'a RunDifference>,
}

/// Least height (px) of a plot of the view: its curves, legend and axis
/// readable. Where the plots do not fit the view at this height, the view
/// scrolls.
pub const MIN_PLOT_PX: f32 = 160.0;

/// The view in a vertical scroll area that takes the mouse wheel: the
/// plots share the view's height, each at least [`MIN_PLOT_PX`].
pub fn show(ui: &mut Ui, c: &Compared<'_>, opts: &mut CompareOptions, cmds: &mut Vec<Command>) {
    super::scrolling_view(ui, "tirecontact.compare.scroll", |ui, room| {
        body(ui, c, opts, cmds, room)
    });
}

/// The view's rows; `room`: where the view's content began.
fn body(
    ui: &mut Ui,
    c: &Compared<'_>,
    opts: &mut CompareOptions,
    cmds: &mut Vec<Command>,
    room: super::ViewRoom,
) {
    let Compared {
        history,
        pinned,
        pinned_smooth,
        diff,
        diff_smooth,
        ..
    } = *c;
    let p = history.num_points();
    if opts.shown.len() != p {
        opts.shown = (0..p).map(|i| i < DEFAULT_SHOWN).collect();
    }
    controls(ui, pinned.is_some(), opts, cmds);
    summary(ui, c, opts.clip_impacts);
    // the reference's point drawn with each current point (the one at the
    // same place, if any)
    let matched = pinned.map_or_else(Vec::new, |pin| pin.matched(&c.scene.points));
    // (no difference plots where no point is compared: the summary says so)
    let rows = if opts.difference && matched.iter().any(Option::is_some) {
        4
    } else {
        2
    };
    let gap = ui.spacing().item_spacing.y;
    let t_end = history
        .last_time()
        .unwrap_or(0.0)
        .max(
            pinned
                .and_then(|p| p.recording.t_s.last().copied())
                .unwrap_or(0.0),
        )
        .max(1e-9);
    // the plots share the view's height left below the rows above them
    let left_px = room.left_px(ui);
    let grid = Grid {
        h: ((left_px - (rows - 1) as f32 * gap) / rows as f32).max(MIN_PLOT_PX),
        link: Id::unique("tirecontact.compare_axes"),
        t_end,
        buckets: (ui.available_width() as usize).clamp(100, 3000),
        rows,
        shown: (0..p).filter(|&i| opts.shown[i]).collect(),
        clip_impacts: opts.clip_impacts,
        matched,
    };
    run_plots(ui, &grid, history, pinned, pinned_smooth);
    if rows == 4 {
        difference_plots(ui, &grid, &diff.cloned().unwrap_or_default(), diff_smooth);
    }
}

/// The buttons, the difference and clip switches and the point choice.
fn controls(ui: &mut Ui, pinned: bool, opts: &mut CompareOptions, cmds: &mut Vec<Command>) {
    ui.horizontal_wrapped(|ui| {
        if ui
            .button(RichText::new("Pin as reference").strong())
            .on_hover_text("keep the current run (its samples and scene) as the reference; it survives edits and restarts")
            .clicked()
        {
            cmds.push(Command::Research(ResearchCommand::PinReference));
        }
        if ui.add_enabled(pinned, egui::Button::new("Unpin")).clicked() {
            cmds.push(Command::Research(ResearchCommand::Unpin));
        }
        if ui
            .add_enabled(pinned, egui::Button::new("Export reference CSV…"))
            .on_hover_text("t_s, u{i}_m, q{i}_N of the pinned run")
            .clicked()
        {
            cmds.push(Command::Research(ResearchCommand::ExportPinnedCsvDialog));
        }
        ui.separator();
        ui.checkbox(&mut opts.difference, "show difference (current − reference)");
        clip_checkbox(ui, &mut opts.clip_impacts);
        ui.separator();
        ui.label("points (curve colours):");
        // (more than eight shown: the labels in their curves' ramp colours)
        let chosen: Vec<usize> = (0..opts.shown.len()).filter(|&i| opts.shown[i]).collect();
        for (i, s) in opts.shown.iter_mut().enumerate().take(24) {
            let color = super::checkbox_point_color(ui.visuals(), &chosen, i);
            ui.checkbox(s, RichText::new(i.to_string()).color(color));
        }
    });
}

/// Under the RMS of the force difference with impacts: why it exceeds the
/// forces plotted without impacts.
pub const IMPACT_RMS_NOTE: &str = "With impacts, each run's impulse / dt spikes (one step each, tens of kN) fall at other steps once the runs differ, and they set the force RMS: it can exceed the forces plotted without impacts. The RMS without impacts is in brackets.";

/// What is pinned, how the scenes differ, and the RMS difference per
/// point compared: of the force the force plot draws, the force without
/// impacts while impacts are clipped, else the whole force (impulses as
/// `impulse / dt` spikes, which dominate its RMS).
fn summary(ui: &mut Ui, c: &Compared<'_>, clip_impacts: bool) {
    let Some(pin) = c.pinned else {
        ui.label("No reference pinned: play a run, press “Pin as reference”, then change parameters; the pinned run is drawn dashed over the new one.");
        return;
    };
    ui.label(RichText::new(format!("reference (dashed): {}", pin.label)).strong());
    for note in pin.unlike(c.scene, c.num_modes) {
        ui.label(RichText::new(format!("Unlike runs: {note}")).color(ui.visuals().warn_fg_color));
    }
    let (diff, force) = if clip_impacts {
        (c.diff_smooth, "force without impacts")
    } else {
        (c.diff, "force with impacts (impulse / dt)")
    };
    if let Some(d) = diff {
        // with impacts, the RMS without them beside it ([`IMPACT_RMS_NOTE`])
        let smooth = c.diff_smooth.filter(|_| !clip_impacts);
        let rms: Vec<String> = (0..d.rms_dq_n.len())
            .filter(|&i| d.matched.get(i).copied().flatten().is_some())
            .map(|i| {
                let without = smooth
                    .and_then(|s| s.rms_dq_n.get(i))
                    .filter(|x| x.is_finite())
                    .map(|x| format!(" ({} N without impacts)", short_num(*x, 4)))
                    .unwrap_or_default();
                format!(
                    "p{i}: {} N{without}, {} mm",
                    short_num(d.rms_dq_n[i], 4),
                    short_num(d.rms_du_m[i] * 1e3, 4)
                )
            })
            .collect();
        if !rms.is_empty() {
            ui.label(format!(
                "RMS of current − reference ({force}; displacement) over {} common samples: {}",
                d.t_s.len(),
                rms.join("; ")
            ));
            if smooth.is_some() {
                ui.label(RichText::new(IMPACT_RMS_NOTE).weak());
            }
        }
    }
}

/// What the plots of the view share: their height, the linked time axis,
/// the decimation, the rows and the points shown.
struct Grid {
    h: f32,
    link: Id,
    t_end: f64,
    buckets: usize,
    rows: usize,
    shown: Vec<usize>,
    clip_impacts: bool,
    /// Per current point, the pinned point at the same place.
    matched: Vec<Option<usize>>,
}

impl Grid {
    /// The pinned run's series of current point `i` (the pinned point at
    /// the same place), if there is one.
    fn reference<'a>(&self, ys: &'a [Vec<f64>], i: usize) -> Option<&'a Vec<f64>> {
        self.matched
            .get(i)
            .copied()
            .flatten()
            .and_then(|j| ys.get(j))
    }
}

impl Grid {
    /// A plot of the grid: linked time axis from 0 to the end, its legend
    /// placed off the curves, its y title (`last`: the time axis below).
    fn plot(
        &self,
        ui: &Ui,
        id: (&str, usize),
        legend_id: Id,
        title: &RichText,
        last: bool,
    ) -> Plot<'static> {
        let mut plot = super::nice_y_axis(Plot::new(id))
            .height(self.h)
            .legend(legend_place::legend(ui.ctx(), legend_id, self.h))
            .link_axis(self.link, [true, false])
            .link_cursor(self.link, [true, false])
            .y_axis_label(title.clone())
            .y_axis_min_width(64.0)
            .include_x(0.0)
            .include_x(self.t_end)
            .allow_scroll(false);
        if last {
            plot = plot.x_title(ui, "time t (s)");
        }
        plot.nice_x()
    }
}

/// Displacement and force of the current run, the reference dashed over it.
fn run_plots(
    ui: &mut Ui,
    grid: &Grid,
    history: &History,
    pinned: Option<&PinnedRun>,
    pinned_smooth: Option<&PinnedRun>,
) {
    let (h, buckets) = (grid.h, grid.buckets);
    let shown = grid.shown.as_slice();
    let quantities = [
        (
            Quantity::Displacement,
            "displacement u (mm, up)",
            "u (mm, up)",
            1e3,
        ),
        (Quantity::Force, "contact force q (N)", "q (N)", 1.0),
    ];
    for (k, (what, y_label, y_short, scale)) in quantities.into_iter().enumerate() {
        let last = grid.rows == 2 && k == 1;
        let legend_id = Id::unique(("tirecontact.compare.legend", k));
        let mut labels = vec![CURRENT];
        if pinned.is_some() {
            labels.push(REFERENCE);
        }
        if grid.clip_impacts && what == Quantity::Force {
            labels.push(IMPACT_LABEL);
        }
        let legend_px = legend_place::legend_size(ui, &labels, h);
        let title_id = Id::unique(("tirecontact.compare.y_title", k));
        let title = axis_title::fit_plot(ui, title_id, y_label, y_short, h, last);
        let mut plot = grid.plot(ui, ("tirecontact.compare", k), legend_id, &title.text, last);
        let clip = grid.clip_impacts && what == Quantity::Force;
        // the curves fill the whole run, so every corner covers some: room
        // above them for the legend; when clipping, above the clip level
        // (the curves' top), so the axis still ends well below the spikes
        if let Some(y) = legend_place::headroom(ui.ctx(), legend_id, legend_px) {
            plot = plot.include_y(y);
        }
        plot = plot.id(Id::unique(if what == Quantity::Force {
            FORCE_PLOT_ID
        } else {
            DISPLACEMENT_PLOT_ID
        }));
        let r = plot.show(ui, |pui| {
            let b = pui.plot_bounds();
            let (t0, t1) = (b.min()[0], b.max()[0]);
            // the clip level fits the force without impacts of both runs
            let top = if clip {
                let current = force_range(history, shown, t0, t1, buckets);
                let reference = pinned_smooth.and_then(|pin| {
                    let r = &pin.recording;
                    let ys: Vec<&Vec<f64>> = shown
                        .iter()
                        .filter_map(|&i| grid.reference(&r.q_n, i))
                        .collect();
                    series_range(&r.t_s, &ys, t0, t1, buckets)
                });
                y_range(
                    current
                        .into_iter()
                        .chain(reference)
                        .flat_map(|(lo, hi)| [lo, hi]),
                )
                .map(clip_level)
            } else {
                None
            };
            let mut marks = Vec::new();
            let mut ink = legend_place::Ink::default();
            for &i in shown {
                let mut pts = history.decimated(what, i, t0, t1, buckets, scale);
                if let Some(top) = top {
                    clip_at(&mut pts, top, &mut marks);
                }
                ink.add(pui, &pts);
                pui.line(
                    Line::new(CURRENT, pts)
                        .color(shown_point_color(shown, i))
                        .width(1.5)
                        .allow_band(false),
                );
                if let Some(pin) = pinned {
                    let r = &pin.recording;
                    let y = match what {
                        Quantity::Force => grid.reference(&r.q_n, i),
                        _ => grid.reference(&r.u_m, i),
                    };
                    if let Some(y) = y {
                        let mut pts = window(&r.t_s, y, t0, t1, buckets, scale);
                        if let Some(top) = top {
                            clip_at(&mut pts, top, &mut marks);
                        }
                        ink.add(pui, &pts);
                        pui.line(
                            Line::new(REFERENCE, pts)
                                .color(shown_point_color(shown, i).gamma_multiply(0.6))
                                .width(1.5)
                                .style(LineStyle::dashed_dense()),
                        );
                    }
                }
            }
            ink.place(pui, legend_id, legend_px);
            impact_marks(pui, marks, MarkerShape::Down);
            (t0, t1)
        });
        axis_title::after_plot(ui, title_id, &title, y_label, &r);
        repaint_if_stale(ui, &r);
    }
}

/// Least half span of the displacement difference's axis (mm): 1 µm, the
/// distance within which points are compared as the same.
pub const MIN_HALF_SPAN_MM: f64 = 1e-3;
/// Least half span of the force difference's axis (N).
pub const MIN_HALF_SPAN_N: f64 = 1e-2;

/// The differences current − reference, both edges clipped when impacts
/// are. Each axis spans at least twice its least half span
/// ([`MIN_HALF_SPAN_MM`], [`MIN_HALF_SPAN_N`]) around the difference.
fn difference_plots(
    ui: &mut Ui,
    grid: &Grid,
    d: &RunDifference,
    diff_smooth: Option<&RunDifference>,
) {
    let (h, buckets) = (grid.h, grid.buckets);
    let shown = grid.shown.as_slice();
    let diffs = [
        (
            &d.du_m,
            "Δu = current − ref (mm)",
            "Δu (mm)",
            1e3,
            MIN_HALF_SPAN_MM,
        ),
        (
            &d.dq_n,
            "Δq = current − ref (N)",
            "Δq (N)",
            1.0,
            MIN_HALF_SPAN_N,
        ),
    ];
    for (k, (series, y_label, y_short, scale, min_half)) in diffs.into_iter().enumerate() {
        let legend_id = Id::unique(("tirecontact.compare_diff.legend", k));
        let labels: &[&str] = if grid.clip_impacts && k == 1 {
            &[DIFFERENCE, IMPACT_LABEL]
        } else {
            &[DIFFERENCE]
        };
        let legend_px = legend_place::legend_size(ui, labels, h);
        let title_id = Id::unique(("tirecontact.compare_diff.y_title", k));
        let title = axis_title::fit_plot(ui, title_id, y_label, y_short, h, k == 1);
        let mut plot = grid.plot(
            ui,
            ("tirecontact.compare_diff", k),
            legend_id,
            &title.text,
            k == 1,
        );
        let clip = grid.clip_impacts && k == 1;
        // room for the legend above the curves (clipped: above the
        // upper clip level)
        if let Some(y) = legend_place::headroom(ui.ctx(), legend_id, legend_px) {
            plot = plot.include_y(y);
        }
        // a (nearly) constant difference, as of a run compared with
        // itself: egui_plot gave a flat line an axis as high as the time
        // axis is wide, with a single labelled tick in a short plot
        let values = shown
            .iter()
            .filter_map(|&i| series.get(i))
            .flat_map(|y| y.iter().map(|v| v * scale));
        if let Some((lo, hi)) = y_range(values).filter(|(lo, hi)| hi - lo < 2.0 * min_half) {
            let mid = 0.5 * (lo + hi);
            plot = plot.include_y(mid - min_half).include_y(mid + min_half);
        }
        plot = plot.id(Id::unique(if k == 1 {
            FORCE_DIFF_PLOT_ID
        } else {
            DISPLACEMENT_DIFF_PLOT_ID
        }));
        let r = plot.show(ui, |pui| {
            let b = pui.plot_bounds();
            let (t0, t1) = (b.min()[0], b.max()[0]);
            // impacts of either run give spikes of both signs: clip both
            // edges at the difference of the forces without impacts
            let range = diff_smooth.filter(|_| clip).and_then(|ds| {
                let ys: Vec<&Vec<f64>> = shown.iter().filter_map(|&i| ds.dq_n.get(i)).collect();
                series_range(&ds.t_s, &ys, t0, t1, buckets)
            });
            let (mut above, mut below) = (Vec::new(), Vec::new());
            let mut ink = legend_place::Ink::default();
            for &i in shown {
                let Some(y) = series.get(i) else { continue };
                let mut pts = window(&d.t_s, y, t0, t1, buckets, scale);
                if let Some((lo, hi)) = range {
                    clip_at(&mut pts, clip_level((lo, hi)), &mut above);
                    let bottom = -clip_level((-hi, -lo));
                    for p in &mut pts {
                        if p[1] < bottom {
                            p[1] = bottom;
                            below.push(*p);
                        }
                    }
                }
                ink.add(pui, &pts);
                pui.line(
                    Line::new(DIFFERENCE, pts)
                        .color(shown_point_color(shown, i))
                        .width(1.5)
                        .allow_band(false),
                );
            }
            ink.place(pui, legend_id, legend_px);
            impact_marks(pui, above, MarkerShape::Down);
            impact_marks(pui, below, MarkerShape::Up);
            (t0, t1)
        });
        axis_title::after_plot(ui, title_id, &title, y_label, &r);
        repaint_if_stale(ui, &r);
    }
}

/// The curves are cut to the time window of the previous frame (all egui_plot
/// gives inside `show`): when the window changed (the run grew, a linked plot
/// moved, the view opened) they are stale, so draw once more at once rather
/// than waiting for input.
fn repaint_if_stale(ui: &Ui, r: &egui_plot::PlotResponse<(f64, f64)>) {
    let b = r.transform.bounds();
    let (t0, t1) = r.inner;
    if window_changed((t0, t1), (b.min()[0], b.max()[0])) {
        ui.ctx().request_repaint();
    }
}

/// Whether the drawn window `now` differs from the window `used` to cut the
/// curves (by more than 1e-9 of its span).
pub fn window_changed(used: (f64, f64), now: (f64, f64)) -> bool {
    let tol = 1e-9 * (now.1 - now.0).abs().max(1e-12);
    (used.0 - now.0).abs() > tol || (used.1 - now.1).abs() > tol
}

/// Lowest and highest of the series `ys` over `[t0, t1]` (decimated as
/// drawn).
fn series_range(
    t: &[f64],
    ys: &[&Vec<f64>],
    t0: f64,
    t1: f64,
    buckets: usize,
) -> Option<(f64, f64)> {
    y_range(
        ys.iter()
            .flat_map(|y| window(t, y, t0, t1, buckets, 1.0))
            .map(|p| p[1]),
    )
}

/// Min/max-decimated `(t, y · scale)` over `[t0, t1]` (one sample beyond each end).
fn window(t: &[f64], y: &[f64], t0: f64, t1: f64, buckets: usize, scale: f64) -> Vec<[f64; 2]> {
    let lo = t.partition_point(|&x| x < t0).saturating_sub(1);
    let hi = (t.partition_point(|&x| x <= t1) + 1)
        .min(t.len())
        .min(y.len());
    if hi <= lo {
        return Vec::new();
    }
    decimate_min_max(&t[lo..hi], |k| y[lo + k] * scale, buckets)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_moved_or_grown_window_is_stale() {
        assert!(!window_changed((0.0, 0.2), (0.0, 0.2)));
        assert!(!window_changed((0.0, 0.2), (0.0, 0.2 + 1e-12)));
        assert!(window_changed((0.0, 0.06), (0.0, 0.2)));
        assert!(window_changed((-0.01, 0.2), (0.0, 0.2)));
    }
}
