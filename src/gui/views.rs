//! Read-only views of the run: time plots, the scene, the Green functions,
//! and the research views (spectra, sweep, A/B compare, fidelity, the
//! identification workbench).
//! They read the scene, the simulation and the history; the only state they
//! change is their own presentation options (window, exaggeration, ...).

pub mod axis_title;
pub mod compare_view;
pub mod fidelity_view;
pub mod force_labels;
pub mod green_view;
pub mod legend_place;
pub mod patch_view;
pub mod scene_legend;
pub mod scene_view;
pub mod spectra_view;
pub mod sweep_view;
pub mod time_plots;
pub mod workbench_view;

use egui::Color32;

/// Height (px) of an x axis with a row of tick labels and a title under
/// it (egui_plot's title gap is a quarter of its height).
pub fn titled_x_axis_px(ui: &egui::Ui) -> f32 {
    2.3 * ui.text_style_height(&egui::TextStyle::Body)
}

/// An x axis titled `title`, as high as its tick labels and title from the
/// first frame on: egui_plot sizes an axis from the labels it drew the
/// frame before, so a plot that opened while the run was paused (no next
/// frame) kept its title over its tick labels.
pub fn titled_x_axis<'a>(
    ui: &egui::Ui,
    title: impl Into<egui::WidgetText>,
) -> egui_plot::AxisHints<'a> {
    egui_plot::AxisHints::new_x()
        .label(title)
        .min_thickness(titled_x_axis_px(ui))
}

/// [`titled_x_axis`] on a plot.
pub trait XTitle {
    /// The plot's x axis titled `title` ([`titled_x_axis`]); set before
    /// its x formatter, which it replaces.
    #[must_use]
    fn x_title(self, ui: &egui::Ui, title: impl Into<egui::WidgetText>) -> Self;
    /// The plot's linear x axis labelled by [`nice_x_axis`]; set after
    /// [`XTitle::x_title`].
    #[must_use]
    fn nice_x(self) -> Self;
}

impl XTitle for egui_plot::Plot<'_> {
    fn x_title(self, ui: &egui::Ui, title: impl Into<egui::WidgetText>) -> Self {
        self.custom_x_axes(vec![titled_x_axis(ui, title)])
    }

    fn nice_x(self) -> Self {
        nice_x_axis(self)
    }
}

/// The point colours: the PNG figures' (`output::figures::PALETTE`), with
/// grey for their black (black would vanish on the dark theme's plots).
pub const PALETTE: [Color32; 10] = [
    Color32::from_rgb(0, 95, 155),
    Color32::from_rgb(213, 94, 0),
    Color32::from_rgb(0, 158, 115),
    Color32::from_rgb(204, 121, 167),
    Color32::from_rgb(86, 180, 233),
    Color32::from_rgb(188, 189, 34),
    Color32::from_rgb(120, 120, 120),
    Color32::from_rgb(136, 34, 85),
    Color32::from_rgb(140, 86, 75),
    Color32::from_rgb(60, 60, 160),
];

/// Colour of point `i` in every view.
pub fn point_color(i: usize) -> Color32 {
    PALETTE[i % PALETTE.len()]
}

/// Colour of point `i` among the `shown` points (in order) of a plot: its
/// own colour up to `output::figures::PALETTE_SERIES_MAX` points, beyond
/// them its step along the colour ramp of the row (the exported figure's).
pub fn shown_point_color(shown: &[usize], i: usize) -> Color32 {
    let k = crate::output::figures::point_color_index(shown, i);
    match crate::output::figures::ramp_fraction(k) {
        Some(f) => {
            let (r, g, b) = crate::output::figures::ramp_rgb(f);
            Color32::from_rgb(r, g, b)
        }
        None => point_color(i),
    }
}

/// A wall-clock time in readable units: "35 ms" below a second (a fast
/// sweep read "0.0 s"), "2.4 s" above.
pub fn wall_time_text(s: f64) -> String {
    if s < 0.0995 {
        format!("{:.1} ms", s * 1e3)
    } else if s < 0.9995 {
        format!("{:.0} ms", s * 1e3)
    } else {
        format!("{s:.1} s")
    }
}

