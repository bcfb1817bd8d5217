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
    // and inside the plot: above its x tick labels (a short plot pushed
    // the lowest lane out)
    let axis = all
        .iter()
        .find(|(t, _)| t == "position along the contact line x (m)")
        .expect("x axis label")
        .1;
    let ticks = all
        .iter()
        .filter(|(t, r)| t.parse::<f64>().is_ok() && r.bottom() <= axis.top() + 1.0)
        .map(|(_, r)| r.top())
        .fold(f32::NEG_INFINITY, f32::max);
    eprintln!("  x tick labels from {ticks} px, axis label {axis:?}");
    for (p, pr) in &phases {
        assert!(
            pr.bottom() <= ticks,
            "{size:?}: {p:?} at {pr:?} below the plot (x tick labels at {ticks} px)"
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
