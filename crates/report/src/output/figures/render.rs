//! Drawing a [`Figure`] (plotters, bitmap backend, font from
//! `epaint_default_fonts`; feature `figures`).

use super::*;
use plotters::chart::SeriesAnno;
use plotters::coord::ranged1d::ValueFormatter;
use plotters::prelude::*;
use std::path::Path;
#[cfg(not(target_arch = "wasm32"))]
use std::sync::Once;

/// The series colours, point `k` in colour `k`: Okabe-Ito's blue (made
/// darker), vermillion, bluish green, reddish purple and sky blue, then
/// olive, black (also the clipped-impact marks), wine, grey and brown.
/// Okabe-Ito's orange is left out: next to its vermillion, points 1 and 4
/// of a five-point scene read as one orange. Its blue (0, 114, 178) and sky
/// blue were 22 apart in CIEDE2000 (24 in L*), one colour in a small
/// README image; (0, 95, 155) is 31 (L* 39 and 70). Any two of the first
/// eight differ by at least 20 in CIEDE2000, two of one hue by at least 20
/// in lightness, points 0 and 4 by at least 30 (`tests/analysis/palette.rs`). The
/// visualiser's first eight are these with grey for black
/// (`gui::views::PALETTE`).
pub const PALETTE: [RGBColor; 10] = [
    RGBColor(0, 95, 155),
    RGBColor(213, 94, 0),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(86, 180, 233),
    RGBColor(188, 189, 34),
    RGBColor(0, 0, 0),
    RGBColor(136, 34, 85),
    RGBColor(128, 128, 128),
    RGBColor(140, 86, 75),
];

/// The colour of series colour index `index`: the palette's (cycled), or
/// a step of the colour ramp (`super::ramp_index`).
pub fn series_color(index: usize) -> RGBColor {
    match super::ramp_fraction(index) {
        Some(f) => {
            let (r, g, b) = super::ramp_rgb(f);
            RGBColor(r, g, b)
        }
        None => PALETTE[index % PALETTE.len()],
    }
}

