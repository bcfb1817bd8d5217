//! The sizes of a figure's panels: where each sits in the stack (its x
//! axis' area, title, margins), the height left to its plot, its y label
//! area and the type scale the panels share.

use super::legend::caption_h;
use super::{FigureBackend, Panel, axis_tick_label, data_ranges, fit_font_px, linear_label_count};
use plotters::prelude::*;

/// How a panel sits in the stack: the text scale, the height (px) of its
/// x axis' label area, whether it carries the x title, its margin above
/// and below (px).
#[derive(Debug, Clone, Copy)]
pub(super) struct Frame {
    pub(super) scale: f64,
    pub(super) x_area: u32,
    pub(super) x_desc: bool,
    pub(super) v_margin: u32,
}

/// What the panels of a figure share: the legend column's width (when the
/// legends are beside the plots), the y label area's width and the type
/// scale.
#[derive(Debug, Clone, Copy)]
pub(super) struct Axes {
    pub(super) column_w: Option<i32>,
    pub(super) y_area: u32,
    pub(super) type_px: TypeScale,
}

/// The height (px) of `panel`'s plot in `area` (estimated: the caption,
/// the x axis' label area and the margins off).
pub(super) fn plot_h_of(
    panel: &Panel,
    area: &DrawingArea<FigureBackend<'_>, plotters::coord::Shift>,
    frame: &Frame,
) -> f64 {
    let area_h = f64::from(area.dim_in_pixel().1);
    let taken = frame.x_area + caption_h(panel, frame.scale) + 2 * frame.v_margin;
    (area_h - f64::from(taken)).max(1.0)
}

/// How many y labels to ask plotters for in a plot `plot_h` px high:
/// categorical, one per name (plotters picks nice values, the integers
/// among them for this count); linear, as many as are 1.8 label heights
/// apart (ten crowded a short panel, three left it with two); log, at most
/// one per 2.5 label heights.
pub(super) fn y_label_count(panel: &Panel, plot_h: f64, scale: f64) -> usize {
    let label_px = (14.0 * scale).round();
    if !panel.y_names.is_empty() {
        panel.y_names.len() + 1
    } else if panel.log_y {
        ((plot_h / (2.5 * label_px)) as usize).clamp(3, 10)
    } else {
        linear_label_count(data_ranges(panel).1, plot_h, 1.8 * label_px)
    }
}

/// How many labels a log x axis `plot_w` px wide takes: at most one per
/// 70 px (× scale; a label such as `2000` is about 30 px wide), 3 to 12.
pub(super) fn x_log_label_count(plot_w: f64, scale: f64) -> usize {
    ((plot_w / (70.0 * scale)) as usize).clamp(3, 12)
}

/// The font size (px) of `panel`'s axis titles: its rotated y title no
/// longer than the plot is high (in a short panel it ran past the plot
/// towards its neighbour's).
pub(super) fn axis_title_px(panel: &Panel, plot_h: f64, scale: f64) -> u32 {
    let fs = |s: f64| (s * scale).round() as u32;
    fit_font_px(&panel.y_label, plot_h as i32, fs(16.0), fs(12.0))
}

/// The width (px) of the area left of `panel`'s plot: its widest y tick
/// label, the tick marks, the rotated y title and gaps; at most the 85 px
/// (× scale) of a log axis, whose labels are not computed here.
pub(super) fn y_area_px(panel: &Panel, plot_h: f64, scale: f64) -> u32 {
    use plotters::coord::ranged1d::{KeyPointHint, Ranged};
    let fs = |s: f64| (s * scale).round() as u32;
    if panel.log_y {
        return fs(85.0);
    }
    let labels: Vec<String> = if panel.y_names.is_empty() {
        let ys = data_ranges(panel).1;
        plotters::coord::types::RangedCoordf64::from(ys.0..ys.1)
            .key_points(y_label_count(panel, plot_h, scale).max_num_points())
            .iter()
            .map(|v| axis_tick_label(*v, false, ys))
            .collect()
    } else {
        panel.y_names.clone()
    };
    let widest = labels
        .iter()
        .map(|t| super::text_width_px(t, fs(14.0)))
        .max()
        .unwrap_or(0);
    let title = if panel.y_label.is_empty() {
        0
    } else {
        (1.5 * f64::from(axis_title_px(panel, plot_h, scale))).round() as u32
    };
    (widest + 5 + fs(8.0) + title + fs(8.0)).min(fs(85.0))
}

/// The font sizes (px) shared by a figure's panels.
#[derive(Debug, Clone, Copy)]
pub(super) struct TypeScale {
    pub(super) caption: u32,
    pub(super) axis_title: u32,
}

/// The largest caption size (px) at which `panel`'s title fits over its
/// chart in `area` (left of the legend column `column_w`, if any), clear
/// of the y-axis title's column on both sides (a long one ran into the
/// rotated y title).
pub(super) fn caption_px(
    panel: &Panel,
    area: &DrawingArea<FigureBackend<'_>, plotters::coord::Shift>,
    column_w: Option<i32>,
    scale: f64,
) -> u32 {
    let fs = |s: f64| (s * scale).round() as u32;
    if panel.title.is_empty() {
        return fs(18.0);
    }
    let w = area.dim_in_pixel().0 as i32;
    let chart_w = column_w.map_or(w, |cw| (w - cw - fs(10.0) as i32).max(w / 2));
    let caption_w = chart_w - 2 * (fs(85.0) + fs(10.0)) as i32;
    fit_font_px(&panel.title, caption_w, fs(18.0), fs(11.0))
}
