//! A phone-sized window (400 × 800): the editing panel hides behind a
//! button instead of covering the views, and comes back in their place.

use crate::harness::{harness_sized, settle, texts};
use egui_kittest::kittest::Queryable;
use tirecontact::gui::App;

#[test]
fn a_narrow_window_keeps_the_editing_panel_behind_a_button() {
    let mut h = harness_sized(App::with_default_preset(), [400.0, 800.0]);
    settle(&mut h);
    h.run_steps(2);
    // the views have the window: no field, the time plots' titles at the
    // left edge
    assert!(
        h.query_by_label("road.amplitude_m").is_none(),
        "the panel covers the views"
    );
    let leftmost = texts(&h)
        .iter()
        .filter(|(t, _)| t.contains("(mm") || t.contains("(N)"))
        .map(|(_, r)| r.left())
        .fold(f32::INFINITY, f32::min);
    assert!(leftmost < 60.0, "the views start at {leftmost} px");
    // the button shows the panel in their place, and back
    h.get_by_label("Edit the scene").click();
    h.run_steps(2);
    assert!(h.query_by_label("road.amplitude_m").is_some());
    h.get_by_label("Back to the views").click();
    h.run_steps(2);
    assert!(h.query_by_label("road.amplitude_m").is_none());
    // a wide window: the panel beside the views, as before
    let mut wide = harness_sized(App::with_default_preset(), [1280.0, 720.0]);
    settle(&mut wide);
    assert!(wide.query_by_label("road.amplitude_m").is_some());
    assert!(wide.query_by_label("Edit the scene").is_none());
}
