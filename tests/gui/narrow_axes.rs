//! Linear x axes labelled by `views::nice_x_axis` (the sweep's, the linear
//! spectra's, the A/B compare's, …) drawn by egui_plot in plots from 80 px
//! wide: every tick label the axis gives is one egui_plot paints (it hides
//! the labels of marks 60 px apart or closer, and those wider than their
//! spacing), and at least two are painted.

use egui_plot::{GridInput, Plot, PlotMemory};
use tirecontact::gui::views::{LabelledAxis, X_LABEL_PX, X_SHOWN_PX, XTitle};

const PLOT_ID: &str = "tirecontact.test.narrow_axis";

/// The labels the axis gives and those egui_plot painted, of a plot
/// `width_px` wide (no y axis: its frame is as wide) including `lo..hi`.
fn labels(width_px: f32, lo: f64, hi: f64) -> (Vec<String>, Vec<String>) {
    let mut h = egui_kittest::Harness::builder()
        .with_size([width_px + 40.0, 200.0])
        .build_ui(move |ui| {
            Plot::new(PLOT_ID)
                .id(egui::Id::unique(PLOT_ID))
                .width(width_px)
                .height(120.0)
                .show_axes([true, false])
                .nice_x()
                .include_x(lo)
                .include_x(hi)
                .include_y(0.0)
                .include_y(1.0)
                .show(ui, |_| {});
        });
    h.run_steps(3);
    let t = PlotMemory::load(&h.ctx, egui::Id::unique(PLOT_ID))
        .expect("the plot's memory")
        .transform();
    let (a, b) = (t.bounds().min()[0], t.bounds().max()[0]);
    let axis = LabelledAxis::new(X_LABEL_PX, X_SHOWN_PX);
    let marks = axis.marks(GridInput {
        bounds: (a, b),
        base_step_size: t.dvalue_dpos()[0].abs() * 8.0,
    });
    let given: Vec<String> = marks
        .into_iter()
        .map(|m| axis.label(m, &(a..=b)))
        .filter(|l| !l.is_empty())
        .collect();
    let mut painted = Vec::new();
    for c in &h.output().shapes {
        if let egui::Shape::Text(t) = &c.shape {
            painted.push(t.galley.text().to_owned());
        }
    }
    (given, painted)
}

#[test]
fn narrow_x_axes_keep_two_painted_labels() {
    for width_px in [80.0, 90.0, 105.0, 130.0, 180.0, 300.0] {
        for (lo, hi) in [
            (0.0, 7.0),
            (0.0, 1.0),
            (0.3, 10.3),
            (-3.3, 2.1),
            (0.0, 0.12),
            (0.05, 0.0502),
            (12.0, 16.0),
            (100.0, 2000.0),
            (5.0, 95.0),
        ] {
            let (given, painted) = labels(width_px, lo, hi);
            for l in &given {
                assert!(
                    painted.contains(l),
                    "{lo}..{hi} in {width_px} px: the label {l:?} is not painted \
                     (given {given:?}, painted {painted:?})"
                );
            }
            assert!(
                painted.len() >= 2,
                "{lo}..{hi} in {width_px} px: painted {painted:?} (given {given:?})"
            );
        }
    }
}