/// WCAG relative luminance of an sRGB colour.
fn luminance(c: Color32) -> f64 {
    let lin = |x: u8| {
        let v = f64::from(x) / 255.0;
        if v <= 0.04045 {
            v / 12.92
        } else {
            ((v + 0.055) / 1.055).powf(2.4)
        }
    };
    0.2126 * lin(c.r()) + 0.7152 * lin(c.g()) + 0.0722 * lin(c.b())
}

/// WCAG contrast ratio of two colours (1 to 21).
pub fn contrast_ratio(a: Color32, b: Color32) -> f64 {
    let (la, lb) = (luminance(a), luminance(b));
    (la.max(lb) + 0.05) / (la.min(lb) + 0.05)
}

/// Smallest WCAG contrast of a point's label on its background (the level
/// for large or bold text and for graphics).
pub const LABEL_CONTRAST: f64 = 3.0;

/// Point `i`'s colour for a label on `bg`: the point's colour where it
/// reads (contrast >= [`LABEL_CONTRAST`]), else mixed toward `text` (the
/// theme's strong text colour) just enough, so the hue still keys the
/// point. Sky blue on the light theme's panel was 2.3:1.
pub fn point_text_color(i: usize, bg: Color32, text: Color32) -> Color32 {
    let c = point_color(i);
    for k in 0..=20 {
        let f = k as f32 / 20.0;
        let mix = |a: u8, b: u8| (f32::from(a) + (f32::from(b) - f32::from(a)) * f).round() as u8;
        let m = Color32::from_rgb(
            mix(c.r(), text.r()),
            mix(c.g(), text.g()),
            mix(c.b(), text.b()),
        );
        if contrast_ratio(m, bg) >= LABEL_CONTRAST {
            return m;
        }
    }
    text
}

/// [`point_text_color`] on the panel of the theme `v`.
pub fn point_label_color(v: &egui::Visuals, i: usize) -> Color32 {
    point_text_color(i, v.panel_fill, v.strong_text_color())
}

/// Colour of point `i`'s checkbox label among the ticked points `chosen`:
/// the colour of its curve when more than eight are shown (the ramp's,
/// [`shown_point_color`]), else its own readable label colour.
pub fn checkbox_point_color(v: &egui::Visuals, chosen: &[usize], i: usize) -> Color32 {
    if chosen.len() > crate::output::figures::PALETTE_SERIES_MAX && chosen.contains(&i) {
        shown_point_color(chosen, i)
    } else {
        point_label_color(v, i)
    }
}

/// Colour of a point in contact / in flight in the scene view.
pub const CONTACT_COLOR: Color32 = Color32::from_rgb(0, 158, 115);
pub const FLIGHT_COLOR: Color32 = Color32::from_rgb(213, 94, 0);

/// The smallest of 1, 2, 5 × 10^k that is at least `x` (> 0).
pub fn nice_step(x: f64) -> f64 {
    let p = 10f64.powf(x.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * p)
        .find(|&s| s >= x * (1.0 - 1e-12))
        .unwrap_or(10.0 * p)
}

/// The 1-2-5 step below `step` (a 1, 2 or 5 times a power of ten).
pub fn finer_125(step: f64) -> f64 {
    let p = 10f64.powf(step.log10().floor());
    match (step / p).round() as i64 {
        1 => 0.5 * p,
        2 => p,
        _ => 2.0 * p,
    }
}

/// Decimals that show a multiple of `step` exactly (0.05 → 2, 0.2 → 1, 100 → 0).
pub fn decimals_for_step(step: f64) -> usize {
    (-step.log10() - 1e-9).ceil().max(0.0) as usize
}

/// Where a scrolling view's content began: the view's height and the
/// content's top (px, scrolled with it), from [`scrolling_view`].
#[derive(Debug, Clone, Copy)]
pub struct ViewRoom {
    view_px: f32,
    top: f32,
}

