//! Figure legends: the corner with the fewest data points under the box,
//! its size, the keys (a line or a dot per series) and their strokes.

use super::*;

/// The corner of the panel with the fewest data points under a legend-sized
/// box (a quarter of the width; `entry_frac` of the plot height per entry),
/// upper right on ties, and how many points are under it. The lines drawn
/// between a series' points count too (samples along each segment): a line
/// crossing a corner between two points outside it is data under a legend.
pub(super) fn legend_corner(panel: &Panel, entry_frac: f64) -> (SeriesLabelPosition, usize) {
    let (xs, ys) = data_ranges(panel);
    let norm = |v: f64, (lo, hi): (f64, f64), log: bool| {
        if log {
            (v.ln() - lo.ln()) / (hi.ln() - lo.ln())
        } else {
            (v - lo) / (hi - lo)
        }
    };
    let corners = [
        (SeriesLabelPosition::UpperRight, true, true),
        (SeriesLabelPosition::UpperLeft, false, true),
        (SeriesLabelPosition::LowerRight, true, false),
        (SeriesLabelPosition::LowerLeft, false, false),
    ];
    let entries = panel.series.iter().filter(|s| !s.name.is_empty()).count();
    let h = (entry_frac * (entries as f64 + 0.5)).min(0.95);
    let mut counts = [0usize; 4];
    let mut count = |x: f64, y: f64| {
        for (c, &(_, right, upper)) in counts.iter_mut().zip(&corners) {
            let in_x = if right { x > 0.75 } else { x < 0.25 };
            let in_y = if upper { y > 1.0 - h } else { y < h };
            *c += usize::from(in_x && in_y);
        }
    };
    // samples per segment of a drawn line (its points are counted apart)
    const SEGMENT_SAMPLES: usize = 16;
    for s in &panel.series {
        let lined = matches!(
            s.style,
            Style::Line | Style::ThinLine | Style::LineMarkers(_)
        );
        let mut last: Option<(f64, f64)> = None;
        for p in &s.points {
            let (x, y) = (norm(p.0, xs, panel.log_x), norm(p.1, ys, panel.log_y));
            if !(x.is_finite() && y.is_finite()) {
                last = None;
                continue;
            }
            count(x, y);
            if let Some((x0, y0)) = last.filter(|_| lined) {
                for k in 1..SEGMENT_SAMPLES {
                    let f = k as f64 / SEGMENT_SAMPLES as f64;
                    count(x0 + f * (x - x0), y0 + f * (y - y0));
                }
            }
            last = Some((x, y));
        }
    }
    let best = (0..4).min_by_key(|&k| (counts[k], k)).unwrap_or(0);
    let corner = corners
        .into_iter()
        .nth(best)
        .map_or(SeriesLabelPosition::UpperRight, |c| c.0);
    (corner, counts[best])
}

/// A legend entry drawn by [`draw_legend`]: name, colour, style, stroke (px).
type LegendEntry = (String, RGBColor, Style, u32);

/// Size (px) of the legend box of `entries` in `font_px` text: a row of
/// 1.6 text heights per entry, a 20 px key, 8 px gaps and padding.
pub(super) fn legend_size(
    area: &DrawingArea<FigureBackend<'_>, plotters::coord::Shift>,
    entries: &[LegendEntry],
    font_px: u32,
) -> (i32, i32) {
    let font = ("sans-serif", font_px as i32).into_font().color(&BLACK);
    let text_w = entries
        .iter()
        .map(|e| {
            area.estimate_text_size(&e.0, &font)
                .map_or(e.0.chars().count() as u32 * font_px, |s| s.0)
        })
        .max()
        .unwrap_or(0);
    (
        text_w as i32 + 20 + 3 * 8,
        legend_height(entries.len(), font_px),
    )
}

/// Height (px) of a legend box of `entries` rows in `font_px` text (as
/// [`legend_size`] lays it out).
pub(super) fn legend_height(entries: usize, font_px: u32) -> i32 {
    (1.6 * f64::from(font_px)).round() as i32 * entries as i32 + 2 * 6
}

/// The least font size (px) a legend is shrunk to.
pub(super) const LEGEND_MIN_FONT_PX: u32 = 7;

/// The font size (px) of a legend of `entries` rows: `font_px`, or the
/// largest smaller size whose box fits in `room_px` (at least
/// [`LEGEND_MIN_FONT_PX`]).
pub(super) fn fitted_legend_font(entries: usize, font_px: u32, room_px: i32) -> u32 {
    (LEGEND_MIN_FONT_PX..=font_px.max(LEGEND_MIN_FONT_PX))
        .rev()
        .find(|&f| legend_height(entries, f) <= room_px)
        .unwrap_or(LEGEND_MIN_FONT_PX)
}

/// Draws the legend box of `entries` with its top left at `(x, y)` of `area`.
pub(super) fn draw_legend(
    area: &DrawingArea<FigureBackend<'_>, plotters::coord::Shift>,
    entries: &[LegendEntry],
    (x, y): (i32, i32),
    (w, h): (i32, i32),
    font_px: u32,
) -> Result<(), Box<dyn std::error::Error>> {
    area.draw(&Rectangle::new([(x, y), (x + w, y + h)], WHITE.filled()))?;
    area.draw(&Rectangle::new(
        [(x, y), (x + w, y + h)],
        RGBColor(180, 180, 180).stroke_width(1),
    ))?;
    let font = ("sans-serif", font_px as i32).into_font().color(&BLACK);
    let row = (1.6 * f64::from(font_px)).round() as i32;
    for (k, (name, c, style, stroke)) in entries.iter().enumerate() {
        let top = y + 6 + row * k as i32;
        let mid = top + row / 2;
        let key_x = x + 8;
        area.draw(&key_element(*style, *c, *stroke, (key_x, mid)))?;
        let text_h = font_px as i32;
        area.draw(&Text::new(
            name.clone(),
            (key_x + 28, mid - text_h / 2),
            font.clone(),
        ))?;
    }
    Ok(())
}

