//! The spectra of a long run are computed on a background thread: the view
//! says "computing…" meanwhile and shows the spectrum after some frames,
//! equal to the library's on the same history.

use crate::harness::{advance, harness};
use egui_kittest::kittest::Queryable;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::analysis::spectrum::Window;
use tirecontact::gui::View;
use tirecontact::gui::research::spectra::history_spectra;
use tirecontact::gui::{App, Command};

#[test]
fn a_long_run_s_spectra_arrive_from_a_background_thread() {
    let scene = Scene::load(Path::new("presets/three_points.ron")).unwrap();
    let mut h = harness(App::new(scene.clone(), None).unwrap());
    h.run();
    // 40 000 steps: 37 000 steady samples x 7 spectra, above the inline limit
    advance(&mut h, 40_000);
    h.state_mut().apply(Command::ShowView(View::Spectra));
    h.run_steps(1);
    assert_eq!(h.state().research().spectra_jobs(), 1, "one job started");
    if h.state().research().spectra_computing().is_some() {
        assert!(h.query_by_label_contains("computing…").is_some());
    }
    let mut frames = 0;
    while h.state().research().spectra().is_none() {
        assert!(frames < 100_000, "no spectrum after {frames} frames");
        std::thread::sleep(std::time::Duration::from_millis(2));
        h.run_steps(1);
        frames += 1;
    }
    h.run_steps(1);
    assert!(h.state().research().spectra_computing().is_none());
    assert!(h.query_by_label_contains("computing…").is_none());
    assert!(h.query_by_label_contains("Hann window, t = ").is_some());
    assert_eq!(h.state().research().spectra_computations(), 1);
    assert_eq!(h.state().research().spectra_jobs(), 1, "paused: no new job");
    // the same spectra as the library's on this history
    let got = h.state().research().spectra().unwrap().as_ref().unwrap();
    let want =
        history_spectra(h.state().history(), scene.ramp_s, scene.dt_s, Window::Hann).unwrap();
    assert_eq!(got.span, want.span);
    assert!(got.span.samples > 30_000);
    for (a, b) in got
        .spectra
        .displacement
        .iter()
        .zip(&want.spectra.displacement)
    {
        assert_eq!(a.amplitude, b.amplitude);
    }
}

/// A spectrum's level axis is set by its curves: it stays the same from
/// frame to frame (the marker labels, placed at the axis top, raised it
/// every frame), and a zoom (Ctrl + wheel, a pinch) or a drag moves the
/// frequencies only.
#[test]
fn the_spectrum_level_axis_stays_under_zoom_and_drag() {
    use egui_plot::PlotMemory;
    let scene = Scene::load(Path::new("presets/three_points.ron")).unwrap();
    let mut h = harness(App::new(scene, None).unwrap());
    h.run();
    advance(&mut h, 8_000);
    h.state_mut().apply(Command::ShowView(View::Spectra));
    for _ in 0..200 {
        if h.state().research().spectra().is_some() {
            break;
        }
        std::thread::sleep(std::time::Duration::from_millis(5));
        h.run_steps(1);
    }
    h.run_steps(2);
    let id = egui::Id::unique("tirecontact.spectra_q");
    let bounds = |h: &egui_kittest::Harness<'_, App>| {
        *PlotMemory::load(&h.ctx, id)
            .expect("force spectrum shown")
            .bounds()
    };
    let before = bounds(&h);
    // idle frames leave it as it is
    h.run_steps(5);
    assert_eq!(bounds(&h), before, "the axis moved by itself");
    let frame = *PlotMemory::load(&h.ctx, id).unwrap().transform().frame();
    h.hover_at(frame.center());
    h.run_steps(1);
    h.event(egui::Event::Zoom(4.0));
    h.run_steps(1);

    h.drag_at(frame.center());
    h.hover_at(frame.center() + egui::vec2(40.0, 60.0));
    h.run_steps(1);
    h.drop_at(frame.center() + egui::vec2(40.0, 60.0));
    h.run_steps(2);
    let after = bounds(&h);
    assert_ne!(
        (after.min()[0], after.max()[0]),
        (before.min()[0], before.max()[0]),
        "the premise: the frequencies zoomed"
    );
    assert_eq!(
        (after.min()[1], after.max()[1]),
        (before.min()[1], before.max()[1]),
        "the level axis moved"
    );
}
