//! Headless PNG figures (plotters, bitmap backend, font from
//! `epaint_default_fonts`): stacked panels of line or marker series, each
//! with a title, axis labels with units, and a legend.

use plotters::prelude::*;
use std::path::Path;
use std::sync::Once;

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Style {
    Line,
    /// A one-pixel line: for dense, spiky data (spectra), where wide
    /// polylines overshoot at sharp peaks.
    ThinLine,
    /// A line with a filled circle of the given radius (px) at each point.
    LineMarkers(u32),
    /// Filled circles of the given radius (px).
    Markers(u32),
    /// Hollow circles of the given radius (px).
    HollowMarkers(u32),
}

/// One named series of `(x, y)` points (an empty name: no legend entry).
#[derive(Debug, Clone)]
pub struct Series {
    pub name: String,
    pub points: Vec<(f64, f64)>,
    pub style: Style,
    /// Colour index into the palette (`None`: by position).
    pub color: Option<usize>,
}

impl Series {
    pub fn line(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series {
            name: name.into(),
            points,
            style: Style::Line,
            color: None,
        }
    }
}

/// One chart panel.
#[derive(Debug, Clone, Default)]
pub struct Panel {
    pub title: String,
    /// Axis labels, with units, e.g. `"time (s)"`.
    pub x_label: String,
    pub y_label: String,
    pub series: Vec<Series>,
    pub log_x: bool,
    pub log_y: bool,
    /// Names of categorical y values `0, 1, 2, …` (e.g. one lane per
    /// point): the y axis is labelled with these at the integers instead of
    /// numbers. Empty: numeric ticks.
    pub y_names: Vec<String>,
}

/// A figure: a title, an optional subtitle line (scene parameters), panels
/// stacked top to bottom.
#[derive(Debug, Clone, Default)]
pub struct Figure {
    pub title: String,
    pub subtitle: String,
    pub panels: Vec<Panel>,
}

/// Errors of figure rendering.
#[derive(Debug, thiserror::Error)]
pub enum FigureError {
    #[error("cannot draw figure {path}: {message}")]
    Draw { path: String, message: String },
    #[error("figure size {width}x{height} px: expected 200..=8000 px per side")]
    Size { width: u32, height: u32 },
}

/// A colour-blind-friendly palette (Okabe-Ito, then a few more).
pub const PALETTE: [RGBColor; 10] = [
    RGBColor(0, 114, 178),
    RGBColor(213, 94, 0),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(230, 159, 0),
    RGBColor(86, 180, 233),
    RGBColor(0, 0, 0),
    RGBColor(240, 228, 66),
    RGBColor(128, 128, 128),
    RGBColor(140, 86, 75),
];

pub(crate) fn register_fonts() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        // The embedded font is valid; a failure would only lose text.
        let _ = plotters::style::register_font(
            "sans-serif",
            FontStyle::Normal,
            epaint_default_fonts::UBUNTU_LIGHT,
        );
        let _ = plotters::style::register_font(
            "sans-serif",
            FontStyle::Bold,
            epaint_default_fonts::UBUNTU_LIGHT,
        );
    });
}

fn range(vals: impl Iterator<Item = f64>, log: bool) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in vals {
        if v.is_finite() && (!log || v > 0.0) {
            lo = lo.min(v);
            hi = hi.max(v);
        }
    }
    if !lo.is_finite() {
        return if log { (1e-3, 1.0) } else { (0.0, 1.0) };
    }
    if log {
        if hi <= lo {
            return (lo / 2.0, hi * 2.0);
        }
        let f = (hi / lo).powf(0.04);
        return (lo / f, hi * f);
    }
    if hi <= lo {
        let d = if lo == 0.0 { 1.0 } else { lo.abs() * 0.1 };
        return (lo - d, hi + d);
    }
    let pad = 0.04 * (hi - lo);
    (lo - pad, hi + pad)
}

/// The label of a categorical y tick at `v`: `names[k]` where `v` is the
/// integer `k`, nothing between (see [`Panel::y_names`]).
pub fn name_tick_label(v: f64, names: &[String]) -> String {
    let k = v.round();
    if (v - k).abs() > 1e-6 || k < 0.0 {
        return String::new();
    }
    names.get(k as usize).cloned().unwrap_or_default()
}