/// How `s` is keyed in its legend: as drawn, except that a line with
/// markers through a single point (no line drawn, one dot) is keyed by its
/// marker alone.
pub(super) fn key_style(s: &Series) -> Style {
    let finite = s
        .points
        .iter()
        .filter(|p| p.0.is_finite() && p.1.is_finite())
        .count();
    match s.style {
        Style::LineMarkers(r) if finite == 1 => Style::Markers(r),
        style => style,
    }
}

/// The width (px) of a line's legend key: at least [`KEY_STROKE_PX`]
/// (the colour of a one-pixel key, 20 px long, was hard to tell).
pub(super) fn key_stroke(stroke: u32) -> u32 {
    stroke.max(KEY_STROKE_PX)
}

/// The least width (px) of a line's legend key.
pub(super) const KEY_STROKE_PX: u32 = 3;

/// The legend key of `style` in colour `c`, 20 px wide, its left end at
/// `(x, y)`: a line, a line with a dot in its middle, or a marker.
pub(super) fn key_element<'a, DB: DrawingBackend + 'a>(
    style: Style,
    c: RGBColor,
    stroke: u32,
    (x, y): (i32, i32),
) -> DynElement<'a, DB, (i32, i32)> {
    let line = move || PathElement::new(vec![(0, 0), (20, 0)], c.stroke_width(key_stroke(stroke)));
    match style {
        Style::Line | Style::ThinLine => (EmptyElement::at((x, y)) + line()).into_dyn(),
        Style::LineMarkers(r) => {
            (EmptyElement::at((x, y)) + line() + Circle::new((10, 0), r, c.filled())).into_dyn()
        }
        Style::Markers(r) => Circle::new((x + 10, y), r, c.filled()).into_dyn(),
        Style::HollowMarkers(r) => Circle::new((x + 10, y), r, c.stroke_width(1)).into_dyn(),
    }
}

/// A panel's legend: its entries, the corner of the plot with the least
/// data under a legend-sized box and how many points are under it, and the
/// legend box's size (px).
pub(super) struct PanelLegend {
    pub(super) entries: Vec<LegendEntry>,
    pub(super) corner: SeriesLabelPosition,
    pub(super) under: usize,
    pub(super) size: (i32, i32),
}

/// The line width (px) of series `s` at `scale`.
pub(super) fn stroke_of(s: &Series, scale: f64) -> u32 {
    if s.style == Style::ThinLine {
        1
    } else {
        (scale * 1.6).max(1.0) as u32
    }
}

/// The height (px) of a panel's caption line at `scale` (none without a
/// title).
pub(super) fn caption_h(panel: &Panel, scale: f64) -> u32 {
    if panel.title.is_empty() {
        0
    } else {
        (27.0 * scale).round() as u32
    }
}

pub(super) fn panel_legend(
    panel: &Panel,
    area: &DrawingArea<FigureBackend<'_>, plotters::coord::Shift>,
    frame: &super::Frame,
) -> PanelLegend {
    let scale = frame.scale;
    let fs = |s: f64| (s * scale).round() as u32;
    // legend entry height over the plot's height
    let plot_h = super::plot_h_of(panel, area, frame);
    let entry_frac = 1.6 * f64::from(fs(14.0)) / plot_h;
    let entries: Vec<LegendEntry> = panel
        .series
        .iter()
        .enumerate()
        .filter(|(_, s)| !s.name.is_empty())
        .map(|(k, s)| {
            let c = series_color(s.color.unwrap_or(k));
            (s.name.clone(), c, key_style(s), stroke_of(s, scale))
        })
        .collect();
    let (corner, under) = legend_corner(panel, entry_frac);
    let size = legend_size(area, &entries, fs(14.0));
    PanelLegend {
        entries,
        corner,
        under,
        size,
    }
}

#[cfg(test)]
mod corner_tests {
    use super::*;

    #[test]
    fn a_legend_shrinks_its_type_to_fit_its_room() {
        // eight entries at 14 px: 8 x 22 + 12 = 188 px
        assert_eq!(legend_height(8, 14), 188);
        assert_eq!(fitted_legend_font(8, 14, 200), 14);
        let f = fitted_legend_font(8, 14, 150);
        assert!(f < 14 && legend_height(8, f) <= 150, "{f}");
        assert!(legend_height(8, f + 1) > 150, "{f}: not the largest");
        // no room at all: the least size, never zero
        assert_eq!(fitted_legend_font(8, 14, 10), LEGEND_MIN_FONT_PX);
    }

    /// A line between two points outside the upper right corner crosses
    /// it: the legend goes to another, empty corner.
    #[test]
    fn a_line_through_a_corner_keeps_the_legend_out_of_it() {
        let series = |name: &str, points: Vec<(f64, f64)>| Series {
            name: name.into(),
            points,
            style: Style::LineMarkers(3),
            color: None,
        };
        let panel = Panel {
            series: vec![
                // through (0.8, 0.9), inside the upper right box
                series("a", vec![(0.6, 1.0), (1.0, 0.8)]),
                // the data's range, clear of every corner
                series("b", vec![(0.0, 0.5), (0.5, 0.0)]),
            ],
            ..Panel::default()
        };
        let (corner, under) = legend_corner(&panel, 0.1);
        assert!(
            !matches!(corner, SeriesLabelPosition::UpperRight),
            "the legend went over the line"
        );
        assert_eq!(under, 0);
    }
}
