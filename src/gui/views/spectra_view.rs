//! Spectra of the steady part of the current run: force (dB re 1 N) and
//! displacement (dB re 1 m) levels against frequency per point, the summed
//! force, third-octave band levels, and markers at the road excitation
//! `n V/λ` and the modal frequencies. Computed by the app (cached by the
//! history's length), only drawn here.

use super::XTitle;
use super::axis_title;
use super::shown_point_color;
use super::time_plots::DEFAULT_SHOWN;
use crate::Scene;
use crate::analysis::spectrum::run::DEFAULT_BANDS_HZ;
use crate::analysis::spectrum::{Spectrum, band_label, markers};
use crate::base::modal::Mode;
use crate::gui::model::command::{Command, ResearchCommand};
use crate::gui::research::spectra::{HistoryCache, HistorySpectra};
use crate::gui::research::state::SpectraOptions;
use egui::{Color32, RichText, Ui};
use egui_plot::{Line, LineStyle, Plot, VLine};

/// Harmonics of the road excitation marked.
pub const HARMONICS: u32 = 10;
/// Dynamic range drawn below the highest level (dB).
const RANGE_DB: f64 = 120.0;
const EXCITATION_COLOR: Color32 = Color32::from_rgb(200, 40, 40);
const MODE_COLOR: Color32 = Color32::from_rgb(110, 110, 110);

/// Label of a log10 axis mark: the frequency at decades and at 2 and 5.
pub fn log_label(v: f64) -> String {
    let x = 10f64.powf(v);
    let m = x / 10f64.powf(v.floor());
    if [1.0, 2.0, 5.0].iter().any(|k| (m - k).abs() < 1e-6) {
        crate::gui::widgets::number::format_number(x)
    } else {
        String::new()
    }
}

/// Level steps (dB) of the level axes: 10 and 20 dB at the usual plot
/// heights, finer when zoomed in, coarser when squeezed.
const DB_STEPS: [f64; 9] = [1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0, 500.0];
/// Smallest distance between labelled level ticks (px); egui_plot shows a
/// tick label from 20 px, fully from 30 px.
const DB_LABEL_PX: f64 = 30.0;

/// Grid marks of a level axis (dB): multiples of the smallest step of
/// `DB_STEPS` at least `DB_LABEL_PX` apart (labelled), with the next finer
/// step between them. egui_plot's default powers of ten left a 100 dB axis
/// with the single label "0".
pub fn db_marks(input: egui_plot::GridInput) -> Vec<egui_plot::GridMark> {
    let (lo, hi) = input.bounds;
    // base_step_size is the value of egui_plot's 8 px minimum grid spacing
    let db_per_px = input.base_step_size / 8.0;
    if !(lo.is_finite() && hi.is_finite() && db_per_px.is_finite() && db_per_px > 0.0) {
        return Vec::new();
    }
    let k = DB_STEPS
        .iter()
        .position(|&s| s / db_per_px >= DB_LABEL_PX)
        .unwrap_or(DB_STEPS.len() - 1);
    let major = DB_STEPS[k];
    let fine = if k > 0 { DB_STEPS[k - 1] } else { major };
    let (first, last) = ((lo / fine).ceil() as i64, (hi / fine).floor() as i64);
    if last - first > 10_000 {
        return Vec::new();
    }
    (first..=last)
        .map(|n| {
            let value = n as f64 * fine;
            let on_major = (value / major - (value / major).round()).abs() < 1e-9;
            egui_plot::GridMark {
                value,
                step_size: if on_major { major } else { fine },
            }
        })
        .collect()
}

