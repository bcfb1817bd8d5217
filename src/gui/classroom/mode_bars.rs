//! The mode bars of classroom mode: each mode's part of the chosen point's
//! displacement, with mute and solo per mode.

use super::{Classroom, point_picker};
use crate::Simulation;
use crate::base::modal::Mode;
use crate::gui::model::command::Command;
use crate::gui::model::mute_set::Mutes;
use crate::gui::views::XTitle;
use crate::gui::views::scene_view;
use egui::{Color32, RichText, Ui};
use egui_plot::{Bar, BarChart, Corner, Legend, Plot};

/// Plot id of the mode bars (its frame is read by the tests).
pub const MODE_BARS_PLOT_ID: &str = "tirecontact.mode_bars";
/// Vertical axis label of the mode bars.
pub const MODE_BARS_Y_LABEL: &str = "part of u (mm)";

/// Per-mode contribution bars of the chosen point, with mute and solo.
pub fn mode_bars(
    ui: &mut Ui,
    sim: &Simulation,
    modes: &[Mode],
    mutes: Option<&Mutes>,
    cls: &mut Classroom,
    cmds: &mut Vec<Command>,
) {
    ui.label(RichText::new("Mode contributions").strong());
    point_picker(ui, cls, sim.num_points());
    let i = cls.point;
    let mut c = vec![0.0; sim.num_modes()];
    let n = c.len();
    sim.mode_displacement_m(i, &mut c);
    let u = sim.displacement_m().get(i).copied().unwrap_or(0.0);
    ui.label(format!(
        "point {i}: u = {:+.3} mm = sum of the bars",
        u * 1e3
    ));
    let muted = |k: usize| mutes.is_some_and(|m| m.muted.get(k).copied().unwrap_or(false));
    let bars: Vec<Bar> = c
        .iter()
        .enumerate()
        .map(|(k, v)| {
            let color = mode_bar_color(ui.visuals(), muted(k));
            Bar::new(k as f64, v * 1e3)
                .width(0.7)
                .fill(color)
                .name(format!("mode {k}"))
        })
        .collect();
    let labels: Vec<String> = modes
        .iter()
        .enumerate()
        .map(|(k, m)| format!("{k}: {:.0} Hz", m.freq_hz))
        .collect();
    let bar_key = mode_bar_color(ui.visuals(), false);
    let ymax = c.iter().fold(1e-3f64, |a, v| a.max(v.abs() * 1e3)) * 1.1;
    let row = ui.spacing().interact_size.y + ui.spacing().item_spacing.y;
    // the vertical axis label is centred on the plot frame: a frame shorter
    // than the label let it run up over the "point i: u = …" line
    let label_w = mode_bars_label_w(ui);
    // a refused mute's line under the plot takes a row
    let note = if cls.mute_refused.is_some() { 1.0 } else { 0.0 };
    let one_line = rows_fit_one_line(ui, &c, modes, mutes);
    let per_mode = if one_line { 1.0 } else { TWO_LINE_ROWS };
    let h = (ui.available_height() - row * (per_mode * n as f32 + 1.2 + note))
        .max(bars_plot_min_px(ui, label_w));
    Plot::new("tirecontact.mode_bars")
        .id(egui::Id::unique(MODE_BARS_PLOT_ID))
        .height(h)
        .legend(Legend::default().position(Corner::RightBottom))
        .x_title(ui, "mode")
        .y_axis_label(MODE_BARS_Y_LABEL)
        .x_axis_formatter(move |m, _| {
            let k = m.value.round();
            if (m.value - k).abs() < 1e-6 && k >= 0.0 && (k as usize) < labels.len() {
                labels[k as usize].clone()
            } else {
                String::new()
            }
        })
        .include_x(-0.6)
        .include_x(n as f64 - 0.4)
        .include_y(-ymax)
        .include_y(ymax)
        .y_grid_spacer(|g| {
            // about three labelled marks at 1-2-5 steps (mm): large text
            // needs room between labels
            let (a, b) = g.bounds;
            let step = scene_view::round_125((b - a) / 3.0);
            let mut out = Vec::new();
            let mut k = (a / step).ceil();
            while k * step <= b && out.len() < 50 {
                out.push(egui_plot::GridMark {
                    value: k * step,
                    step_size: step,
                });
                k += 1.0;
            }
            out
        })
        .y_axis_formatter(|m, _| crate::gui::widgets::number::format_number(m.value))
        .allow_scroll(false)
        .allow_drag(false)
        .allow_zoom(false)
        .show(ui, |pui| {
            pui.bar_chart(BarChart::new("now (mm)", bars).color(bar_key));
        });
    if let Some(r) = &cls.mute_refused {
        refusal_note(ui, r, cmds);
    }
    // many modes in a short panel: the rows scroll under the plot; where
    // not even two of them would show (a small window, the plot at its
    // least height) they follow it, and the panel scrolls (`mode_bars_panel`)
    let shown = row * per_mode * (n.min(2) as f32);
    if ui.available_height() >= shown {
        egui::ScrollArea::vertical()
            .id_salt("tirecontact.mode_mutes_scroll")
            .show(ui, |ui| mute_rows(ui, &c, modes, mutes, one_line, cmds));
    } else {
        mute_rows(ui, &c, modes, mutes, one_line, cmds);
    }
}