pub(crate) fn register_fonts() {
    // in a browser plotters takes its fonts from the page
    #[cfg(not(target_arch = "wasm32"))]
    static ONCE: Once = Once::new();
    #[cfg(not(target_arch = "wasm32"))]
    ONCE.call_once(|| {
        // Ubuntu Light with its glyphs starting at x = 0 (plotters drops
        // side bearings: "1 0" for "10", see font.rs); once per process
        let font: &'static [u8] = font::with_origin_points(epaint_default_fonts::UBUNTU_LIGHT)
            .map_or(epaint_default_fonts::UBUNTU_LIGHT, |f| {
                Box::leak(f.into_boxed_slice())
            });
        // The embedded font is valid; a failure would only lose text.
        let _ = plotters::style::register_font("sans-serif", FontStyle::Normal, font);
        let _ = plotters::style::register_font("sans-serif", FontStyle::Bold, font);
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

/// Width (px) of `text` in the figures' font at `size` px: as plotters
/// measures it on the desktop, as [`GlyphBitmap`] draws it in a browser.
pub(crate) fn text_width_px(text: &str, size: u32) -> u32 {
    #[cfg(target_arch = "wasm32")]
    {
        backend::text_box(text, f64::from(size)).0.max(0) as u32
    }
    #[cfg(not(target_arch = "wasm32"))]
    {
        ("sans-serif", size as i32)
            .into_font()
            .box_size(text)
            .map_or(text.chars().count() as u32 * size / 2, |b| b.0)
    }
}

/// The largest font size from `px` down to `min_px` at which `text` is at
/// most `max_w` pixels wide (`min_px` when none is).
pub fn fit_font_px(text: &str, max_w: i32, px: u32, min_px: u32) -> u32 {
    register_fonts();
    let mut size = px;
    while size > min_px {
        let w = text_width_px(text, size);
        if w as i64 <= i64::from(max_w) {
            break;
        }
        size -= 1;
    }
    size
}

/// How many numeric labels to ask plotters for on a linear axis of
/// `range` drawn `length_px` long: the most (up to 12) whose nice values
/// (plotters' own) are at least `min_gap_px` apart, or, when those are
/// fewer than three, two thirds of that apart. A short panel asked for
/// three got two (`0`, `5000`; one, `500000`, on a range of 0-900000).
pub fn linear_label_count(range: (f64, f64), length_px: f64, min_gap_px: f64) -> usize {
    use plotters::coord::ranged1d::{KeyPointHint, Ranged};
    let span = range.1 - range.0;
    if !(span.is_finite() && span > 0.0 && length_px > 0.0) {
        return 3;
    }
    let axis = plotters::coord::types::RangedCoordf64::from(range.0..range.1);
    let values = |n: usize| axis.key_points(n.max_num_points());
    let most = |gap: f64| {
        (2..=12).rev().find(|&n| {
            values(n)
                .windows(2)
                .all(|w| (w[1] - w[0]).abs() / span * length_px >= gap)
        })
    };
    let n = most(min_gap_px).unwrap_or(2);
    if values(n).len() >= 3 {
        return n;
    }
    most(min_gap_px / 1.5)
        .filter(|&m| values(m).len() >= 3)
        .unwrap_or(n)
}

/// Renders `fig` as a PNG of `width × height` px at `path`.
pub fn render_png(fig: &Figure, path: &Path, width: u32, height: u32) -> Result<(), FigureError> {
    render_png_layout(fig, path, width, height).map(|_| ())
}

/// Where a panel was drawn, in the PNG's pixels (x right, y down).
#[derive(Debug, Clone, Default)]
pub struct PanelLayout {
    /// The plotting area (inside the axes): left, top, right, bottom.
    pub plot_px: [i32; 4],
    /// The legend's box when it is drawn outside the plotting area, at its
    /// right (no corner of the plot was free of data); `None` when it is in
    /// a corner of the plot (plotters' layout) or there is none.
    pub legend_px: Option<[i32; 4]>,
    /// Every series' points as drawn (finite ones), in pixels.
    pub curves_px: Vec<Vec<(i32, i32)>>,
    /// The caption's and the axis titles' font sizes (px): one for all
    /// the figure's panels.
    pub caption_px: u32,
    pub axis_title_px: u32,
}

/// [`render_png`], returning where each panel was drawn.
pub fn render_png_layout(
    fig: &Figure,
    path: &Path,
    width: u32,
    height: u32,
) -> Result<Vec<PanelLayout>, FigureError> {
    check_size(width, height)?;
    let err = |e: &dyn std::fmt::Display| FigureError::Draw {
        path: path.display().to_string(),
        message: e.to_string(),
    };
    #[cfg(target_arch = "wasm32")]
    return {
        let _ = fig;
        Err(err(&"a page in the browser writes no files"))
    };
    #[cfg(not(target_arch = "wasm32"))]
    {
        let root = BitMapBackend::new(path, (width, height)).into_drawing_area();
        let layouts = render_on(fig, &root, width, height).map_err(|e| err(&e))?;
        root.present().map_err(|e| err(&e))?;
        Ok(layouts)
    }
}

/// `fig` as the bytes of a `width × height` PNG file, drawn in memory (the
/// web page offers them as a download; on the desktop [`render_png`] writes
/// the file).
pub fn render_png_bytes(fig: &Figure, width: u32, height: u32) -> Result<Vec<u8>, FigureError> {
    use image::ImageEncoder;
    let (rgb, _) = render_rgb_layout(fig, width, height)?;
    let mut png = Vec::new();
    image::codecs::png::PngEncoder::new(&mut png)
        .write_image(&rgb, width, height, image::ExtendedColorType::Rgb8)
        .map_err(|e| FigureError::Draw {
            path: "(memory)".into(),
            message: e.to_string(),
        })?;
    Ok(png)
}

/// [`render_png_layout`] into memory: the RGB pixels (3 bytes each, rows
/// top to bottom) and where each panel was drawn.
pub fn render_rgb_layout(
    fig: &Figure,
    width: u32,
    height: u32,
) -> Result<(Vec<u8>, Vec<PanelLayout>), FigureError> {
    check_size(width, height)?;
    let err = |e: &dyn std::fmt::Display| FigureError::Draw {
        path: "(memory)".into(),
        message: e.to_string(),
    };
    let mut rgb = vec![0u8; width as usize * height as usize * 3];
    let layouts = {
        let root = FigureBackend::with_buffer(&mut rgb, (width, height)).into_drawing_area();
        let layouts = render_on(fig, &root, width, height).map_err(|e| err(&e))?;
        root.present().map_err(|e| err(&e))?;
        layouts
    };
    Ok((rgb, layouts))
}

fn check_size(width: u32, height: u32) -> Result<(), FigureError> {
    if !(200..=8000).contains(&width) || !(200..=8000).contains(&height) {
        return Err(FigureError::Size { width, height });
    }
    Ok(())
}

/// Draws `fig` on `root` (`width × height` px).
fn render_on(
    fig: &Figure,
    root: &DrawingArea<FigureBackend<'_>, plotters::coord::Shift>,
    width: u32,
    height: u32,
) -> Result<Vec<PanelLayout>, Box<dyn std::error::Error>> {
    register_fonts();
    root.fill(&WHITE)?;
    let scale = figure_text_scale(fig, width, height);
    let fs = |s: f64| (s * scale).round() as i32;
    let mut top = fs(10.0);
    // title and subtitle within the width (with text scaled by the width,
    // Fig. 2's title came within 25 px of the right edge)
    let line_w = width as i32 - 2 * fs(12.0);
    let title_px = fit_font_px(&fig.title, line_w, fs(24.0) as u32, fs(14.0) as u32);
    root.draw(&Text::new(
        fig.title.clone(),
        (fs(12.0), top),
        ("sans-serif", title_px as i32).into_font().color(&BLACK),
    ))?;
    top += fs(30.0);
    if !fig.subtitle.is_empty() {
        let sub_px = fit_font_px(&fig.subtitle, line_w, fs(15.0) as u32, fs(11.0) as u32);
        root.draw(&Text::new(
            fig.subtitle.clone(),
            (fs(12.0), top),
            ("sans-serif", sub_px as i32)
                .into_font()
                .color(&RGBColor(70, 70, 70)),
        ))?;
        top += fs(22.0);
    }
    let body = root.margin(top as u32, 0, 0, 0);
    let n = fig.panels.len().max(1);
    // Stacked panels over one x axis (the time plots, a sweep's metrics)
    // share it: the x title only under the last panel, which is taller by
    // that much, and tighter margins between them (each panel with its own
    // x title and margins left 4 % of a 1000 px figure to the plots).
    let shared_x = n > 1
        && fig.panels.windows(2).all(|w| {
            w[0].x_label == w[1].x_label
                && w[0].log_x == w[1].log_x
                && data_ranges(&w[0]).0 == data_ranges(&w[1]).0
        });
    let frames: Vec<Frame> = (0..n)
        .map(|k| {
            let last = k + 1 == n;
            Frame {
                scale,
                x_desc: !shared_x || last,
                x_area: if !shared_x || last {
                    fs(45.0)
                } else {
                    fs(26.0)
                } as u32,
                v_margin: if shared_x { fs(4.0) } else { fs(10.0) } as u32,
            }
        })
        .collect();
    let areas = if shared_x {
        let extra = frames[n - 1].x_area as i32 - frames[0].x_area as i32;
        let each = (body.dim_in_pixel().1 as i32 - extra) / n as i32;
        let breaks: Vec<i32> = (1..n as i32).map(|k| k * each).collect();
        body.split_by_breakpoints([] as [i32; 0], breaks)
    } else {
        body.split_evenly((n, 1))
    };
    // When a panel's legend must go in a column right of its plot (no
    // corner free of data), every panel gets a column of the same width and
    // puts its legend there: the panels' plots keep one width and their x
    // axes line up (the exported time plots are read against each other).
    let legends: Vec<PanelLegend> = fig
        .panels
        .iter()
        .zip(areas.iter())
        .zip(&frames)
        .map(|((panel, area), frame)| panel_legend(panel, area, frame))
        .collect();
    let column_w = legends
        .iter()
        .any(|l| !l.entries.is_empty() && l.under > 0)
        .then(|| legends.iter().map(|l| l.size.0).max().unwrap_or(0));
    // one y label area for all the panels, as wide as the widest needs
    // (85 px x scale left Fig. 2's "900" with 60 px to spare): their x axes
    // line up
    let y_area = fig
        .panels
        .iter()
        .zip(areas.iter())
        .zip(&frames)
        .map(|((panel, area), frame)| y_area_px(panel, plot_h_of(panel, area, frame), scale))
        .max()
        .unwrap_or(0);
    // one type scale: every panel's caption and axis titles at the size
    // that fits the tightest panel (each fitted alone, a figure's panels
    // had captions of three different sizes)
    type Area<'a> = DrawingArea<FigureBackend<'a>, plotters::coord::Shift>;
    let fitted = |f: &dyn Fn(&Panel, &Area<'_>, &Frame) -> u32| {
        fig.panels
            .iter()
            .zip(areas.iter())
            .zip(&frames)
            .map(|((panel, area), frame)| f(panel, area, frame))
            .min()
            .unwrap_or(fs(14.0) as u32)
    };
    let type_px = TypeScale {
        caption: fitted(&|panel, area, _| caption_px(panel, area, column_w, scale)),
        axis_title: fitted(&|panel, area, frame| {
            axis_title_px(panel, plot_h_of(panel, area, frame), scale)
        }),
    };
    let mut layouts = Vec::with_capacity(fig.panels.len());
    for (((panel, area), legend), frame) in fig
        .panels
        .iter()
        .zip(areas.iter())
        .zip(&legends)
        .zip(&frames)
    {
        let axes = Axes {
            column_w,
            y_area,
            type_px,
        };
        layouts.push(draw_panel(panel, area, frame, legend, &axes)?);
    }
    Ok(layouts)
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

/// Draws `panel` in `area`; its legend in the corner with the least data,
/// or, with `column_w` (the figure's legend column, px), in a column of
/// that width right of the plot (when every corner of some panel has data:
/// Fig. 2, whose force spikes fill the whole plot).
fn draw_panel(
    panel: &Panel,
    area: &DrawingArea<FigureBackend<'_>, plotters::coord::Shift>,
    frame: &Frame,
    legend: &PanelLegend,
    axes: &Axes,
) -> Result<PanelLayout, Box<dyn std::error::Error>> {
    let scale = frame.scale;
    let Axes {
        column_w,
        y_area,
        type_px,
    } = *axes;
    let fs = |s: f64| (s * scale).round() as u32;
    let (xs, ys) = data_ranges(panel);
    let plot_h = plot_h_of(panel, area, frame);
    let outside = column_w.is_some() && !legend.entries.is_empty();
    let (chart_area, legend_area) = match column_w {
        Some(cw) => {
            let w = area.dim_in_pixel().0 as i32;
            area.split_horizontally((w - cw - fs(10.0) as i32).max(w / 2))
        }
        None => area.split_horizontally(area.dim_in_pixel().0),
    };
    let mut layout = PanelLayout {
        caption_px: type_px.caption,
        axis_title_px: type_px.axis_title,
        ..PanelLayout::default()
    };
    let mut builder = ChartBuilder::on(&chart_area);
    if !panel.title.is_empty() {
        // none for no title: Fig. 1 and 2 kept an empty line over the plot
        builder.caption(&panel.title, ("sans-serif", type_px.caption as i32));
    }
    builder
        .margin(fs(10.0))
        .margin_top(frame.v_margin)
        .margin_bottom(frame.v_margin)
        .x_label_area_size(frame.x_area)
        .y_label_area_size(y_area);
    let chart_w = f64::from(chart_area.dim_in_pixel().0);
    let parts = ChartParts {
        panel,
        frame,
        plot_h,
        x_ticks: if panel.log_x {
            log_axis_ticks(xs.0, xs.1, x_log_label_count(chart_w, scale))
        } else {
            LogTicks::default()
        },
        y_ticks: if panel.log_y {
            log_axis_ticks(ys.0, ys.1, y_label_count(panel, plot_h, scale))
        } else {
            LogTicks::default()
        },
        axis_title_px: type_px.axis_title,
        legend,
        beside: outside.then_some(&legend_area),
    };
    // a log axis's ticks are chosen here (plotters' named some values twice)
    let log_axis = |(lo, hi): (f64, f64), ticks: &LogTicks| {
        (lo..hi)
            .log_scale()
            .with_key_points(ticks.labelled.iter().map(|t| t.0).collect())
            .with_light_points(ticks.light.iter().copied())
    };
    match (panel.log_x, panel.log_y) {
        (false, false) => draw_chart(
            builder.build_cartesian_2d(xs.0..xs.1, ys.0..ys.1)?,
            &parts,
            &mut layout,
        ),
        (true, false) => draw_chart(
            builder.build_cartesian_2d(log_axis(xs, &parts.x_ticks), ys.0..ys.1)?,
            &parts,
            &mut layout,
        ),
        (false, true) => draw_chart(
            builder.build_cartesian_2d(xs.0..xs.1, log_axis(ys, &parts.y_ticks))?,
            &parts,
            &mut layout,
        ),
        (true, true) => draw_chart(
            builder
                .build_cartesian_2d(log_axis(xs, &parts.x_ticks), log_axis(ys, &parts.y_ticks))?,
            &parts,
            &mut layout,
        ),
    }?;
    Ok(layout)
}

/// The chart of a panel, on linear or log axes.
type PanelChart<'a, 'b, X, Y> = ChartContext<'a, FigureBackend<'b>, Cartesian2d<X, Y>>;

/// What [`draw_chart`] draws besides the chart's axes.
struct ChartParts<'p, 'a, 'b> {
    panel: &'p Panel,
    frame: &'p Frame,
    /// The plot's estimated height (px), for the number of y ticks.
    plot_h: f64,
    /// The ticks of a log x axis (none on a linear one).
    x_ticks: LogTicks,
    /// The ticks of a log y axis (none on a linear one).
    y_ticks: LogTicks,
    axis_title_px: u32,
    legend: &'p PanelLegend,
    /// The legend column right of the plot, when the legend goes there.
    beside: Option<&'a DrawingArea<FigureBackend<'b>, plotters::coord::Shift>>,
}

/// Draws the axes, the series and the legend of a panel on `chart`, and
/// notes in `layout` where the plot, the curves and a legend beside it are.
fn draw_chart<'a, 'b: 'a, X, Y>(
    mut chart: PanelChart<'a, 'b, X, Y>,
    parts: &ChartParts<'_, '_, '_>,
    layout: &mut PanelLayout,
) -> Result<(), Box<dyn std::error::Error>>
where
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let ChartParts { panel, frame, .. } = *parts;
    let scale = frame.scale;
    let fs = |s: f64| (s * scale).round() as u32;
    draw_axes(&mut chart, parts)?;
    let (px, py) = chart.plotting_area().get_pixel_range();
    layout.plot_px = [px.start, py.start, px.end, py.end];
    for (k, s) in panel.series.iter().enumerate() {
        layout.curves_px.push(plot_series(&mut chart, s, k, scale)?);
    }
    let (entries, legend_wh) = (&parts.legend.entries, parts.legend.size);
    if let Some(legend_area) = parts.beside {
        // level with the plot's top, in the column's absolute pixels
        let (lx, ly) = legend_area.get_base_pixel();
        let (x, y) = (fs(5.0) as i32, py.start - ly);
        // in smaller type where the column's room below the plot's top is
        // short of the entries (eight in a quarter of 720 px: the last two
        // drawn over each other at the panel's bottom)
        let room = legend_area.dim_in_pixel().1 as i32 - y;
        let font_px = fitted_legend_font(entries.len(), fs(14.0), room);
        let legend_wh = if font_px == fs(14.0) {
            legend_wh
        } else {
            legend_size(legend_area, entries, font_px)
        };
        draw_legend(legend_area, entries, (x, y), legend_wh, font_px)?;
        layout.legend_px = Some([lx + x, ly + y, lx + x + legend_wh.0, ly + y + legend_wh.1]);
    } else if !entries.is_empty() {
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(RGBColor(180, 180, 180))
            .label_font(("sans-serif", fs(14.0) as i32))
            .position(parts.legend.corner.clone())
            .draw()?;
    }
    Ok(())
}

/// The grid, the tick labels (numbers, or the panel's y names) and the axis
/// titles of a panel (the x title only where the frame shows it).
fn draw_axes<X, Y>(
    chart: &mut PanelChart<'_, '_, X, Y>,
    parts: &ChartParts<'_, '_, '_>,
) -> Result<(), Box<dyn std::error::Error>>
where
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let ChartParts { panel, frame, .. } = *parts;
    let scale = frame.scale;
    let fs = |s: f64| (s * scale).round() as u32;
    let (lx, ly) = (panel.log_x, panel.log_y);
    let (xr, yr) = (chart.x_range(), chart.y_range());
    let (x_ticks, y_ticks) = (&parts.x_ticks, &parts.y_ticks);
    let fx = move |v: &f64| {
        if lx {
            x_ticks.label(*v)
        } else {
            axis_tick_label(*v, false, (xr.start, xr.end))
        }
    };
    let names = &panel.y_names;
    let fy = move |v: &f64| {
        if ly && names.is_empty() {
            y_ticks.label(*v)
        } else if names.is_empty() {
            axis_tick_label(*v, ly, (yr.start, yr.end))
        } else {
            name_tick_label(*v, names)
        }
    };
    let y_ticks = y_label_count(panel, parts.plot_h, scale);
    let x_desc = if frame.x_desc {
        panel.x_label.as_str()
    } else {
        ""
    };
    chart
        .configure_mesh()
        .x_label_formatter(&fx)
        .y_label_formatter(&fy)
        .y_labels(y_ticks)
        .x_desc(x_desc)
        .y_desc(panel.y_label.as_str())
        .label_style(("sans-serif", fs(14.0) as i32))
        .axis_desc_style(("sans-serif", parts.axis_title_px as i32))
        .light_line_style(RGBColor(235, 235, 235))
        .draw()?;
    Ok(())
}