/// A level axis (dB) with [`db_marks`] and whole-dB labels.
/// A level axis in dB, set by the curves alone: frequencies zoom and pan
/// (double-click restores them), levels do not (a zoom over the levels
/// squashed the curves to a line, with no way back).
fn db_y_axis(plot: Plot<'_>) -> Plot<'_> {
    plot.y_grid_spacer(db_marks)
        .y_axis_formatter(|m, _| format!("{:.0}", m.value))
        .allow_zoom([true, false])
        .allow_drag([true, false])
        .allow_axis_zoom_drag([true, false])
        .allow_boxed_zoom(false)
}

/// x coordinate of a frequency on the plot (log10 when `log`).
fn fx(f: f64, log: bool) -> f64 {
    if log { f.log10() } else { f }
}

/// The excitation summary shown above the plots (also what tests read).
pub fn excitation_text(scene: &Scene) -> String {
    let m = markers(scene, &[], f64::INFINITY, 1);
    match m.excitation_hz.first() {
        Some((_, f)) => format!(
            "road excitation V/λ = {f:.2} Hz (harmonics n·V/λ to n = {HARMONICS} marked red)"
        ),
        None => "road excitation: broadband road, no discrete V/λ line".to_string(),
    }
}

/// Plot ids of the force, displacement and band level plots (their frames
/// are read by the tests).
pub const PLOT_IDS: [&str; 3] = [
    "tirecontact.spectra_q",
    "tirecontact.spectra_u",
    "tirecontact.spectra_bands",
];
/// The y titles of the three plots, full and short (the short one where
/// the full one is longer than its plot's frame).
pub const Y_TITLES: [(&str, &str); 3] = [
    ("force level (dB re 1 N)", "q (dB re 1 N)"),
    ("displacement level (dB re 1 m)", "u (dB re 1 m)"),
    ("band level (dB re 1 N)", "band (dB re 1 N)"),
];
/// Least height (px) of a spectrum plot: its marker labels, level axis and
/// y title readable. Where the three do not fit the view at this height,
/// the view scrolls.
pub const MIN_PLOT_PX: f32 = 200.0;

/// The view in a vertical scroll area that takes the mouse wheel: the
/// three plots share the view's height, each at least [`MIN_PLOT_PX`].
pub fn show(
    ui: &mut Ui,
    scene: &Scene,
    modes: &[Mode],
    cache: &HistoryCache<Result<HistorySpectra, String>>,
    computing: Option<f64>,
    opts: &mut SpectraOptions,
    playing: bool,
    cmds: &mut Vec<Command>,
) {
    let p = scene.num_points();
    if opts.shown.len() != p {
        opts.shown = (0..p).map(|i| i < DEFAULT_SHOWN).collect();
    }
    super::scrolling_view(ui, "tirecontact.spectra.scroll", |ui, room| {
        body(
            ui,
            Shown {
                scene,
                modes,
                cache,
                computing,
                playing,
                room,
            },
            opts,
            cmds,
        )
    });
}

/// What the view's body draws, and where it began.
struct Shown<'a> {
    scene: &'a Scene,
    modes: &'a [Mode],
    cache: &'a HistoryCache<Result<HistorySpectra, String>>,
    computing: Option<f64>,
    playing: bool,
    /// Where the view's content began.
    room: super::ViewRoom,
}

fn body(ui: &mut Ui, what: Shown<'_>, opts: &mut SpectraOptions, cmds: &mut Vec<Command>) {
    let Shown {
        scene,
        modes,
        cache,
        computing,
        playing,
        room,
    } = what;
    controls(ui, opts, cmds);
    ui.label(RichText::new(excitation_text(scene)).color(EXCITATION_COLOR));
    if let Some(f) = computing {
        ui.horizontal(|ui| {
            ui.spinner();
            ui.label(format!("computing… {:.0} %", 100.0 * f));
        });
    }
    let hs = match cache.get() {
        Some(Ok(hs)) => hs,
        // a running computation replaces the reason there was none
        _ if computing.is_some() => return,
        Some(Err(e)) => {
            ui.label(format!("No spectrum yet: {e}"));
            return;
        }
        None => {
            ui.label(if playing {
                "No spectrum yet: computing when the run has advanced."
            } else {
                "No spectrum yet: play the run past the ramp, then press Recompute."
            });
            return;
        }
    };
    ui.label(RichText::new(format!("Window: {}", hs.caption())).strong());
    legend_row(ui, scene, modes, opts);
    let s = &hs.spectra;
    let nyquist = 0.5 * hs.span.sample_rate_hz;
    let max_hz = opts.max_hz.min(nyquist);
    let gap = ui.spacing().item_spacing.y;
    // three plots and the band caption line below them, in the view's
    // height left below the rows above them
    let caption = ui.text_style_height(&egui::TextStyle::Body) + gap;
    let left_px = room.left_px(ui);
    let pl = Plots {
        h: ((left_px - 3.0 * gap - caption) / 3.0).max(MIN_PLOT_PX),
        max_hz,
        log: opts.log_x,
        marks: markers(scene, modes, max_hz, HARMONICS),
        modal: modes
            .iter()
            .map(|m| m.freq_hz)
            .filter(|&f| f > 0.0 && f <= max_hz)
            .collect(),
        // the summed force: black in a light theme, white in a dark one
        total_color: ui.visuals().strong_text_color(),
        shown: opts.shown.clone(),
        total: opts.total,
    };
    narrow(
        ui,
        &pl,
        PLOT_IDS[0],
        Y_TITLES[0],
        &s.force,
        Some(&s.total_force),
        "q",
    );
    narrow(
        ui,
        &pl,
        PLOT_IDS[1],
        Y_TITLES[1],
        &s.displacement,
        None,
        "u",
    );
    bands(ui, &pl, s, nyquist);
}