/// The contents of a panel holding the mode bars (`add`) in a vertical
/// scroll area: in a window too short for the bars' plot at its least
/// height and their Mute/Solo rows, the rows are reached by scrolling
/// instead of lying below the window's edge.
pub fn mode_bars_panel<R>(ui: &mut Ui, add: impl FnOnce(&mut Ui) -> R) -> R {
    egui::ScrollArea::vertical()
        .id_salt("tirecontact.mode_bars_panel_scroll")
        .auto_shrink([false, true])
        .show(ui, add)
        .inner
}

/// Rows (of Mute/Solo height) a mode takes when its row is split in two:
/// the frequency and part of u, then Mute and Solo, and a separator.
const TWO_LINE_ROWS: f32 = 2.4;

/// Whether a mode's frequency, part of u, Mute and Solo fit on one row of
/// the panel's width; else each mode takes two (a narrow panel: at
/// 720 × 600 the Solo buttons ran past the window's right edge).
fn rows_fit_one_line(ui: &Ui, c: &[f64], modes: &[Mode], mutes: Option<&Mutes>) -> bool {
    let body = egui::TextStyle::Body.resolve(ui.style());
    let text_w = |s: String| {
        ui.painter()
            .layout_no_wrap(s, body.clone(), Color32::WHITE)
            .size()
            .x
    };
    let sp = ui.spacing();
    let col_min = sp.interact_size.x;
    let mut label_w: f32 = 0.0;
    let mut value_w: f32 = 0.0;
    for (k, v) in c.iter().enumerate() {
        let f = modes.get(k).map_or(0.0, |m| m.freq_hz);
        label_w = label_w.max(text_w(format!("{k}: {f:.0} Hz")));
        value_w = value_w.max(text_w(format!("{:+.3} mm", v * 1e3)));
    }
    if mutes.is_some() {
        // "muted" is strong: a little wider than its body width
        value_w = value_w.max(text_w("muted".to_owned()) * 1.1);
    }
    let button_w =
        text_w("Mute".to_owned()).max(text_w("Solo".to_owned())) + 2.0 * sp.button_padding.x;
    let need = label_w.max(col_min)
        + value_w.max(col_min)
        + 2.0 * button_w.max(col_min)
        + 3.0 * sp.item_spacing.x;
    need <= ui.available_width()
}

/// Fill of a mode's bar: the theme's strong text colour, grey when muted.
/// Not a point's colour: beside the coloured point picker, mode k in point
/// k+1's colour read as that point's bar.
pub fn mode_bar_color(visuals: &egui::Visuals, muted: bool) -> Color32 {
    if muted {
        Color32::GRAY
    } else {
        visuals.strong_text_color()
    }
}