/// Draws series `s`, the `k`th of its panel, and its legend key (named
/// series only). Returns its finite points in pixels.
fn plot_series<'a, 'b: 'a, X, Y>(
    chart: &mut PanelChart<'a, 'b, X, Y>,
    s: &Series,
    k: usize,
    scale: f64,
) -> Result<Vec<(i32, i32)>, Box<dyn std::error::Error>>
where
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let c = series_color(s.color.unwrap_or(k));
    let pts = s
        .points
        .iter()
        .copied()
        .filter(|p| p.0.is_finite() && p.1.is_finite());
    let curve_px = pts.clone().map(|p| chart.backend_coord(&p)).collect();
    let stroke = stroke_of(s, scale);
    let anno = match s.style {
        Style::Line | Style::ThinLine => {
            chart.draw_series(LineSeries::new(pts, c.stroke_width(stroke)))?
        }
        Style::LineMarkers(r) => {
            let pts: Vec<(f64, f64)> = pts.collect();
            chart.draw_series(pts.iter().map(|&p| Circle::new(p, r, c.filled())))?;
            chart.draw_series(LineSeries::new(pts, c.stroke_width(stroke)))?
        }
        Style::Markers(r) => chart.draw_series(pts.map(move |p| Circle::new(p, r, c.filled())))?,
        Style::HollowMarkers(r) => {
            chart.draw_series(pts.map(move |p| Circle::new(p, r, c.stroke_width(1))))?
        }
    };
    if !s.name.is_empty() {
        add_key(anno.label(s.name.clone()), key_style(s), c, stroke);
    }
    Ok(curve_px)
}

