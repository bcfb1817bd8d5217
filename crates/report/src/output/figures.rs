//! Figures as data, drawn headlessly as PNG: stacked panels of line or
//! marker series, each with a title, axis labels with units, and a legend.
//! The description ([`Figure`], [`Panel`], [`Series`]) and the tick labels
//! are always here; drawing them (plotters, bitmap backend, font from
//! `epaint_default_fonts`) needs the `figures` feature.

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
    /// Colour index into the palette (`None`: by position), or from
    /// [`RAMP_BASE`] on a step of the colour ramp ([`ramp_index`]).
    pub color: Option<usize>,
}

/// The most series told apart by the palette's colours: more (a patch's
/// row of 16 points) take colours along [`ramp_rgb`] in their order, and
/// the legend names the first and the last.
pub const PALETTE_SERIES_MAX: usize = 8;

/// The first [`Series::color`] index of the colour ramp's steps.
pub const RAMP_BASE: usize = 1 << 16;
/// Steps of the colour ramp as series colour indices.
pub const RAMP_STEPS: usize = 256;

/// The series colour index of the ramp at `f` (0 to 1).
pub fn ramp_index(f: f64) -> usize {
    let f = if f.is_finite() {
        f.clamp(0.0, 1.0)
    } else {
        0.0
    };
    RAMP_BASE + (f * (RAMP_STEPS - 1) as f64).round() as usize
}

/// The ramp's step of series colour index `index` (0 to 1), if it is one.
pub fn ramp_fraction(index: usize) -> Option<f64> {
    (RAMP_BASE..RAMP_BASE + RAMP_STEPS)
        .contains(&index)
        .then(|| (index - RAMP_BASE) as f64 / (RAMP_STEPS - 1) as f64)
}