impl ViewRoom {
    /// The view's height left below the cursor (px), the same whatever the
    /// scroll offset: plots sized from it share the view's height.
    pub fn left_px(&self, ui: &egui::Ui) -> f32 {
        self.view_px - (ui.cursor().top() - self.top)
    }
}

/// A view in a vertical scroll area that takes the mouse wheel; `add`
/// draws it, with the room the view had (the content's height, not the
/// scrolled one: inside the area the room below the cursor moves with the
/// scroll offset).
pub fn scrolling_view(ui: &mut egui::Ui, id_salt: &str, add: impl FnOnce(&mut egui::Ui, ViewRoom)) {
    let view_px = ui.available_height();
    egui::ScrollArea::vertical()
        .id_salt(id_salt)
        .auto_shrink(false)
        .show(ui, |ui| {
            let top = ui.cursor().top();
            add(ui, ViewRoom { view_px, top });
        });
}

/// A value axis with 1-2-5 ticks and labels every ~30 px: egui_plot's default
/// powers of ten leave a 0–700 N axis with the single label "0". The labels
/// of one axis share their decimals, those of its labelled step (each label
/// took its own mark's: "0.0005", "0.000", "0.001").
pub fn nice_y_axis(plot: egui_plot::Plot<'_>) -> egui_plot::Plot<'_> {
    let axis = LabelledAxis::new(30.0, Y_SHOWN_PX);
    let marks = axis.clone();
    plot.y_grid_spacer(move |input| marks.marks(input))
        .y_axis_formatter(move |mark, range| axis.label(mark, range))
}

/// Horizontal distance (px) at least between the labelled marks of a
/// linear x axis ([`nice_x_axis`]).
pub const X_LABEL_PX: f64 = 80.0;

/// Spacing (px) of the marks at and below which egui_plot does not paint
/// the tick labels of an x axis (its default label spacing, 60 to 80 px).
pub const X_SHOWN_PX: f64 = 60.0;

/// Spacing (px) of the marks at and below which egui_plot does not paint
/// the tick labels of a y axis (its default label spacing, 20 to 30 px).
pub const Y_SHOWN_PX: f64 = 20.0;

/// A linear x axis (time, a swept parameter) labelled as [`nice_y_axis`]:
/// 1-2-5 marks, every label with the decimals of the labelled step (egui_plot's
/// default gave each label its own mark's: "0.09, 0.1, 0.11").
pub fn nice_x_axis(plot: egui_plot::Plot<'_>) -> egui_plot::Plot<'_> {
    let axis = LabelledAxis::new(X_LABEL_PX, X_SHOWN_PX);
    let marks = axis.clone();
    plot.x_grid_spacer(move |input| marks.marks(input))
        .x_axis_formatter(move |mark, range| axis.label(mark, range))
}

/// Which marks of an axis are labelled, and how: those of a step size of
/// at least `labelled`, with the decimals of a multiple of `decimals_of`
/// (the labelled step, or the rounding of the two end labels of a narrow
/// axis: [`axis_marks`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AxisScale {
    pub labelled: f64,
    pub decimals_of: f64,
}

/// The grid spacer and the tick labels of one axis, sharing the scale the
/// spacer chose ([`axis_marks`]): every label has its decimals, marks
/// finer than its labelled step have none ([`tick_label`]).
#[derive(Debug, Clone)]
pub struct LabelledAxis {
    label_px: f64,
    shown_px: f64,
    scale: std::rc::Rc<std::cell::Cell<Option<AxisScale>>>,
}

impl LabelledAxis {
    /// An axis whose labelled marks are at least `label_px` apart, drawn
    /// by egui_plot with labels only where marks are more than `shown_px`
    /// apart ([`X_SHOWN_PX`], [`Y_SHOWN_PX`], or the axis's own label
    /// spacing's start).
    pub fn new(label_px: f64, shown_px: f64) -> Self {
        LabelledAxis {
            label_px,
            shown_px,
            scale: std::rc::Rc::new(std::cell::Cell::new(None)),
        }
    }

    /// The grid marks of the axis ([`axis_marks`]); remembers their scale
    /// for [`Self::label`].
    pub fn marks(&self, input: egui_plot::GridInput) -> Vec<egui_plot::GridMark> {
        match axis_marks(&input, self.label_px, self.shown_px) {
            Some((scale, marks)) => {
                self.scale.set(Some(scale));
                marks
            }
            None => {
                self.scale.set(None);
                Vec::new()
            }
        }
    }

    /// The label of `mark` on the axis showing `range`.
    pub fn label(
        &self,
        mark: egui_plot::GridMark,
        range: &std::ops::RangeInclusive<f64>,
    ) -> String {
        let widest = range.start().abs().max(range.end().abs());
        tick_label(mark, self.scale.get(), widest)
    }
}

/// A tick label of an axis of `scale`: a labelled mark with the scale's
/// decimals, none for a finer mark (it would bring its own decimals);
/// `scale` `None`: the mark's own decimals.
pub fn tick_label(mark: egui_plot::GridMark, scale: Option<AxisScale>, widest: f64) -> String {
    let Some(s) = scale.filter(|s| s.labelled.is_finite() && s.labelled > 0.0) else {
        return axis_number(mark.value, mark.step_size, widest);
    };
    if mark.step_size < s.labelled * (1.0 - 1e-9) {
        return String::new();
    }
    axis_number(mark.value, s.decimals_of, widest)
}

/// A tick label: the decimals a multiple of `step` needs, and on an axis
/// reaching five digits (`widest`: its largest magnitude) whole numbers in
/// groups of three (`1 000 000`, not `1000000`; `5 000` beside `10 000`).
pub fn axis_number(value: f64, step: f64, widest: f64) -> String {
    let text = format!("{:.*}", decimals_for_step(step), value);
    let (sign, digits) = match text.strip_prefix('-') {
        Some(d) => ("-", d),
        None => ("", text.as_str()),
    };
    if widest < 1e4 || digits.len() < 4 || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return text;
    }
    let mut grouped = String::from(sign);
    for (k, c) in digits.chars().enumerate() {
        if k > 0 && (digits.len() - k) % 3 == 0 {
            grouped.push(' ');
        }
        grouped.push(c);
    }
    grouped
}