/// Name of the summed force's curves (legend row, hover).
pub const TOTAL_NAME: &str = "total: sum of all points";
/// Names of the markers' legend entries.
pub const EXCITATION_NAME: &str = "road n·V/λ";
pub const MODES_NAME: &str = "modal frequencies";

/// One legend for the three plots, in a row above them: a plot's own
/// legend, eight entries in a 150 px plot at 1280 × 720, covered its
/// low-frequency curves and ran out of the plot's top.
fn legend_row(ui: &mut Ui, scene: &Scene, modes: &[Mode], opts: &SpectraOptions) {
    use super::scene_legend::{Key, item};
    let style = egui::TextStyle::Body;
    let total_color = ui.visuals().strong_text_color();
    ui.horizontal_wrapped(|ui| {
        ui.spacing_mut().item_spacing.x = 12.0;
        let shown = shown_indices(&opts.shown);
        for &i in &shown {
            item(
                ui,
                &format!("point {i}"),
                shown_point_color(&shown, i),
                Key::Line,
                &style,
            );
        }
        if opts.total {
            item(ui, TOTAL_NAME, total_color, Key::Line, &style);
        }
        if !markers(scene, modes, opts.max_hz, HARMONICS)
            .excitation_hz
            .is_empty()
        {
            item(
                ui,
                EXCITATION_NAME,
                EXCITATION_COLOR,
                Key::DashedLine,
                &style,
            );
        }
        if !modes.is_empty() {
            item(ui, MODES_NAME, MODE_COLOR, Key::DottedLine, &style);
        }
    });
}

/// Recompute, automatic updates, the axis and the curves shown.
fn controls(ui: &mut Ui, opts: &mut SpectraOptions, cmds: &mut Vec<Command>) {
    ui.horizontal_wrapped(|ui| {
        if ui
            .button("Recompute")
            .on_hover_text("transform the run's steady part now")
            .clicked()
        {
            cmds.push(Command::Research(ResearchCommand::RecomputeSpectra));
        }
        ui.checkbox(&mut opts.auto, "update while playing")
            .on_hover_text(
                "recompute when the run grew by 25 %; off: only on Recompute or when paused",
            );
        ui.checkbox(&mut opts.log_x, "log frequency axis");
        ui.label("up to");
        ui.add(
            egui::DragValue::new(&mut opts.max_hz)
                .range(10.0..=1e6)
                .speed(10.0)
                .suffix(" Hz"),
        )
        .accessible_name("highest frequency");
        ui.separator();
        ui.label("points:");
        // (more than eight shown: the labels in their curves' ramp colours)
        let chosen: Vec<usize> = (0..opts.shown.len()).filter(|&i| opts.shown[i]).collect();
        for (i, s) in opts.shown.iter_mut().enumerate().take(24) {
            let color = super::checkbox_point_color(ui.visuals(), &chosen, i);
            ui.checkbox(s, RichText::new(i.to_string()).color(color));
        }
        ui.checkbox(&mut opts.total, "total force");
    });
}

/// What the three spectra plots share.
struct Plots {
    h: f32,
    max_hz: f64,
    log: bool,
    marks: crate::analysis::spectrum::Markers,
    modal: Vec<f64>,
    total_color: Color32,
    shown: Vec<bool>,
    total: bool,
}

impl Plots {
    fn x_label(&self) -> &'static str {
        if self.log {
            "frequency f (Hz, log scale)"
        } else {
            "frequency f (Hz)"
        }
    }
}