/// The legend key of a series drawn in colour `c` with line width
/// `stroke`, as `key_element` draws them in a legend column.
fn add_key<'a, 'b: 'a>(
    anno: &mut SeriesAnno<'a, FigureBackend<'b>>,
    style: Style,
    c: RGBColor,
    stroke: u32,
) {
    let line = move || PathElement::new(vec![(0, 0), (20, 0)], c.stroke_width(key_stroke(stroke)));
    match style {
        Style::Line | Style::ThinLine => {
            anno.legend(move |at| EmptyElement::at(at) + line());
        }
        Style::LineMarkers(r) => {
            anno.legend(move |at| {
                EmptyElement::at(at) + line() + Circle::new((10, 0), r, c.filled())
            });
        }
        Style::Markers(r) => {
            anno.legend(move |(x, y)| Circle::new((x + 10, y), r, c.filled()));
        }
        Style::HollowMarkers(r) => {
            anno.legend(move |(x, y)| Circle::new((x + 10, y), r, c.stroke_width(1)));
        }
    }
}

// (its glyph fix is for the fonts registered natively)
mod backend;
#[cfg_attr(target_arch = "wasm32", allow(dead_code))]
mod font;
mod layout;
mod legend;
pub use backend::{FigureBackend, GlyphBitmap};
use layout::*;
use legend::*;

#[cfg(test)]
pub(crate) mod tests;