/// Grid marks at 1-2-5 steps whose labelled step is at least `label_px`
/// apart, with nested finer and coarser steps ([`axis_marks`]).
pub fn nice_marks(
    input: egui_plot::GridInput,
    label_px: f64,
    shown_px: f64,
) -> Vec<egui_plot::GridMark> {
    axis_marks(&input, label_px, shown_px).map_or_else(Vec::new, |(_, marks)| marks)
}

/// The grid marks of an axis and the scale of its labels: 1-2-5 steps
/// whose labelled (major) step is at least `label_px` apart, with nested
/// finer and coarser steps. Where that step has fewer than two marks on
/// the axis (a short or narrow plot: one label, as the A/B compare view's
/// displacement difference showed), the next finer 1-2-5 step is labelled
/// if its marks are more than `shown_px` apart, egui_plot painting no
/// label of a closer step (a narrow sweep or spectra axis lost its labels
/// so); else the two marks nearest the axis's ends at the roundest values
/// more than `shown_px` apart are. `None` for an axis without a scale.
pub fn axis_marks(
    input: &egui_plot::GridInput,
    label_px: f64,
    shown_px: f64,
) -> Option<(AxisScale, Vec<egui_plot::GridMark>)> {
    // the value of a pixel (base_step_size: egui_plot's 8 px least grid spacing)
    let unit = input.base_step_size.abs() / 8.0;
    let (lo, hi) = input.bounds;
    if !(unit.is_finite() && unit > 0.0 && lo.is_finite() && hi.is_finite()) {
        return None;
    }
    let on_axis = |step: f64| (hi / step).floor() - (lo / step).ceil() + 1.0;
    // (half a pixel over egui_plot's limit, which it compares in f32)
    let shown = |step: f64| step / unit > shown_px + 0.5;
    let major = nice_step(label_px * unit);
    if on_axis(major) >= 2.0 {
        return nested_marks(lo, hi, major);
    }
    let finer = finer_125(major);
    if shown(finer) && on_axis(finer) >= 2.0 {
        return nested_marks(lo, hi, finer);
    }
    let mut round = finer;
    while round / unit >= 0.5 {
        let (a, b) = ((lo / round).ceil() * round, (hi / round).floor() * round);
        if b > a && shown(b - a) {
            return Some(end_marks(a, b, round, unit));
        }
        round = finer_125(round);
    }
    // too narrow for two labels
    nested_marks(lo, hi, major)
}

