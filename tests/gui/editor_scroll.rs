//! The editing panel scrolls back to its top when another scene comes in
//! (it kept the old scene's scroll, and a shorter scene opened on its
//! modes table, its name and description out of sight).

use crate::harness::{harness, settle, wheel};
use egui_kittest::kittest::Queryable;
use tirecontact::Scene;
use tirecontact::gui::{App, Command};

#[test]
fn another_scene_opens_at_the_top_of_the_editing_panel() {
    let path = format!("{}/presets/patch_texture.ron", env!("CARGO_MANIFEST_DIR"));
    let app = App::new(Scene::load(std::path::Path::new(&path)).unwrap(), None).unwrap();
    let mut h = harness(app);
    settle(&mut h);
    let tags = |h: &egui_kittest::Harness<'_, App>| h.get_by_label("Tags:").rect().top();
    // the scene's name heads the panel
    let heading = |h: &egui_kittest::Harness<'_, App>| {
        let name = h.state().scene().name.clone();
        h.get_all_by_label(&name)
            .map(|n| n.rect().top())
            .fold(f32::INFINITY, f32::min)
    };
    let top = tags(&h);
    let heading_top = heading(&h);
    let at = h.get_by_label("Tags:").rect().center();
    wheel(&mut h, at, -120.0, 8);
    assert!(
        tags(&h) < top - 500.0,
        "the panel did not scroll: {} -> {}",
        top,
        tags(&h)
    );
    // (the same scene again: as long, it could keep the scroll)
    h.state_mut().apply(Command::OpenPreset(4));
    settle(&mut h);
    h.run_steps(3);
    assert!(
        (heading(&h) - heading_top).abs() < 2.0,
        "the new scene's panel is scrolled: its name at {} px, {} px at the top",
        heading(&h),
        heading_top
    );
}
