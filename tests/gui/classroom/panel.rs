//! Leaving classroom mode gives the editing side panel back at the width it
//! had before: it came back wider, because the first frame after leaving
//! still laid the panel out in classroom mode's large text, and a panel
//! keeps the width its contents pushed it to. Measured at the panel's
//! resize handle (its right edge).

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::{App, Command};

/// Width (px) of the editing side panel: the x of its resize handle (the
/// leftmost vertical one; the classroom mode bars' is at the right).
fn side_panel(h: &Harness<'_, App>) -> Option<f32> {
    h.query_all_by_label("Resize panel")
        .map(|n| n.rect())
        .filter(|r| r.height() > 100.0)
        .map(|r| r.center().x)
        .min_by(f32::total_cmp)
}

fn check(preset: &str, size: [f32; 2]) {
    let scene = Scene::load(&Path::new("presets").join(preset)).unwrap();
    let mut h = crate::harness::harness_sized(App::new(scene, None).unwrap(), size);
    h.run_steps(4);
    let before = side_panel(&h).expect("side panel shown");
    h.state_mut().apply(Command::SetClassroom(true));
    h.run_steps(4);
    assert!(h.state().classroom());
    assert!(
        side_panel(&h).is_none_or(|x| x > 0.5 * size[0]),
        "no editing panel in classroom mode"
    );
    h.state_mut().apply(Command::SetClassroom(false));
    // the first frame after leaving, and later ones
    for frames in [1, 4] {
        h.run_steps(frames);
        let after = side_panel(&h).expect("side panel back");
        eprintln!(
            "{preset} {size:?}: side panel {:.1} px wide before classroom mode, {:.1} px after leaving (+{frames} frames)",
            before, after
        );
        assert!(
            (after - before).abs() <= 1.0,
            "{preset} {size:?}: the side panel was {:.1} px wide, came back {:.1} px",
            before,
            after
        );
    }
    // and again: the width does not creep up with every visit
    h.state_mut().apply(Command::SetClassroom(true));
    h.run_steps(4);
    h.state_mut().apply(Command::SetClassroom(false));
    h.run_steps(4);
    let again = side_panel(&h).expect("side panel back");
    assert!((again - before).abs() <= 1.0, "{again} px, was {before} px");
}

#[test]
fn the_side_panel_returns_to_its_width_after_classroom_mode() {
    for size in [[1280.0, 720.0], [1600.0, 1000.0]] {
        check("paper.ron", size);
        check("guided_1a_soft_tyre.ron", size);
    }
}