/// A narrow-band level plot of `specs` (and of their `total`), the road's
/// excitation and the modal frequencies marked.
fn narrow(
    ui: &mut Ui,
    pl: &Plots,
    id: &str,
    (y_label, y_short): (&str, &str),
    specs: &[Spectrum],
    total: Option<&Spectrum>,
    unit: &str,
) {
    // the top level and the floor of the drawn curves
    let shown = shown_indices(&pl.shown);
    let curves: Vec<(String, Color32, Vec<[f64; 2]>)> = specs
        .iter()
        .enumerate()
        .filter(|(i, _)| pl.shown.get(*i).copied().unwrap_or(false))
        .map(|(i, sp)| {
            (
                format!("{unit}{i}: point {i}"),
                shown_point_color(&shown, i),
                sp,
            )
        })
        .chain(
            total
                .filter(|_| pl.total)
                .map(|sp| (format!("{unit} {TOTAL_NAME}"), pl.total_color, sp)),
        )
        .map(|(name, c, sp)| (name, c, level_points(sp, pl.max_hz, pl.log)))
        .collect();
    let top = curves
        .iter()
        .flat_map(|c| c.2.iter().map(|p| p[1]))
        .fold(f64::NEG_INFINITY, f64::max);
    let floor = top - RANGE_DB;
    // room above the curves for the markers' labels: two rows of small
    // text over a frame about the plot's height less its x axis, which
    // shows at most RANGE_DB below them
    let rows_px = f64::from(2.0 * label_row_px(ui));
    let frame_px = f64::from(pl.h - super::titled_x_axis_px(ui));
    let label_db = rows_px * RANGE_DB / (frame_px - rows_px).max(1.0);
    let title_id = egui::Id::unique(id).with("y_title");
    let title = axis_title::fit_plot(ui, title_id, y_label, y_short, pl.h, true);
    let mut plot = db_y_axis(Plot::new(id))
        .id(egui::Id::unique(id))
        .height(pl.h)
        .x_title(ui, pl.x_label())
        .y_axis_label(title.text.clone())
        .y_axis_min_width(64.0)
        .allow_scroll(false);
    if pl.log {
        plot = plot
            .x_grid_spacer(super::log_marks)
            .x_axis_formatter(|m, _| log_label(m.value));
    } else {
        plot = plot.nice_x();
    }
    if top.is_finite() {
        plot = plot.include_y(top + label_db);
    }
    let r = plot.show(ui, |pui| {
        for (name, c, pts) in curves {
            let pts: Vec<[f64; 2]> = pts.into_iter().map(|p| [p[0], p[1].max(floor)]).collect();
            pui.line(Line::new(name, pts).color(c).width(1.2).allow_band(false));
        }
        if top.is_finite() {
            marker_lines(pui, &pl.marks.excitation_hz, &pl.modal, pl.log);
        }
    });
    if top.is_finite() {
        marker_labels(
            ui,
            &r.transform,
            &pl.marks.excitation_hz,
            &pl.modal,
            pl.log,
            top + label_db,
        );
    }
    axis_title::after_plot(ui, title_id, &title, y_label, &r);
}

/// Third-octave bands of the forces, drawn as steps over the band edges.
fn bands(ui: &mut Ui, pl: &Plots, s: &crate::analysis::spectrum::run::RunSpectra, nyquist: f64) {
    let hi = DEFAULT_BANDS_HZ.1.min(nyquist / 10f64.powf(0.05));
    let (y_label, y_short) = Y_TITLES[2];
    let title_id = egui::Id::unique(PLOT_IDS[2]).with("y_title");
    let title = axis_title::fit_plot(ui, title_id, y_label, y_short, pl.h, true);
    let r = db_y_axis(Plot::new(PLOT_IDS[2]))
        .id(egui::Id::unique(PLOT_IDS[2]))
        .height(pl.h)
        .x_title(ui, "third-octave band (Hz, log scale; IEC 61260 base 10)")
        .y_axis_label(title.text.clone())
        .y_axis_min_width(64.0)
        .x_grid_spacer(super::log_marks)
        .x_axis_formatter(|m, _| log_label(m.value))
        .allow_scroll(false)
        .show(ui, |pui| {
            let shown = shown_indices(&pl.shown);
            let mut series: Vec<(String, Color32, &Spectrum)> = s
                .force
                .iter()
                .enumerate()
                .filter(|(i, _)| pl.shown.get(*i).copied().unwrap_or(false))
                .map(|(i, sp)| (format!("q{i}: point {i}"), shown_point_color(&shown, i), sp))
                .collect();
            if pl.total {
                series.push((format!("q {TOTAL_NAME}"), pl.total_color, &s.total_force));
            }
            for (name, c, sp) in series {
                let mut pts = Vec::new();
                for b in sp.third_octave_levels(DEFAULT_BANDS_HZ.0, hi, 1.0) {
                    if b.resolved && b.level_db.is_finite() {
                        pts.push([b.band.lower_hz.log10(), b.level_db]);
                        pts.push([b.band.upper_hz.log10(), b.level_db]);
                    }
                }
                // steps: no min/max band merging of the vertical edges
                pui.line(Line::new(name, pts).color(c).width(1.5).allow_band(false));
            }
            for &(n, f) in pl.marks.excitation_hz.iter().filter(|m| m.1 <= hi) {
                if n <= 3 {
                    pui.vline(
                        VLine::new(EXCITATION_NAME, f.log10())
                            .color(EXCITATION_COLOR)
                            .style(LineStyle::dashed_loose()),
                    );
                }
            }
        });
    axis_title::after_plot(ui, title_id, &title, y_label, &r);
    if hi > DEFAULT_BANDS_HZ.0 {
        ui.label(
            RichText::new(format!(
                "bands {}–{} Hz; only bands below Nyquist and at least one bin wide are drawn",
                band_label(DEFAULT_BANDS_HZ.0),
                band_label(hi)
            ))
            .weak(),
        );
    }
}