/// Marks of `lo..hi` at multiples of `major` (labelled) and of the nested
/// finer and coarser 1-2-5 steps: 1 → (0.5, 5), 2 → (1, 10), 5 → (1, 10).
fn nested_marks(lo: f64, hi: f64, major: f64) -> Option<(AxisScale, Vec<egui_plot::GridMark>)> {
    let mantissa = (major / 10f64.powf(major.log10().floor())).round();
    let (fine, coarse) = match mantissa as i64 {
        1 => (0.5, 5.0),
        2 => (0.5, 5.0),
        _ => (0.2, 2.0),
    };
    let steps = [major * fine, major, major * coarse];
    let first = (lo / steps[0]).ceil() as i64;
    let last = (hi / steps[0]).floor() as i64;
    if last - first > 10_000 {
        return None;
    }
    let marks = (first..=last)
        .map(|n| {
            let value = n as f64 * steps[0];
            let step_size = steps
                .iter()
                .rev()
                .copied()
                .find(|s| (value / s - (value / s).round()).abs() < 1e-6)
                .unwrap_or(steps[0]);
            egui_plot::GridMark { value, step_size }
        })
        .collect();
    let scale = AxisScale {
        labelled: major,
        decimals_of: major,
    };
    Some((scale, marks))
}

/// The two labelled marks `a` and `b` near a narrow axis's ends (multiples
/// of `round`, given the step between them), and grid marks at the
/// multiples of `round` between them where they are 8 px apart or more
/// (`unit`: the value of a pixel).
fn end_marks(a: f64, b: f64, round: f64, unit: f64) -> (AxisScale, Vec<egui_plot::GridMark>) {
    let span = b - a;
    let end = |value| egui_plot::GridMark {
        value,
        step_size: span,
    };
    let n = (span / round).round() as i64;
    let mut marks = vec![end(a)];
    if round / unit >= 8.0 && n <= 10_000 {
        marks.extend((1..n).map(|k| egui_plot::GridMark {
            value: a + k as f64 * round,
            step_size: round,
        }));
    }
    marks.push(end(b));
    let scale = AxisScale {
        labelled: span,
        decimals_of: round,
    };
    (scale, marks)
}

