//! Values of the scene view's force arrows: each arrow gets its force in N
//! under its tail, largest first, as long as the label does not overlap one
//! already placed; with many points (50 in a tyre patch) only the largest
//! that fit are labelled, and the others stay readable as arrow lengths.

use egui::{Align2, Color32, RichText, TextStyle};
use egui_plot::{PlotPoint, PlotUi, Text};

/// Text of a force label.
pub fn force_text(q_n: f64) -> String {
    if q_n >= 100.0 {
        format!("{q_n:.0} N")
    } else if q_n >= 10.0 {
        format!("{q_n:.1} N")
    } else {
        format!("{q_n:.2} N")
    }
}

/// Which of the arrows at screen `x_px` with forces `q_n` get a label
/// `width_px` wide: largest force first, each only if it keeps `width_px`
/// from every label already chosen. Returned in order of x.
pub fn pick_labels(x_px: &[f32], q_n: &[f64], width_px: f32) -> Vec<usize> {
    let mut order: Vec<usize> = (0..x_px.len().min(q_n.len())).collect();
    order.sort_by(|&a, &b| q_n[b].total_cmp(&q_n[a]));
    let mut chosen: Vec<usize> = Vec::new();
    for i in order {
        if !x_px[i].is_finite() || q_n[i].is_nan() || q_n[i] <= 0.0 {
            continue;
        }
        if chosen
            .iter()
            .all(|&j| (x_px[i] - x_px[j]).abs() >= width_px)
        {
            chosen.push(i);
        }
    }
    chosen.sort_by(|&a, &b| x_px[a].total_cmp(&x_px[b]));
    chosen
}

/// The lowest and highest y of the polyline `line` (points in order of x)
/// between `x0` and `x1`: its vertices there and its values at both ends;
/// `None` where it does not reach.
pub fn y_span(line: &[[f64; 2]], x0: f64, x1: f64) -> Option<(f64, f64)> {
    let mut ys: Vec<f64> = line
        .iter()
        .filter(|p| (x0..=x1).contains(&p[0]))
        .map(|p| p[1])
        .collect();
    for x in [x0, x1] {
        for w in line.windows(2) {
            let ([xa, ya], [xb, yb]) = (w[0], w[1]);
            if xa < x && x < xb {
                ys.push(ya + (yb - ya) * (x - xa) / (xb - xa));
            }
        }
    }
    let lo = ys.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = ys.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    (lo <= hi).then_some((lo, hi))
}

/// Draws the labels of the arrows whose tails are at `tails` (plot units)
/// with forces `q_n`, under the tails, in `color` (a strong text colour);
/// a label that would lie over the line `keep_off` (the undeformed tyre,
/// dashed, with markers of `keep_off_px` radius) goes under it instead.
/// They join the arrows' legend entry `name` with the arrows' colour
/// `legend_color` (egui_plot greys out an entry whose items differ in
/// colour). Returns the lowest y (plot units) the labels reach, for other
/// text to keep below (the classroom's phase labels).
pub fn draw(
    pui: &mut PlotUi<'_>,
    name: &str,
    legend_color: Color32,
    tails: &[[f64; 2]],
    q_n: &[f64],
    color: Color32,
    keep_off: &[[f64; 2]],
    keep_off_px: f32,
) -> Option<f64> {
    let font_px = pui
        .ctx()
        .global_style()
        .text_styles
        .get(&TextStyle::Body)
        .map_or(14.0, |f| f.size);
    let chars = q_n.iter().map(|q| force_text(*q).len()).max().unwrap_or(0);
    let width_px = chars as f32 * 0.6 * font_px + 8.0;
    let x_px: Vec<f32> = tails
        .iter()
        .map(|t| pui.screen_from_plot(PlotPoint::new(t[0], t[1])).x)
        .collect();
    // a label's height in plot units (its row, with a gap)
    let [dx_dpx, dy_dpx] = pui.transform().dvalue_dpos().map(f64::abs);
    let label_h = f64::from(LINE_HEIGHT * font_px + 4.0) * dy_dpx;
    let (half_w, pad) = (
        0.5 * f64::from(width_px) * dx_dpx,
        f64::from(keep_off_px + 2.0) * dy_dpx,
    );
    let mut lowest: Option<f64> = None;
    for i in pick_labels(&x_px, q_n, width_px) {
        let [x, mut top] = tails[i];
        // over the line (or its markers) within the label's width: under it
        if let Some((lo, hi)) = y_span(keep_off, x - half_w, x + half_w)
            && top - label_h < hi + pad
            && top > lo - pad
        {
            top = lo - pad;
        }
        let bottom = top - label_h;
        lowest = Some(lowest.map_or(bottom, |l| l.min(bottom)));
        // body size, strong colour: egui_plot's default small text in the
        // arrows' blue was unreadable on the road's fill
        let text = RichText::new(force_text(q_n[i])).size(font_px).color(color);
        pui.text(
            Text::new(name, PlotPoint::new(x, top), text)
                .anchor(Align2::CENTER_TOP)
                // the glyphs keep `color` (set in the text); this is the
                // item's colour, shown by the legend
                .color(legend_color),
        );
    }
    lowest
}

/// Height of a line of text relative to its font size (Ubuntu: about 1.2;
/// a little more, to be safe).
pub const LINE_HEIGHT: f32 = 1.3;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spaced_arrows_all_get_labels() {
        let x = [100.0, 200.0, 300.0, 400.0, 500.0];
        let q = [10.0, 50.0, 20.0, 5.0, 1.0];
        assert_eq!(pick_labels(&x, &q, 60.0), vec![0, 1, 2, 3, 4]);
    }

    #[test]
    fn crowded_arrows_label_the_largest_without_overlap() {
        // 50 arrows 10 px apart, labels 60 px wide
        let x: Vec<f32> = (0..50).map(|i| 100.0 + 10.0 * i as f32).collect();
        let q: Vec<f64> = (0..50)
            .map(|i| 1000.0 - (i as f64 - 20.0).powi(2))
            .collect();
        let p = pick_labels(&x, &q, 60.0);
        assert!(p.contains(&20), "the largest force is labelled: {p:?}");
        for w in p.windows(2) {
            assert!(x[w[1]] - x[w[0]] >= 60.0, "{p:?}");
        }
        // at most one label per 60 px of 490 px
        assert!(p.len() <= 9 && p.len() >= 5, "{p:?}");
        // no force: no label
        assert!(pick_labels(&[0.0], &[0.0], 10.0).is_empty());
    }

    #[test]
    fn y_span_reads_the_line_over_an_x_range() {
        let line = [[0.0, 0.0], [1.0, 2.0], [2.0, -1.0]];
        // a vertex inside, the ends interpolated
        assert_eq!(y_span(&line, 0.5, 1.5), Some((0.5, 2.0)));
        // between two vertices: the two interpolated values
        assert_eq!(y_span(&line, 0.25, 0.75), Some((0.5, 1.5)));
        // beyond the line
        assert_eq!(y_span(&line, 3.0, 4.0), None);
        assert_eq!(y_span(&[], 0.0, 1.0), None);
    }

    #[test]
    fn force_text_has_its_unit_and_three_figures() {
        assert_eq!(force_text(1234.4), "1234 N");
        assert_eq!(force_text(56.78), "56.8 N");
        assert_eq!(force_text(0.5), "0.50 N");
    }
}
