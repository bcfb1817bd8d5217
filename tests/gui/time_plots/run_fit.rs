//! The time axis fits the run: a run shorter than the followed window
//! fills the plot, and no time past the run's end is labelled (the strip
//! past it holds the legends).

use crate::harness::{advance, harness_sized, texts};
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::App;
use tirecontact::gui::views::time_plots::{CONTACT_PLOT_ID, FORCE_PLOT_ID};

fn run_of(duration_s: f64, size: [f32; 2]) -> egui_kittest::Harness<'static, App> {
    let mut scene = Scene::load(Path::new("presets/three_points.ron")).unwrap();
    scene.duration_s = duration_s;
    let steps = (duration_s / scene.dt_s).round() as u64;
    let mut h = harness_sized(App::new(scene, None).unwrap(), size);
    h.run();
    advance(&mut h, steps);
    h.run_steps(3);
    h
}

fn memory(h: &egui_kittest::Harness<'_, App>, id: &str) -> egui_plot::PlotMemory {
    egui_plot::PlotMemory::load(&h.ctx, egui::Id::unique(id)).expect("plot shown")
}

#[test]
fn a_run_shorter_than_the_window_fills_the_time_axis() {
    for size in [[1280.0, 720.0], [1600.0, 1000.0]] {
        let h = run_of(0.002, size);
        let t = memory(&h, FORCE_PLOT_ID).transform();
        let frame = t.frame();
        let t_end = h.state().simulation().time_s();
        assert!((t_end - 0.002).abs() < 1e-9, "{t_end}");
        // the run spans the frame less the legends' strip (at most 1/4)
        let run_px = t.position_from_point_x(t_end) - t.position_from_point_x(0.0);
        assert!(
            run_px > 0.6 * frame.width(),
            "{size:?}: 2 ms span {run_px} of {} px",
            frame.width()
        );
    }
}

#[test]
fn no_time_past_the_runs_end_is_labelled() {
    let h = run_of(0.2, [1600.0, 1000.0]);
    let frame = *memory(&h, CONTACT_PLOT_ID).transform().frame();
    // the bottom plot's time labels: numbers under its frame
    let labels: Vec<f64> = texts(&h)
        .into_iter()
        .filter(|(_, r)| r.top() >= frame.bottom() - 1.0 && r.top() < frame.bottom() + 30.0)
        .filter(|(_, r)| r.center().x > frame.left() && r.center().x < frame.right())
        .filter_map(|(s, _)| s.trim().parse::<f64>().ok())
        .collect();
    let last = labels.iter().copied().fold(f64::MIN, f64::max);
    assert!(labels.len() >= 3, "{labels:?}");
    assert!(last <= 0.2 + 1e-9, "labelled on to {last} s: {labels:?}");
    assert!(last >= 0.19, "the run's end is not labelled: {labels:?}");
}
