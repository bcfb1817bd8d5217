//! Every label of a time axis (and of the other linear x axes) has the
//! decimals of the axis's labelled step: each mark's own decimals mixed
//! "0.09, 0.1, 0.11" on one axis.

use tirecontact::gui::views::time_plots::TIME_LABEL_SPACING;
use tirecontact::gui::views::{LabelledAxis, X_LABEL_PX, X_SHOWN_PX};

/// The non-empty labels of an axis from `lo` to `hi` s drawn `px` wide
/// (egui_plot's grid input: its smallest step spans 8 px).
fn labels(axis: &LabelledAxis, lo: f64, hi: f64, px: f64) -> Vec<String> {
    let input = egui_plot::GridInput {
        bounds: (lo, hi),
        base_step_size: (hi - lo) / px * 8.0,
    };
    let range = lo..=hi;
    axis.marks(input)
        .into_iter()
        .map(|m| axis.label(m, &range))
        .filter(|l| !l.is_empty())
        .collect()
}

fn decimals(label: &str) -> usize {
    label.split('.').nth(1).map_or(0, str::len)
}

#[test]
fn time_axis_labels_share_one_decimal_count() {
    let time_px = (
        f64::from(*TIME_LABEL_SPACING.end()),
        f64::from(*TIME_LABEL_SPACING.start()),
    );
    for (label_px, shown_px) in [time_px, (X_LABEL_PX, X_SHOWN_PX)] {
        for (lo, hi, px) in [
            (0.0, 0.12, 600.0),
            (0.0, 0.12, 1200.0),
            (0.0, 1.0, 800.0),
            (0.0, 1.0, 300.0),
            (0.05, 0.0502, 500.0),
            (0.08, 0.13, 900.0),
            (0.0, 12.0, 700.0),
        ] {
            let axis = LabelledAxis::new(label_px, shown_px);
            let got = labels(&axis, lo, hi, px);
            assert!(got.len() >= 2, "{lo}..{hi} s, {px} px: {got:?}");
            let d = decimals(&got[0]);
            assert!(
                got.iter().all(|l| decimals(l) == d),
                "{lo}..{hi} s over {px} px (labels {label_px} px apart): {got:?}"
            );
            // the labels are the marks' values, no two alike
            let mut unique = got.clone();
            unique.dedup();
            assert_eq!(unique, got, "{lo}..{hi} s: {got:?}");
            for l in &got {
                let v: f64 = l.replace(' ', "").parse().unwrap();
                assert!(v >= lo - 1e-12 && v <= hi + 1e-12, "{l} outside {lo}..{hi}");
            }
        }
    }
}
