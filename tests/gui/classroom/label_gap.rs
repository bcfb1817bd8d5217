//! In classroom mode at 1280 × 720 the force value labels ("592 N") and the
//! phase labels ("p3: IMPACT") of the paper preset's scene view keep at
//! least 2 px apart over the whole run: their boxes came within 0.6 px
//! (read from the painted text shapes every 100 steps).

use crate::harness::{advance, texts};
use egui::Rect;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::View;
use tirecontact::gui::{App, Command};

/// Distance (px) between two boxes: the larger of their horizontal and
/// vertical gaps (negative when they overlap).
fn gap(a: &Rect, b: &Rect) -> f32 {
    let dx = (a.left() - b.right()).max(b.left() - a.right());
    let dy = (a.top() - b.bottom()).max(b.top() - a.bottom());
    dx.max(dy)
}

#[test]
fn force_and_phase_labels_keep_two_pixels_apart_over_a_run() {
    let scene = Scene::load(Path::new("presets/paper.ron")).unwrap();
    let total = scene.num_steps();
    let mut h = crate::harness::harness_sized(App::new(scene, None).unwrap(), [1280.0, 720.0]);
    h.run();
    h.state_mut().apply(Command::ShowView(View::Scene));
    h.state_mut().apply(Command::SetClassroom(true));
    h.run_steps(2);
    let (mut closest, mut at, mut pairs) = (f32::INFINITY, String::new(), 0usize);
    let mut done = 0;
    while done + 100 <= total {
        advance(&mut h, 100);
        done += 100;
        let all = texts(&h);
        let forces: Vec<&(String, Rect)> = all
            .iter()
            .filter(|(t, _)| t.ends_with(" N") && t[..t.len() - 2].parse::<f64>().is_ok())
            .collect();
        // phase labels in the plot (the strip above lists them all on one
        // line, with two spaces between)
        let phases: Vec<&(String, Rect)> = all
            .iter()
            .filter(|(t, _)| t.starts_with('p') && t.matches(": ").count() == 1)
            .filter(|(t, _)| !t.contains("  "))
            .collect();
        for (f, fr) in &forces {
            for (p, pr) in &phases {
                pairs += 1;
                let g = gap(fr, pr);
                if g < closest {
                    closest = g;
                    at = format!("step {done}: {f:?} at {fr:?}, {p:?} at {pr:?}");
                }
            }
        }
    }
    eprintln!("closest {closest} px over {pairs} pairs: {at}");
    assert!(pairs > 50, "only {pairs} force/phase label pairs seen");
    assert!(closest >= 2.0, "labels {closest} px apart: {at}");
}
