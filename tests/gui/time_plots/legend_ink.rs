//! The time plots' legends sit where no curve is: after the paper preset's
//! run at 1600 × 1000 the force plot's legend (fixed at the top left while
//! following) covered the curves. Measured on the painted shapes: the length
//! of the points' curves inside each legend's box, in all four plots, at
//! 1600 × 1000 and 1280 × 720, mid-run and after the run.

use crate::harness::{advance, curves, ink};
use egui::{Pos2, Rect};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use egui_plot::PlotMemory;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::App;
use tirecontact::gui::views::point_color;
use tirecontact::gui::views::time_plots::{
    CONTACT_PLOT_ID, DISPLACEMENT_PLOT_ID, FORCE_PLOT_ID, GAP_PLOT_ID, IMPACT_LABEL,
};

const PLOTS: [&str; 4] = [
    DISPLACEMENT_PLOT_ID,
    FORCE_PLOT_ID,
    GAP_PLOT_ID,
    CONTACT_PLOT_ID,
];

/// The legend box of the plot framed by `frame`: its entries (widgets with
/// the points' names, and the clipped impacts') in egui_plot's frame (8 px
/// margins left and right, 4 px above and below).
fn legend_box(h: &Harness<'_, App>, frame: Rect, points: usize) -> Option<Rect> {
    let mut names: Vec<String> = (0..points).map(|i| format!("point {i}")).collect();
    names.push(IMPACT_LABEL.to_owned());
    names
        .iter()
        .flat_map(|n| h.get_all_by_label(n).map(|n| n.rect()).collect::<Vec<_>>())
        .filter(|r| frame.contains(r.center()))
        .reduce(|a, b| a.union(b))
        .map(|r| r.expand2(egui::vec2(8.0, 4.0)))
}

fn check(h: &Harness<'_, App>, size: [f32; 2], when: &str) {
    let points = h.state().simulation().num_points();
    let colors: Vec<_> = (0..points).map(point_color).collect();
    let curves = curves(h, &colors, 3);
    assert!(
        curves.len() >= 4 * points,
        "{size:?} {when}: {} curves drawn",
        curves.len()
    );
    for id in PLOTS {
        let frame = *PlotMemory::load(&h.ctx, egui::Id::unique(id))
            .expect("plot shown")
            .transform()
            .frame();
        let legend = legend_box(h, frame, points).unwrap_or_else(|| panic!("no legend in {id}"));
        let in_frame: Vec<Vec<Pos2>> = curves
            .iter()
            .filter(|c| c.iter().all(|p| frame.expand(2.0).contains(*p)))
            .cloned()
            .collect();
        let total = ink(frame, &in_frame);
        let under = ink(legend, &in_frame);
        eprintln!(
            "{size:?} {when}: {id}: legend {:.0}x{:.0} px at ({:.0}, {:.0}) in a frame {:.0}x{:.0} px at ({:.0}, {:.0}); {under:.1} px of {total:.0} px of curves under it",
            legend.width(),
            legend.height(),
            legend.left(),
            legend.top(),
            frame.width(),
            frame.height(),
            frame.left(),
            frame.top(),
        );
        assert!(
            total > frame.width(),
            "{size:?} {when}: {id}: the curves are drawn ({total} px)"
        );
        assert!(
            under <= 2.0,
            "{size:?} {when}: {id}: {under:.1} px of curves under the legend {legend:?}"
        );
    }
}

#[test]
fn the_time_plots_legends_cover_no_curve() {
    let scene = Scene::load(Path::new("presets/paper.ron")).unwrap();
    let steps = (scene.duration_s / scene.dt_s).round() as u64;
    for size in [[1600.0, 1000.0], [1280.0, 720.0]] {
        let mut h = crate::harness::harness_sized(App::new(scene.clone(), None).unwrap(), size);
        h.run();
        // mid-run (the 0.1 s window full), then after the run
        advance(&mut h, steps / 2);
        h.run_steps(4);
        check(&h, size, "mid-run");
        advance(&mut h, steps - steps / 2);
        h.run_steps(4);
        assert!(h.state().simulation().finished());
        check(&h, size, "after the run");
    }
}
