//! The A/B compare view is current without input: after a run completes
//! while paused its difference plots span the whole run like the plots
//! above them (they lagged at the time of the last input), and its legends
//! have one entry per run style rather than one per point and run.

use crate::harness::{advance, harness};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use egui_plot::PlotMemory;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::View;
use tirecontact::gui::views::compare_view::{
    CURRENT, DIFFERENCE, DISPLACEMENT_DIFF_PLOT_ID, FORCE_DIFF_PLOT_ID, FORCE_PLOT_ID, REFERENCE,
};
use tirecontact::gui::{App, Command};
use tirecontact::scene::Tyre;

/// The time axis `(t0, t1)` of the compare view's plot `id`, as drawn.
fn x_axis(h: &Harness<'_, App>, id: &str) -> (f64, f64) {
    let mem = PlotMemory::load(&h.ctx, egui::Id::unique(id)).expect("plot shown");
    let b = mem.bounds();
    (b.min()[0], b.max()[0])
}

#[test]
fn difference_plots_span_the_whole_run_once_it_completes_while_paused() {
    let mut scene = Scene::load(Path::new("presets/three_points.ron")).unwrap();
    scene.duration_s = 0.03;
    let steps = 3000;
    let mut h = harness(App::new(scene.clone(), None).unwrap());
    h.run();
    advance(&mut h, steps);
    h.state_mut().apply(Command::ShowView(View::Compare));
    h.run_steps(2);
    h.get_by_label("Pin as reference").click();
    h.run_steps(2);
    let mut edited = scene.clone();
    if let Tyre::Modal { modes } = &mut edited.tyre {
        modes[0].freq_hz *= 1.1;
    }
    h.state_mut().apply(Command::EditScene(Box::new(edited)));
    h.run_steps(1);
    // a third of the new run, drawn and settled
    advance(&mut h, steps / 3);
    h.run();
    // the rest while paused, then no input: only the frames the app asks for
    advance(&mut h, steps - steps / 3);
    h.run();
    assert!(h.state().simulation().finished());
    let t_end = h.state().history().last_time().unwrap();
    assert!((t_end - 0.03).abs() < 1e-9, "{t_end} s");
    for id in [FORCE_PLOT_ID, DISPLACEMENT_DIFF_PLOT_ID, FORCE_DIFF_PLOT_ID] {
        let (t0, t1) = x_axis(&h, id);
        assert!(
            t0 <= 0.0 && t1 >= t_end && t1 <= 1.2 * t_end,
            "{id}: time axis {t0}..{t1} s, run 0..{t_end} s"
        );
    }
}

#[test]
fn compare_legends_have_one_entry_per_run_style() {
    let scene = Scene::load(Path::new("presets/paper.ron")).unwrap();
    let mut h = harness(App::new(scene, None).unwrap());
    h.run();
    advance(&mut h, 500);
    h.state_mut().apply(Command::ShowView(View::Compare));
    h.run_steps(2);
    h.get_by_label("Pin as reference").click();
    h.run_steps(3);
    // five points: two plots with a current and a reference entry each, two
    // difference plots with one entry each, and nothing per point
    assert_eq!(h.query_all_by_label(CURRENT).count(), 2);
    assert_eq!(h.query_all_by_label(REFERENCE).count(), 2);
    assert_eq!(h.query_all_by_label(DIFFERENCE).count(), 2);
    assert!(h.query_by_label_contains("ref: point").is_none());
    assert!(h.query_by_label_contains("point 4").is_none());
}
