//! In classroom mode the scene view's phase labels ("p3: IMPACT") keep clear
//! of the force arrows' value labels ("592 N"): at the end of the paper
//! preset's run they were drawn over each other. Read from the painted text
//! shapes, at 1600 × 1000 and 1280 × 720, and with one point.

use crate::harness::{advance, texts};
use egui::Rect;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::View;
use tirecontact::gui::{App, Command};

fn check(preset: &str, size: [f32; 2], steps: u64) {
    let scene = Scene::load(Path::new(preset)).unwrap();
    let mut h = crate::harness::harness_sized(App::new(scene, None).unwrap(), size);
    h.run();
    h.state_mut().apply(Command::ShowView(View::Scene));
    h.state_mut().apply(Command::SetClassroom(true));
    h.run_steps(2);
    advance(&mut h, steps);
    // then on until a point pushes (one point's label is always shown)
    for _ in 0..400 {
        if h.state().simulation().force_n().iter().any(|q| *q > 0.0) {
            break;
        }
        advance(&mut h, 25);
    }
    h.run_steps(2);
    let all = texts(&h);
    // value labels "592 N"; phase labels "p3: IMPACT" drawn in the plot
    // (the strip above the plot lists them all on one line)
    let forces: Vec<&(String, Rect)> = all
        .iter()
        .filter(|(t, _)| t.ends_with(" N") && t[..t.len() - 2].parse::<f64>().is_ok())
        .collect();
    let phases: Vec<&(String, Rect)> = all
        .iter()
        .filter(|(t, _)| t.starts_with('p') && t.contains(": ") && !t.contains("  "))
        .filter(|(t, _)| t.matches(": ").count() == 1)
        .collect();
    eprintln!("{preset} {size:?}: forces {forces:?}\n  phases {phases:?}");
    assert!(!forces.is_empty(), "no force label");
    assert!(!phases.is_empty(), "no phase label");
    // and inside the plot's frame (a short plot pushed the lowest lane
    // out, over the x tick labels)
    let frame = *egui_plot::PlotMemory::load(
        &h.ctx,
        egui::Id::unique(tirecontact::gui::views::scene_view::SCENE_PLOT_ID),
    )
    .expect("scene plot shown")
    .transform()
    .frame();
    for (p, pr) in phases.iter().filter(|(_, r)| r.top() >= frame.top()) {
        assert!(
            pr.bottom() <= frame.bottom() && pr.left() >= frame.left(),
            "{size:?}: {p:?} at {pr:?} outside the plot {frame:?}"
        );
    }
    for (f, fr) in &forces {
        for (p, pr) in &phases {
            assert!(
                !fr.intersects(*pr),
                "{size:?}: {f:?} at {fr:?} under {p:?} at {pr:?}"
            );
        }
    }
}

#[test]
fn phase_labels_keep_clear_of_the_force_labels() {
    for size in [[1600.0, 1000.0], [1280.0, 720.0]] {
        check("presets/paper.ron", size, 20_000);
        check("presets/single_mode.ron", size, 0);
    }
}