/// `(x, level)` of the bins from the first non-DC bin up to `max_hz`.
fn level_points(sp: &Spectrum, max_hz: f64, log: bool) -> Vec<[f64; 2]> {
    sp.freq_hz
        .iter()
        .zip(sp.levels_db(1.0))
        .skip(1)
        .take_while(|(f, _)| **f <= max_hz)
        .filter(|(_, l)| l.is_finite())
        .map(|(&f, l)| [fx(f, log), l])
        .collect()
}

/// Height (px) of a marker label's row.
fn label_row_px(ui: &Ui) -> f32 {
    ui.text_style_height(&egui::TextStyle::Small) + 2.0
}

/// The vertical markers: the road excitation harmonics (red, dashed) and
/// the modal frequencies (grey, dotted).
fn marker_lines(
    pui: &mut egui_plot::PlotUi<'_>,
    excitation: &[(u32, f64)],
    modal: &[f64],
    log: bool,
) {
    for &(_, f) in excitation {
        pui.vline(
            VLine::new(EXCITATION_NAME, fx(f, log))
                .color(EXCITATION_COLOR)
                .width(1.0)
                .style(LineStyle::dashed_loose()),
        );
    }
    for &f in modal {
        pui.vline(
            VLine::new(MODES_NAME, fx(f, log))
                .color(MODE_COLOR)
                .width(1.0)
                .style(LineStyle::dotted_loose()),
        );
    }
}

/// Gap (px) a marker label keeps from the one before it in its row.
const LABEL_GAP_PX: f32 = 4.0;

/// Where the marker labels go (px): each label's left edge just right of
/// its marker (`x_px`) and its `width_px`, in row `row` (0: the road
/// excitation's, 1: the modes' below it), from `top_px` down, one row
/// `row_px` high. A label is left out where it would reach the frame's
/// `right_px` or come within [`LABEL_GAP_PX`] of the one before it in its
/// row; the rows do not overlap, so no two labels do. Returns, per label
/// in the order given, its rect or `None`.
fn place_marker_labels(
    labels: &[(usize, f32, f32)],
    top_px: f32,
    row_px: f32,
    right_px: f32,
) -> Vec<Option<egui::Rect>> {
    let mut last_right = [f32::NEG_INFINITY; 2];
    labels
        .iter()
        .map(|&(row, x_px, width_px)| {
            let row = row.min(1);
            let left = x_px + 2.0;
            if left < last_right[row] + LABEL_GAP_PX || left + width_px > right_px {
                return None;
            }
            last_right[row] = left + width_px;
            let top = top_px + row as f32 * row_px;
            Some(egui::Rect::from_min_size(
                egui::pos2(left, top),
                egui::vec2(width_px, row_px),
            ))
        })
        .collect()
}

