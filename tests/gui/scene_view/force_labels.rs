//! The scene view labels its force arrows with their forces in N: every
//! arrow of the paper preset's points gets its value, and the labels do not
//! overlap.

use crate::harness::{advance, harness};
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::View;
use tirecontact::gui::views::force_labels::force_text;
use tirecontact::gui::{App, Command};

#[test]
fn every_arrow_shows_its_force_in_newtons() {
    let scene = Scene::load(Path::new("presets/paper.ron")).unwrap();
    let mut h = harness(App::new(scene, None).unwrap());
    h.run();
    h.state_mut().apply(Command::ShowView(View::Scene));
    advance(&mut h, 3_000);
    // on until at least two points push (bounded)
    for _ in 0..200 {
        if h.state()
            .simulation()
            .force_n()
            .iter()
            .filter(|q| **q > 0.0)
            .count()
            >= 2
        {
            break;
        }
        advance(&mut h, 50);
    }
    h.run_steps(3);
    let q: Vec<f64> = h.state().simulation().force_n().to_vec();
    let pushing: Vec<f64> = q.iter().copied().filter(|q| *q > 0.0).collect();
    assert!(pushing.len() >= 2, "points in contact: {q:?}");
    // plot texts are painted, not widgets: read them from the shapes
    let mut texts: Vec<(String, egui::Rect)> = Vec::new();
    fn collect(s: &egui::Shape, out: &mut Vec<(String, egui::Rect)>) {
        match s {
            egui::Shape::Vec(v) => v.iter().for_each(|s| collect(s, out)),
            egui::Shape::Text(t) => {
                out.push((t.galley.text().to_owned(), t.visual_bounding_rect()))
            }
            _ => {}
        }
    }
    for c in &h.output().shapes {
        collect(&c.shape, &mut texts);
    }
    let mut rects = Vec::new();
    for f in &pushing {
        let text = force_text(*f);
        let r = texts
            .iter()
            .find(|(t, _)| *t == text)
            .unwrap_or_else(|| panic!("no label `{text}` (forces {q:?})"))
            .1;
        rects.push(r);
    }
    eprintln!("labels {rects:?}");
    for (i, a) in rects.iter().enumerate() {
        for b in &rects[i + 1..] {
            assert!(!a.intersects(*b), "labels overlap: {a:?} {b:?}");
        }
    }
}
