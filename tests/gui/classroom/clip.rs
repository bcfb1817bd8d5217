//! The classroom's point plot of the contact force clips impact spikes like
//! the time plots: its axis fits the force without impacts and the clipped
//! impacts are marked (rigid contact draws an impact as impulse / dt, which
//! left the force a flat line under the spikes).

use crate::harness::{advance, harness};
use egui_kittest::kittest::Queryable;
use egui_plot::PlotMemory;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::Quantity;
use tirecontact::gui::classroom::CLASSROOM_PLOT_ID;
use tirecontact::gui::views::time_plots::clip_level;
use tirecontact::gui::{App, Command};

#[test]
fn the_classroom_force_plot_clips_impacts() {
    let scene = Scene::load(Path::new("presets/three_points.ron")).unwrap();
    let mut h = harness(App::new(scene, None).unwrap());
    h.run();
    h.state_mut().apply(Command::SetClassroom(true));
    h.run_steps(2);
    advance(&mut h, 15_000);
    h.get_by_label("contact force").click();
    h.run_steps(4);

    // point 0 over the plot's window, the latest 0.1 s
    let hist = h.state().history();
    let t1 = hist.last_time().unwrap();
    let from = hist.times().partition_point(|&t| t < t1 - 0.1);
    let range = |what| {
        (from..hist.len())
            .map(|k| hist.value(what, 0, k))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), y| {
                (lo.min(y), hi.max(y))
            })
    };
    let raw = range(Quantity::Force);
    let top = clip_level(range(Quantity::ForceWithoutImpacts));
    assert!(raw.1 > 5.0 * top, "impact spikes: {} N vs {top} N", raw.1);
    let mem = PlotMemory::load(&h.ctx, egui::Id::unique(CLASSROOM_PLOT_ID)).expect("plot shown");
    let (lo, hi) = (mem.bounds().min()[1], mem.bounds().max()[1]);
    assert!(hi >= top, "axis top {hi} N below the clip level {top} N");
    assert!(
        hi <= top + 0.1 * (top - lo),
        "axis top {hi} N beyond the clip level {top} N (spikes {} N)",
        raw.1
    );
    assert!(
        h.query_by_label_contains("impact (impulse / dt, clipped)")
            .is_some()
    );
}
