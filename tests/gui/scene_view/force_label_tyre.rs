//! The scene view's force values ("592 N", under each arrow's tail) keep
//! off the undeformed tyre's dashed line and its markers: at the end of the
//! paper preset's run, in classroom mode at 1280 × 720, the label lay over
//! the line. Read from the painted shapes (the line's grey segments and
//! hollow circles, the labels' text), at 1280 × 720 and 1600 × 1000, in
//! classroom mode and not; in classroom mode the phase labels ("p1:
//! IMPACT") stay clear of the moved force values.

use crate::harness::{advance, curves, ink, shapes, texts};
use egui::{Color32, Rect};
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::View;
use tirecontact::gui::{App, Command};

/// Force labels drawn over the undeformed tyre's line or markers in this
/// frame, described; and how many force labels there were.
fn overlaps(h: &egui_kittest::Harness<'_, App>) -> (Vec<String>, usize) {
    let forces: Vec<(String, Rect)> = texts(h)
        .into_iter()
        .filter(|(t, _)| t.ends_with(" N") && t[..t.len() - 2].parse::<f64>().is_ok())
        .collect();
    // the undeformed tyre: grey dashes and grey hollow circles
    let dashes = curves(h, &[Color32::GRAY], 2);
    let rings: Vec<Rect> = shapes(h)
        .into_iter()
        .filter_map(|s| match s {
            egui::Shape::Circle(c) if c.stroke.color == Color32::GRAY => Some(
                Rect::from_center_size(c.center, egui::Vec2::splat(2.0 * c.radius)),
            ),
            _ => None,
        })
        .collect();
    assert!(!dashes.is_empty(), "no undeformed tyre line found");
    assert_eq!(rings.len(), 5, "the five points' markers");
    // the classroom's phase labels drawn in the plot ("p3: IMPACT"; the
    // strip above the plot lists them all on one line)
    let phases: Vec<(String, Rect)> = texts(h)
        .into_iter()
        .filter(|(t, _)| t.starts_with('p') && t.matches(": ").count() == 1 && !t.contains("  "))
        .collect();
    let mut bad = Vec::new();
    for (t, r) in &forces {
        // (boxes touching by a pixel: their glyphs do not)
        for (p, pr) in phases
            .iter()
            .filter(|(_, pr)| pr.shrink(1.0).intersects(r.shrink(1.0)))
        {
            bad.push(format!("{t:?} at {r:?} under {p:?} at {pr:?}"));
        }
        let r = r.shrink(1.0);
        let over = ink(r, &dashes);
        if over > 0.0 {
            bad.push(format!("{t:?} at {r:?} over {over:.1} px of the line"));
        }
        for m in rings.iter().filter(|m| r.intersects(**m)) {
            bad.push(format!("{t:?} at {r:?} over the marker at {m:?}"));
        }
    }
    (bad, forces.len())
}

/// The paper preset's run, frames every 200 steps: no force label over
/// the undeformed tyre in any of them.
fn check(size: [f32; 2], classroom: bool) -> usize {
    let scene = Scene::load(Path::new("presets/paper.ron")).unwrap();
    let mut h = crate::harness::harness_sized(App::new(scene, None).unwrap(), size);
    h.run();
    h.state_mut().apply(Command::ShowView(View::Scene));
    h.state_mut().apply(Command::SetClassroom(classroom));
    h.run_steps(2);
    let mut labels = 0;
    for _ in 0..100 {
        advance(&mut h, 200);
        h.run();
        let (bad, n) = overlaps(&h);
        labels += n;
        let t = h.state().simulation().steps();
        assert!(
            bad.is_empty(),
            "{size:?} classroom {classroom}, step {t}: {bad:?}"
        );
    }
    labels
}

#[test]
fn force_values_keep_off_the_undeformed_tyre() {
    let mut labels = 0;
    for (size, classroom) in [
        ([1280.0, 720.0], true),
        ([1280.0, 720.0], false),
        ([1600.0, 1000.0], true),
    ] {
        labels += check(size, classroom);
    }
    assert!(labels >= 100, "{labels} force labels in 300 frames");
}