/// The colour ramp at `f` (0 to 1): blue, green, olive, orange, wine, each
/// dark enough to read on white and light enough on a dark background.
pub fn ramp_rgb(f: f64) -> (u8, u8, u8) {
    const STOPS: [(f64, f64, f64); 5] = [
        (0.0, 95.0, 155.0),
        (0.0, 158.0, 115.0),
        (160.0, 160.0, 20.0),
        (213.0, 94.0, 0.0),
        (136.0, 34.0, 85.0),
    ];
    let f = if f.is_finite() {
        f.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let x = f * (STOPS.len() - 1) as f64;
    let k = (x.floor() as usize).min(STOPS.len() - 2);
    let t = x - k as f64;
    let (a, b) = (STOPS[k], STOPS[k + 1]);
    let mix = |u: f64, v: f64| (u + t * (v - u)).round() as u8;
    (mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// The colour index of point `i` among `chosen` (the points drawn, in
/// order): its own palette colour up to [`PALETTE_SERIES_MAX`] points, else
/// its step along the ramp.
pub fn point_color_index(chosen: &[usize], i: usize) -> usize {
    let n = chosen.len();
    if n <= PALETTE_SERIES_MAX {
        return i;
    }
    let rank = chosen.iter().position(|&c| c == i).unwrap_or(0);
    ramp_index(rank as f64 / (n - 1) as f64)
}

/// The legend name of point `i` among `chosen`: `point i`; beyond
/// [`PALETTE_SERIES_MAX`] points only the first and the last are named
/// (`point 32 (first of 16)`, `point 47 (last)`), the others colours
/// between them on the ramp.
pub fn point_legend_name(chosen: &[usize], i: usize) -> String {
    let n = chosen.len();
    if n <= PALETTE_SERIES_MAX {
        return format!("point {i}");
    }
    if chosen.first() == Some(&i) {
        format!("point {i} (first of {n}, colours along the ramp)")
    } else if chosen.last() == Some(&i) {
        format!("point {i} (last)")
    } else {
        String::new()
    }
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

/// The label of a categorical y tick at `v`: `names[k]` where `v` is the
/// integer `k`, nothing between (see [`Panel::y_names`]).
pub fn name_tick_label(v: f64, names: &[String]) -> String {
    let k = v.round();
    if (v - k).abs() > 1e-6 || k < 0.0 {
        return String::new();
    }
    names.get(k as usize).cloned().unwrap_or_default()
}

/// A compact tick label: `90000`, `0.25`, `1.5e-7`; on log axes plain from
/// 1 to 10000 (`10`, `100`, `1000` Hz read at a glance), `1e-5` below and
/// beyond (an error axis keeps one style: `1e-3`, `1e-2`, not `1e-3`, `0.01`).
pub fn tick_label(v: f64, log: bool) -> String {
    if v == 0.0 {
        return "0".into();
    }
    let a = v.abs();
    // a log axis names 1, 2 and 5 of each decade: plotters marks every
    // integer multiple, and "90" and "100" run into each other
    if log {
        let m = a / 10f64.powf(a.log10().floor());
        if ![1.0, 2.0, 5.0, 10.0]
            .iter()
            .any(|n| (m - n).abs() < 1e-6 * n)
        {
            return String::new();
        }
    }
    let plain = if log { 1.0..1e5 } else { 1e-3..1e6 };
    if !plain.contains(&a) {
        let s = format!("{v:.1e}");
        return s.replace(".0e", "e");
    }
    let s = format!("{v:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    s.to_string()
}

/// A tick label of a linear axis spanning `(lo, hi)`: every tick of the
/// axis in one style, chosen by the axis's largest magnitude: plain
/// decimals (`0.0002`, `0.0004`, …, `0.0012`) from 1e-3 to 1e6, exponent
/// form (`2e-4`, `4e-4`, `6e-4`) below and beyond; a log axis as
/// [`tick_label`]. (Labelled one by one, a 0 to 2 ms axis read `2e-4`,
/// …, `8e-4`, `0.001`.)
pub fn axis_tick_label(v: f64, log: bool, (lo, hi): (f64, f64)) -> String {
    if log {
        return tick_label(v, true);
    }
    let a = lo.abs().max(hi.abs());
    // a tick computed as a sum of steps: 1e-19 stands for 0
    if v == 0.0 || !a.is_finite() || a == 0.0 || v.abs() < 1e-9 * a {
        return "0".into();
    }
    if (1e-3..1e6).contains(&a) {
        // the decimals of a fiftieth of the span: enough for any tick step
        let span = (hi - lo).abs().max(1e-12 * a);
        let decimals = (-(span / 50.0).log10().floor()).clamp(0.0, 17.0) as usize;
        let s = format!("{v:.decimals$}");
        if !s.contains('.') {
            return s;
        }
        return s.trim_end_matches('0').trim_end_matches('.').to_string();
    }
    // two significant digits of the step's size are plenty for a tick
    let s = format!("{v:.2e}");
    let (m, e) = s.split_once('e').unwrap_or((&s, "0"));
    let m = if m.contains('.') {
        m.trim_end_matches('0').trim_end_matches('.')
    } else {
        m
    };
    format!("{m}e{e}")
}

/// The factor of a figure's text sizes (px) at `width × height` px: the
/// width over 760 (a figure placed at half width in an A4 report is read at
/// its width: the tick labels of `identify --figures`' 1200 × 700 figures
/// were 12 px, their digits 8 px), and at most the height over 430 (a wide
/// strip keeps room for its plot).
pub fn text_scale(width: u32, height: u32) -> f64 {
    (f64::from(width) / 760.0)
        .min(f64::from(height) / 430.0)
        .clamp(0.6, 3.0)
}

/// [`text_scale`] for `fig`'s stack of panels: at most the height over
/// 150 px per panel and 100 px of titles, so that a tall stack keeps its
/// plots high (four panels at 1600 × 1000 px had plots 41 px high under
/// their text).
pub fn figure_text_scale(fig: &Figure, width: u32, height: u32) -> f64 {
    let n = fig.panels.len().max(1) as f64;
    text_scale(width, height).min((f64::from(height) / (150.0 * n + 100.0)).max(0.6))
}

/// The font size (px) of the tick labels of a figure of `width × height`
/// px: 14 × [`text_scale`], 22 px at 1200 px width (digits 14 px tall).
pub fn tick_label_px(width: u32, height: u32) -> u32 {
    (14.0 * text_scale(width, height)).round() as u32
}

#[cfg(feature = "figures")]
mod render;
#[cfg(feature = "figures")]
pub use render::*;
mod ticks;
pub use ticks::{LogTicks, log_axis_ticks};

#[cfg(all(test, feature = "figures"))]
pub(crate) use render::tests;
