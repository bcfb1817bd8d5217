//! The editing panel's texts stay inside it at 1280 × 720 on every shipped
//! preset (the random road's "excitation … at V" line ran past its edge
//! and was cut): every painted text left of the views ends before them.

use crate::harness::{harness_sized, settle, texts};
use egui_kittest::kittest::Queryable;
use tirecontact::Scene;
use tirecontact::gui::{App, Command, View};

#[test]
fn no_text_of_the_editing_panel_runs_past_its_edge() {
    let mut presets: Vec<_> = std::fs::read_dir("presets")
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "ron"))
        .collect();
    presets.sort();
    assert!(presets.len() >= 10, "{presets:?}");
    for path in presets {
        let scene = Scene::load(&path).unwrap();
        let mut h = harness_sized(
            App::new(scene, Some(path.clone())).unwrap(),
            [1280.0, 720.0],
        );
        settle(&mut h);
        h.state_mut().apply(Command::ShowView(View::TimePlots));
        h.run_steps(3);
        // the views start at the time plots' first control
        let views_left = h.get_by_label("follow latest").rect().left();
        for (t, r) in texts(&h) {
            if r.left() < views_left - 20.0 && r.top() > 60.0 && r.bottom() < 690.0 {
                assert!(
                    r.right() <= views_left - 4.0,
                    "{}: {t:?} at {r:?} runs past the panel's edge (views from x = {views_left})",
                    path.display()
                );
            }
        }
    }
}