/// One row per mode: its frequency, its part of u, Mute and Solo.
fn mute_rows(
    ui: &mut Ui,
    c: &[f64],
    modes: &[Mode],
    mutes: Option<&Mutes>,
    one_line: bool,
    cmds: &mut Vec<Command>,
) {
    let muted = |k: usize| mutes.is_some_and(|m| m.muted.get(k).copied().unwrap_or(false));
    let text = |ui: &mut Ui, k: usize, v: f64| {
        let f = modes.get(k).map_or(0.0, |m| m.freq_hz);
        ui.label(format!("{k}: {f:.0} Hz"));
        if muted(k) {
            ui.label(RichText::new("muted").color(Color32::GRAY).strong());
        } else {
            ui.label(format!("{:+.3} mm", v * 1e3));
        }
    };
    let buttons = |ui: &mut Ui, k: usize, cmds: &mut Vec<Command>| {
        let m = ui
            .selectable_label(muted(k), "Mute")
            .on_hover_text("remove this mode's contribution (residue × 0); restarts the run; click again to bring it back");
        if m.clicked() {
            cmds.push(Command::ToggleMute(k));
        }
        let soloed =
            mutes.is_some_and(|ms| ms.muted.iter().enumerate().all(|(j, x)| *x == (j != k)));
        let s = ui
            .selectable_label(soloed, "Solo")
            .on_hover_text("mute every other mode; click again to bring them back");
        if s.clicked() {
            cmds.push(Command::SoloMode(k));
        }
    };
    if one_line {
        egui::Grid::new("tirecontact.mode_mutes")
            .striped(true)
            .num_columns(4)
            .show(ui, |ui| {
                for (k, v) in c.iter().enumerate() {
                    text(ui, k, *v);
                    buttons(ui, k, cmds);
                    ui.end_row();
                }
            });
    } else {
        // a narrow panel: the mode's figures, then its buttons below them
        for (k, v) in c.iter().enumerate() {
            if k > 0 {
                ui.separator();
            }
            ui.horizontal_wrapped(|ui| text(ui, k, *v));
            ui.horizontal_wrapped(|ui| buttons(ui, k, cmds));
        }
    }
    if mutes.is_some() && ui.button("Un-mute all").clicked() {
        cmds.push(Command::UnmuteAll);
    }
}

/// A refused mute or solo, where it was asked: a short line (the banner
/// says why) and the ways out (compliant contact, or keeping the modes
/// playing), in as little height as the rows below can spare.
fn refusal_note(ui: &mut Ui, r: &crate::gui::classroom::MuteRefusal, cmds: &mut Vec<Command>) {
    ui.horizontal_wrapped(|ui| {
        let what = if r.solo { "Solo" } else { "Mute" };
        ui.label(
            RichText::new(format!("{what} {} refused:", r.mode))
                .color(crate::gui::widgets::fields::ERROR_COLOR),
        )
        .on_hover_text(r.text.as_str());
        if r.rigid
            && ui
                .small_button("Use compliant contact")
                .on_hover_text("a tread spring at each point (2 kN/mm), then the mute or solo; restarts the run")
                .clicked()
        {
            cmds.push(Command::MuteWithCompliantContact);
        }
        if ui.small_button("Keep the modes playing").clicked() {
            cmds.push(Command::DismissMuteRefusal);
        }
    });
}

/// Least height (px) of the mode bars' plot: its y label (`label_w` px
/// long, drawn vertically) beside the frame, and the x axis below it.
fn bars_plot_min_px(ui: &Ui, label_w: f32) -> f32 {
    // the x axis below the frame: tick labels and the axis label
    let x_axis_h = 3.0 * ui.text_style_height(&egui::TextStyle::Body);
    (label_w + x_axis_h + 16.0).max(150.0)
}

/// Width (px) of the mode bars' vertical axis label in body text.
fn mode_bars_label_w(ui: &Ui) -> f32 {
    let body = egui::TextStyle::Body.resolve(ui.style());
    ui.painter()
        .layout_no_wrap(MODE_BARS_Y_LABEL.to_owned(), body, Color32::WHITE)
        .size()
        .x
}

/// Rows of the modes' Mute/Solo list kept in view below the bars; more
/// scroll (reserving a row for each of the paper's 13 modes left its
/// description two lines at 1280 × 720).
pub const MUTE_ROWS_SHOWN: usize = 3;

/// Height (px) the mode bars need below the description: their heading,
/// point picker and sum line, the plot at its least height and a row per
/// mode, up to `MUTE_ROWS_SHOWN` (`mode_bars` then fits the plot to the
/// rest).
pub fn mode_bars_min_px(ui: &Ui, num_modes: usize) -> f32 {
    let label_w = mode_bars_label_w(ui);
    let row = ui.spacing().interact_size.y + ui.spacing().item_spacing.y;
    bars_plot_min_px(ui, label_w) + row * (num_modes.min(MUTE_ROWS_SHOWN) as f32 + 4.2)
}