/// The markers' labels, in small text from the level `top` (dB) down (the
/// room kept above the curves): the road excitation harmonics'
/// (`V/λ 100 Hz`, `2V/λ`, …) in one row, the modal frequencies' (`fk`) in
/// the row below, each where it is clear of the one before it in its row
/// ([`place_marker_labels`], from the labels' laid-out widths). Painted
/// over the plot by the transform the plot was drawn with: as plot items
/// placed by the transform of the frame before, they overlapped in the
/// frame drawn after a zoom out.
fn marker_labels(
    ui: &Ui,
    t: &egui_plot::PlotTransform,
    excitation: &[(u32, f64)],
    modal: &[f64],
    log: bool,
    top: f64,
) {
    let font = egui::TextStyle::Small.resolve(ui.style());
    let texts: Vec<(usize, f64, String, Color32)> = excitation
        .iter()
        .map(|&(n, f)| {
            let label = if n == 1 {
                format!("V/λ {f:.0} Hz")
            } else {
                format!("{n}V/λ")
            };
            (0, f, label, EXCITATION_COLOR)
        })
        .chain(
            modal
                .iter()
                .enumerate()
                .map(|(k, &f)| (1, f, format!("f{k}"), MODE_COLOR)),
        )
        .collect();
    let galleys: Vec<_> = texts
        .iter()
        .map(|(_, _, s, c)| ui.painter().layout_no_wrap(s.clone(), font.clone(), *c))
        .collect();
    let frame = *t.frame();
    let boxes: Vec<(usize, f32, f32)> = texts
        .iter()
        .zip(&galleys)
        .map(|((row, f, _, _), g)| (*row, t.position_from_point_x(fx(*f, log)), g.size().x))
        .collect();
    let row_px = label_row_px(ui);
    let top_px = t.position_from_point_y(top);
    let painter = ui.painter_at(frame);
    for ((g, (_, _, _, c)), rect) in galleys.into_iter().zip(&texts).zip(place_marker_labels(
        &boxes,
        top_px,
        row_px,
        frame.right(),
    )) {
        if let Some(rect) = rect.filter(|r| frame.contains(r.left_top())) {
            painter.galley(rect.min, g, *c);
        }
    }
}

/// The indices of the points ticked in `shown`.
fn shown_indices(shown: &[bool]) -> Vec<usize> {
    (0..shown.len()).filter(|&i| shown[i]).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Labelled marks (those egui_plot labels: >= 20 px apart) of a level
    /// axis over `bounds` drawn `px` high.
    fn labelled(bounds: (f64, f64), px: f64) -> Vec<f64> {
        let base_step_size = 8.0 * (bounds.1 - bounds.0) / px;
        db_marks(egui_plot::GridInput {
            bounds,
            base_step_size,
        })
        .into_iter()
        .filter(|m| m.step_size * px / (bounds.1 - bounds.0) > 20.0)
        .map(|m| m.value)
        .collect()
    }

    #[test]
    fn level_axes_get_several_labels_at_round_decibels() {
        // the force and displacement axes of the paper preset's spectra
        for (bounds, px) in [((-55.0, 52.0), 180.0), ((-175.0, -55.0), 180.0)] {
            let l = labelled(bounds, px);
            assert!(l.len() >= 4, "{bounds:?} at {px} px: {l:?}");
            assert!(l.iter().all(|v| v % 10.0 == 0.0), "{l:?}");
            assert!(l.iter().all(|v| *v >= bounds.0 && *v <= bounds.1));
        }
        // the labelled step (>= 30 px) is 10 or 20 dB over 120 dB at plot heights 180..400 px
        for px in [180.0, 250.0, 300.0, 400.0] {
            let bounds = (-60.0, 60.0);
            let marks = db_marks(egui_plot::GridInput {
                bounds,
                base_step_size: 8.0 * 120.0 / px,
            });
            let major = marks.iter().map(|m| m.step_size).fold(0.0, f64::max);
            assert!(major == 10.0 || major == 20.0, "{px} px: {major} dB");
            assert!(major * px / 120.0 >= DB_LABEL_PX);
        }
        // squeezed or zoomed in: coarser / finer, never empty
        assert!(!labelled((-200.0, 100.0), 60.0).is_empty());
        assert!(labelled((-3.0, 3.0), 200.0).len() >= 4);
        assert!(
            db_marks(egui_plot::GridInput {
                bounds: (f64::NEG_INFINITY, 0.0),
                base_step_size: 1.0
            })
            .is_empty()
        );
    }

    #[test]
    fn log_labels_at_1_2_5() {
        assert_eq!(log_label(2.0), "100");
        assert_eq!(log_label(2.0f64.log10() + 2.0), "200");
        assert_eq!(log_label(3.0f64.log10() + 2.0), "");
    }
}
