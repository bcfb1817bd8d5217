//! The time plots' header: the notes of the points left out of the
//! checkboxes ("(+72 more)") stay whole on one row at every window width
//! (one wrapped at a row's end, "(+72" above "more)").

use crate::harness::{harness_sized, settle, texts};
use tirecontact::Scene;
use tirecontact::gui::App;

#[test]
fn the_more_points_note_is_never_split() {
    let scene = Scene::load(std::path::Path::new("presets/patch_texture.ron")).unwrap();
    let mut h = harness_sized(App::new(scene, None).unwrap(), [1500.0, 950.0]);
    settle(&mut h);
    let row = texts(&h)
        .into_iter()
        .find(|(t, _)| t == "points:")
        .map(|(_, r)| r.height())
        .expect("the header's points label");
    let mut seen = 0;
    for w in (700..=1600).step_by(13) {
        h.set_size(egui::vec2(w as f32, 950.0));
        h.run_steps(3);
        for (t, r) in texts(&h) {
            if t.starts_with("(+") {
                seen += 1;
                assert!(r.height() < 1.5 * row, "{w} px: {t:?} at {r:?} is split");
            }
        }
    }
    assert!(seen > 0, "no note of the points left out");
}