/// A compact tick label: `1e-5` on log axes, `90000`, `0.25`, `1.5e-7` otherwise.
pub fn tick_label(v: f64, log: bool) -> String {
    if v == 0.0 {
        return "0".into();
    }
    let a = v.abs();
    if log || !(1e-3..1e6).contains(&a) {
        let s = format!("{v:.1e}");
        return s.replace(".0e", "e");
    }
    let s = format!("{v:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    s.to_string()
}

/// Renders `fig` as a PNG of `width × height` px at `path`.
pub fn render_png(fig: &Figure, path: &Path, width: u32, height: u32) -> Result<(), FigureError> {
    if !(200..=8000).contains(&width) || !(200..=8000).contains(&height) {
        return Err(FigureError::Size { width, height });
    }
    register_fonts();
    let err = |e: &dyn std::fmt::Display| FigureError::Draw {
        path: path.display().to_string(),
        message: e.to_string(),
    };
    let root = BitMapBackend::new(path, (width, height)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| err(&e))?;
    let scale = (height.min(width) as f64 / 800.0).clamp(0.6, 3.0);
    let fs = |s: f64| (s * scale).round() as i32;
    let mut top = fs(10.0);
    root.draw(&Text::new(
        fig.title.clone(),
        (fs(12.0), top),
        ("sans-serif", fs(24.0)).into_font().color(&BLACK),
    ))
    .map_err(|e| err(&e))?;
    top += fs(30.0);
    if !fig.subtitle.is_empty() {
        root.draw(&Text::new(
            fig.subtitle.clone(),
            (fs(12.0), top),
            ("sans-serif", fs(15.0))
                .into_font()
                .color(&RGBColor(70, 70, 70)),
        ))
        .map_err(|e| err(&e))?;
        top += fs(22.0);
    }
    let body = root.margin(top as u32, 0, 0, 0);
    let n = fig.panels.len().max(1);
    let areas = body.split_evenly((n, 1));
    for (panel, area) in fig.panels.iter().zip(areas.iter()) {
        draw_panel(panel, area, scale).map_err(|e| err(&e))?;
    }
    root.present().map_err(|e| err(&e))?;
    Ok(())
}

/// The x and y ranges of all the panel's points (on log axes, of the
/// positive ones).
fn data_ranges(panel: &Panel) -> ((f64, f64), (f64, f64)) {
    let points = || panel.series.iter().flat_map(|s| s.points.iter());
    (
        range(points().map(|p| p.0), panel.log_x),
        range(points().map(|p| p.1), panel.log_y),
    )
}

/// The corner of the panel with the fewest data points under a legend-sized
/// box (a quarter of the width; `entry_frac` of the plot height per entry);
/// upper right on ties.
fn legend_corner(panel: &Panel, entry_frac: f64) -> SeriesLabelPosition {
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
    for s in &panel.series {
        for p in &s.points {
            let (x, y) = (norm(p.0, xs, panel.log_x), norm(p.1, ys, panel.log_y));
            if !(x.is_finite() && y.is_finite()) {
                continue;
            }
            for (c, &(_, right, upper)) in counts.iter_mut().zip(&corners) {
                let in_x = if right { x > 0.75 } else { x < 0.25 };
                let in_y = if upper { y > 1.0 - h } else { y < h };
                *c += usize::from(in_x && in_y);
            }
        }
    }
    let best = (0..4).min_by_key(|&k| (counts[k], k)).unwrap_or(0);
    corners
        .into_iter()
        .nth(best)
        .map_or(SeriesLabelPosition::UpperRight, |c| c.0)
}

fn draw_panel(
    panel: &Panel,
    area: &DrawingArea<BitMapBackend<'_>, plotters::coord::Shift>,
    scale: f64,
) -> Result<(), Box<dyn std::error::Error>> {
    let fs = |s: f64| (s * scale).round() as u32;
    let (xs, ys) = data_ranges(panel);
    // legend entry height over the plot's height (caption, axis area, margins off)
    let area_h = f64::from(area.dim_in_pixel().1);
    let plot_h = (area_h - f64::from(fs(45.0) + fs(27.0) + 2 * fs(10.0))).max(1.0);
    let entry_frac = 1.6 * f64::from(fs(14.0)) / plot_h;
    let mut builder = ChartBuilder::on(area);
    builder
        .caption(&panel.title, ("sans-serif", fs(18.0) as i32))
        .margin(fs(10.0))
        .x_label_area_size(fs(45.0))
        .y_label_area_size(fs(85.0));
    macro_rules! finish {
        ($chart:expr) => {{
            let mut chart = $chart;
            let (lx, ly) = (panel.log_x, panel.log_y);
            let fx = move |v: &f64| tick_label(*v, lx);
            let names = &panel.y_names;
            let fy = move |v: &f64| {
                if names.is_empty() {
                    tick_label(*v, ly)
                } else {
                    name_tick_label(*v, names)
                }
            };
            // categorical: one tick per name (plotters picks nice values,
            // the integers among them for this count); numeric: at most one
            // label per 2.5 label heights (ten crowded a short panel)
            let y_ticks = if names.is_empty() {
                ((plot_h / (2.5 * f64::from(fs(14.0)))) as usize).clamp(3, 10)
            } else {
                names.len() + 1
            };
            chart
                .configure_mesh()
                .x_label_formatter(&fx)
                .y_label_formatter(&fy)
                .y_labels(y_ticks)
                .x_desc(panel.x_label.as_str())
                .y_desc(panel.y_label.as_str())
                .label_style(("sans-serif", fs(14.0) as i32))
                .axis_desc_style(("sans-serif", fs(16.0) as i32))
                .light_line_style(RGBColor(235, 235, 235))
                .draw()?;
            for (k, s) in panel.series.iter().enumerate() {
                let c = PALETTE[s.color.unwrap_or(k) % PALETTE.len()];
                let pts = s
                    .points
                    .iter()
                    .copied()
                    .filter(|p| p.0.is_finite() && p.1.is_finite());
                let stroke = (scale * 1.6).max(1.0) as u32;
                let stroke = if s.style == Style::ThinLine {
                    1
                } else {
                    stroke
                };
                match s.style {
                    Style::Line | Style::ThinLine => {
                        let anno =
                            chart.draw_series(LineSeries::new(pts, c.stroke_width(stroke)))?;
                        if !s.name.is_empty() {
                            anno.label(s.name.clone()).legend(move |(x, y)| {
                                PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(stroke))
                            });
                        }
                    }
                    Style::LineMarkers(r) => {
                        let pts: Vec<(f64, f64)> = pts.collect();
                        chart.draw_series(pts.iter().map(|&p| Circle::new(p, r, c.filled())))?;
                        let anno =
                            chart.draw_series(LineSeries::new(pts, c.stroke_width(stroke)))?;
                        if !s.name.is_empty() {
                            anno.label(s.name.clone()).legend(move |(x, y)| {
                                PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(stroke))
                            });
                        }
                    }
                    Style::Markers(r) | Style::HollowMarkers(r) => {
                        let filled = matches!(s.style, Style::Markers(_));
                        let style = if filled {
                            c.filled()
                        } else {
                            c.stroke_width(1)
                        };
                        let anno = chart.draw_series(pts.map(move |p| Circle::new(p, r, style)))?;
                        if !s.name.is_empty() {
                            anno.label(s.name.clone())
                                .legend(move |(x, y)| Circle::new((x + 10, y), r, style));
                        }
                    }
                }
            }
            if panel.series.iter().any(|s| !s.name.is_empty()) {
                chart
                    .configure_series_labels()
                    .background_style(WHITE.mix(0.85))
                    .border_style(RGBColor(180, 180, 180))
                    .label_font(("sans-serif", fs(14.0) as i32))
                    .position(legend_corner(panel, entry_frac))
                    .draw()?;
            }
        }};
    }
    match (panel.log_x, panel.log_y) {
        (false, false) => finish!(builder.build_cartesian_2d(xs.0..xs.1, ys.0..ys.1)?),
        (true, false) => finish!(builder.build_cartesian_2d((xs.0..xs.1).log_scale(), ys.0..ys.1)?),
        (false, true) => finish!(builder.build_cartesian_2d(xs.0..xs.1, (ys.0..ys.1).log_scale())?),
        (true, true) => {
            finish!(builder.build_cartesian_2d((xs.0..xs.1).log_scale(), (ys.0..ys.1).log_scale())?)
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn renders_a_png_of_the_requested_size() {
        let dir = std::env::temp_dir().join(format!("tc-fig-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("f.png");
        let fig = Figure {
            title: "test".into(),
            subtitle: "a = 1".into(),
            panels: vec![Panel {
                title: "sine".into(),
                x_label: "time (s)".into(),
                y_label: "u (mm)".into(),
                series: vec![Series::line(
                    "u0",
                    (0..100)
                        .map(|k| (k as f64, (k as f64 * 0.1).sin()))
                        .collect(),
                )],
                ..Panel::default()
            }],
        };
        render_png(&fig, &path, 640, 400).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        assert_eq!(&bytes[1..4], b"PNG");
        // IHDR width and height
        let w = u32::from_be_bytes(bytes[16..20].try_into().unwrap());
        let h = u32::from_be_bytes(bytes[20..24].try_into().unwrap());
        assert_eq!((w, h), (640, 400));
        assert!(render_png(&fig, &path, 10, 400).is_err());
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn categorical_ticks_name_the_integers_only() {
        let names: Vec<String> = (0..5).map(|k| format!("p{k}")).collect();
        assert_eq!(name_tick_label(0.0, &names), "p0");
        assert_eq!(name_tick_label(3.0000000001, &names), "p3");
        assert_eq!(name_tick_label(4.0, &names), "p4");
        for v in [0.5, 2.3, -1.0, 5.0, 7.0] {
            assert_eq!(name_tick_label(v, &names), "", "at {v}");
        }
    }
}