/// Grid marks of a log10 axis: decades, and 2..9 when few decades show.
pub fn log_marks(input: egui_plot::GridInput) -> Vec<egui_plot::GridMark> {
    let (a, b) = input.bounds;
    let mut out = Vec::new();
    if !(a.is_finite() && b.is_finite()) || b - a > 40.0 {
        return out;
    }
    let mut d = a.floor();
    while d <= b.ceil() {
        out.push(egui_plot::GridMark {
            value: d,
            step_size: 1.0,
        });
        if b - a < 4.0 {
            for k in 2..10 {
                out.push(egui_plot::GridMark {
                    value: d + (k as f64).log10(),
                    step_size: 0.1,
                });
            }
        }
        d += 1.0;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every label of an axis has the decimals of its labelled step, over
    /// ranges of many scales and plot heights (a 1-2-5 step of mantissa 5
    /// labelled "0.0005", "0.000", "0.001" on one axis).
    #[test]
    fn the_labels_of_one_axis_share_their_decimals() {
        let decimals = |t: &str| t.split('.').nth(1).map_or(0, str::len);
        let mut mixed_before = 0;
        for exp in -6..=4 {
            for mantissa in [1.0, 1.3, 2.4, 3.7, 6.1] {
                let half = mantissa * 10f64.powi(exp);
                for (lo, hi) in [(-half, half), (0.0, half), (0.3 * half, 2.0 * half)] {
                    for px in [80.0, 105.0, 160.0, 300.0, 700.0] {
                        let input = egui_plot::GridInput {
                            bounds: (lo, hi),
                            base_step_size: (hi - lo) / px * 8.0,
                        };
                        let (scale, marks) = axis_marks(&input, 30.0, Y_SHOWN_PX).unwrap();
                        let major = scale.labelled;
                        let widest = lo.abs().max(hi.abs());
                        // (every mark: egui_plot labels any mark 20 px
                        // from the next, finer ones included)
                        let texts: Vec<String> = marks
                            .iter()
                            .map(|&m| tick_label(m, Some(scale), widest))
                            .filter(|t| !t.is_empty())
                            .collect();
                        assert!(texts.len() >= 2, "{lo}..{hi} at {px} px: {texts:?}");
                        let labelled: Vec<_> = marks
                            .into_iter()
                            .filter(|m| m.step_size >= major * (1.0 - 1e-9))
                            .collect();
                        assert!(
                            texts.iter().all(|t| decimals(t) == decimals(&texts[0])),
                            "{lo}..{hi} at {px} px: {texts:?}"
                        );
                        let own: Vec<String> = labelled
                            .iter()
                            .map(|m| axis_number(m.value, m.step_size, widest))
                            .collect();
                        mixed_before +=
                            usize::from(own.iter().any(|t| decimals(t) != decimals(&own[0])));
                    }
                }
            }
        }
        // (the cases above do meet the mixed labels of each mark's own step)
        assert!(mixed_before > 0);
    }

    #[test]
    fn wall_times_below_a_second_are_in_milliseconds() {
        assert_eq!(wall_time_text(0.0351), "35.1 ms");
        assert_eq!(wall_time_text(0.004), "4.0 ms");
        assert_eq!(wall_time_text(0.35), "350 ms");
        assert_eq!(wall_time_text(0.9999), "1.0 s");
        assert_eq!(wall_time_text(2.44), "2.4 s");
    }

    #[test]
    fn large_tick_labels_are_grouped_by_thousands() {
        // (value, step, the axis's largest magnitude, label)
        for (v, step, widest, want) in [
            (1e6, 2e5, 1.2e6, "1 000 000"),
            (-25_000.0, 5_000.0, 3e4, "-25 000"),
            (5_000.0, 5_000.0, 1.5e4, "5 000"),
            (9_500.0, 500.0, 9_900.0, "9500"),
            (950.0, 50.0, 2e4, "950"),
            (-0.05, 0.05, 0.1, "-0.05"),
            (123_456.0, 1.0, 2e5, "123 456"),
            (0.0, 1e5, 1e6, "0"),
        ] {
            assert_eq!(axis_number(v, step, widest), want, "{v}");
        }
    }

    #[test]
    fn nice_steps_are_1_2_5_decades_at_least_the_request() {
        for (x, s) in [
            (0.7, 1.0),
            (1.0, 1.0),
            (1.01, 2.0),
            (3.0, 5.0),
            (6.0, 10.0),
            (0.013, 0.02),
            (420.0, 500.0),
        ] {
            assert!(
                (nice_step(x) - s).abs() < 1e-12 * s,
                "{x}: {} vs {s}",
                nice_step(x)
            );
        }
        assert_eq!(decimals_for_step(0.05), 2);
        assert_eq!(decimals_for_step(0.5), 1);
        assert_eq!(decimals_for_step(0.2), 1);
        assert_eq!(decimals_for_step(1.0), 0);
        assert_eq!(decimals_for_step(100.0), 0);
    }
}
